//! Compares a technique's receiver image against the exact photon reference
//! ([`crate::reference`]).
//!
//! Both images are `receiver.exr`-style: a main layer with `R,G,B` relative irradiance
//! `E/E0` (optionally `E0`), optionally a `caustic` layer (`R,G,B`, W/m²). `b` is the
//! reference. Per texel the value is the mean of `R,G,B`. The region is the set of texels
//! where `|a − 1| > 0.05` or `|b − 1| > 0.05` (and `E0 > 0` in each image that has `E0`).
//! * `rel_rmse = sqrt(Σ(a − b)² / Σ b²)` over the region;
//! * `best_scale s = Σab / Σa²` and `rel_rmse_scaled` = the same with `s·a`;
//! * `peak_ratio = max a / max b` over the region, `peak_offset_texels` = distance between
//!   the argmax texels;
//! * `caustic_flux_ratio = Σ caustic_a / Σ caustic_b` (mean RGB of the `caustic` layers)
//!   when both have one, else `Σ max(v − 1, 0)·E0` over all texels.
//!
//! A texel that is not finite in either map (NaN or infinite: its mean RGB, `E0` or caustic
//! value) is counted in `non_finite_texels` and, where its mean RGB is, is in the region, so
//! the errors read NaN or infinite rather than leaving it out; [`Comparison::within`] fails it.
//!
//! [`Region::Lit`] compares every texel instead (where `E0 > 0`): the relative RMS error "between
//! the two caustics" of Trendall & Stewart 2000 Sec. 5.2, over the whole image.

pub mod final_image;
pub mod perceptual;
mod report;

pub use report::{report, report_files, Figures, Report};

use crate::error::InputError;
use crate::image_io::{read_exr, ImageF32, Layer};
use std::fmt;
use std::path::Path;

/// Texels whose relative irradiance differs from 1 by more than this are compared.
pub const REGION_THRESHOLD: f64 = 0.05;

/// Which texels the errors are over.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, clap::ValueEnum)]
pub enum Region {
    /// Where either map's E/E0 differs from 1 by more than 0.05 (`REGION_THRESHOLD`), and `E0 > 0`.
    #[default]
    Caustic,
    /// Every texel with `E0 > 0` in both maps (every texel where there is no `E0`).
    Lit,
}

#[derive(Clone, Debug, PartialEq)]
pub struct Comparison {
    pub region_texels: usize,
    pub rel_rmse: f64,
    pub rel_rmse_scaled: f64,
    pub best_scale: f64,
    pub peak_ratio: f64,
    pub peak_offset_texels: f64,
    pub caustic_flux_ratio: f64,
    /// Texels not finite in either map (see the module docs).
    pub non_finite_texels: usize,
}

impl Comparison {
    /// Every texel finite, the relative RMSE at most `rel_rmse` and the caustic flux ratio within
    /// `flux` of 1; false when any of them is NaN.
    pub fn within(&self, rel_rmse: f64, flux: f64) -> bool {
        self.non_finite_texels == 0 && self.rel_rmse <= rel_rmse && (self.caustic_flux_ratio - 1.0).abs() <= flux
    }
}

impl fmt::Display for Comparison {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let rows: [(&str, String); 8] = [
            ("region texels", self.region_texels.to_string()),
            ("relative RMSE", format!("{:.6}", self.rel_rmse)),
            ("relative RMSE (scaled)", format!("{:.6}", self.rel_rmse_scaled)),
            ("best scale", format!("{:.6}", self.best_scale)),
            ("peak ratio", format!("{:.6}", self.peak_ratio)),
            ("peak offset (texels)", format!("{:.3}", self.peak_offset_texels)),
            ("caustic flux ratio", format!("{:.6}", self.caustic_flux_ratio)),
            ("non-finite texels", self.non_finite_texels.to_string()),
        ];
        let w = rows.iter().map(|r| r.0.len()).max().unwrap_or(0);
        for (k, v) in rows {
            writeln!(f, "{k:<w$}  {v:>14}")?;
        }
        Ok(())
    }
}

/// Per-texel mean of `R,G,B` and the optional `E0` of the main layer.
struct Values {
    v: Vec<f64>,
    e0: Option<Vec<f64>>,
    caustic: Option<Vec<f64>>,
}

fn channel(layer: &Layer, name: &str) -> Option<usize> {
    layer.channels.iter().position(|c| c == name)
}

fn mean_rgb(layer: &Layer, texels: usize, what: &str, label: &str) -> anyhow::Result<Vec<f64>> {
    let mut idx = [0usize; 3];
    for (k, c) in ["R", "G", "B"].iter().enumerate() {
        idx[k] = channel(layer, c).ok_or_else(|| InputError::new(format!("{label}: {what} has no channel `{c}`")))?;
    }
    let nc = layer.channels.len();
    anyhow::ensure!(
        layer.data.len() == texels * nc,
        InputError::new(format!("{label}: {what} has the wrong number of values"))
    );
    Ok((0..texels).map(|t| idx.iter().map(|&c| layer.data[t * nc + c] as f64).sum::<f64>() / 3.0).collect())
}

fn values(img: &ImageF32, label: &str) -> anyhow::Result<Values> {
    let texels = img.width as usize * img.height as usize;
    let main = img.layer(None).ok_or_else(|| InputError::new(format!("{label}: no main layer (channels R, G, B)")))?;
    let v = mean_rgb(main, texels, "the main layer", label)?;
    let e0 = channel(main, "E0").map(|c| {
        let nc = main.channels.len();
        (0..texels).map(|t| main.data[t * nc + c] as f64).collect()
    });
    let caustic = match img.layer(Some("caustic")) {
        Some(l) => Some(mean_rgb(l, texels, "layer `caustic`", label)?),
        None => None,
    };
    Ok(Values { v, e0, caustic })
}

fn ratio(a: f64, b: f64) -> f64 {
    if b != 0.0 {
        a / b
    } else if a == 0.0 {
        1.0
    } else {
        f64::INFINITY
    }
}

/// Compares `a` against the reference `b`; see the module docs. Returns the metrics and an
/// error image (main layer `A`, `B`, `diff = a − b`, `in_region` ∈ {0, 1}).
pub fn compare(a: &ImageF32, b: &ImageF32) -> anyhow::Result<(Comparison, ImageF32)> {
    compare_labelled(a, "image A", b, "image B", Region::Caustic)
}

/// [`compare`] on two EXR files, naming the files in errors, over `region`.
pub fn compare_files(a: &Path, b: &Path, region: Region) -> anyhow::Result<(Comparison, ImageF32)> {
    let ia = read_exr(a)?;
    let ib = read_exr(b)?;
    compare_labelled(&ia, &a.display().to_string(), &ib, &b.display().to_string(), region)
}

fn same_size(a: &ImageF32, la: &str, b: &ImageF32, lb: &str) -> Result<(), InputError> {
    if (a.width, a.height) != (b.width, b.height) {
        return Err(InputError::new(format!(
            "size mismatch: {la} is {}x{} but {lb} is {}x{}",
            a.width, a.height, b.width, b.height
        )));
    }
    Ok(())
}

fn compare_labelled(
    a: &ImageF32,
    la: &str,
    b: &ImageF32,
    lb: &str,
    region_kind: Region,
) -> anyhow::Result<(Comparison, ImageF32)> {
    same_size(a, la, b, lb)?;
    let (w, h) = (a.width as usize, a.height as usize);
    let va = values(a, la)?;
    let vb = values(b, lb)?;
    let texels = w * h;

    let finite = |v: &Values, t: usize| {
        v.v[t].is_finite()
            && v.e0.as_ref().is_none_or(|e| e[t].is_finite())
            && v.caustic.as_ref().is_none_or(|c| c[t].is_finite())
    };
    let non_finite_texels = (0..texels).filter(|&t| !(finite(&va, t) && finite(&vb, t))).count();
    let in_region: Vec<bool> = (0..texels)
        .map(|t| {
            let (x, y) = (va.v[t], vb.v[t]);
            if !(x.is_finite() && y.is_finite()) {
                return true;
            }
            let lit = [&va.e0, &vb.e0].iter().all(|e| match e {
                Some(e) => e[t] > 0.0,
                None => true,
            });
            let differs = (x - 1.0).abs() > REGION_THRESHOLD || (y - 1.0).abs() > REGION_THRESHOLD;
            lit && (differs || region_kind == Region::Lit)
        })
        .collect();

    let (mut sab, mut saa, mut sbb, mut sdd) = (0.0, 0.0, 0.0, 0.0);
    let mut region = 0usize;
    let mut peak_a: Option<(f64, usize)> = None;
    let mut peak_b: Option<(f64, usize)> = None;
    for t in (0..texels).filter(|&t| in_region[t]) {
        let (x, y) = (va.v[t], vb.v[t]);
        region += 1;
        sab += x * y;
        saa += x * x;
        sbb += y * y;
        sdd += (x - y) * (x - y);
        // The peaks of the finite texels (a NaN would reset the running maximum).
        if x.is_finite() && !matches!(peak_a, Some(p) if x <= p.0) {
            peak_a = Some((x, t));
        }
        if y.is_finite() && !matches!(peak_b, Some(p) if y <= p.0) {
            peak_b = Some((y, t));
        }
    }
    let rel = |num: f64| -> f64 {
        if sbb > 0.0 {
            (num / sbb).sqrt()
        } else if num == 0.0 {
            0.0
        } else {
            f64::INFINITY
        }
    };
    let best_scale = if saa > 0.0 || saa.is_nan() { sab / saa } else { 1.0 };
    // Σ(s·a − b)² = s²Σa² − 2sΣab + Σb², evaluated directly for accuracy.
    let sdd_scaled: f64 = (0..texels).filter(|&t| in_region[t]).map(|t| (best_scale * va.v[t] - vb.v[t]).powi(2)).sum();
    let (peak_ratio, peak_offset_texels) = match (peak_a, peak_b) {
        (Some((ma, ta)), Some((mb, tb))) => {
            let (dx, dy) = ((ta % w) as f64 - (tb % w) as f64, (ta / w) as f64 - (tb / w) as f64);
            (ratio(ma, mb), (dx * dx + dy * dy).sqrt())
        }
        _ => (1.0, 0.0),
    };

    let caustic_flux_ratio = match (&va.caustic, &vb.caustic) {
        (Some(ca), Some(cb)) => ratio(ca.iter().sum(), cb.iter().sum()),
        _ => {
            let excess = |v: &Values, label: &str| -> anyhow::Result<f64> {
                let e0 = v.e0.as_ref().ok_or_else(|| {
                    InputError::new(format!(
                        "{label}: main layer has no channel `E0` (needed for the caustic flux \
                         without a `caustic` layer in both images): is it a receiver map? `compare` takes the \
                         receiver.exr of `render --dump receiver` or of `reference`"
                    ))
                })?;
                Ok(v.v.iter().zip(e0).map(|(x, e)| (x - 1.0).max(0.0) * e).sum())
            };
            ratio(excess(&va, la)?, excess(&vb, lb)?)
        }
    };

    let mut data = Vec::with_capacity(texels * 4);
    #[allow(clippy::needless_range_loop)]
    for t in 0..texels {
        data.extend_from_slice(&[
            va.v[t] as f32,
            vb.v[t] as f32,
            (va.v[t] - vb.v[t]) as f32,
            if in_region[t] { 1.0 } else { 0.0 },
        ]);
    }
    let err = ImageF32 {
        width: a.width,
        height: a.height,
        layers: vec![Layer::new(None, &["A", "B", "diff", "in_region"], data)],
    };
    Ok((
        Comparison {
            region_texels: region,
            rel_rmse: rel(sdd),
            rel_rmse_scaled: rel(sdd_scaled),
            best_scale,
            peak_ratio,
            peak_offset_texels,
            caustic_flux_ratio,
            non_finite_texels,
        },
        err,
    ))
}

#[cfg(test)]
mod tests;
