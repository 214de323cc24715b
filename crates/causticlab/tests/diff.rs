//! `causticlab diff`: two renders of the same settings are the same; a changed texel, a changed
//! photon count, a missing dump or a texel list in another order are found, each named.

mod common;

use caustics::image_io::{read_exr, write_exr};
use common::*;
use std::path::Path;

fn render(out: &Path) {
    let run = causticlab(&[
        "render",
        "--scene",
        &scene("sphere_on_plane"),
        "--technique",
        "hcm",
        "--photons",
        "64",
        "--caustic-map-resolution",
        "64",
        "--dump",
        "receiver,splats",
        "--out",
        &out.display().to_string(),
    ]);
    assert_eq!(run.code, Some(0), "{}", run.describe());
}

fn diff(a: &Path, b: &Path, extra: &[&str]) -> Run {
    let mut args = vec!["diff".to_string(), a.display().to_string(), b.display().to_string()];
    args.extend(extra.iter().map(|s| s.to_string()));
    causticlab(&args)
}

fn copy_dir(from: &Path, to: &Path) {
    std::fs::create_dir_all(to).unwrap();
    for e in std::fs::read_dir(from).unwrap() {
        let e = e.unwrap();
        std::fs::copy(e.path(), to.join(e.file_name())).unwrap();
    }
}

#[test]
fn renders_that_differ_are_told_apart_by_file_channel_and_count() {
    let dir = scratch("diff");
    let (a, b) = (dir.join("a"), dir.join("b"));
    render(&a);
    render(&b);
    // The same settings twice (the transform-feedback path: a fixed order): identical.
    let same = diff(&a, &b, &[]);
    assert_eq!(same.code, Some(0), "{}", same.describe());
    assert!(same.stdout.contains("receiver.exr: same") && same.stdout.contains("timings.json counts: same"));
    assert!(same.stdout.contains("timings.json pass names: same"), "{}", same.describe());
    let counts: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(a.join("timings.json")).unwrap()).unwrap();
    assert!(counts["counts"]["splats_drawn"].as_u64().is_some_and(|n| n > 0), "{counts}");

    // One texel of one channel moved by 1%.
    let changed = dir.join("changed");
    copy_dir(&b, &changed);
    let mut img = read_exr(&changed.join("receiver.exr")).unwrap();
    let layer = img.layers.iter_mut().find(|l| l.name.as_deref() == Some("irradiance")).expect("irradiance layer");
    let i = layer.data.iter().position(|v| *v > 0.0).unwrap();
    layer.data[i] *= 1.01;
    write_exr(&changed.join("receiver.exr"), &img).unwrap();
    let run = diff(&a, &changed, &[]);
    assert_eq!(run.code, Some(1), "{}", run.describe());
    assert!(
        run.stdout.contains("receiver.exr: irradiance.") && run.stdout.contains("1 texels differ"),
        "{}",
        run.describe()
    );
    // A difference is diff's answer, not an error.
    assert!(run.stdout.contains("1 difference(s) between"), "{}", run.describe());
    assert!(!run.stderr.contains("error"), "{}", run.describe());
    // Within a tolerance above the change, the same.
    assert_eq!(diff(&a, &changed, &["--tolerance", "0.5"]).code, Some(0));

    // The splats' order changed: differs as an image, the same as an unordered list.
    let reordered = dir.join("reordered");
    copy_dir(&b, &reordered);
    let mut splats = read_exr(&reordered.join("splats.exr")).unwrap();
    for layer in &mut splats.layers {
        let n = layer.channels.len();
        let texels = layer.data.len() / n;
        let (first, rest) = layer.data.split_at_mut(n);
        first.swap_with_slice(&mut rest[(texels - 2) * n..]);
    }
    write_exr(&reordered.join("splats.exr"), &splats).unwrap();
    assert_eq!(diff(&a, &reordered, &[]).code, Some(1));
    let unordered = diff(&a, &reordered, &["--unordered", "splats"]);
    assert_eq!(unordered.code, Some(0), "{}", unordered.describe());
    // The same, with every dump declared a list of records unordered (splats is one).
    let records = diff(&a, &reordered, &["--unordered-records"]);
    assert_eq!(records.code, Some(0), "{}", records.describe());
    assert!(records.stdout.contains("splats.exr (unordered)"), "{}", records.describe());
    // A misspelt name is refused, not an option silently off.
    for flag in ["--unordered", "--ignore"] {
        let typo = diff(&a, &reordered, &[flag, "splat"]);
        assert_eq!(typo.code, Some(2), "{flag}\n{}", typo.describe());
        assert!(typo.stderr.contains(flag) && typo.stderr.contains("splat:"), "{}", typo.describe());
    }
    // Two files: --unordered may name B's stem (here a dump's too), and --ignore, which leaves out
    // files of folders, is refused.
    let (fa, fb) = (a.join("splats.exr"), reordered.join("splats.exr"));
    assert_eq!(diff(&fa, &fb, &["--unordered", "splats"]).code, Some(0));
    let renamed = dir.join("renamed_splats.exr");
    std::fs::copy(&fb, &renamed).unwrap();
    assert_eq!(diff(&fa, &renamed, &["--unordered", "renamed_splats"]).code, Some(0));
    let ignore = diff(&fa, &fb, &["--ignore", "splats"]);
    assert_eq!(ignore.code, Some(2), "{}", ignore.describe());
    assert!(ignore.stderr.contains("--ignore") && ignore.stderr.contains("folders"), "{}", ignore.describe());
    // An image is not a list: receiver texels swapped still differ under --unordered-records.
    let swapped = dir.join("swapped");
    copy_dir(&b, &swapped);
    let mut receiver = read_exr(&swapped.join("receiver.exr")).unwrap();
    for layer in &mut receiver.layers {
        let n = layer.channels.len();
        let texels = layer.data.len() / n;
        let Some(i) = (0..texels).find(|&t| layer.data[t * n] != layer.data[0]) else { continue };
        let (first, rest) = layer.data.split_at_mut(n);
        first.swap_with_slice(&mut rest[(i - 1) * n..i * n]);
    }
    write_exr(&swapped.join("receiver.exr"), &receiver).unwrap();
    let image = diff(&a, &swapped, &["--unordered-records"]);
    assert_eq!(image.code, Some(1), "{}", image.describe());
    assert!(!image.stdout.contains("receiver.exr (unordered)"), "{}", image.describe());

    // A photon count changed, and a dump missing on one side.
    let recounted = dir.join("recounted");
    copy_dir(&b, &recounted);
    let text = std::fs::read_to_string(recounted.join("timings.json")).unwrap();
    let mut v: serde_json::Value = serde_json::from_str(&text).unwrap();
    let drawn = v["counts"]["splats_drawn"].as_u64().unwrap();
    v["counts"]["splats_drawn"] = (drawn + 1).into();
    v["passes"][0]["name"] = "renamed.light0".into();
    std::fs::write(recounted.join("timings.json"), v.to_string()).unwrap();
    std::fs::remove_file(recounted.join("splats.exr")).unwrap();
    let run = diff(&a, &recounted, &[]);
    assert_eq!(run.code, Some(1), "{}", run.describe());
    assert!(
        run.stdout.contains("timings.json counts:") && run.stdout.contains("splats.exr: only in"),
        "{}",
        run.describe()
    );

    // A folder against a file is the user's mistake.
    let run = diff(&a, &b.join("final.exr"), &[]);
    assert_eq!(run.code, Some(2), "{}", run.describe());
    assert!(run.stderr.contains("two EXR files or two folders"), "{}", run.describe());
    // A file that cannot be read is trouble (2), not a difference (1), as in diff(1).
    let broken = dir.join("broken.exr");
    std::fs::write(&broken, b"not an EXR").unwrap();
    let run = diff(&b.join("final.exr"), &broken, &[]);
    assert_eq!(run.code, Some(2), "{}", run.describe());
    assert!(run.stderr.contains("error:") && run.stderr.contains("not a readable OpenEXR file"), "{}", run.describe());
    assert_eq!(run.stderr.matches("broken.exr").count(), 1, "the file named once\n{}", run.describe());
}
