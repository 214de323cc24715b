//! Shah et al.'s caustics mapping tutorial as written (`faithful = true`): one refraction where
//! the light meets the object (its `psIntersectPts`), rayGeo with one iteration, and its
//! `psDiffuse` lookup, `diffuse + diffuse * pow(caustic, 1.3)` (`lookup = "tutorial"`).
//!
//! The lookup is checked against a CPU evaluation of the tutorial's formula on the physical
//! lookup's own receiver map, validation layer on: with c = E_caustic / E0 (the caustic
//! irradiance over the light's unoccluded irradiance, the scale `docs/papers.md` gives the
//! tutorial's map values), the tutorial's caustic term is E0 * c^1.3 texel for texel. Where the
//! caustic is brighter than the light unrefracted (c > 1, the focus) it reads brighter than the
//! physical lookup, and dimmer around it (c < 1).

use caustics::image_io::ImageF32;
use caustics::scene::{CausticOverrides, CausticSettings, Scene};

mod common;
use common::{render_dumps, shipped};

fn overrides(toml_text: &str) -> CausticOverrides {
    toml::from_str(toml_text).unwrap_or_else(|e| panic!("{toml_text}: {e}"))
}

/// The settings a scene's `[caustics]` (`scene`) and then a command line (`cli`) leave in effect,
/// or the error `validate_combination` gives.
fn settled(scene: &str, cli: &str) -> Result<CausticSettings, String> {
    let mut s = CausticSettings::default();
    overrides(scene).apply(&mut s);
    overrides(cli).apply(&mut s);
    s.validate_combination("scene.toml", "caustics.").map(|_| s.clone()).map_err(|e| e.to_string())
}

/// `faithful = true` is the tutorial's three choices, as its text gives them; a contrary value
/// of any of them, in the same table or a later one, is refused with its key; and it belongs to
/// Shah's techniques.
#[test]
fn faithful_is_the_tutorials_three_choices() {
    for technique in ["shah", "shah-vertex"] {
        let s = settled(&format!("technique = \"{technique}\"\nfaithful = true"), "").expect("valid");
        let shown = toml::to_string(&s).expect("serializable");
        for line in ["refractions = \"one\"", "iterations = 1", "lookup = \"tutorial\"", "faithful = true"] {
            assert!(shown.lines().any(|l| l == line), "{technique}: `{line}` missing from\n{shown}");
        }
    }
    // The defaults without it: two refractions, 4 iterations, the physical lookup.
    let s = toml::to_string(&settled("technique = \"shah\"", "").expect("valid")).expect("serializable");
    for line in ["refractions = \"two\"", "iterations = 4", "lookup = \"physical\""] {
        assert!(s.lines().any(|l| l == line), "`{line}` missing from\n{s}");
    }
    // A contrary value in the same table, or on the command line over the scene's, is refused.
    for (scene, cli, key) in [
        ("technique = \"shah\"\nfaithful = true\niterations = 4", "", "caustics.iterations"),
        ("technique = \"shah\"\nfaithful = true", "refractions = \"two\"", "caustics.refractions"),
        ("technique = \"shah\"\nfaithful = true", "lookup = \"physical\"", "caustics.lookup"),
    ] {
        let err = settled(scene, cli).expect_err("a contradiction");
        assert!(err.contains(key) && err.contains("faithful"), "{scene} + {cli}: {err}");
    }
    // Setting faithful later re-applies the tutorial's choices over the scene's.
    let s = settled("technique = \"shah\"\niterations = 8", "faithful = true").expect("valid");
    assert_eq!(s.iterations, 1);
    let err = settled("technique = \"wd-points\"\nfaithful = true", "").expect_err("not Shah's");
    assert!(err.contains("caustics.faithful") && err.contains("shah"), "{err}");
}

fn scene(lookup: &str) -> Scene {
    let mut s = shipped("sphere_on_plane.toml");
    s.caustics.technique = "shah".parse().expect("a known name");
    s.caustics.lookup = lookup.parse().expect("a known name");
    s.caustics.photons = 128;
    s.caustics.caustic_map_resolution = 256;
    s.caustics.fresnel = false;
    s.camera.width = 64;
    s.camera.height = 64;
    s.receiver_map.as_mut().expect("a receiver map").resolution = 64;
    s
}

/// Per receiver texel: (E0, the caustic irradiance), each the mean of R, G, B (the light is
/// white).
fn caustic_and_e0(img: &ImageF32) -> Vec<(f64, f64)> {
    let main = img.layer(None).expect("the E/E0 layer");
    let caustic = img.layer(Some("caustic")).expect("the caustic layer");
    let e0 = main.data.chunks_exact(main.channels.len()).map(|p| p[3] as f64);
    let ec = caustic.data.chunks_exact(caustic.channels.len()).map(|p| p.iter().map(|&v| v as f64).sum::<f64>() / 3.0);
    e0.zip(ec).collect()
}

#[test]
fn tutorial_lookup_is_the_lambert_term_times_c_to_the_1_3() {
    let physical = caustic_and_e0(&render_dumps(&scene("physical"), 1, &["receiver"]).remove(0).1);
    let tutorial = caustic_and_e0(&render_dumps(&scene("tutorial"), 1, &["receiver"]).remove(0).1);
    let (mut focus, mut around, mut worst) = (0, 0, 0.0f64);
    for (&(e0, ec), &(e0_t, et)) in physical.iter().zip(&tutorial) {
        assert!((e0 - e0_t).abs() <= 1e-6 * e0, "E0 differs: {e0} against {e0_t}");
        let c = if e0 > 0.0 { ec / e0 } else { 0.0 };
        let expected = e0 * c.powf(1.3);
        let err = (et - expected).abs() / (expected + 1e-4 * e0);
        worst = worst.max(err);
        assert!(err < 1e-3, "texel with c = {c}: tutorial {et} W/m², E0 c^1.3 = {expected} W/m²");
        focus += (c > 2.0) as usize;
        around += (c > 0.01 && c < 0.5) as usize;
    }
    println!(
        "tutorial lookup: {focus} texels with c > 2, {around} with 0.01 < c < 0.5, worst relative error {worst:.2e}"
    );
    // Both sides of c = 1 occur, where the two lookups differ by more than 20%: the exponent is tested.
    assert!(focus >= 4 && around >= 20, "{focus} focus texels, {around} around it");
}
