//! The light-space dumps of a caustic pipeline: one set of light-space buffers serves every
//! light in turn, so a frame leaves only its last light's there. With several lights each
//! light's source and selection are recorded again alone (the same inputs, so the same
//! buffers) and read back; the layers of light l are named `light<l>.<layer>`.

use super::CausticPipeline;
use crate::dump::{Dump, Space};
use crate::image_io::ImageF32;
use crate::techniques::shared::{records_image, CausticTargets, FrameInputs, LightDump};
use anyhow::Result;
use vkcore::{Context, FrameOptions, ShaderCompiler};

/// A light-space dump put together light by light.
enum Collected {
    Image(ImageF32),
    Records(&'static [&'static str], Vec<(String, Vec<Vec<f32>>)>),
}

impl CausticPipeline {
    /// Whether this pipeline's stages have the light-space buffer `d`, one that every light
    /// uses in turn ([`Space::LightInTurn`]).
    pub fn has_light_space_dump(&self, d: &'static Dump) -> bool {
        d.space == Space::LightInTurn && self.source.has_dump(d) && self.selection.has_dump(d)
    }

    /// Makes what reading the light-space dumps `wanted` needs beyond the frame's passes.
    pub fn prepare_dumps(&mut self, ctx: &Context, sh: &ShaderCompiler, wanted: &[&'static Dump]) -> Result<()> {
        self.selection.prepare_dumps(ctx, sh, wanted)
    }

    /// The light-space dumps `wanted` (each one this pipeline has: see
    /// [`Self::has_light_space_dump`]) of `lights` lights, as (name, image), after a frame
    /// with these inputs.
    pub fn light_space_dumps(
        &self,
        ctx: &Context,
        inputs: &FrameInputs,
        targets: &CausticTargets,
        lights: u32,
        wanted: &[&'static Dump],
    ) -> Result<Vec<(&'static Dump, ImageF32)>> {
        if wanted.is_empty() {
            return Ok(vec![]);
        }
        let mut collected: Vec<Option<Collected>> = wanted.iter().map(|_| None).collect();
        for l in 0..lights {
            if lights > 1 {
                let mut f = ctx.frame(FrameOptions::default())?;
                self.record_light_space(&mut f, inputs, targets, l)?;
                f.submit()?;
            }
            let c = self.passes(inputs, targets);
            for (i, d) in wanted.iter().enumerate() {
                let part = match self.source.dump(ctx, d)? {
                    Some(img) => LightDump::Image(img),
                    None => match self.selection.dump(ctx, &c, d, l)? {
                        Some(part) => part,
                        None => LightDump::Image(self.photons.dump(ctx, d)?),
                    },
                };
                collected[i] = Some(add_light(collected[i].take(), part, l)?);
            }
        }
        let mut out = vec![];
        for (d, got) in wanted.iter().zip(collected) {
            let img = match got {
                Some(Collected::Image(img)) => img,
                Some(Collected::Records(channels, lists)) => records_image(lists, channels),
                None => continue,
            };
            out.push((*d, img));
        }
        Ok(out)
    }

    /// The dump `d` of the eye's view that the deposit owns (`eye_caustic`), None where it has
    /// none.
    pub fn dump(&self, ctx: &Context, d: &'static Dump) -> Result<Option<ImageF32>> {
        self.deposit.dump(ctx, d)
    }
}

/// `got` with light `l`'s part added: an image's layers renamed `light<l>` (the unnamed one)
/// and `light<l>.<name>`, beside the other lights' (the same size: one buffer of several
/// lights); lists of records named so too.
fn add_light(got: Option<Collected>, part: LightDump, l: u32) -> Result<Collected> {
    let named = |n: Option<String>| match n {
        None => format!("light{l}"),
        Some(n) => format!("light{l}.{n}"),
    };
    Ok(match (got, part) {
        (None, LightDump::Image(mut img)) => {
            img.layers.iter_mut().for_each(|layer| layer.name = Some(named(layer.name.take())));
            Collected::Image(img)
        }
        (Some(Collected::Image(mut a)), LightDump::Image(mut b)) => {
            anyhow::ensure!(
                (a.width, a.height) == (b.width, b.height),
                "merging {}x{} and {}x{} dumps",
                a.width,
                a.height,
                b.width,
                b.height
            );
            b.layers.iter_mut().for_each(|layer| layer.name = Some(named(layer.name.take())));
            a.layers.extend(b.layers);
            Collected::Image(a)
        }
        (got, LightDump::Records { channels, lists }) => {
            let mut all = match got {
                Some(Collected::Records(_, all)) => all,
                None => vec![],
                Some(Collected::Image(_)) => anyhow::bail!("a dump read as an image and as records"),
            };
            all.extend(lists.into_iter().map(|(n, records)| (named((!n.is_empty()).then_some(n)), records)));
            Collected::Records(channels, all)
        }
        (Some(Collected::Records(..)), LightDump::Image(_)) => anyhow::bail!("a dump read as records and as an image"),
    })
}
