//! `causticlab compare A.exr B.exr`: how far a receiver map is from a reference.

use crate::cli::CompareArgs;
use anyhow::{Context as _, Result};
use caustics::compare::compare_files;
use caustics::image_io;

pub fn run(args: &CompareArgs) -> Result<()> {
    let (c, error_image) = compare_files(&args.a, &args.b)?;
    if args.json {
        let v = serde_json::json!({
            "a": args.a.display().to_string(),
            "b": args.b.display().to_string(),
            "region_texels": c.region_texels,
            "rel_rmse": c.rel_rmse,
            "rel_rmse_scaled": c.rel_rmse_scaled,
            "best_scale": c.best_scale,
            "peak_ratio": c.peak_ratio,
            "peak_offset_texels": c.peak_offset_texels,
            "caustic_flux_ratio": c.caustic_flux_ratio,
        });
        println!("{}", serde_json::to_string_pretty(&v).context("serialising the comparison")?);
    } else {
        println!("A: {}\nB (reference): {}\n{c}", args.a.display(), args.b.display());
    }
    if let Some(p) = &args.error_image {
        image_io::write_exr(p, &error_image)?;
        println!("wrote {}", p.display());
    }
    Ok(())
}
