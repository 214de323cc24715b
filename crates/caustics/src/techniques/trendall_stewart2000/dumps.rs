//! The pool's dumps (`--dump`, docs/dumps.md): each pass's function on the n x n grid, decoded
//! to its physical values (the faithful path's 8-bit values also as stored, layer `adjusted`),
//! and the receiver map. Row j of every image is z_j (row 0 at z = -side/2).

use super::adjusted::{Adjustments, Encoding};
use super::cpu::CpuPasses;
use super::settings::{
    CONVOLUTIONS, HEIGHT_FIELD, PASS1_NORMALS, PASS2_GAMMA_N, PASS3_TRANSMITTED, PASS4_DIRECTION, PASS5_INTEGRAND,
    PASS6_CONVOLUTIONS, XYZ,
};
use super::targets::PoolTargets;
use crate::dump::Dump;
use crate::gpu::Target;
use crate::image_io::{ImageF32, Layer};
use anyhow::{Context as _, Result};
use vkcore::{Context, Format};

const U: Encoding = Encoding::UNADJUSTED;

/// The channels each dump of a pass target holds, and the encodings of the faithful path.
fn layout(d: &'static Dump, adj: &Adjustments) -> Option<(&'static [&'static str], [Encoding; 4])> {
    Some(match d {
        d if d == &HEIGHT_FIELD => (&["h"], [adj.height, U, U, U]),
        d if d == &PASS1_NORMALS => (XYZ, [adj.normal[0], adj.normal[1], adj.normal[2], U]),
        d if d == &PASS2_GAMMA_N => (XYZ, [adj.gamma_n[0], adj.gamma_n[1], adj.gamma_n[2], U]),
        d if d == &PASS3_TRANSMITTED => (&["value"], [U; 4]),
        d if d == &PASS4_DIRECTION || d == &PASS5_INTEGRAND => {
            (XYZ, [adj.direction[0], adj.direction[1], adj.direction[2], U])
        }
        d if d == &PASS6_CONVOLUTIONS => (CONVOLUTIONS, adj.convolution),
        _ => return None,
    })
}

fn target<'a>(t: &'a PoolTargets, d: &'static Dump) -> Option<&'a Target> {
    Some(match d {
        d if d == &HEIGHT_FIELD => &t.height,
        d if d == &PASS1_NORMALS => &t.normals,
        d if d == &PASS2_GAMMA_N => &t.gamma_n,
        d if d == &PASS3_TRANSMITTED => &t.transmitted,
        d if d == &PASS4_DIRECTION => &t.direction,
        d if d == &PASS5_INTEGRAND => &t.integrand,
        d if d == &PASS6_CONVOLUTIONS => &t.convolutions,
        _ => return None,
    })
}

/// A target's texels as stored: RGBA in [0, 1] for 8-bit UNORM, floats otherwise.
pub(super) fn read(ctx: &Context, t: &Target) -> Result<Vec<[f32; 4]>> {
    if t.image.desc.format == Format::R8G8B8A8_UNORM {
        let bytes = ctx.read_image(&t.image, 0, 0)?;
        Ok(bytes.chunks_exact(4).map(|c| [0, 1, 2, 3].map(|k| c[k] as f32 / 255.0)).collect())
    } else {
        Ok(ctx.read_image_f32(&t.image, 0, 0)?.chunks_exact(4).map(|c| [c[0], c[1], c[2], c[3]]).collect())
    }
}

fn layer(name: Option<&str>, channels: &[&str], texels: &[[f32; 4]]) -> Layer {
    let data = texels.iter().flat_map(|t| t[..channels.len()].to_vec()).collect();
    Layer::new(name, channels, data)
}

fn image(n: usize, layers: Vec<Layer>) -> ImageF32 {
    ImageF32 { width: n as u32, height: n as u32, layers }
}

/// A pass target's dump from the GPU: decoded values, and on the faithful path the stored ones.
pub(super) fn gpu_pass(
    ctx: &Context,
    t: &PoolTargets,
    adj: &Adjustments,
    d: &'static Dump,
    n: usize,
) -> Result<Option<ImageF32>> {
    let (Some((channels, enc)), Some(target)) = (layout(d, adj), target(t, d)) else {
        return Ok(None);
    };
    let stored = read(ctx, target).with_context(|| format!("reading back {d}"))?;
    if target.image.desc.format != Format::R8G8B8A8_UNORM {
        let mut layers = vec![layer(None, channels, &stored)];
        if d == &PASS6_CONVOLUTIONS {
            layers.push(layer(Some("flat"), CONVOLUTIONS, &read(ctx, &t.flat)?));
        }
        return Ok(Some(image(n, layers)));
    }
    let decoded: Vec<[f32; 4]> =
        stored.iter().map(|s| [0, 1, 2, 3].map(|k| (enc[k].lo + enc[k].span * s[k] as f64) as f32)).collect();
    let mut layers = vec![layer(None, channels, &decoded), layer(Some("adjusted"), channels, &stored)];
    if d == &PASS6_CONVOLUTIONS {
        let flat = read(ctx, &t.flat)?;
        let flat: Vec<[f32; 4]> =
            flat.iter().map(|s| [0, 1, 2, 3].map(|k| (enc[k].lo + enc[k].span * s[k] as f64) as f32)).collect();
        layers.push(layer(Some("flat"), CONVOLUTIONS, &flat));
    }
    Ok(Some(image(n, layers)))
}

/// A pass's dump from the CPU path.
pub(super) fn cpu_pass(c: &CpuPasses, flat: &CpuPasses, d: &'static Dump) -> Option<ImageF32> {
    let v3 =
        |v: &[glam::DVec3]| -> Vec<[f32; 4]> { v.iter().map(|d| [d.x as f32, d.y as f32, d.z as f32, 0.0]).collect() };
    let s1 = |v: &[f64]| -> Vec<[f32; 4]> { v.iter().map(|&x| [x as f32, 0.0, 0.0, 0.0]).collect() };
    let c4 = |v: &[[f64; 4]]| -> Vec<[f32; 4]> { v.iter().map(|e| e.map(|x| x as f32)).collect() };
    let layers = match d {
        d if d == &HEIGHT_FIELD => vec![layer(None, &["h"], &s1(&c.height))],
        d if d == &PASS1_NORMALS => vec![layer(None, XYZ, &v3(&c.normals))],
        d if d == &PASS2_GAMMA_N => vec![layer(None, XYZ, &v3(&c.gamma_n))],
        d if d == &PASS3_TRANSMITTED => vec![layer(None, &["value"], &s1(&c.transmitted))],
        d if d == &PASS4_DIRECTION => vec![layer(None, XYZ, &v3(&c.direction))],
        d if d == &PASS5_INTEGRAND => vec![layer(None, XYZ, &v3(&c.integrand))],
        d if d == &PASS6_CONVOLUTIONS => vec![
            layer(None, CONVOLUTIONS, &c4(&c.convolutions)),
            layer(Some("flat"), CONVOLUTIONS, &c4(&flat.convolutions)),
        ],
        _ => return None,
    };
    Some(image(c.n, layers))
}

/// The receiver map from E and E_flat per texel: main layer R, G, B = E / E_flat (0 where
/// E_flat is 0) and E0 = E_flat; layer `irradiance`: R, G, B = E.
pub fn receiver_image(n: usize, e: &[f64], e_flat: &[f64]) -> ImageF32 {
    let ratio = super::relative(e, e_flat);
    let main: Vec<[f32; 4]> =
        ratio.iter().zip(e_flat).map(|(&r, &f)| [r as f32, r as f32, r as f32, f as f32]).collect();
    let irr: Vec<[f32; 4]> = e.iter().map(|&x| [x as f32; 4]).collect();
    image(n, vec![layer(None, &["R", "G", "B", "E0"], &main), layer(Some("irradiance"), &["R", "G", "B"], &irr)])
}

/// The receiver map the GPU's `pool.receiver` pass wrote (E / E_flat, E, E_flat per texel).
pub(super) fn gpu_receiver(ctx: &Context, t: &PoolTargets, n: usize) -> Result<ImageF32> {
    let texels = read(ctx, &t.receiver)?;
    let e: Vec<f64> = texels.iter().map(|x| x[1] as f64).collect();
    let flat: Vec<f64> = texels.iter().map(|x| x[2] as f64).collect();
    let mut img = receiver_image(n, &e, &flat);
    // The ratio as the GPU computed it, not recomputed here.
    if let Some(main) = img.layers.iter_mut().find(|l| l.name.is_none()) {
        for (i, x) in texels.iter().enumerate() {
            main.data[i * 4..i * 4 + 3].fill(x[0]);
        }
    }
    Ok(img)
}
