//! The viewer's keys, by name (a winit key or a `--script` `key` line map through here, so
//! a script presses exactly what a person does). The arrow keys and Page Up/Down fly the
//! camera in fly mode and are read while held, not here.

/// What a key press does.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Command {
    Exit,
    /// final.png and final.exr of the current frame into `--out`.
    Save,
    /// The `--dump` buffers of the current frame into `--out`/dumps.
    Dump,
    /// Show the other technique (`--compare`) instead of this one.
    ToggleAb,
    /// Split view: this technique left, the other right.
    ToggleSplit,
    /// Play or pause the animation paths.
    PlayPause,
    /// Rebuild the pipelines from `shaders_glsl/` now.
    ReloadShaders,
    /// Orbit or fly.
    CameraMode,
    /// Hide or show the panel.
    TogglePanel,
    /// Time every pass (the graph) or whole frames.
    TogglePassTiming,
}

/// Every key name, as `--script` writes it and the panel lists it.
pub const NAMES: &[&str] = &["escape", "s", "d", "tab", "v", "space", "r", "c", "t", "f1"];

/// The command of the key `name` (lower case), if it has one.
pub fn command(name: &str) -> Option<Command> {
    Some(match name {
        "escape" => Command::Exit,
        "s" => Command::Save,
        "d" => Command::Dump,
        "tab" => Command::ToggleAb,
        "v" => Command::ToggleSplit,
        "space" => Command::PlayPause,
        "r" => Command::ReloadShaders,
        "c" => Command::CameraMode,
        "t" => Command::TogglePassTiming,
        "f1" => Command::TogglePanel,
        _ => return None,
    })
}

/// The name of a winit key, as [`command`] takes it.
pub fn name_of(key: &winit::keyboard::Key) -> Option<String> {
    use winit::keyboard::{Key, NamedKey};
    match key {
        Key::Named(NamedKey::Escape) => Some("escape".into()),
        Key::Named(NamedKey::Tab) => Some("tab".into()),
        Key::Named(NamedKey::Space) => Some("space".into()),
        Key::Named(NamedKey::F1) => Some("f1".into()),
        Key::Character(c) => Some(c.to_lowercase()),
        _ => None,
    }
}

/// One line per key for the panel's help.
pub fn help() -> Vec<(&'static str, &'static str)> {
    vec![
        ("Esc", "exit"),
        ("S", "save final.png, final.exr"),
        ("D", "dump the --dump buffers"),
        ("Tab", "A/B: show the other technique"),
        ("V", "split view A | B"),
        ("Space", "play / pause the animation"),
        ("R", "reload shaders"),
        ("C", "orbit / fly camera"),
        ("T", "time every pass / whole frames"),
        ("F1", "hide / show this panel"),
        ("drag", "turn the camera (Ctrl: move the light)"),
        ("wheel", "move in and out"),
        ("arrows, PgUp/PgDn", "fly (fly mode)"),
    ]
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_named_key_has_a_command_and_the_commands_differ() {
        let commands: Vec<Command> = NAMES.iter().filter_map(|n| command(n)).collect();
        assert_eq!(commands.len(), NAMES.len());
        for (i, c) in commands.iter().enumerate() {
            assert!(!commands[..i].contains(c), "{c:?} twice");
        }
        assert_eq!(command("x"), None);
    }
}
