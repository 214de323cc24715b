//! The registry of variants: every technique variant the project stands behind, one row each
//! in `variants.toml` (its head says what a row holds). The conformance suite
//! (`tests/conformance.rs`) holds each row with a `stated` accuracy to it; `causticlab
//! variants` prints the rows for scripts (`scripts/same_maps.sh`, `scripts/quality_table.sh`)
//! and readers; tests check the README's technique table, `docs/command_line.md` and the
//! quality and front configs against them.

use super::{CausticOverrides, CausticSettings, Technique};
use serde::Deserialize;
use vkcore::Feature;

/// The registry, compiled into the binary.
const REGISTRY: &str = include_str!("variants.toml");

/// The papers a row may name: the claims check's keys, and `causticlab` beyond them.
pub const PAPERS: &[&str] =
    &["causticlab", "trendall2000", "shah", "wyman_davis2006", "wyman2008", "wyman_nichols2009"];

/// Where a row is rendered when it names no scenes: the two sphere scenes of the conformance
/// suite.
pub const SPHERE_SCENES: &[&str] = &["sphere_on_plane", "sphere_oblique"];

/// What a variant promises on the sphere scenes at the conformance settings.
#[derive(Debug, Clone, Copy, PartialEq, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Stated {
    /// Largest |caustic-map power / landed photon power - 1|.
    pub power: f64,
    /// Largest relative RMSE of the receiver map against the exact reference.
    pub rel_rmse: f64,
}

/// One row of the registry.
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Variant {
    pub name: String,
    pub label: String,
    pub paper: String,
    pub section: String,
    /// The technique's defaults: what `--technique` alone renders.
    #[serde(default)]
    pub default: bool,
    pub settings: CausticOverrides,
    pub stated: Option<Stated>,
    /// Also held to `stated` with the photon buffer made by deferred shading.
    #[serde(default)]
    pub deferred_photons: bool,
    /// In `scripts/quality_table.sh`'s tables.
    #[serde(default)]
    pub quality: bool,
    scenes: Option<Vec<String>>,
    /// Frames the conformance suite renders before it reads the row's buffers (a progressive
    /// row's accumulation); 1 when unset.
    frames: Option<u32>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct File {
    variant: Vec<Variant>,
}

impl Variant {
    pub fn technique(&self) -> Technique {
        self.settings.technique.unwrap_or(Technique::None)
    }

    /// The scenes (names under `scenes/`) the row is rendered on.
    pub fn scenes(&self) -> Vec<&str> {
        match &self.scenes {
            Some(s) => s.iter().map(String::as_str).collect(),
            None => SPHERE_SCENES.to_vec(),
        }
    }

    /// Frames rendered before the row is read (`frames`, at least 1).
    pub fn frames(&self) -> u32 {
        self.frames.unwrap_or(1).max(1)
    }

    /// The settings as `render` flags: `--technique wd-points --splat thin-lens`.
    pub fn flags(&self) -> Vec<String> {
        let table = toml::Value::try_from(&self.settings).ok();
        let mut out = vec![];
        for key in self.settings.keys_set() {
            let value = match table.as_ref().and_then(|t| t.get(key)) {
                Some(toml::Value::String(s)) => s.clone(),
                Some(v) => v.to_string(),
                None => continue,
            };
            out.push(format!("--{}", key.replace('_', "-")));
            out.push(value);
        }
        out
    }

    /// The settings in effect: the defaults with the row's settings over them.
    pub fn settings_in_effect(&self) -> CausticSettings {
        let mut s = CausticSettings::default();
        self.settings.apply(&mut s);
        s
    }

    /// The device features the row's settings need beyond its technique's own
    /// (`Technique::required_features`): those of its refraction, photon refraction, traversal
    /// path, splat path and own settings (`CausticSettings::device_needs`, what
    /// `render::check_device` requires). `photon-trace --trace ray-query` needs acceleration
    /// structures and ray queries, `--path xfb` transform feedback, the compute splat float
    /// atomics. A device without them refuses the row by name; the conformance suite and
    /// `scripts/same_maps.sh` skip it there with a line saying so (`scripts/mesa25_check.sh`
    /// runs every row on Mesa 25).
    pub fn needs(&self) -> Vec<Feature> {
        let own = self.technique().required_features();
        let mut out: Vec<Feature> = vec![];
        for (_, features) in self.settings_in_effect().device_needs() {
            for f in features {
                if !own.contains(f) && !out.contains(f) {
                    out.push(*f);
                }
            }
        }
        out
    }

    /// [`Self::needs`] by name, `-` for none: `acceleration_structure,ray_query`.
    pub fn needs_names(&self) -> String {
        let names: Vec<&str> = self.needs().iter().map(|f| f.name()).collect();
        if names.is_empty() {
            "-".to_string()
        } else {
            names.join(",")
        }
    }
}

/// Every row, in the registry's order, each checked (see [`parse`]).
pub fn registry() -> anyhow::Result<Vec<Variant>> {
    parse(REGISTRY, "crates/caustics/src/techniques/variants.toml")
}

/// Reads a registry and checks each row: a unique name (lower-case words joined by `-`) and
/// label, a technique, a known paper, settings that belong together and are in range, `stated`
/// only for a technique that renders meshes (pool-convolution states its accuracy in its own
/// suite) and with positive bounds, `deferred_photons` only with `stated` and a photon buffer;
/// and, over all rows, exactly one `default` row for every technique.
pub fn parse(text: &str, origin: &str) -> anyhow::Result<Vec<Variant>> {
    let file: File = toml::from_str(text).map_err(|e| crate::input_error!("{origin}: {e}"))?;
    let rows = file.variant;
    let bad =
        |name: &str, msg: String| -> anyhow::Error { crate::input_error!("{origin}: variant `{name}`: {msg}").into() };
    for (i, v) in rows.iter().enumerate() {
        let n = v.name.as_str();
        let word = |w: &str| !w.is_empty() && w.chars().all(|c| c.is_ascii_lowercase() || c.is_ascii_digit());
        if !n.split('-').all(word) {
            return Err(bad(n, "a name is lower-case letters and digits, words joined by `-`".into()));
        }
        if rows[..i].iter().any(|o| o.name == v.name) {
            return Err(bad(n, "a second row of this name".into()));
        }
        if rows[..i].iter().any(|o| o.label == v.label) {
            return Err(bad(n, format!("label `{}` is another row's", v.label)));
        }
        // `causticlab variants --lines` separates its fields with `|`, one row per line.
        if v.label.contains(['|', '\n']) || v.section.contains('\n') {
            return Err(bad(n, "a label has no `|` and a label or section no line break".into()));
        }
        if v.scenes.as_ref().is_some_and(|s| s.is_empty() || s.iter().any(|x| x.is_empty() || x.contains([',', '|']))) {
            return Err(bad(n, "scenes: one or more scene names (files under scenes/, without .toml)".into()));
        }
        if v.technique() == Technique::PoolConvolution && v.scenes.is_none() {
            return Err(bad(n, "pool-convolution renders pool scenes only: name them in `scenes`".into()));
        }
        // The quality table sets the photon count and Fresnel itself.
        if v.quality && (v.settings.photons.is_some() || v.settings.fresnel.is_some()) {
            return Err(bad(n, "a quality row leaves photons and fresnel to scripts/quality_table.sh".into()));
        }
        if v.flags().len() != 2 * v.settings.keys_set().len() {
            return Err(bad(n, format!("settings {:?} do not all read as flags", v.settings.keys_set())));
        }
        if v.settings.technique.is_none() {
            return Err(bad(n, "settings name no technique".into()));
        }
        if !PAPERS.contains(&v.paper.as_str()) {
            return Err(bad(n, format!("paper `{}` is none of {}", v.paper, PAPERS.join(", "))));
        }
        let s = v.settings_in_effect();
        s.validate(origin, &format!("variant {n}: settings."))?;
        s.validate_combination(origin, &format!("variant {n}: settings."))?;
        if let Some(st) = v.stated {
            if !v.technique().renders_meshes() {
                return Err(bad(
                    n,
                    format!("`{}` renders no mesh scene: its suite states its accuracy", v.technique()),
                ));
            }
            if !(st.power > 0.0 && st.rel_rmse > 0.0) {
                return Err(bad(n, format!("stated bounds must be > 0, got {st:?}")));
            }
        }
        if v.deferred_photons && (v.stated.is_none() || !v.technique().has_photon_buffer()) {
            return Err(bad(n, "deferred_photons holds a stated accuracy of a photon-buffer technique".into()));
        }
    }
    for &t in Technique::ALL {
        let defaults = rows.iter().filter(|v| v.default && v.technique() == t).count();
        if defaults != 1 {
            return Err(
                crate::input_error!("{origin}: technique `{t}` has {defaults} rows marked default, not 1").into()
            );
        }
    }
    Ok(rows)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_registry_reads_and_every_technique_has_its_default() {
        let rows = registry().expect("the registry");
        let wd = rows.iter().find(|v| v.name == "wd-points-thin-lens").expect("a row");
        assert_eq!(wd.flags(), ["--technique", "wd-points", "--splat", "thin-lens"]);
        assert_eq!(wd.scenes(), SPHERE_SCENES);
        let one = rows.iter().find(|v| v.name == "shah-one-iteration").expect("a row");
        assert_eq!(one.flags(), ["--technique", "shah", "--iterations", "1", "--fresnel", "false"]);
        let pool = rows.iter().find(|v| v.name == "pool-float").expect("a row");
        assert_eq!(pool.scenes(), ["pool", "pool_oblique"]);
    }

    /// What a row needs of the device follows from its settings: nothing beyond the technique
    /// for the compute traversal, acceleration structures and ray queries for ray queries.
    #[test]
    fn a_rows_needs_follow_from_its_settings() {
        let rows = registry().expect("the registry");
        let get = |name: &str| rows.iter().find(|v| v.name == name).unwrap_or_else(|| panic!("row {name}"));
        assert_eq!(get("photon-trace").needs(), []);
        assert_eq!(get("photon-trace").needs_names(), "-");
        assert_eq!(get("photon-trace-ray-query").needs(), [Feature::AccelerationStructure, Feature::RayQuery]);
        assert_eq!(get("photon-trace-ray-query").needs_names(), "acceleration_structure,ray_query");
        assert_eq!(get("photon-trace-receiver-map").needs(), [Feature::BufferFloat32AtomicAdd]);
        // Beyond photon-trace: the compute splat's float atomics, the xfb path's transform
        // feedback (its geometry shader is adaptive's own), nothing for the paper's defaults.
        assert_eq!(get("wd-points-compute-splat").needs(), [Feature::BufferFloat32AtomicAdd]);
        let xfb = get("adaptive").needs();
        assert!(xfb.contains(&Feature::TransformFeedback) && !xfb.contains(&Feature::GeometryShader), "{xfb:?}");
        assert_eq!(get("shah").needs(), []);
    }

    /// Each rule of [`parse`], broken by one row of an otherwise valid registry.
    #[test]
    fn a_row_that_breaks_a_rule_is_refused_by_name() {
        let row = |name: &str, extra: &str| {
            format!("[[variant]]\nname = \"{name}\"\nlabel = \"{name}\"\npaper = \"shah\"\nsection = \"3\"\n{extra}\n")
        };
        let defaults: String = Technique::ALL
            .iter()
            .map(|t| {
                let scenes = if *t == Technique::PoolConvolution { "\nscenes = [\"pool\"]" } else { "" };
                row(&format!("d-{t}"), &format!("default = true\nsettings = {{ technique = \"{t}\" }}{scenes}"))
            })
            .collect();
        assert!(parse(&defaults, "r.toml").is_ok(), "{:?}", parse(&defaults, "r.toml").err());
        let cases = [
            (row("Bad_Name", "settings = { technique = \"shah\" }"), "lower-case"),
            (row("x", "settings = { technique = \"shah\" }").replace("label = \"x\"", "label = \"d-shah\""), "is another row's"),
            (row("x", "settings = { technique = \"shah\" }").replace("label = \"x\"", "label = \"a|b\""), "no `|`"),
            (row("x", "settings = { technique = \"shah\" }\nscenes = []"), "scenes"),
            (row("x", "settings = { technique = \"pool-convolution\", precision = \"f64\" }"), "pool scenes only"),
            (row("x", "settings = { technique = \"shah\", photons = 256 }\nquality = true"), "leaves photons"),
            (row("x", "settings = { technique = \"shah\" }\nstated = { power = 0.1, rel_rmse = -1.0 }"), "> 0"),
            (row("d-shah", "settings = { technique = \"shah\" }"), "a second row"),
            (row("x", "settings = { photons = 256 }"), "no technique"),
            (row("x", "settings = { technique = \"shah\" }").replace("\"shah\"\nsection", "\"nobody\"\nsection"), "paper"),
            (row("x", "settings = { technique = \"shah\", photons = 5 }"), "settings.photons"),
            (row("x", "settings = { technique = \"shah\", cluster = \"last\" }"), "settings.cluster"),
            (row("x", "settings = { technique = \"shah\" }\nstated = { power = 0.0, rel_rmse = 0.1 }"), "> 0"),
            (row("x", "settings = { technique = \"pool-convolution\" }\nscenes = [\"pool\"]\nstated = { power = 1.0, rel_rmse = 0.1 }"), "renders no mesh"),
            (row("x", "settings = { technique = \"adaptive\" }\nstated = { power = 1.0, rel_rmse = 0.1 }\ndeferred_photons = true"), "deferred_photons"),
            (row("x", "settings = { technique = \"shah\" }\ndeferred_photons = true"), "deferred_photons"),
            (row("x", "default = true\nsettings = { technique = \"shah\" }"), "2 rows marked default"),
            (row("x", "settings = { technique = \"shah\" }\ncolour = 1"), "unknown field"),
        ];
        for (extra, want) in cases {
            let text = format!("{defaults}{extra}");
            let e = parse(&text, "r.toml").err().unwrap_or_else(|| panic!("accepted: {extra}"));
            let msg = format!("{e:#}");
            assert!(msg.contains(want) && msg.contains("r.toml"), "{extra}: {msg}");
        }
        let no_default = defaults.replace(
            "name = \"d-hcm\"\nlabel = \"d-hcm\"\npaper = \"shah\"\nsection = \"3\"\ndefault = true",
            "name = \"d-hcm\"\nlabel = \"d-hcm\"\npaper = \"shah\"\nsection = \"3\"",
        );
        let e = parse(&no_default, "r.toml").expect_err("hcm has no default row");
        assert!(format!("{e:#}").contains("`hcm` has 0 rows"), "{e:#}");
    }
}
