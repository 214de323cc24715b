//! The photon view (`caustics.photon_view`): the share of the photon buffer's texels that meet
//! the glass sphere of `sphere_on_plane` follows from the frustum alone, and the caustic the
//! photons carry does not depend on the view. Validation layer on.
//!
//! The sphere (radius r = 0.5, 20480 triangles) sits d = 5 below the point light, on the
//! photon buffer's axis. On the image plane at unit distance it covers a disc of radius
//! tan(asin(r / d)); a square frustum of half-angle h covers [-tan h, tan h]^2, with texels
//! uniform on that plane, so a share pi tan^2(asin(r / d)) / (4 tan^2 h) of the texels see the
//! sphere: about 0.755 for the fitted view (h = 1.02 asin(r / d)), 0.0079 for the papers' 90 degrees.

use caustics::compare::compare;
use caustics::render::{FrameStep, Renderer, RendererOptions};
use caustics::scene::Scene;
use caustics::techniques::{PhotonView, Technique};
use std::path::PathBuf;

mod common;
use common::context;

fn scene(view: PhotonView, fov: f32, photons: u32) -> Scene {
    let p = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../../scenes/sphere_on_plane.toml");
    let mut s = Scene::load(&p).expect("shipped scene");
    s.caustics.technique = Technique::WdPoints;
    s.caustics.photons = photons;
    s.caustics.fresnel = false;
    s.caustics.photon_view = view;
    s.caustics.photon_fov = fov;
    s.caustics.caustic_map_resolution = 512;
    s.camera.width = 64;
    s.camera.height = 64;
    s
}

/// The analytic share of texels that see the sphere, for a frustum of half-angle `half`.
fn disc_share(half: f64) -> f64 {
    let a = (0.5f64 / 5.0).asin();
    std::f64::consts::PI * a.tan().powi(2) / (4.0 * half.tan().powi(2))
}

#[test]
fn valid_photons_follow_the_frustum_and_the_caustic_does_not() {
    let (ctx, sh) = context();
    let fitted_half = (0.5f64 / 5.0).asin() * 1.02;
    let cases = [
        (PhotonView::Fitted, 90.0, 256, fitted_half),
        (PhotonView::FixedFov, 90.0, 1024, 45f64.to_radians()),
        (PhotonView::FixedFov, 40.0, 512, 20f64.to_radians()),
        // The light is straight above: the shadow map's -Y face is the 90-degree view.
        (PhotonView::ShadowMap, 90.0, 1024, 45f64.to_radians()),
    ];
    let mut receivers = vec![];
    for (view, fov, photons, half) in cases {
        let mut r =
            Renderer::new(&ctx, &sh, &scene(view, fov, photons), &RendererOptions::default()).expect("renderer");
        r.frame(FrameStep::default()).expect("frame");
        let valid = r.valid_photons(None).expect("read back").expect("wd-points has a photon buffer");
        let share = valid as f64 / (photons as f64).powi(2);
        let want = disc_share(half);
        println!("{view} {fov}: {valid} valid photons of {photons}^2, share {share:.5}, disc {want:.5}");
        // A few per cent are lost at the rim (total internal reflection, grazing exits); a
        // wrong half-angle (full vs half, degrees vs radians) is off by a factor of 4 or more.
        assert!(share <= want * 1.01 && share >= want * 0.95, "{view} {fov}: share {share} vs disc {want}");
        receivers.push((format!("{view} {fov}"), r.dump("receiver").expect("dump").expect("receiver map")));
        let log = ctx.validation_log();
        assert_eq!(log.count(), 0, "{view}: validation messages:\n{}", log.messages().join("\n"));
    }
    // The same caustic power reaches the floor whichever view emitted it.
    let (fitted_name, fitted) = &receivers[0];
    for (name, img) in &receivers[1..] {
        let (c, _) = compare(img, fitted).expect("compare");
        println!("{name} against {fitted_name}: {c:?}");
        assert!(
            (c.caustic_flux_ratio - 1.0).abs() < 0.03,
            "{name}: caustic flux {} of the fitted view's",
            c.caustic_flux_ratio
        );
    }
}
