//! Photon counts beyond 4096 in a bench config: allowed up to 16384, where a technique can run
//! there by the renderer's rule (`adaptive` with a `photon_memory_limit`); a count no technique
//! of the config can run at, or a technique that runs at none of the counts, is an error
//! naming the file and the key.

use bench::config::LoadedConfig;
use caustics::scratch::ScratchDir;
use std::path::Path;

fn config(name: &str, photons: &str, adaptive_limit: u32) -> ScratchDir {
    let scene = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../scenes/sphere_on_plane.toml");
    let text = format!(
        r#"
[table]
paper = "p"
number = "1"
caption = "c"

[matrix]
scenes = ["{}"]
photons = {photons}

[[technique]]
label = "hier"
technique = "hcm"

[[technique]]
label = "adaptive"
technique = "adaptive"
photon_memory_limit = {adaptive_limit}

[[metric]]
label = "splatted"
kind = "splats_drawn"

[layout]
rows = ["photons"]
columns = ["technique"]
"#,
        scene.display()
    );
    let path = ScratchDir::new("bench-photon-limits", name).within(name);
    std::fs::write(&path, text).expect("write config");
    path
}

#[test]
fn counts_up_to_16384_load_where_a_technique_runs_there() {
    let lc = LoadedConfig::load(&config("ok.toml", "[1024, 8192, 16384]", 96)).expect("loads");
    let c = &lc.config;
    assert!(c.runs(1, 16384) && c.runs(1, 8192) && !c.runs(0, 8192) && c.runs(0, 1024));
}

#[test]
fn a_count_no_technique_runs_at_is_an_error_naming_the_key() {
    // Without a memory limit adaptive stops at 4096 too.
    let path = config("none_runs.toml", "[1024, 8192]", 0);
    let err = format!("{:#}", LoadedConfig::load(&path).expect_err("refused"));
    assert!(err.contains("none_runs.toml") && err.contains("matrix.photons") && err.contains("8192"), "{err}");
    // Above the most any technique takes.
    let path = config("too_many.toml", "[1024, 32768]", 96);
    let err = format!("{:#}", LoadedConfig::load(&path).expect_err("refused"));
    assert!(err.contains("matrix.photons") && err.contains("32768"), "{err}");
}

#[test]
fn a_technique_that_runs_at_no_count_is_an_error_naming_it() {
    let path = config("hier_nowhere.toml", "[8192, 16384]", 96);
    let err = format!("{:#}", LoadedConfig::load(&path).expect_err("refused"));
    assert!(err.contains("matrix.photons") && err.contains("`hier`") && err.contains("4096"), "{err}");
}
