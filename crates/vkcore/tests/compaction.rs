//! Stream compaction on the GPU, both paths, against a CPU reference at awkward sizes, and a
//! second GPU-driven step (count never read back in between) against the same reference.

mod common;
use common::*;
use vkcore::{AppendCounter, CompactStream, CompactionPath, Compactor, FrameOptions, QueryPool, Source};

const SIZES: [u32; 6] = [1, 27, 64, 2049, 100_003, 0];

fn input(n: u32, seed: u64) -> Vec<[u32; 4]> {
    let mut r = Rng(seed);
    (0..n).map(|i| [i, r.next_u32(), r.next_u32(), r.next_u32().is_multiple_of(3) as u32]).collect()
}

/// Step 1 keeps `w != 0`; step 2 keeps odd `y`.
const STEP1: &str = "(v.w != 0u)";
const STEP2: &str = "((v.y & 1u) == 1u)";

/// (step-1 output, step-2 output, xfb query (written, needed)).
type Outcome = (Vec<[u32; 4]>, Vec<[u32; 4]>, Option<(u64, u64)>);

fn run(path: CompactionPath, n: u32) -> Outcome {
    let (ctx, shaders) = context();
    let data = input(n, 0x9E37_79B9 ^ n as u64);
    let bytes: Vec<u8> = bytemuck::cast_slice(&data).to_vec();
    let in_buf = ctx.buffer_with_data("input", if bytes.is_empty() { &[0u8; 16] } else { &bytes }).unwrap();
    let c1 = Compactor::new(&ctx, &shaders, path, STEP1).unwrap();
    let c2 = Compactor::new(&ctx, &shaders, path, STEP2).unwrap();
    let s1 = CompactStream::new(&ctx, "step1", path, n.max(1)).unwrap();
    let s2 = CompactStream::new(&ctx, "step2", path, n.max(1)).unwrap();
    let pool = (path == CompactionPath::TransformFeedback).then(|| QueryPool::transform_feedback(&ctx, 1).unwrap());
    let mut f = ctx.frame(FrameOptions { timestamps: true, pipeline_statistics: true, ..Default::default() }).unwrap();
    c1.record(&mut f, "compact.step1", Source::Array(&in_buf, n), &s1, pool.as_ref().map(|p| (p, 0))).unwrap();
    c2.record(&mut f, "compact.step2", Source::Stream(&s1), &s2, None).unwrap();
    let report = f.submit().unwrap();
    assert!(report.pass("compact.step1").is_some());
    let out1 = s1.read(&ctx).unwrap();
    let out2 = s2.read(&ctx).unwrap();
    if path == CompactionPath::Compute {
        // The Rust twin of compact_counter.glsl reads what finalize wrote: the count, then
        // VkDispatchIndirectCommand over 64-wide groups (at least one) and VkDrawIndirectCommand.
        let header: AppendCounter = ctx.read_buffer_as::<AppendCounter>(s1.counter()).unwrap()[0];
        let k = out1.len() as u32;
        assert_eq!((header.count, header.capacity), (k, n.max(1)), "n = {n}");
        assert_eq!(header.dispatch, [k.div_ceil(64).max(1), 1, 1, 0], "n = {n}");
        assert_eq!(header.draw, [k, 1, 0, 0], "n = {n}");
    }
    let q = pool.map(|p| p.read_xfb().unwrap()[0]);
    drop((c1, c2, s1, s2, in_buf));
    assert_no_validation_messages(&ctx);
    (out1, out2, q)
}

fn check(path: CompactionPath) {
    for n in SIZES {
        let data = input(n, 0x9E37_79B9 ^ n as u64);
        let want1: Vec<[u32; 4]> = data.iter().copied().filter(|v| v[3] != 0).collect();
        let want2: Vec<[u32; 4]> = want1.iter().copied().filter(|v| v[1] & 1 == 1).collect();
        let (mut got1, mut got2, q) = run(path, n);
        if path == CompactionPath::Compute {
            // Append order is whatever the atomics gave; compare as sets.
            got1.sort();
            got2.sort();
        }
        assert_eq!(got1, want1, "{path:?} step 1, n = {n}");
        assert_eq!(got2, want2, "{path:?} step 2 (GPU-driven count), n = {n}");
        if let Some((written, needed)) = q {
            assert_eq!(written, want1.len() as u64, "xfb primitives-written query, n = {n}");
            assert_eq!(needed, want1.len() as u64, "xfb primitives-needed query, n = {n}");
        }
    }
}

#[test]
fn transform_feedback_compaction_matches_cpu() {
    check(CompactionPath::TransformFeedback);
}

#[test]
fn compute_append_compaction_matches_cpu() {
    check(CompactionPath::Compute);
}

#[test]
fn both_paths_give_the_same_set() {
    let n = 2049;
    let (mut a1, mut a2, _) = run(CompactionPath::TransformFeedback, n);
    let (mut b1, mut b2, _) = run(CompactionPath::Compute, n);
    for v in [&mut a1, &mut a2, &mut b1, &mut b2] {
        v.sort();
    }
    assert_eq!(a1, b1);
    assert_eq!(a2, b2);
}

#[test]
fn xfb_path_without_transform_feedback_names_the_feature() {
    let opts = vkcore::ContextOptions::for_tests(vec![vkcore::Feature::TransformFeedback]);
    let ctx = vkcore::Context::new(&opts).unwrap();
    let shaders = vkcore::ShaderCompiler::new(&shader_root()).unwrap();
    let err = Compactor::new(&ctx, &shaders, CompactionPath::TransformFeedback, STEP1).err().expect("must fail");
    let msg = err.to_string();
    assert!(msg.contains("transform_feedback") && msg.contains("VK_EXT_transform_feedback"), "got: {msg}");
    assert_no_validation_messages(&ctx);
}

/// A seed (elements uploaded once, `upload_seeded_counter`) feeds a GPU-driven step on both
/// paths: the xfb path draws it from its byte count, the compute path dispatches it from the
/// arguments of [`AppendCounter::full`].
#[test]
fn a_seeded_stream_feeds_a_step_on_both_paths() {
    for path in [CompactionPath::TransformFeedback, CompactionPath::Compute] {
        let (ctx, shaders) = context();
        let n = 300;
        let data = input(n, 7);
        let seed = CompactStream::new(&ctx, "seed", path, n).unwrap();
        ctx.upload_buffer(seed.data(), bytemuck::cast_slice(&data)).unwrap();
        seed.upload_seeded_counter(&ctx, n).unwrap();
        assert_eq!(seed.count(&ctx).unwrap(), n, "{path:?}");
        let out = CompactStream::new(&ctx, "out", path, n).unwrap();
        let c = Compactor::new(&ctx, &shaders, path, STEP1).unwrap();
        let mut f = ctx.frame(FrameOptions::default()).unwrap();
        c.record(&mut f, "compact.seeded", Source::Stream(&seed), &out, None).unwrap();
        f.submit().unwrap();
        let mut got = out.read(&ctx).unwrap();
        got.sort();
        let want: Vec<[u32; 4]> = data.iter().copied().filter(|v| v[3] != 0).collect();
        assert_eq!(got, want, "{path:?}");
        drop((c, seed, out));
        assert_no_validation_messages(&ctx);
    }
}
