//! The `flip` metric (issue 51): the mean HDR-FLIP of a cell's final image against the
//! reference final image of its scene (`caustics::final_reference`, what `causticlab reference
//! --final` writes), both at the cell's output size, at [`flip::default_ppd`] pixels per degree,
//! the exposures found from the reference (`caustics::compare::perceptual`, as `causticlab
//! compare` computes it).
//!
//! The reference is the cell's scene (its lights, output size and shadow maps) with the caustic
//! settings of its scene file and the config's `[caustics]` (not the technique entry's: a
//! technique's own lookup or refraction is part of what is measured), and the technique's
//! `fresnel`, as the receiver map's CPU reference takes it; its caustic map is filled by exact
//! photons at refinement [`caustics::final_reference::TABLE_LEVEL`] (`[quality] final_level`). It is rendered once per
//! scene and settings within a run ([`References`]), as the receiver maps' references are
//! traced once. A quick run renders a small one ([`QUICK_BASE`], level 0): a smoke test.

use anyhow::{Context as _, Result};
use caustics::compare::perceptual::final_image_flip;
use caustics::final_reference::{render_final, Base, Refinement, BASE};
use caustics::flip::{self, HdrFlip};
use caustics::image_io::ImageF32;
use caustics::input_error;
use caustics::scene::{CausticSettings, Scene};
use serde::{Deserialize, Serialize};
use std::collections::HashMap;
use vkcore::{Context, ShaderCompiler};

/// Level 0 of a quick run's reference final image: a 128² caustic map and 256² photons
/// (`[quick]`'s 128² output; the receiver map's quick reference traces as many).
pub const QUICK_BASE: Base = Base { caustic_map_resolution: 128, photons: 256 };

/// The photon-trace seed of the reference final image's first frame (`reference --final`'s
/// default).
pub const SEED: u32 = 1;

/// The reference final image a cell's FLIP was measured against.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct ReferenceFinal {
    pub level: u32,
    pub caustic_map_resolution: u32,
    /// The photon buffer's side of each frame (side² photons per light and frame).
    pub photons: u32,
    pub frames: u32,
    /// Gaussian, caustic-map texels.
    pub splat_radius: f32,
    pub seed: u32,
}

impl ReferenceFinal {
    pub fn of(r: &Refinement) -> ReferenceFinal {
        ReferenceFinal {
            level: r.level,
            caustic_map_resolution: r.caustic_map_resolution,
            photons: r.photons,
            frames: r.frames,
            splat_radius: r.splat_radius,
            seed: SEED,
        }
    }

    /// For a sentence: "level 1: a 512² caustic map, 2 × 2048² exact photons per light, ...".
    pub fn described(&self) -> String {
        format!(
            "level {}: a {}² caustic map of {} × {}² exact photons per light (photon-trace, seeds from {}), \
             Gaussian splats of {} texels",
            self.level, self.caustic_map_resolution, self.frames, self.photons, self.seed, self.splat_radius
        )
    }
}

/// A cell's FLIP and what it was computed at, kept in the cell's JSON (`final_flip`).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct FinalFlip {
    pub mean: f64,
    pub ppd: f64,
    pub width: u32,
    pub height: u32,
    pub start_exposure: f64,
    pub stop_exposure: f64,
    pub exposure_count: usize,
    pub reference: ReferenceFinal,
}

impl FinalFlip {
    fn of(f: &HdrFlip, reference: ReferenceFinal) -> FinalFlip {
        FinalFlip {
            mean: f.mean(),
            ppd: f.ppd(),
            width: f.map.width as u32,
            height: f.map.height as u32,
            start_exposure: f.start_exposure,
            stop_exposure: f.stop_exposure,
            exposure_count: f.exposure_count,
            reference,
        }
    }
}

/// HDR-FLIP of the cell's final image `ours` against the reference final image, the exposures
/// found from the reference. Both must be final images (`R, G, B` radiance) of one size.
pub fn flip_of(ours: &ImageF32, reference: &ImageF32, about: ReferenceFinal) -> Result<FinalFlip> {
    let f = final_image_flip(ours, "the cell's final image", reference, "the reference final image")
        .map_err(|e| input_error!("flip: {e}"))?;
    debug_assert_eq!(f.ppd(), flip::default_ppd());
    Ok(FinalFlip::of(&f, about))
}

/// The refinement of the reference final image: `level` of [`BASE`], or of [`QUICK_BASE`] in a
/// quick run.
pub fn refinement(level: u32, quick: bool) -> Result<Refinement> {
    if quick {
        Refinement::at(0, QUICK_BASE)
    } else {
        Refinement::at(level, BASE)
    }
}

/// The scene whose reference final image a cell is measured against: the cell's scene with
/// `shared` (its scene file's caustic settings and the config's `[caustics]`) and the cell's
/// `fresnel`. It keeps the cell's receiver map, whose rectangle frames the caustic map
/// (`caustics::techniques::uniforms`): the reference's caustic map covers what the cell's does,
/// and, the cell keeping its scene's (`Runner::cell_scene`), the image is the one `causticlab
/// reference --final` makes of the scene.
pub fn reference_scene(cell: &Scene, shared: &CausticSettings) -> Result<Scene> {
    if cell.pool.is_some() {
        return Err(input_error!(
            "flip: {} is a pool scene; the reference final image is of mesh scenes",
            cell.path.display()
        )
        .into());
    }
    let mut s = cell.clone();
    s.caustics = shared.clone();
    s.caustics.fresnel = cell.caustics.fresnel;
    Ok(s)
}

/// Reference final images rendered so far in a run, by scene and settings.
#[derive(Default)]
pub struct References {
    images: HashMap<String, ImageF32>,
}

impl References {
    /// The reference final image of `scene` (from [`reference_scene`]) at `r`, rendered the
    /// first time a scene with these settings asks.
    pub fn get(&mut self, ctx: &Context, shaders: &ShaderCompiler, scene: &Scene, r: &Refinement) -> Result<&ImageF32> {
        let key = format!(
            "{:?}|{:?}|{:?}|{:?}|{:?}|{:?}|{:?}",
            scene.path, scene.lights, scene.camera, scene.render, scene.receiver_map, scene.caustics, r
        );
        if !self.images.contains_key(&key) {
            eprintln!(
                "bench: rendering the reference final image of {} ({})",
                scene.path.display(),
                ReferenceFinal::of(r).described()
            );
            let image = render_final(ctx, shaders, scene, r, SEED, |_| {}).with_context(|| {
                format!("rendering the reference final image of {} (level {})", scene.path.display(), r.level)
            })?;
            self.images.insert(key.clone(), image);
        }
        Ok(&self.images[&key])
    }
}

/// Checks `[quality] final_level` (a level the reference final image renders, whether or not a
/// metric reads it) and a config's `flip` metrics: the reference final image is of the scene as
/// loaded, so every path in `[run]` stays still.
pub(crate) fn validate(c: &crate::config::Config, bad: &dyn Fn(&str, String) -> anyhow::Error) -> Result<()> {
    let level = c.quality.final_level;
    if level > caustics::final_reference::MAX_LEVEL {
        return Err(bad(
            "quality.final_level",
            format!(
                "{level}: the reference final image's levels go from 0 to {}",
                caustics::final_reference::MAX_LEVEL
            ),
        ));
    }
    let Some(i) = c.metrics.iter().position(|m| crate::config::is_flip_metric(&m.kind)) else { return Ok(()) };
    let r = &c.run;
    for (key, path) in
        [("run.light_path", &r.light_path), ("run.camera_path", &r.camera_path), ("run.object_path", &r.object_path)]
    {
        if path != "static" {
            return Err(bad(
                key,
                format!(
                    "`{path}`: `flip` (metric[{i}]) compares the final image with the reference final image of the \
                     scene as loaded; it needs every path static"
                ),
            ));
        }
    }
    Ok(())
}

/// The table header's line on a config's `flip` metrics: what the reference is, the sizes and
/// the pixels per degree the cells were measured at (`None` when no cell has a FLIP).
pub fn header_line(results: &crate::results::Results) -> Option<String> {
    let flips: Vec<(&str, &FinalFlip)> =
        results.cells.iter().filter_map(|c| Some((c.cell.scene.as_str(), c.final_flip.as_ref()?))).collect();
    if flips.is_empty() {
        return None;
    }
    let mut sizes: Vec<(String, Vec<String>)> = vec![];
    for (scene, f) in &flips {
        let size = format!("{}×{}", f.width, f.height);
        let scene = crate::plan::scene_label(scene);
        match sizes.iter_mut().find(|(s, _)| *s == size) {
            Some((_, scenes)) if scenes.contains(&scene) => {}
            Some((_, scenes)) => scenes.push(scene),
            None => sizes.push((size, vec![scene])),
        }
    }
    let sizes: Vec<String> =
        sizes.iter().map(|(size, scenes)| format!("{size} pixels ({})", scenes.join(", "))).collect();
    let ppds = crate::format::first_seen(flips.iter().map(|(_, f)| format!("{:.2}", f.ppd)));
    let references = crate::format::first_seen(flips.iter().map(|(_, f)| f.reference.described()));
    Some(format!(
        "- **FLIP:** the mean HDR-FLIP of each cell's final image against the reference final image of its scene \
         (`causticlab reference --final`, {}; the scene file's caustic settings and the config's `[caustics]`, \
         with the technique's `fresnel`), both at the cell's output size, {}, at {} pixels per degree, the \
         exposures found from the reference (docs/flip.md)",
        references.join("; "),
        sizes.join(", "),
        ppds.join(", ")
    ))
}

#[cfg(test)]
mod tests {
    use super::*;
    use caustics::final_reference::TABLE_LEVEL;
    use caustics::flip::{Exposures, Rgb};
    use caustics::image_io::Layer;

    /// A final image: a dim floor with a bright spot of `peak` at column `cx` (rows alike).
    fn final_image(cx: usize, peak: f32) -> ImageF32 {
        let (w, h) = (24usize, 16usize);
        let data = (0..w * h)
            .flat_map(|i| {
                let x = i % w;
                let v = if x.abs_diff(cx) <= 1 { peak } else { 0.2 + 0.01 * x as f32 };
                [v, 0.9 * v, 0.8 * v]
            })
            .collect();
        ImageF32 { width: w as u32, height: h as u32, layers: vec![Layer::new(None, &["R", "G", "B"], data)] }
    }

    fn about() -> ReferenceFinal {
        ReferenceFinal::of(&Refinement::at(TABLE_LEVEL, BASE).expect("the table's level"))
    }

    #[test]
    fn the_flip_is_of_the_final_image_against_the_reference() {
        let (ours, reference) = (final_image(8, 3.0), final_image(12, 6.0));
        let f = flip_of(&ours, &reference, about()).expect("two final images");
        let rgb = |img: &ImageF32| Rgb::from_exr(img).expect("R, G, B");
        let want = flip::hdr(&rgb(&reference), &rgb(&ours), flip::default_ppd(), Exposures::Auto).expect("flip");
        let swapped = flip::hdr(&rgb(&ours), &rgb(&reference), flip::default_ppd(), Exposures::Auto).expect("flip");
        assert_eq!(f.mean, want.mean());
        // The exposures come from the reference: the other way round is another number.
        assert!((f.mean - swapped.mean()).abs() > 1e-4, "{} against {}", f.mean, swapped.mean());
        assert_eq!((f.start_exposure, f.stop_exposure), (want.start_exposure, want.stop_exposure));
        assert_eq!((f.width, f.height, f.ppd), (24, 16, flip::default_ppd()));
        assert!(f.mean > 0.0);
        assert_eq!(flip_of(&reference, &reference, about()).expect("itself").mean, 0.0);
    }

    #[test]
    fn a_receiver_map_or_another_size_is_refused_naming_the_image() {
        let reference = final_image(12, 6.0);
        let mut receiver = final_image(8, 3.0);
        receiver.layers[0] = Layer::new(None, &["R", "G", "B", "E0"], vec![1.0; 24 * 16 * 4]);
        let e = flip_of(&receiver, &reference, about()).unwrap_err().to_string();
        assert!(e.contains("the cell's final image is a receiver map"), "{e}");
        let mut small = final_image(8, 3.0);
        small.width = 12;
        small.height = 32;
        let e = flip_of(&small, &reference, about()).unwrap_err().to_string();
        assert!(e.contains("the cell's final image is 12x32 but the reference final image is 24x16"), "{e}");
        let black = ImageF32 { layers: vec![Layer::new(None, &["R", "G", "B"], vec![0.0; 24 * 16 * 3])], ..reference };
        let e = flip_of(&final_image(8, 3.0), &black, about()).unwrap_err().to_string();
        assert!(e.starts_with("flip: the reference final image (reference): "), "{e}");
        // Two receiver maps are of one kind, but not what `flip` measures.
        let e = flip_of(&receiver, &receiver.clone(), about()).unwrap_err().to_string();
        assert!(e.contains("are receiver maps, not final images"), "{e}");
    }

    #[test]
    fn the_reference_takes_the_scene_files_settings_and_the_cells_fresnel() {
        let p = std::path::PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../../scenes/sphere_on_plane.toml");
        let mut cell = Scene::load(&p).expect("a shipped scene");
        let shared = cell.caustics.clone();
        cell.caustics.technique = "shah".parse().expect("a known name");
        cell.caustics.lookup = "tutorial".parse().expect("a known name");
        cell.caustics.fresnel = !shared.fresnel;
        cell.camera.width = 64;
        let r = reference_scene(&cell, &shared).expect("a mesh scene");
        assert_eq!(r.caustics, CausticSettings { fresnel: !shared.fresnel, ..shared });
        // The receiver map frames the caustic map: the reference keeps the cell's.
        assert!(r.receiver_map.is_some() && r.receiver_map == cell.receiver_map);
        assert_eq!(r.camera.width, 64);
        let level = refinement(TABLE_LEVEL, false).expect("a level");
        assert_eq!((level.caustic_map_resolution, level.photons, level.frames), (512, 2048, 2));
        let quick = refinement(TABLE_LEVEL, true).expect("a level");
        assert_eq!((quick.caustic_map_resolution, quick.photons, quick.frames), (128, 256, 1));
    }
}
