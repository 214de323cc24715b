//! The receiver rectangle: texel binning, direct irradiance (with shadows) and the output
//! image.

// NaN-rejecting comparisons are written as negated comparisons on purpose.
#![allow(clippy::neg_cmp_op_on_partial_ord)]

use crate::bvh::Bvh;
use crate::image_io::{ImageF32, Layer};
use crate::scene::spot_projector::SpotProjector;
use crate::scene::{Light, ReceiverMapSpec};
use glam::DVec3;

/// The horizontal receiver rectangle `y = plane_y`, `x ∈ x_range`, `z ∈ z_range`, split
/// into `n × n` texels; texel `(i, j)` (column, row) is centred at
/// `(x0 + (i + ½)(x1 − x0)/n, plane_y, z0 + (j + ½)(z1 − z0)/n)`, row 0 at `z0`.
#[derive(Clone, Copy, Debug)]
pub struct Receiver {
    pub plane_y: f64,
    pub x: [f64; 2],
    pub z: [f64; 2],
    pub n: usize,
    /// A hit counts as on the plane when `|y − plane_y| < tolerance`.
    pub tolerance: f64,
}

impl Receiver {
    pub fn new(spec: &ReceiverMapSpec, tolerance: f64) -> Receiver {
        Receiver {
            plane_y: spec.plane_y as f64,
            x: spec.x_range.map(|v| v as f64),
            z: spec.z_range.map(|v| v as f64),
            n: spec.resolution as usize,
            tolerance,
        }
    }

    /// Area of one texel, `(x1 − x0)(z1 − z0)/n²`.
    pub fn texel_area(&self) -> f64 {
        (self.x[1] - self.x[0]) * (self.z[1] - self.z[0]) / (self.n * self.n) as f64
    }

    pub fn texel_centre(&self, i: usize, j: usize) -> DVec3 {
        let n = self.n as f64;
        DVec3::new(
            self.x[0] + (i as f64 + 0.5) * (self.x[1] - self.x[0]) / n,
            self.plane_y,
            self.z[0] + (j as f64 + 0.5) * (self.z[1] - self.z[0]) / n,
        )
    }

    /// Row-major texel index (`j * n + i`) of a point, if it lies on the plane and inside
    /// the rectangle.
    #[inline]
    pub fn texel_of(&self, p: DVec3) -> Option<usize> {
        if !((p.y - self.plane_y).abs() < self.tolerance) {
            return None;
        }
        let fx = (p.x - self.x[0]) / (self.x[1] - self.x[0]);
        let fz = (p.z - self.z[0]) / (self.z[1] - self.z[0]);
        if !((0.0..1.0).contains(&fx) && (0.0..1.0).contains(&fz)) {
            return None;
        }
        let n = self.n;
        let i = ((fx * n as f64) as usize).min(n - 1);
        let j = ((fz * n as f64) as usize).min(n - 1);
        Some(j * n + i)
    }
}

/// What a light emits towards a unit direction, per RGB channel, as a factor on its intensity:
/// 1 for a point light; for a spot light 0 outside its cone and its projected texture's colour
/// inside it (white without a texture), sampled as the renderer samples it
/// ([`SpotProjector`]): the texture shapes the direct light and the photons alike.
pub struct Emitter(Option<SpotProjector>);

impl Emitter {
    pub fn of(light: &Light) -> anyhow::Result<Emitter> {
        Ok(Emitter(SpotProjector::of(light)?))
    }

    #[inline]
    pub fn emission(&self, dir: DVec3) -> [f64; 3] {
        match &self.0 {
            None => [1.0; 3],
            Some(spot) => spot.emission(dir),
        }
    }
}

/// Unshadowed irradiance `E0` and direct irradiance (with visibility) per texel and RGB
/// channel, `n*n*3` each, in W/m²: `Σ_lights I · max(cos θ, 0) / r²` with the receiver
/// normal `+y`, visibility 1 when no triangle of `bvh` blocks the segment texel centre →
/// light.
pub fn direct_irradiance(rx: &Receiver, lights: &[Light], emitters: &[&Emitter], bvh: &Bvh) -> (Vec<f64>, Vec<f64>) {
    let n = rx.n;
    let mut e0 = vec![0.0; n * n * 3];
    let mut ed = vec![0.0; n * n * 3];
    for j in 0..n {
        for i in 0..n {
            let p = rx.texel_centre(i, j);
            let k = (j * n + i) * 3;
            for (light, emitter) in lights.iter().zip(emitters) {
                let to = light.position.as_dvec3() - p;
                let r2 = to.length_squared();
                if r2 <= 0.0 {
                    continue;
                }
                let r = r2.sqrt();
                let cos = to.y / r;
                if cos <= 0.0 {
                    continue;
                }
                let f = emitter.emission(-to / r);
                if f == [0.0; 3] {
                    continue;
                }
                let g = cos / r2;
                let visible = !bvh.occluded(p.as_vec3(), to.as_vec3(), 1e-4, 1.0 - 1e-4);
                let intensity = light.intensity.as_dvec3().to_array();
                for c in 0..3 {
                    let e = intensity[c] * f[c] * g;
                    e0[k + c] += e;
                    if visible {
                        ed[k + c] += e;
                    }
                }
            }
        }
    }
    (e0, ed)
}

/// Builds `receiver.exr`: main layer `R,G,B,E0` (relative irradiance and mean-RGB `E0`),
/// layer `irradiance` (`R,G,B`, W/m²) and layer `caustic` (`R,G,B`, W/m²).
pub fn build_image(n: usize, e0: &[f64], direct: &[f64], caustic: &[f64]) -> ImageF32 {
    let mut main = Vec::with_capacity(n * n * 4);
    let mut irr = Vec::with_capacity(n * n * 3);
    let mut cau = Vec::with_capacity(n * n * 3);
    for t in 0..n * n {
        for c in 0..3 {
            let k = t * 3 + c;
            let e = direct[k] + caustic[k];
            main.push(if e0[k] > 0.0 { (e / e0[k]) as f32 } else { 0.0 });
            irr.push(e as f32);
            cau.push(caustic[k] as f32);
        }
        main.push(((e0[t * 3] + e0[t * 3 + 1] + e0[t * 3 + 2]) / 3.0) as f32);
    }
    ImageF32 {
        width: n as u32,
        height: n as u32,
        layers: vec![
            Layer::new(None, &["R", "G", "B", "E0"], main),
            Layer::new(Some("irradiance"), &["R", "G", "B"], irr),
            Layer::new(Some("caustic"), &["R", "G", "B"], cau),
        ],
    }
}
