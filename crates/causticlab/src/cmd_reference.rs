//! `causticlab reference`: the exact CPU photon tracer's receiver map, written atomically with a
//! JSON record of the fluxes it measured.

use crate::cli::{GlobalOpts, ReferenceArgs};
use anyhow::{Context as _, Result};
use caustics::image_io::{self, header, OutputDir};
use caustics::reference::{trace_reference, ReferenceOptions};
use caustics::scene::Scene;
use serde::Serialize;
use std::sync::Arc;
use vkcore::ValidationLog;

#[derive(Serialize)]
struct Record {
    scene: String,
    photons_per_light: u64,
    seed: u64,
    fresnel: bool,
    max_bounces: u32,
    outside_reflection: bool,
    smooth_normals: bool,
    /// End to end: the BVH build, the tracing, the direct light, the image.
    seconds: f64,
    /// The photons' tracing and binning alone (`ReferenceResult::trace_seconds`): what
    /// `photon-trace`'s trace pass does, its BVH built beforehand.
    trace_seconds: f64,
    /// Worker threads that traced (its photons per second depend on them).
    threads: usize,
    photons_traced: u64,
    emitted_flux_w: [f64; 3],
    caustic_flux_w: [f64; 3],
    lost_tir_w: [f64; 3],
    lost_other_w: [f64; 3],
}

/// The photon options in effect: each one given, else `ReferenceOptions`' default (Fresnel: the
/// scene's). `reference --final` reads its seed, bounces, outside reflection and Fresnel here too.
pub fn options(args: &ReferenceArgs, scene: &Scene) -> ReferenceOptions {
    let defaults = ReferenceOptions::default();
    ReferenceOptions {
        photons: args.photons.unwrap_or(defaults.photons),
        seed: args.seed.unwrap_or(defaults.seed),
        fresnel: args.fresnel.unwrap_or(scene.caustics.fresnel),
        max_bounces: args.max_bounces.unwrap_or(defaults.max_bounces),
        outside_reflection: args.outside_reflection.unwrap_or(defaults.outside_reflection),
        threads: args.threads.unwrap_or(defaults.threads),
        smooth_normals: !args.facet_normals,
    }
}

pub fn run(g: &GlobalOpts, args: &ReferenceArgs, validation: &mut Option<Arc<ValidationLog>>) -> Result<()> {
    let scene = Scene::load(&args.scene)?;
    if args.final_image {
        return crate::cmd_reference_final::run(g, args, scene, validation);
    }
    if args.level.is_some() {
        return Err(
            caustics::input_error!("--level: only with --final (the reference final image's refinement)").into()
        );
    }
    if scene.pool.is_some() {
        // Passes 1-6 in f64 trace no photons: a photon option given here would be ignored.
        let photon_options = [
            (args.photons.is_some(), "--photons"),
            (args.seed.is_some(), "--seed"),
            (args.fresnel.is_some(), "--fresnel"),
            (args.max_bounces.is_some(), "--max-bounces"),
            (args.outside_reflection.is_some(), "--outside-reflection"),
            (args.threads.is_some(), "--threads"),
            (args.facet_normals, "--facet-normals"),
        ];
        if let Some((_, flag)) = photon_options.iter().find(|(given, _)| *given) {
            return Err(caustics::input_error!(
                "{flag}: a photon option, and {} is a pool scene, whose reference traces no photons (its options: \
                 --direct, --grid, --kernel)",
                args.scene.display()
            )
            .into());
        }
        return crate::cmd_pool_reference::run(args, &scene);
    }
    for (set, flag) in [(args.direct, "--direct"), (args.grid.is_some(), "--grid"), (args.kernel.is_some(), "--kernel")]
    {
        if set {
            return Err(caustics::input_error!(
                "{flag}: only for pool scenes ([pool], technique pool-convolution); {} is not one",
                args.scene.display()
            )
            .into());
        }
    }
    let opts = options(args, &scene);
    let out = OutputDir::create(&args.out).context("--out")?;
    let start = std::time::Instant::now();
    let r =
        trace_reference(&scene, &opts).with_context(|| format!("tracing the reference of {}", args.scene.display()))?;
    let seconds = start.elapsed().as_secs_f64();
    if r.threads < r.threads_asked {
        eprintln!(
            "warning: the system started {} of the {} threads asked for ({}); the photons were traced by those \
             (the same image)",
            r.threads,
            r.threads_asked,
            r.thread_refused.as_deref().unwrap_or("no reason given")
        );
    }
    // What made the map, as `render` records it, so that `compare` can tell a mismatch.
    let header = [
        (header::TECHNIQUE, "reference (exact CPU photon trace)".to_string()),
        (header::PHOTONS, opts.photons.to_string()),
        (header::FRESNEL, opts.fresnel.to_string()),
        (header::COMMIT, bench::meta::commit()),
        (header::SCENE, args.scene.display().to_string()),
    ];
    image_io::write_exr_with(&out.path("receiver.exr"), &r.image, &header)?;
    let record = Record {
        scene: args.scene.display().to_string(),
        photons_per_light: opts.photons,
        seed: opts.seed,
        fresnel: opts.fresnel,
        max_bounces: opts.max_bounces,
        outside_reflection: opts.outside_reflection,
        smooth_normals: opts.smooth_normals,
        seconds,
        trace_seconds: r.trace_seconds,
        threads: r.threads,
        photons_traced: r.photons_traced,
        emitted_flux_w: r.emitted_flux,
        caustic_flux_w: r.caustic_flux,
        lost_tir_w: r.lost_tir,
        lost_other_w: r.lost_other,
    };
    let json = serde_json::to_string_pretty(&record).context("serialising reference.json")?;
    image_io::write_file_atomically(&out.path("reference.json"), json.as_bytes())?;
    let dir = out.final_dir().to_path_buf();
    out.commit()?;
    println!(
        "{}: {} photons in {seconds:.1} s ({:.2} M photons/s), caustic flux {:.4} W of {:.4} W emitted (TIR lost {:.4} W)",
        args.scene.display(),
        r.photons_traced,
        r.photons_traced as f64 / seconds / 1e6,
        r.caustic_flux[1],
        r.emitted_flux[1],
        r.lost_tir[1]
    );
    println!("wrote {}", dir.join("receiver.exr").display());
    Ok(())
}
