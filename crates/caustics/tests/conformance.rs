//! The conformance suite: every row of the registry of variants
//! (`crates/caustics/src/techniques/variants.toml`) that states an accuracy, on both sphere
//! scenes, validation layer on:
//! - renders with no validation message;
//! - conserves caustic power: the caustic map holds the power of the photons that landed (read
//!   from the photon buffer dump; `adaptive`: from its output photons), within the row's
//!   stated tolerance (`stated.power`);
//! - stays within its stated error of the exact CPU photon reference (relative RMSE and caustic
//!   flux ratio of the receiver map, `caustics::compare`; `stated.rel_rmse`);
//! - writes every dump it declares (`render::dumps_for`) and no other.
//!
//! A row whose settings need a device feature beyond its technique's (`Variant::needs`: ray
//! queries for `photon-trace-ray-query`) is skipped, with a line naming it, on a device without
//! it; `scripts/mesa25_check.sh` runs `conformance_beyond_the_papers` on Mesa 25's lavapipe with
//! `CAUSTICLAB_REQUIRE_FEATURES` set, where a skip fails.
//!
//! Every technique that renders meshes has a row that states an accuracy (checked below), so a
//! technique is covered the moment it is added; a row added to the registry is run here at once
//! (one test per paper of `variants::PAPERS`, checked below too). Rows marked `deferred_photons`
//! are also held to it with their photon buffer made by deferred shading.
//! `none` has no caustics, and `pool-convolution` renders pool scenes only (it refuses the
//! sphere scenes, checked here); its own suite is `tests/trendall_stewart2000_pool.rs`.
//!
//! Settings: 256² photons, Fresnel on (transmittance at both interfaces, as the techniques
//! apply it), a 512² caustic map, then the row's settings. Wyman & Davis 2006's rows that state
//! an accuracy light their photons from the light's direction (Eq. 11 and Eq. 4: for a
//! Lambertian receiver these keep a photon's flux, where Eq. 9, 10 and 3 re-light it with
//! cos(photon) / cos(direct): `tests/wyman_davis2006.rs` checks those against the photons'
//! cosines, and `results/quality/` measures them). The reference traces 2M photons with exact Fresnel, internal reflections and
//! total internal reflection, leaving out only the light the sphere reflects off its outside
//! (`outside_reflection: false`), which no paper draws (5% of the caustic flux here, measured
//! in `results/quality/README.md`); its own noise is about 0.02 relative RMSE. Each scene's
//! reference is traced once for the whole file.
//!
//! A light-space technique's receiver map averages the caustic map's irradiance over each
//! receiver texel (`caustic_irradiance_over` in `shaders_glsl/common/caustic_lookup.glsl`), as
//! the reference does: a point sample per texel aliased between the two grids and moved the
//! caustic flux by up to 7%.
//!
//! Power: a technique with a caustic map must hold in it the power of the photons that landed;
//! an eye-space one (whose receiver map comes from its orthographic receiver view) must put on
//! the receiver map the power of the photons that landed on the receiver rectangle.

// `!(error <= bound)` fails a NaN, where `error > bound` would pass it.
#![allow(clippy::neg_cmp_op_on_partial_ord)]

use caustics::compare::compare;
use caustics::dump::Dump;
use caustics::image_io::ImageF32;
use caustics::reference::{trace_reference, ReferenceOptions};
use caustics::render::{all_dump_names, dumps_for, FrameStep, Renderer, RendererOptions};
use caustics::scene::Scene;
use caustics::techniques::variants::{registry, Variant};
use caustics::techniques::wyman2008::SplatMode;
use caustics::techniques::{PhotonRefraction, Technique};
use std::path::PathBuf;
use std::sync::OnceLock;
use vkcore::Context;

mod common;
use common::{context, runs_here};

/// Every technique's caustic flux is within this fraction of the reference's (the issue "Faithful
/// by default": 3%, no technique excepted). The losses the papers make by design (quads culled
/// where a photon did not land or the block spans surfaces, the gathers' three-photon rule,
/// splats too wide for the multi-resolution map) are each bounded by their power drift (the
/// registry's `stated.power`), and stay within this bound too (measured: 0.984-1.006 of the
/// reference's flux over every test of this file).
const FLUX_WITHIN: f64 = 0.03;

const SCENES: [&str; 2] = ["sphere_on_plane", "sphere_oblique"];

/// The exact reference of each of [`SCENES`], traced once for all the tests of this file (they
/// run in parallel; the first to need a scene's traces it, the others wait for it).
static REFERENCES: [OnceLock<ImageF32>; 2] = [OnceLock::new(), OnceLock::new()];

/// A sphere scene at the suite's settings (256² photons, Fresnel on, a 512² caustic map, a 128²
/// eye), with `technique`.
fn load(name: &str, technique: Technique) -> Scene {
    let p = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join(format!("../../scenes/{name}.toml"));
    let mut s = Scene::load(&p).expect("shipped scene");
    s.caustics.technique = technique;
    s.caustics.photons = 256;
    s.caustics.fresnel = true;
    s.caustics.caustic_map_resolution = 512;
    if technique == Technique::PhotonTrace {
        // The reference leaves out what the sphere reflects off its outside (below).
        s.caustics.outside_reflection = false;
    }
    s.camera.width = 128;
    s.camera.height = 128;
    s
}

/// Sum over texels of the mean of channels R, G, B of `layer` (where `valid`, if given, is
/// over 0.5).
fn power(img: &ImageF32, layer: &str, valid: Option<&str>) -> f64 {
    let l = img.layer(Some(layer)).unwrap_or_else(|| panic!("no layer {layer}"));
    let v = valid.map(|v| img.layer(Some(v)).unwrap_or_else(|| panic!("no layer {v}")));
    let nc = l.channels.len();
    (0..(img.width * img.height) as usize)
        .filter(|&i| v.is_none_or(|v| v.data[i * v.channels.len() + 3] > 0.5))
        .map(|i| (l.data[i * nc] as f64 + l.data[i * nc + 1] as f64 + l.data[i * nc + 2] as f64) / 3.0)
        .sum()
}

/// Light 0's caustic-map power: its layer, or the levels of its multi-resolution map
/// (`light0_level<i>`).
fn light0_power(cmap: &ImageF32) -> f64 {
    let names: Vec<&str> = cmap
        .layers
        .iter()
        .filter_map(|l| l.name.as_deref())
        .filter(|n| *n == "light0" || n.starts_with("light0_level"))
        .collect();
    assert!(!names.is_empty(), "no light0 layer in the caustic map");
    names.iter().map(|n| power(cmap, n, None)).sum()
}

/// The power (mean of R, G, B, in W) of the adaptive traversal's output photons, from the
/// `adaptive_lists` dump: the photons that landed (with batches, those converged above the
/// batches' level and every batch's).
fn adaptive_landed(lists: &ImageF32) -> f64 {
    let photons: Vec<_> = lists
        .layers
        .iter()
        .filter(|l| l.name.as_deref().is_some_and(|n| n.starts_with("light0.") && n.ends_with("photons")))
        .collect();
    assert!(!photons.is_empty(), "no photons layer");
    photons
        .iter()
        .flat_map(|l| l.data.chunks_exact(l.channels.len()))
        .filter(|r| r[10] > 0.5)
        .map(|r| (r[6] as f64 + r[7] as f64 + r[8] as f64) / 3.0)
        .sum()
}

/// Photons that landed on the receiver rectangle of `scene` (mean of R, G, B, in W).
fn landed_on_receiver(photons: &ImageF32, scene: &Scene) -> f64 {
    let r = scene.receiver_map.as_ref().expect("a receiver map");
    let pos = photons.layer(Some("light0.position")).expect("positions");
    let pow = photons.layer(Some("light0.power")).expect("power");
    let (np, nw) = (pos.channels.len(), pow.channels.len());
    (0..(photons.width * photons.height) as usize)
        .filter(|&i| {
            let p = &pos.data[i * np..i * np + 4];
            p[3] > 0.5
                && (p[0] - r.x_range[0]) * (p[0] - r.x_range[1]) < 0.0
                && (p[2] - r.z_range[0]) * (p[2] - r.z_range[1]) < 0.0
                && (p[1] - r.plane_y).abs() < 1e-2
        })
        .map(|i| (pow.data[i * nw] as f64 + pow.data[i * nw + 1] as f64 + pow.data[i * nw + 2] as f64) / 3.0)
        .sum()
}

/// The caustic flux of a receiver map's `caustic` layer (W).
fn receiver_flux(receiver: &ImageF32, scene: &Scene) -> f64 {
    let r = scene.receiver_map.as_ref().expect("a receiver map");
    let area = (r.x_range[1] - r.x_range[0]) as f64 * (r.z_range[1] - r.z_range[0]) as f64
        / (r.resolution as f64 * r.resolution as f64);
    power(receiver, "caustic", None) * area
}

/// The exact reference of `scene_name`, traced the first time a test needs it.
fn reference_of<'a>(scene_name: &str, cell: &'a OnceLock<ImageF32>) -> &'a ImageF32 {
    cell.get_or_init(|| {
        let opts =
            ReferenceOptions { photons: 2_000_000, fresnel: true, outside_reflection: false, ..Default::default() };
        trace_reference(&load(scene_name, Technique::None), &opts).expect("reference").image
    })
}

/// The registry's rows that state an accuracy, of `paper`.
fn stated_rows(paper: &str) -> Vec<Variant> {
    registry().expect("the registry").into_iter().filter(|v| v.paper == paper && v.stated.is_some()).collect()
}

/// Renders each row on both sphere scenes (with its photon buffer made by deferred shading where
/// `photon_refraction` says so) and returns what broke its stated accuracy.
fn check(rows: &[Variant], photon_refraction: PhotonRefraction) -> Vec<String> {
    let (ctx, sh) = context();
    let rows: Vec<&Variant> = rows.iter().filter(|r| runs_here(&ctx, r)).collect();
    let mut failures = vec![];
    for (scene_name, reference) in SCENES.iter().zip(&REFERENCES) {
        let reference = reference_of(scene_name, reference);
        for row in &rows {
            let t = row.technique();
            let mut scene = load(scene_name, t);
            row.settings.apply(&mut scene.caustics);
            if photon_refraction == PhotonRefraction::Deferred {
                scene.caustics.photon_refraction = photon_refraction;
            }
            let mut label = row.name.clone();
            if photon_refraction == PhotonRefraction::Deferred {
                label += " (deferred photons)";
            }
            let mut r = Renderer::new(&ctx, &sh, &scene, &RendererOptions::default()).expect("renderer");
            for _ in 0..row.frames() {
                r.frame(FrameStep::default()).expect("frame");
            }
            let dumps = every_dump(&ctx, &mut r, &scene, &label, scene_name);
            let receiver = &dumps.iter().find(|(n, _)| n == "receiver").expect("a receiver map").1;
            let (c, _) = compare(receiver, reference).expect("compare");
            let want = row.stated.expect("a row with a stated accuracy");
            let get = |name: &str| &dumps.iter().find(|(n, _)| n == name).unwrap_or_else(|| panic!("{name}")).1;
            let (landed, held) = if scene.caustics.eye_space() {
                (landed_on_receiver(get("photon_buffer"), &scene), receiver_flux(receiver, &scene))
            } else if t == Technique::Adaptive {
                (adaptive_landed(get("adaptive_lists")), light0_power(get("caustic_map")))
            } else if scene.caustics.splat == SplatMode::Interpolated {
                // Every layer holds every photon at its own radius: the layer farthest from
                // the power that landed is the one compared.
                let (cmap, landed) =
                    (get("caustic_map"), power(get("photon_buffer"), "light0.power", Some("light0.position")));
                let levels = (0..4).map(|i| power(cmap, &format!("light0_level{i}"), None));
                (landed, levels.max_by(|a, b| (a - landed).abs().total_cmp(&(b - landed).abs())).expect("4 layers"))
            } else {
                (power(get("photon_buffer"), "light0.power", Some("light0.position")), light0_power(get("caustic_map")))
            };
            let drift = held / landed - 1.0;
            println!(
                "{scene_name:16} {label:36} power drift {drift:+.2e}  rel. RMSE {:.4}  flux ratio {:.4}",
                c.rel_rmse, c.caustic_flux_ratio
            );
            if !(drift.abs() <= want.power) {
                failures.push(format!("{label} on {scene_name}: holds {held} W, landed {landed} W"));
            }
            if !c.within(want.rel_rmse, FLUX_WITHIN) {
                failures.push(format!("{label} on {scene_name}: {c:?} outside its stated error"));
            }
        }
    }
    failures
}

/// Every dump the frame declares (`render::dumps_for`) and no other, with no validation message.
fn every_dump(
    ctx: &Context,
    r: &mut Renderer,
    scene: &Scene,
    label: &str,
    scene_name: &str,
) -> Vec<(String, ImageF32)> {
    let all: Vec<String> = all_dump_names().iter().map(|s| s.to_string()).collect();
    let dumps = r.dumps(&all).expect("dumps");
    let written: Vec<&'static Dump> = dumps.iter().map(|(d, _)| *d).collect();
    assert_eq!(written, dumps_for(&scene.caustics), "{label} on {scene_name}: dumps written vs declared");
    let log = ctx.validation_log();
    assert_eq!(log.count(), 0, "{label} on {scene_name}: validation messages:\n{}", log.messages().join("\n"));
    dumps.into_iter().map(|(d, img)| (d.name.to_string(), img)).collect()
}

fn assert_none(failures: Vec<String>) {
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}

/// Every technique that renders meshes states its accuracy in at least one row, so a technique
/// is held to the reference the moment it is added.
#[test]
fn every_mesh_technique_states_its_accuracy() {
    let rows = registry().expect("the registry");
    // `none` renders no caustics: the test below holds it to caustic flux 0.
    for &t in Technique::ALL.iter().filter(|&&t| t.renders_meshes() && t != Technique::None) {
        assert!(
            rows.iter().any(|v| v.technique() == t && v.stated.is_some()),
            "`{t}`: no registry row states its accuracy"
        );
    }
}

/// `none` renders no caustics (its receiver map is the direct light alone: caustic flux 0), and
/// `pool-convolution` refuses the sphere scenes (its suite is tests/trendall_stewart2000_pool.rs).
#[test]
fn none_has_no_caustics_and_pool_convolution_refuses_a_mesh_scene() {
    let (ctx, sh) = context();
    for (scene_name, reference) in SCENES.iter().zip(&REFERENCES) {
        let pool = load(scene_name, Technique::PoolConvolution);
        let err = Renderer::new(&ctx, &sh, &pool, &RendererOptions::default()).err().map(|e| e.to_string());
        assert!(err.as_deref().is_some_and(|e| e.contains("[pool]")), "pool-convolution on {scene_name}: {err:?}");
        let reference = reference_of(scene_name, reference);
        let scene = load(scene_name, Technique::None);
        let mut r = Renderer::new(&ctx, &sh, &scene, &RendererOptions::default()).expect("renderer");
        r.frame(FrameStep::default()).expect("frame");
        let dumps = every_dump(&ctx, &mut r, &scene, "none", scene_name);
        let receiver = &dumps.iter().find(|(n, _)| n == "receiver").expect("a receiver map").1;
        let (c, _) = compare(receiver, reference).expect("compare");
        assert_eq!(c.caustic_flux_ratio, 0.0, "none on {scene_name}: {c:?}");
    }
}

// One test per paper (they run in parallel): a row added to the registry is held here at once.
const TESTED_PAPERS: [&str; 5] = ["shah", "wyman_davis2006", "wyman2008", "wyman_nichols2009", "causticlab"];

/// Every row that states an accuracy is of a paper with its test below (a paper added to the
/// registry's list needs its test here).
#[test]
fn every_stated_row_is_of_a_tested_paper() {
    for v in registry().expect("the registry").iter().filter(|v| v.stated.is_some()) {
        assert!(TESTED_PAPERS.contains(&v.paper.as_str()), "{}: paper `{}` has no conformance test", v.name, v.paper);
    }
}

#[test]
fn conformance_shah() {
    assert_none(check(&stated_rows("shah"), PhotonRefraction::Forward));
}

#[test]
fn conformance_wyman_davis2006() {
    assert_none(check(&stated_rows("wyman_davis2006"), PhotonRefraction::Forward));
}

#[test]
fn conformance_wyman2008() {
    assert_none(check(&stated_rows("wyman2008"), PhotonRefraction::Forward));
}

#[test]
fn conformance_wyman_nichols2009() {
    assert_none(check(&stated_rows("wyman_nichols2009"), PhotonRefraction::Forward));
}

#[test]
fn conformance_beyond_the_papers() {
    assert_none(check(&stated_rows("causticlab"), PhotonRefraction::Forward));
}

/// The rows marked `deferred_photons`, with their photon buffer created by deferred shading
/// (Wyman & Nichols 2009's deferred caustic maps, `photon_refraction = deferred`): the same
/// photons, so the same stated accuracy.
#[test]
fn conformance_deferred_photons() {
    let rows: Vec<Variant> = registry().expect("the registry").into_iter().filter(|v| v.deferred_photons).collect();
    assert!(!rows.is_empty(), "no row marked deferred_photons");
    assert_none(check(&rows, PhotonRefraction::Deferred));
}
