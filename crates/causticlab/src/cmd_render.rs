//! `causticlab render`: check every input before touching the GPU, render, then write
//! final.exr, final.png, the dumps and timings.json into a staging directory that only
//! becomes `--out` when everything succeeded.

use crate::cli::{GlobalOpts, RenderArgs};
use anyhow::{Context as _, Result};
use bench::Timings;
use caustics::dump::named_in;
use caustics::image_io::{self, header, ImageF32, OutputDir};
use caustics::input_error;
use caustics::render::{self, RenderRequest};
use caustics::scene::Scene;
use caustics::techniques::wyman2008::SplatMode;
use caustics::techniques::{Refraction, SplatPath, Technique};
use std::sync::Arc;
use vkcore::{Context, DeviceInfo, ShaderCompiler, ValidationLog};

pub fn run(g: &GlobalOpts, args: &RenderArgs, validation: &mut Option<Arc<ValidationLog>>) -> Result<()> {
    let opts = crate::context_options(g)?;
    let mut dumps = parse_dumps(args.dump.as_deref())?;
    // The loader's messages already name the file and the key.
    let mut scene = Scene::load(&args.scene)?;
    crate::cli::apply_caustic_flags(&args.caustics, &mut scene.caustics, &args.scene)?;
    let technique = scene.caustics.technique;
    // `all` means every buffer this render has; naming a buffer of another technique is a
    // mistake worth saying.
    let own = render::dumps_for(&scene.caustics);
    // (The pool's techniques make their own `receiver`.)
    let no_receiver_map = technique.renders_meshes() && scene.receiver_map.is_none();
    let receiver = render::dumps::RECEIVER.name;
    if no_receiver_map && !dump_all(args.dump.as_deref()) && dumps.iter().any(|d| d == receiver) {
        return Err(input_error!(
            "--dump: `receiver` is the receiver map, and {} has no [receiver_map] table",
            args.scene.display()
        )
        .into());
    }
    if let Some(n) = dumps.iter().find(|d| named_in(&own, d).is_none() && !dump_all(args.dump.as_deref())) {
        // The pool's technique renders the pool alone: no mesh renderer, no photons.
        if !technique.renders_meshes() {
            let names: Vec<&str> = own.iter().map(|d| d.name).collect();
            let whose = if named_in(render::EYE_DUMPS, n).is_some() { "the mesh renderer" } else { "a mesh technique" };
            return Err(input_error!(
                "--dump: `{n}` is a buffer of {whose}, which `{technique}` does not use (it renders the pool \
                 alone); its buffers: {}",
                names.join(", ")
            )
            .into());
        }
        if let Some(r) = Refraction::ALL.iter().find(|r| named_in(render::dumps::refraction_dumps(**r), n).is_some()) {
            return Err(input_error!(
                "--dump: `{n}` is a buffer of --refraction {r}, not of `{}`",
                scene.caustics.refraction
            )
            .into());
        }
        if n == caustics::techniques::wyman_nichols2009::settings::PHOTON_GEOMETRY_BUFFERS.name
            && technique.has_photon_buffer()
        {
            return Err(input_error!(
                "--dump: `{n}` is a buffer of --photon-refraction deferred, not of `{}`",
                scene.caustics.photon_refraction
            )
            .into());
        }
        if n == caustics::techniques::shared::settings::PHOTON_FOOTPRINTS.name && technique == Technique::PhotonTrace {
            return Err(input_error!("--dump: `{n}` is a buffer of `photon-trace` with --differentials true").into());
        }
        if technique == Technique::PhotonTrace {
            // Screen-space photon mapping has the eye's caustic and no caustic map; the other
            // deposits the reverse.
            let eye = caustics::techniques::wyman_davis2006::settings::EYE_CAUSTIC.name;
            let needs = if n == eye { "screen-space" } else { "caustic-map or receiver-map" };
            if n == eye || n == caustics::techniques::shared::settings::CAUSTIC_MAP.name {
                return Err(input_error!(
                    "--dump: `{n}` is a buffer of `photon-trace` with --deposit {needs}, not with --deposit {}",
                    scene.caustics.deposit
                )
                .into());
            }
        }
        if named_in(&technique.dumps(), n).is_some() {
            return Err(input_error!(
                "--dump: `{n}` is a buffer of `{technique}` with --space {}, not with --space {}",
                if scene.caustics.eye_space() { "light" } else { "eye" },
                scene.caustics.space
            )
            .into());
        }
        let having: Vec<Technique> =
            Technique::ALL.iter().copied().filter(|t| named_in(&t.dumps(), n).is_some()).collect();
        let owners: Vec<&str> = having.iter().map(|t| t.name()).collect();
        // (`technique` renders meshes here: the pool's returned above.)
        if scene.pool.is_none() && having.iter().all(|t| !t.renders_meshes()) {
            return Err(input_error!(
                "--dump: `{n}` is a buffer of technique {}, which renders pool scenes ([pool]) only, and {} is a \
                 mesh scene",
                owners.join(", "),
                args.scene.display()
            )
            .into());
        }
        return Err(input_error!(
            "--dump: `{n}` is a buffer of technique {}, not of `{technique}`; add --technique {}",
            owners.join(", "),
            owners.join("|")
        )
        .into());
    }
    dumps.retain(|d| named_in(&own, d).is_some());
    // Before the device: an --out that cannot become a directory fails now, not after the render.
    let out = OutputDir::create(&args.out).context("--out")?;
    let ctx = Context::new(&opts).context("opening the Vulkan device")?;
    *validation = Some(ctx.validation_log());
    check_sizes(&scene, ctx.info())?;
    ctx.record_frame_graphs(args.graph);
    render::check_device(&ctx, &scene)?;

    let shaders = ShaderCompiler::new(&render::shader_root()).context("creating the shader compiler")?;
    let frame_mode = render::FrameMode::parse(&args.frame_mode)
        .ok_or_else(|| input_error!("--frame-mode: `{}`: expected per-pass or throughput", args.frame_mode))?;
    let req = RenderRequest { dumps, frames: args.frames, frame_mode };
    let rendered = render::render(&ctx, &shaders, &scene, &req)
        .with_context(|| format!("rendering {} with technique `{technique}`", args.scene.display()))?;

    // What made these images, in each EXR header (tev and `exrheader` show it).
    let header = [
        (header::TECHNIQUE, technique.to_string()),
        (header::PHOTONS, photons_header(&scene, rendered.counts.photons_emitted)),
        (header::PHOTON_BUFFER, photon_buffer_header(&scene)),
        (header::FRESNEL, scene.caustics.fresnel.to_string()),
        (header::COMMIT, bench::meta::commit()),
        (header::DEVICE, format!("{} ({})", ctx.info().name, ctx.info().driver_info)),
        (header::SCENE, args.scene.display().to_string()),
    ];
    let mut written = write_final_images(&out, &rendered.final_image, &header, scene.render.exposure)?;
    for (dump, image) in &rendered.dumps {
        let file = format!("{}.exr", dump.name);
        image_io::write_exr_with(&out.path(&file), image, &dump.header(&header))?;
        written.push(file);
        if [&render::dumps::RECEIVER, &caustics::techniques::trendall_stewart2000::settings::RECEIVER].contains(dump) {
            // To look at without an EXR viewer: E/E0 from black (0) through grey (1) to white (2).
            let ratio = receiver_ratio(image)?;
            image_io::write_png_grey(&out.path(RECEIVER_PNG), image.width, image.height, &ratio, 2.0)?;
            written.push(RECEIVER_PNG.to_string());
        }
    }
    let mut timings = Timings::new(
        ctx.info(),
        &scene.caustics,
        rendered.counts.photons_emitted,
        &args.scene,
        ctx.validation_enabled(),
        frame_mode.name(),
        &rendered.frames,
    );
    timings.counts = Some(rendered.counts.clone());
    timings.host_frame_ms = rendered.host_ms.clone();
    let json = serde_json::to_string_pretty(&timings).context("serialising timings.json")?;
    image_io::write_file_atomically(&out.path("timings.json"), json.as_bytes())?;
    written.push("timings.json".to_string());
    let graph = rendered.frames.last().map(|f| f.graph.as_slice()).unwrap_or_default();
    if args.graph {
        let title = format!("{} · {technique}", args.scene.display());
        image_io::write_file_atomically(&out.path(GRAPH_TXT), render::graph::text(graph).as_bytes())?;
        image_io::write_file_atomically(&out.path(GRAPH_DOT), render::graph::dot(graph, &title).as_bytes())?;
        written.extend([GRAPH_TXT.to_string(), GRAPH_DOT.to_string()]);
    }
    let final_dir = out.final_dir().to_path_buf();
    out.commit()?;
    // Dumps an earlier render left in the same folder would read as this run's: remove the
    // buffers this run did not write (only names causticlab writes; nothing else is touched).
    let ours = [RECEIVER_PNG, GRAPH_TXT, GRAPH_DOT].map(String::from);
    for file in render::all_dump_names().iter().map(|n| format!("{n}.exr")).chain(ours) {
        if !written.contains(&file) && final_dir.join(&file).is_file() {
            std::fs::remove_file(final_dir.join(&file))
                .with_context(|| format!("removing the stale {}", final_dir.join(&file).display()))?;
        }
    }

    println!(
        "{} on {} ({}), {} {} frame(s), technique `{}`",
        args.scene.display(),
        ctx.info().name,
        ctx.info().driver_info,
        timings.frames,
        timings.frame_mode,
        technique
    );
    if frame_mode != render::FrameMode::PerPass {
        let gpu: Vec<String> =
            timings.per_frame.iter().filter_map(|f| f.gpu_frame_ms).map(|ms| format!("{ms:.3}")).collect();
        println!("GPU ms per frame (whole frames; no pass is timed alone): {}", gpu.join(" "));
    } else if timings.passes.is_empty() {
        println!("(no GPU timings: the device has no timestamps)");
    } else {
        println!("{:<32} {:>10} {:>10} {:>10}", "pass", "median ms", "min ms", "max ms");
        for p in &timings.passes {
            println!("{:<32} {:>10.3} {:>10.3} {:>10.3}", p.name, p.median_ms, p.min_ms, p.max_ms);
        }
        let passes: f64 = timings.passes.iter().map(|p| p.median_ms).sum();
        let host = &timings.host_frame_ms;
        if let Some(median) = bench::stats::median(host) {
            let (min, max) = host.iter().fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), &x| (a.min(x), b.max(x)));
            println!("{:<32} {:>10.3}", "(sum of the pass medians)", passes);
            println!("{:<32} {:>10.3} {:>10.3} {:>10.3}", "(frame, host wall)", median, min, max);
            if passes < 0.5 * median {
                println!(
                    "note: the passes' timestamps account for {passes:.1} of the frame's {median:.1} ms of host \
                     wall time; the rest is untimed work (docs/command_line.md, \"What render's pass table does not time\")"
                );
            }
        }
    }
    if args.graph {
        println!("frame graph (the last frame's passes, what each read and wrote):");
        print!("{}", render::graph::text(graph));
    }
    for f in &written {
        println!("wrote {}", final_dir.join(f).display());
    }
    Ok(())
}

/// The EXR header's photon count: emitted per frame, or what the pool's techniques have instead.
fn photons_header(scene: &Scene, emitted: u64) -> String {
    if scene.caustics.technique.renders_meshes() {
        emitted.to_string()
    } else {
        format!("none (a {0}x{0} height field)", scene.caustics.photons)
    }
}

/// The EXR header's photon buffer: N x N, or none where photons are not a light-space grid.
fn photon_buffer_header(scene: &Scene) -> String {
    match scene.caustics.technique {
        Technique::ShahVertex => {
            format!("none: a photon per mesh vertex ({0}x{0} light-space back faces)", scene.caustics.photons)
        }
        t if !t.renders_meshes() => "none".to_string(),
        _ => format!("{0}x{0}", scene.caustics.photons),
    }
}

/// The receiver map as a PNG, beside receiver.exr.
const RECEIVER_PNG: &str = "receiver.png";
/// The frame graph (`--graph`): text and Graphviz DOT.
const GRAPH_TXT: &str = "graph.txt";
const GRAPH_DOT: &str = "graph.dot";

/// The mean of R, G, B of the receiver map's main layer (E/E0), per texel.
fn receiver_ratio(image: &ImageF32) -> Result<Vec<f32>> {
    let (_, _, rgb) = main_rgb(image)?;
    Ok(rgb.chunks_exact(3).map(|p| (p[0] + p[1] + p[2]) / 3.0).collect())
}

/// Whether `--dump` says `all`.
fn dump_all(arg: Option<&str>) -> bool {
    arg.unwrap_or("").split(',').any(|s| s.trim() == "all")
}

/// `all` or a comma-separated list of dump names ([`render::all_dump_names`]), without
/// duplicates, in the order given.
pub(crate) fn parse_dumps(arg: Option<&str>) -> Result<Vec<String>> {
    let all = render::all_dump_names();
    let mut dumps: Vec<String> = vec![];
    // `--dump ''` (or `--dump ,`) names nothing: said, rather than a render without the dumps asked for.
    if arg.is_some_and(|a| a.split(',').all(|s| s.trim().is_empty())) {
        return Err(input_error!("--dump: no buffer named; give `all` or names such as {}", all[..2].join(",")).into());
    }
    for name in arg.unwrap_or("").split(',').map(str::trim).filter(|s| !s.is_empty()) {
        let names: Vec<&str> = if name == "all" {
            all.clone()
        } else if all.contains(&name) {
            vec![name]
        } else {
            return Err(input_error!("--dump: unknown buffer `{name}`; valid names: all, {}", all.join(", ")).into());
        };
        for n in names {
            if !dumps.iter().any(|d| d == n) {
                dumps.push(n.to_string());
            }
        }
    }
    Ok(dumps)
}

/// Image sizes the scene asks for must fit the device's `maxImageDimension2D`.
fn check_sizes(scene: &Scene, info: &DeviceInfo) -> Result<()> {
    let max = info.max_image_dimension_2d;
    let file = scene.path.display();
    let mut sizes = vec![("camera.resolution", scene.camera.width.max(scene.camera.height))];
    if let Some(r) = &scene.receiver_map {
        sizes.push(("receiver_map.resolution", r.resolution));
    }
    sizes.push(("render.shadow_map_resolution", scene.render.shadow_map_resolution));
    let c = &scene.caustics;
    if !c.technique.renders_meshes() {
        sizes.push(("caustics.photons", c.photons));
    } else if c.technique.has_caustics() {
        sizes.push(("caustics.caustic_map_resolution", c.caustic_map_resolution));
        sizes.push(("caustics.photons", c.photons));
        // The compute splat draws no points.
        let point = c.splat.largest_point(c.splat_radius);
        let (key, what) = match c.splat {
            SplatMode::Fixed => ("caustics.splat_radius", c.splat_radius.to_string()),
            SplatMode::Interpolated => {
                ("caustics.splat_radius", format!("{} with interpolated splats (8 times as wide)", c.splat_radius))
            }
            _ => ("caustics.splat", c.splat.to_string()),
        };
        // Modes that draw points only have no compute splat to suggest.
        let hint = if c.splat.needs().points.is_none() { " (splat_path = \"compute\" draws none)" } else { "" };
        if c.splat_path == SplatPath::Raster && point > info.point_size_range[1] {
            return Err(input_error!(
                "{file}: key `{key}`: {what} needs points of {point} pixels, but `{}` draws points of at most {}{hint}",
                info.name,
                info.point_size_range[1]
            )
            .into());
        }
    }
    for (key, size) in sizes {
        if size == 0 || size > max {
            return Err(input_error!(
                "{file}: key `{key}`: {size} must be between 1 and the device's maxImageDimension2D ({max}) on `{}`",
                info.name
            )
            .into());
        }
    }
    Ok(())
}

/// `final.exr` (the linear image, `header` in its attributes) and `final.png` (tone-mapped at
/// `exposure`) into `out`, as `render` and the viewer's screenshot write them; their names.
pub(crate) fn write_final_images(
    out: &OutputDir,
    image: &ImageF32,
    header: &[(&str, String)],
    exposure: f32,
) -> Result<Vec<String>> {
    image_io::write_exr_with(&out.path("final.exr"), image, header)?;
    let (w, h, rgb) = main_rgb(image)?;
    image_io::write_png_tonemapped(&out.path("final.png"), w, h, &rgb, exposure)?;
    Ok(vec!["final.exr".to_string(), "final.png".to_string()])
}

/// The final image's R, G, B channels, interleaved, for the PNG.
fn main_rgb(image: &ImageF32) -> Result<(u32, u32, Vec<f32>)> {
    let layer = image.layer(None).or_else(|| image.layers.first()).context("the final image has no layers")?;
    let idx = |c: &str| layer.channels.iter().position(|x| x == c);
    let (r, g, b) = match (idx("R"), idx("G"), idx("B")) {
        (Some(r), Some(g), Some(b)) => (r, g, b),
        _ => anyhow::bail!("the final image's main layer has channels {:?}, not R, G, B", layer.channels),
    };
    let nc = layer.channels.len();
    let pixels = image.width as usize * image.height as usize;
    anyhow::ensure!(
        layer.data.len() == pixels * nc,
        "the final image has {} values for {}x{}x{nc}",
        layer.data.len(),
        image.width,
        image.height
    );
    let rgb = layer.data.chunks_exact(nc).flat_map(|p| [p[r], p[g], p[b]]).collect();
    Ok((image.width, image.height, rgb))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn dump_lists() {
        assert_eq!(parse_dumps(None).expect("no dumps"), Vec::<String>::new());
        assert_eq!(parse_dumps(Some("all")).expect("all").len(), render::all_dump_names().len());
        let two = parse_dumps(Some("receiver, shadow_map,receiver")).expect("two names");
        assert_eq!(two, vec!["receiver".to_string(), "shadow_map".to_string()]);
        for empty in ["", " , "] {
            let err = parse_dumps(Some(empty)).err().map(|e| e.to_string()).unwrap_or_default();
            assert!(err.contains("--dump") && err.contains("no buffer named"), "{empty:?}: {err}");
        }
        let err = parse_dumps(Some("receiver,bogus")).err().map(|e| e.to_string()).unwrap_or_default();
        assert!(err.contains("bogus") && err.contains("shadow_map"), "{err}");
    }
}
