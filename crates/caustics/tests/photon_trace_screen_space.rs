//! Screen-space photon mapping (`photon-trace --deposit screen-space`, Kim 2019;
//! `techniques::shared::screen_space`): its edge-aware filter does not carry a caustic across a
//! depth edge. `scenes/sphere_by_step.toml` is made for it: seen from the eye, the top of a
//! diffuse step 0.3 m high borders the glass sphere's caustic on the floor behind it, so in
//! screen space the caustic lies pixels away from the step's top. With the depth-edge test
//! removed from the shader (`joined` in `shaders_glsl/shared/screen_space_filter.comp`), 70
//! step-top pixels get the floor's light and the test fails. In the same eye's view, across the
//! edge, the filter keeps the photons' power: the caustic irradiance times each pixel's area
//! sums to the photons' power drawn into the view. (In the receiver view, and its accuracy
//! against the exact reference, are the conformance suite's: registry row
//! `photon-trace-screen-space`.) Validation layer on.

use caustics::image_io::{ImageF32, Layer};
use caustics::techniques::photon_trace::settings::Deposit;
use caustics::techniques::shared::screen_space::MAX_RADIUS;
use caustics::techniques::Technique;

mod common;

fn layer<'a>(dumps: &'a [(String, ImageF32)], dump: &str, name: Option<&str>) -> &'a Layer {
    let img = &dumps.iter().find(|(n, _)| n == dump).unwrap_or_else(|| panic!("no {dump}")).1;
    img.layer(name).unwrap_or_else(|| panic!("{dump} has no layer {name:?}"))
}

/// What a pixel of the eye's view sees.
#[derive(Clone, Copy, PartialEq, Debug)]
enum Surface {
    Floor,
    StepTop,
    Other,
}

#[test]
fn the_filter_does_not_carry_the_caustic_across_the_steps_depth_edge() {
    let mut scene = common::shipped("sphere_by_step.toml");
    scene.caustics.technique = Technique::PhotonTrace;
    scene.caustics.deposit = Deposit::ScreenSpace;
    scene.caustics.photons = 64;
    // Few photons, so that the kernels at the caustic's edge grow to their largest (dense
    // photons keep them within a pixel, and there is nothing to carry); and only the light the
    // sphere refracts, so that the step's top holds few photons of its own.
    scene.caustics.fresnel = false;
    scene.caustics.outside_reflection = false;
    scene.camera.width = 256;
    scene.camera.height = 256;
    let dumps = common::render_dumps(&scene, 1, &["eye_gbuffer", "eye_caustic"]);
    let (w, h) = (scene.camera.width as i32, scene.camera.height as i32);
    let position = layer(&dumps, "eye_gbuffer", Some("position"));
    let normal = layer(&dumps, "eye_gbuffer", Some("normal"));
    let caustic = layer(&dumps, "eye_caustic", None);
    let photons = layer(&dumps, "eye_caustic", Some("photons"));
    let at = |l: &Layer, x: i32, y: i32, c: usize| l.sample(w as u32, x as u32, y as u32, c);
    let surface = |x: i32, y: i32| {
        let (py, hit, ny) = (at(position, x, y, 1), at(position, x, y, 3), at(normal, x, y, 1));
        match () {
            _ if hit < 0.5 || ny < 0.99 => Surface::Other,
            _ if py.abs() < 1e-3 => Surface::Floor,
            _ if (py - 0.3).abs() < 1e-3 => Surface::StepTop,
            _ => Surface::Other,
        }
    };
    let irradiance = |x: i32, y: i32| (0..3).map(|c| at(caustic, x, y, c)).sum::<f32>();
    let has_photons = |x: i32, y: i32| at(photons, x, y, 3) > 0.0;
    let near = |x: i32, y: i32, r: i32, f: &dyn Fn(i32, i32) -> bool| {
        (-r..=r).any(|dy| {
            (-r..=r).any(|dx| {
                let (qx, qy) = (x + dx, y + dy);
                (0..w).contains(&qx) && (0..h).contains(&qy) && f(qx, qy)
            })
        })
    };
    // Each pixel's distance in pixels (Chebyshev, up to 24) to the other side of the edge.
    let distance_to =
        |x: i32, y: i32, other: Surface| (0..=24).find(|&d| near(x, y, d, &|qx, qy| surface(qx, qy) == other));
    let mean = |v: &[f32]| v.iter().sum::<f32>() / v.len().max(1) as f32;
    // A step-top pixel's world area, from its neighbours on the step's top (it is flat).
    let p = |x: i32, y: i32| glam::Vec3::new(at(position, x, y, 0), at(position, x, y, 1), at(position, x, y, 2));
    let side = |x: i32, y: i32, dx: i32, dy: i32| {
        let on = |qx: i32, qy: i32| (0..w).contains(&qx) && (0..h).contains(&qy) && surface(qx, qy) == Surface::StepTop;
        match (on(x + dx, y + dy), on(x - dx, y - dy)) {
            (true, true) => (p(x + dx, y + dy) - p(x - dx, y - dy)) * 0.5,
            (true, false) => p(x + dx, y + dy) - p(x, y),
            (false, true) => p(x, y) - p(x - dx, y - dy),
            (false, false) => glam::Vec3::ZERO,
        }
    };
    let area = |x: i32, y: i32| side(x, y, 1, 0).cross(side(x, y, 0, 1)).length();
    let power = |x: i32, y: i32| (0..3).map(|c| at(photons, x, y, c)).sum::<f32>();
    let (mut binned_power, mut binned_area) = (0.0f32, 0.0f32);
    let (mut floor_edge, mut step_edge, mut step_far) = (vec![], vec![], vec![]);
    for y in 0..h {
        for x in 0..w {
            match (surface(x, y), distance_to(x, y, Surface::Floor), distance_to(x, y, Surface::StepTop)) {
                (Surface::Floor, _, Some(d)) if d <= 2 => floor_edge.push(irradiance(x, y)),
                (Surface::StepTop, Some(d), _) if d <= 2 => {
                    step_edge.push(irradiance(x, y));
                    binned_power += power(x, y);
                    binned_area += area(x, y);
                }
                (Surface::StepTop, Some(d), _) if (12..=24).contains(&d) => step_far.push(irradiance(x, y)),
                (Surface::StepTop, None, _) => step_far.push(irradiance(x, y)),
                _ => {}
            }
        }
    }
    let (f, e, far) = (mean(&floor_edge), mean(&step_edge), mean(&step_far));
    let own = binned_power / binned_area;
    println!(
        "mean caustic irradiance (W/m^2): the floor within 2 px of the step's top {f:.4} ({} px); the step's top \
         within 2 px of the floor {e:.4} ({} px), its own photons there over its area {own:.4}; the step's top 12 px \
         or more from the floor {far:.4} ({} px)",
        floor_edge.len(),
        step_edge.len(),
        step_far.len()
    );
    // Exactly: a step-top pixel with no photon of the step's top within the largest kernel's
    // reach gets nothing, however close the floor's caustic.
    let r = MAX_RADIUS as i32;
    let (mut guarded, mut carried) = (0, vec![]);
    for y in 0..h {
        for x in 0..w {
            let beside = surface(x, y) == Surface::StepTop && distance_to(x, y, Surface::Floor).is_some_and(|d| d <= 2);
            if beside && !near(x, y, r, &|qx, qy| surface(qx, qy) == Surface::StepTop && has_photons(qx, qy)) {
                guarded += 1;
                if irradiance(x, y) != 0.0 {
                    carried.push((x, y, irradiance(x, y)));
                }
            }
        }
    }
    println!("{guarded} step-top pixels within 2 px of the floor and {r} px of no photon of the step's top");
    assert!(floor_edge.len() >= 50 && step_edge.len() >= 50 && step_far.len() >= 50, "too few pixels");
    // The scene does what it is made for: the caustic on the floor meets the edge, far brighter
    // than the light the step's top gets there.
    assert!(f > 10.0 * own, "the caustic at the edge ({f}) is not much brighter than the step's top beside it ({own})");
    assert!(guarded >= 20, "only {guarded} step-top pixels beside the caustic hold no photon of their own");
    assert!(
        carried.is_empty(),
        "the caustic carried onto the step's top at {} pixels, e.g. {:?}",
        carried.len(),
        &carried[..carried.len().min(4)]
    );
    // On average too, the step's top beside it holds what its own photons give there (the
    // kernels of the band's photons and of those behind it trade light), not the floor's caustic.
    assert!(e < 1.25 * own, "the step's top beside the caustic gets {e} W/m^2, its own photons {own}");

    // The power: sum_t E_t A_t over the view against the photons drawn into it, A_t from the
    // geometry buffer as the filter takes it (`shaders_glsl/shared/pixel_area.glsl`).
    let on = |x: i32, y: i32| (0..w).contains(&x) && (0..h).contains(&y) && at(position, x, y, 3) > 0.5;
    let edge = |x: i32, y: i32, dx: i32, dy: i32| {
        let (va, vb) = (on(x + dx, y + dy), on(x - dx, y - dy));
        let da = if va { p(x + dx, y + dy) - p(x, y) } else { glam::Vec3::ZERO };
        let db = if vb { p(x, y) - p(x - dx, y - dy) } else { glam::Vec3::ZERO };
        match (va, vb) {
            (true, true) => {
                let (la, lb) = (da.length(), db.length());
                if la < 2.0 * lb && lb < 2.0 * la {
                    0.5 * (da + db)
                } else if la < lb {
                    da
                } else {
                    db
                }
            }
            (true, false) => da,
            (false, true) => db,
            (false, false) => glam::Vec3::ZERO,
        }
    };
    let (mut held, mut drawn) = (0.0f64, 0.0f64);
    for y in 0..h {
        for x in 0..w {
            drawn += power(x, y) as f64 / 3.0;
            if on(x, y) {
                let a = edge(x, y, 1, 0).cross(edge(x, y, 0, 1)).length();
                held += irradiance(x, y) as f64 / 3.0 * a as f64;
            }
        }
    }
    println!("the eye's view holds {held:.6} W of the {drawn:.6} W drawn into it");
    // Float sums over 65536 pixels: 2e-5. (Normalised over the photon pixel's own area instead of
    // its neighbours', the filter is off by 3.6e-4 here.)
    assert!(drawn > 0.0 && (held / drawn - 1.0).abs() < 2e-5, "held {held} W of {drawn} W");
}
