//! Pipeline-statistics queries around a frame that mixes a graphics pass pushing constants with
//! compute passes, under validation, on whatever device the tests run on (in CI, Debian 12's
//! lavapipe and, through scripts/mesa25_check.sh, Mesa 25's). Before pipelines named only their
//! own stages, a graphics pass pushed constants for the compute stage too, and both lavapipes
//! dereferenced a null compute shader at the next pass's vkCmdBeginQuery: this frame crashed
//! (docs/mesa_lavapipe_statistics_crash.md).

mod common;
use common::*;
use vkcore::*;

vkcore::push_constants! {
    /// pushed_value.frag's push constants.
    pub struct ValueConstants {
        pub value: f32,
    }
}

const SIZE: u32 = 16;
const N: u32 = 256;

#[test]
fn statistics_count_a_pushed_draw_and_the_dispatches_after_it() {
    let (ctx, _) = context();
    if ctx.info().driver_name == "llvmpipe" {
        // No lavapipe lists a statistics quirk any more: the crash was ours to avoid.
        assert!(ctx.info().has(Feature::PipelineStatisticsQuery), "quirks: {:?}", ctx.info().quirks);
    }
    if !ctx.info().has(Feature::PipelineStatisticsQuery) {
        eprintln!("{} has no pipeline statistics; checking the frame renders without them", ctx.info().name);
    }
    let sh = test_shaders();
    let frag = sh.compile("pushed_value.frag", &[]).unwrap();
    check_push_constants::<ValueConstants>(&frag).unwrap();
    let mut desc = GraphicsDesc::new("pushed value", sh.compile("fullscreen_layer.vert", &[]).unwrap(), Some(frag));
    desc.color_formats = vec![Format::R32G32B32A32_SFLOAT];
    let draw = Pipeline::graphics(&ctx, &desc).unwrap();
    let add = add_pipeline(&ctx);
    let target = Image::new(&ctx, ImageDesc::new_2d("target", Format::R32G32B32A32_SFLOAT, SIZE, SIZE)).unwrap();
    let view = target.full_view().unwrap();
    let input: Vec<u32> = (0..N).collect();
    let a = ctx.buffer_with_data("a", bytemuck::cast_slice(&input)).unwrap();
    let b = Buffer::new(&ctx, "b", N as u64 * 4, Memory::Gpu).unwrap();

    let mut f = ctx.frame(FrameOptions { timestamps: true, pipeline_statistics: true, ..Default::default() }).unwrap();
    f.pass("draw")
        .bind(&draw, [])
        .uses([Use::view(&view, Access::COLOR_ATTACHMENT)])
        .record(|c| {
            c.begin_rendering(&Targets::color(&view, Some([0.0; 4])))?;
            c.push(&ValueConstants { value: 0.75 })?;
            c.draw(3, 1, 0, 0);
            c.end_rendering();
            Ok(())
        })
        .unwrap();
    // The pass after a pushed draw begins its query with no compute pipeline bound yet.
    record_adds(&mut f, &add, N, &[("add", &a, &b, 5)]);
    let report = f.submit().unwrap();

    let texels = ctx.read_image_f32(&target, 0, 0).unwrap();
    assert!(texels.chunks(4).all(|t| t[0] == 0.75), "the pushed value in every texel: {:?}", &texels[..8]);
    let got: Vec<u32> = ctx.read_buffer_as(&b).unwrap();
    assert_eq!(got[..N as usize], input.iter().map(|x| x + 5).collect::<Vec<_>>()[..]);
    if ctx.info().has(Feature::PipelineStatisticsQuery) {
        let stats = |name| report.pass(name).unwrap().stats.unwrap_or_else(|| panic!("{name}: no statistics"));
        let (d, c) = (stats("draw"), stats("add"));
        // One triangle of three vertices; every texel of the target shaded at least once, and
        // not twice over (the spec lets a device count helper invocations: lavapipe clips the
        // oversized triangle into three and shades 2x2 quads on their shared edges, 320 for 256).
        assert_eq!((d.input_vertices, d.input_primitives, d.compute_invocations), (3, 1, 0), "{d:?}");
        let texels = (SIZE * SIZE) as u64;
        assert!((texels..2 * texels).contains(&d.fragment_invocations), "{d:?}");
        // add.comp's 64-wide groups over N values; no vertex or fragment work.
        assert_eq!((c.compute_invocations, c.input_vertices, c.fragment_invocations), (N as u64, 0, 0), "{c:?}");
    }
    drop((draw, add, view, target, a, b));
    assert_no_validation_messages(&ctx);
}
