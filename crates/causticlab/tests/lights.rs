//! Spot lights with projected textures and several lights, on the GPU: the receiver map's
//! irradiance against I cos(theta) / r^2, the cone, and the texture's colour, computed here.

mod common;

use caustics::image_io::{read_exr, write_png_tonemapped};
use common::*;

/// Receiver texel centre (x, z) for column i, row j of an n x n map over [-2, 2]^2.
fn centre(i: u32, j: u32, n: u32) -> (f64, f64) {
    let s = 4.0 / n as f64;
    (-2.0 + (i as f64 + 0.5) * s, -2.0 + (j as f64 + 0.5) * s)
}

/// Renders `dir/scene.toml` with validation on and returns its receiver map.
fn render_receiver(dir: &std::path::Path) -> caustics::image_io::ImageF32 {
    let out = dir.join("out");
    let scene = dir.join("scene.toml").display().to_string();
    let run = causticlab(&[
        "--validate",
        "render",
        "--scene",
        &scene,
        "--dump",
        "receiver",
        "--out",
        &out.display().to_string(),
    ]);
    assert_eq!(run.code, Some(0), "{}", run.describe());
    assert!(!run.stderr.contains("[validation"), "{}", run.describe());
    read_exr(&out.join("receiver.exr")).unwrap()
}

#[test]
fn spot_light_with_projected_texture_lights_its_cone_only() {
    let dir = scratch("spot");
    // A magenta texture: linear (1, 0, 1) after sRGB decoding (255, 0, 255).
    write_png_tonemapped(&dir.join("magenta.png"), 4, 4, &[1e6, 0.0, 1e6].repeat(16), 1.0).unwrap();
    let text = std::fs::read_to_string(scene("sphere_on_plane")).unwrap();
    let light = "type = \"point\"\nposition = [0.0, 6.0, 0.0]";
    assert!(text.contains(light), "sphere_on_plane's light changed");
    let spot = "type = \"spot\"\nposition = [0.0, 6.0, 0.0]\ndirection = [0.0, -1.0, 0.0]\ncone_angle = 15.0\ntexture = \"magenta.png\"";
    std::fs::write(dir.join("scene.toml"), text.replace(light, spot)).unwrap();
    let r = render_receiver(&dir);
    let red = find_channel(&r, "irradiance.R").unwrap();
    let green = find_channel(&r, "irradiance.G").unwrap();
    let n = r.width;
    let cone = 15f64.to_radians();
    let (mut inside, mut outside) = (0, 0);
    for j in 0..n {
        for i in 0..n {
            let (x, z) = centre(i, j, n);
            let rho = (x * x + z * z).sqrt();
            // Skip the sphere's shadow (radius ~0.6 m) and a band of 2 texels around the cone's edge.
            let angle = rho.atan2(6.0);
            let band = 2.0 * 4.0 / n as f64 / 6.0;
            if rho < 0.7 || (angle - cone).abs() < band {
                continue;
            }
            let r2 = 36.0 + rho * rho;
            let e = 100.0 * (6.0 / r2.sqrt()) / r2;
            let (er, eg) = (value(&r, red, i, j), value(&r, green, i, j));
            if angle < cone {
                inside += 1;
                assert!((er / e - 1.0).abs() < 0.01, "({x:.2}, {z:.2}): E.R {er} vs {e}");
                assert!(eg.abs() < 1e-6 * e, "({x:.2}, {z:.2}): the texture has no green, E.G {eg}");
            } else {
                outside += 1;
                assert_eq!(er, 0.0, "({x:.2}, {z:.2}) is outside the cone");
            }
        }
    }
    assert!(inside > 1000 && outside > 1000, "inside {inside}, outside {outside}");
}

#[test]
fn two_lights_add_up() {
    let dir = scratch("two");
    let text = std::fs::read_to_string(scene("sphere_on_plane")).unwrap();
    let second =
        "[[lights]]\ntype = \"point\"\nposition = [2.0, 5.0, 1.0]\nintensity = [0.0, 50.0, 0.0]\n\n[materials.floor]";
    std::fs::write(dir.join("scene.toml"), text.replacen("[materials.floor]", second, 1)).unwrap();
    let r = render_receiver(&dir);
    let e0 = find_channel(&r, "E0").unwrap();
    let n = r.width;
    let term = |x: f64, z: f64, l: [f64; 3], i: f64| {
        let d = [l[0] - x, l[1], l[2] - z];
        let r2 = d[0] * d[0] + d[1] * d[1] + d[2] * d[2];
        i * (d[1] / r2.sqrt()) / r2
    };
    for j in (0..n).step_by(7) {
        for i in (0..n).step_by(7) {
            let (x, z) = centre(i, j, n);
            // E0 is the mean over R, G, B: light 1 is white (100 W/sr in each), light 2 green only.
            let want = (2.0 * term(x, z, [0.0, 6.0, 0.0], 100.0)
                + term(x, z, [0.0, 6.0, 0.0], 100.0)
                + term(x, z, [2.0, 5.0, 1.0], 50.0))
                / 3.0;
            let got = value(&r, e0, i, j);
            assert!((got / want - 1.0).abs() < 0.01, "({x:.2}, {z:.2}): E0 {got} vs {want}");
        }
    }
}

#[test]
fn the_reference_projects_a_spot_texture_as_the_renderer_does() {
    // Four quadrants of different brightness (mean RGB 1/3, 2/3, 0, 1) through a 30-degree
    // spot: the exact reference's E0 must equal the renderer's texel for texel (same
    // orientation, same filtering), away from the quadrant seams and the cone's edge.
    let dir = scratch("spot-reference");
    let quadrants = [[1e6, 0.0, 0.0], [1e6, 1e6, 0.0], [0.0, 0.0, 0.0], [1e6, 1e6, 1e6]].concat();
    write_png_tonemapped(&dir.join("quadrants.png"), 2, 2, &quadrants, 1.0).unwrap();
    let text = std::fs::read_to_string(scene("sphere_on_plane")).unwrap();
    let light = "type = \"point\"\nposition = [0.0, 6.0, 0.0]";
    let spot = "type = \"spot\"\nposition = [0.0, 6.0, 0.0]\ndirection = [0.0, -1.0, 0.0]\ncone_angle = 15.0\ntexture = \"quadrants.png\"";
    std::fs::write(dir.join("scene.toml"), text.replace(light, spot)).unwrap();
    let gpu = render_receiver(&dir);
    let out = dir.join("reference");
    let scene_path = dir.join("scene.toml").display().to_string();
    let run =
        causticlab(&["reference", "--scene", &scene_path, "--photons", "20000", "--out", &out.display().to_string()]);
    assert_eq!(run.code, Some(0), "{}", run.describe());
    let cpu = read_exr(&out.join("receiver.exr")).unwrap();
    let (eg, ec) = (find_channel(&gpu, "E0").unwrap(), find_channel(&cpu, "E0").unwrap());
    let n = gpu.width;
    let (mut compared, mut levels) = (0, std::collections::BTreeSet::new());
    for j in 0..n {
        for i in 0..n {
            let (x, z) = centre(i, j, n);
            let angle = (x * x + z * z).sqrt().atan2(6.0);
            if x.abs() < 0.1 || z.abs() < 0.1 || (angle - 15f64.to_radians()).abs() < 0.02 {
                continue;
            }
            let (g, c) = (value(&gpu, eg, i, j), value(&cpu, ec, i, j));
            assert!((g - c).abs() <= 1e-3 * g.abs().max(1e-3), "({x:.2}, {z:.2}): E0 renderer {g}, reference {c}");
            if angle < 15f64.to_radians() {
                levels.insert((g / (100.0 * 6.0 / (36.0 + x * x + z * z).powf(1.5)) * 3.0).round() as i64);
            }
            compared += 1;
        }
    }
    // Every quadrant was inside the compared region: the four levels 0, 1, 2, 3 (thirds).
    assert_eq!(levels.into_iter().collect::<Vec<_>>(), vec![0, 1, 2, 3], "quadrant levels");
    assert!(compared > 10_000, "compared {compared} texels");
}
