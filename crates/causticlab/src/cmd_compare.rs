//! `causticlab compare A.exr B.exr`: how far a receiver map or a final image is from a reference,
//! in its figures and HDR-FLIP (`caustics::compare::report`).

use crate::cli::CompareArgs;
use anyhow::{Context as _, Result};
use caustics::compare::perceptual::{FlipLine, ImageKind};
use caustics::compare::{final_image, report_files, Figures};
use caustics::error_png;
use caustics::flip::{Exposures, HdrFlip};
use caustics::image_io::{self, header};
use caustics::input_error;
use std::io::{ErrorKind, Read as _};
use std::path::Path;

pub fn run(args: &CompareArgs) -> Result<()> {
    check_exr(&args.a)?;
    check_exr(&args.b)?;
    let png = match &args.error_image {
        Some(p) => match p.extension().and_then(|e| e.to_str()).map(str::to_ascii_lowercase).as_deref() {
            Some("exr") => false,
            Some("png") => true,
            _ => {
                return Err(input_error!(
                    "--error-image {}: name an .exr (the error's layers) or a .png (its picture)",
                    p.display()
                )
                .into())
            }
        },
        None => false,
    };
    if let Some(s) = args.error_scale {
        if !(s.is_finite() && s > 0.0) {
            return Err(input_error!("--error-scale {s}: must be a positive number").into());
        }
    }
    for line in mismatches(&args.a, &args.b) {
        eprintln!("warning: {line}");
    }
    let r = report_files(&args.a, &args.b, args.region)?;
    let non_finite = match &r.figures {
        Figures::Receiver(c) => c.non_finite_texels,
        Figures::Final(c) => c.non_finite_pixels,
    };
    if non_finite > 0 {
        eprintln!(
            "warning: {non_finite} {} NaN or infinite in A or B: the errors over them are not to be trusted",
            if r.kind == ImageKind::ReceiverMap { "texel(s) (mean RGB, E0 or caustic value)" } else { "pixel(s)" }
        );
    }
    if let Err(e) = &r.flip {
        eprintln!("warning: no HDR-FLIP: {e}");
    }
    if args.json {
        let figures = match &r.figures {
            Figures::Receiver(c) => serde_json::json!({
                "region": format!("{:?}", args.region).to_lowercase(),
                "region_texels": c.region_texels,
                "rel_rmse": c.rel_rmse,
                "rel_rmse_scaled": c.rel_rmse_scaled,
                "best_scale": c.best_scale,
                "peak_ratio": c.peak_ratio,
                "peak_offset_texels": c.peak_offset_texels,
                "caustic_flux_ratio": c.caustic_flux_ratio,
                "non_finite_texels": c.non_finite_texels,
            }),
            Figures::Final(c) => serde_json::json!({
                "pixels": c.pixels,
                "rel_rmse": c.rel_rmse,
                "non_finite_pixels": c.non_finite_pixels,
            }),
        };
        // A, B and the kind first, then the figures, then FLIP.
        let mut v = serde_json::json!({
            "a": args.a.display().to_string(),
            "b": args.b.display().to_string(),
            "kind": r.kind.name(),
        });
        if let (Some(v), serde_json::Value::Object(f)) = (v.as_object_mut(), figures) {
            v.extend(f);
        }
        v["flip"] = r.flip.as_ref().map_or(serde_json::Value::Null, |f| flip_json(r.kind, f));
        if let Err(e) = &r.flip {
            v["flip_error"] = e.to_string().into();
        }
        println!("{}", serde_json::to_string_pretty(&v).context("serialising the comparison")?);
    } else {
        println!("A: {}\nB (reference): {}", args.a.display(), args.b.display());
        match &r.figures {
            Figures::Receiver(c) => print!("{c}"),
            Figures::Final(c) => print!("{c}"),
        }
        if let Ok(f) = &r.flip {
            println!("{}", FlipLine { kind: r.kind, flip: f });
        }
    }
    if let Some(p) = &args.error_image {
        let flip_path = beside(p);
        if png {
            let scale = args.error_scale.unwrap_or_else(|| match r.kind {
                ImageKind::ReceiverMap => error_png::default_scale(&r.error_image),
                ImageKind::FinalImage => final_image::default_error_scale(&r.error_image),
            });
            error_png::write_error_png(p, &r.error_image, scale)?;
            let said =
                format!("wrote {} (red: A brighter, blue: A darker, saturated at |A - B| = {scale:.3})", p.display());
            say(args.json, &said);
            if let Ok(f) = &r.flip {
                f.map.write_magma_png(&flip_path)?;
                say(
                    args.json,
                    &format!(
                        "wrote {} (HDR-FLIP per pixel through magma: black none, pale yellow 1)",
                        flip_path.display()
                    ),
                );
            }
        } else {
            image_io::write_exr(p, &r.error_image)?;
            say(args.json, &format!("wrote {}", p.display()));
            if let Ok(f) = &r.flip {
                f.write_exr(&flip_path)?;
                say(args.json, &format!("wrote {} (channels FLIP and exposure)", flip_path.display()));
            }
        }
    }
    Ok(())
}

/// The JSON object `--json` writes under `flip`: the mean with the pixels per degree, the size
/// and the exposures it was computed at.
fn flip_json(kind: ImageKind, r: &HdrFlip) -> serde_json::Value {
    serde_json::json!({
        "kind": kind.name(),
        "mean": r.mean(),
        "ppd": r.ppd(),
        "width": r.map.width,
        "height": r.map.height,
        "start_exposure": r.start_exposure,
        "stop_exposure": r.stop_exposure,
        "exposure_count": r.exposure_count,
        "exposures": if r.exposures == Exposures::Auto { "found from the reference" } else { "given" },
    })
}

/// Where the FLIP error image goes beside the error image `p`: `x.png` gives `x.flip.png`,
/// `x.exr` gives `x.flip.exr`.
pub fn beside(p: &Path) -> std::path::PathBuf {
    let stem = p.file_stem().map(|s| s.to_string_lossy().into_owned()).unwrap_or_default();
    let ext = p.extension().map(|s| s.to_string_lossy().into_owned()).unwrap_or_default();
    p.with_file_name(format!("{stem}.flip.{ext}"))
}

/// What the two maps' headers (`render` and `reference` write them) say differs: the scene or
/// the Fresnel setting. A comparison across them is allowed (a study of Fresnel's share, say)
/// but rarely meant, so it is said.
fn mismatches(a: &Path, b: &Path) -> Vec<String> {
    let (Ok(ha), Ok(hb)) = (image_io::exr_text_attributes(a), image_io::exr_text_attributes(b)) else {
        return vec![];
    };
    let same_scene = |x: &str, y: &str| match (std::fs::canonicalize(x), std::fs::canonicalize(y)) {
        (Ok(x), Ok(y)) => x == y,
        _ => Path::new(x).file_name() == Path::new(y).file_name(),
    };
    let mut out = vec![];
    if let (Some(x), Some(y)) = (ha.get(header::SCENE), hb.get(header::SCENE)) {
        if !same_scene(x, y) {
            out.push(format!("A is a map of {x}, B of {y}: the comparison is across scenes"));
        }
    }
    if let (Some(x), Some(y)) = (ha.get(header::FRESNEL), hb.get(header::FRESNEL)) {
        if x != y {
            out.push(format!(
                "A was made with fresnel {x}, B with fresnel {y}: the difference includes Fresnel's share"
            ));
        }
    }
    out
}

/// Progress lines: on stderr under --json, so that stdout stays one JSON object.
fn say(json: bool, line: &str) {
    if json {
        eprintln!("{line}");
    } else {
        println!("{line}");
    }
}

/// OpenEXR files start with these four bytes (the "magic number" of the EXR file layout).
const EXR_MAGIC: [u8; 4] = [0x76, 0x2f, 0x31, 0x01];

/// A missing input or one that is not an EXR file (`final.png`, say) is the user's to fix, as a
/// missing scene file is; the EXR reader's own message ("file identifier missing") does not say so.
fn check_exr(path: &Path) -> Result<()> {
    let not_exr = |what: &str| -> Result<()> {
        Err(input_error!(
            "{}: {what}; compare reads the receiver maps and final images causticlab writes as OpenEXR \
             (receiver.exr of a render with --dump receiver, or of a reference; final.exr of a render or of \
             reference --final)",
            path.display()
        )
        .into())
    };
    if path.is_dir() {
        return not_exr("is a directory");
    }
    let mut head = [0u8; 4];
    match std::fs::File::open(path).and_then(|mut f| f.read_exact(&mut head)) {
        Ok(()) if head == EXR_MAGIC => Ok(()),
        Ok(()) => not_exr("not an OpenEXR file"),
        Err(e) if e.kind() == ErrorKind::UnexpectedEof => not_exr("not an OpenEXR file (shorter than its header)"),
        Err(e) if e.kind() == ErrorKind::NotFound => Err(input_error!("{}: no such file", path.display()).into()),
        Err(e) => Err(anyhow::Error::new(e).context(format!("reading {}", path.display()))),
    }
}
