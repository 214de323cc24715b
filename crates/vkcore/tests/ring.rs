//! The throughput frame mode (`FrameRing`): warm frames create no Vulkan object and submit once;
//! frames in flight that share buffers still see each other's writes in order (the tracker's
//! barriers, checked by synchronization validation); the result equals the one-shot frames'; a
//! frame that never finishes is named with its slot.

mod common;
use common::*;
use vkcore::*;

const N: u32 = 4096;

/// One frame of the test's work: b = a + k, then a = b + 1, so each frame reads what the one
/// before it wrote (a hazard across frames in flight).
fn record(f: &mut Frame, p: &Pipeline, a: &Buffer, b: &Buffer, k: u32) {
    record_adds(f, p, N, &[("step", a, b, k), ("back", b, a, 1)]);
}

#[test]
fn warm_ring_frames_create_nothing_submit_once_and_equal_one_shot_frames() {
    let (ctx, _) = context();
    let p = add_pipeline(&ctx);
    let start: Vec<u32> = (0..N).collect();
    let frames = 12u32;
    // One-shot frames (the per-pass mode): each makes its command buffer, queries, marker, fence.
    let (a, b) = (
        ctx.buffer_with_data("a", bytemuck::cast_slice(&start)).unwrap(),
        Buffer::new(&ctx, "b", N as u64 * 4, Memory::Gpu).unwrap(),
    );
    for k in 0..frames {
        let before = ctx.counters();
        let mut f = ctx.frame(FrameOptions { timestamps: true, ..Default::default() }).unwrap();
        record(&mut f, &p, &a, &b, k);
        let report = f.submit().unwrap();
        let used = ctx.counters().since(&before);
        assert_eq!(used, report.counters);
        assert!(used.objects >= 4, "a one-shot frame makes its own objects: {used:?}");
        assert_eq!(used.submits, 1);
        assert!(report.passes.iter().all(|p| p.gpu_ms.is_some() || !ctx.info().has(Feature::Timestamps)));
    }
    let one_shot: Vec<u32> = ctx.read_buffer_as(&a).unwrap();

    // The same frames through a ring of two slots.
    let (a, b) = (
        ctx.buffer_with_data("a", bytemuck::cast_slice(&start)).unwrap(),
        Buffer::new(&ctx, "b", N as u64 * 4, Memory::Gpu).unwrap(),
    );
    let mut ring = FrameRing::new(&ctx, RingOptions::default()).unwrap();
    assert_eq!(ring.slots(), 2);
    let mut reports = vec![];
    for k in 0..frames {
        let slot = ring.slot();
        let before = ctx.counters();
        let mut f = ring.frame().unwrap();
        record(&mut f, &p, &a, &b, k);
        ring.submit(f).unwrap();
        let used = ctx.counters().since(&before);
        assert_eq!(used.submits, 1, "frame {k}: one submit per frame");
        if k >= 2 {
            // Warm: both slots have made their query chunk.
            assert_eq!(used.objects, 0, "frame {k} (slot {slot}) created or allocated Vulkan objects: {used:?}");
        }
        reports.extend(ring.reports());
    }
    reports.extend(ring.finish().unwrap());
    let ring_result: Vec<u32> = ctx.read_buffer_as(&a).unwrap();
    assert_eq!(ring_result, one_shot, "ring frames and one-shot frames computed different results");
    let want: Vec<u32> = start.iter().map(|x| x + frames * (frames - 1) / 2 + frames).collect();
    assert_eq!(ring_result, want);

    // Every frame reported once, in order, alternating slots, timed as a whole.
    assert_eq!(reports.iter().map(|r| r.index).collect::<Vec<_>>(), (0..frames as u64).collect::<Vec<_>>());
    for r in &reports {
        assert_eq!(r.slot, Some((r.index % 2) as usize));
        assert_eq!(r.passes.iter().map(|p| p.name.as_str()).collect::<Vec<_>>(), ["step", "back"]);
        assert!(r.passes.iter().all(|p| p.gpu_ms.is_none()), "per-frame timing writes no pass timestamps");
        assert_eq!(r.counters.submits, 1);
        if ctx.info().has(Feature::Timestamps) {
            assert!(r.frame_gpu_ms.is_some_and(|ms| ms > 0.0), "frame {}: {:?}", r.index, r.frame_gpu_ms);
            assert_eq!(r.counters.timestamps, 2, "a pair per frame, none per pass");
        }
        assert!(r.counters.barriers >= 2, "the cross-pass hazards and the frame's crash marker");
    }
    drop((ring, p, a, b));
    assert_no_validation_messages(&ctx);
}

#[test]
fn ring_frames_timed_per_pass_report_every_pass() {
    let (ctx, _) = context();
    // lavapipe and every GPU this project targets have timestamps: no silent pass without them.
    assert!(ctx.info().has(Feature::Timestamps), "{} has no timestamps", ctx.info().name);
    let p = add_pipeline(&ctx);
    let (a, b) = (
        Buffer::new(&ctx, "a", N as u64 * 4, Memory::Gpu).unwrap(),
        Buffer::new(&ctx, "b", N as u64 * 4, Memory::Gpu).unwrap(),
    );
    let mut ring =
        FrameRing::new(&ctx, RingOptions { slots: 3, timing: Timing::PerPass, fence_timeout: None }).unwrap();
    for k in 0..5 {
        let mut f = ring.frame().unwrap();
        record(&mut f, &p, &a, &b, k);
        ring.submit(f).unwrap();
    }
    let reports = ring.finish().unwrap();
    assert_eq!(reports.len(), 5);
    for r in &reports {
        assert!(r.passes.iter().all(|p| p.gpu_ms.is_some()), "{:?}", r.passes);
        assert!(r.frame_gpu_ms.is_none());
        assert_eq!(r.counters.timestamps, 4);
    }
    drop((ring, p, a, b));
    assert_no_validation_messages(&ctx);
}

#[test]
fn a_ring_frame_that_times_out_names_its_frame_and_slot() {
    let (ctx, _) = context();
    let shader = test_shaders().compile("spin.comp", &[]).unwrap();
    let spin = Pipeline::compute(&ctx, "spin", &shader).unwrap();
    let mut release = Buffer::new(&ctx, "release", 16, Memory::Upload).unwrap();
    release.write_mapped(0, &[0u8; 16]).unwrap();
    let scratch = Buffer::new(&ctx, "scratch", 16, Memory::Gpu).unwrap();
    let timeout = std::time::Duration::from_millis(300);
    let mut ring =
        FrameRing::new(&ctx, RingOptions { slots: 2, timing: Timing::PerFrame, fence_timeout: Some(timeout) }).unwrap();
    // Frame 0 (slot 0) is quick and finished; frame 1 (slot 1) spins until released.
    let mut f = ring.frame().unwrap();
    f.pass("quick")
        .uses([Use::buffer(&scratch, Access::TRANSFER_WRITE)])
        .record(|cmd| {
            cmd.fill_buffer(&scratch, 7);
            Ok(())
        })
        .unwrap();
    ring.submit(f).unwrap();
    assert_eq!(ring.finish().unwrap().len(), 1);
    let mut f = ring.frame().unwrap();
    f.pass("slow")
        .bind(&spin, [("Release", Bind::Buffer(&release))])
        .record(|cmd| {
            cmd.dispatch(256, 1, 1);
            Ok(())
        })
        .unwrap();
    ring.submit(f).unwrap();
    let releaser = std::thread::spawn(move || {
        std::thread::sleep(timeout * 6);
        release.write_mapped(0, &0x8000_0000u32.to_le_bytes()).unwrap();
        release
    });
    // Frame 2 (slot 0) is dropped unsubmitted (the slot remakes what it freed); frame 3 reuses
    // slot 1, whose frame 1 has not finished. (lavapipe does not time out a wait for an earlier
    // submission while a later one runs, so nothing else is queued behind frame 1.)
    drop(ring.frame().unwrap());
    let started = std::time::Instant::now();
    let err = ring.frame().err().expect("waiting for frame 1 should time out");
    assert!(started.elapsed() >= timeout, "the wait gave up too early");
    let release = releaser.join().unwrap();
    match &err {
        VkError::FrameFailed { ring: Some((frame, slot, _)), passes, .. } => {
            assert_eq!((*frame, *slot), (1, 1), "{err}");
            assert_eq!(passes, &vec!["slow".to_string()]);
        }
        other => panic!("expected a failed ring frame, got: {other}"),
    }
    let text = err.to_string();
    assert!(
        text.contains("frame 1") && text.contains("slot 1") && text.contains("TIMEOUT") && text.contains("slow"),
        "{text}"
    );
    // The ring and the context are still usable.
    let f = ring.frame().unwrap();
    ring.submit(f).unwrap();
    ring.finish().unwrap();
    assert_eq!(ctx.read_buffer_as::<u32>(&scratch).unwrap(), vec![7; 4]);
    drop((ring, spin, release, scratch));
    assert_no_validation_messages(&ctx);
}
