//! The faithful Wyman & Davis 2006 path (copy the photon buffer into a vertex array, then one
//! vertex per photon) must give the caustic map our instanced fetch gives (Wyman 2008 Sec. 4):
//! the same photons, so the same map up to float summation order (32-bit) or half-float
//! rounding (16-bit copies). Also: static lighting (reused photon buffer) leaves the map as
//! it was. Validation layer on; any message fails.

use caustics::render::{FrameStep, Renderer, RendererOptions};
use caustics::scene::Scene;
use caustics::techniques::CopyType;
use std::path::PathBuf;
use vkcore::{Context, FrameReport, ShaderCompiler};

mod common;
use common::context;

fn scene() -> Scene {
    scene_with(1024)
}

fn scene_with(instance_vertices: u32) -> Scene {
    let p = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../../scenes/sphere_on_plane.toml");
    let mut s = Scene::load(&p).expect("shipped scene");
    s.caustics.technique = "wd-points".parse().expect("a known name");
    s.caustics.photons = 128;
    s.caustics.caustic_map_resolution = 256;
    s.camera.width = 64;
    s.camera.height = 64;
    s.caustics.instance_vertices = instance_vertices;
    s.receiver_map = None;
    s
}

/// [`caustic_map_of`] the 128² photon scene with 1024 vertices per instance.
fn caustic_map(ctx: &Context, sh: &ShaderCompiler, copy: Option<CopyType>, steps: &[FrameStep]) -> Rendered {
    caustic_map_of(ctx, sh, &scene(), copy, steps)
}

/// What a renderer gave: light 0's mean-RGB caustic map after its frames (one per step), the
/// last frame's report, and the device memory the renderer held once made (live allocations
/// beyond those before it).
struct Rendered {
    map: Vec<f64>,
    last: FrameReport,
    memory: u64,
}

fn caustic_map_of(
    ctx: &Context,
    sh: &ShaderCompiler,
    scene: &Scene,
    copy: Option<CopyType>,
    steps: &[FrameStep],
) -> Rendered {
    let before = ctx.device_memory().0;
    let mut r =
        Renderer::new(ctx, sh, scene, &RendererOptions { photon_copy: copy, ..Default::default() }).expect("renderer");
    let memory = ctx.device_memory().0 - before;
    let mut last = None;
    for s in steps {
        last = Some(r.frame(*s).expect("frame"));
    }
    let img = r.dump("caustic_map").expect("dump").expect("a caustic map");
    let layer = img.layers.first().expect("a layer");
    let nc = layer.channels.len();
    let map = layer.data.chunks_exact(nc).map(|p| (p[0] as f64 + p[1] as f64 + p[2] as f64) / 3.0).collect();
    Rendered { map, last: last.expect("at least one frame"), memory }
}

/// (relative difference of the totals, Σ|a − b| / Σ|b|).
fn difference(a: &[f64], b: &[f64]) -> (f64, f64) {
    let (sa, sb): (f64, f64) = (a.iter().sum(), b.iter().sum());
    let l1: f64 = a.iter().zip(b).map(|(x, y)| (x - y).abs()).sum();
    ((sa - sb).abs() / sb, l1 / b.iter().map(|x| x.abs()).sum::<f64>())
}

/// Whether `report` has a pass named `name` (as `caustics/src/gpu/pass_name.rs` names them).
fn has_pass(report: &FrameReport, name: &str) -> bool {
    report.pass(name).is_some()
}

#[test]
fn copied_vertex_arrays_splat_the_same_caustic_map_as_instanced_fetch() {
    let (ctx, sh) = context();
    let once = [FrameStep::default()];
    let fetched = caustic_map(&ctx, &sh, None, &once);
    // The maps below would match whatever path ran: the passes say the options took effect.
    assert!(
        has_pass(&fetched.last, "photon_buffer.light0") && !has_pass(&fetched.last, "photon_copy.light0"),
        "instanced fetch: a photon buffer and no copy"
    );
    let fetched = fetched.map;
    let total: f64 = fetched.iter().sum();
    assert!(total > 0.0, "no caustic: the comparison would be vacuous");
    let copied = caustic_map(&ctx, &sh, Some(CopyType::Float32ToFloat32), &once);
    assert!(has_pass(&copied.last, "photon_copy.light0"), "32-to-32 copy: no copy pass");
    let (dt, dl1) = difference(&copied.map, &fetched);
    assert!(dt < 1e-5 && dl1 < 1e-5, "32-to-32 copy: totals differ by {dt}, texels by {dl1}");
    for ty in [CopyType::Half16ToFloat32, CopyType::Half16ToHalf16] {
        let copied = caustic_map(&ctx, &sh, Some(ty), &once);
        assert!(has_pass(&copied.last, "photon_copy.light0"), "{ty:?}: no copy pass");
        let (dt, dl1) = difference(&copied.map, &fetched);
        // Half floats keep 11 bits: power within ~1e-3, positions within a fraction of a texel.
        assert!(dt < 2e-3, "{ty:?}: totals differ by {dt}");
        assert!(dl1 < 0.05, "{ty:?}: texels differ by {dl1} (L1, relative)");
    }
    // Static lighting: frames that reuse the photon buffer splat the same photons again, and
    // render neither the photon buffer nor the light-space back faces it needs.
    let reused =
        caustic_map(&ctx, &sh, None, &[FrameStep::default(), FrameStep { reuse_photons: true, ..Default::default() }]);
    for pass in ["photon_back_faces.light0", "photon_buffer.light0"] {
        assert!(!has_pass(&reused.last, pass), "the frame that reuses the photon buffer ran `{pass}`");
    }
    assert!(has_pass(&reused.last, "splat.light0"), "the frame that reuses the photon buffer splatted nothing");
    let (dt, dl1) = difference(&reused.map, &fetched);
    assert!(dt < 1e-6 && dl1 < 1e-6, "reused photon buffer: totals differ by {dt}, texels by {dl1}");
    let log = ctx.validation_log();
    assert_eq!(log.count(), 0, "validation messages:\n{}", log.messages().join("\n"));
}

/// Wyman 2008 Sec. 4 draws one small vertex buffer (1024, 2048 or 4096 vertices) instanced: the
/// size must not change which photons are splatted. 128² photons are 16 instances of 1024,
/// 8 of 2048, 4 of 4096, and 1 of 65536 (which pads 49,152 vertices past the photon buffer:
/// those must splat nothing); 64 vertices make 256 instances.
#[test]
fn every_instance_size_splats_the_same_photons() {
    let (ctx, sh) = context();
    let once = [FrameStep::default()];
    let base = caustic_map(&ctx, &sh, None, &once);
    assert!(base.map.iter().sum::<f64>() > 0.0, "no caustic: the comparison would be vacuous");
    for n in [64, 2048, 4096, 65536] {
        let r = caustic_map_of(&ctx, &sh, &scene_with(n), None, &once);
        let (dt, dl1) = difference(&r.map, &base.map);
        assert!(dt < 1e-5 && dl1 < 1e-5, "{n} vertices per instance: totals differ by {dt}, texels by {dl1}");
        // The same map from every size would also come from a size that never left the
        // default: the renderer's memory shows the size taken. Its vertex buffer holds one
        // 32-bit vertex id per vertex of an instance, and nothing else depends on the size
        // (the draw's vertex count itself needs pipeline statistics, which lavapipe before
        // Mesa 23 does not offer: `vkcore::device`). Exact on lavapipe; a GPU may round an
        // allocation up to its alignment, hence the 256 bytes.
        let grown = r.memory as i64 - base.memory as i64;
        let want = 4 * (n as i64 - 1024);
        assert!((grown - want).abs() <= 256, "{n} vertices per instance: {grown} B against 1024's, not {want}");
    }
    let log = ctx.validation_log();
    assert_eq!(log.count(), 0, "validation messages:\n{}", log.messages().join("\n"));
}
