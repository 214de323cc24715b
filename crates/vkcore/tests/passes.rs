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
                cmd.push(&[N, add])?;
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
            cmd.push(&[N, add])?;
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
