//! Progressive accumulation (`progressive = true`): every frame traces new photons (a new seed)
//! and the caustic map the eye and the receiver map read is the mean of every frame's since the
//! last change of the lights or the objects, each frame's splatted with a smaller radius.
//!
//! This is Knaus & Zwicker's probabilistic progressive photon mapping (2011, "Progressive photon
//! mapping: a probabilistic approach", ACM TOG 30(3)), the form of Hachisuka & Jensen's
//! progressive photon mapping (2008, 2009) whose frames are independent: frame i is a whole
//! photon map of its own photons with its own radius r_i, and the estimate after N frames is the
//! plain mean of the N frames' estimates, c_N = (1/N) sum_i c_i (their Eq. 8). The radius follows
//! their global rule (Eq. 15), r_{i+1}^2 = r_i^2 (i + alpha) / (i + 1), r_1 the splat radius:
//! the variance of a 2D density estimate grows as 1/r_i^2, so it is allowed to grow slowly
//! (alpha < 1) while the bias, which shrinks with r_i^2, vanishes; on surfaces the mean squared
//! error then falls as N^-2/3 with alpha = 2/3 (their Sec. 4.3), the default here.
//!
//! What accumulates: each light's caustic-map layers, and with `deposit = "receiver-map"` the
//! photons binned into the receiver map (no radius: the mean of independent binnings). The
//! caustic map is light space and the receiver map is the receiver's, so a moving camera keeps
//! the accumulation; a pose that changes a light or moves an object starts it again
//! ([`Accumulation::restart`]). The splat kernel gives a photon's whole power to its nearest
//! texel once the radius misses every texel centre (`shared/splat_kernel.glsl`): from there on
//! the frames are binned on the caustic map's grid, whose resolution bounds the error.

use super::push::AccumulateConstants;
use crate::gpu::formats::COLOR;
use crate::gpu::{Stage, Target};
use anyhow::Result;
use vkcore::{Bind, Buffer, Context, Frame, ImageDesc, Memory, Pipeline, ShaderCompiler};

pub use super::settings::DEFAULT_ALPHA;

/// r_i / r_1 after the global rule r_{k+1}^2 = r_k^2 (k + alpha) / (k + 1), for frame `i` (1
/// for the first frame since the last restart), from the product (`Accumulation` keeps it
/// running).
pub fn radius_scale(i: u32, alpha: f32) -> f32 {
    let alpha = f64::from(alpha);
    let squared: f64 = (1..i.max(1)).map(|k| (f64::from(k) + alpha) / (f64::from(k) + 1.0)).product();
    squared.sqrt() as f32
}

/// The tracer's seed for frame `i` since the last restart: the setting's own for the first
/// frame (so one progressive frame is the plain tracer's), then a new one per frame.
pub fn frame_seed(seed: u32, i: u32) -> u32 {
    seed.wrapping_add(i.saturating_sub(1).wrapping_mul(0x9E37_79B9))
}

/// The running means and the pass that updates them.
pub struct Accumulation {
    alpha: f32,
    /// The first frame's splat radius (`splat_radius`, caustic-map texels).
    radius: f32,
    /// Frames in the means (the one being recorded included), 0 before the first.
    frames: u32,
    /// r_i^2 / r_1^2 of the frame being recorded (the rule kept running, not recomputed).
    squared: f64,
    /// The caustic map's mean, every light's layers.
    mean_map: Target,
    /// The receiver-map binning's mean (`deposit = "receiver-map"`), else none.
    mean_flux: Option<Buffer>,
    map_pipeline: Pipeline,
    flux_pipeline: Option<Pipeline>,
}

impl Accumulation {
    /// Means for a caustic map of `side`² texels and `layers` layers and, with `flux_bytes`,
    /// the receiver-map binning's buffer of that size.
    pub fn new(
        ctx: &Context,
        sh: &ShaderCompiler,
        side: u32,
        layers: u32,
        flux_bytes: Option<u64>,
        alpha: f32,
        radius: f32,
    ) -> Result<Accumulation> {
        let desc = ImageDesc::new_2d("photon_trace mean caustic map", COLOR, side, side).layers(layers);
        let mean_flux = match flux_bytes {
            Some(bytes) => Some(Buffer::new(ctx, "photon_trace mean receiver flux", bytes, Memory::Gpu)?),
            None => None,
        };
        let flux_pipeline = match flux_bytes {
            Some(_) => Some(Pipeline::compute(
                ctx,
                "photon_trace accumulate flux",
                &sh.compile("photon_trace/accumulate.comp", &[("FLUX", "1")])?,
            )?),
            None => None,
        };
        Ok(Accumulation {
            alpha,
            radius,
            frames: 0,
            squared: 1.0,
            mean_map: Target::array(ctx, desc)?,
            mean_flux,
            map_pipeline: Pipeline::compute(
                ctx,
                "photon_trace accumulate",
                &sh.compile("photon_trace/accumulate.comp", &[])?,
            )?,
            flux_pipeline,
        })
    }

    /// The next frame: one more in the means. Returns its splat radius.
    pub fn next_frame(&mut self) -> f32 {
        self.frames = self.frames.saturating_add(1);
        self.squared = match self.frames {
            1 => 1.0,
            // r_i^2 = r_{i-1}^2 (i - 1 + alpha) / i.
            i => self.squared * (f64::from(i - 1) + f64::from(self.alpha)) / f64::from(i),
        };
        self.radius * self.squared.sqrt() as f32
    }

    /// Frames in the means, the one being recorded included.
    pub fn frames(&self) -> u32 {
        self.frames
    }

    /// Starts the means again: the next frame is the first.
    pub fn restart(&mut self) {
        self.frames = 0;
    }

    /// After every light's deposit: each mean takes the frame's share 1/i, and the frame's
    /// buffers (what the eye and the receiver map read) take the means.
    pub fn record(&self, f: &mut Frame, caustic_map: &Target, receiver_flux: &Buffer) -> Result<()> {
        let weight = 1.0 / self.frames.max(1) as f32;
        let (side, _) = caustic_map.view.extent;
        let layers = caustic_map.image.desc.array_layers;
        let binds =
            vec![("caustic_map", Bind::Storage(&caustic_map.view)), ("mean_map", Bind::Storage(&self.mean_map.view))];
        f.pass(&Stage::PhotonTraceAccumulate.pass()).bind(&self.map_pipeline, binds).record(|cmd| {
            cmd.push(&AccumulateConstants { weight, count: 0 })?;
            cmd.dispatch(side.div_ceil(8), side.div_ceil(8), layers);
            Ok(())
        })?;
        if let (Some(mean), Some(pipeline)) = (&self.mean_flux, &self.flux_pipeline) {
            let count = (receiver_flux.size() / 16) as u32;
            let binds = vec![("FrameFlux", Bind::Buffer(receiver_flux)), ("MeanFlux", Bind::Buffer(mean))];
            f.pass(&Stage::PhotonTraceAccumulate.pass().view("flux")).bind(pipeline, binds).record(|cmd| {
                cmd.push(&AccumulateConstants { weight, count })?;
                let (x, y) = vkcore::dispatch_grid(count.div_ceil(64));
                cmd.dispatch(x, y, 1);
                Ok(())
            })?;
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_radius_rule_at_its_ends() {
        // alpha = 1 keeps the radius; alpha = 0 gives r_i^2 = r_1^2 / i (the product telescopes).
        for i in 1..50 {
            assert!((radius_scale(i, 1.0) - 1.0).abs() < 1e-6);
            assert!((radius_scale(i, 0.0) - (1.0 / i as f32).sqrt()).abs() < 1e-6, "{i}");
        }
        // alpha = 1/2: r_2^2 / r_1^2 = 1.5 / 2, r_3^2 / r_1^2 = 0.75 * 2.5 / 3.
        assert!((radius_scale(2, 0.5) - 0.75f32.sqrt()).abs() < 1e-6);
        assert!((radius_scale(3, 0.5) - 0.625f32.sqrt()).abs() < 1e-6);
        assert_eq!(radius_scale(0, 0.5), 1.0);
    }

    #[test]
    fn the_running_rule_is_the_product() {
        let running = |alpha: f32| {
            let mut squared = 1.0f64;
            (1..=200u32)
                .map(|i| {
                    if i > 1 {
                        squared *= (f64::from(i - 1) + f64::from(alpha)) / f64::from(i);
                    }
                    (i, squared.sqrt() as f32)
                })
                .collect::<Vec<_>>()
        };
        for alpha in [DEFAULT_ALPHA, 0.25, 1.0] {
            for (i, r) in running(alpha) {
                assert!((r - radius_scale(i, alpha)).abs() < 1e-6, "alpha {alpha}, frame {i}");
            }
        }
    }

    #[test]
    fn the_first_frame_is_the_plain_tracers_and_the_next_ones_differ() {
        assert_eq!(frame_seed(7, 1), 7);
        assert_eq!(frame_seed(7, 0), 7);
        let seeds: std::collections::BTreeSet<u32> = (1..1000).map(|i| frame_seed(7, i)).collect();
        assert_eq!(seeds.len(), 999);
    }
}
