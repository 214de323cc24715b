//! Reads intermediate buffers back as named EXR layers (`--dump`).

use super::targets::{EyeTargets, Target};
use crate::image_io::{ImageF32, Layer};
use anyhow::Result;
use vkcore::Context;

const FACES: [&str; 6] = ["px", "nx", "py", "ny", "pz", "nz"];

/// RGBA32F texels of `t` (mip 0, `layer`), keeping the channels at `pick` under `names`.
fn layer(
    ctx: &Context,
    t: &Target,
    layer_index: u32,
    name: Option<&str>,
    names: &[&str],
    pick: &[usize],
) -> Result<Layer> {
    let texels = ctx.read_image_f32(&t.image, 0, layer_index)?;
    let stride = texels.len() / (t.view.extent.0 * t.view.extent.1) as usize;
    let data = texels.chunks(stride).flat_map(|px| pick.iter().map(move |&c| px[c])).collect();
    Ok(Layer::new(name, names, data))
}

fn image(t: &Target, layers: Vec<Layer>) -> ImageF32 {
    ImageF32 { width: t.view.extent.0, height: t.view.extent.1, layers }
}

/// The final linear radiance.
pub fn final_image(ctx: &Context, t: &EyeTargets) -> Result<ImageF32> {
    Ok(image(&t.final_image, vec![layer(ctx, &t.final_image, 0, None, &["R", "G", "B"], &[0, 1, 2])?]))
}

/// The named intermediate buffer; None if this scene has no such buffer (no receiver map).
pub fn dump(ctx: &Context, t: &EyeTargets, name: &str) -> Result<Option<ImageF32>> {
    let rgb = ["R", "G", "B"];
    Ok(Some(match name {
        "shadow_map" => {
            let mut layers = vec![];
            for l in 0..t.shadow.lights {
                for (f, face) in FACES.iter().enumerate() {
                    let n = format!("light{l}_{face}");
                    layers.push(layer(ctx, &t.shadow.distance, 6 * l + f as u32, Some(&n), &["distance"], &[0])?);
                }
            }
            image(&t.shadow.distance, layers)
        }
        "background" => image(&t.background, vec![layer(ctx, &t.background, 0, None, &rgb, &[0, 1, 2])?]),
        "eye_gbuffer" => image(
            &t.position,
            vec![
                layer(ctx, &t.position, 0, Some("position"), &["X", "Y", "Z", "hit"], &[0, 1, 2, 3])?,
                layer(ctx, &t.normal, 0, Some("normal"), &["X", "Y", "Z"], &[0, 1, 2])?,
            ],
        ),
        "refractor_back_faces" => image(
            &t.back_faces,
            vec![layer(ctx, &t.back_faces, 0, None, &["NX", "NY", "NZ", "distance"], &[0, 1, 2, 3])?],
        ),
        "refractor_front_faces" => {
            image(&t.surface, vec![layer(ctx, &t.surface, 0, None, &["R", "G", "B", "A"], &[0, 1, 2, 3])?])
        }
        "receiver" => match &t.receiver {
            None => return Ok(None),
            Some((ratio, irradiance)) => {
                // Main layer: E/E0 per channel and mean E0 (W/m^2); layer `irradiance`: E (W/m^2).
                let r = ctx.read_image_f32(&ratio.image, 0, 0)?;
                let e = ctx.read_image_f32(&irradiance.image, 0, 0)?;
                let main = r.chunks(4).zip(e.chunks(4)).flat_map(|(a, b)| [a[0], a[1], a[2], b[3]]).collect();
                image(
                    ratio,
                    vec![
                        Layer::new(None, &["R", "G", "B", "E0"], main),
                        layer(ctx, irradiance, 0, Some("irradiance"), &rgb, &[0, 1, 2])?,
                    ],
                )
            }
        },
        other => anyhow::bail!("no intermediate buffer called `{other}`"),
    }))
}
