//! Building one `[[objects]]` entry: shape-specific keys, the mesh, the transform.

use super::load::{Ctx, MAX_COORDINATE, MAX_SUBDIVISIONS};
use super::schema::{self, FitOrigin, Numbers, ShapeType};
use super::{obj, procedural, water, Material, ModelSearchPath, Object};
use glam::{Affine3A, Mat3, Vec3};
use std::path::Path;

pub(super) fn build_object(
    ctx: &Ctx,
    index: usize,
    o: &schema::ObjectDef,
    materials: &[Material],
    search: &ModelSearchPath,
) -> anyhow::Result<Object> {
    let key = format!("objects[{index}]");
    let k = |s: &str| format!("{key}.{s}");
    let material = materials.iter().position(|m| m.name == o.material).ok_or_else(|| {
        let names: Vec<&str> = materials.iter().map(|m| m.name.as_str()).collect();
        ctx.err(
            &k("material"),
            format!(
                "no material named {:?} (defined: {})",
                o.material,
                if names.is_empty() { "none".to_string() } else { names.join(", ") }
            ),
        )
    })?;
    let allowed: &[&str] = match o.shape {
        ShapeType::Plane | ShapeType::Box => &["size"],
        ShapeType::Room => &["size", "open_top"],
        ShapeType::Icosphere => &["radius", "subdivisions"],
        ShapeType::Torus => &["major_radius", "minor_radius", "segments"],
        ShapeType::Ring => &["radius", "height", "thickness", "segments"],
        ShapeType::Octahedron => &["radius"],
        ShapeType::Obj => &["file", "fit_size", "fit_origin"],
        ShapeType::Water => &["file", "segments"],
    };
    if let Some(bad) = o.present_shape_keys().into_iter().find(|f| !allowed.contains(f)) {
        return Err(
            ctx.err(&k(bad), format!("not a key of shape \"{}\" (its keys: {})", o.shape.name(), allowed.join(", ")))
        );
    }
    let need = |v: Option<f32>, field: &str| -> anyhow::Result<f32> {
        let v = v.ok_or_else(|| ctx.err(&k(field), format!("required for shape \"{}\"", o.shape.name())))?;
        ctx.positive(&k(field), v)
    };
    let size = |n: usize| -> anyhow::Result<Vec<f32>> {
        let v =
            o.size.as_ref().ok_or_else(|| ctx.err(&k("size"), format!("required for shape \"{}\"", o.shape.name())))?;
        if v.len() != n || !v.iter().all(|x| x.is_finite() && *x > 0.0 && *x <= 2.0 * MAX_COORDINATE) {
            return Err(ctx.err(
                &k("size"),
                format!("must be {n} numbers > 0 and at most {:e}, got {v:?}", 2.0 * MAX_COORDINATE),
            ));
        }
        Ok(v.clone())
    };
    let mut fit = Affine3A::IDENTITY;
    let mut model = None;
    let mut mesh = match o.shape {
        ShapeType::Plane => {
            let s = size(2)?;
            procedural::plane(s[0], s[1])
        }
        ShapeType::Box => procedural::box_mesh(Vec3::from_slice(&size(3)?)),
        ShapeType::Room => procedural::room(Vec3::from_slice(&size(3)?), o.open_top.unwrap_or(false)),
        ShapeType::Icosphere => {
            let r = need(o.radius, "radius")?;
            let s = o.subdivisions.unwrap_or(4);
            if s > MAX_SUBDIVISIONS {
                return Err(ctx.err(&k("subdivisions"), format!("must be between 0 and {MAX_SUBDIVISIONS}, got {s}")));
            }
            procedural::icosphere(r, s)
        }
        ShapeType::Octahedron => procedural::octahedron(need(o.radius, "radius")?),
        ShapeType::Torus => {
            let (big, small) = (need(o.major_radius, "major_radius")?, need(o.minor_radius, "minor_radius")?);
            if small >= big {
                return Err(
                    ctx.err(&k("minor_radius"), format!("must be smaller than major_radius ({big}), got {small}"))
                );
            }
            let seg = o.segments.clone().unwrap_or(Numbers(vec![64.0, 32.0]));
            let seg = ctx.counts(&k("segments"), &seg, 2, 3, 2048)?;
            procedural::torus(big, small, seg[0], seg[1])
        }
        ShapeType::Ring => {
            let r = need(o.radius, "radius")?;
            let h = need(o.height, "height")?;
            let t = need(o.thickness, "thickness")?;
            let seg = o.segments.clone().unwrap_or(Numbers(vec![128.0]));
            let seg = ctx.counts(&k("segments"), &seg, 1, 3, 65536)?;
            procedural::ring(r, h, t, seg[0])
        }
        ShapeType::Obj => {
            let file = o.file.as_deref().ok_or_else(|| ctx.err(&k("file"), "required for shape \"obj\""))?;
            let path = search.find(file).ok_or_else(|| {
                ctx.err(
                    &k("file"),
                    format!(
                        "model {file:?} not found; searched: {} (add directories with $CAUSTICLAB_MODELS)",
                        search.describe()
                    ),
                )
            })?;
            let bytes = std::fs::read(&path).map_err(|e| ctx.err(&k("file"), format!("{}: {e}", path.display())))?;
            let file = super::models::ModelFile::of(&path, &bytes);
            super::models::warn_once(&file);
            model = Some(file);
            let mesh =
                obj::load_obj_bytes(&bytes).map_err(|e| ctx.err(&k("file"), format!("{}: {e}", path.display())))?;
            let (lo, hi) = mesh.bounds();
            let origin = match o.fit_origin {
                None => Vec3::ZERO,
                Some(FitOrigin::Center) => 0.5 * (lo + hi),
                Some(FitOrigin::Bottom) => Vec3::new(0.5 * (lo.x + hi.x), lo.y, 0.5 * (lo.z + hi.z)),
            };
            let scale = match o.fit_size {
                None => 1.0,
                Some(s) => {
                    let s = ctx.positive(&k("fit_size"), s)?;
                    let extent = (hi - lo).max_element();
                    if extent.partial_cmp(&0.0) != Some(std::cmp::Ordering::Greater) {
                        return Err(
                            ctx.err(&k("fit_size"), format!("{} has zero extent and cannot be fitted", path.display()))
                        );
                    }
                    let scale = s / extent;
                    if !scale.is_normal() {
                        return Err(ctx.err(
                            &k("fit_size"),
                            format!("{} cannot be fitted: its extent {extent} gives the scale {scale}", path.display()),
                        ));
                    }
                    scale
                }
            };
            fit = Affine3A::from_scale(Vec3::splat(scale)) * Affine3A::from_translation(-origin);
            mesh
        }
        ShapeType::Water => {
            let file =
                o.file.as_deref().ok_or_else(|| ctx.err(&k("file"), "required for shape \"water\" (a pool scene)"))?;
            let path = ctx.beside(&k("file"), file, "pool scene")?;
            let pool = load_water_scene(ctx.file, &path)
                .map_err(|e| match e.downcast::<WaterLoop>() {
                    Ok(WaterLoop(files)) => ctx.err(
                        &k("file"),
                        format!("the water would take its surface from itself, in a loop of files: {files}"),
                    ),
                    Err(e) => ctx.err(&k("file"), format!("{e:#}")),
                })?
                .pool
                .ok_or_else(|| {
                    ctx.err(&k("file"), format!("{} has no [pool] to take the water's surface from", path.display()))
                })?;
            let seg = o.segments.clone().unwrap_or(Numbers(vec![256.0]));
            let seg = ctx.counts(&k("segments"), &seg, 1, 1, water::MAX_WATER_SEGMENTS)?;
            water::water(&pool, seg[0])
        }
    };
    let transform = object_transform(ctx, &key, o)? * fit;
    mesh.transform(&transform);
    if !mesh.positions.iter().chain(&mesh.normals).all(|p| p.is_finite()) {
        return Err(ctx.err(&key, "the transformed mesh has non-finite coordinates (absurd scale or translate?)"));
    }
    let name = o.name.clone().unwrap_or_else(|| format!("{}{index}", o.shape.name()));
    Ok(Object { name, mesh, material, model })
}

thread_local! {
    /// The pool scenes being loaded for `water` objects on this thread, outermost first.
    static WATER_FILES: std::cell::RefCell<Vec<std::path::PathBuf>> = const { std::cell::RefCell::new(vec![]) };
}

/// A `water` object whose pool scene leads back to a file being loaded: the files of the
/// loop, from the file it returns to (`a.toml → b.toml → a.toml`, raised in b.toml).
#[derive(Debug)]
struct WaterLoop(String);

impl std::fmt::Display for WaterLoop {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "a loop of pool scenes: {}", self.0)
    }
}

impl std::error::Error for WaterLoop {}

/// Loads the pool scene `path` that a `water` object of the scene file `from` names, refusing
/// one that leads back to a file being loaded, `from` itself included (loading it would
/// recurse until the stack overflows). The error is raised in the file that closes the loop,
/// so that its file and key are named once.
fn load_water_scene(from: &Path, path: &Path) -> anyhow::Result<super::Scene> {
    let canonical = |p: &Path| std::fs::canonicalize(p).unwrap_or_else(|_| p.to_path_buf());
    let (from_id, id) = (canonical(from), canonical(path));
    let stack = WATER_FILES.with(|w| w.borrow().clone());
    if let Some(at) = stack.iter().chain([&from_id]).position(|f| *f == id) {
        let names: Vec<String> = stack.iter().chain([&from_id, &id]).skip(at).map(|f| name_of(f)).collect();
        return Err(WaterLoop(names.join(" → ")).into());
    }
    WATER_FILES.with(|w| w.borrow_mut().push(from_id));
    let scene = super::Scene::load(path);
    WATER_FILES.with(|w| w.borrow_mut().pop());
    scene
}

/// A file's name alone, for a loop's listing (the error's prefix names the full path).
fn name_of(path: &Path) -> String {
    path.file_name().map_or_else(|| path.display().to_string(), |n| n.to_string_lossy().into_owned())
}

/// translate · Rz · Ry · Rx · scale (rotation applied X first, then Y, then Z).
fn object_transform(ctx: &Ctx, key: &str, o: &schema::ObjectDef) -> anyhow::Result<Affine3A> {
    let scale = match &o.scale {
        None => Vec3::ONE,
        Some(s) => {
            let v = match s.0.as_slice() {
                [x] => [*x; 3],
                [x, y, z] => [*x, *y, *z],
                _ => {
                    return Err(
                        ctx.err(&format!("{key}.scale"), format!("must be a number or [x, y, z], got {:?}", s.0))
                    )
                }
            };
            // Checked as the f32 the transform holds: 1e-50 is not zero, its f32 is.
            if !v.iter().all(|x| (*x as f32).is_normal() && x.abs() < 1e12) {
                return Err(ctx.err(
                    &format!("{key}.scale"),
                    format!("each factor must be finite and non-zero (beyond 1e-38 in size), got {v:?}"),
                ));
            }
            Vec3::new(v[0] as f32, v[1] as f32, v[2] as f32)
        }
    };
    let rot = ctx.vec3(&format!("{key}.rotate"), o.rotate.unwrap_or([0.0; 3]))?;
    let translate = ctx.vec3(&format!("{key}.translate"), o.translate.unwrap_or([0.0; 3]))?;
    let r = Mat3::from_rotation_z(rot.z.to_radians())
        * Mat3::from_rotation_y(rot.y.to_radians())
        * Mat3::from_rotation_x(rot.x.to_radians());
    Ok(Affine3A::from_mat3_translation(r * Mat3::from_diagonal(scale), translate))
}
