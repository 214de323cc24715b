//! `causticlab soak`: many animated throughput frames of one scene, sampling the process's
//! resident memory, the device memory and the Vulkan objects made (`caustics::render::soak`);
//! prints the samples and how much each drifted after the warm-up, and writes them as CSV.

use crate::cli::{GlobalOpts, SoakArgs};
use anyhow::{Context as _, Result};
use caustics::render::{self, soak};
use caustics::scene::Scene;
use std::fmt::Write as _;
use std::sync::Arc;
use vkcore::{Context, ShaderCompiler, ValidationLog};

pub fn run(g: &GlobalOpts, args: &SoakArgs, validation: &mut Option<Arc<ValidationLog>>) -> Result<()> {
    let opts = crate::context_options(g)?;
    let mut scene = Scene::load(&args.scene)?;
    crate::cli::apply_caustic_flags(&args.caustics, &mut scene.caustics, &args.scene)?;
    if let Some(s) = args.size {
        scene.camera.width = s;
        scene.camera.height = s;
    }
    scene.receiver_map = None;
    if let Some(csv) = &args.csv {
        if csv.is_dir() {
            return Err(caustics::input_error!("--csv: {} is a directory", csv.display()).into());
        }
        if let Some(parent) = csv.parent().filter(|p| !p.as_os_str().is_empty()) {
            caustics::image_io::check_output_dir(parent).context("--csv")?;
            std::fs::create_dir_all(parent).with_context(|| format!("--csv: creating {}", parent.display()))?;
        }
    }
    let ctx = Context::new(&opts).context("opening the Vulkan device")?;
    *validation = Some(ctx.validation_log());
    render::check_device(&ctx, &scene)?;
    let shaders = ShaderCompiler::new(&render::shader_root()).context("creating the shader compiler")?;
    let samples = soak::soak(&ctx, &shaders, &scene, args.frames, args.every, args.period)?;
    let mut csv =
        String::from("frame,seconds,resident_bytes,device_allocated_bytes,device_reserved_bytes,vulkan_objects\n");
    println!(
        "{:>8} {:>9} {:>14} {:>16} {:>16} {:>8}",
        "frame", "seconds", "resident", "device alloc.", "device reserved", "objects"
    );
    for s in &samples {
        println!(
            "{:>8} {:>9.1} {:>14} {:>16} {:>16} {:>8}",
            s.frame, s.seconds, s.resident_bytes, s.device_allocated, s.device_reserved, s.objects
        );
        let _ = writeln!(
            csv,
            "{},{:.3},{},{},{},{}",
            s.frame, s.seconds, s.resident_bytes, s.device_allocated, s.device_reserved, s.objects
        );
    }
    let (resident, device, objects) = soak::drift(&samples, args.after);
    println!(
        "after frame {}: resident memory varies by {:.2}%, device memory by {:.2}%; {objects} Vulkan objects made",
        args.after,
        resident * 100.0,
        device * 100.0
    );
    if let Some(path) = &args.csv {
        caustics::image_io::write_file_atomically(path, csv.as_bytes())?;
        println!("wrote {}", path.display());
    }
    Ok(())
}
