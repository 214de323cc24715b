//! The memory check before a renderer is made (`caustics::render::memory`) counts no more than
//! the renderer allocates, so that it never refuses a scene the device could render: for every
//! key it counts, doubling the key grows the device memory a new renderer holds by at least what
//! the count grows by, and the whole count is within what the renderer holds. Validation on.

use caustics::render::memory::needs;
use caustics::render::{Renderer, RendererOptions};
use caustics::scene::Scene;
use vkcore::{Context, ShaderCompiler};

mod common;
use common::{context, shipped};

fn base(technique: &str) -> Scene {
    let mut s = shipped("sphere_on_plane.toml");
    s.caustics.technique = technique.parse().expect("a known technique");
    s.caustics.photons = 64;
    s.caustics.caustic_map_resolution = 128;
    s.render.shadow_map_resolution = 128;
    s.camera.width = 128;
    s.camera.height = 128;
    if let Some(r) = &mut s.receiver_map {
        r.resolution = 64;
    }
    s
}

/// Device memory a renderer of `scene` holds once made.
fn held(ctx: &Context, sh: &ShaderCompiler, scene: &Scene) -> u64 {
    let before = ctx.device_memory().0;
    let r = Renderer::new(ctx, sh, scene, &RendererOptions::default()).expect("renderer");
    let after = ctx.device_memory().0;
    drop(r);
    after - before
}

fn counted(scene: &Scene) -> u64 {
    needs(scene).iter().map(|n| n.bytes).sum()
}

#[test]
fn the_count_is_a_lower_bound_of_what_a_renderer_allocates() {
    let (ctx, sh) = context();
    type Edit = fn(&mut Scene);
    let doublings: [(&str, Edit); 5] = [
        ("camera.resolution", |s| {
            s.camera.width *= 2;
            s.camera.height *= 2;
        }),
        ("render.shadow_map_resolution", |s| s.render.shadow_map_resolution *= 2),
        ("receiver_map.resolution", |s| s.receiver_map.as_mut().expect("a receiver map").resolution *= 2),
        ("caustics.caustic_map_resolution", |s| s.caustics.caustic_map_resolution *= 2),
        ("caustics.photons", |s| s.caustics.photons *= 2),
    ];
    for technique in ["wd-points", "shah-vertex", "adaptive"] {
        let scene = base(technique);
        let whole = held(&ctx, &sh, &scene);
        assert!(counted(&scene) <= whole, "{technique}: counted {} of {whole} bytes held", counted(&scene));
        for (key, double) in doublings {
            let mut bigger = scene.clone();
            double(&mut bigger);
            let grew = held(&ctx, &sh, &bigger) as i64 - whole as i64;
            let counted_growth = counted(&bigger) as i64 - counted(&scene) as i64;
            assert!(
                counted_growth <= grew,
                "{technique}: doubling `{key}` grew the count by {counted_growth} bytes, the renderer by {grew}"
            );
            // A key the count names must be counted (photons are not, for adaptive caustic
            // maps: their storage is planned under photon_memory_limit).
            let names_key = needs(&bigger).iter().any(|n| n.key == key);
            assert_eq!(names_key, counted_growth > 0, "{technique}: `{key}`");
        }
    }
    let log = ctx.validation_log();
    assert_eq!(log.count(), 0, "validation messages:\n{}", log.messages().join("\n"));
}
