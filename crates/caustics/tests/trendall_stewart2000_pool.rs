//! Trendall & Stewart 2000 on the GPU (lavapipe or a real device, validation on, no message
//! allowed), against the CPU reference and against formulas written out here: the height field
//! and its wall reflections, Fresnel T, a flat surface, the float and 8-bit paths.

use caustics::image_io::ImageF32;
use caustics::render::{FrameStep, Renderer, RendererOptions};
use caustics::scene::Scene;
use caustics::techniques::trendall_stewart2000::{self as ts, Precision};
use caustics::techniques::Technique;
use glam::{DVec2, DVec3};
use std::path::PathBuf;
use vkcore::{Context, ShaderCompiler};

mod common;
use common::context;

fn scene(name: &str, precision: Precision) -> Scene {
    let p = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join(format!("../../scenes/{name}.toml"));
    let mut s = Scene::load(&p).expect("shipped scene");
    assert_eq!(s.caustics.technique, Technique::PoolConvolution);
    s.caustics.precision = precision;
    s.camera.width = 64;
    s.camera.height = 64;
    s
}

/// One frame of `scene`, then the named dumps.
fn render(ctx: &Context, sh: &ShaderCompiler, scene: &Scene, dumps: &[&str]) -> Vec<ImageF32> {
    let mut r = Renderer::new(ctx, sh, scene, &RendererOptions::default()).expect("renderer");
    r.frame(FrameStep::default()).expect("frame");
    let names: Vec<String> = dumps.iter().map(|s| s.to_string()).collect();
    let out = r.dumps(&names).expect("dumps");
    assert_eq!(out.len(), dumps.len(), "dumps written");
    let log = ctx.validation_log();
    assert_eq!(log.count(), 0, "validation messages:\n{}", log.messages().join("\n"));
    out.into_iter().map(|(_, img)| img).collect()
}

/// Channel `c` of layer `layer` per texel.
fn channel(img: &ImageF32, layer: Option<&str>, c: &str) -> Vec<f64> {
    let l = img.layer(layer).unwrap_or_else(|| panic!("no layer {layer:?}"));
    let k = l.channels.iter().position(|x| x == c).unwrap_or_else(|| panic!("no channel {c}"));
    let nc = l.channels.len();
    (0..(img.width * img.height) as usize).map(|i| l.data[i * nc + k] as f64).collect()
}

fn rel_rms(a: &[f64], b: &[f64]) -> f64 {
    let num: f64 = a.iter().zip(b).map(|(x, y)| (x - y).powi(2)).sum();
    (num / b.iter().map(|y| y * y).sum::<f64>()).sqrt()
}

/// h of Sec. 4.3 written out: every impulse that has started, and its images through the walls
/// x = +-side/2, z = +-side/2.
fn height_formula(pool: &caustics::scene::PoolSpec, x: f64, z: f64) -> f64 {
    let w = &pool.wave;
    let mut h = 0.0;
    for imp in &pool.impulses {
        let t = pool.time - imp.start;
        let p = imp.position;
        let s = pool.side;
        let mut images = vec![p];
        if pool.wall_reflections {
            images.extend([
                DVec2::new(s - p.x, p.y),
                DVec2::new(-s - p.x, p.y),
                DVec2::new(p.x, s - p.y),
                DVec2::new(p.x, -s - p.y),
            ]);
        }
        for q in images {
            let d = DVec2::new(x, z).distance(q);
            let front = w.angular_frequency / w.wave_number * t;
            if t > 0.0 && d < front {
                h += w.amplitude
                    * (-w.distance_damping * (front - d)).exp()
                    * (-w.time_damping * t).exp()
                    * (w.wave_number * d - w.angular_frequency * t).sin();
            }
        }
    }
    h
}

#[test]
fn the_height_field_is_the_formula_at_sample_points() {
    let (ctx, sh) = context();
    for (name, precision) in
        [("pool_overhead", Precision::Float), ("pool", Precision::Float), ("pool", Precision::Unorm8)]
    {
        let s = scene(name, precision);
        let pool = s.pool.clone().expect("pool");
        let n = s.caustics.photons as usize;
        let h = channel(&render(&ctx, &sh, &s, &["height_field"])[0], None, "h");
        // 8-bit: half a step of the scale and bias, plus the clamp of the range.
        let tol = if precision == Precision::Unorm8 { 2.0 * pool.height_range / 255.0 * 0.5 + 1e-6 } else { 2e-7 };
        let mut worst = 0.0f64;
        for (i, j) in [(0, 0), (17, 200), (128, 128), (205, 154), (230, 160), (255, 3), (99, 31), (250, 250)] {
            let x = -0.5 * pool.side + (i as f64 + 0.5) * pool.side / n as f64;
            let z = -0.5 * pool.side + (j as f64 + 0.5) * pool.side / n as f64;
            let mut want = height_formula(&pool, x, z);
            if precision == Precision::Unorm8 {
                // The adjusted height is clamped to its range (Sec. 3.2).
                want = want.clamp(-pool.height_range, pool.height_range);
            }
            worst = worst.max((h[j * n + i] - want).abs());
        }
        println!("{name} {precision}: |h - formula| <= {worst:.2e} m (tolerance {tol:.1e})");
        assert!(worst <= tol, "{name} {precision}: {worst}");
    }
}

#[test]
fn wall_reflections_make_the_field_symmetric() {
    let (ctx, sh) = context();
    // A pebble at the centre, late enough that every wall's reflection has come back in: the
    // field has the square's symmetries only if all four images are where they belong.
    let mut s = scene("pool_overhead", Precision::Float);
    s.caustics.photons = 128;
    let pool = s.pool.as_mut().expect("pool");
    pool.impulses[0].position = DVec2::ZERO;
    pool.time = 5.6;
    pool.wave.time_damping = 0.0;
    let n = 128;
    let h = channel(&render(&ctx, &sh, &s, &["height_field"])[0], None, "h");
    let peak = h.iter().fold(0.0f64, |m, v| m.max(v.abs()));
    let mut worst = 0.0f64;
    for j in 0..n {
        for i in 0..n {
            let v = h[j * n + i];
            for m in [h[j * n + (n - 1 - i)], h[(n - 1 - j) * n + i], h[i * n + j]] {
                worst = worst.max((v - m).abs());
            }
        }
    }
    println!("centred impulse: asymmetry {worst:.2e} m of a peak {peak:.2e} m");
    assert!(peak > 1e-4 && worst < 1e-5 * peak.max(1e-3), "asymmetry {worst} of {peak}");

    // Off centre: with its reflection through x = +side/2 the field is even about that wall, so
    // its slope across the wall vanishes; without, the wave runs into the wall at full slope.
    let slope_at_wall = |reflections: bool| -> f64 {
        let mut s = scene("pool_overhead", Precision::Float);
        s.caustics.photons = 1024;
        s.pool.as_mut().expect("pool").wall_reflections = reflections;
        let n = 1024;
        let texel = 1.0 / n as f64;
        let h = channel(&render(&ctx, &sh, &s, &["height_field"])[0], None, "h");
        // dh/dx at x = 0.5 from the last three texels (second order), on the rows the wave
        // meets the wall well behind its front (the front, a kink in h, is at z = 0.1 +- 0.22).
        let rows = (0..n).filter(|&j| ((j as f64 + 0.5) * texel - 0.5 - 0.1).abs() < 0.15);
        rows.map(|j| {
            let r = &h[j * n..(j + 1) * n];
            ((r[n - 3] - 4.0 * r[n - 2] + 3.0 * r[n - 1]) / (2.0 * texel)
                + (r[n - 3] - 2.0 * r[n - 2] + r[n - 1]) / (2.0 * texel))
                .abs()
        })
        .fold(0.0, f64::max)
    };
    let (with, without) = (slope_at_wall(true), slope_at_wall(false));
    println!("slope across the +x wall: {with:.4} with its reflection, {without:.4} without");
    assert!(without > 0.05 && with < 0.05 * without, "{with} vs {without}");
}

/// Fresnel T on the GPU (Pass 3 over flat water is L_s cos(theta_i) T) against the textbook
/// 1 - (R_s + R_p) / 2 at several angles of incidence.
#[test]
fn fresnel_transmittance_on_the_gpu_is_the_closed_form() {
    let (ctx, sh) = context();
    for precision in [Precision::Float, Precision::Unorm8] {
        for deg in [0.0f64, 20.0, 40.0, 60.0, 75.0] {
            let mut s = scene("pool_overhead", precision);
            s.caustics.photons = 64;
            let pool = s.pool.as_mut().expect("pool");
            pool.impulses.clear();
            let a = deg.to_radians();
            pool.light_direction = DVec3::new(a.sin(), -a.cos(), 0.0);
            let v = channel(&render(&ctx, &sh, &s, &["pass3_transmitted"])[0], None, "value");
            let (n1, n2, ci): (f64, f64, f64) = (1.0, 1.333, a.cos());
            let ct = (1.0 - (n1 / n2).powi(2) * (1.0 - ci * ci)).sqrt();
            let rs = ((n1 * ci - n2 * ct) / (n1 * ci + n2 * ct)).powi(2);
            let rp = ((n2 * ci - n1 * ct) / (n2 * ci + n1 * ct)).powi(2);
            let want = ci * (1.0 - 0.5 * (rs + rp));
            // 8-bit: the table's step in its output and in cos(theta_i) (over [c_lo, 1]).
            let tol = if precision == Precision::Unorm8 { 1.5 / 255.0 } else { 1e-6 };
            let worst = v.iter().map(|x| (x - want).abs()).fold(0.0, f64::max);
            println!("{precision} {deg:>2} deg: cos T = {:.6} (textbook {want:.6})", v[0]);
            assert!(worst <= tol, "{precision} at {deg} deg: {worst}");
        }
    }
}

/// Relative RMS of E over the texels flat water lights.
fn irradiance_rms(gpu: &ImageF32, cpu_e: &[f64], cpu_flat: &[f64]) -> f64 {
    let e = channel(gpu, Some("irradiance"), "R");
    let keep: Vec<usize> = (0..e.len()).filter(|&i| cpu_flat[i] > 0.0).collect();
    let pick = |v: &[f64]| keep.iter().map(|&i| v[i]).collect::<Vec<_>>();
    rel_rms(&pick(&e), &pick(cpu_e))
}

#[test]
fn float_gpu_and_cpu_reference_agree_within_a_thousandth_on_both_canonical_scenes() {
    let (ctx, sh) = context();
    for name in ["pool_overhead", "pool_oblique"] {
        let s = scene(name, Precision::Float);
        let pool = s.pool.clone().expect("pool");
        let (wavy, flat) = ts::reference(&pool, 256, 7).expect("reference");
        let dumps = render(&ctx, &sh, &s, &["receiver", "pass1_normals", "pass5_integrand"]);
        let rms = irradiance_rms(&dumps[0], &wavy.irradiance(), &flat.irradiance());
        let ratio = channel(&dumps[0], None, "R");
        let want = ts::relative(&wavy.irradiance(), &flat.irradiance());
        let ratio_rms = rel_rms(&ratio, &want);
        let ny = channel(&dumps[1], None, "Y");
        let normal_err = ny.iter().zip(&wavy.normals).map(|(a, b)| (a - b.y).abs()).fold(0.0, f64::max);
        let fz = channel(&dumps[2], None, "Z");
        let cpu_fz: Vec<f64> = wavy.integrand.iter().map(|f| f.z).collect();
        println!(
            "{name}: float GPU vs f64 CPU: E {rms:.2e}, E/E_flat {ratio_rms:.2e}, F_z {:.2e}, N_y {normal_err:.1e}",
            rel_rms(&fz, &cpu_fz)
        );
        assert!(rms < 1e-3 && ratio_rms < 1e-3, "{name}: {rms} {ratio_rms}");
        assert!(rel_rms(&fz, &cpu_fz) < 1e-3 && normal_err < 1e-5, "{name}");
    }
}

/// The f64 path runs the CPU convolution (`cpu::run`, the reference's own code) and uploads
/// it: this checks what it adds, the upload, the receiver pass and the dumps. The convolution
/// itself is checked against closed forms and Eq. 2 in `trendall_stewart2000/tests.rs`, and
/// the f64 path against flat water's closed form in `a_flat_surface_gives_one_on_every_path`.
#[test]
fn the_f64_path_carries_the_cpu_convolution_to_the_receiver_and_the_dumps() {
    let (ctx, sh) = context();
    let s = scene("pool_oblique", Precision::F64);
    let (wavy, flat) = ts::reference(s.pool.as_ref().expect("pool"), 256, 7).expect("reference");
    let dumps = render(&ctx, &sh, &s, &["receiver", "pass6_convolutions"]);
    assert!(irradiance_rms(&dumps[0], &wavy.irradiance(), &flat.irradiance()) < 1e-7);
    let e = channel(&dumps[1], None, "E");
    assert!(rel_rms(&e, &wavy.irradiance()) < 1e-7);
}

/// A flat surface on every path: E / E_flat = 1 wherever flat water lights the bottom, and E
/// away from the walls is L_s cos T times the kernel's sum, written out here.
#[test]
fn a_flat_surface_gives_one_on_every_path() {
    let (ctx, sh) = context();
    for precision in [Precision::Float, Precision::Unorm8, Precision::F64] {
        for name in ["pool_overhead", "pool_oblique"] {
            let mut s = scene(name, precision);
            s.caustics.photons = 128;
            let pool = s.pool.as_mut().expect("pool");
            // The pebble drops after the time the frame shows.
            pool.impulses[0].start = 10.0;
            let pool = pool.clone();
            let dumps = render(&ctx, &sh, &s, &["receiver"]);
            let ratio = channel(&dumps[0], None, "R");
            let e0 = channel(&dumps[0], None, "E0");
            let e = channel(&dumps[0], Some("irradiance"), "R");
            let lit: Vec<usize> = (0..ratio.len()).filter(|&i| e0[i] > 0.0).collect();
            assert!(lit.len() > 128 * 100, "{name}: {} lit texels", lit.len());
            assert!(lit.iter().all(|&i| ratio[i] == 1.0), "{precision} {name}: E / E_flat != 1");
            // Away from the walls: every tap of the 7 x 7 window over water.
            let k = ts::kernels::kernels(&pool, 128, 7);
            let ci = -pool.light_direction.y;
            let ct = (1.0 - (1.0 / 1.333f64).powi(2) * (1.0 - ci * ci)).sqrt();
            let rs = ((ci - 1.333 * ct) / (ci + 1.333 * ct)).powi(2);
            let rp = ((1.333 * ci - ct) / (1.333 * ci + ct)).powi(2);
            let lt = DVec3::new(pool.light_direction.x / 1.333, -ct, 0.0);
            let texel = 1.0 / 128.0;
            let mut sum = 0.0;
            for b in -3..=3 {
                for a in -3..=3 {
                    let p = DVec3::new((a + k.offset[0]) as f64 * texel, -0.3, (b + k.offset[1]) as f64 * texel);
                    sum += lt.dot(p.normalize()).powf(4000.0) * (0.3 / p.length()) * (-0.5 * p.length()).exp();
                }
            }
            let want = ci * (1.0 - 0.5 * (rs + rp)) * sum * texel * texel;
            let tol = match precision {
                Precision::Unorm8 => 0.02,
                _ => 1e-5,
            };
            let mut worst = 0.0f64;
            for j in 8..120 {
                for i in 8..120 {
                    let (si, sj) = (i as i32 - k.offset[0], j as i32 - k.offset[1]);
                    if (4..124).contains(&si) && (4..124).contains(&sj) {
                        worst = worst.max((e[j * 128 + i] / want - 1.0).abs());
                    }
                }
            }
            println!("{precision} {name}: flat E within {worst:.1e} of the closed form {want:.4e}");
            assert!(worst < tol, "{precision} {name}: {worst}");
        }
    }
}

/// The 8-bit path against the float path on the canonical scenes and the animated pool's
/// complex frame (Sec. 5.2's comparison; the paper measured 26% on its worst-case frame). Stated:
/// the lavapipe measurements (0.135, 0.169, 0.224 for E) with about 20% margin.
#[test]
fn the_faithful_8_bit_path_stays_within_its_stated_error_of_float() {
    let (ctx, sh) = context();
    for (name, stated) in [("pool_overhead", 0.16), ("pool_oblique", 0.2), ("pool", 0.27)] {
        let float = render(&ctx, &sh, &scene(name, Precision::Float), &["receiver"]).remove(0);
        let faithful = render(&ctx, &sh, &scene(name, Precision::Unorm8), &["receiver"]).remove(0);
        let e0 = channel(&float, None, "E0");
        let keep: Vec<usize> = (0..e0.len()).filter(|&i| e0[i] > 0.0).collect();
        let pick = |img: &ImageF32, layer: Option<&str>| {
            let v = channel(img, layer, "R");
            keep.iter().map(|&i| v[i]).collect::<Vec<_>>()
        };
        let e_rms = rel_rms(&pick(&faithful, Some("irradiance")), &pick(&float, Some("irradiance")));
        let ratio_rms = rel_rms(&pick(&faithful, None), &pick(&float, None));
        println!("{name}: 8-bit vs float: relative RMS of E {e_rms:.4}, of E / E_flat {ratio_rms:.4}");
        assert!(e_rms < stated && ratio_rms < stated, "{name}: {e_rms} {ratio_rms}");
        assert!(e_rms > 1e-3, "{name}: the 8-bit path should not be this exact: {e_rms}");
    }
}

/// Footnote 1: L_s varies over the surface with a projected texture; Pass 3 carries it.
#[test]
fn a_projected_texture_scales_pass_3() {
    let (ctx, sh) = context();
    let dir = caustics::scratch::ScratchDir::new("causticlab", "pool-texture");
    // Left half black, right half white (sRGB 255 is linear 1).
    let png = dir.join("half.png");
    caustics::image_io::write_png_grey(&png, 2, 1, &[0.0, 1.0], 1.0).expect("png");
    for precision in [Precision::Float, Precision::Unorm8, Precision::F64] {
        let mut s = scene("pool_overhead", precision);
        s.caustics.photons = 64;
        let pool = s.pool.as_mut().expect("pool");
        pool.impulses.clear();
        pool.light_texture = Some(png.clone());
        pool.light_radiance = 0.5;
        let v = channel(&render(&ctx, &sh, &s, &["pass3_transmitted"])[0], None, "value");
        let want = 0.5 * (1.0 - (0.333f64 / 2.333).powi(2));
        for j in [0, 31, 63] {
            assert_eq!(v[j * 64 + 10], 0.0, "{precision}: the black half");
            assert!((v[j * 64 + 50] - want).abs() < 2.0 / 255.0, "{precision}: {} vs {want}", v[j * 64 + 50]);
        }
    }
}
