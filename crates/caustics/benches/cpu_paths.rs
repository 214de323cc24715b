//! Criterion benchmarks of the CPU paths: scene loading, OBJ parsing, BVH build and the exact
//! photon reference (`scripts/criterion.sh` runs them and records the medians under
//! `results/criterion/`; `results/criterion/README.md` says what each one measures).
//!
//! Paths are resolved from `CARGO_MANIFEST_DIR`, so the bench runs from any directory. The
//! Stanford bunny is looked up on the scene's model search path (`../shared/models` beside the
//! repository, or `$CAUSTICLAB_MODELS`); when it is missing, the benchmarks that need it are
//! skipped with a message naming the file and the directories searched.

use caustics::bvh::{Bvh, Triangle};
use caustics::reference::{trace_reference, ReferenceOptions};
use caustics::scene::obj::load_obj;
use caustics::scene::{ModelSearchPath, Scene};
use criterion::measurement::WallTime;
use criterion::{criterion_group, criterion_main, BatchSize, BenchmarkGroup, BenchmarkId, Criterion, Throughput};
use std::hint::black_box;
use std::path::{Path, PathBuf};
use std::sync::OnceLock;
use std::time::Duration;

const SPHERE_SCENE: &str = "sphere_on_plane.toml";
const BUNNY_SCENE: &str = "bunny_in_room.toml";
const BUNNY_MODEL: &str = "stanford-bunny.obj";

/// `scenes/<name>` of this workspace.
fn scene_file(name: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../../scenes").join(name)
}

/// The bunny OBJ as `bunny_in_room.toml` would find it, or `None` when absent (said once).
fn bunny_model() -> Option<&'static Path> {
    static FOUND: OnceLock<Option<PathBuf>> = OnceLock::new();
    FOUND
        .get_or_init(|| {
            let search = ModelSearchPath::for_scene(&scene_file(BUNNY_SCENE));
            let found = search.find(BUNNY_MODEL);
            if found.is_none() {
                eprintln!(
                    "cpu_paths: SKIPPING the bunny benchmarks: model {BUNNY_MODEL} not found; searched: {} \
                     (add its directory to $CAUSTICLAB_MODELS)",
                    search.describe()
                );
            }
            found
        })
        .as_deref()
}

/// Loads `scenes/<name>`, or prints why it could not and returns `None`.
fn load_scene(name: &str) -> Option<Scene> {
    let path = scene_file(name);
    match Scene::load(&path) {
        Ok(scene) => Some(scene),
        Err(e) => {
            eprintln!("cpu_paths: SKIPPING benchmarks of {}: {e:#}", path.display());
            None
        }
    }
}

/// Every object's triangles in one list, tagged as the reference tracer tags them
/// (`object` = object index, `prim` = triangle index within the object).
fn scene_triangles(scene: &Scene) -> Vec<Triangle> {
    let mut tris = Vec::with_capacity(scene.triangle_count());
    for (oi, obj) in scene.objects.iter().enumerate() {
        let p = &obj.mesh.positions;
        for (pi, [a, b, c]) in obj.mesh.triangles().enumerate() {
            tris.push(Triangle { v: [p[a], p[b], p[c]], object: oi as u32, prim: pi as u32 });
        }
    }
    tris
}

/// Small samples (criterion's minimum of 10), so the whole bench takes a few minutes on two cores.
fn configure(group: &mut BenchmarkGroup<'_, WallTime>, measure_s: u64) {
    group.sample_size(10).warm_up_time(Duration::from_millis(500)).measurement_time(Duration::from_secs(measure_s));
}

/// (a) `Scene::load`: TOML parse, procedural meshes or OBJ through the search path, transforms.
fn scene_load(c: &mut Criterion) {
    let mut group = c.benchmark_group("scene_load");
    configure(&mut group, 3);
    for (name, needs_bunny) in [(SPHERE_SCENE, false), (BUNNY_SCENE, true)] {
        if needs_bunny && bunny_model().is_none() {
            continue;
        }
        let Some(scene) = load_scene(name) else { continue };
        group.throughput(Throughput::Elements(scene.triangle_count() as u64));
        let path = scene_file(name);
        let id = name.trim_end_matches(".toml");
        group.bench_function(id, |b| b.iter(|| Scene::load(black_box(&path)).expect("scene loaded once already")));
    }
    group.finish();
}

/// (b) `load_obj` of the Stanford bunny alone (tobj parse, validation, normals); bytes/s.
fn obj_load(c: &mut Criterion) {
    let Some(model) = bunny_model() else { return };
    let bytes = match std::fs::metadata(model) {
        Ok(m) => m.len(),
        Err(e) => {
            eprintln!("cpu_paths: SKIPPING obj_load: cannot stat {}: {e}", model.display());
            return;
        }
    };
    if let Err(e) = load_obj(model) {
        eprintln!("cpu_paths: SKIPPING obj_load: {}: {e}", model.display());
        return;
    }
    let mut group = c.benchmark_group("obj_load");
    configure(&mut group, 3);
    group.throughput(Throughput::Bytes(bytes));
    group.bench_function("stanford_bunny", |b| b.iter(|| load_obj(black_box(model)).expect("loaded once already")));
    group.finish();
}

/// (c) `Bvh::build` (binned SAH) over a scene's triangles, as the reference tracer builds it.
fn bvh_build(c: &mut Criterion) {
    let mut group = c.benchmark_group("bvh_build");
    configure(&mut group, 3);
    for (name, needs_bunny) in [(SPHERE_SCENE, false), (BUNNY_SCENE, true)] {
        if needs_bunny && bunny_model().is_none() {
            continue;
        }
        let Some(scene) = load_scene(name) else { continue };
        let tris = scene_triangles(&scene);
        group.throughput(Throughput::Elements(tris.len() as u64));
        group.bench_function(name.trim_end_matches(".toml"), |b| {
            b.iter_batched(|| tris.clone(), |t| Bvh::build(black_box(t)), BatchSize::LargeInput)
        });
    }
    group.finish();
}

/// (d) `trace_reference` end to end (BVH build, photon tracing on every core, direct
/// irradiance of the receiver grid); photons/s.
fn reference_trace(c: &mut Criterion) {
    let mut group = c.benchmark_group("reference_trace");
    configure(&mut group, 5);
    for (name, side, needs_bunny) in
        [(SPHERE_SCENE, 256u64, false), (SPHERE_SCENE, 512, false), (BUNNY_SCENE, 256, true)]
    {
        if needs_bunny && bunny_model().is_none() {
            continue;
        }
        let Some(scene) = load_scene(name) else { continue };
        let opts = ReferenceOptions { photons: side * side, ..ReferenceOptions::default() };
        if let Err(e) = trace_reference(&scene, &opts) {
            eprintln!("cpu_paths: SKIPPING reference_trace of {name}: {e:#}");
            continue;
        }
        group.throughput(Throughput::Elements(opts.photons));
        let id = BenchmarkId::new(name.trim_end_matches(".toml"), format!("{side}x{side}"));
        group
            .bench_function(id, |b| b.iter(|| trace_reference(black_box(&scene), &opts).expect("traced once already")));
    }
    group.finish();
}

criterion_group!(benches, scene_load, obj_load, bvh_build, reference_trace);
criterion_main!(benches);
