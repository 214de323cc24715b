//! Shah et al.'s caustics mapping tutorial refracts a photon once, where the light meets the
//! object, and searches for the receiver from there (`refractions = one`, its `psIntersectPts`);
//! causticlab's default refracts into and out of the object (`two`). Checked against the
//! analytic sphere of `sphere_on_plane` (centre (0, 1, 0), radius 0.5, n = 1.5), validation
//! layer on.

use caustics::image_io::ImageF32;
use caustics::scene::Scene;
use glam::DVec3;

mod common;
use common::{render_dumps, shipped};

fn scene(technique: &str, refractions: &str) -> Scene {
    let mut s = shipped("sphere_on_plane.toml");
    s.caustics.technique = technique.parse().expect("a known name");
    s.caustics.refractions = refractions.parse().expect("a known name");
    s.caustics.photons = 64;
    s.caustics.caustic_map_resolution = 256;
    s.caustics.fresnel = false;
    s
}

fn photon_buffer(scene: &Scene) -> ImageF32 {
    render_dumps(scene, 1, &["photon_buffer"]).remove(0).1
}

/// Snell's law for the unit direction `v` entering through the unit normal `n` (against `v`)
/// with relative index `eta`.
fn refract(v: DVec3, n: DVec3, eta: f64) -> DVec3 {
    let cos_i = -n.dot(v);
    let k = 1.0 - eta * eta * (1.0 - cos_i * cos_i);
    eta * v + (eta * cos_i - k.sqrt()) * n
}

/// Of the photons that landed, (how many, how many travel along the light's ray refracted once
/// by the sphere): traced back from where it landed, a photon's line crosses the sphere, and at
/// the crossing nearer the light Snell's law takes the light's ray to the photon's direction
/// within 0.01 rad.
fn refracted_once(scene: &Scene, photons: &ImageF32) -> (usize, usize) {
    let light = scene.lights[0].position.as_dvec3();
    let (centre, radius, eta) = (DVec3::new(0.0, 1.0, 0.0), 0.5, 1.0 / 1.5);
    let pos = &photons.layer(Some("light0.position")).expect("positions");
    let dir = &photons.layer(Some("light0.direction")).expect("directions");
    let (np, nd) = (pos.channels.len(), dir.channels.len());
    let (mut landed, mut once) = (0, 0);
    for i in 0..(photons.width * photons.height) as usize {
        let p = &pos.data[i * np..i * np + 4];
        if p[3] < 0.5 {
            continue;
        }
        landed += 1;
        let x = DVec3::new(p[0] as f64, p[1] as f64, p[2] as f64);
        let d =
            DVec3::new(dir.data[i * nd] as f64, dir.data[i * nd + 1] as f64, dir.data[i * nd + 2] as f64).normalize();
        // x - s d on the sphere: s^2 - 2 s (d.(x - c)) + |x - c|^2 - r^2 = 0; the larger root is
        // the crossing nearer the light.
        let (b, c) = (d.dot(x - centre), (x - centre).length_squared() - radius * radius);
        let disc = b * b - c;
        if disc < 0.0 {
            continue;
        }
        let entry = x - (b + disc.sqrt()) * d;
        let expected = refract((entry - light).normalize(), (entry - centre).normalize(), eta);
        if expected.angle_between(d) < 0.01 {
            once += 1;
        }
    }
    (landed, once)
}

#[test]
fn one_refraction_photons_travel_the_front_surfaces_refracted_ray() {
    for technique in ["shah", "shah-vertex"] {
        let s = scene(technique, "one");
        let (landed, once) = refracted_once(&s, &photon_buffer(&s));
        println!("{technique} refractions = one: {once} of {landed} landed photons refracted once");
        assert!(landed > 100, "{technique}: {landed} photons landed");
        assert!(once as f64 > 0.99 * landed as f64, "{technique}: {once} of {landed} refracted once");
        let s = scene(technique, "two");
        let (landed, once) = refracted_once(&s, &photon_buffer(&s));
        println!("{technique} refractions = two: {once} of {landed} landed photons refracted once");
        assert!((once as f64) < 0.1 * landed as f64, "{technique}, two refractions: {once} of {landed} refracted once");
    }
}

/// `refractions` is Shah et al.'s: another technique refuses it, naming the key.
#[test]
fn refractions_belong_to_shah() {
    let s = scene("wd-points", "one");
    let err = s.caustics.validate_combination("scene.toml", "caustics.").expect_err("refused").to_string();
    assert!(err.contains("caustics.refractions") && err.contains("shah"), "{err}");
}
