//! A crash is never silent: a SIGSEGV inside a pass (raised by vkcore's test hook after the
//! passes before it ran, as a driver crashing in that pass would leave the crash marker) prints
//! the driver, the frame and the pass before the process dies of the signal.

mod common;
use common::*;
use std::os::unix::process::ExitStatusExt;
use std::process::Command;

#[test]
fn a_segfault_inside_a_pass_names_the_pass_the_last_one_finished_and_the_driver() {
    let dir = scratch("crash");
    let (clean, crashed) = (dir.join("clean"), dir.join("crashed"));
    let args = |out: &std::path::Path| {
        vec![
            "render".to_string(),
            "--scene".into(),
            scene("sphere_on_plane"),
            "--technique".into(),
            "shah".into(),
            "--photons".into(),
            "64".into(),
            "--out".into(),
            out.display().to_string(),
        ]
    };
    // The passes in order, from a run that did not crash.
    let run = causticlab(&args(&clean));
    assert_eq!(run.code, Some(0), "{}", run.describe());
    let timings: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(clean.join("timings.json")).unwrap()).unwrap();
    let passes: Vec<&str> = timings["passes"].as_array().unwrap().iter().map(|p| p["name"].as_str().unwrap()).collect();
    let target = "photon_buffer.light0";
    let i = passes.iter().position(|p| *p == target).unwrap_or_else(|| panic!("{target} not in {passes:?}"));
    assert!(i > 0, "{target} must follow another pass: {passes:?}");
    let device = timings["device"]["name"].as_str().unwrap();

    // Through sh, to turn core files off for the crash (no unsafe pre_exec in this crate).
    let out = Command::new("sh")
        .arg("-c")
        .arg("ulimit -c 0; exec \"$0\" \"$@\"")
        .arg(env!("CARGO_BIN_EXE_causticlab"))
        .args(args(&crashed))
        .current_dir(workspace())
        .env(vkcore::TEST_SEGFAULT_ENV, target)
        .output()
        .unwrap();
    let stderr = String::from_utf8_lossy(&out.stderr);
    // SIGSEGV is 11 on Linux.
    assert_eq!(out.status.signal(), Some(11), "died of SIGSEGV: {:?}\n{stderr}", out.status);
    for needle in [
        "causticlab: fatal SIGSEGV (signal 11)".to_string(),
        format!("on device `{device}`, driver "),
        format!("its crash marker says {i} of its {} passes finished", i + 1),
        format!("the last `{}`", passes[i - 1]),
        format!("it stopped in pass `{target}`"),
    ] {
        assert!(stderr.contains(&needle), "stderr lacks {needle:?}:\n{stderr}");
    }
    assert!(!crashed.join("final.exr").exists(), "no result is written by a crashed frame");
}
