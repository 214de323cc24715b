//! Shared by the caustics crate's GPU tests: a lavapipe-or-GPU context with the Khronos
//! validation layer on (the tests fail on any message it reports).

use caustics::scene::Scene;
use vkcore::{Context, ContextOptions, ShaderCompiler};

/// A validated context on `$CAUSTICLAB_TEST_DEVICE` (default: the default device).
pub fn context() -> (Context, ShaderCompiler) {
    let opts = ContextOptions::for_tests(vec![]);
    let ctx = Context::new(&opts).expect("a Vulkan 1.3 device with the validation layer (run scripts/setup.sh)");
    let shaders = ShaderCompiler::new(&caustics::render::shader_root()).expect("shaderc");
    (ctx, shaders)
}

/// A scene shipped in `scenes/` (`name` with its extension), loaded as a user would.
#[allow(dead_code)] // not every test crate that shares this module loads a shipped scene
pub fn shipped(name: &str) -> Scene {
    let p = std::path::PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../../scenes").join(name);
    Scene::load(&p).unwrap_or_else(|e| panic!("shipped scene {name}: {e:#}"))
}

/// Renders `frames` frames of `scene` on a fresh validated context and returns the named dumps,
/// failing on any validation message.
#[allow(dead_code)] // not every test crate that shares this module renders through it
pub fn render_dumps(scene: &Scene, frames: u32, names: &[&str]) -> Vec<(String, caustics::image_io::ImageF32)> {
    use caustics::render::{FrameStep, Renderer, RendererOptions};
    let (ctx, sh) = context();
    let mut r = Renderer::new(&ctx, &sh, scene, &RendererOptions::default()).expect("renderer");
    for _ in 0..frames {
        r.frame(FrameStep::default()).expect("frame");
    }
    let dumps = r.dumps(&names.iter().map(|s| s.to_string()).collect::<Vec<_>>()).expect("dumps");
    let log = ctx.validation_log();
    assert_eq!(log.count(), 0, "validation messages:\n{}", log.messages().join("\n"));
    dumps.into_iter().map(|(d, img)| (d.name.to_string(), img)).collect()
}

/// Whether `ctx`'s device has everything registry row `v` needs (its settings'
/// `CausticSettings::device_needs`, what `render::check_device` requires: beyond the
/// technique's own, `trace = "ray-query"` needs acceleration structures and ray queries).
/// Where it has not, the row is skipped with a line naming the feature and the device (printed
/// to the test's output: `--nocapture` shows it), and with `CAUSTICLAB_REQUIRE_FEATURES=1`
/// (scripts/mesa25_check.sh sets it on Mesa 25's lavapipe, which has every feature a row
/// needs) the skip is a failure instead.
#[allow(dead_code)] // not every test crate that shares this module reads the registry
pub fn runs_here(ctx: &vkcore::Context, v: &caustics::techniques::variants::Variant) -> bool {
    let missing = v
        .settings_in_effect()
        .device_needs()
        .into_iter()
        .find_map(|(who, features)| ctx.require(&format!("registry row `{}`: {who}", v.name), features).err());
    let Some(e) = missing else { return true };
    let required = std::env::var("CAUSTICLAB_REQUIRE_FEATURES").is_ok_and(|v| v == "1");
    assert!(!required, "CAUSTICLAB_REQUIRE_FEATURES=1: {e}");
    println!("skipped: {e} (scripts/mesa25_check.sh runs it on Mesa 25's lavapipe)");
    false
}
