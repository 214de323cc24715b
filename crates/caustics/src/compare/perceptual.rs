//! HDR-FLIP beside `compare`'s figures (issue 51): how visible the difference between a
//! technique's image and the reference is, for the two kinds of image `compare` reads.
//!
//! * A **receiver map** (`receiver.exr` of `render --dump receiver` or of `reference`: a main
//!   layer with `E0`, or a `caustic` layer): FLIP of its E/E0 (`R, G, B`), one texel a pixel, at
//!   the map's own resolution (the scene's `[receiver_map].resolution`).
//! * A **final image** (`final.exr` of `render`, or of `reference --final`: a main layer of
//!   `R, G, B` alone): FLIP of its linear radiance at the camera's resolution.
//!
//! Both at [`flip::default_ppd`] pixels per degree, the exposures found from the reference
//! (`b`) as the HDR-FLIP paper finds them (`docs/flip.md`); every value is written with both.

use crate::error::InputError;
use crate::flip::{self, Exposures, HdrFlip, Rgb};
use crate::image_io::ImageF32;
use std::fmt;

/// What two compared images are.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum ImageKind {
    /// E/E0 of the receiver rectangle, with `E0` or a `caustic` layer.
    ReceiverMap,
    /// The eye's linear radiance: `R, G, B` and nothing else a receiver map has.
    FinalImage,
}

impl ImageKind {
    /// As `--json` writes it.
    pub fn name(self) -> &'static str {
        match self {
            ImageKind::ReceiverMap => "receiver-map",
            ImageKind::FinalImage => "final-image",
        }
    }

    /// For sentences: "a receiver map", "a final image".
    pub fn described(self) -> &'static str {
        match self {
            ImageKind::ReceiverMap => "a receiver map (E/E0 with E0)",
            ImageKind::FinalImage => "a final image (R, G, B radiance, no E0)",
        }
    }

    /// Of one image, named `label` in errors: a main layer with `R, G, B` is required.
    pub fn of(img: &ImageF32, label: &str) -> Result<ImageKind, InputError> {
        let main = img.layer(None).ok_or_else(|| crate::input_error!("{label}: no main layer (channels R, G, B)"))?;
        for c in ["R", "G", "B"] {
            if !main.channels.iter().any(|x| x == c) {
                return Err(crate::input_error!("{label}: the main layer has no channel `{c}`"));
            }
        }
        let receiver = main.channels.iter().any(|c| c == "E0") || img.layer(Some("caustic")).is_some();
        Ok(if receiver { ImageKind::ReceiverMap } else { ImageKind::FinalImage })
    }

    /// Of a pair: both must be of the same kind.
    pub fn of_pair(a: &ImageF32, la: &str, b: &ImageF32, lb: &str) -> Result<ImageKind, InputError> {
        let (ka, kb) = (ImageKind::of(a, la)?, ImageKind::of(b, lb)?);
        if ka != kb {
            return Err(crate::input_error!(
                "{la} is {} but {lb} is {}: compare two receiver maps or two final images",
                ka.described(),
                kb.described()
            ));
        }
        Ok(ka)
    }
}

/// HDR-FLIP of `a` against the reference `b` (same size: checked by the caller's comparison),
/// at the default pixels per degree, the exposures found from `b`. A value FLIP refuses (NaN,
/// infinite, negative) or a black reference is an input error naming the file.
pub fn hdr_flip(a: &ImageF32, la: &str, b: &ImageF32, lb: &str) -> Result<HdrFlip, InputError> {
    let rgb = |img: &ImageF32, label: &str| Rgb::from_exr(img).map_err(|e| crate::input_error!("{label}: {e}"));
    let (ra, rb) = (rgb(a, la)?, rgb(b, lb)?);
    flip::hdr(&rb, &ra, flip::default_ppd(), Exposures::Auto).map_err(|e| crate::input_error!("{lb} (reference): {e}"))
}

/// HDR-FLIP of the final image `a` against the reference final image `b`, as [`hdr_flip`],
/// after the checks `compare` makes of the pair (both final images, one size): the bench's
/// `flip` metric, which must not measure a receiver map or a resized image.
pub fn final_image_flip(a: &ImageF32, la: &str, b: &ImageF32, lb: &str) -> Result<HdrFlip, InputError> {
    if ImageKind::of_pair(a, la, b, lb)? != ImageKind::FinalImage {
        return Err(crate::input_error!("{la} and {lb} are receiver maps, not final images"));
    }
    super::same_size(a, la, b, lb)?;
    hdr_flip(a, la, b, lb)
}

/// FLIP's figures as `compare` prints them: the kind and size compared with every mean.
pub struct FlipLine<'a> {
    pub kind: ImageKind,
    pub flip: &'a HdrFlip,
}

impl fmt::Display for FlipLine<'_> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let what = match self.kind {
            ImageKind::ReceiverMap => "receiver map, E/E0",
            ImageKind::FinalImage => "final image",
        };
        let r = self.flip;
        let how = if r.exposures == Exposures::Auto { "found from the reference" } else { "given" };
        write!(
            f,
            "HDR-FLIP ({what}): {}; {} exposures from {:.4} to {:.4} stops ({how})",
            r.map, r.exposure_count, r.start_exposure, r.stop_exposure
        )
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::image_io::Layer;

    fn image(channels: &[&str], values: &[f32], caustic: bool) -> ImageF32 {
        let n = channels.len();
        let data: Vec<f32> = values.iter().flat_map(|&v| std::iter::repeat_n(v, n)).collect();
        let mut layers = vec![Layer::new(None, channels, data)];
        if caustic {
            layers.push(Layer::new(Some("caustic"), &["R", "G", "B"], values.iter().flat_map(|&v| [v; 3]).collect()));
        }
        ImageF32 { width: values.len() as u32, height: 1, layers }
    }

    #[test]
    fn a_map_with_e0_or_a_caustic_layer_is_a_receiver_map_else_a_final_image() {
        let v = [1.0, 2.0];
        assert_eq!(ImageKind::of(&image(&["R", "G", "B", "E0"], &v, false), "x"), Ok(ImageKind::ReceiverMap));
        assert_eq!(ImageKind::of(&image(&["R", "G", "B"], &v, true), "x"), Ok(ImageKind::ReceiverMap));
        assert_eq!(ImageKind::of(&image(&["B", "G", "R", "A"], &v, false), "x"), Ok(ImageKind::FinalImage));
        let e = ImageKind::of(&image(&["R", "G"], &v, false), "x.exr").unwrap_err();
        assert!(e.0.contains("x.exr") && e.0.contains("`B`"), "{e}");
        let e = ImageKind::of_pair(
            &image(&["R", "G", "B", "E0"], &v, false),
            "a.exr",
            &image(&["R", "G", "B"], &v, false),
            "b.exr",
        )
        .unwrap_err();
        assert!(e.0.contains("a.exr is a receiver map") && e.0.contains("b.exr is a final image"), "{e}");
    }

    #[test]
    fn an_image_against_itself_is_0_and_a_black_reference_names_the_file() {
        let a = image(&["R", "G", "B"], &[0.5, 2.0, 0.1, 4.0], false);
        let r = hdr_flip(&a, "a.exr", &a, "b.exr").unwrap();
        assert_eq!(r.mean(), 0.0);
        assert_eq!(r.ppd(), flip::default_ppd());
        let black = image(&["R", "G", "B"], &[0.0; 4], false);
        let e = hdr_flip(&a, "a.exr", &black, "b.exr").unwrap_err();
        assert!(e.0.starts_with("b.exr (reference): "), "{e}");
        let nan = image(&["R", "G", "B"], &[0.5, f32::NAN, 0.1, 4.0], false);
        let e = hdr_flip(&nan, "a.exr", &a, "b.exr").unwrap_err();
        assert!(e.0.starts_with("a.exr: ") && e.0.contains("NaN"), "{e}");
    }
}
