//! The eye render's intermediate buffers (`--dump`), declared here and read back as EXR layers;
//! the light-space buffers of the photon techniques that the eye render holds too
//! (`receiver_positions`, `caustic_map`; declared by their owner). Deferred refraction's are its
//! stage's (`techniques::stages::EyeRefraction`).

use super::targets::{EyeTargets, Target};
use crate::dump::{layer, Dump, Format, Space, FACES};
use crate::image_io::{ImageF32, Layer};
use crate::techniques::shared::settings::{CAUSTIC_MAP, RECEIVER_POSITIONS};
use crate::techniques::stages::refraction::{DEFERRED_REFRACTION_DUMPS, REFRACTION_LAYERS, REFRACTOR_GEOMETRY};
use crate::techniques::{CausticTargets, PhotonTargets, Refraction};
use anyhow::Result;
use vkcore::Context;

/// The distance to the nearest occluder, per light and cube face.
pub static SHADOW_MAP: Dump = Dump::new(
    "shadow_map",
    module_path!(),
    Space::LightLayers,
    Format::Image,
    &[layer("light<l>_<face>", &["distance"])],
);
/// The diffuse surfaces' radiance from the eye.
pub static BACKGROUND: Dump = Dump::new("background", module_path!(), Space::Eye, Format::Image, &[layer("", RGB)]);
/// Forward refraction's first pass (Wyman 2005): the refractors' nearest back faces.
pub static REFRACTOR_BACK_FACES: Dump = Dump::new(
    "refractor_back_faces",
    module_path!(),
    Space::Eye,
    Format::Image,
    &[layer("", &["NX", "NY", "NZ", "distance"])],
);
/// Forward refraction's radiance of the refractive and reflective surfaces.
pub static REFRACTOR_FRONT_FACES: Dump =
    Dump::new("refractor_front_faces", module_path!(), Space::Eye, Format::Image, &[layer("", &["R", "G", "B", "A"])]);
/// The diffuse surfaces' world position and normal per pixel.
pub static EYE_GBUFFER: Dump = Dump::new(
    "eye_gbuffer",
    module_path!(),
    Space::Eye,
    Format::Image,
    &[layer("position", &["X", "Y", "Z", "hit"]), layer("normal", &["X", "Y", "Z"])],
);
/// The receiver map: E/E0, E0, E and its caustic part on the scene's `[receiver_map]`.
pub static RECEIVER: Dump = Dump::new(
    "receiver",
    module_path!(),
    Space::Eye,
    Format::Image,
    &[layer("", &["R", "G", "B", "E0"]), layer("irradiance", RGB), layer("caustic", RGB)],
);

const RGB: &[&str] = &["R", "G", "B"];

/// The eye render's buffers, with both refractions' (the order of `--dump all`).
pub static EYE_DUMPS: &[&Dump] = &[
    &SHADOW_MAP,
    &BACKGROUND,
    &REFRACTOR_BACK_FACES,
    &REFRACTOR_FRONT_FACES,
    &REFRACTOR_GEOMETRY,
    &REFRACTION_LAYERS,
    &EYE_GBUFFER,
    &RECEIVER,
];

/// The eye render's buffers only forward refraction (Wyman 2005) has.
pub static FORWARD_REFRACTION_DUMPS: &[&Dump] = &[&REFRACTOR_BACK_FACES, &REFRACTOR_FRONT_FACES];

/// The eye render's buffers that only `refraction` has.
pub fn refraction_dumps(refraction: Refraction) -> &'static [&'static Dump] {
    match refraction {
        Refraction::Forward => FORWARD_REFRACTION_DUMPS,
        Refraction::Deferred => DEFERRED_REFRACTION_DUMPS,
    }
}

/// The final linear radiance.
pub fn final_image(ctx: &Context, t: &EyeTargets) -> Result<ImageF32> {
    Ok(t.final_image.as_image(vec![t.final_image.read_layer(ctx, 0, None, &["R", "G", "B"], &[0, 1, 2])?]))
}

/// Every array layer of `t` as layers `light<l>` with the given channels.
fn per_light(ctx: &Context, t: &Target, names: &[&str], pick: &[usize]) -> Result<ImageF32> {
    let layers = (0..t.image.desc.array_layers)
        .map(|l| t.read_layer(ctx, l, Some(&format!("light{l}")), names, pick))
        .collect::<Result<Vec<_>>>()?;
    Ok(t.as_image(layers))
}

/// Every declared dump, owner by owner: the order of `--dump all`, and of every render's dumps
/// (`render::dumps_for` lists each render's in this order; the conformance suite checks it).
pub fn all() -> Vec<&'static Dump> {
    [EYE_DUMPS.to_vec(), crate::techniques::technique_dumps()].concat()
}

/// The distinct names of [`all`] (what `--dump` accepts besides `all`), in its order.
pub fn all_names() -> Vec<&'static str> {
    let mut names: Vec<&'static str> = vec![];
    for d in all() {
        if !names.contains(&d.name) {
            names.push(d.name);
        }
    }
    names
}

/// Every declaration as a Markdown table (`causticlab dumps`, docs/dumps.md's "Every dump"
/// section, which a test keeps equal to it): name, owner, space, format, the techniques that
/// have it under some settings, and its layers and channels.
pub fn markdown_table() -> String {
    use crate::techniques::Technique;
    let mut out = String::from("| name | declared in | space | format | techniques | layers and channels |\n");
    out.push_str("|---|---|---|---|---|---|\n");
    let mesh: Vec<Technique> = Technique::ALL.iter().copied().filter(|t| t.renders_meshes()).collect();
    for d in all() {
        let having: Vec<Technique> =
            Technique::ALL.iter().copied().filter(|&t| super::dumps_of(t).contains(&d)).collect();
        let techniques = if having == mesh {
            "every mesh technique".to_string()
        } else {
            having.iter().map(|t| format!("`{}`", t.name())).collect::<Vec<_>>().join(", ")
        };
        let owner = d.owner.strip_prefix("caustics::").unwrap_or(d.owner);
        out.push_str(&format!(
            "| `{}` | `{owner}` | {:?} | {:?} | {techniques} | {} |\n",
            d.name,
            d.space,
            d.format,
            d.layers_markdown()
        ));
    }
    out
}

/// The dump called `name` that a render with `settings` has (None: it has none of that name).
pub fn named(name: &str, settings: &crate::techniques::CausticSettings) -> Option<&'static Dump> {
    crate::dump::named_in(&super::dumps_for(settings), name)
}

/// The eye render's buffer `d` (or the receiver positions or caustic map it holds); None if this
/// render has no such buffer (no receiver map, or no caustic technique).
pub fn dump(
    ctx: &Context,
    t: &EyeTargets,
    ct: &CausticTargets,
    photons: Option<&PhotonTargets>,
    d: &'static Dump,
) -> Result<Option<ImageF32>> {
    let rgb = ["R", "G", "B"];
    Ok(Some(match d {
        d if d == &SHADOW_MAP => {
            let mut layers = vec![];
            for l in 0..t.shadow.lights {
                for (f, face) in FACES.iter().enumerate() {
                    let n = format!("light{l}_{face}");
                    layers.push(t.shadow.distance.read_layer(ctx, 6 * l + f as u32, Some(&n), &["distance"], &[0])?);
                }
            }
            t.shadow.distance.as_image(layers)
        }
        d if d == &BACKGROUND => {
            t.background.as_image(vec![t.background.read_layer(ctx, 0, None, &rgb, &[0, 1, 2])?])
        }
        d if d == &EYE_GBUFFER => t.position.as_image(vec![
            t.position.read_layer(ctx, 0, Some("position"), &["X", "Y", "Z", "hit"], &[0, 1, 2, 3])?,
            t.normal.read_layer(ctx, 0, Some("normal"), &["X", "Y", "Z"], &[0, 1, 2])?,
        ]),
        d if d == &REFRACTOR_BACK_FACES => t.back_faces.as_image(vec![t.back_faces.read_layer(
            ctx,
            0,
            None,
            &["NX", "NY", "NZ", "distance"],
            &[0, 1, 2, 3],
        )?]),
        d if d == &REFRACTOR_FRONT_FACES => {
            t.surface.as_image(vec![t.surface.read_layer(ctx, 0, None, &["R", "G", "B", "A"], &[0, 1, 2, 3])?])
        }
        d if d == &RECEIVER => match &t.receiver {
            None => return Ok(None),
            Some((ratio, irradiance, caustic)) => {
                // Main layer: E/E0 per channel and mean E0 (W/m^2); layer `irradiance`: E (W/m^2);
                // layer `caustic`: the caustic part of E (W/m^2).
                let r = ctx.read_image_f32(&ratio.image, 0, 0)?;
                let e = ctx.read_image_f32(&irradiance.image, 0, 0)?;
                let main = r.chunks(4).zip(e.chunks(4)).flat_map(|(a, b)| [a[0], a[1], a[2], b[3]]).collect();
                ratio.as_image(vec![
                    Layer::new(None, &["R", "G", "B", "E0"], main),
                    irradiance.read_layer(ctx, 0, Some("irradiance"), &rgb, &[0, 1, 2])?,
                    caustic.read_layer(ctx, 0, Some("caustic"), &rgb, &[0, 1, 2])?,
                ])
            }
        },
        // Light-space buffers of the caustic techniques.
        d if (d == &RECEIVER_POSITIONS || d == &CAUSTIC_MAP) && photons.is_none() => return Ok(None),
        d if d == &RECEIVER_POSITIONS => {
            per_light(ctx, &ct.receiver_positions, &["X", "Y", "Z", "hit"], &[0, 1, 2, 3])?
        }
        d if d == &CAUSTIC_MAP && ct.levels > 1 => {
            // The multi-resolution map: level i of light l in layer 4l + i, its splats in the
            // layer's corner of (M / 2^i)^2 texels (Wyman 2008 Sec. 3.3); interpolated splats:
            // radius splat_radius 2^i in layer 4l + i, full resolution (Fig. 7).
            let t = &ct.caustic_map;
            let layers = (0..t.image.desc.array_layers)
                .map(|i| {
                    let name = format!("light{}_level{}", i / ct.levels, i % ct.levels);
                    t.read_layer(ctx, i, Some(&name), &["R", "G", "B", "photons"], &[0, 1, 2, 3])
                })
                .collect::<Result<Vec<_>>>()?;
            t.as_image(layers)
        }
        d if d == &CAUSTIC_MAP => per_light(ctx, &ct.caustic_map, &["R", "G", "B", "photons"], &[0, 1, 2, 3])?,
        other => anyhow::bail!("the eye render has no buffer `{other}`"),
    }))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::techniques::CausticSettings;

    /// The names docs/dumps.md's tables describe (the first cell of each row).
    fn documented() -> Vec<String> {
        let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../../docs/dumps.md");
        let text = std::fs::read_to_string(path).expect("docs/dumps.md");
        let mut names: Vec<String> = vec![];
        for line in text.lines().filter(|l| l.starts_with("| `")) {
            let name = line.split('`').nth(1).expect("a name").to_string();
            if !names.contains(&name) {
                names.push(name);
            }
        }
        names
    }

    #[test]
    fn docs_every_dump_table_is_the_declarations() {
        let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../../docs/dumps.md");
        let text = std::fs::read_to_string(path).expect("docs/dumps.md");
        let begin = "<!-- begin: `causticlab dumps`";
        let start = text.find(begin).expect("docs/dumps.md has the generated table's begin marker");
        let start = start + text[start..].find('\n').expect("a line after the marker") + 1;
        let end = text.find("<!-- end: `causticlab dumps` -->").expect("and its end marker");
        assert_eq!(
            &text[start..end],
            markdown_table(),
            "docs/dumps.md's \"Every dump\" table differs from the declarations: paste `causticlab dumps` there"
        );
    }

    #[test]
    fn a_layer_declared_for_every_file_is_one_every_file_has() {
        // A layer only some files have is conditional, or `Dump::check` refuses the others (the
        // conformance suite reads every dump of every registry row through it).
        let every = |d: &Dump| d.layers.iter().filter(|l| l.when.is_none()).map(|l| l.name).collect::<Vec<_>>();
        assert_eq!(every(&CAUSTIC_MAP), Vec::<&str>::new(), "one level or several: neither is every file's");
        for d in all() {
            assert!(!d.layers.is_empty(), "`{d}` declares no layers");
            for l in d.layers {
                assert!(!l.channels.is_empty(), "`{d}`'s layer `{}` declares no channels", l.name);
            }
        }
    }

    #[test]
    fn docs_describe_every_declared_dump_and_no_other() {
        let docs = documented();
        for name in all_names() {
            assert!(docs.iter().any(|d| d == name), "docs/dumps.md does not describe `{name}`");
        }
        for d in &docs {
            assert!(all_names().contains(&d.as_str()), "docs/dumps.md describes `{d}`, which nothing declares");
        }
    }

    #[test]
    fn a_dump_is_its_declaration_not_its_name() {
        let pool_technique = crate::techniques::Technique::PoolConvolution;
        // The pool's own declaration, found by its owner (not by the lookup under test).
        let pool_receiver =
            all().into_iter().find(|d| d.name == "receiver" && d.owner.contains("trendall_stewart2000"));
        let pool_receiver_dump = pool_receiver.expect("the pool declares a receiver map");
        let eye = &RECEIVER;
        assert_eq!(eye.name, pool_receiver_dump.name);
        assert!(eye != pool_receiver_dump && eye == &RECEIVER);
        assert!(eye.owner.ends_with("render::dumps") && pool_receiver_dump.owner.contains("trendall_stewart2000"));
        // Each render reads a name as the one declaration it has.
        let pool = CausticSettings { technique: pool_technique, ..Default::default() };
        assert!(named("receiver", &pool) == Some(pool_receiver_dump));
        assert!(named("receiver", &CausticSettings::default()) == Some(eye));
        assert!(named("hierarchy", &CausticSettings::default()).is_none());
    }
}
