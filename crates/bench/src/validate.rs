//! Checks a parsed config before anything runs: ranges, names, files, and that the layout and
//! the paper's values fit the matrix. Every message names the file and the key.

use crate::config::{fnv1a, Config, LoadedConfig, MAX_FRAMES, MAX_PHOTONS, MAX_RESOLUTION, METRIC_KINDS};
use anyhow::{Context as _, Result};
use caustics::animation::PATHS;
use caustics::input_error;
use caustics::scene::CausticSettings;
use caustics::techniques::wyman2008::photon_copy::COPY_TYPES;
use caustics::techniques::SplatPath;
use std::path::Path;

impl LoadedConfig {
    /// Reads, parses and validates the bench config at `path`.
    pub fn load(path: &Path) -> Result<LoadedConfig> {
        let bytes =
            std::fs::read(path).map_err(|e| input_error!("{}: cannot read the bench config: {e}", path.display()))?;
        let text = String::from_utf8(bytes.clone())
            .map_err(|_| input_error!("{}: the bench config is not UTF-8", path.display()))?;
        // The scene parser's error mapping: unknown keys name their path (`technique[0].clustr`).
        let config: Config = caustics::scene::parse_toml(path, &text)?;
        let name = path
            .file_stem()
            .and_then(|s| s.to_str())
            .with_context(|| format!("{}: the config file has no name", path.display()))?
            .to_string();
        let loaded = LoadedConfig { path: path.to_path_buf(), name, hash: fnv1a(&bytes), text, config };
        validate(&loaded)?;
        Ok(loaded)
    }
}

pub fn validate(lc: &LoadedConfig) -> Result<()> {
    let file = lc.path.display().to_string();
    let c = &lc.config;
    let bad = |key: &str, msg: String| -> anyhow::Error { input_error!("{file}: key `{key}`: {msg}").into() };
    let unique = |key: &str, v: Vec<String>| -> Result<()> {
        for (i, x) in v.iter().enumerate() {
            if v[..i].contains(x) {
                return Err(bad(key, format!("`{x}` appears twice")));
            }
        }
        Ok(())
    };
    for (key, v) in
        [("table.paper", &c.table.paper), ("table.number", &c.table.number), ("table.caption", &c.table.caption)]
    {
        if v.trim().is_empty() {
            return Err(bad(key, "must not be empty".into()));
        }
    }
    if let Some(f) = &c.front {
        crate::front::validate(c, f, &bad)?;
    }
    crate::final_flip::validate(c, &bad)?;
    let r = &c.run;
    if r.warmup_frames > MAX_FRAMES {
        return Err(bad("run.warmup_frames", format!("{} is more than {MAX_FRAMES}", r.warmup_frames)));
    }
    if !(1..=MAX_FRAMES).contains(&r.measured_frames) {
        return Err(bad(
            "run.measured_frames",
            format!("must be between 1 and {MAX_FRAMES}, got {}", r.measured_frames),
        ));
    }
    check_budget(&bad, "run", r.time_budget_s, r.measured_frames, r.max_frames)?;
    for (key, p) in
        [("run.light_path", &r.light_path), ("run.camera_path", &r.camera_path), ("run.object_path", &r.object_path)]
    {
        if !PATHS.contains(&p.as_str()) {
            return Err(bad(key, format!("unknown path `{p}`; expected one of {}", PATHS.join(", "))));
        }
    }
    if !(1..=1000).contains(&r.block_frames) {
        return Err(bad("run.block_frames", format!("must be between 1 and 1000, got {}", r.block_frames)));
    }
    if !(1..=MAX_FRAMES).contains(&r.period_frames) {
        return Err(bad("run.period_frames", format!("must be between 1 and {MAX_FRAMES}, got {}", r.period_frames)));
    }

    let m = &c.matrix;
    if m.scenes.is_empty() {
        return Err(bad("matrix.scenes", "lists no scene".into()));
    }
    for s in &m.scenes {
        let p = lc.scene_path(s);
        if !p.is_file() {
            return Err(bad("matrix.scenes", format!("scene `{s}` not found (looked for {})", p.display())));
        }
    }
    unique("matrix.scenes", m.scenes.iter().map(|s| crate::plan::scene_label(s)).collect())?;
    check_photons(&bad, "matrix.photons", &m.photons)?;
    for &l in &m.lights {
        if !(1..=caustics::gpu::MAX_LIGHTS as u32).contains(&l) {
            let max = caustics::gpu::MAX_LIGHTS;
            return Err(bad("matrix.lights", format!("{l} lights: must be between 1 and {max}")));
        }
    }
    unique("matrix.lights", m.lights.iter().map(|l| l.to_string()).collect())?;
    check_resolutions(&bad, "matrix.resolution", &m.resolution)?;
    unique("matrix.resolution", m.resolution.iter().map(|r| format!("{}x{}", r[0], r[1])).collect())?;
    if m.lighting.is_empty() {
        return Err(bad("matrix.lighting", "lists nothing; use [\"dynamic\"], [\"static\"] or both".into()));
    }
    for l in &m.lighting {
        if l != "static" && l != "dynamic" {
            return Err(bad("matrix.lighting", format!("unknown lighting `{l}`; expected static or dynamic")));
        }
    }
    unique("matrix.lighting", m.lighting.clone())?;

    for k in c.caustics.keys_set() {
        if k == "technique" || k == "photons" {
            return Err(bad(&format!("caustics.{k}"), "set per [[technique]] entry and by `matrix.photons`".into()));
        }
        if let Some((_, owners)) = CausticSettings::OWNED.iter().find(|(name, _)| *name == k) {
            let owners: Vec<&str> = owners.iter().map(|t| t.name()).collect();
            return Err(bad(
                &format!("caustics.{k}"),
                format!("a setting of technique {} only: set it in those [[technique]] entries", owners.join(", ")),
            ));
        }
    }

    if c.techniques.is_empty() {
        return Err(bad("technique", "no [[technique]] entries".into()));
    }
    unique("technique.label", c.techniques.iter().map(|t| t.label.clone()).collect())?;
    for (i, t) in c.techniques.iter().enumerate() {
        let key = |k: &str| format!("technique[{i}].{k}");
        let Some(technique) = t.settings.technique else {
            return Err(bad(&key("technique"), "missing; every [[technique]] names its technique".into()));
        };
        if t.settings.photons.is_some() {
            return Err(bad(&key("photons"), "set by `matrix.photons`, not per technique".into()));
        }
        if !COPY_TYPES.contains(&t.photon_copy.as_str()) {
            return Err(bad(
                &key("photon_copy"),
                format!("unknown copy `{}`; expected one of {}", t.photon_copy, COPY_TYPES.join(", ")),
            ));
        }
        if t.photon_copy != "none" && !technique.splats_the_photon_buffer() {
            return Err(bad(
                &key("photon_copy"),
                format!("copies a photon buffer, which technique `{technique}` does not have"),
            ));
        }
        if t.photon_copy != "none" && t.settings.splat_path == Some(SplatPath::Compute) {
            return Err(bad(
                &key("photon_copy"),
                "the copied vertex array is splatted as points; it has no compute splat (splat_path = \"compute\")"
                    .into(),
            ));
        }
        let s = c.technique_settings(i);
        s.validate(&file, &format!("technique[{i}]."))?;
        s.validate_combination(&file, &format!("technique[{i}]."))?;
    }

    check_runnable(c, &bad, "matrix.photons", &m.photons)?;

    if c.metrics.is_empty() {
        return Err(bad("metric", "no [[metric]] entries".into()));
    }
    unique("metric.label", c.metrics.iter().map(|m| m.label.clone()).collect())?;
    // The plausibility rules' declarations.
    let matrix_axes = ["scene", "technique", "photons", "lights", "resolution", "lighting"];
    for (k, a) in c.plausibility.work_grows_with.iter().enumerate() {
        if !["scene", "technique", "photons", "lights", "resolution"].contains(&a.as_str()) {
            return Err(bad(
                &format!("plausibility.work_grows_with[{k}]"),
                format!("`{a}`: the work can grow along scene, technique, photons, lights or resolution"),
            ));
        }
    }
    for (k, e) in c.plausibility.explained.iter().enumerate() {
        if !["a", "b", "c", "d", "e", "f", "g"].contains(&e.rule.as_str()) {
            return Err(bad(
                &format!("plausibility.explained[{k}].rule"),
                format!("`{}`: rules are a to g (bench_configs/README.md)", e.rule),
            ));
        }
        if !c.metrics.iter().any(|m| m.label == e.metric) {
            return Err(bad(
                &format!("plausibility.explained[{k}].metric"),
                format!("no metric is labelled `{}`", e.metric),
            ));
        }
        if e.why.trim().is_empty() {
            return Err(bad(&format!("plausibility.explained[{k}].why"), "say why, citing a measurement".into()));
        }
    }
    for (i, mt) in c.metrics.iter().enumerate() {
        for (k, a) in mt.independent_of.iter().enumerate() {
            if !matrix_axes.contains(&a.as_str()) {
                return Err(bad(
                    &format!("metric[{i}].independent_of[{k}]"),
                    format!("`{a}`: expected one of {}", matrix_axes.join(", ")),
                ));
            }
        }
        // Rules c and f read a time in ms or a rate in M photons/s: no other kind.
        if mt.bytes_per_photon.is_some() && !crate::plausibility::takes_bytes_per_photon(&mt.kind) {
            let takes: Vec<&str> =
                METRIC_KINDS.iter().copied().filter(|k| crate::plausibility::takes_bytes_per_photon(k)).collect();
            return Err(bad(
                &format!("metric[{i}].bytes_per_photon"),
                format!(
                    "kind `{}` is neither a time in ms nor a photon rate: only {} take it",
                    mt.kind,
                    takes.join(", ")
                ),
            ));
        }
        if let Some(crate::config::BytesPerPhoton::ByTechnique(m)) = &mt.bytes_per_photon {
            if let Some(t) = m.keys().find(|t| !c.techniques.iter().any(|x| &x.label == *t)) {
                return Err(bad(&format!("metric[{i}].bytes_per_photon"), format!("no technique is labelled `{t}`")));
            }
        }
    }
    for (i, mt) in c.metrics.iter().enumerate() {
        if !crate::config::is_depth_complexity_metric(&mt.kind) {
            continue;
        }
        let quads = Some(caustics::techniques::Technique::WdQuads);
        if let Some((k, t)) = c.techniques.iter().enumerate().find(|(_, t)| t.settings.technique != quads) {
            return Err(bad(
                &format!("metric[{i}].kind"),
                format!(
                    "`{}` counts the caustic quads' fragments: every technique must be wd-quads, technique[{k}] (`{}`) is not",
                    mt.kind, t.label
                ),
            ));
        }
    }
    for (i, mt) in c.metrics.iter().enumerate() {
        if !METRIC_KINDS.contains(&mt.kind.as_str()) {
            return Err(bad(
                &format!("metric[{i}].kind"),
                format!("unknown kind `{}`; expected one of {}", mt.kind, METRIC_KINDS.join(", ")),
            ));
        }
        let per_pass = matches!(
            mt.kind.as_str(),
            "pass_ms" | "pass_fps" | "pass_mphotons" | "pass_host_ms" | "pass_host_mphotons"
        );
        // A progressive metric may time its frames by their passes (or their wall time).
        let optional = crate::progressive::is_progressive_metric(&mt.kind);
        if !optional && per_pass == mt.passes.is_empty() {
            let msg = if mt.passes.is_empty() {
                format!("kind {} needs `passes`", mt.kind)
            } else {
                "only kinds pass_ms, pass_fps, pass_mphotons, pass_host_ms, pass_host_mphotons and the progressive \
                 ones take `passes`"
                    .to_string()
            };
            return Err(bad(&format!("metric[{i}].passes"), msg));
        }
        match mt.mode() {
            "per-pass" => {}
            "throughput" if !crate::config::THROUGHPUT_KINDS.contains(&mt.kind.as_str()) => {
                return Err(bad(
                    &format!("metric[{i}].mode"),
                    format!(
                        "kind `{}` needs per-pass timestamps; throughput metrics are {}",
                        mt.kind,
                        crate::config::THROUGHPUT_KINDS.join(", ")
                    ),
                ))
            }
            "throughput" if !mt.exclude.is_empty() => {
                return Err(bad(
                    &format!("metric[{i}].exclude"),
                    "throughput frames time no pass alone: `exclude` needs mode = \"per-pass\"".into(),
                ))
            }
            "throughput" => {}
            other => {
                return Err(bad(
                    &format!("metric[{i}].mode"),
                    format!("`{other}`: expected `per-pass` or `throughput`"),
                ))
            }
        }
        if !mt.exclude.is_empty() && !matches!(mt.kind.as_str(), "fps" | "frame_ms" | "frame_mphotons") {
            return Err(bad(
                &format!("metric[{i}].exclude"),
                "only kinds fps, frame_ms and frame_mphotons take `exclude`".into(),
            ));
        }
    }

    let q = &c.quick;
    check_photons(&bad, "quick.photons", &q.photons)?;
    check_runnable(c, &bad, "quick.photons", &q.photons)?;
    check_resolutions(&bad, "quick.resolution", &q.resolution)?;
    unique("quick.resolution", q.resolution.iter().map(|r| format!("{}x{}", r[0], r[1])).collect())?;
    if !(1..=MAX_FRAMES).contains(&q.measured_frames) {
        return Err(bad("quick.measured_frames", format!("must be between 1 and {MAX_FRAMES}")));
    }
    if q.warmup_frames > MAX_FRAMES {
        return Err(bad("quick.warmup_frames", format!("must be at most {MAX_FRAMES}")));
    }
    check_budget(&bad, "quick", q.time_budget_s, q.measured_frames, q.max_frames)?;
    if let Some(scenes) = &q.scenes {
        if scenes.is_empty() {
            return Err(bad(
                "quick.scenes",
                "empty: name some of `matrix.scenes`, or leave the key out for all".into(),
            ));
        }
        if let Some(s) = scenes.iter().find(|s| !c.matrix.scenes.contains(s)) {
            return Err(bad("quick.scenes", format!("`{s}` is not one of `matrix.scenes`")));
        }
        unique("quick.scenes", scenes.clone())?;
    }
    if !(16..=8192).contains(&q.caustic_map_resolution) {
        return Err(bad(
            "quick.caustic_map_resolution",
            format!("must be between 16 and 8192, got {}", q.caustic_map_resolution),
        ));
    }
    for (key, n) in
        [("quality.reference_photons", c.quality.reference_photons), ("quick.reference_photons", q.reference_photons)]
    {
        if !(1..=1 << 30).contains(&n) {
            return Err(bad(key, format!("{n}: must be between 1 and 2^30")));
        }
    }
    // Along an animation a quality metric compares the last frame with the CPU reference of
    // that frame's pose. temporal_change compares each frame with the one before it.
    // The receiver map moves with the light and the objects, not with the camera.
    let moving = [&r.light_path, &r.object_path].iter().any(|p| *p != "static");
    let moving_camera = r.camera_path != "static";
    let posed = moving || moving_camera;
    for (i, mt) in c.metrics.iter().enumerate() {
        if !crate::config::is_pose_metric(&mt.kind) {
            continue;
        }
        if !posed {
            return Err(bad(
                &format!("metric[{i}].kind"),
                format!(
                    "`{}` measures the pose updates between frames: it needs something that moves (run.light_path, \
                     run.camera_path or run.object_path = \"orbit\")",
                    mt.kind
                ),
            ));
        }
        if c.matrix.lighting.iter().any(|l| l == "static") && !moving_camera {
            return Err(bad(
                "matrix.lighting",
                format!(
                    "`static` keeps the light and the objects still, and no camera path moves: `{}` (metric[{i}]) would \
                     have no pose update to measure",
                    mt.kind
                ),
            ));
        }
        // Frame 0 is the scene's own pose: a pose update comes before every later frame.
        for (key, warmup, measured) in [
            ("run.measured_frames", r.warmup_frames, r.measured_frames),
            ("quick.measured_frames", c.quick.warmup_frames, c.quick.measured_frames),
        ] {
            if warmup + measured < 2 {
                return Err(bad(
                    key,
                    format!(
                        "`{}` (metric[{i}]) measures the pose update before each frame after the first: warm-up and \
                         measured frames must be at least 2 together, got {warmup} and {measured}",
                        mt.kind
                    ),
                ));
            }
        }
    }
    for (i, mt) in c.metrics.iter().enumerate() {
        if !crate::config::is_temporal_metric(&mt.kind) {
            continue;
        }
        if !moving {
            return Err(bad(
                &format!("metric[{i}].kind"),
                "`temporal_change` compares each frame's receiver map with the last one's: it needs a moving \
                 light or objects (run.light_path or run.object_path = \"orbit\")"
                    .into(),
            ));
        }
        if c.matrix.lighting.iter().any(|l| l == "static") {
            return Err(bad(
                "matrix.lighting",
                format!("`static` keeps the light and the objects still, which `temporal_change` (metric[{i}]) needs moving"),
            ));
        }
        for (key, n) in [("run.measured_frames", r.measured_frames), ("quick.measured_frames", c.quick.measured_frames)]
        {
            if n < 2 {
                return Err(bad(
                    key,
                    format!("`temporal_change` (metric[{i}]) compares consecutive frames: needs at least 2, got {n}"),
                ));
            }
        }
        let timed = c.metrics.iter().position(|m| !m.throughput() && crate::results::is_timing(&m.kind));
        if let Some(j) = timed {
            return Err(bad(
                &format!("metric[{j}].kind"),
                format!(
                    "`{}` times the per-pass frames, which `temporal_change` (metric[{i}]) reads back after every \
                     frame: put them in separate configs, or time them in throughput mode",
                    c.metrics[j].kind
                ),
            ));
        }
    }
    validate_progressive(c, moving, &bad)?;
    crate::validate_layout::validate_layout(lc, &bad)
}

/// The progressive metrics (`crate::progressive`): each reads its curve at `frames` or at
/// `after_ms` as its kind allows, within [`crate::progressive::MAX_FRAMES`] and an hour; they
/// share their `passes` (one time per frame); the light and objects stay still (a pose that
/// moves them starts the means again), and `static` lighting, which reuses the photons, is
/// refused.
fn validate_progressive(
    c: &crate::config::Config,
    moving: bool,
    bad: &dyn Fn(&str, String) -> anyhow::Error,
) -> Result<()> {
    use crate::progressive::{is_progressive_metric, MAX_FRAMES};
    let mut passes: Option<&Vec<String>> = None;
    for (i, m) in c.metrics.iter().enumerate() {
        let progressive = is_progressive_metric(&m.kind);
        if !progressive {
            for (key, set) in [("frames", m.frames.is_some()), ("after_ms", m.after_ms.is_some())] {
                if set {
                    return Err(bad(
                        &format!("metric[{i}].{key}"),
                        format!("is where a progressive metric reads its curve; `{}` has no curve", m.kind),
                    ));
                }
            }
            continue;
        }
        let (frames_ok, ms_ok) = match m.kind.as_str() {
            "progressive_ms" => (true, false),
            "progressive_frames" => (false, true),
            _ => (true, true),
        };
        match (m.frames, m.after_ms) {
            (Some(_), Some(_)) => {
                return Err(bad(&format!("metric[{i}]"), "set `frames` or `after_ms`, not both".into()));
            }
            (None, None) => {
                let which = match (frames_ok, ms_ok) {
                    (true, true) => "`frames` or `after_ms`",
                    (true, false) => "`frames`",
                    _ => "`after_ms`",
                };
                return Err(bad(
                    &format!("metric[{i}]"),
                    format!("`{}` needs {which}: where it reads the curve", m.kind),
                ));
            }
            (Some(n), None) if !frames_ok || !(1..=MAX_FRAMES).contains(&n) => {
                let msg = match frames_ok {
                    true => format!("must be between 1 and {MAX_FRAMES}, got {n}"),
                    false => format!("`{}` reads the curve at a time: set `after_ms`", m.kind),
                };
                return Err(bad(&format!("metric[{i}].frames"), msg));
            }
            (None, Some(t)) if !(ms_ok && t.is_finite() && t > 0.0 && t <= 3.6e6) => {
                let msg = match ms_ok {
                    true => format!("must be in (0, 3600000] ms, got {t}"),
                    false => format!("`{}` reads the curve at a frame: set `frames`", m.kind),
                };
                return Err(bad(&format!("metric[{i}].after_ms"), msg));
            }
            _ => {}
        }
        if passes.is_some_and(|p| p != &m.passes) {
            return Err(bad(
                &format!("metric[{i}].passes"),
                "the progressive metrics time one curve: give them the same `passes`".into(),
            ));
        }
        passes = Some(&m.passes);
        if moving {
            return Err(bad(
                &format!("metric[{i}].kind"),
                format!(
                    "`{}` accumulates frames of a still light and still objects (a pose that moves them starts the \
                     means again): run.light_path and run.object_path must be \"static\"",
                    m.kind
                ),
            ));
        }
        if c.matrix.lighting.iter().any(|l| l == "static") {
            return Err(bad(
                "matrix.lighting",
                format!(
                    "`static` reuses the last frame's photons, which `{}` (metric[{i}]) needs new every frame",
                    m.kind
                ),
            ));
        }
    }
    Ok(())
}

/// Longest time budget a cell may have, seconds.
const MAX_BUDGET_S: f64 = 3600.0;

fn check_budget(
    bad: &dyn Fn(&str, String) -> anyhow::Error,
    section: &str,
    budget: f64,
    min: u32,
    max: Option<u32>,
) -> Result<()> {
    if !(budget.is_finite() && (0.0..=MAX_BUDGET_S).contains(&budget)) {
        return Err(bad(
            &format!("{section}.time_budget_s"),
            format!("must be between 0 and {MAX_BUDGET_S} seconds, got {budget}"),
        ));
    }
    if let Some(max) = max {
        if !(min..=MAX_FRAMES).contains(&max) {
            return Err(bad(
                &format!("{section}.max_frames"),
                format!("must be between {section}.measured_frames ({min}) and {MAX_FRAMES}, got {max}"),
            ));
        }
    }
    Ok(())
}

fn check_photons(bad: &dyn Fn(&str, String) -> anyhow::Error, key: &str, v: &[u32]) -> Result<()> {
    if v.is_empty() {
        return Err(bad(key, "lists no photon count".into()));
    }
    for &p in v {
        if !(64..=MAX_PHOTONS).contains(&p) {
            return Err(bad(key, format!("{p}: photon counts per side must be between 64 and {MAX_PHOTONS}")));
        }
    }
    if (1..v.len()).any(|i| v[..i].contains(&v[i])) {
        return Err(bad(key, "lists a photon count twice".into()));
    }
    Ok(())
}

/// Every photon count some technique can run at, and every technique at some photon count (by
/// the renderer's rule, [`Config::runs`]); cells that cannot run are N/A. Checked after the
/// techniques' own settings.
fn check_runnable(c: &Config, bad: &dyn Fn(&str, String) -> anyhow::Error, key: &str, v: &[u32]) -> Result<()> {
    let techniques = 0..c.techniques.len();
    for &p in v {
        if !techniques.clone().any(|t| c.runs(t, p)) {
            return Err(bad(
                key,
                format!(
                    "{p}: no technique of this config runs at {p}² photons (more than 4096 per side only \
                     `adaptive` with a photon_memory_limit)"
                ),
            ));
        }
    }
    for t in techniques {
        if !v.iter().any(|&p| c.runs(t, p)) {
            let most = c.technique_settings(t).most_photons();
            return Err(bad(
                key,
                format!("technique `{}` runs at none of these counts (it takes at most {most})", c.techniques[t].label),
            ));
        }
    }
    Ok(())
}

fn check_resolutions(bad: &dyn Fn(&str, String) -> anyhow::Error, key: &str, v: &[[u32; 2]]) -> Result<()> {
    for r in v {
        if r.iter().any(|&x| !(1..=MAX_RESOLUTION).contains(&x)) {
            return Err(bad(key, format!("{}x{}: sides must be between 1 and {MAX_RESOLUTION}", r[0], r[1])));
        }
    }
    Ok(())
}
