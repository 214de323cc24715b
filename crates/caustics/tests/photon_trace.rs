//! `photon-trace`, the exact GPU photon tracer, against the exact CPU reference
//! (`causticlab reference`, which shares no code with it but the BVH's build), validation layer
//! on:
//! - the caustic flux of its receiver map within 0.5% of the reference's on both sphere scenes,
//!   the metal ring's cardioid, the stacked spheres and the glass bunny, Fresnel on (measured
//!   on lavapipe, printed: 1.0006-1.0025 with 1024² photons against 2M-photon references),
//!   and the receiver map texel by texel within the two estimators' combined noise;
//! - total internal reflection: with Fresnel off a photon that meets it is dropped, marked so in
//!   the photon buffer, and the power dropped is the reference's share on the glass octahedron;
//!   with Fresnel on it reflects and none is dropped;
//! - equal power per photon, I Ω / N² over the cone that subtends the specular objects'
//!   bounding sphere (computed here from the mesh);
//! - seeded: the same seed gives the same photons in every frame, another seed others.

// `!(error <= bound)` fails a NaN, where `error > bound` would pass it.
#![allow(clippy::neg_cmp_op_on_partial_ord)]

use caustics::compare::compare;
use caustics::image_io::ImageF32;
use caustics::reference::{trace_reference, ReferenceOptions, ReferenceResult};
use caustics::scene::Scene;
use glam::DVec3;

mod common;
use common::{render_dumps, shipped};

fn scene(name: &str, photons: u32, fresnel: bool) -> Scene {
    let mut s = shipped(name);
    s.caustics.technique = "photon-trace".parse().expect("a known name");
    s.caustics.photons = photons;
    s.caustics.fresnel = fresnel;
    s.camera.width = 64;
    s.camera.height = 64;
    s
}

fn reference(s: &Scene, photons: u64, fresnel: bool) -> ReferenceResult {
    trace_reference(s, &ReferenceOptions { photons, fresnel, ..Default::default() }).expect("reference")
}

/// Per texel of a receiver map's `caustic` layer: the mean of R, G, B (W/m²).
fn caustic(img: &ImageF32) -> Vec<f64> {
    let l = img.layer(Some("caustic")).expect("the caustic layer");
    l.data.chunks_exact(l.channels.len()).map(|p| p.iter().map(|&v| v as f64).sum::<f64>() / 3.0).collect()
}

/// Mean of R, G, B of every photon's power in the photon buffer, and of those whose
/// `direction.w` (why it carries nothing) is `why`.
fn photon_powers(buffer: &ImageF32, why: Option<f32>) -> Vec<f64> {
    let power = buffer.layer(Some("light0.power")).expect("power");
    let direction = buffer.layer(Some("light0.direction")).expect("direction");
    let (np, nd) = (power.channels.len(), direction.channels.len());
    power
        .data
        .chunks_exact(np)
        .zip(direction.data.chunks_exact(nd))
        .filter(|(_, d)| why.is_none_or(|w| d[3] == w))
        .map(|(p, _)| (p[0] as f64 + p[1] as f64 + p[2] as f64) / 3.0)
        .collect()
}

/// Per-texel z-scores of a receiver map's caustic irradiance against the reference's, over the
/// texels either lights.
struct ZScores {
    rms: f64,
    beyond_4: usize,
    lit: usize,
}

impl ZScores {
    /// The two estimators' noise per texel: a photon of power φ landing in a texel of area A
    /// adds φ / A, so an irradiance E made of such photons varies by E φ / A (the GPU's photons
    /// from its photon buffer, the reference's from its emitted power and count).
    fn of(receiver: &ImageF32, photons: &ImageF32, r: &ReferenceResult, area: f64) -> ZScores {
        let phi_gpu = photon_powers(photons, None)[0];
        let phi_ref = r.emitted_flux.iter().sum::<f64>() / 3.0 / r.photons_traced as f64;
        let (e_gpu, e_ref) = (caustic(receiver), caustic(&r.image));
        let z: Vec<f64> = e_gpu
            .iter()
            .zip(&e_ref)
            .filter(|(g, r)| **g > 0.0 || **r > 0.0)
            .map(|(g, r)| (g - r) / ((g * phi_gpu + r * phi_ref) / area).sqrt())
            .collect();
        let rms = (z.iter().map(|v| v * v).sum::<f64>() / z.len().max(1) as f64).sqrt();
        ZScores { rms, beyond_4: z.iter().filter(|v| !(v.abs() <= 4.0)).count(), lit: z.len() }
    }
}

#[test]
fn photon_trace_matches_the_exact_reference_on_five_scenes() {
    let mut failures = vec![];
    for name in [
        "sphere_on_plane.toml",
        "sphere_oblique.toml",
        "ring_cardioid.toml",
        "stacked_spheres.toml",
        "bunny_in_room.toml",
    ] {
        let mut s = scene(name, 1024, true);
        // 32² receiver texels: each holds thousands of both tracers' photons where the caustic is.
        let spec = s.receiver_map.as_mut().expect("a receiver map");
        spec.resolution = 32;
        let area = (spec.x_range[1] - spec.x_range[0]) as f64 * (spec.z_range[1] - spec.z_range[0]) as f64 / 1024.0;
        let r = reference(&s, 2_000_000, true);
        let gpu = render_dumps(&s, 1, &["receiver", "photon_buffer"]);
        let (receiver, photons) = (&gpu[0].1, &gpu[1].1);
        let (c, _) = compare(receiver, &r.image).expect("compare");
        let z = ZScores::of(receiver, photons, &r, area);
        let (rms_z, beyond_4) = (z.rms, z.beyond_4);
        println!(
            "{name:22} flux ratio {:.4}  rel. RMSE {:.4}  peak ratio {:.3}  lit texels {}  rms z {rms_z:.2}  |z| > 4: {beyond_4}",
            c.caustic_flux_ratio,
            c.rel_rmse,
            c.peak_ratio,
            z.lit
        );
        if !c.within(f64::INFINITY, 0.005) {
            failures.push(format!(
                "{name}: caustic flux ratio {} beyond 0.5%, or {} texels not finite",
                c.caustic_flux_ratio, c.non_finite_texels
            ));
        }
        if !(rms_z <= 2.0 && beyond_4 * 100 <= z.lit) {
            failures.push(format!("{name}: rms z {rms_z:.2}, {beyond_4} of {} texels beyond 4 sigma", z.lit));
        }
    }
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}

/// `direction.w` of a photon dropped at total internal reflection (trace.comp).
const LOST_TIR: f32 = 1.0;

#[test]
fn total_internal_reflection_drops_without_fresnel_and_reflects_with_it() {
    // The glass octahedron's faces reflect nearly half the light totally inside (Fresnel off:
    // the image-space model, two refractions, or none).
    let off = scene("octahedron.toml", 512, false);
    let r = reference(&off, 1_000_000, false);
    let expected = r.lost_tir.iter().sum::<f64>() / r.emitted_flux.iter().sum::<f64>();
    let buffer = render_dumps(&off, 1, &["photon_buffer"]).remove(0).1;
    let all: f64 = photon_powers(&buffer, None).iter().sum();
    let tir: f64 = photon_powers(&buffer, Some(LOST_TIR)).iter().sum();
    println!("octahedron, Fresnel off: {:.4} of the power dropped at TIR, the reference {expected:.4}", tir / all);
    assert!(expected > 0.2, "the scene shows total internal reflection: {expected}");
    assert!((tir / all - expected).abs() < 0.01, "dropped {} against {expected}", tir / all);
    let on = scene("octahedron.toml", 512, true);
    let buffer = render_dumps(&on, 1, &["photon_buffer"]).remove(0).1;
    assert!(photon_powers(&buffer, Some(LOST_TIR)).is_empty(), "with Fresnel, total internal reflection reflects");
}

#[test]
fn every_photon_carries_the_light_over_the_cone_shared_evenly() {
    let s = scene("sphere_on_plane.toml", 128, true);
    let sphere = s.objects.iter().find(|o| o.name == "sphere").expect("the sphere");
    let (lo, hi) = sphere
        .mesh
        .positions
        .iter()
        .fold((DVec3::INFINITY, DVec3::NEG_INFINITY), |(lo, hi), p| (lo.min(p.as_dvec3()), hi.max(p.as_dvec3())));
    let centre = 0.5 * (lo + hi);
    let radius = sphere.mesh.positions.iter().map(|p| p.as_dvec3().distance(centre)).fold(0.0, f64::max);
    let light = &s.lights[0];
    let d = light.position.as_dvec3().distance(centre);
    let omega = 2.0 * std::f64::consts::PI * (1.0 - (1.0 - (radius / d).powi(2)).sqrt());
    let expected = light.intensity.x as f64 * omega / (128.0 * 128.0);
    let buffer = render_dumps(&s, 1, &["photon_buffer"]).remove(0).1;
    let powers = photon_powers(&buffer, None);
    assert_eq!(powers.len(), 128 * 128);
    for p in powers {
        assert!((p / expected - 1.0).abs() < 1e-4, "a photon carries {p} W, I Ω / N² = {expected} W");
    }
}

#[test]
fn seeded_photons_are_the_same_every_frame_and_differ_by_seed() {
    let a = scene("sphere_oblique.toml", 128, true);
    let once = render_dumps(&a, 1, &["photon_buffer"]).remove(0).1;
    let thrice = render_dumps(&a, 3, &["photon_buffer"]).remove(0).1;
    let bits =
        |img: &ImageF32| -> Vec<u32> { img.layers.iter().flat_map(|l| l.data.iter().map(|v| v.to_bits())).collect() };
    assert_eq!(bits(&once), bits(&thrice), "the same seed, frame 1 and frame 3");
    let mut b = a.clone();
    b.caustics.seed = 2;
    let other = render_dumps(&b, 1, &["photon_buffer"]).remove(0).1;
    let differ = bits(&once).iter().zip(bits(&other)).filter(|(x, y)| *x != y).count();
    assert!(differ > 1000, "seed 2 moved only {differ} values");
}

/// `deposit = "receiver-map"`: the receiver map's caustic term is the traced photons binned into
/// its texels, as the reference bins its own. Checked against the photon buffer's photons binned
/// here on the CPU (their power over the texel's area, texel for texel), and against the
/// reference at the scene's own receiver resolution (flux within 0.5%; per-texel z-scores).
#[test]
fn the_direct_deposit_bins_the_photons_as_the_reference_does() {
    let mut failures = vec![];
    for name in ["sphere_on_plane.toml", "ring_cardioid.toml"] {
        let mut s = scene(name, 1024, true);
        s.caustics.deposit = "receiver-map".parse().expect("a known name");
        let spec = s.receiver_map.clone().expect("a receiver map");
        let n = spec.resolution as usize;
        let (x0, x1, z0, z1) =
            (spec.x_range[0] as f64, spec.x_range[1] as f64, spec.z_range[0] as f64, spec.z_range[1] as f64);
        let area = (x1 - x0) * (z1 - z0) / (n * n) as f64;
        let (lo, hi) = s.bounds();
        let tolerance = 1e-4 * (hi - lo).length() as f64;
        let gpu = render_dumps(&s, 1, &["receiver", "photon_buffer"]);
        let (receiver, photons) = (&gpu[0].1, &gpu[1].1);
        // The photons binned here: (x, y, z, landed) and (r, g, b).
        let pos = photons.layer(Some("light0.position")).expect("positions");
        let pow = photons.layer(Some("light0.power")).expect("power");
        let mut binned = vec![0.0f64; n * n];
        for (p, w) in pos.data.chunks_exact(pos.channels.len()).zip(pow.data.chunks_exact(pow.channels.len())) {
            let (x, y, z) = (p[0] as f64, p[1] as f64, p[2] as f64);
            if p[3] < 0.5 || (y - spec.plane_y as f64).abs() >= tolerance {
                continue;
            }
            let (fx, fz) = ((x - x0) / (x1 - x0), (z - z0) / (z1 - z0));
            if !((0.0..1.0).contains(&fx) && (0.0..1.0).contains(&fz)) {
                continue;
            }
            let (i, j) = (((fx * n as f64) as usize).min(n - 1), ((fz * n as f64) as usize).min(n - 1));
            binned[j * n + i] += (w[0] as f64 + w[1] as f64 + w[2] as f64) / 3.0 / area;
        }
        let e_gpu = caustic(receiver);
        let lit = binned.iter().filter(|b| **b > 0.0).count();
        assert!(lit > n * n / 10, "{name}: only {lit} texels lit");
        // The same power in all (up to the order of float additions), and in each texel but
        // where a photon within float rounding of a texel's edge fell on the other side here.
        let (total_gpu, total_cpu) = (e_gpu.iter().sum::<f64>(), binned.iter().sum::<f64>());
        assert!((total_gpu / total_cpu - 1.0).abs() < 1e-5, "{name}: {total_gpu} W/m² summed against {total_cpu}");
        let phi_gpu = photon_powers(photons, None)[0];
        let photon = phi_gpu / area;
        let moved = e_gpu.iter().zip(&binned).filter(|(g, b)| !((*g - *b).abs() <= 1e-4 * b.max(photon))).count();
        let worst = e_gpu.iter().zip(&binned).map(|(g, b)| (g - b).abs() / photon).fold(0.0, f64::max);
        assert!(e_gpu.iter().all(|v| v.is_finite()), "{name}: a texel is not finite");
        assert!(
            moved * 200 <= n * n && worst <= 3.0,
            "{name}: {moved} texels differ from the photons binned here, by up to {worst:.2} photons"
        );
        let worst = moved;

        let r = reference(&s, 2_000_000, true);
        let (c, _) = compare(receiver, &r.image).expect("compare");
        let z = ZScores::of(receiver, photons, &r, area);
        let (rms_z, beyond_4) = (z.rms, z.beyond_4);
        println!(
            "{name:22} {n}² texels, direct deposit: {worst} texels differ from the photons binned here by a photon at an edge; against the reference flux ratio {:.4}, rms z {rms_z:.2} over {} texels, |z| > 4: {beyond_4}",
            c.caustic_flux_ratio,
            z.lit
        );
        if !(c.within(f64::INFINITY, 0.005) && rms_z <= 1.5 && beyond_4 * 100 <= z.lit) {
            failures.push(format!(
                "{name}: flux ratio {}, rms z {rms_z:.2}, {beyond_4} beyond 4, {} texels not finite",
                c.caustic_flux_ratio, c.non_finite_texels
            ));
        }
    }
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}

/// The tracer's BVH is built once, when the renderer is made: a pose that moves an object is
/// refused, naming it (an input error, not a stale trace); the same pose again is taken.
#[test]
fn a_pose_that_moves_an_object_is_refused_by_name() {
    use caustics::render::{FrameStep, Renderer, RendererOptions};
    let s = scene("sphere_on_plane.toml", 64, true);
    let (ctx, sh) = common::context();
    let mut r = Renderer::new(&ctx, &sh, &s, &RendererOptions::default()).expect("renderer");
    r.frame(FrameStep::default()).expect("frame");
    r.set_pose(&s).expect("the same pose");
    let mut moved = s.clone();
    let (i, name) = moved.objects.iter().enumerate().map(|(i, o)| (i, o.name.clone())).next().expect("an object");
    for p in moved.objects[i].mesh.positions.iter_mut() {
        p.y += 0.01;
    }
    let err = r.set_pose(&moved).expect_err("a moved object").to_string();
    assert!(err.contains("photon-trace") && err.contains(&format!("`{name}` moves")), "{err}");
}
