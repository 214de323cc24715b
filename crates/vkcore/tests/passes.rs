//! The pass builder: descriptors named once give both the push descriptor and the barrier
//! (synchronization validation checks the barriers), and descriptors a pass did not declare are
//! refused.

mod common;
use common::*;
use std::path::PathBuf;
use vkcore::*;

fn test_shaders() -> ShaderCompiler {
    ShaderCompiler::new(&PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("tests/shaders")).unwrap()
}

const N: u32 = 1000;

vkcore::push_constants! {
    /// add.comp's push constants.
    struct AddConstants {
        count: u32,
        add: u32,
    }
}

#[test]
fn add_constants_match_their_glsl_twin() {
    check_push_constants::<AddConstants>(&test_shaders().compile("add.comp", &[]).unwrap()).unwrap();
}

fn add_pipeline(ctx: &Context) -> Pipeline {
    let shader = test_shaders().compile("add.comp", &[]).unwrap();
    Pipeline::compute(ctx, "add", &shader, &[BindingKind::StorageBuffer, BindingKind::StorageBuffer]).unwrap()
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
    for (name, src, dst, add) in [("first", &a, &b, 1u32), ("second", &b, &c, 2), ("third", &c, &b, 3)] {
        f.pass(name)
            .bind(&p, [Bind::BufferRead(src), Bind::Buffer(dst)])
            .record(|cmd| {
                cmd.push(&AddConstants { count: N, add })?;
                cmd.dispatch(N.div_ceil(64), 1, 1);
                Ok(())
            })
            .unwrap();
    }
    f.submit().unwrap();
    let got: Vec<u32> = ctx.read_buffer_as(&b).unwrap();
    let want: Vec<u32> = input.iter().map(|x| x + 6).collect();
    assert_eq!(&got[..N as usize], &want[..]);
    drop((p, a, b, c));
    assert_no_validation_messages(&ctx);
}

#[test]
fn declared_sets_may_be_pushed_inside_and_others_are_refused() {
    let (ctx, _) = context();
    let p = add_pipeline(&ctx);
    let a = ctx.buffer_with_data("a", bytemuck::cast_slice(&[5u32; N as usize])).unwrap();
    let b = Buffer::new(&ctx, "b", N as u64 * 4, Memory::Gpu).unwrap();
    let c = Buffer::new(&ctx, "c", N as u64 * 4, Memory::Gpu).unwrap();
    let mut f = ctx.frame(FrameOptions::default()).unwrap();
    // Two sets pushed one after the other inside the pass, both declared.
    let sets = [[Bind::BufferRead(&a), Bind::Buffer(&b)], [Bind::BufferRead(&a), Bind::Buffer(&c)]];
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
    // A set the pass did not declare: its barriers would be missing.
    let err = f
        .pass("undeclared")
        .declare(&p, &[Bind::BufferRead(&a), Bind::Buffer(&b)])
        .record(|cmd| {
            cmd.bind_pipeline(&p);
            cmd.bind(&[Bind::BufferRead(&b), Bind::Buffer(&c)])
        })
        .unwrap_err()
        .to_string();
    assert!(err.contains("not declared"), "got: {err}");
    // Descriptors that do not fit the pipeline are refused before anything is recorded.
    let err = f.pass("too few").bind(&p, [Bind::Buffer(&b)]).record(|_| Ok(())).unwrap_err().to_string();
    assert!(err.contains("too few") && err.contains("2 bindings, 1 given"), "got: {err}");
    let err = f.pass("wrong kind").bind(&p, [Bind::Uniform(&a), Bind::Buffer(&b)]).record(|_| Ok(())).unwrap_err();
    assert!(err.to_string().contains("binding 0"), "got: {err}");
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
    let spin = Pipeline::compute(&ctx, "spin", &shader, &[BindingKind::StorageBuffer]).unwrap();
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
        .bind(&spin, [Bind::Buffer(&release)])
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
