//! `causticlab compare`'s report: the figures of a receiver map or of a final image against the
//! reference, with HDR-FLIP of either (`perceptual`) and the error image.

use super::final_image::{compare_final, FinalComparison};
use super::perceptual::{self, ImageKind};
use super::{compare_labelled, same_size, Comparison, Region};
use crate::error::InputError;
use crate::flip::HdrFlip;
use crate::image_io::{read_exr, ImageF32};
use std::path::Path;

/// `compare`'s figures of either kind of image (`perceptual::ImageKind`).
pub enum Figures {
    Receiver(Comparison),
    Final(FinalComparison),
}

/// What `causticlab compare` reports on two images of one kind: their figures, HDR-FLIP (or the
/// input error that kept it from being computed: a NaN, a negative value, a black reference) and
/// the error image (`A`, `B`, `diff`, `in_region`).
pub struct Report {
    pub kind: ImageKind,
    pub figures: Figures,
    pub flip: Result<HdrFlip, InputError>,
    pub error_image: ImageF32,
}

/// [`Report`] of the EXR files `a` against the reference `b`, naming the files in errors;
/// `region` is for receiver maps.
pub fn report_files(a: &Path, b: &Path, region: Region) -> anyhow::Result<Report> {
    let (ia, ib) = (read_exr(a)?, read_exr(b)?);
    report(&ia, &a.display().to_string(), &ib, &b.display().to_string(), region)
}

/// [`Report`] of `a` (named `la`) against the reference `b` (`lb`).
pub fn report(a: &ImageF32, la: &str, b: &ImageF32, lb: &str, region: Region) -> anyhow::Result<Report> {
    // The kinds first: a receiver map against a final image is the mistake to name, whatever
    // their sizes.
    let kind = ImageKind::of_pair(a, la, b, lb)?;
    same_size(a, la, b, lb)?;
    let (figures, error_image) = match kind {
        ImageKind::ReceiverMap => {
            let (c, e) = compare_labelled(a, la, b, lb, region)?;
            (Figures::Receiver(c), e)
        }
        ImageKind::FinalImage => {
            let (c, e) = compare_final(a, la, b, lb)?;
            (Figures::Final(c), e)
        }
    };
    Ok(Report { kind, figures, flip: perceptual::hdr_flip(a, la, b, lb), error_image })
}
