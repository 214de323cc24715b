//! Reads intermediate buffers back as named EXR layers (`--dump`).

use super::targets::{EyeTargets, Target};
use crate::gpu::target::read_image_layer;
use crate::image_io::{ImageF32, Layer};
use crate::techniques::wyman_nichols2009::DeferredRefraction;
use crate::techniques::{CausticTargets, PhotonTargets};
use anyhow::Result;
use vkcore::Context;

const FACES: [&str; 6] = ["px", "nx", "py", "ny", "pz", "nz"];

/// The final linear radiance.
pub fn final_image(ctx: &Context, t: &EyeTargets) -> Result<ImageF32> {
    Ok(t.final_image.as_image(vec![t.final_image.read_layer(ctx, 0, None, &["R", "G", "B"], &[0, 1, 2])?]))
}

/// Every array layer of `t` as layers `light<l>` with the given channels.
fn per_light(ctx: &Context, t: &Target, names: &[&str], pick: &[usize]) -> Result<ImageF32> {
    let layers = (0..t.image.desc.array_layers)
        .map(|l| t.read_layer(ctx, l, Some(&format!("light{l}")), names, pick))
        .collect::<Result<Vec<_>>>()?;
    Ok(t.as_image(layers))
}

/// The named intermediate buffer; None if this render has no such buffer (no receiver map, or
/// no caustic technique).
pub fn dump(
    ctx: &Context,
    t: &EyeTargets,
    ct: &CausticTargets,
    photons: Option<&PhotonTargets>,
    name: &str,
) -> Result<Option<ImageF32>> {
    let rgb = ["R", "G", "B"];
    Ok(Some(match name {
        "shadow_map" => {
            let mut layers = vec![];
            for l in 0..t.shadow.lights {
                for (f, face) in FACES.iter().enumerate() {
                    let n = format!("light{l}_{face}");
                    layers.push(t.shadow.distance.read_layer(ctx, 6 * l + f as u32, Some(&n), &["distance"], &[0])?);
                }
            }
            t.shadow.distance.as_image(layers)
        }
        "background" => t.background.as_image(vec![t.background.read_layer(ctx, 0, None, &rgb, &[0, 1, 2])?]),
        "eye_gbuffer" => t.position.as_image(vec![
            t.position.read_layer(ctx, 0, Some("position"), &["X", "Y", "Z", "hit"], &[0, 1, 2, 3])?,
            t.normal.read_layer(ctx, 0, Some("normal"), &["X", "Y", "Z"], &[0, 1, 2])?,
        ]),
        "refractor_back_faces" => t.back_faces.as_image(vec![t.back_faces.read_layer(
            ctx,
            0,
            None,
            &["NX", "NY", "NZ", "distance"],
            &[0, 1, 2, 3],
        )?]),
        "refractor_front_faces" => {
            t.surface.as_image(vec![t.surface.read_layer(ctx, 0, None, &["R", "G", "B", "A"], &[0, 1, 2, 3])?])
        }
        "receiver" => match &t.receiver {
            None => return Ok(None),
            Some((ratio, irradiance, caustic)) => {
                // Main layer: E/E0 per channel and mean E0 (W/m^2); layer `irradiance`: E (W/m^2);
                // layer `caustic`: the caustic part of E (W/m^2).
                let r = ctx.read_image_f32(&ratio.image, 0, 0)?;
                let e = ctx.read_image_f32(&irradiance.image, 0, 0)?;
                let main = r.chunks(4).zip(e.chunks(4)).flat_map(|(a, b)| [a[0], a[1], a[2], b[3]]).collect();
                ratio.as_image(vec![
                    Layer::new(None, &["R", "G", "B", "E0"], main),
                    irradiance.read_layer(ctx, 0, Some("irradiance"), &rgb, &[0, 1, 2])?,
                    caustic.read_layer(ctx, 0, Some("caustic"), &rgb, &[0, 1, 2])?,
                ])
            }
        },
        // Light-space buffers of the caustic techniques.
        "receiver_positions" | "caustic_map" if photons.is_none() => return Ok(None),
        "receiver_positions" => per_light(ctx, &ct.receiver_positions, &["X", "Y", "Z", "hit"], &[0, 1, 2, 3])?,
        "caustic_map" if ct.levels > 1 => {
            // The multi-resolution map: level i of light l in layer 4l + i, its splats in the
            // layer's corner of (M / 2^i)^2 texels (Wyman 2008 Sec. 3.3); interpolated splats:
            // radius splat_radius 2^i in layer 4l + i, full resolution (Fig. 7).
            let t = &ct.caustic_map;
            let layers = (0..t.image.desc.array_layers)
                .map(|i| {
                    let name = format!("light{}_level{}", i / ct.levels, i % ct.levels);
                    t.read_layer(ctx, i, Some(&name), &["R", "G", "B", "photons"], &[0, 1, 2, 3])
                })
                .collect::<Result<Vec<_>>>()?;
            t.as_image(layers)
        }
        "caustic_map" => per_light(ctx, &ct.caustic_map, &["R", "G", "B", "photons"], &[0, 1, 2, 3])?,
        other => anyhow::bail!("no intermediate buffer called `{other}`"),
    }))
}

/// The deferred refraction's buffers (Wyman & Nichols 2009 Sec. 3.1), refractor k (0: the
/// farthest) in layers `layer<k>.*`: `refractor_geometry`, its front and back faces (normal and
/// distance, window depth and thickness); `refraction_layers`, the image after its pass.
pub fn deferred(ctx: &Context, d: &DeferredRefraction, t: &EyeTargets, name: &str) -> Result<ImageF32> {
    let mut layers = vec![];
    for k in 0..d.layers.len() as u32 {
        match name {
            "refractor_geometry" => {
                for (face, l) in [("front", 2 * k), ("back", 2 * k + 1)] {
                    let (surface, depth) = (format!("layer{k}.{face}"), format!("layer{k}.{face}_depth"));
                    layers.push(read_image_layer(
                        ctx,
                        &d.surfaces,
                        l,
                        Some(&surface),
                        &["NX", "NY", "NZ", "distance"],
                        &[0, 1, 2, 3],
                    )?);
                    layers.push(read_image_layer(ctx, &d.depths, l, Some(&depth), &["depth", "thickness"], &[0, 1])?);
                }
            }
            "refraction_layers" => {
                let n = Some(format!("layer{k}"));
                layers.push(match &d.results {
                    Some(r) if k + 1 < d.layers.len() as u32 => {
                        read_image_layer(ctx, r, k, n.as_deref(), &["R", "G", "B"], &[0, 1, 2])?
                    }
                    _ => t.final_image.read_layer(ctx, 0, n.as_deref(), &["R", "G", "B"], &[0, 1, 2])?,
                });
            }
            other => anyhow::bail!("no deferred refraction buffer called `{other}`"),
        }
    }
    Ok(t.final_image.as_image(layers))
}
