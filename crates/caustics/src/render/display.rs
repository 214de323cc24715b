//! The viewer's display image (`causticlab view`): one compute pass at the end of a frame turns
//! the final image's linear radiance into the 8-bit sRGB codes that final.png holds
//! (`shaders_glsl/viewer/display.comp`), at the window's size; the window's presenter copies it
//! into the swapchain. In split view the right part comes from a second renderer's final image.

use crate::gpu::Target;
use anyhow::Result;
use vkcore::{
    push_constants, Bind, Context, Filter, Format, Frame, ImageDesc, ImageView, Pipeline, Sampler, ShaderCompiler,
};

push_constants! {
    /// `viewer/display.comp`.
    pub struct DisplayConstants {
        /// The scene's `render.exposure`.
        pub exposure: f32,
        /// The first column drawn from the second render (the width or more: none).
        pub split: u32,
    }
}

/// The display image's format: 8-bit codes, already sRGB-encoded by the pass.
pub const DISPLAY_FORMAT: Format = Format::R8G8B8A8_UNORM;

/// The pass name in the frame's timings.
pub const DISPLAY_PASS: &str = "display";

pub struct Display {
    pipeline: Pipeline,
    nearest: Sampler,
    pub target: Target,
}

impl Display {
    pub fn new(ctx: &Context, shaders: &ShaderCompiler, size: (u32, u32)) -> Result<Display> {
        let spirv = shaders.compile("viewer/display.comp", &[])?;
        vkcore::check_push_constants::<DisplayConstants>(&spirv).map_err(anyhow::Error::msg)?;
        Ok(Display {
            pipeline: Pipeline::compute(ctx, DISPLAY_PASS, &spirv)?,
            nearest: Sampler::new(ctx, Filter::Nearest)?,
            target: Target::new(ctx, ImageDesc::new_2d("display", DISPLAY_FORMAT, size.0.max(1), size.1.max(1)))?,
        })
    }

    /// The display image's width and height.
    pub fn size(&self) -> (u32, u32) {
        self.target.view.extent
    }

    /// A display image of `size` (the window's), when it differs.
    pub fn resize(&mut self, ctx: &Context, size: (u32, u32)) -> Result<()> {
        let size = (size.0.max(1), size.1.max(1));
        if size != self.size() {
            self.target = Target::new(ctx, ImageDesc::new_2d("display", DISPLAY_FORMAT, size.0, size.1))?;
        }
        Ok(())
    }

    /// Records the display pass into `f`: `a` everywhere, or with `b` the columns from `split`
    /// on from `b`.
    pub fn record(&self, f: &mut Frame, a: &ImageView, b: Option<(&ImageView, u32)>, exposure: f32) -> Result<()> {
        let (w, h) = self.size();
        let (b_view, split) = b.unwrap_or((a, u32::MAX));
        let binds = [
            ("render_a", Bind::Sampled(a, &self.nearest)),
            ("render_b", Bind::Sampled(b_view, &self.nearest)),
            ("display", Bind::Storage(&self.target.view)),
        ];
        let constants = DisplayConstants { exposure, split };
        f.pass(DISPLAY_PASS).bind(&self.pipeline, binds).record(|cmd| {
            cmd.push(&constants)?;
            cmd.dispatch(w.div_ceil(8), h.div_ceil(8), 1);
            Ok(())
        })?;
        Ok(())
    }

    /// The display image as 8-bit RGB, row 0 at the top (a screenshot of the window without
    /// its panel). Call when the frame that wrote it has finished.
    pub fn read_rgb8(&self, ctx: &Context) -> Result<(u32, u32, Vec<u8>)> {
        let (w, h) = self.size();
        let rgba = ctx.read_image(&self.target.image, 0, 0)?;
        anyhow::ensure!(rgba.len() == (w * h * 4) as usize, "the display image read back {} bytes", rgba.len());
        Ok((w, h, rgba.chunks_exact(4).flat_map(|p| [p[0], p[1], p[2]]).collect()))
    }
}
