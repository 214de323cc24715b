//! Our FLIP (`caustics::flip`) against NVIDIA's reference implementation, flip-evaluator 1.7 from
//! PyPI, on the pairs in `tests/fixtures/flip/` (`scripts/flip_fixtures.sh` made them and ran the
//! reference on them; `manifest.toml` holds its means, exposures, pixels per degree and magma
//! colours; `*.map.f32` its per-pixel maps). docs/flip.md says what the pairs are.
//!
//! Tolerances: per pixel, |ours − reference| ≤ [`MAP_TOLERANCE`]; the mean within
//! [`MEAN_TOLERANCE`]; the exposures within [`EXPOSURE_TOLERANCE`] stops and their count equal;
//! the magma colours equal. Both compute in f32 in the same order; what is left is rounding
//! (docs/flip.md gives what each pair reached). On a failure the two maps are written as magma
//! PNGs into the test's temporary folder, named in the message.

use caustics::flip::{self, colormap, Exposures, Rgb};
use serde::Deserialize;
use std::path::{Path, PathBuf};

/// The largest per-pixel difference allowed from the reference's map (every pixel of every pair
/// is identical on x86-64 Linux; the margin is for another libm's `expf` and `powf`).
const MAP_TOLERANCE: f32 = 1e-5;
/// The largest difference allowed from the reference's mean: it sums its map in f32 pixel by
/// pixel, we in f64 ([`the_reference_s_mean_is_its_map_summed_in_f32`] shows that this is all
/// that differs).
const MEAN_TOLERANCE: f64 = 2e-6;
/// The largest difference allowed from the reference's start and stop exposures, in stops.
const EXPOSURE_TOLERANCE: f64 = 1e-5;

#[derive(Deserialize)]
struct Manifest {
    flip_evaluator: String,
    width: usize,
    height: usize,
    pair: Vec<Pair>,
    magma: Vec<[f64; 4]>,
}

#[derive(Deserialize)]
struct Pair {
    name: String,
    kind: String,
    reference: String,
    test: String,
    ppd: f64,
    ppd_given: bool,
    mean: f64,
    map: String,
    exposures: Option<String>,
    start_exposure: Option<f64>,
    stop_exposure: Option<f64>,
    exposure_count: Option<usize>,
}

fn folder() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/fixtures/flip")
}

fn manifest() -> Manifest {
    let text = std::fs::read_to_string(folder().join("manifest.toml")).expect("tests/fixtures/flip/manifest.toml");
    toml::from_str(&text).unwrap_or_else(|e: toml::de::Error| panic!("manifest.toml: {}", e.message()))
}

/// An IEEE half float (binary16) as f32: every half is exact in f32.
fn half_to_f32(h: u16) -> f32 {
    let sign = if h & 0x8000 != 0 { -1.0 } else { 1.0 };
    let (exponent, mantissa) = (i32::from((h >> 10) & 0x1f), f32::from(h & 0x3ff));
    sign * match exponent {
        0 => mantissa * 2f32.powi(-24),
        31 if mantissa == 0.0 => f32::INFINITY,
        31 => f32::NAN,
        e => (1.0 + mantissa / 1024.0) * 2f32.powi(e - 15),
    }
}

fn read_rgb(m: &Manifest, file: &str) -> Rgb {
    let bytes = std::fs::read(folder().join(file)).unwrap_or_else(|e| panic!("{file}: {e}"));
    if file.ends_with(".f16") {
        let values: Vec<f32> = bytes.chunks_exact(2).map(|b| half_to_f32(u16::from_le_bytes([b[0], b[1]]))).collect();
        Rgb::new(m.width, m.height, &values).unwrap()
    } else {
        assert!(file.ends_with(".srgb8"), "{file}: neither .f16 nor .srgb8");
        Rgb::from_srgb8(m.width, m.height, &bytes).unwrap()
    }
}

fn read_map(file: &str) -> Vec<f32> {
    let bytes = std::fs::read(folder().join(file)).unwrap_or_else(|e| panic!("{file}: {e}"));
    bytes.chunks_exact(4).map(|b| f32::from_le_bytes([b[0], b[1], b[2], b[3]])).collect()
}

/// The pair's ppd: the default unless the fixture gave one (whose value the reference reports).
fn ppd(p: &Pair) -> f64 {
    if p.ppd_given {
        p.ppd
    } else {
        flip::default_ppd()
    }
}

/// Ours on the pair, as the reference ran it: the map, and for HDR the exposures.
fn ours(m: &Manifest, p: &Pair) -> (flip::FlipMap, Option<flip::HdrFlip>) {
    let (reference, test) = (read_rgb(m, &p.reference), read_rgb(m, &p.test));
    if p.kind == "ldr" {
        return (flip::ldr(&reference, &test, ppd(p)).unwrap(), None);
    }
    let exposures = match p.exposures.as_deref() {
        Some("auto") => Exposures::Auto,
        Some("given") => Exposures::Given { start: p.start_exposure.unwrap(), stop: p.stop_exposure.unwrap() },
        other => panic!("{}: exposures {other:?}", p.name),
    };
    let r = flip::hdr(&reference, &test, ppd(p), exposures).unwrap();
    (r.map.clone(), Some(r))
}

#[test]
fn every_map_and_mean_is_the_reference_s() {
    let m = manifest();
    let mut report = vec![];
    let mut failed = vec![];
    for p in &m.pair {
        let (map, _) = ours(&m, p);
        let reference = read_map(&p.map);
        assert_eq!(reference.len(), map.values.len(), "{}", p.name);
        let diffs: Vec<f32> = map.values.iter().zip(&reference).map(|(a, b)| (a - b).abs()).collect();
        let max = diffs.iter().copied().fold(0.0f32, f32::max);
        let over = diffs.iter().filter(|&&d| d > MAP_TOLERANCE).count();
        let identical = diffs.iter().filter(|&&d| d == 0.0).count();
        let mean_diff = (map.mean - p.mean).abs();
        report.push(format!(
            "{:8} max |Δ| {max:.2e}, {identical} of {} pixels identical, mean {:.6} against {:.6} (|Δ| {mean_diff:.1e})",
            p.name,
            diffs.len(),
            map.mean,
            p.mean
        ));
        if max > MAP_TOLERANCE || mean_diff > MEAN_TOLERANCE {
            let dir = PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join("flip_reference");
            std::fs::create_dir_all(&dir).unwrap();
            map.write_magma_png(&dir.join(format!("{}.ours.png", p.name))).unwrap();
            colormap::write_magma_png(&dir.join(format!("{}.reference.png", p.name)), m.width, m.height, &reference)
                .unwrap();
            failed.push(format!("{}: {over} pixels over {MAP_TOLERANCE:e} (maps in {})", p.name, dir.display()));
        }
    }
    println!("{}", report.join("\n"));
    assert!(failed.is_empty(), "{}\n{}", failed.join("\n"), report.join("\n"));
}

/// The reference's mean is `Σ e / n` with `Σ` an f32 running sum in row order
/// (`FLIP::evaluate`), which our f64 sum of the same values differs from by rounding alone.
#[test]
fn the_reference_s_mean_is_its_map_summed_in_f32() {
    for p in &manifest().pair {
        let map = read_map(&p.map);
        let sum = map.iter().fold(0.0f32, |acc, &e| acc + e);
        assert_eq!(sum / map.len() as f32, p.mean as f32, "{}", p.name);
    }
}

#[test]
fn the_exposures_are_the_reference_s() {
    let m = manifest();
    let mut checked = 0;
    for p in m.pair.iter().filter(|p| p.kind == "hdr") {
        let (_, r) = ours(&m, p);
        let r = r.unwrap();
        let (start, stop) = (p.start_exposure.unwrap(), p.stop_exposure.unwrap());
        assert!(
            (r.start_exposure - start).abs() <= EXPOSURE_TOLERANCE
                && (r.stop_exposure - stop).abs() <= EXPOSURE_TOLERANCE,
            "{}: exposures {} to {}, the reference's {start} to {stop}",
            p.name,
            r.start_exposure,
            r.stop_exposure
        );
        assert_eq!(r.exposure_count, p.exposure_count.unwrap(), "{}: the number of exposures", p.name);
        checked += usize::from(p.exposures.as_deref() == Some("auto"));
    }
    assert!(checked >= 3, "the automatic range is checked on {checked} pairs");
}

#[test]
fn the_colour_map_gives_the_reference_s_colours() {
    let m = manifest();
    let mut entries = std::collections::BTreeSet::new();
    for &[error, r, g, b] in &m.magma {
        let ours = colormap::magma(error as f32);
        assert_eq!(ours, [r as f32, g as f32, b as f32], "error {error}");
        entries.insert(colormap::magma_index(error as f32));
    }
    assert!(entries.len() >= 250, "the fixtures show {} of the 256 entries", entries.len());
}

#[test]
fn the_fixtures_are_flip_evaluator_1_7_s_at_the_default_viewing() {
    let m = manifest();
    assert_eq!(m.flip_evaluator, "1.7");
    for p in m.pair.iter().filter(|p| !p.ppd_given) {
        assert_eq!(flip::default_ppd() as f32, p.ppd as f32, "{}: the default pixels per degree", p.name);
    }
    let kinds: Vec<&str> = m.pair.iter().map(|p| p.kind.as_str()).collect();
    assert!(kinds.contains(&"ldr") && kinds.iter().filter(|k| **k == "hdr").count() >= 4, "{kinds:?}");
}

#[test]
fn half_floats_decode() {
    assert_eq!(half_to_f32(0x3c00), 1.0);
    assert_eq!(half_to_f32(0x5240), 50.0);
    assert_eq!(half_to_f32(0x0001), 2f32.powi(-24));
    assert_eq!(half_to_f32(0xc000), -2.0);
    assert_eq!(half_to_f32(0x7c00), f32::INFINITY);
}
