//! HDR-FLIP (Andersson et al., "Visualizing Errors in Rendered High Dynamic Range Images",
//! Eurographics 2021 short papers): LDR-FLIP of the two images tone mapped at a range of
//! exposures, the largest error over the exposures kept per pixel.
//!
//! * Tone mapper: the ACES filmic curve fitted by Narkowicz (2015), per channel, with its
//!   pre-exposure of 0.6 folded into the coefficients ([`ACES`]), then clamped to [0, 1].
//! * Exposure range, found as the paper does from the reference alone: `x_max` is the input at
//!   which the tone curve reaches 0.85; the start exposure `log2(x_max / Y_max)` maps the
//!   reference's brightest luminance there, the stop exposure `log2(x_max / Y_median)` its median
//!   luminance (the median is the reference implementation's: the element of rank ⌊n/2⌋, raised
//!   to f32 ε when more than half the pixels are black, as flip-evaluator 1.7 does).
//! * Exposures: `max(2, ⌈stop − start⌉)` of them, evenly spaced from start to stop (about one per
//!   stop); at exposure c both images are multiplied by 2^c.
//! * The exposure map: per pixel, which exposure gave the largest error, as `i / (N − 1)`.

use super::colour::{luminance, Triple};
use super::ldr::flip_ldr;
use crate::error::InputError;

/// The tone curve `(c0 x² + c1 x + c2) / (c3 x² + c4 x + c5)`: Narkowicz's ACES fit
/// `x (2.51 x + 0.03) / (x (2.43 x + 0.59) + 0.14)` at `0.6 x` (the reference implementation's
/// `ToneMappingCoefficients[1]`, "0.6 is pre-exposure cancellation").
pub const ACES: [f32; 6] = [0.6 * 0.6 * 2.51, 0.6 * 0.03, 0.0, 0.6 * 0.6 * 2.43, 0.6 * 0.59, 0.14];

/// The tone-mapped value the exposure range is built around (HDR-FLIP paper: the brightest and the
/// median luminance are each brought to where the curve reaches 0.85).
pub const TONE_TARGET: f32 = 0.85;

/// [`ACES`] at `x`, unclamped.
pub fn tone_map(x: f32) -> f32 {
    let c = ACES;
    ((x * x) * c[0] + x * c[1] + c[2]) / (x * x * c[3] + x * c[4] + c[5])
}

/// [`tone_map`] clamped to [0, 1], as the reference implementation clamps before LDR-FLIP. An
/// input so large that `x²` overflows (inf / inf) is the curve's limit, clamped: 1.
pub fn tone_map_clamped(x: f32) -> f32 {
    let t = tone_map(x);
    if t.is_nan() {
        1.0
    } else {
        t.clamp(0.0, 1.0)
    }
}

/// `x_max`: the input at which [`tone_map`] equals [`TONE_TARGET`], the larger root of
/// `(c0 − t c3) x² + (c1 − t c4) x + (c2 − t c5) = 0`.
pub fn tone_target_input() -> f32 {
    let c = ACES;
    let t = TONE_TARGET;
    let (a, b, k) = (c[0] - t * c[3], c[1] - t * c[4], c[2] - t * c[5]);
    let mid = -0.5 * (b / a);
    mid + (mid * mid - k / a).sqrt()
}

/// The exposure range from the reference's luminances: `(start, stop)`, in stops.
pub fn auto_exposures(reference: &[Triple]) -> Result<(f32, f32), InputError> {
    let mut y: Vec<f32> = reference.iter().map(|&c| luminance(c)).collect();
    let y_max = y.iter().copied().fold(0.0f32, f32::max);
    if y_max <= 0.0 {
        return Err(InputError::new(
            "HDR-FLIP: the reference image is black, so it sets no exposure range: give the start and stop exposures",
        ));
    }
    let rank = y.len() / 2;
    let (_, &mut y_median, _) = y.select_nth_unstable_by(rank, f32::total_cmp);
    let y_median = y_median.max(f32::EPSILON);
    let x_max = tone_target_input();
    let stops = |y: f32| ((x_max / y) as f64).log2() as f32;
    Ok((stops(y_max), stops(y_median)))
}

/// How many exposures span `start..=stop`: `max(2, ⌈stop − start⌉)`.
pub fn exposure_count(start: f32, stop: f32) -> usize {
    (stop - start).ceil().max(2.0) as usize
}

/// HDR-FLIP's error map and exposure map over `count` exposures from `start` to `stop`.
pub fn flip_hdr(
    width: usize,
    height: usize,
    reference: &[Triple],
    test: &[Triple],
    ppd: f32,
    (start, stop, count): (f32, f32, usize),
) -> (Vec<f32>, Vec<f32>) {
    let mut error = vec![0.0f32; width * height];
    let mut exposure_map = vec![0.0f32; width * height];
    let step = (stop - start) / (count - 1) as f32;
    let ldr_at = |i: usize| -> Vec<f32> {
        let scale = 2.0f32.powf(start + i as f32 * step);
        let exposed =
            |img: &[Triple]| -> Vec<Triple> { img.iter().map(|c| c.map(|v| tone_map_clamped(v * scale))).collect() };
        flip_ldr(width, height, &exposed(reference), &exposed(test), ppd)
    };
    // The exposures are independent: threads take them in turn (crate::workers, at most one per
    // core), each map kept in its exposure's slot, so that the result is the same as one after
    // the other.
    let threads = std::thread::available_parallelism().map_or(1, |n| n.get()).clamp(1, count);
    let next = std::sync::atomic::AtomicUsize::new(0);
    let slots = std::sync::Mutex::new(vec![None; count]);
    crate::workers::run(threads, "hdr-flip", || loop {
        let i = next.fetch_add(1, std::sync::atomic::Ordering::Relaxed);
        if i >= count {
            break;
        }
        let map = ldr_at(i);
        slots.lock().expect("no exposure panicked holding the slots")[i] = Some(map);
    });
    let maps = slots.into_inner().expect("no exposure panicked holding the slots");
    for (i, e) in maps.into_iter().enumerate() {
        let e = e.expect("every exposure was taken by a worker");
        let which = i as f32 / (count - 1) as f32;
        for ((best, at), v) in error.iter_mut().zip(exposure_map.iter_mut()).zip(e) {
            if v > *best {
                (*best, *at) = (v, which);
            }
        }
    }
    (error, exposure_map)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Narkowicz's fit itself (coefficients 2.51, 0.03, 2.43, 0.59, 0.14) at 0.6 x.
    #[test]
    fn the_tone_curve_is_narkowicz_aces_after_a_pre_exposure_of_0_6() {
        for x in [0.01f32, 0.18, 1.0, 4.0, 50.0] {
            let y = 0.6 * x;
            let narkowicz = y * (2.51 * y + 0.03) / (y * (2.43 * y + 0.59) + 0.14);
            assert!((tone_map(x) - narkowicz).abs() < 1e-5, "{x}");
        }
        assert_eq!(tone_map(0.0), 0.0);
        assert_eq!((tone_map_clamped(1e30), tone_map_clamped(f32::INFINITY), tone_map_clamped(1e3)), (1.0, 1.0, 1.0));
    }

    #[test]
    fn x_max_is_where_the_curve_reaches_0_85() {
        let x = tone_target_input();
        assert!((tone_map(x) - 0.85).abs() < 1e-5, "tone_map({x}) = {}", tone_map(x));
        assert!(x > 1.0 && x < 3.0, "{x}");
    }

    /// Luminances 1, 2, 4 and 8 (grey pixels): the maximum is 8, the median (rank 2 of 4) is 4.
    #[test]
    fn the_exposure_range_runs_from_the_brightest_to_the_median_pixel() {
        let img: Vec<Triple> = [2.0f32, 8.0, 1.0, 4.0].iter().map(|&v| [v; 3]).collect();
        let (start, stop) = auto_exposures(&img).unwrap();
        let x = tone_target_input();
        assert!((start - (x / 8.0).log2()).abs() < 1e-5 && (stop - (x / 4.0).log2()).abs() < 1e-5, "{start} {stop}");
        assert_eq!(exposure_count(start, stop), 2, "one stop apart, but never fewer than two");
        assert_eq!(exposure_count(-3.2, 4.1), 8);
    }

    #[test]
    fn a_mostly_black_reference_stops_at_epsilon_and_a_black_one_is_refused() {
        let img: Vec<Triple> = [0.0f32, 0.0, 0.0, 2.0].iter().map(|&v| [v; 3]).collect();
        let (_, stop) = auto_exposures(&img).unwrap();
        assert!((stop - (tone_target_input() / f32::EPSILON).log2()).abs() < 1e-4, "{stop}");
        let err = auto_exposures(&[[0.0; 3]; 4]).unwrap_err();
        assert!(err.0.contains("black"), "{err}");
    }

    /// The exposure map names the exposure where a pixel's error peaked: a difference in a dim
    /// pixel (0.01 against 0.02) is seen at a bright exposure (by hand, in CIELab lightness: about
    /// 12 apart at 2^2, 19 at 2^4, 11 at 2^6), one in a bright pixel (100 against 50) at the
    /// darkest, 2^−6 (10 apart, 2 at 2^−4).
    #[test]
    fn the_exposure_map_names_the_exposure_that_saw_the_error() {
        let (w, h) = (24, 12);
        let reference: Vec<Triple> = (0..w * h).map(|i| if i % w < w / 2 { [0.01; 3] } else { [100.0; 3] }).collect();
        let mut test = reference.clone();
        test[6 * w + 3] = [0.02; 3];
        test[6 * w + 20] = [50.0; 3];
        let (error, at) = flip_hdr(w, h, &reference, &test, 30.0, (-6.0, 8.0, 8));
        assert!(error[6 * w + 3] > 0.1 && error[6 * w + 20] > 0.1);
        assert!(at[6 * w + 3] > 0.5, "the dim pixel's exposure {}", at[6 * w + 3]);
        assert_eq!(at[6 * w + 20], 0.0, "the bright pixel's exposure");
    }
}
