//! Wyman 2008 Fig. 7's varying splats from a per-photon thin-lens model (`splat = thin-lens`):
//! what the setting needs of the others, and the uniform the shaders read it by. Its caustic,
//! against the exact photon reference, is held by the conformance suite to the registry rows `shah-thin-lens` and
//! `wd-points-thin-lens` (`conformance_wyman2008`).

use caustics::render::{Renderer, RendererOptions};
use caustics::scene::Scene;
use caustics::techniques::wyman2008::SplatMode;
use caustics::techniques::{CopyType, Technique};
use std::path::PathBuf;

mod common;
use common::context;

fn scene(technique: &str) -> Scene {
    let p = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../../scenes/sphere_on_plane.toml");
    let mut s = Scene::load(&p).expect("shipped scene");
    s.caustics.technique = technique.parse().expect("a known name");
    s.caustics.splat = "thin-lens".parse().expect("a known name");
    s.caustics.photons = 64;
    s.caustics.caustic_map_resolution = 64;
    s
}

/// Thin-lens splats size the photon buffer's points: shah and wd-points only, on the raster
/// path, in the fitted photon view, with the back faces the forward photon buffer draws; each
/// refusal names the key and what it needs.
#[test]
fn thin_lens_splats_belong_to_the_photon_buffers_points() {
    let refused: [(&str, &str, &str, &[&str]); 5] = [
        ("hcm", "", "", &["caustics.splat", "thin-lens", "shah or wd-points", "hcm"]),
        ("shah-vertex", "", "", &["caustics.splat", "shah-vertex"]),
        ("wd-points", "splat_path", "compute", &["caustics.splat", "compute"]),
        ("shah", "photon_refraction", "deferred", &["caustics.splat", "photon_refraction", "forward"]),
        ("wd-points", "photon_view", "shadow-map", &["caustics.splat", "fitted", "shadow-map"]),
    ];
    for (technique, key, value, needles) in refused {
        let mut s = scene(technique);
        match key {
            "splat_path" => s.caustics.splat_path = value.parse().expect("a known name"),
            "photon_refraction" => s.caustics.photon_refraction = value.parse().expect("a known name"),
            "photon_view" => s.caustics.photon_view = value.parse().expect("a known name"),
            _ => {}
        }
        let err = s.caustics.validate_combination("scene.toml", "caustics.").expect_err(technique).to_string();
        for n in needles {
            assert!(err.contains(n), "{technique} {key} {value}: `{err}` does not name {n}");
        }
    }
    for technique in ["shah", "wd-points"] {
        let s = scene(technique);
        s.caustics.validate_combination("scene.toml", "caustics.").unwrap_or_else(|e| panic!("{technique}: {e}"));
    }
}

/// Thin-lens splats size the photon buffer's own points: with a copy into a vertex array the
/// renderer refuses, naming both.
#[test]
fn a_copy_has_no_thin_lens_splats() {
    let (ctx, sh) = context();
    let opts = RendererOptions { photon_copy: Some(CopyType::Float32ToFloat32), ..Default::default() };
    let err = Renderer::new(&ctx, &sh, &scene("wd-points"), &opts).err().map(|e| e.to_string()).unwrap_or_default();
    assert!(err.contains("thin-lens") && err.contains("photon_copy"), "{err}");
}

/// The caustic uniforms' splat sizes (`splat.w`) read as `common/caustics.glsl`'s
/// SPLAT_VARYING_SINGLE for the techniques thin-lens sizes, SPLAT_FIXED for the others.
#[test]
fn thin_lens_packs_as_one_varying_map() {
    let p = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../../shaders_glsl/common/caustics.glsl");
    let text = std::fs::read_to_string(p).expect("shipped shader");
    let define = |name: &str| -> f32 {
        let line = text.lines().find(|l| l.split_whitespace().take(2).eq(["#define", name]));
        let v = line.and_then(|l| l.split_whitespace().nth(2)).unwrap_or_else(|| panic!("no #define {name}"));
        v.parse().unwrap_or_else(|e| panic!("#define {name} {v}: {e}"))
    };
    for t in [Technique::Shah, Technique::WdPoints] {
        assert_eq!(SplatMode::ThinLens.uniform(t), define("SPLAT_VARYING_SINGLE"), "{t}");
    }
    for t in [Technique::Hcm, Technique::Adaptive, Technique::ShahVertex] {
        assert_eq!(SplatMode::ThinLens.uniform(t), define("SPLAT_FIXED"), "{t}");
    }
}
