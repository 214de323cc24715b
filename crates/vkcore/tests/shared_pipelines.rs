//! Pipelines of equal descriptions share one Vulkan pipeline while either lives; any difference
//! (name, SPIR-V, fixed-function state) makes a new one; the last holder destroys it.

mod common;
use common::*;
use vkcore::*;

#[test]
fn equal_compute_pipelines_are_made_once_and_outlive_their_first_holder() {
    let (ctx, _) = context();
    let sh = test_shaders();
    let mark = ctx.pipelines_made();
    let a = add_pipeline(&ctx);
    let b = add_pipeline(&ctx);
    assert!(a.shares(&b));
    assert_eq!(ctx.pipelines_made_since(mark), vec!["add".to_string()]);

    let renamed = Pipeline::compute(&ctx, "add again", &sh.compile("add.comp", &[]).unwrap()).unwrap();
    let other_code = Pipeline::compute(&ctx, "add", &sh.compile("spin.comp", &[]).unwrap()).unwrap();
    assert!(!renamed.shares(&a) && !other_code.shares(&a));
    assert_eq!(ctx.pipelines_made_since(mark), vec!["add", "add again", "add"]);

    // The first holder goes; the second still runs the pipeline.
    drop(a);
    let n = 100u32;
    let input: Vec<u32> = (0..n).collect();
    let src = ctx.buffer_with_data("in", bytemuck::cast_slice(&input)).unwrap();
    let dst = Buffer::new(&ctx, "out", n as u64 * 4, Memory::Gpu).unwrap();
    let mut f = ctx.frame(FrameOptions::default()).unwrap();
    record_adds(&mut f, &b, n, &[("add 7", &src, &dst, 7)]);
    f.submit().unwrap();
    let got: Vec<u32> = ctx.read_buffer_as::<u32>(&dst).unwrap();
    assert_eq!(got, input.iter().map(|v| v + 7).collect::<Vec<_>>());

    // Once no holder is left, the next request makes it again.
    drop(b);
    let made = ctx.pipelines_made();
    let c = add_pipeline(&ctx);
    assert_eq!(ctx.pipelines_made_since(made), vec!["add".to_string()]);
    drop((c, renamed, other_code, src, dst));
    assert_no_validation_messages(&ctx);
}

#[test]
fn graphics_pipelines_differing_only_in_fixed_function_state_are_not_shared() {
    let (ctx, _) = context();
    let sh = test_shaders();
    let desc = || {
        let mut d = GraphicsDesc::new(
            "layer value",
            sh.compile("fullscreen_layer.vert", &[]).unwrap(),
            Some(sh.compile("layer_value.frag", &[]).unwrap()),
        );
        d.color_formats = vec![Format::R32G32B32A32_SFLOAT];
        d
    };
    let mark = ctx.pipelines_made();
    let a = Pipeline::graphics(&ctx, &desc()).unwrap();
    let b = Pipeline::graphics(&ctx, &desc()).unwrap();
    assert!(a.shares(&b));
    let mut additive = desc();
    additive.blend = Blend::Additive;
    let mut other_format = desc();
    other_format.color_formats = vec![Format::R16G16B16A16_SFLOAT];
    let mut culled = desc();
    culled.cull = Cull::Back;
    let others: Vec<Pipeline> =
        [additive, other_format, culled].iter().map(|d| Pipeline::graphics(&ctx, d).unwrap()).collect();
    assert!(others.iter().all(|p| !p.shares(&a)));
    assert_eq!(ctx.pipelines_made_since(mark).len(), 4);
    drop((a, b, others));
    assert_no_validation_messages(&ctx);
}
