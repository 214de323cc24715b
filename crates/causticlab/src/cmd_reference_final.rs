//! `causticlab reference --final`: the reference final image (`caustics::final_reference`), the
//! eye's frame with its caustic map filled by exact GPU photons, written atomically as
//! final.exr, final.png and reference.json (the refinement that made it).

use crate::cli::{GlobalOpts, ReferenceArgs};
use anyhow::{Context as _, Result};
use caustics::final_reference::{render_final, Refinement, BASE};
use caustics::image_io::{self, header, OutputDir};
use caustics::input_error;
use caustics::render;
use caustics::scene::Scene;
use serde::Serialize;
use std::sync::Arc;
use vkcore::{Context, ShaderCompiler, ValidationLog};

#[derive(Serialize)]
struct Record {
    scene: String,
    kind: &'static str,
    refinement: Refinement,
    photons_per_light: u64,
    seed: u32,
    fresnel: bool,
    max_bounces: u32,
    outside_reflection: bool,
    width: u32,
    height: u32,
    device: String,
    seconds: f64,
}

pub fn run(
    g: &GlobalOpts,
    args: &ReferenceArgs,
    mut scene: Scene,
    validation: &mut Option<Arc<ValidationLog>>,
) -> Result<()> {
    if !scene.caustics.technique.renders_meshes() || scene.pool.is_some() {
        return Err(input_error!(
            "--final: {} is a pool scene; the reference final image is of mesh scenes (the pool's reference is \
             `reference` without --final)",
            args.scene.display()
        )
        .into());
    }
    let opts = crate::cmd_reference::options(args, &scene);
    let seed = u32::try_from(opts.seed).map_err(|_| {
        input_error!("--seed {}: with --final the seed is a photon-trace seed, at most {}", opts.seed, u32::MAX)
    })?;
    let c = &mut scene.caustics;
    c.fresnel = opts.fresnel;
    c.max_bounces = opts.max_bounces;
    c.outside_reflection = opts.outside_reflection;
    let r = Refinement::at(args.level.unwrap_or(caustics::final_reference::TABLE_LEVEL), BASE)?;
    // Every setting checked before the device opens.
    r.scene(&scene, seed, 0)?;
    let out = OutputDir::create(&args.out).context("--out")?;
    let ctx = Context::new(&crate::context_options(g)?).context("opening the Vulkan device")?;
    *validation = Some(ctx.validation_log());
    render::check_device(&ctx, &r.scene(&scene, seed, 0)?)?;
    let shaders = ShaderCompiler::new(&render::shader_root()).context("creating the shader compiler")?;
    println!(
        "{}: the reference final image, level {}: a {}² caustic map, splat radius {} texels, {} frame(s) of {}² photons",
        args.scene.display(),
        r.level,
        r.caustic_map_resolution,
        r.splat_radius,
        r.frames,
        r.photons
    );
    let start = std::time::Instant::now();
    let image = render_final(&ctx, &shaders, &scene, &r, seed, |f| {
        if r.frames > 1 {
            eprintln!("reference final image: frame {} of {} traced", f + 1, r.frames);
        }
    })
    .with_context(|| format!("rendering the reference final image of {}", args.scene.display()))?;
    let seconds = start.elapsed().as_secs_f64();
    let device = format!("{} ({})", ctx.info().name, ctx.info().driver_info);
    let header = [
        (header::TECHNIQUE, format!("reference final image (photon-trace, level {})", r.level)),
        (header::PHOTONS, r.total_photons().to_string()),
        (header::FRESNEL, scene.caustics.fresnel.to_string()),
        (header::COMMIT, bench::meta::commit()),
        (header::DEVICE, device.clone()),
        (header::SCENE, args.scene.display().to_string()),
    ];
    let written = crate::cmd_render::write_final_images(&out, &image, &header, scene.render.exposure)?;
    let record = Record {
        scene: args.scene.display().to_string(),
        kind: "final image",
        refinement: r,
        photons_per_light: r.total_photons(),
        seed,
        fresnel: scene.caustics.fresnel,
        max_bounces: scene.caustics.max_bounces,
        outside_reflection: scene.caustics.outside_reflection,
        width: image.width,
        height: image.height,
        device,
        seconds,
    };
    let json = serde_json::to_string_pretty(&record).context("serialising reference.json")?;
    image_io::write_file_atomically(&out.path("reference.json"), json.as_bytes())?;
    let dir = out.final_dir().to_path_buf();
    out.commit()?;
    for f in written.iter().map(String::as_str).chain(["reference.json"]) {
        println!("wrote {}", dir.join(f).display());
    }
    Ok(())
}
