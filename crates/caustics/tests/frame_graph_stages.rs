//! The frame as recorded against the stages it is declared to be made of: every row of the
//! registry of variants that renders meshes, one frame on `sphere_on_plane` at small sizes,
//! validation layer on. Its frame graph (`FrameReport::graph`, what `render --graph` prints)
//! must hold only passes of its three caustic stages (`Source`, `Selection`, `Deposit`: each
//! declares the pass stages it records, `techniques/stages/`) and of the frame around them (the
//! eye render, the receiver map); each stage that records passes must have recorded one, the
//! source's before the selection's before the deposit's; and the stages table in
//! `techniques/stages/mod.rs` must name the three for the row's technique. A row needing a
//! device feature this device lacks (`Variant::needs`) is skipped, saying so
//! (`scripts/mesa25_check.sh` runs this on Mesa 25's lavapipe, where none may be).

use caustics::gpu::Stage;
use caustics::render::{FrameStep, Renderer, RendererOptions};
use caustics::techniques::variants::registry;
use caustics::techniques::Technique;

mod common;
use common::{context, runs_here, shipped};

/// Passes the renderer records around the caustic stages.
const FRAME: &[Stage] = &[
    Stage::Uniforms,
    Stage::UploadMeshes,
    Stage::CausticsClear,
    Stage::ReceiverPositions,
    Stage::ShadowMap,
    Stage::Background,
    Stage::RefractorBackFaces,
    Stage::RefractorFrontFaces,
    Stage::RefractorGeometry,
    Stage::DeferredRefraction,
    Stage::Composite,
    Stage::ReceiverMap,
];

/// The stages table's row for `technique` (the doc comment of `techniques/stages/mod.rs`).
fn table_row(technique: Technique) -> String {
    let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("src/techniques/stages/mod.rs");
    let text = std::fs::read_to_string(&path).expect("stages/mod.rs");
    let t = format!("`{technique}`");
    text.lines()
        .filter(|l| l.starts_with("//! | `"))
        .find(|l| l.split('|').nth(1).is_some_and(|first| first.contains(&t)))
        .unwrap_or_else(|| panic!("the stages table has no row for {t}"))
        .to_string()
}

#[test]
fn every_variant_records_its_declared_stages_in_order() {
    let (ctx, sh) = context();
    // Off by default: a frame records no graph until asked.
    let mut plain =
        Renderer::new(&ctx, &sh, &shipped("sphere_on_plane.toml"), &RendererOptions::default()).expect("renderer");
    assert!(plain.frame(FrameStep::default()).expect("frame").graph.is_empty(), "a graph recorded unasked");
    ctx.record_frame_graphs(true);
    let mut failures = vec![];
    for v in registry().expect("the registry") {
        let t = v.technique();
        if !t.renders_meshes() || t == Technique::None || !runs_here(&ctx, &v) {
            continue;
        }
        let mut scene = shipped("sphere_on_plane.toml");
        scene.caustics.technique = t;
        scene.caustics.photons = 64;
        scene.caustics.caustic_map_resolution = 64;
        v.settings.apply(&mut scene.caustics);
        scene.camera.width = 64;
        scene.camera.height = 64;
        let mut r = Renderer::new(&ctx, &sh, &scene, &RendererOptions::default())
            .unwrap_or_else(|e| panic!("{}: {e:#}", v.name));
        let report = r.frame(FrameStep::default()).unwrap_or_else(|e| panic!("{}: {e:#}", v.name));
        let stages = r.caustic_stages().unwrap_or_else(|| panic!("{}: no caustic stages", v.name));
        let graph: Vec<(&str, Option<Stage>)> =
            report.graph.iter().map(|p| (p.name.as_str(), Stage::of_pass(&p.name))).collect();
        let mut fail = |what: String| failures.push(format!("{}: {what}", v.name));
        for (pass, stage) in &graph {
            let declared = stage.is_some_and(|s| FRAME.contains(&s) || stages.iter().any(|(_, ss)| ss.contains(&s)));
            if !declared {
                fail(format!("pass `{pass}` is in none of its stages {:?} nor the frame's", stages.map(|s| s.0)));
            }
        }
        // Where each stage's first pass sits in the frame.
        let mut firsts = vec![];
        for (name, declared) in stages {
            let first = graph.iter().position(|(_, s)| s.is_some_and(|s| declared.contains(&s)));
            match (first, declared.is_empty()) {
                (None, false) => fail(format!("stage {name} recorded none of {declared:?}")),
                (Some(i), _) => firsts.push((name, i)),
                (None, true) => {}
            }
        }
        if firsts.windows(2).any(|w| w[0].1 > w[1].1) {
            fail(format!("stages out of order (name, first pass): {firsts:?}"));
        }
        let row = table_row(t);
        for (name, _) in stages {
            if !row.contains(&format!("`{name}`")) {
                fail(format!("the stages table's row for `{t}` does not name `{name}`: {row}"));
            }
        }
        let log = ctx.validation_log();
        if log.count() > 0 {
            fail(format!("validation messages:\n{}", log.messages().join("\n")));
        }
    }
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}
