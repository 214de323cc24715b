//! `bench_configs/README.md`'s table of pass names, the names a config's `passes` patterns
//! match, against the frames as recorded (`FrameReport::graph`, what `render --graph` prints):
//! lavapipe, validation layer on, small sizes. Frames: every row of the registry of variants that
//! renders meshes on `sphere_on_plane`, and what no registry row reaches (a moving light's second
//! frame, `technique = "none"`, deferred photons and deferred refraction through two refractors,
//! adaptive batches under a photon memory limit, the three photon copies, the pool scene in its
//! three precisions with moving water). A row needing a device feature this device lacks
//! (`Variant::needs`: `photon-trace-ray-query` on Mesa 22.3) is skipped, saying so;
//! `scripts/mesa25_check.sh` runs this on Mesa 25's lavapipe, where none may be.
//!
//! Every recorded pass must match exactly one row's pattern; in every frame the rows must first
//! appear in the table's order ("Per frame, in order"); every row must be matched by some frame
//! (a stale row fails as a missing pass does). The same of the pool's table, but for the order
//! (its f64 passes run on the CPU first).
//!
//! The README's "How a frame flows": the pass stages its left column names (`gpu::Stage` names)
//! must each be recorded by some frame, and in every frame that records two of them (the
//! eye-space techniques' aside, which render the eye first) in the diagram's order; its right
//! column must name only buffers `--dump` has.

use caustics::animation::{scene_at, Animation};
use caustics::gpu::Stage;
use caustics::render::{FrameStep, Renderer, RendererOptions};
use caustics::scene::Scene;
use caustics::techniques::variants::registry;
use caustics::techniques::CopyType;
use caustics::techniques::Technique;

mod common;
use common::{context, runs_here, shipped};

fn readme() -> String {
    let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../../bench_configs/README.md");
    std::fs::read_to_string(path).expect("bench_configs/README.md")
}

/// The backticked parts of `text`.
fn backticked(text: &str) -> Vec<String> {
    text.split('`').skip(1).step_by(2).map(str::to_string).collect()
}

/// A row of a pass table: its patterns and the kernels its `<kernel>` stands for (the
/// backticked lower-case words of its second cell).
struct Row {
    patterns: Vec<String>,
    kernels: Vec<String>,
}

impl Row {
    fn matches(&self, pass: &str) -> bool {
        self.patterns.iter().any(|p| matches(p, pass, &self.kernels))
    }
}

/// The table under `header`: its rows.
fn table(text: &str, header: &str) -> Vec<Row> {
    let rows: Vec<Row> = text
        .lines()
        .skip_while(|l| *l != header)
        .skip(2)
        .take_while(|l| l.starts_with('|'))
        .map(|l| {
            let cells: Vec<&str> = l.split('|').collect();
            let word = |w: &String| !w.is_empty() && w.chars().all(|c| c.is_ascii_lowercase());
            Row { patterns: backticked(cells[1]), kernels: backticked(cells[2]).into_iter().filter(word).collect() }
        })
        .collect();
    assert!(rows.len() > 3 && rows.iter().all(|r| !r.patterns.is_empty()), "no table under {header:?}");
    rows
}

/// Whether `name` matches `pattern`: `<l>`, `<k>`, `<m>`, `<b>` stand for a number, `<batch>`
/// for nothing, `.batch<b>` or `.breadth`, `<kernel>` for one of `kernels`; the rest is literal.
fn matches(pattern: &str, name: &str, kernels: &[String]) -> bool {
    let Some(open) = pattern.find('<') else { return pattern == name };
    let Some(rest) = name.strip_prefix(&pattern[..open]) else { return false };
    let close = open + pattern[open..].find('>').unwrap_or_else(|| panic!("unclosed < in `{pattern}`"));
    let tail = &pattern[close + 1..];
    let ends: Vec<usize> = match &pattern[open + 1..close] {
        "l" | "k" | "m" | "b" => {
            let digits = rest.chars().take_while(char::is_ascii_digit).count();
            (1..=digits).collect()
        }
        "kernel" => kernels.iter().filter(|k| rest.starts_with(k.as_str())).map(String::len).collect(),
        "batch" => {
            let mut e = vec![0];
            if rest.starts_with(".breadth") {
                e.push(".breadth".len());
            }
            if let Some(after) = rest.strip_prefix(".batch") {
                let d = after.chars().take_while(char::is_ascii_digit).count();
                e.extend((1..=d).map(|d| ".batch".len() + d));
            }
            e
        }
        other => panic!("unknown placeholder <{other}> in `{pattern}`"),
    };
    ends.into_iter().any(|e| matches(tail, &rest[e..], kernels))
}

/// The passes of one frame, in order.
struct Frame {
    what: String,
    /// Recorded by an eye-space technique (`CausticSettings::eye_space`).
    eye_space: bool,
    passes: Vec<String>,
}

fn frame_of(what: &str, r: &mut Renderer, failures: &mut Vec<String>, ctx: &vkcore::Context) -> Vec<String> {
    let report = r.frame(FrameStep::default()).unwrap_or_else(|e| panic!("{what}: {e:#}"));
    let log = ctx.validation_log();
    if log.count() > 0 {
        failures.push(format!("{what}: validation messages:\n{}", log.messages().join("\n")));
    }
    let passes: Vec<String> = report.passes.iter().map(|p| p.name.clone()).collect();
    // The graph holds the passes recorded on the GPU; host-timed work (the pool's f64 passes,
    // its upload) is timed as a pass without one.
    for p in &report.graph {
        if !passes.contains(&p.name) {
            failures.push(format!("{what}: graph pass `{}` is not among the timed passes {passes:?}", p.name));
        }
    }
    passes
}

fn small(name: &str, technique: Technique) -> Scene {
    let mut s = shipped(name);
    s.caustics.technique = technique;
    s.caustics.photons = 64;
    s.caustics.caustic_map_resolution = 64;
    s.camera.width = 64;
    s.camera.height = 64;
    s
}

/// One frame of `scene` (the second frame of its `anim` if given).
fn render(
    ctx: &vkcore::Context,
    sh: &vkcore::ShaderCompiler,
    what: &str,
    scene: &Scene,
    opts: &RendererOptions,
    anim: Option<&Animation>,
    failures: &mut Vec<String>,
) -> Frame {
    let mut r = Renderer::new(ctx, sh, scene, opts).unwrap_or_else(|e| panic!("{what}: {e:#}"));
    if let Some(a) = anim {
        frame_of(what, &mut r, failures, ctx);
        r.set_pose(&scene_at(scene, a, 1)).unwrap_or_else(|e| panic!("{what}: {e:#}"));
    }
    let passes = frame_of(what, &mut r, failures, ctx);
    Frame { what: what.to_string(), eye_space: scene.caustics.eye_space(), passes }
}

fn frames(failures: &mut Vec<String>) -> (Vec<Frame>, Vec<Frame>) {
    let (ctx, sh) = context();
    ctx.record_frame_graphs(true);
    let plain = RendererOptions::default();
    let mut mesh = vec![];
    let go = |what: &str, s: &Scene, opts: &RendererOptions, anim: Option<&Animation>, f: &mut Vec<String>| {
        render(&ctx, &sh, what, s, opts, anim, f)
    };
    for v in registry().expect("the registry") {
        let t = v.technique();
        if !t.renders_meshes() || !runs_here(&ctx, &v) {
            continue;
        }
        let mut s = small("sphere_on_plane.toml", t);
        v.settings.apply(&mut s.caustics);
        mesh.push(go(&v.name, &s, &plain, None, failures));
    }
    let orbit = Animation { light: true, camera: false, object: false, period_frames: 8 };
    mesh.push(go("moving light", &small("sphere_on_plane.toml", Technique::WdPoints), &plain, Some(&orbit), failures));
    mesh.push(go("technique none", &small("sphere_on_plane.toml", Technique::None), &plain, None, failures));
    let mut two = small("stacked_spheres.toml", Technique::WdPoints);
    two.caustics.photon_refraction = "deferred".parse().expect("a known name");
    two.caustics.refraction = "deferred".parse().expect("a known name");
    mesh.push(go("two refractors, deferred", &two, &plain, None, failures));
    let mut batched = small("sphere_on_plane.toml", Technique::Adaptive);
    batched.caustics.photons = 256;
    batched.caustics.photon_batches = 2;
    mesh.push(go("adaptive, 2 batches", &batched, &plain, None, failures));
    for copy in [CopyType::Half16ToFloat32, CopyType::Float32ToFloat32, CopyType::Half16ToHalf16] {
        let opts = RendererOptions { photon_copy: Some(copy), ..RendererOptions::default() };
        mesh.push(go(
            &format!("photon copy {copy:?}"),
            &small("sphere_on_plane.toml", Technique::WdPoints),
            &opts,
            None,
            failures,
        ));
    }
    let water = Animation { light: false, camera: false, object: true, period_frames: 8 };
    let mut pool = vec![];
    for precision in ["unorm8", "float", "f64"] {
        let mut s = shipped("pool.toml");
        s.caustics.precision = precision.parse().expect("a known name");
        pool.push(go(&format!("pool {precision}"), &s, &plain, Some(&water), failures));
    }
    (mesh, pool)
}

/// Each pass's row in `rows` (exactly one, else a failure), for the frame `what`.
fn rows_of(what: &str, passes: &[String], rows: &[Row], failures: &mut Vec<String>) -> Vec<usize> {
    let mut out = vec![];
    for pass in passes {
        let hits: Vec<usize> = (0..rows.len()).filter(|&i| rows[i].matches(pass)).collect();
        match hits.as_slice() {
            [i] => out.push(*i),
            [] => failures.push(format!("{what}: pass `{pass}` matches no row of its table")),
            _ => {
                let hit: Vec<&Vec<String>> = hits.iter().map(|&i| &rows[i].patterns).collect();
                failures.push(format!("{what}: pass `{pass}` matches several rows: {hit:?}"))
            }
        }
    }
    out
}

/// Every row of `rows` matched in some frame.
fn all_used(rows: &[Row], used: &[usize], failures: &mut Vec<String>) {
    for (i, row) in rows.iter().enumerate() {
        if !used.contains(&i) {
            failures.push(format!("no frame records a pass of the row {:?}", row.patterns));
        }
    }
}

#[test]
fn the_pass_tables_and_the_readme_diagram_follow_the_recorded_frames() {
    let text = readme();
    let (rows, pool_rows) = (table(&text, "| pass | when |"), table(&text, "| pool pass | when |"));
    let row_of = |pattern: &str| rows.iter().position(|r| r.patterns[0] == pattern).expect(pattern);
    // Eye-space techniques render the eye first: their shadow maps and background rank first.
    let (shadow, background) = (row_of("shadow_map.light<l>"), row_of("background"));
    let mut failures = vec![];
    let (mesh, pool) = frames(&mut failures);
    let mut used = vec![];
    for f in &mesh {
        let mut firsts: Vec<usize> = vec![];
        for i in rows_of(&f.what, &f.passes, &rows, &mut failures) {
            if !firsts.contains(&i) {
                firsts.push(i);
            }
        }
        used.extend(&firsts);
        let rank = |i: usize| match i {
            _ if !f.eye_space => i as f64,
            _ if i == shadow => 0.25,
            _ if i == background => 0.5,
            _ => i as f64,
        };
        if firsts.windows(2).any(|w| rank(w[0]) > rank(w[1])) {
            let seen: Vec<&String> = firsts.iter().map(|&i| &rows[i].patterns[0]).collect();
            failures.push(format!("{}: rows first appear out of the table's order: {seen:?}", f.what));
        }
    }
    all_used(&rows, &used, &mut failures);
    let mut used = vec![];
    for f in &pool {
        used.extend(rows_of(&f.what, &f.passes, &pool_rows, &mut failures));
    }
    all_used(&pool_rows, &used, &mut failures);
    diagram_follows(&mesh, &mut failures);
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}

/// The README's "How a frame flows" against the frames (see the module docs).
fn diagram_follows(mesh: &[Frame], failures: &mut Vec<String>) {
    let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../../README.md");
    let text = std::fs::read_to_string(path).expect("README.md");
    let block: Vec<&str> = text
        .lines()
        .skip_while(|l| *l != "## How a frame flows")
        .skip_while(|l| *l != "```")
        .skip(2)
        .take_while(|l| *l != "```")
        .collect();
    assert!(block.len() > 10, "no diagram under \"## How a frame flows\": {block:?}");
    let word = |c: char| !(c.is_ascii_lowercase() || c.is_ascii_digit() || c == '_' || c == '.');
    let (mut stages, mut dumps) = (vec![], vec![]);
    for line in &block {
        // The columns are apart by three spaces or more.
        let trimmed = line.trim_start();
        let (left, right) = match trimmed.find("   ") {
            Some(i) => (&trimmed[..i], trimmed[i..].trim()),
            None => (trimmed, ""),
        };
        for w in left.split(word).map(|w| w.trim_end_matches('.')) {
            if let Some(s) = Stage::ALL.iter().find(|s| s.name() == w) {
                if !stages.contains(s) {
                    stages.push(*s);
                }
            }
        }
        dumps.extend(right.split(',').map(str::trim).filter(|d| !d.is_empty()));
    }
    assert!(stages.len() > 10 && dumps.len() > 10, "the diagram's columns: {stages:?} {dumps:?}");
    let known = caustics::render::all_dump_names();
    for d in dumps {
        if !known.contains(&d) {
            failures.push(format!("the README's diagram names `{d}`, which `--dump` does not have"));
        }
    }
    let mut seen = vec![false; stages.len()];
    for f in mesh.iter().filter(|f| !f.eye_space) {
        let firsts: Vec<Option<usize>> =
            stages.iter().map(|s| f.passes.iter().position(|p| Stage::of_pass(p) == Some(*s))).collect();
        let recorded: Vec<(usize, usize)> =
            firsts.iter().enumerate().filter_map(|(i, at)| at.map(|at| (i, at))).collect();
        for &(i, _) in &recorded {
            seen[i] = true;
        }
        if recorded.windows(2).any(|w| w[0].1 > w[1].1) {
            let order: Vec<&str> = recorded.iter().map(|&(i, _)| stages[i].name()).collect();
            let mut by_frame = recorded.clone();
            by_frame.sort_by_key(|&(_, at)| at);
            let frame: Vec<&str> = by_frame.iter().map(|&(i, _)| stages[i].name()).collect();
            failures.push(format!("{}: the diagram says {order:?}, the frame {frame:?}", f.what));
        }
    }
    for (s, seen) in stages.iter().zip(seen) {
        if !seen {
            failures.push(format!("the README's diagram names the pass `{}`, which no frame records", s.name()));
        }
    }
}

#[test]
fn a_pattern_matches_its_numbers_and_kernels_only() {
    let none: &[String] = &[];
    let m = |p: &str, n: &str| matches(p, n, none);
    assert!(m("splat.light<l>", "splat.light0") && m("splat.light<l>", "splat.light12"));
    assert!(!m("splat.light<l>", "splat.light") && !m("splat.light<l>", "splat.clear.light0"));
    assert!(!m("splat.light<l>", "splat.light0x") && !m("splat.light<l>", "splat.batch0.light0"));
    let kernels = ["traverse".to_string(), "emit".to_string(), "hits".to_string()];
    let p = "adaptive.<kernel>.level<k><batch>.light<l>";
    for yes in
        ["adaptive.traverse.level3.light0", "adaptive.emit.level2.batch1.light0", "adaptive.hits.level1.breadth.light1"]
    {
        assert!(matches(p, yes, &kernels), "{yes}");
    }
    for no in [
        "adaptive.reset.light0",
        "adaptive.traverse.level.light0",
        "adaptive.coverage.level3.light0",
        "adaptive.emit.level2.batch.light0",
    ] {
        assert!(!matches(p, no, &kernels), "{no}");
    }
    assert!(m("background", "background") && !m("background", "background2"));
}
