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
