//! The pool's buffers on the GPU: one n x n target per pass (8-bit UNORM on the faithful path,
//! 32-bit float otherwise), the flat surface's convolutions (E_flat), L_s, the receiver map, the
//! final image, the Pass 6 kernels and the faithful path's lookup tables.

use super::adjusted;
use super::settings::Precision;
use super::Init;
use crate::gpu::Target;
use anyhow::Result;
use vkcore::{Buffer, Context, Format, ImageDesc};

/// The format the passes of `precision` store their functions in.
pub fn pass_format(precision: Precision) -> Format {
    match precision {
        Precision::Unorm8 => Format::R8G8B8A8_UNORM,
        Precision::Float | Precision::F64 => Format::R32G32B32A32_SFLOAT,
    }
}

/// The 8-bit path's lookup tables (Sec. 4.1): the normals' pixel texture and the colour tables.
pub struct LookupTables {
    pub pixel_texture: Target,
    pub colour_tables: Target,
}

pub struct PoolTargets {
    pub height: Target,
    pub normals: Target,
    pub gamma_n: Target,
    pub transmitted: Target,
    pub direction: Target,
    pub integrand: Target,
    /// Pass 6: E_x, E_y, E_z, E.
    pub convolutions: Target,
    /// Pass 6 for a flat surface (E_flat), computed once.
    pub flat: Target,
    /// L_s per texel (footnote 1).
    pub light_radiance: Target,
    /// E / E_flat, E, E_flat (float).
    pub receiver: Target,
    pub final_image: Target,
    /// (K_x, K_y, K_z, 0) per tap.
    pub kernels: Buffer,
    pub tables: Option<LookupTables>,
}

fn rgba8(values: &[f64], code: impl Fn(f64) -> u8) -> Vec<u8> {
    values.iter().flat_map(|&v| [code(v), 0, 0, 255]).collect()
}

impl PoolTargets {
    /// The targets of `init`, with a final image of `width` x `height`.
    pub fn new(ctx: &Context, init: &Init, width: u32, height: u32) -> Result<PoolTargets> {
        let (n, precision, adj, k) = (init.n as u32, init.precision, &init.adjustments, &init.kernels);
        let light_radiance = &init.light_radiance;
        let format = pass_format(precision);
        let grid = |name: &str| Target::new(ctx, ImageDesc::new_2d(name, format, n, n));
        let float =
            |name: &str, w: u32, h: u32| Target::new(ctx, ImageDesc::new_2d(name, pass_format(Precision::Float), w, h));
        let taps: Vec<[f32; 4]> = k.taps.iter().map(|t| [t[0] as f32, t[1] as f32, t[2] as f32, 0.0]).collect();
        let light = grid("pool light radiance")?;
        match precision {
            Precision::Unorm8 => ctx.upload_image(
                &light.image,
                0,
                0,
                &rgba8(light_radiance, |v| (v.clamp(0.0, 1.0) * 255.0).round() as u8),
            )?,
            _ => {
                let texels: Vec<[f32; 4]> = light_radiance.iter().map(|&v| [v as f32, 0.0, 0.0, 1.0]).collect();
                ctx.upload_image(&light.image, 0, 0, bytemuck::cast_slice(&texels))?
            }
        }
        let tables = if precision == Precision::Unorm8 {
            let rgba = Format::R8G8B8A8_UNORM;
            let pixel_texture = Target::new(ctx, ImageDesc::new_2d("pool pixel texture", rgba, 256, 256))?;
            ctx.upload_image(&pixel_texture.image, 0, 0, &adjusted::pixel_texture(adj))?;
            let colour = Target::new(ctx, ImageDesc::new_2d("pool colour tables", rgba, 256, 1))?;
            ctx.upload_image(&colour.image, 0, 0, &adjusted::colour_tables(&init.pool, adj))?;
            Some(LookupTables { pixel_texture, colour_tables: colour })
        } else {
            None
        };
        Ok(PoolTargets {
            height: grid("pool height field")?,
            normals: grid("pool pass 1 normals")?,
            gamma_n: grid("pool pass 2 gamma n")?,
            transmitted: grid("pool pass 3 transmitted")?,
            direction: grid("pool pass 4 direction")?,
            integrand: grid("pool pass 5 integrand")?,
            convolutions: grid("pool pass 6 convolutions")?,
            flat: grid("pool pass 6 flat")?,
            light_radiance: light,
            receiver: float("pool receiver", n, n)?,
            final_image: float("pool final image", width, height)?,
            kernels: ctx.buffer_with_data("pool kernels", bytemuck::cast_slice(&taps))?,
            tables,
        })
    }
}
