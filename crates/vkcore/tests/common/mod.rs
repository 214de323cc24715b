//! Shared by vkcore's GPU tests: a lavapipe-or-GPU context with the Khronos validation layer
//! (synchronization validation on) and a check that no message was reported.
#![allow(dead_code)]

use std::path::PathBuf;
use vkcore::{Bind, Buffer, Context, ContextOptions, Frame, Pipeline, ShaderCompiler};

pub fn shader_root() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../../shaders_glsl")
}

/// A validated context on `$CAUSTICLAB_TEST_DEVICE` (default: the default device).
pub fn context() -> (Context, ShaderCompiler) {
    let opts = ContextOptions::for_tests(vec![]);
    let ctx = Context::new(&opts).expect("a Vulkan 1.3 device with the validation layer (run scripts/setup.sh)");
    let shaders = ShaderCompiler::new(&shader_root()).expect("shaderc");
    (ctx, shaders)
}

/// Fails the test if the validation layer reported anything.
pub fn assert_no_validation_messages(ctx: &Context) {
    let log = ctx.validation_log();
    assert_eq!(log.count(), 0, "validation messages:\n{}", log.messages().join("\n"));
}

/// A tiny deterministic PRNG (xorshift64*), so tests need no crates.
pub struct Rng(pub u64);
impl Rng {
    pub fn next_u32(&mut self) -> u32 {
        self.0 ^= self.0 >> 12;
        self.0 ^= self.0 << 25;
        self.0 ^= self.0 >> 27;
        (self.0.wrapping_mul(0x2545_F491_4F6C_DD1D) >> 32) as u32
    }
}

/// The compiler of the tests' own shaders (`tests/shaders`).
pub fn test_shaders() -> ShaderCompiler {
    ShaderCompiler::new(&PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("tests/shaders")).unwrap()
}

vkcore::push_constants! {
    /// add.comp's push constants.
    pub struct AddConstants {
        pub count: u32,
        pub add: u32,
    }
}

/// add.comp: Out[i] = In[i] + add for i < count.
pub fn add_pipeline(ctx: &Context) -> Pipeline {
    let shader = test_shaders().compile("add.comp", &[]).unwrap();
    Pipeline::compute(ctx, "add", &shader).unwrap()
}

/// One add.comp pass per step `(name, from, to, add)` over `n` values, in order.
pub fn record_adds(f: &mut Frame, p: &Pipeline, n: u32, steps: &[(&str, &Buffer, &Buffer, u32)]) {
    for &(name, src, dst, add) in steps {
        f.pass(name)
            .bind(p, [("In", Bind::BufferRead(src)), ("Out", Bind::Buffer(dst))])
            .record(|cmd| {
                cmd.push(&AddConstants { count: n, add })?;
                cmd.dispatch(n.div_ceil(64), 1, 1);
                Ok(())
            })
            .unwrap();
    }
}
