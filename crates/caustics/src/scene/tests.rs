//! Loader tests: error messages (file + key), transforms, defaults.

use super::*;
use crate::error::InputError;
use crate::scratch::ScratchDir;

/// A fresh temp directory for one test, removed on drop.
fn temp_dir() -> ScratchDir {
    ScratchDir::new("causticlab-scene", "loader")
}

const BASE: &str = r#"
[camera]
eye = [0.0, 2.0, 5.0]
target = [0.0, 0.0, 0.0]
fov_y = 40.0
resolution = [64, 48]

[[lights]]
type = "point"
position = [0.0, 5.0, 0.0]
intensity = [50.0, 50.0, 50.0]

[materials.floor]
type = "diffuse"
albedo = [0.5, 0.5, 0.5]

[materials.glass]
type = "refractive"
ior = 1.5

[[objects]]
shape = "plane"
size = [4.0, 4.0]
material = "floor"
"#;

fn load_text(name: &str, text: &str) -> anyhow::Result<Scene> {
    let dir = temp_dir();
    let path = dir.join(name);
    std::fs::write(&path, text).unwrap();
    Scene::load_with_search_path(&path, &ModelSearchPath { dirs: vec![dir.to_path_buf(), dir.join("more")] })
}

/// Loads `text`, expects an `InputError` whose message names the file and contains every
/// one of `needles`.
fn expect_error(name: &str, text: &str, needles: &[&str]) -> String {
    let err = match load_text(name, text) {
        Ok(_) => panic!("{name}: loaded without error"),
        Err(e) => e,
    };
    let input = err.downcast_ref::<InputError>().unwrap_or_else(|| panic!("{name}: not an InputError: {err:#}"));
    let msg = input.0.clone();
    assert!(msg.contains(name), "message does not name the file {name}: {msg}");
    for n in needles {
        assert!(msg.contains(n), "message lacks {n:?}: {msg}");
    }
    msg
}

#[test]
fn base_scene_loads_with_defaults() {
    let s = load_text("base.toml", BASE).unwrap();
    assert_eq!(s.objects.len(), 1);
    assert_eq!(s.objects[0].name, "plane0");
    assert_eq!(s.camera.up, Vec3::Y);
    assert_eq!((s.camera.width, s.camera.height), (64, 48));
    assert_eq!(s.render, RenderSettings { shadow_map_resolution: 1024, exposure: 1.0, background: Vec3::ZERO });
    assert!(s.receiver_map.is_none());
    // Materials sorted by name; the refractive default transmission is white.
    assert_eq!(s.materials[1].name, "glass");
    assert_eq!(s.materials[1].kind, MaterialKind::Refractive { ior: Vec3::splat(1.5), transmission: Vec3::ONE });
    assert_eq!(s.material_of(&s.objects[0]).name, "floor");
    assert_eq!(s.triangle_count(), 2);
}

#[test]
fn unknown_key_is_named() {
    let text = BASE.replace("fov_y = 40.0", "fov_y = 40.0\nfocal = 3.0");
    expect_error("unknown.toml", &text, &["camera.focal", "focal"]);
    let text = format!("{BASE}\n[[objects]]\nshape = \"box\"\nsize = [1,1,1]\nmaterial = \"glass\"\ncolour = 1\n");
    expect_error("unknown2.toml", &text, &["objects[1].colour"]);
}

#[test]
fn wrong_type_is_named() {
    let text = BASE.replace("fov_y = 40.0", "fov_y = \"wide\"");
    expect_error("type.toml", &text, &["camera.fov_y", "line 5"]);
    let text = BASE.replace("type = \"point\"", "type = \"area\"");
    expect_error("lighttype.toml", &text, &["lights[0].type", "area"]);
}

#[test]
fn syntax_error_names_the_line() {
    let text = BASE.replace("fov_y = 40.0", "fov_y = = 40.0");
    expect_error("syntax.toml", &text, &["line 5", "syntax"]);
}

#[test]
fn missing_file_is_an_input_error() {
    let dir = temp_dir();
    let path = dir.join("nope.toml");
    let err = Scene::load(&path).unwrap_err();
    let msg = err.downcast_ref::<InputError>().expect("InputError").0.clone();
    assert!(msg.contains("nope.toml"), "{msg}");
}

#[test]
fn resolution_out_of_range() {
    expect_error("res0.toml", &BASE.replace("[64, 48]", "[0, 48]"), &["camera.resolution", "16384", "got 0"]);
    expect_error("resbig.toml", &BASE.replace("[64, 48]", "[64, 100000]"), &["camera.resolution", "100000"]);
    let text = format!("{BASE}\n[receiver_map]\nx_range = [-1, 1]\nz_range = [-1, 1]\nresolution = 0\n");
    expect_error("rmap.toml", &text, &["receiver_map.resolution"]);
    let text = format!("{BASE}\n[render]\nshadow_map_resolution = 20000\n");
    expect_error("smap.toml", &text, &["render.shadow_map_resolution"]);
}

#[test]
fn unknown_material_is_named() {
    expect_error(
        "mat.toml",
        &BASE.replace("material = \"floor\"", "material = \"flor\""),
        &["objects[0].material", "flor", "floor, glass"],
    );
}

#[test]
fn absurd_subdivisions() {
    let text =
        format!("{BASE}\n[[objects]]\nshape = \"icosphere\"\nradius = 1\nsubdivisions = 9\nmaterial = \"glass\"\n");
    expect_error("subdiv.toml", &text, &["objects[1].subdivisions", "9"]);
}

#[test]
fn missing_obj_lists_search_dirs() {
    let text = format!("{BASE}\n[[objects]]\nshape = \"obj\"\nfile = \"nothere.obj\"\nmaterial = \"glass\"\n");
    let msg = expect_error("noobj.toml", &text, &["objects[1].file", "nothere.obj", "searched"]);
    assert!(msg.contains("causticlab-scene-") && msg.contains("more"), "{msg}");
}

#[test]
fn malformed_obj_is_named() {
    let dir = temp_dir();
    std::fs::write(dir.join("bad.obj"), "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 9\n").unwrap();
    std::fs::write(dir.join("empty.obj"), "# no faces\nv 0 0 0\n").unwrap();
    for obj in ["bad.obj", "empty.obj"] {
        let text = format!("{BASE}\n[[objects]]\nshape = \"obj\"\nfile = \"{obj}\"\nmaterial = \"glass\"\n");
        let path = dir.join("malformed.toml");
        std::fs::write(&path, text).unwrap();
        let err = Scene::load(&path).unwrap_err();
        let msg = err.downcast_ref::<InputError>().expect("InputError").0.clone();
        for n in ["malformed.toml", "objects[1].file", obj, "malformed OBJ"] {
            assert!(msg.contains(n), "lacks {n}: {msg}");
        }
    }
}

/// A user's own copy of a shared model loads, and the scene knows it is not the listed file;
/// a model the project does not list is loaded as it is.
#[test]
fn a_model_file_is_known_by_its_checksum() {
    let dir = temp_dir();
    let tri = "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n";
    std::fs::write(dir.join("spot.obj"), tri).unwrap();
    std::fs::write(dir.join("mine.obj"), tri).unwrap();
    let text = format!(
        "{BASE}\n[[objects]]\nshape = \"obj\"\nfile = \"spot.obj\"\nmaterial = \"glass\"\n\
         [[objects]]\nshape = \"obj\"\nfile = \"mine.obj\"\nmaterial = \"glass\"\n\
         [[objects]]\nshape = \"obj\"\nfile = \"mine.obj\"\nmaterial = \"glass\"\n"
    );
    let path = dir.join("models.toml");
    std::fs::write(&path, text).unwrap();
    let s = Scene::load(&path).expect("a differing model still loads");
    let models = s.models();
    let names: Vec<&str> = models.iter().map(|m| m.file.as_str()).collect();
    assert_eq!(names, ["mine.obj", "spot.obj"], "each file once");
    let sha = crate::scene::models::sha256_hex(tri.as_bytes());
    assert!(models.iter().all(|m| m.sha256 == sha));
    assert!(models[1].differs() && models[1].expected.as_deref() == Some(crate::scene::models::KNOWN[6].sha256));
    assert!(!models[0].differs() && models[0].expected.is_none());
    assert!(s.objects[0].model.is_none(), "the floor is no model file");
}

#[test]
fn other_invalid_values() {
    let cases: Vec<(String, &[&str])> = vec![
        (BASE.replace("target = [0.0, 0.0, 0.0]", "target = [0.0, 2.0, 5.0]"), &["camera.target"]),
        (BASE.replace("target = [0.0, 0.0, 0.0]", "target = [0.0, 0.0, 5.0]\nup = [0.0, 1.0, 0.0]"), &["camera.up"]),
        (BASE.replace("eye = [0.0, 2.0, 5.0]", "eye = [0.0, nan, 5.0]"), &["camera.eye", "finite"]),
        (BASE.replace("fov_y = 40.0", "fov_y = 180.0"), &["camera.fov_y"]),
        // A target within a millionth of the eye's distance from the origin is the eye.
        (
            BASE.replace("eye = [0.0, 2.0, 5.0]", "eye = [10000.0, 0.0, 0.0]")
                .replace("target = [0.0, 0.0, 0.0]", "target = [10000.005, 0.0, 0.0]"),
            &["camera.target", "must differ"],
        ),
        // A positive setting: zero, negative and infinite are each refused.
        (format!("{BASE}\n[render]\nexposure = 0.0\n"), &["render.exposure", "finite number > 0"]),
        (format!("{BASE}\n[render]\nexposure = -1.0\n"), &["render.exposure", "finite number > 0"]),
        (format!("{BASE}\n[render]\nexposure = inf\n"), &["render.exposure", "finite number > 0"]),
        // A count of the wrong length.
        (
            format!("{BASE}\n[[objects]]\nshape = \"torus\"\nmajor_radius = 1.0\nminor_radius = 0.2\nsegments = [16]\nmaterial = \"glass\"\n"),
            &["objects[1].segments", "2 integers"],
        ),
        (BASE.replace("size = [4.0, 4.0]", "size = [0.0, 4.0]"), &["objects[0].size"]),
        (BASE.replace("size = [4.0, 4.0]", "size = [4.0, 4.0, 1.0]"), &["objects[0].size"]),
        (BASE.replace("size = [4.0, 4.0]", "radius = 1.0"), &["objects[0].radius", "plane"]),
        (BASE.replace("ior = 1.5", "ior = 0.5"), &["materials.glass.ior"]),
        (BASE.replace("ior = 1.5", "ior = [1.5, 1.6]"), &["materials.glass.ior"]),
        (
            BASE.replace("albedo = [0.5, 0.5, 0.5]", "albedo = [0.5, 0.5, 0.5]\nspecular = [1, 1, 1]"),
            &["materials.floor.specular"],
        ),
        (BASE.replace("intensity = [50.0, 50.0, 50.0]", "intensity = [50.0, inf, 50.0]"), &["lights[0].intensity"]),
        // Finite, but its length overflows f32 (a light direction of 3e38 normalises to zero).
        (BASE.replace("position = [0.0, 5.0, 0.0]", "position = [3e38, 5.0, 0.0]"), &["lights[0].position", "1e6"]),
        (BASE.replace("size = [4.0, 4.0]", "size = [3e38, 4.0]"), &["objects[0].size"]),
        // Not zero in f64, zero in the f32 the transform holds.
        (BASE.replace("size = [4.0, 4.0]", "size = [4.0, 4.0]\nscale = [1.0, 1e-50, 1.0]"), &["objects[0].scale"]),
        (BASE.replace("type = \"point\"", "type = \"spot\""), &["lights[0].direction"]),
        (
            BASE.replace("type = \"point\"", "type = \"spot\"\ndirection = [0, -1, 0]\ncone_angle = 95"),
            &["lights[0].cone_angle"],
        ),
        (
            BASE.replace(
                "type = \"point\"",
                "type = \"spot\"\ndirection = [0, -1, 0]\ncone_angle = 30\ntexture = \"gobo.png\"",
            ),
            &["lights[0].texture", "gobo.png"],
        ),
        (BASE.replace("material = \"floor\"", "material = \"floor\"\nscale = 0"), &["objects[0].scale"]),
        (
            BASE.replace(
                "material = \"floor\"",
                "material = \"floor\"\nscale = [1e30, 1, 1]\ntranslate = [1e30, 0, 0]",
            ),
            &["objects[0]"],
        ),
    ];
    for (i, (text, needles)) in cases.iter().enumerate() {
        expect_error(&format!("invalid{i}.toml"), text, needles);
    }
}

/// Each range's edge, from both sides: the value just outside is refused by name, the edge
/// itself (where the range includes it) and the value just inside load.
#[test]
fn range_edges_are_held_from_both_sides() {
    let spot = |angle: &str| {
        BASE.replace("type = \"point\"", &format!("type = \"spot\"\ndirection = [0, -1, 0]\ncone_angle = {angle}"))
    };
    let receiver =
        |x: &str, z: &str| format!("{BASE}\n[receiver_map]\nx_range = {x}\nz_range = {z}\nresolution = 16\n");
    let refused: Vec<(String, &[&str])> = vec![
        // fov_y in (0, 180): zero is no view.
        (BASE.replace("fov_y = 40.0", "fov_y = 0.0"), &["camera.fov_y", "exclusive"]),
        // A spot's half-angle in (0, 90]: zero lights nothing.
        (spot("0.0"), &["lights[0].cone_angle"]),
        (spot("90.01"), &["lights[0].cone_angle"]),
        // A receiver range is [min, max] with min < max: equal or reversed ends are refused,
        // and so is a finite end beyond the coordinate bound.
        (receiver("[1.0, 1.0]", "[-1.0, 1.0]"), &["receiver_map.x_range", "min < max"]),
        (receiver("[-1.0, 1.0]", "[2.0, -2.0]"), &["receiver_map.z_range", "min < max"]),
        (receiver("[-1.0, 2e6]", "[-1.0, 1.0]"), &["receiver_map.x_range", "1e6"]),
    ];
    for (i, (text, needles)) in refused.iter().enumerate() {
        expect_error(&format!("edge{i}.toml"), text, needles);
    }
    let accepted = [
        BASE.replace("fov_y = 40.0", "fov_y = 0.01"),
        BASE.replace("fov_y = 40.0", "fov_y = 179.99"),
        spot("90.0"),
        spot("0.01"),
        receiver("[-1e6, 1e6]", "[0.0, 0.001]"),
    ];
    for (i, text) in accepted.iter().enumerate() {
        if let Err(e) = load_text(&format!("inside{i}.toml"), text) {
            panic!("inside{i}.toml: refused a value inside its range: {e:#}");
        }
    }
}

#[test]
fn no_lights_and_no_objects() {
    let no_lights =
        BASE.replace("[[lights]]\ntype = \"point\"\nposition = [0.0, 5.0, 0.0]\nintensity = [50.0, 50.0, 50.0]\n", "");
    expect_error("nolights.toml", &no_lights, &["lights"]);
    let no_objects = BASE.replace("[[objects]]\nshape = \"plane\"\nsize = [4.0, 4.0]\nmaterial = \"floor\"\n", "");
    expect_error("noobjects.toml", &no_objects, &["objects"]);
    expect_error("nocamera.toml", "", &["camera"]);
}

#[test]
fn transformed_plane_lands_where_expected() {
    // A unit plane (normal +y) rotated 90 degrees about x faces +z; then translated.
    let text = BASE.replace(
        "size = [4.0, 4.0]\nmaterial = \"floor\"",
        "size = [1.0, 1.0]\nrotate = [90.0, 0.0, 0.0]\ntranslate = [1.0, 2.0, 3.0]\nmaterial = \"floor\"",
    );
    let s = load_text("moved.toml", &text).unwrap();
    let m = &s.objects[0].mesh;
    let (lo, hi) = m.bounds();
    assert!((lo - Vec3::new(0.5, 1.5, 3.0)).length() < 1e-5, "{lo}");
    assert!((hi - Vec3::new(1.5, 2.5, 3.0)).length() < 1e-5, "{hi}");
    for n in &m.normals {
        assert!((*n - Vec3::Z).length() < 1e-5, "{n}");
    }
    // Rotation order: X then Y then Z. +y -> (X 90) +z -> (Y 90) +x -> (Z 90) +y.
    let text = BASE.replace("material = \"floor\"", "rotate = [90.0, 90.0, 90.0]\nmaterial = \"floor\"");
    let s = load_text("order.toml", &text).unwrap();
    for n in &s.objects[0].mesh.normals {
        assert!((*n - Vec3::Y).length() < 1e-5, "{n}");
    }
    // Non-uniform scale: normals stay unit and perpendicular to the (scaled) surface.
    let text = format!(
        "{BASE}\n[[objects]]\nshape = \"icosphere\"\nradius = 1\nsubdivisions = 2\nscale = [2, 1, 0.5]\nrotate = [30, 40, 50]\nmaterial = \"glass\"\n"
    );
    let s = load_text("ellipsoid.toml", &text).unwrap();
    let m = &s.objects[1].mesh;
    mesh::tests::assert_unit_normals(m);
    // Analytic ellipsoid normal: gradient of |S^-1 R^T p|^2, i.e. R (S^-2 R^T p).
    let r = glam::Mat3::from_rotation_z(50f32.to_radians())
        * glam::Mat3::from_rotation_y(40f32.to_radians())
        * glam::Mat3::from_rotation_x(30f32.to_radians());
    let s2 = Vec3::new(4.0, 1.0, 0.25);
    for (p, n) in m.positions.iter().zip(&m.normals) {
        let q = r.transpose() * *p;
        assert!(((q / Vec3::new(2.0, 1.0, 0.5)).length() - 1.0).abs() < 1e-5, "{p} off the ellipsoid");
        let expect = (r * (q / s2)).normalize();
        assert!((*n - expect).length() < 1e-4, "{n} vs {expect}");
    }
    for [a, b, c] in m.triangles() {
        let g = (m.positions[b] - m.positions[a]).cross(m.positions[c] - m.positions[a]);
        assert!(g.dot(m.normals[a] + m.normals[b] + m.normals[c]) > 0.0, "facet faces inward");
    }
    let exact = 4.0 / 3.0 * std::f64::consts::PI * 2.0 * 1.0 * 0.5;
    assert!((m.signed_volume() - exact).abs() / exact < 0.05);
}

#[test]
fn obj_fit_scales_and_places() {
    let dir = temp_dir();
    // A 2 x 4 x 1 box-like tetrahedron spanning x 1..3, y 5..9, z 0..1.
    std::fs::write(dir.join("t.obj"), "v 1 5 0\nv 3 5 0\nv 1 9 0\nv 1 5 1\nf 1 3 2\nf 1 2 4\nf 1 4 3\nf 2 3 4\n")
        .unwrap();
    let text = format!(
        "{BASE}\n[[objects]]\nshape = \"obj\"\nfile = \"t.obj\"\nfit_size = 2.0\nfit_origin = \"bottom\"\ntranslate = [0, 1, 0]\nmaterial = \"glass\"\n"
    );
    let path = dir.join("fit.toml");
    std::fs::write(&path, text).unwrap();
    let s = Scene::load(&path).unwrap();
    let o = &s.objects[1];
    assert_eq!(o.name, "obj1");
    let (lo, hi) = o.mesh.bounds();
    // Scale 2/4 = 0.5; bottom centre (2, 5, 0.5) -> origin, then up by 1.
    assert!((lo - Vec3::new(-0.5, 1.0, -0.25)).length() < 1e-5, "{lo}");
    assert!((hi - Vec3::new(0.5, 3.0, 0.25)).length() < 1e-5, "{hi}");
    assert!(o.mesh.signed_volume() > 0.0);
}

/// The object keys' edges and the forms each takes: a size up to twice the coordinate bound,
/// subdivisions up to their maximum, a scale as one number, a scale of 1e12 refused by its key,
/// an OBJ fitted about its centre.
#[test]
fn object_sizes_scales_and_fits_at_their_edges() {
    let obj = |extra: &str| format!("{BASE}\n[[objects]]\n{extra}\nmaterial = \"glass\"\n");
    let loaded = |name: &str, text: &str| load_text(name, text).unwrap_or_else(|e| panic!("{name}: {e:#}"));
    // A plane 1.5e6 wide: within 2 x 1e6 (its half-width is within the coordinate bound).
    let wide = loaded("wide.toml", &obj("shape = \"plane\"\nsize = [1.5e6, 1.0]"));
    let (lo, hi) = wide.objects[1].mesh.bounds();
    assert!((hi.x - lo.x - 1.5e6).abs() < 1.0, "{lo} {hi}");
    expect_error("wider.toml", &obj("shape = \"plane\"\nsize = [2.5e6, 1.0]"), &["objects[1].size"]);
    // Subdivisions up to MAX_SUBDIVISIONS (7), not beyond.
    let fine = loaded("fine.toml", &obj("shape = \"icosphere\"\nradius = 1.0\nsubdivisions = 7"));
    assert_eq!(fine.objects[1].mesh.triangle_count(), 20 * 4usize.pow(7));
    expect_error(
        "finer.toml",
        &obj("shape = \"icosphere\"\nradius = 1.0\nsubdivisions = 8"),
        &["objects[1].subdivisions"],
    );
    // One number scales every axis.
    let twice = loaded("twice.toml", &obj("shape = \"plane\"\nsize = [2.0, 4.0]\nscale = 2.0"));
    let (lo, hi) = twice.objects[1].mesh.bounds();
    assert!((hi - lo - Vec3::new(4.0, 0.0, 8.0)).length() < 1e-5, "{lo} {hi}");
    expect_error(
        "huge.toml",
        &obj("shape = \"plane\"\nsize = [2.0, 4.0]\nscale = 1e12"),
        &["objects[1].scale", "each factor"],
    );
    // An OBJ fitted about the centre of its bounds: x 1..3, y 5..9, z 0..1 -> centred, scale 0.5.
    let dir = temp_dir();
    std::fs::write(dir.join("t.obj"), "v 1 5 0\nv 3 5 0\nv 1 9 0\nv 1 5 1\nf 1 3 2\nf 1 2 4\nf 1 4 3\nf 2 3 4\n")
        .unwrap();
    let path = dir.join("centre.toml");
    std::fs::write(&path, obj("shape = \"obj\"\nfile = \"t.obj\"\nfit_size = 2.0\nfit_origin = \"center\"")).unwrap();
    let s = Scene::load(&path).unwrap();
    let (lo, hi) = s.objects[1].mesh.bounds();
    assert!((lo - Vec3::new(-0.5, -1.0, -0.25)).length() < 1e-5, "{lo}");
    assert!((hi - Vec3::new(0.5, 1.0, 0.25)).length() < 1e-5, "{hi}");
}

#[test]
fn hierarchy_settings_belong_to_hcm() {
    let with = |caustics: &str| format!("{BASE}\n[caustics]\n{caustics}\n");
    // A scene may set hcm's keys and leave the technique to the command line: it loads, and the
    // final settings are checked together.
    let cases: Vec<(&str, &[&str])> = vec![
        ("technique = \"wd-points\"\ncluster = \"all\"", &["caustics.cluster", "--cluster", "hcm", "wd-points"]),
        ("path = \"compute\"", &["caustics.path", "hcm", "none"]),
        ("technique = \"wd-points\"\nsplat = \"varying-single\"", &["caustics.splat", "hcm"]),
        ("technique = \"hcm\"\nvarying_radius = \"beam-area\"", &["caustics.varying_radius", "varying"]),
    ];
    for (i, (text, needles)) in cases.iter().enumerate() {
        let s = load_text(&format!("hcm_only{i}.toml"), &with(text)).expect("a scene's hcm keys load on their own");
        let err = s.caustics.validate_combination("scene.toml", "caustics.").expect_err(text).to_string();
        for n in *needles {
            assert!(err.contains(n), "{text}: `{err}` does not name {n}");
        }
        let mut hcm = s.caustics.clone();
        hcm.technique = crate::techniques::Technique::Hcm;
        if hcm.varying_radius == crate::techniques::wyman2008::VaryingRadius::BeamArea {
            hcm.splat = crate::techniques::wyman2008::SplatMode::VaryingMultires;
        }
        hcm.validate_combination("scene.toml", "caustics.").expect("with technique hcm they belong");
    }
    expect_error(
        "bad_radius.toml",
        &with("technique = \"hcm\"\nsplat = \"varying-multires\"\nvarying_radius = \"area\""),
        &["caustics.varying_radius", "beam-area", "max-distance"],
    );
}

/// A pool scene (Trendall & Stewart 2000): no objects or lights, a `[pool]` instead.
const POOL: &str = r#"
[camera]
eye = [0.0, 1.7, 1.0]
target = [0.0, -0.3, 0.0]
fov_y = 40.0
resolution = [64, 64]

[caustics]
technique = "pool-convolution"

[pool]
side = 1.0
depth = 0.3
albedo = 0.8
ior = 1.333
time = 2.4
light_direction = [0.0, -2.0, 0.0]
scattering = 2000.0
extinction = 0.5

[pool.wave]
amplitude = 0.005
wavelength = 0.1
frequency = 1.25
time_damping = 0.3
distance_damping = 10.0

[[pool.impulses]]
position = [0.3, 0.1]
"#;

#[test]
fn pool_scene_loads_with_defaults() {
    let s = load_text("pool.toml", POOL).unwrap();
    let p = s.pool.expect("a pool");
    assert!(s.objects.is_empty() && s.lights.is_empty());
    assert_eq!(p.light_direction, glam::DVec3::NEG_Y);
    assert_eq!((p.ior_air, p.light_radiance, p.exponent, p.wall_reflections), (1.0, 1.0, 4000.0, true));
    assert_eq!(p.impulses[0].start, 0.0);
    // The faithful path's bounds default to one wave's: A and A (K + beta).
    assert_eq!(p.height_range, 0.005);
    assert!((p.slope_range - 0.005 * (std::f64::consts::TAU / 0.1 + 10.0)).abs() < 1e-12);
}

#[test]
fn pool_keys_and_values_are_checked() {
    expect_error("pool_key.toml", &POOL.replace("depth = 0.3", "depth = 0.3\ndeep = 1"), &["pool.deep", "deep"]);
    expect_error("pool_wave_key.toml", &POOL.replace("amplitude", "amplitud"), &["pool.wave.amplitud"]);
    let text = POOL.replace("position = [0.3, 0.1]", "position = [0.3, 0.1]\nsize = 2");
    expect_error("pool_impulse_key.toml", &text, &["pool.impulses[0].size"]);
    expect_error("pool_depth.toml", &POOL.replace("depth = 0.3", "depth = -0.3"), &["pool.depth", "-0.3"]);
    expect_error("pool_ior.toml", &POOL.replace("ior = 1.333", "ior = 0.9"), &["pool.ior", "ior_air"]);
    let up = POOL.replace("[0.0, -2.0, 0.0]", "[0.0, 1.0, 0.0]");
    expect_error("pool_up.toml", &up, &["pool.light_direction", "downwards"]);
    let out = POOL.replace("[0.3, 0.1]", "[0.7, 0.1]");
    expect_error("pool_outside.toml", &out, &["pool.impulses[0].position", "inside the pool"]);
    let ls = POOL.replace("extinction = 0.5", "extinction = 0.5\nlight_radiance = 2.0");
    expect_error("pool_ls.toml", &ls, &["pool.light_radiance", "between 0 and 1"]);
    let tex = POOL.replace("extinction = 0.5", "extinction = 0.5\nlight_texture = \"nope.png\"");
    expect_error("pool_tex.toml", &tex, &["pool.light_texture", "nope.png"]);
    let wave = POOL.replace("wavelength = 0.1", "wavelength = 0");
    expect_error("pool_wavelength.toml", &wave, &["pool.wave.wavelength"]);
    // Finite but absurd: a NaN render, or Pass 6's kernel offset past the grid (an overflow).
    expect_error("pool_huge.toml", &POOL.replace("amplitude = 0.005", "amplitude = 1e300"), &["pool.wave.amplitude"]);
    expect_error("pool_time.toml", &POOL.replace("time = 2.4", "time = 1e300"), &["pool.time"]);
    expect_error(
        "pool_n.toml",
        &POOL.replace("extinction = 0.5", "extinction = 0.5\nexponent = 1e300"),
        &["pool.exponent"],
    );
    // 30 degrees from straight down refracts to 22: 3 m deep, it lands 1.21 m over, past the 1 m pool.
    let oblique = POOL.replace("[0.0, -2.0, 0.0]", "[0.5, -0.8660254, 0.0]");
    load_text("pool_oblique_ok.toml", &oblique.replace("depth = 0.3", "depth = 2.4")).expect("0.97 m over: inside");
    expect_error("pool_deep.toml", &oblique.replace("depth = 0.3", "depth = 3.0"), &["pool.depth", "1.214 m"]);
}

#[test]
fn a_pool_scene_has_no_objects_lights_or_receiver_map() {
    let lights = format!("{POOL}\n[[lights]]\ntype = \"point\"\nposition = [0, 5, 0]\nintensity = [1, 1, 1]\n");
    expect_error("pool_lights.toml", &lights, &["lights", "pool.light_direction"]);
    let rmap = format!("{POOL}\n[receiver_map]\nx_range = [-1, 1]\nz_range = [-1, 1]\nresolution = 8\n");
    expect_error("pool_rmap.toml", &rmap, &["receiver_map", "height-field grid"]);
    // Without [pool] the usual rules hold.
    let no_pool = POOL[..POOL.find("[caustics]").unwrap()].to_string();
    expect_error("no_pool.toml", &no_pool, &["lights"]);
}

#[test]
fn pool_settings_belong_to_pool_convolution() {
    let text = BASE.to_string() + "\n[caustics]\ntechnique = \"wd-points\"\nprecision = \"unorm8\"\n";
    let s = load_text("precision.toml", &text).unwrap();
    let err = s.caustics.validate_combination("precision.toml", "caustics.").unwrap_err().to_string();
    assert!(err.contains("caustics.precision") && err.contains("pool-convolution"), "{err}");
    expect_error("kernel.toml", &(BASE.to_string() + "\n[caustics]\nkernel = 8\n"), &["caustics.kernel", "odd"]);
    expect_error(
        "precision_bad.toml",
        &(BASE.to_string() + "\n[caustics]\nprecision = \"fp16\"\n"),
        &["precision", "fp16"],
    );
}

#[test]
fn water_errors_name_the_file_and_key() {
    let water = |rest: &str| format!("{BASE}\n[[objects]]\nshape = \"water\"\nmaterial = \"glass\"\n{rest}\n");
    expect_error("nowater.toml", &water("file = \"nothere.toml\""), &["objects[1].file", "nothere.toml", "not found"]);
    expect_error("nofile.toml", &water(""), &["objects[1].file", "required", "pool scene"]);
    expect_error("radius.toml", &water("file = \"p.toml\"\nradius = 1"), &["objects[1].radius", "\"water\""]);
    // A scene beside it with no [pool], and one whose [pool] is broken.
    let dir = temp_dir();
    std::fs::write(dir.join("mesh.toml"), BASE).unwrap();
    let pool = std::fs::read_to_string(
        std::path::PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../../scenes/pool_overhead.toml"),
    )
    .unwrap();
    std::fs::write(dir.join("pool.toml"), &pool).unwrap();
    std::fs::write(dir.join("badpool.toml"), pool.replace("side = 1.0", "side = -1.0")).unwrap();
    let load = |name: &str, rest: &str| {
        let path = dir.join(name);
        std::fs::write(&path, water(rest)).unwrap();
        Scene::load(&path)
    };
    let msg = |r: anyhow::Result<Scene>| match r {
        Ok(_) => panic!("loaded without error"),
        Err(e) => e.downcast_ref::<InputError>().expect("InputError").0.clone(),
    };
    let m = msg(load("w1.toml", "file = \"mesh.toml\""));
    assert!(m.contains("w1.toml") && m.contains("objects[1].file") && m.contains("no [pool]"), "{m}");
    let m = msg(load("w2.toml", "file = \"badpool.toml\""));
    assert!(m.contains("w2.toml") && m.contains("badpool.toml") && m.contains("pool.side"), "{m}");
    for segments in ["0", "5000", "2.5"] {
        let m = msg(load("w3.toml", &format!("file = \"pool.toml\"\nsegments = {segments}")));
        assert!(m.contains("objects[1].segments"), "{m}");
    }
    // A pool scene whose water takes its surface from itself, directly or through another file.
    std::fs::write(dir.join("self.toml"), water("file = \"self.toml\"")).unwrap();
    // The file that closes the loop names its key once, then the loop.
    let m = msg(Scene::load(&dir.join("self.toml")));
    assert!(m.ends_with("key `objects[1].file`: the water would take its surface from itself, in a loop of files: self.toml → self.toml"), "{m}");
    assert_eq!(m.matches("objects[1].file").count(), 1, "{m}");
    std::fs::write(dir.join("a.toml"), water("file = \"b.toml\"")).unwrap();
    std::fs::write(dir.join("b.toml"), water("file = \"a.toml\"")).unwrap();
    let m = msg(Scene::load(&dir.join("a.toml")));
    assert!(
        m.contains("b.toml: key `objects[1].file`") && m.ends_with("loop of files: a.toml → b.toml → a.toml"),
        "{m}"
    );
    assert_eq!(m.matches("objects[1].file").count(), 2, "a.toml's key, then b.toml's: {m}");
    // And a good one: 8² cells, 128 triangles on top, 4 x 8 wall quads and their 32 bottom fans.
    let s = load("w4.toml", "file = \"pool.toml\"\nsegments = 8").expect("a water scene");
    assert_eq!(s.objects[1].mesh.triangle_count(), 128 + 64 + 32);
}
