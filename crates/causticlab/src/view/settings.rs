//! The panel's technique settings, generated from the settings table
//! (`caustics::techniques::settings`): every key of `[caustics]` with its help line and, for a
//! named value, its choices (from the `render` flags clap derives from the same table), its
//! current value (the settings serialized as TOML) and its owners. A new setting in the table
//! appears here without viewer code. A change is the TOML line `key = value` read as a
//! `[caustics]` override and checked as the command line is, so the panel, `--script` and the
//! flags give the same errors.

use caustics::scene::{CausticOverrides, CausticSettings};
use caustics::techniques::Technique;
use clap::Args as _;

/// What kind of value a setting takes, and so which widget shows it.
#[derive(Debug, Clone, PartialEq)]
pub enum Kind {
    /// One of named values (a combo box).
    Choice(Vec<String>),
    Bool,
    /// A number or anything else typed as TOML (a text field applied on Enter).
    Text,
}

/// One row of the panel.
#[derive(Debug, Clone)]
pub struct Setting {
    pub key: String,
    pub help: String,
    pub kind: Kind,
    /// The value in effect as TOML writes it (`"hcm"`, `512`, `1.5`, `true`); None: unset (the
    /// technique's own choice).
    pub value: Option<toml::Value>,
}

impl Setting {
    /// The value as the panel shows it (strings without quotes).
    pub fn shown(&self) -> String {
        match &self.value {
            Some(toml::Value::String(s)) => s.clone(),
            Some(v) => v.to_string(),
            None => String::new(),
        }
    }
}

/// The settings that apply to `s.technique` (those owned by other techniques left out), in the
/// table's order.
pub fn rows(s: &CausticSettings) -> Vec<Setting> {
    let values = match toml::Value::try_from(s) {
        Ok(toml::Value::Table(t)) => t,
        _ => Default::default(),
    };
    let cmd = CausticOverrides::augment_args(clap::Command::new("view"));
    let mut rows = vec![];
    for arg in cmd.get_arguments() {
        let key = arg.get_id().as_str().to_string();
        if let Some((_, owners)) = CausticSettings::OWNED.iter().find(|(k, _)| *k == key) {
            if !owners.contains(&s.technique) {
                continue;
            }
        }
        let value = values.get(&key).cloned();
        let choices: Vec<String> = arg.get_possible_values().iter().map(|v| v.get_name().to_string()).collect();
        let kind = match &value {
            Some(toml::Value::Boolean(_)) => Kind::Bool,
            _ if !choices.is_empty() && choices != ["true", "false"] => Kind::Choice(choices),
            _ => Kind::Text,
        };
        let help = arg.get_help().map(|h| h.to_string()).unwrap_or_default();
        rows.push(Setting { key, help, kind, value });
    }
    rows
}

/// `s` with `key` set to `text` (a number, `true`/`false` or a name, as in a scene's
/// `[caustics]`), checked like the command line's flags. Changing the technique first returns
/// every setting the new technique does not own to its default.
pub fn apply(s: &CausticSettings, key: &str, text: &str) -> anyhow::Result<CausticSettings> {
    let text = text.trim();
    // A name is a TOML string; numbers and booleans are themselves.
    let literal = if text.parse::<f64>().is_ok() || text == "true" || text == "false" {
        text.to_string()
    } else {
        toml::Value::String(text.to_string()).to_string()
    };
    let line = format!("{key} = {literal}");
    let overrides: CausticOverrides =
        toml::from_str(&line).map_err(|e| caustics::input_error!("`{line}`: {}", e.message()))?;
    let mut next = s.clone();
    if key == "technique" {
        if let Some(t) = overrides.technique {
            next = with_technique(s, t);
        }
    }
    overrides.apply(&mut next);
    next.validate("viewer", "")?;
    next.validate_combination("viewer", "")?;
    Ok(next)
}

/// `s` for technique `t`: the settings `t` does not own back to their defaults.
pub fn with_technique(s: &CausticSettings, t: Technique) -> CausticSettings {
    let d = CausticSettings::default();
    let (Ok(toml::Value::Table(mut now)), Ok(toml::Value::Table(defaults))) =
        (toml::Value::try_from(s), toml::Value::try_from(&d))
    else {
        return CausticSettings { technique: t, ..d };
    };
    for (key, owners) in CausticSettings::OWNED {
        if !owners.contains(&t) {
            match defaults.get(*key) {
                Some(v) => now.insert(key.to_string(), v.clone()),
                None => now.remove(*key),
            };
        }
    }
    now.insert("technique".into(), toml::Value::String(t.name().into()));
    let overrides: Result<CausticOverrides, _> = toml::Value::Table(now).try_into();
    let mut out = d;
    match overrides {
        Ok(o) => o.apply(&mut out),
        Err(_) => out.technique = t,
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn rows_follow_the_table_and_the_technique() {
        let s = CausticSettings { technique: Technique::Hcm, ..Default::default() };
        let r = rows(&s);
        let keys: Vec<&str> = r.iter().map(|r| r.key.as_str()).collect();
        // An hcm setting is there, a Shah-only one is not; shared ones are.
        assert!(keys.contains(&"cluster") && keys.contains(&"photons") && keys.contains(&"technique"), "{keys:?}");
        assert!(!keys.contains(&"refractions") && !keys.contains(&"kernel"), "{keys:?}");
        let technique = r.iter().find(|r| r.key == "technique").map(|r| r.kind.clone());
        match technique {
            Some(Kind::Choice(c)) => assert!(c.contains(&"shah".to_string()) && c.contains(&"adaptive".to_string())),
            other => panic!("technique row: {other:?}"),
        }
        let fresnel = r.iter().find(|r| r.key == "fresnel").map(|r| (r.kind.clone(), r.shown()));
        assert_eq!(fresnel, Some((Kind::Bool, "true".to_string())));
        let photons = r.iter().find(|r| r.key == "photons").map(|r| (r.kind.clone(), r.shown()));
        assert_eq!(photons, Some((Kind::Text, "512".to_string())));
        // Unset options are rows without a value.
        assert!(r.iter().any(|r| r.key == "intersect" && r.value.is_none()));
    }

    #[test]
    fn apply_checks_like_the_command_line() {
        let s = CausticSettings { technique: Technique::Shah, ..Default::default() };
        let t = apply(&s, "photons", "256").expect("photons 256");
        assert_eq!(t.photons, 256);
        let t = apply(&t, "refractions", "one").expect("a Shah setting");
        assert_eq!(t.refractions.name(), "one");
        // Switching technique drops what the new one does not own, keeps the rest.
        let h = apply(&t, "technique", "hcm").expect("to hcm");
        assert_eq!((h.technique, h.photons), (Technique::Hcm, 256));
        assert_eq!(h.refractions, CausticSettings::default().refractions);
        let err = apply(&s, "photons", "3").err().map(|e| e.to_string()).unwrap_or_default();
        assert!(err.contains("photons") && err.contains("64"), "{err}");
        let err = apply(&s, "cluster", "last").err().map(|e| e.to_string()).unwrap_or_default();
        assert!(err.contains("cluster"), "{err}");
        let err = apply(&s, "no_such_key", "1").err().map(|e| e.to_string()).unwrap_or_default();
        assert!(err.contains("no_such_key"), "{err}");
    }
}
