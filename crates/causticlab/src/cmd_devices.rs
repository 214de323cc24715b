//! `causticlab devices`: every physical device with the features and limits this project uses.

use crate::cli::GlobalOpts;
use anyhow::{Context as _, Result};
use std::sync::Arc;
use vkcore::{choose_device, driver_label, enumerate_devices, DeviceInfo, Feature, Instance, ValidationLog};

pub fn run(g: &GlobalOpts, validation: &mut Option<Arc<ValidationLog>>) -> Result<()> {
    let opts = crate::context_options(g)?;
    let instance = Instance::new(g.validate, g.validate).context("creating the Vulkan instance")?;
    *validation = Some(instance.validation_log());
    let devices = enumerate_devices(&instance).context("listing Vulkan devices")?;
    if devices.is_empty() {
        println!("no Vulkan devices found (Debian: apt-get install mesa-vulkan-drivers for lavapipe)");
    }
    let default = choose_device(&devices, None).ok();
    let selected = match &g.device {
        Some(q) => Some(choose_device(&devices, Some(q))?),
        None => None,
    };
    for d in &devices {
        let mut marks = vec![];
        if Some(d.index) == default {
            marks.push("default");
        }
        if Some(d.index) == selected {
            marks.push("selected by --device");
        }
        print_device(d, &marks, &opts.without);
    }
    Ok(())
}

fn print_device(d: &DeviceInfo, marks: &[&str], without: &[Feature]) {
    let mark = if marks.is_empty() { String::new() } else { format!("  [{}]", marks.join(", ")) };
    println!("[{}] {}{mark}", d.index, d.name);
    println!("    type                          {}", d.device_type);
    println!("    Vulkan                        {}", d.api_version);
    println!("    driver                        {}", driver_label(d));
    println!("    vendor/device id              {:#06x}/{:#06x}", d.vendor_id, d.device_id);
    println!("    features:");
    for f in Feature::ALL {
        let state = match (d.has(f), without.contains(&f)) {
            (true, true) => "no (--without-feature)",
            (true, false) => "yes",
            (false, _) => "no",
        };
        println!("      {:<36} {state}", f.name());
    }
    if !d.baseline_missing.is_empty() {
        println!("    UNUSABLE: lacks baseline features {}", d.baseline_missing.join(", "));
    }
    if d.quirks.is_empty() {
        println!("    quirks                        none");
    } else {
        println!("    quirks (treated as absent):");
        for q in &d.quirks {
            println!("      {q}");
        }
    }
    println!("    timestampValidBits            {}", d.timestamp_valid_bits);
    println!("    timestampPeriod               {} ns", d.timestamp_period_ns);
    println!(
        "    point size range              {} .. {} (granularity {})",
        d.point_size_range[0], d.point_size_range[1], d.point_size_granularity
    );
    println!("    maxImageDimension2D           {}", d.max_image_dimension_2d);
    println!("    maxImageArrayLayers           {}", d.max_image_array_layers);
    println!("    maxFramebufferLayers          {}", d.max_framebuffer_layers);
    println!("    maxGeometryOutputVertices     {}", d.max_geometry_output_vertices);
    println!("    maxTransformFeedbackBufferSize {}", d.max_transform_feedback_buffer_size);
    println!("    device-local memory           {:.1} MiB", d.device_local_bytes as f64 / (1024.0 * 1024.0));
}
