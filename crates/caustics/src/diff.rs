//! Texel-by-texel differences between two EXR images of the same buffer (a dump of one run
//! against the same dump of another): what `causticlab diff` reports and what
//! `scripts/same_maps.sh` uses to show that a refactor kept every image.
//!
//! Unlike [`crate::compare`], which judges a receiver map against a reference in E/E0, this
//! knows nothing of what the channels mean: every channel of every layer is compared, and a
//! channel's difference is its largest |a − b| relative to the largest |b| of that channel.

use crate::image_io::ImageF32;

/// How one channel of one layer differs.
#[derive(Debug, Clone, PartialEq)]
pub struct ChannelDiff {
    /// `layer.channel` (`channel` alone in the unnamed main layer).
    pub channel: String,
    /// The largest |a − b| over the texels (infinite where one is NaN and the other is not).
    pub max_abs_diff: f64,
    /// The largest finite |b| over the texels.
    pub max_abs: f64,
    /// Texels whose values are not identical (NaN equals NaN).
    pub texels_differing: usize,
}

impl ChannelDiff {
    /// `max_abs_diff` relative to `max_abs` (the difference itself where B is all zero).
    pub fn relative(&self) -> f64 {
        if self.max_abs > 0.0 {
            self.max_abs_diff / self.max_abs
        } else {
            self.max_abs_diff
        }
    }
}

/// Every channel of `a` against the same channel of `b`, in `b`'s order; `Err` says how their
/// shapes differ (size, layers, channels), which no tolerance forgives.
pub fn diff_images(a: &ImageF32, b: &ImageF32) -> Result<Vec<ChannelDiff>, String> {
    if (a.width, a.height) != (b.width, b.height) {
        return Err(format!("{}x{} against {}x{}", a.width, a.height, b.width, b.height));
    }
    let names = |img: &ImageF32| -> Vec<String> {
        img.layers.iter().map(|l| format!("{}[{}]", l.name.as_deref().unwrap_or(""), l.channels.join(","))).collect()
    };
    let mut out = vec![];
    for lb in &b.layers {
        let la = a.layer(lb.name.as_deref()).filter(|la| la.channels == lb.channels);
        let Some(la) = la else {
            return Err(format!("layers {:?} against {:?}", names(a), names(b)));
        };
        let n = lb.channels.len();
        for (c, channel) in lb.channels.iter().enumerate() {
            let mut d = ChannelDiff {
                channel: match &lb.name {
                    Some(l) => format!("{l}.{channel}"),
                    None => channel.clone(),
                },
                max_abs_diff: 0.0,
                max_abs: 0.0,
                texels_differing: 0,
            };
            for (va, vb) in la.data.iter().skip(c).step_by(n).zip(lb.data.iter().skip(c).step_by(n)) {
                let (va, vb) = (f64::from(*va), f64::from(*vb));
                if vb.is_finite() {
                    d.max_abs = d.max_abs.max(vb.abs());
                }
                let same = va == vb || (va.is_nan() && vb.is_nan());
                if !same {
                    d.texels_differing += 1;
                    let diff = if va.is_finite() && vb.is_finite() { (va - vb).abs() } else { f64::INFINITY };
                    d.max_abs_diff = d.max_abs_diff.max(diff);
                }
            }
            out.push(d);
        }
    }
    if a.layers.len() != b.layers.len() {
        return Err(format!("layers {:?} against {:?}", names(a), names(b)));
    }
    Ok(out)
}

/// Sorts each layer's texels (as tuples of their channels, NaN last): for lists whose order
/// an atomic counter sets (the compute traversal's and splat's appends), so that two runs
/// that appended the same entries in another order compare equal.
pub fn sort_texels(image: &mut ImageF32) {
    for layer in &mut image.layers {
        let n = layer.channels.len().max(1);
        let mut texels: Vec<&[f32]> = layer.data.chunks_exact(n).collect();
        texels.sort_by(|a, b| {
            a.iter().zip(b.iter()).map(|(x, y)| x.total_cmp(y)).find(|o| o.is_ne()).unwrap_or(std::cmp::Ordering::Equal)
        });
        layer.data = texels.concat();
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::image_io::Layer;

    fn image(layers: Vec<Layer>) -> ImageF32 {
        ImageF32 { width: 2, height: 1, layers }
    }

    #[test]
    fn equal_images_have_no_difference_and_nan_equals_nan() {
        let a = image(vec![Layer::new(None, &["R", "G"], vec![1.0, f32::NAN, -3.0, 0.0])]);
        let d = diff_images(&a, &a.clone()).unwrap();
        assert_eq!(d.len(), 2);
        assert!(d.iter().all(|c| c.texels_differing == 0 && c.max_abs_diff == 0.0), "{d:?}");
        assert_eq!(d[0].max_abs, 3.0);
    }

    #[test]
    fn a_changed_texel_is_found_in_its_own_channel() {
        let b = image(vec![Layer::new(Some("light0"), &["x", "y"], vec![1.0, 10.0, 2.0, 20.0])]);
        let mut a = b.clone();
        a.layers[0].data[3] = 20.5;
        let d = diff_images(&a, &b).unwrap();
        assert_eq!(d[0].channel, "light0.x");
        assert_eq!(d[0].texels_differing, 0);
        assert_eq!(d[1].channel, "light0.y");
        assert_eq!(d[1].texels_differing, 1);
        assert_eq!(d[1].max_abs_diff, 0.5);
        assert_eq!(d[1].relative(), 0.5 / 20.0);
        a.layers[0].data[0] = f32::NAN;
        assert_eq!(diff_images(&a, &b).unwrap()[0].max_abs_diff, f64::INFINITY);
    }

    #[test]
    fn sorted_texels_forget_the_order_but_not_the_pairs() {
        let b = image(vec![Layer::new(None, &["x", "y"], vec![1.0, 5.0, 0.0, 7.0])]);
        let mut a = image(vec![Layer::new(None, &["x", "y"], vec![0.0, 7.0, 1.0, 5.0])]);
        let mut b_sorted = b.clone();
        sort_texels(&mut a);
        sort_texels(&mut b_sorted);
        assert_eq!(diff_images(&a, &b_sorted).unwrap().iter().map(|c| c.texels_differing).sum::<usize>(), 0);
        // The same x and y values paired differently are another list.
        let mut c = image(vec![Layer::new(None, &["x", "y"], vec![0.0, 5.0, 1.0, 7.0])]);
        sort_texels(&mut c);
        assert!(diff_images(&c, &b_sorted).unwrap().iter().any(|c| c.texels_differing > 0));
    }

    #[test]
    fn different_shapes_are_errors() {
        let b = image(vec![Layer::new(None, &["R"], vec![1.0, 2.0])]);
        let renamed = image(vec![Layer::new(None, &["G"], vec![1.0, 2.0])]);
        assert!(diff_images(&renamed, &b).is_err());
        let extra = image(vec![Layer::new(None, &["R"], vec![1.0, 2.0]), Layer::new(Some("x"), &["R"], vec![0.0; 2])]);
        assert!(diff_images(&extra, &b).is_err());
        assert!(diff_images(&b, &extra).is_err());
        let wide = ImageF32 { width: 1, height: 2, layers: b.layers.clone() };
        assert!(diff_images(&wide, &b).is_err());
    }
}
