//! An image with its full view: what every render target and intermediate buffer is.

use super::formats::{COLOR, DEPTH};
use anyhow::Result;
use vkcore::{Context, Image, ImageDesc, ImageView, ViewKind};

/// An image with its full view.
pub struct Target {
    pub image: Image,
    pub view: ImageView,
}

impl Target {
    pub fn new(ctx: &Context, desc: ImageDesc) -> Result<Target> {
        let image = Image::new(ctx, desc)?;
        let view = image.full_view()?;
        Ok(Target { image, view })
    }
    /// A 2D-array view even for one layer (for `sampler2DArray` bindings).
    pub fn array(ctx: &Context, desc: ImageDesc) -> Result<Target> {
        let image = Image::new(ctx, desc)?;
        let view = image.view(ViewKind::D2Array, 0..1, 0..image.desc.array_layers)?;
        Ok(Target { image, view })
    }
    pub fn color(ctx: &Context, name: &str, w: u32, h: u32) -> Result<Target> {
        Target::new(ctx, ImageDesc::new_2d(name, COLOR, w, h))
    }
    pub fn depth(ctx: &Context, name: &str, w: u32, h: u32) -> Result<Target> {
        Target::new(ctx, ImageDesc::new_2d(name, DEPTH, w, h))
    }
}

impl Target {
    /// A dump image of this target's size holding `layers` (read from it or its like).
    pub fn as_image(&self, layers: Vec<crate::image_io::Layer>) -> crate::image_io::ImageF32 {
        crate::image_io::ImageF32 { width: self.view.extent.0, height: self.view.extent.1, layers }
    }

    /// Mip 0 of array layer `layer_index` as a dump layer: the channels at `pick` of each
    /// texel (of any float format), under `names`.
    pub fn read_layer(
        &self,
        ctx: &Context,
        layer_index: u32,
        name: Option<&str>,
        names: &[&str],
        pick: &[usize],
    ) -> Result<crate::image_io::Layer> {
        read_image_layer(ctx, &self.image, layer_index, name, names, pick)
    }
}

/// [`Target::read_layer`] of any image.
pub fn read_image_layer(
    ctx: &Context,
    image: &Image,
    layer_index: u32,
    name: Option<&str>,
    names: &[&str],
    pick: &[usize],
) -> Result<crate::image_io::Layer> {
    let texels = ctx.read_image_f32(image, 0, layer_index)?;
    let stride = texels.len() / (image.desc.width * image.desc.height) as usize;
    let data = texels.chunks(stride).flat_map(|px| pick.iter().map(move |&c| px[c])).collect();
    Ok(crate::image_io::Layer::new(name, names, data))
}
