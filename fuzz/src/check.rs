//! The property every fuzz target checks, shared with the replay test
//! (`crates/causticlab/tests/fuzz_regressions.rs` includes this file): a reader given arbitrary
//! bytes as a user's file returns `Ok` or an error whose message names that file. It must never
//! panic (AFL counts the abort as a crash), hang or allocate without bound (AFL's `-t` and `-m`
//! limits in scripts/fuzz.sh; the replay gives each input a deadline).

use std::path::{Path, PathBuf};

/// One reader of files from users.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Target {
    /// A scene file (`caustics::scene::Scene::load`): TOML with its `[caustics]` and `[pool]`
    /// tables, procedural shapes, models on the search path.
    Scene,
    /// An OBJ model, reached as a user reaches it: named by a scene's `[[object]]`.
    Obj,
    /// A bench config (`bench::config::LoadedConfig::load`) with its layout and paper tables,
    /// in a `bench_configs/` folder beside the shipped `scenes/`.
    BenchConfig,
    /// An OpenEXR file (`caustics::image_io::read_exr`, what `causticlab compare` reads).
    Exr,
    /// The scene reader past the TOML syntax: the bytes choose, key by key, what a shipped
    /// scene holds (kept, removed, an unknown key beside it, or an extreme value: 0, -1, huge,
    /// NaN, infinities, empty, another setting's word), see [`structured_scene`].
    SceneValues,
}

impl Target {
    pub const ALL: [Target; 5] = [Target::Scene, Target::Obj, Target::BenchConfig, Target::Exr, Target::SceneValues];

    pub fn name(self) -> &'static str {
        match self {
            Target::Scene => "scene",
            Target::Obj => "obj",
            Target::BenchConfig => "bench_config",
            Target::Exr => "exr",
            Target::SceneValues => "scene_values",
        }
    }

    /// The file the bytes become, relative to the fuzzing folder.
    pub fn file(self) -> &'static str {
        match self {
            Target::Scene => "scene.toml",
            Target::Obj => "model.obj",
            Target::BenchConfig => "bench_configs/config.toml",
            Target::Exr => "image.exr",
            Target::SceneValues => "scene.toml",
        }
    }
}

/// `sphere_on_plane.toml` with its sphere replaced by `model.obj` beside it.
const OBJ_SCENE: &str = include_str!("obj_scene.toml");

/// Makes the folder a target reads its files in (under `root`, which must exist): the shipped
/// `scenes/` linked in for bench configs, the scene that names `model.obj`.
pub fn prepare(root: &Path, repo: &Path) -> std::io::Result<PathBuf> {
    std::fs::create_dir_all(root.join("bench_configs"))?;
    let scenes = root.join("scenes");
    if !scenes.exists() {
        std::os::unix::fs::symlink(repo.join("scenes"), &scenes)?;
    }
    std::fs::write(root.join("obj_scene.toml"), OBJ_SCENE)?;
    // A scene's folder's `models/` comes before ../shared/models on the search path: loading
    // the real dragon takes a second, so the fuzzed scenes read a tetrahedron under each
    // shipped model's name (the OBJ reader has its own target) and run hundreds of times faster.
    let models = root.join("models");
    std::fs::create_dir_all(&models)?;
    for name in STAND_IN_MODELS {
        std::fs::write(models.join(name), TETRAHEDRON)?;
    }
    Ok(root.to_path_buf())
}

/// The models the shipped scenes name (`grep -ho '"[^"]*\.obj"' scenes/*.toml`).
pub const STAND_IN_MODELS: [&str; 7] =
    ["beast.obj", "nefertiti.obj", "ogre.obj", "spot.obj", "stanford-bunny.obj", "stanford-dragon.obj", "teapot.obj"];

/// A closed, outward-facing tetrahedron.
const TETRAHEDRON: &str = "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf 1 3 2\nf 1 2 4\nf 1 4 3\nf 2 3 4\n";

/// Writes `bytes` as `target`'s file under `root` (made by [`prepare`]) and reads it. `Err`
/// says how the property failed (a panic is not caught here: it fails the caller).
pub fn check(target: Target, root: &Path, bytes: &[u8]) -> Result<(), String> {
    let path = root.join(target.file());
    let text;
    let bytes = match target {
        Target::SceneValues => {
            text = structured_scene(bytes);
            text.as_bytes()
        }
        _ => bytes,
    };
    std::fs::write(&path, bytes).map_err(|e| format!("writing {}: {e}", path.display()))?;
    // Every error must name the fuzzed file, `model.obj` too (read through the scene naming it).
    let result = match target {
        Target::Scene | Target::SceneValues => caustics::scene::Scene::load(&path).map(drop),
        Target::Obj => caustics::scene::Scene::load(&root.join("obj_scene.toml")).map(drop),
        Target::BenchConfig => bench::config::LoadedConfig::load(&path).map(drop),
        Target::Exr => caustics::image_io::read_exr(&path).map(drop),
    };
    holds(&path, result)
}

/// The property for one reader's result on `file`: `Ok`, or an error naming the file.
pub fn holds(file: &Path, result: anyhow::Result<()>) -> Result<(), String> {
    match result {
        Ok(()) => Ok(()),
        Err(e) => {
            let message = format!("{e:#}");
            let name = file.file_name().and_then(|f| f.to_str()).unwrap_or_default();
            if !name.is_empty() && message.contains(name) {
                Ok(())
            } else {
                Err(format!("the error does not name {name}: {message}"))
            }
        }
    }
}

/// The templates of [`Target::SceneValues`]: a glass sphere on a plane with a `[caustics]` table
/// of adaptive caustic maps' settings, and the pool with its `[pool]` tables.
const SPHERE_ON_PLANE: &str = include_str!("../../scenes/sphere_on_plane.toml");
const CAUSTICS_TABLE: &str = "
[caustics]
technique = \"adaptive\"
photons = 512
splat_radius = 1.5
caustic_map_resolution = 512
iterations = 2
photon_view = \"fitted\"
metric = \"max-error\"
max_level = 4
gbuffer_scale = 0.25
photon_memory_limit = 96
photon_batches = 2
";
const POOL: &str = include_str!("../../scenes/pool.toml");

/// The bytes as choices, 0 once they run out.
struct Choices<'a>(&'a [u8], usize);

impl Choices<'_> {
    fn next(&mut self) -> u8 {
        let b = self.0.get(self.1).copied().unwrap_or(0);
        self.1 += 1;
        b
    }
}

/// Values a user might write where a number, a word or a list belongs.
fn extreme(k: u8) -> toml::Value {
    use toml::Value::*;
    match k % 20 {
        0 => Integer(0),
        1 => Integer(-1),
        2 => Integer(i64::MAX),
        3 => Integer(1 << 32),
        4 => Integer(16385),
        5 => Float(f64::NAN),
        6 => Float(f64::INFINITY),
        7 => Float(f64::NEG_INFINITY),
        8 => Float(-0.0),
        9 => Float(1e300),
        10 => Float(-1e-300),
        11 => String(std::string::String::new()),
        12 => String("é".repeat(3)),
        13 => Boolean(true),
        14 => Array(vec![]),
        15 => Table(toml::Table::new()),
        16 => String("hcm".into()),
        17 => String("compute".into()),
        18 => String("deferred".into()),
        _ => Array(vec![Float(1e-30); 3]),
    }
}

/// Changes `v` as the choices say: in a table each key is kept, changed within, removed, or
/// given an unknown neighbour; an array may lose its tail or repeat its first element; a leaf
/// is kept or replaced by an extreme value.
fn mutate(v: &mut toml::Value, c: &mut Choices, depth: u32) {
    match v {
        toml::Value::Table(t) => {
            let keys: Vec<std::string::String> = t.keys().cloned().collect();
            for key in keys {
                match c.next() % 8 {
                    0 => {
                        t.remove(&key);
                    }
                    1 => {
                        t.insert(format!("{key}_unknown"), toml::Value::Integer(1));
                    }
                    _ => {
                        if let Some(child) = t.get_mut(&key) {
                            mutate(child, c, depth + 1);
                        }
                    }
                }
            }
        }
        toml::Value::Array(a) => match c.next() % 6 {
            0 => a.truncate(a.len() / 2),
            1 if !a.is_empty() && depth < 4 => {
                let first = a[0].clone();
                a.push(first);
            }
            _ => {
                for x in a.iter_mut() {
                    mutate(x, c, depth + 1);
                }
            }
        },
        leaf => {
            let k = c.next();
            if k >= 160 {
                *leaf = extreme(k);
            }
        }
    }
}

/// The scene text [`Target::SceneValues`] reads: a template (the first byte picks it) changed
/// key by key by the bytes that follow. A value TOML cannot write leaves the template as it is.
pub fn structured_scene(bytes: &[u8]) -> String {
    let mut c = Choices(bytes, 0);
    let template = if c.next() % 2 == 0 { format!("{SPHERE_ON_PLANE}{CAUSTICS_TABLE}") } else { POOL.to_string() };
    let Ok(mut doc) = template.parse::<toml::Table>() else { return template };
    let mut value = toml::Value::Table(std::mem::take(&mut doc));
    mutate(&mut value, &mut c, 0);
    toml::to_string(&value).unwrap_or(template)
}
