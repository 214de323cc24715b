//! The pass builder: descriptors named once give both the push descriptor and the barrier
//! (synchronization validation checks the barriers), and descriptors a pass did not declare are
//! refused.

mod common;
use common::*;
use vkcore::*;

const N: u32 = 1000;

#[test]
fn add_constants_match_their_glsl_twin() {
    check_push_constants::<AddConstants>(&test_shaders().compile("add.comp", &[]).unwrap()).unwrap();
}

/// Passes `first`, `second`, `third`: b = a + 1, c = b + 2, b = c + 3 (buffers `[a, b, c]`).
fn record_chain(f: &mut Frame, p: &Pipeline, [a, b, c]: [&Buffer; 3]) {
    record_adds(f, p, N, &[("first", a, b, 1), ("second", b, c, 2), ("third", c, b, 3)]);
}

#[test]
fn bound_descriptors_get_their_barriers() {
    let (ctx, _) = context();
    let p = add_pipeline(&ctx);
    let input: Vec<u32> = (0..N).map(|i| i * 3).collect();
    let a = ctx.buffer_with_data("a", bytemuck::cast_slice(&input)).unwrap();
    let b = Buffer::new(&ctx, "b", N as u64 * 4, Memory::Gpu).unwrap();
    let c = Buffer::new(&ctx, "c", N as u64 * 4, Memory::Gpu).unwrap();
    let mut f = ctx.frame(FrameOptions::default()).unwrap();
    // b = a + 1, then c = b + 2 (read after write), then b = c + 3 (write after read): each
    // hazard needs the barrier its descriptors imply.
    record_chain(&mut f, &p, [&a, &b, &c]);
    f.submit().unwrap();
    let got: Vec<u32> = ctx.read_buffer_as(&b).unwrap();
    let want: Vec<u32> = input.iter().map(|x| x + 6).collect();
    assert_eq!(&got[..N as usize], &want[..]);
    drop((p, a, b, c));
    assert_no_validation_messages(&ctx);
}

/// `host_pass_times`: each pass is submitted and waited for alone, its host time kept, and
/// what one pass wrote is what the next reads (the barriers and the command buffer survive the
/// submits in between).
#[test]
fn host_pass_times_submit_every_pass_and_keep_the_frames_result() {
    let (ctx, _) = context();
    let p = add_pipeline(&ctx);
    let input: Vec<u32> = (0..N).map(|i| i * 5).collect();
    let a = ctx.buffer_with_data("a", bytemuck::cast_slice(&input)).unwrap();
    let b = Buffer::new(&ctx, "b", N as u64 * 4, Memory::Gpu).unwrap();
    let c = Buffer::new(&ctx, "c", N as u64 * 4, Memory::Gpu).unwrap();
    let before = ctx.counters();
    let opts = FrameOptions { timestamps: true, host_pass_times: true, ..Default::default() };
    let mut f = ctx.frame(opts).unwrap();
    record_chain(&mut f, &p, [&a, &b, &c]);
    let report = f.submit().unwrap();
    let submits = ctx.counters().since(&before).submits;
    let got: Vec<u32> = ctx.read_buffer_as(&b).unwrap();
    let want: Vec<u32> = input.iter().map(|x| x + 6).collect();
    assert_eq!(&got[..N as usize], &want[..]);
    // One submit per pass, and the frame's own (the commands after the last pass).
    assert_eq!(submits, 4, "submits of a frame of three passes timed on the host");
    let names: Vec<&str> = report.passes.iter().map(|p| p.name.as_str()).collect();
    assert_eq!(names, ["first", "second", "third"]);
    for pass in &report.passes {
        let ms = pass.host_ms.unwrap_or_else(|| panic!("pass {} has no host time", pass.name));
        assert!(ms.is_finite() && ms > 0.0, "pass {}: host time {ms} ms", pass.name);
    }
    // Without the option no pass has a host time, and the frame submits once.
    let before = ctx.counters();
    let mut f = ctx.frame(FrameOptions::default()).unwrap();
    f.pass("only")
        .bind(&p, [("In", Bind::BufferRead(&a)), ("Out", Bind::Buffer(&c))])
        .record(|cmd| {
            cmd.push(&AddConstants { count: N, add: 1 })?;
            cmd.dispatch(N.div_ceil(64), 1, 1);
            Ok(())
        })
        .unwrap();
    let report = f.submit().unwrap();
    assert_eq!(ctx.counters().since(&before).submits, 1);
    assert!(report.passes[0].host_ms.is_none());
    drop((p, a, b, c));
    assert_no_validation_messages(&ctx);
}

#[test]
fn declared_sets_may_be_pushed_inside_and_others_are_refused() {
    let (ctx, _) = context();
    let p = add_pipeline(&ctx);
    let input: Vec<u32> = (0..N).map(|i| i * 7).collect();
    let a = ctx.buffer_with_data("a", bytemuck::cast_slice(&input)).unwrap();
    let b = Buffer::new(&ctx, "b", N as u64 * 4, Memory::Gpu).unwrap();
    let c = Buffer::new(&ctx, "c", N as u64 * 4, Memory::Gpu).unwrap();
    let mut f = ctx.frame(FrameOptions::default()).unwrap();
    // Two sets pushed one after the other inside the pass, both declared: add.comp writes
    // Out[i] = In[i] + add, so b = a + 1 and c = a + 2 once the frame ran.
    let sets = [
        [("In", Bind::BufferRead(&a)), ("Out", Bind::Buffer(&b))],
        [("In", Bind::BufferRead(&a)), ("Out", Bind::Buffer(&c))],
    ];
    let mut pass = f.pass("two sets");
    for set in &sets {
        pass = pass.declare(&p, set);
    }
    pass.record(|cmd| {
        cmd.bind_pipeline(&p);
        for (set, add) in sets.iter().zip([1u32, 2]) {
            cmd.bind(set)?;
            cmd.push(&AddConstants { count: N, add })?;
            cmd.dispatch(N.div_ceil(64), 1, 1);
        }
        Ok(())
    })
    .unwrap();
    f.submit().unwrap();
    let got_b: Vec<u32> = ctx.read_buffer_as(&b).unwrap();
    let got_c: Vec<u32> = ctx.read_buffer_as(&c).unwrap();
    let want_b: Vec<u32> = input.iter().map(|x| x + 1).collect();
    let want_c: Vec<u32> = input.iter().map(|x| x + 2).collect();
    assert_eq!(&got_b[..N as usize], &want_b[..], "b, written by the first pushed set");
    assert_eq!(&got_c[..N as usize], &want_c[..], "c, written by the second pushed set");
    // The refused passes record nothing, in a frame of their own that is never submitted.
    let mut f = ctx.frame(FrameOptions::default()).unwrap();
    // A set the pass did not declare: its barriers would be missing.
    let err = f
        .pass("undeclared")
        .declare(&p, &[("In", Bind::BufferRead(&a)), ("Out", Bind::Buffer(&b))])
        .record(|cmd| {
            cmd.bind_pipeline(&p);
            cmd.bind(&[("In", Bind::BufferRead(&b)), ("Out", Bind::Buffer(&c))])
        })
        .unwrap_err()
        .to_string();
    assert!(err.contains("not declared"), "got: {err}");
    // Descriptors that do not fit the pipeline are refused before anything is recorded.
    let err = f.pass("too few").bind(&p, [("In", Bind::Buffer(&b))]).record(|_| Ok(())).unwrap_err().to_string();
    assert!(err.contains("too few") && err.contains("binding 1 `Out`") && err.contains("not given"), "got: {err}");
    let err = f
        .pass("wrong kind")
        .bind(&p, [("In", Bind::Uniform(&a)), ("Out", Bind::Buffer(&b))])
        .record(|_| Ok(()))
        .unwrap_err();
    assert!(err.to_string().contains("binding 0 `In` is a StorageBuffer"), "got: {err}");
    // Two buffers of one kind swapped: the names say so, where the kinds could not.
    let err = f
        .pass("swapped")
        .bind(&p, [("Out", Bind::Buffer(&b)), ("In", Bind::BufferRead(&a))])
        .record(|_| Ok(()))
        .unwrap_err()
        .to_string();
    assert!(
        err.contains("pipeline `add`")
            && err.contains("binding 0 is `In`")
            && err.contains("gives `Out`")
            && err.contains("`Out` is binding 1"),
        "got: {err}"
    );
    drop((f, p, a, b, c));
    assert_no_validation_messages(&ctx);
}

/// Work groups of spin.comp: enough that llvmpipe, which caps each invocation's loops, would
/// take seconds over them if they were never released (about 10 s on two cores).
const SPINNERS: u32 = 256;

#[test]
fn a_frame_that_times_out_names_the_last_pass_that_finished() {
    let (ctx, _) = context();
    let shader = test_shaders().compile("spin.comp", &[]).unwrap();
    let spin = Pipeline::compute(&ctx, "spin", &shader).unwrap();
    let mut release = Buffer::new(&ctx, "release", 16, Memory::Upload).unwrap();
    release.write_mapped(0, &[0u8; 16]).unwrap();
    let scratch = Buffer::new(&ctx, "scratch", 16, Memory::Gpu).unwrap();
    let timeout = std::time::Duration::from_millis(300);
    let mut f = ctx.frame(FrameOptions { fence_timeout: Some(timeout), ..Default::default() }).unwrap();
    f.pass("quick")
        .uses([Use::buffer(&scratch, Access::TRANSFER_WRITE)])
        .record(|cmd| {
            cmd.fill_buffer(&scratch, 7);
            Ok(())
        })
        .unwrap();
    f.pass("slow")
        .bind(&spin, [("Release", Bind::Buffer(&release))])
        .record(|cmd| {
            cmd.dispatch(SPINNERS, 1, 1);
            Ok(())
        })
        .unwrap();
    // The slow pass spins until released, well after the fence wait gave up (submit waits for
    // the GPU to finish before it returns the error).
    let releaser = std::thread::spawn(move || {
        std::thread::sleep(timeout * 6);
        release.write_mapped(0, &0x8000_0000u32.to_le_bytes()).unwrap();
        release
    });
    let started = std::time::Instant::now();
    let result = f.submit();
    let release = releaser.join().unwrap();
    let err = result.unwrap_err();
    match &err {
        VkError::FrameFailed { last_finished, next, .. } => {
            assert_eq!(last_finished.as_deref(), Some("quick"), "{err}");
            assert_eq!(next.as_deref(), Some("slow"), "{err}");
        }
        other => panic!("expected a failed frame, got: {other}"),
    }
    let text = err.to_string();
    assert!(text.contains("TIMEOUT") && text.contains("`quick`") && text.contains("`slow`"), "{text}");
    assert!(started.elapsed() >= timeout, "the wait gave up too early");
    // The context is still usable after the GPU finished the frame.
    assert_eq!(ctx.read_buffer_as::<u32>(&scratch).unwrap(), vec![7; 4]);
    drop((spin, release, scratch));
    assert_no_validation_messages(&ctx);
}

/// What a command reads or writes outside its descriptors (vertex and index buffers, indirect
/// arguments, transform-feedback buffers and counters) needs its barrier too: each command
/// refuses a buffer the pass did not declare with that access, naming the buffer and the access.
#[test]
fn vertex_index_indirect_and_transform_feedback_buffers_must_be_declared() {
    let (ctx, _) = context();
    let buf = Buffer::new(&ctx, "undeclared args", 64, Memory::Gpu).unwrap();
    let other = Buffer::new(&ctx, "declared for something else", 64, Memory::Gpu).unwrap();
    let mut f = ctx.frame(FrameOptions::default()).unwrap();
    type Command = fn(&mut Cmd, &Buffer) -> Result<()>;
    let commands: [(&str, &str, Command); 8] = [
        ("bind_vertex_buffer", "VERTEX_INPUT", |c, b| c.bind_vertex_buffer(b, 0)),
        ("bind_index_buffer", "VERTEX_INPUT", |c, b| c.bind_index_buffer(b)),
        ("draw_indirect", "INDIRECT", |c, b| c.draw_indirect(b, 0)),
        ("dispatch_indirect", "INDIRECT", |c, b| c.dispatch_indirect(b, 0)),
        ("bind_xfb_buffers", "XFB_WRITE", |c, b| c.bind_xfb_buffers(&[b])),
        ("begin_xfb", "XFB_COUNTER", |c, b| c.begin_xfb(&[b], true)),
        ("end_xfb", "XFB_COUNTER", |c, b| c.end_xfb(&[b])),
        ("draw_indirect_byte_count", "INDIRECT", |c, b| c.draw_indirect_byte_count(1, b, 4)),
    ];
    for (name, access, command) in commands {
        // Declared, but for a transfer: not what the command does with it.
        let err = f
            .pass(name)
            .uses([Use::buffer(&other, Access::TRANSFER_WRITE)])
            .record(|cmd| command(cmd, &buf))
            .unwrap_err()
            .to_string();
        assert!(
            err.contains(name) && err.contains("`undeclared args`") && err.contains(&format!("Access::{access}")),
            "{name}: {err}"
        );
        let err = f
            .pass(name)
            .uses([Use::buffer(&other, Access::TRANSFER_WRITE)])
            .record(|cmd| command(cmd, &other))
            .unwrap_err()
            .to_string();
        assert!(err.contains("`declared for something else`"), "{name}: {err}");
    }
    drop((f, buf, other));
}
