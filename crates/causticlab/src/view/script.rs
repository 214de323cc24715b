//! `--script FILE`: timed actions that drive the viewer without a person (the tests under
//! Xvfb). One action per line, `<frame> <action> [arguments]`, run once that many frames have
//! been shown; `#` starts a comment. Actions:
//! - `key NAME`: a key press, as the keyboard would (`view::keys`: escape, s, d, tab, v, space, r, c);
//! - `set KEY VALUE`: a `[caustics]` setting, as the panel sets it (`technique hcm`, `photons 256`);
//! - `screenshot DIR`: final.png and final.exr as `render` writes them, and display.png (the
//!   window's image without its panel) into DIR;
//! - `dump DIR [all|NAME,...]`: the current frame's buffers as `render --dump` writes them;
//! - `resize W H`: asks the window for W × H pixels;
//! - `reload`: looks for edited shaders now (as the watcher does a few times a second);
//! - `await PATH`: waits until PATH exists (at most a minute), so that a test can edit a shader
//!   at a known frame;
//! - `exit`.

use anyhow::{bail, Context as _, Result};
use std::path::{Path, PathBuf};

#[derive(Debug, Clone, PartialEq)]
pub enum Action {
    Key(String),
    Set(String, String),
    Screenshot(PathBuf),
    Dump(PathBuf, Option<String>),
    Resize(u32, u32),
    Reload,
    Await(PathBuf),
    Exit,
}

#[derive(Debug, Clone, PartialEq)]
pub struct Step {
    /// Run once this many frames have been shown.
    pub frame: u32,
    pub action: Action,
    /// `file:line`, for messages.
    pub origin: String,
}

/// Parses a script; errors name the file and line.
pub fn parse(path: &Path, text: &str) -> Result<Vec<Step>> {
    let mut steps = vec![];
    for (i, raw) in text.lines().enumerate() {
        let origin = format!("{}:{}", path.display(), i + 1);
        let line = raw.split('#').next().unwrap_or("").trim();
        if line.is_empty() {
            continue;
        }
        let words: Vec<&str> = line.split_whitespace().collect();
        let frame: u32 =
            words[0].parse().map_err(|_| caustics::input_error!("{origin}: `{}` is not a frame number", words[0]))?;
        let args = &words[1..];
        let action = match args {
            ["key", name] => {
                if super::keys::command(name).is_none() {
                    bail!(caustics::input_error!(
                        "{origin}: unknown key `{name}`; keys: {}",
                        super::keys::NAMES.join(", ")
                    ));
                }
                Action::Key(name.to_string())
            }
            ["set", key, value @ ..] if !value.is_empty() => Action::Set(key.to_string(), value.join(" ")),
            ["screenshot", dir] => Action::Screenshot(dir.into()),
            ["dump", dir] => Action::Dump(dir.into(), None),
            ["dump", dir, names] => Action::Dump(dir.into(), Some(names.to_string())),
            ["resize", w, h] => {
                let size = |s: &str| s.parse::<u32>().ok().filter(|v| (8..=8192).contains(v));
                match (size(w), size(h)) {
                    (Some(w), Some(h)) => Action::Resize(w, h),
                    _ => bail!(caustics::input_error!("{origin}: resize wants two sizes in 8..=8192, got `{w} {h}`")),
                }
            }
            ["reload"] => Action::Reload,
            ["await", path] => Action::Await(path.into()),
            ["exit"] => Action::Exit,
            _ => bail!(caustics::input_error!(
                "{origin}: `{line}`: expected `<frame> key NAME|set KEY VALUE|screenshot DIR|dump DIR [NAMES]|resize W H|reload|await PATH|exit`"
            )),
        };
        if let Some(last) = steps.last().map(|s: &Step| s.frame) {
            if frame < last {
                bail!(caustics::input_error!("{origin}: frame {frame} comes before the previous line's {last}"));
            }
        }
        steps.push(Step { frame, action, origin });
    }
    Ok(steps)
}

/// Reads and parses the script at `path`.
pub fn load(path: &Path) -> Result<Vec<Step>> {
    let text = std::fs::read_to_string(path)
        .map_err(|e| caustics::input_error!("--script: cannot read {}: {e}", path.display()))
        .context("reading the script")?;
    parse(path, &text)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn parses_each_action_and_names_the_line_of_a_bad_one() {
        let text = "# a test\n10 screenshot out/a\n10 set technique hcm\n12 key tab\n15 resize 200 150\n\
                    16 dump out/d receiver,shadow_map\n17 await out/go\n17 reload\n20 exit\n";
        let steps = parse(Path::new("s.txt"), text).expect("parses");
        let actions: Vec<Action> = steps.iter().map(|s| s.action.clone()).collect();
        assert_eq!(
            actions,
            vec![
                Action::Screenshot("out/a".into()),
                Action::Set("technique".into(), "hcm".into()),
                Action::Key("tab".into()),
                Action::Resize(200, 150),
                Action::Dump("out/d".into(), Some("receiver,shadow_map".into())),
                Action::Await("out/go".into()),
                Action::Reload,
                Action::Exit,
            ]
        );
        assert_eq!(steps[3].frame, 15);
        for (bad, what) in [
            ("5 key nope", "s.txt:1: unknown key `nope`"),
            ("x exit", "not a frame number"),
            ("5 resize 2 2", "resize wants"),
            ("5 fly", "expected"),
            ("5 exit\n3 exit", "s.txt:2: frame 3 comes before"),
        ] {
            let err = parse(Path::new("s.txt"), bad).err().map(|e| format!("{e:#}")).unwrap_or_default();
            assert!(err.contains(what), "{bad}: {err}");
        }
    }
}
