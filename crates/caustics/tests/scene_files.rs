//! Every shipped scene in `scenes/` loads, and the named ones have the expected content.

use caustics::scene::{LightKind, MaterialKind, Scene, Vec3};
use std::path::{Path, PathBuf};

fn scenes_dir() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../../scenes")
}

fn load(name: &str) -> Scene {
    let path = scenes_dir().join(name);
    Scene::load(&path).unwrap_or_else(|e| panic!("{}: {e:#}", path.display()))
}

#[test]
fn every_shipped_scene_loads() {
    let mut names: Vec<PathBuf> = std::fs::read_dir(scenes_dir())
        .expect("scenes/ exists")
        .map(|e| e.unwrap().path())
        .filter(|p| p.extension().is_some_and(|x| x == "toml"))
        .collect();
    names.sort();
    for required in ["sphere_on_plane", "sphere_oblique", "bunny_in_room", "two_lights", "ring", "octahedron"] {
        assert!(names.iter().any(|p| p.file_stem().unwrap() == required), "scenes/{required}.toml missing");
    }
    for path in names {
        let s = Scene::load(&path).unwrap_or_else(|e| panic!("{}: {e:#}", path.display()));
        if let Some(pool) = &s.pool {
            // A pool scene (Trendall & Stewart 2000): its light and surfaces are the pool's.
            assert!(s.lights.is_empty() && s.objects.is_empty() && s.receiver_map.is_none());
            assert!(!pool.impulses.is_empty(), "{}", path.display());
            continue;
        }
        assert!(!s.lights.is_empty() && !s.objects.is_empty());
        assert!(s.receiver_map.is_some(), "{}: no receiver map", path.display());
        for o in &s.objects {
            assert!(o.material < s.materials.len());
            assert_eq!(o.mesh.normals.len(), o.mesh.positions.len());
            assert!(o.mesh.positions.iter().all(|p| p.is_finite()));
            assert!(o.mesh.normals.iter().all(|n| (n.length() - 1.0).abs() < 1e-4));
            assert!(o.mesh.indices.iter().all(|&i| (i as usize) < o.mesh.positions.len()));
        }
    }
}

#[test]
fn sphere_on_plane_matches_its_description() {
    let s = load("sphere_on_plane.toml");
    let sphere = s.objects.iter().find(|o| o.name == "sphere").expect("sphere");
    assert!(sphere.mesh.triangle_count() >= 20_000, "{}", sphere.mesh.triangle_count());
    for p in &sphere.mesh.positions {
        assert!(((*p - Vec3::new(0.0, 1.0, 0.0)).length() - 0.5).abs() < 1e-5);
    }
    assert!(
        matches!(s.materials[sphere.material].kind, MaterialKind::Refractive { ior, .. } if ior == Vec3::splat(1.5))
    );
    assert_eq!(s.lights.len(), 1);
    assert_eq!(s.lights[0].position, Vec3::new(0.0, 6.0, 0.0));
    assert_eq!(s.lights[0].kind, LightKind::Point);
    assert_eq!((s.camera.width, s.camera.height), (512, 512));
    let floor = s.objects.iter().find(|o| o.name == "floor").expect("floor");
    assert_eq!(floor.mesh.bounds(), (Vec3::new(-20.0, 0.0, -20.0), Vec3::new(20.0, 0.0, 20.0)));
    let r = s.receiver_map.clone().unwrap();
    assert_eq!((r.plane_y, r.x_range, r.z_range, r.resolution), (0.0, [-2.0, 2.0], [-2.0, 2.0], 256));

    let o = load("sphere_oblique.toml");
    assert_eq!(o.lights[0].position, Vec3::new(2.0, 5.0, 1.0));
    assert_eq!(o.triangle_count(), s.triangle_count());
}

#[test]
fn bunny_stands_on_the_floor_inside_the_room() {
    for name in ["bunny_in_room.toml", "two_lights.toml"] {
        let s = load(name);
        let bunny = s.objects.iter().find(|o| o.name == "bunny").expect("bunny");
        assert!(bunny.mesh.triangle_count() > 60_000);
        let (lo, hi) = bunny.mesh.bounds();
        assert!(lo.y.abs() < 1e-4, "{lo}");
        assert!(((hi - lo).max_element() - 1.5).abs() < 1e-3);
        // Everything else (the room) encloses the bunny and the camera and lights.
        let (rlo, rhi) = s.bounds();
        for p in [lo, hi, s.camera.eye].into_iter().chain(s.lights.iter().map(|l| l.position)) {
            assert!(p.cmpge(rlo).all() && p.cmple(rhi).all(), "{p} outside {rlo}..{rhi}");
        }
        // Walls face into the room.
        let centre = 0.5 * (rlo + rhi);
        for o in s.objects.iter().filter(|o| o.name != "bunny") {
            let p = o.mesh.positions[0];
            assert!((centre - p).dot(o.mesh.normals[0]) > 0.0, "{} faces out", o.name);
        }
    }
    assert_eq!(load("two_lights.toml").lights.len(), 2);
}

/// Wyman & Nichols 2009 Fig. 4 / Fig. 13: a glass sphere behind the glass dragon, rendered with
/// deferred refraction, the sphere first (farther from the eye), clear of the dragon and on the floor.
#[test]
fn sphere_behind_dragon_is_two_refractors_back_to_front() {
    use caustics::techniques::wyman_nichols2009::deferred_refraction::back_to_front;
    use caustics::techniques::Refraction;
    let s = load("sphere_behind_dragon.toml");
    assert_eq!(s.caustics.refraction, Refraction::Deferred);
    let index = |name: &str| s.objects.iter().position(|o| o.name == name).expect(name);
    let (dragon, sphere) = (index("dragon"), index("sphere"));
    assert!(s.objects[dragon].mesh.triangle_count() > 200_000);
    assert_eq!(back_to_front(&s), vec![sphere, dragon]);
    let ((dlo, dhi), (slo, shi)) = (s.objects[dragon].mesh.bounds(), s.objects[sphere].mesh.bounds());
    assert!(shi.z < dlo.z, "the sphere ({slo}..{shi}) is behind the dragon ({dlo}..{dhi})");
    assert!(slo.y.abs() < 1e-3, "the sphere stands on the floor: {slo}");
}

/// The canonical pools of Trendall & Stewart 2000, exactly as issue 17 gives them.
#[test]
fn the_canonical_pools_have_the_issues_numbers() {
    use caustics::techniques::Technique;
    use std::f64::consts::TAU;
    for (name, light) in [("pool_overhead.toml", [0.0, -1.0, 0.0]), ("pool_oblique.toml", [0.5, -0.8660254, 0.0])] {
        let s = load(name);
        let p = s.pool.clone().expect("a pool");
        assert_eq!((p.side, p.depth, p.albedo, p.ior, p.ior_air, p.time), (1.0, 0.3, 0.8, 1.333, 1.0, 2.4));
        let want = glam::DVec3::from_array(light).normalize();
        assert!((p.light_direction - want).length() < 1e-12, "{name}");
        assert_eq!((p.scattering, p.exponent, p.extinction), (2000.0, 4000.0, 0.5));
        let w = p.wave;
        assert_eq!((w.amplitude, w.time_damping, w.distance_damping), (0.005, 0.3, 10.0));
        assert!((w.wave_number - TAU / 0.1).abs() < 1e-12 && (w.angular_frequency - TAU * 1.25).abs() < 1e-12);
        assert_eq!(p.impulses.len(), 1);
        assert_eq!((p.impulses[0].position.x, p.impulses[0].position.y, p.impulses[0].start), (0.3, 0.1, 0.0));
        assert!(p.wall_reflections);
        assert_eq!(s.caustics.technique, Technique::PoolConvolution);
        assert_eq!((s.caustics.photons, s.caustics.kernel), (256, 7));
    }
    let animated = load("pool.toml").pool.expect("a pool");
    assert!(animated.impulses.len() >= 3 && animated.time_step > 0.0);
}
