//! `causticlab reference` on a pool scene (Trendall & Stewart 2000): passes 1-6 in f64, the
//! paper's software implementation, or with `--direct` Eq. 2 itself; the receiver map E / E_flat
//! into DIR/receiver.exr, with a JSON record.

use crate::cli::ReferenceArgs;
use anyhow::{Context as _, Result};
use caustics::image_io::{self, OutputDir};
use caustics::scene::Scene;
use caustics::techniques::trendall_stewart2000::{self as ts, direct, dumps, water_surface};
use serde::Serialize;

#[derive(Serialize)]
struct Record {
    scene: String,
    method: &'static str,
    grid: u32,
    kernel: Option<u32>,
    time_s: f64,
    seconds: f64,
    /// Sum of E over the bottom (texel areas included), m^2 times Eq. 2's units.
    flux: f64,
    flat_flux: f64,
}

pub fn run(args: &ReferenceArgs, scene: &Scene) -> Result<()> {
    let pool = ts::pool_of(scene)?;
    let mut settings = scene.caustics.clone();
    if let Some(g) = args.grid {
        settings.photons = g;
    }
    if let Some(k) = args.kernel {
        settings.kernel = k;
    }
    settings.validate("command line", "--")?;
    let n = settings.photons as usize;
    let out = OutputDir::create(&args.out).context("--out")?;
    let start = std::time::Instant::now();
    let (e, flat) = if args.direct {
        let ls = ts::light_radiance(pool, n)?;
        let h = water_surface::height_field(pool, n);
        (direct::direct_irradiance(pool, n, &h, &ls), direct::direct_irradiance(pool, n, &vec![0.0; n * n], &ls))
    } else {
        let (wavy, flat) = ts::reference(pool, n, settings.kernel as usize)?;
        (wavy.irradiance(), flat.irradiance())
    };
    let seconds = start.elapsed().as_secs_f64();
    image_io::write_exr(&out.path("receiver.exr"), &dumps::receiver_image(n, &e, &flat))?;
    let area = (pool.side / n as f64).powi(2);
    let record = Record {
        scene: args.scene.display().to_string(),
        method: if args.direct { "Eq. 2, direct" } else { "passes 1-6, f64" },
        grid: settings.photons,
        kernel: (!args.direct).then_some(settings.kernel),
        time_s: pool.time,
        seconds,
        flux: e.iter().sum::<f64>() * area,
        flat_flux: flat.iter().sum::<f64>() * area,
    };
    let json = serde_json::to_string_pretty(&record).context("serialising reference.json")?;
    image_io::write_file_atomically(&out.path("reference.json"), json.as_bytes())?;
    let dir = out.final_dir().to_path_buf();
    out.commit()?;
    println!(
        "{}: {} on {n}x{n} in {seconds:.2} s, flux ratio to flat water {:.4}",
        args.scene.display(),
        record.method,
        record.flux / record.flat_flux
    );
    println!("wrote {}", dir.join("receiver.exr").display());
    Ok(())
}
