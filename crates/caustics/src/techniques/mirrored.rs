//! Constants written twice, in Rust and in GLSL (`#define`s the shaders share), checked equal:
//! a change on one side alone fails here rather than as a wrong image. (The caustic uniforms'
//! flag bits are checked in `uniforms.rs`, the push constants and bindings by SPIR-V
//! reflection in vkcore.)

#[cfg(test)]
mod tests {
    use crate::gpu::{MATERIAL_DIFFUSE, MATERIAL_REFLECTIVE, MATERIAL_REFRACTIVE, MAX_LIGHTS};
    use crate::techniques::trendall_stewart2000::uniforms::MAX_SOURCES;
    use crate::techniques::wyman2008::entry::{ENTRY_FINAL_SHIFT, ENTRY_LEVEL_SHIFT, ENTRY_Y_SHIFT};
    use crate::techniques::wyman2008::settings::{INTERPOLATED_LEVELS, MULTIRES_LEVELS};
    use crate::techniques::wyman_nichols2009::adaptive::photon::{CELL_LEVEL_SHIFT, CELL_MASK, CELL_Y_SHIFT};
    use crate::techniques::wyman_nichols2009::refractor_layers::MAX_REFRACTORS;
    use crate::techniques::wyman_nichols2009::settings::TOP_PHOTONS;

    fn shader(file: &str) -> String {
        let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../../shaders_glsl").join(file);
        std::fs::read_to_string(&path).unwrap_or_else(|e| panic!("{}: {e}", path.display()))
    }

    /// The value of `#define name value` in `file` (a trailing `u` dropped, hex allowed).
    fn define(file: &str, name: &str) -> u64 {
        let text = shader(file);
        let line = text
            .lines()
            .find(|l| l.split_whitespace().take(2).eq(["#define", name]))
            .unwrap_or_else(|| panic!("{file}: no #define {name}"));
        let v = line.split_whitespace().nth(2).unwrap_or_default().trim_end_matches('u');
        match v.strip_prefix("0x") {
            Some(hex) => u64::from_str_radix(hex, 16),
            None => v.parse(),
        }
        .unwrap_or_else(|e| panic!("{file}: #define {name} {v}: {e}"))
    }

    #[test]
    fn the_shaders_defines_equal_their_rust_twins() {
        let twins: [(&str, &str, u64); 14] = [
            ("common/caustics.glsl", "MULTIRES_LEVELS", MULTIRES_LEVELS as u64),
            ("common/caustics.glsl", "INTERPOLATED_LEVELS", INTERPOLATED_LEVELS as u64),
            ("common/frame.glsl", "MAX_LIGHTS", MAX_LIGHTS as u64),
            ("common/materials.glsl", "MATERIAL_DIFFUSE", MATERIAL_DIFFUSE as u64),
            ("common/materials.glsl", "MATERIAL_REFRACTIVE", MATERIAL_REFRACTIVE as u64),
            ("common/materials.glsl", "MATERIAL_REFLECTIVE", MATERIAL_REFLECTIVE as u64),
            ("trendall_stewart2000/pool.glsl", "MAX_SOURCES", MAX_SOURCES as u64),
            ("wyman2008/entry.glsl", "ENTRY_Y_SHIFT", ENTRY_Y_SHIFT as u64),
            ("wyman2008/entry.glsl", "ENTRY_LEVEL_SHIFT", ENTRY_LEVEL_SHIFT as u64),
            ("wyman2008/entry.glsl", "ENTRY_FINAL_SHIFT", ENTRY_FINAL_SHIFT as u64),
            ("wyman_nichols2009/adaptive_photon.glsl", "CELL_Y_SHIFT", CELL_Y_SHIFT as u64),
            ("wyman_nichols2009/adaptive_photon.glsl", "CELL_LEVEL_SHIFT", CELL_LEVEL_SHIFT as u64),
            ("wyman_nichols2009/adaptive_photon.glsl", "CELL_MASK", CELL_MASK as u64),
            ("wyman_nichols2009/adaptive.glsl", "TOP_PHOTONS", TOP_PHOTONS as u64),
        ];
        let wrong: Vec<String> = twins
            .iter()
            .filter_map(|&(file, name, rust)| {
                let glsl = define(file, name);
                (glsl != rust).then(|| format!("{file}: #define {name} {glsl}, Rust has {rust}"))
            })
            .collect();
        assert!(wrong.is_empty(), "{}", wrong.join("\n"));
    }

    /// `SplatMode::uniform` packs the splat sizes as `common/caustics.glsl`'s SPLAT_* read
    /// them (float defines), and only for the techniques each mode sizes (a mode added since
    /// checks its own, in its paper's tests).
    #[test]
    fn splat_modes_pack_as_the_shaders_read_them() {
        use crate::techniques::wyman2008::settings::SplatMode;
        use crate::techniques::Technique;
        let float = |name: &str| define_float("common/caustics.glsl", name);
        let cases = [
            (SplatMode::Fixed, Technique::Hcm, "SPLAT_FIXED"),
            (SplatMode::VaryingSingle, Technique::Hcm, "SPLAT_VARYING_SINGLE"),
            (SplatMode::VaryingMultires, Technique::Adaptive, "SPLAT_VARYING_MULTIRES"),
            (SplatMode::VaryingMultires, Technique::Shah, "SPLAT_FIXED"),
            (SplatMode::Interpolated, Technique::Hcm, "SPLAT_INTERPOLATED"),
            (SplatMode::Interpolated, Technique::Adaptive, "SPLAT_FIXED"),
        ];
        for (mode, technique, name) in cases {
            assert_eq!(mode.uniform(technique), float(name), "{mode} with {technique}");
        }
    }

    /// The value of `#define name value` in `file` as a float.
    fn define_float(file: &str, name: &str) -> f32 {
        let text = shader(file);
        let line = text.lines().find(|l| l.split_whitespace().take(2).eq(["#define", name]));
        let v = line.and_then(|l| l.split_whitespace().nth(2)).unwrap_or_else(|| panic!("{file}: no #define {name}"));
        v.parse().unwrap_or_else(|e| panic!("{file}: #define {name} {v}: {e}"))
    }

    /// `SplatMode::largest_point`, which `causticlab render` checks against the device's point
    /// sizes, is the widest point `shared/splat_photon.glsl` draws: 2 ceil(r) + 2 pixels, a
    /// varying splat being dropped from r = D 2^L / 2 on (D = MULTIRES_MAX_DIAMETER, L =
    /// MULTIRES_LEVELS) and under D in its level of the multi-resolution map.
    #[test]
    fn the_largest_points_follow_the_splats_drop_rule() {
        use crate::techniques::wyman2008::settings::SplatMode;
        let d = define_float("common/caustics.glsl", "MULTIRES_MAX_DIAMETER");
        let levels = define("common/caustics.glsl", "MULTIRES_LEVELS") as i32;
        let point = |r: f32| 2.0 * r.ceil() + 2.0;
        let dropped = 0.5 * d * 2f32.powi(levels);
        assert_eq!(SplatMode::VaryingSingle.largest_point(1.5), point(dropped));
        assert_eq!(SplatMode::VaryingMultires.largest_point(1.5), point(d));
        assert_eq!(SplatMode::Fixed.largest_point(3.2), point(3.2));
        let widest = 1 << (define("common/caustics.glsl", "INTERPOLATED_LEVELS") - 1);
        assert_eq!(SplatMode::Interpolated.largest_point(1.5), point(1.5 * widest as f32));
    }

    /// The codes the photon buffer's `direction.W` gives a lost photon (`shared/trace_surface.glsl`)
    /// are the ones `docs/dumps.md` tells a reader of the dump.
    #[test]
    fn the_lost_photon_codes_are_the_documented_ones() {
        let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../../docs/dumps.md");
        let docs = std::fs::read_to_string(&path).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
        for (name, why) in
            [("PHOTON_LOST_TIR", "total internal reflection"), ("PHOTON_LOST_NO_RECEIVER", "no receiver found")]
        {
            let code = define_float("shared/trace_surface.glsl", name);
            let text = format!("{code} {why}");
            assert!(docs.contains(&text), "docs/dumps.md does not say `{text}` ({name})");
        }
    }

    #[test]
    fn the_layered_trace_declares_buffers_for_max_refractors() {
        // deferred_photon_layers.glsl declares each object's buffers with LAYER_BINDINGS(k).
        let text = shader("wyman_nichols2009/deferred_photon_layers.glsl");
        let declared = (0..16).filter(|k| text.contains(&format!("LAYER_BINDINGS({k})"))).count();
        assert_eq!(declared, MAX_REFRACTORS);
    }
}
