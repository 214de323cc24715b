use super::*;
use crate::scratch::ScratchDir;

/// A fresh directory for one test, removed on drop.
fn temp_dir(tag: &str) -> ScratchDir {
    ScratchDir::new("causticlab-test", tag)
}

fn entries(dir: &Path) -> Vec<String> {
    let mut v: Vec<String> =
        std::fs::read_dir(dir).unwrap().map(|e| e.unwrap().file_name().to_string_lossy().into_owned()).collect();
    v.sort();
    v
}

/// Values that exercise the full f32 range, bit-exactly.
fn tricky(i: usize) -> f32 {
    match i % 7 {
        0 => i as f32 * 0.1,
        1 => -1.0e-38 * i as f32,
        2 => 3.0e38,
        3 => f32::from_bits(0x0000_0001 + i as u32), // denormals
        4 => f32::INFINITY,
        5 => -0.0,
        _ => 1.0 / (i as f32 + 3.0),
    }
}

#[test]
fn exr_round_trip_two_layers_odd_size() {
    let dir = temp_dir("exr");
    let (w, h) = (7u32, 3u32);
    let n = (w * h) as usize;
    let image = ImageF32 {
        width: w,
        height: h,
        layers: vec![
            // Deliberately not in alphabetical order.
            Layer::new(None, &["R", "G", "B"], (0..n * 3).map(tricky).collect()),
            Layer::new(Some("caustic"), &["Z", "X", "Y"], (0..n * 3).map(|i| tricky(i + 5) - 2.0).collect()),
            Layer::new(Some("depth.linear"), &["distance"], (0..n).map(|i| i as f32 * 1.5).collect()),
        ],
    };
    let path = dir.join("out.exr");
    write_exr(&path, &image).unwrap();
    assert_eq!(entries(&dir), vec!["out.exr".to_owned()], "no temp files left behind");
    let back = read_exr(&path).unwrap();
    assert_eq!((back.width, back.height), (w, h));
    assert_eq!(back.layers.len(), 3);
    for (a, b) in image.layers.iter().zip(&back.layers) {
        assert_eq!(a.name, b.name);
        assert_eq!(a.channels, b.channels);
        let abits: Vec<u32> = a.data.iter().map(|v| v.to_bits()).collect();
        let bbits: Vec<u32> = b.data.iter().map(|v| v.to_bits()).collect();
        assert_eq!(abits, bbits, "layer {:?} not bit-exact", a.name);
    }
    // Row 0 is the top row: pixel (x=6, y=0) and (x=0, y=2).
    let main = back.layer(None).unwrap();
    assert_eq!(main.sample(w, 6, 0, 1).to_bits(), tricky(6 * 3 + 1).to_bits());
    assert_eq!(main.sample(w, 0, 2, 2).to_bits(), tricky(14 * 3 + 2).to_bits());

    // NaN survives as NaN; overwriting an existing file works.
    let nan = ImageF32 { width: 1, height: 1, layers: vec![Layer::new(None, &["Y"], vec![f32::NAN])] };
    write_exr(&path, &nan).unwrap();
    let back = read_exr(&path).unwrap();
    assert!(back.layers[0].data[0].is_nan());
    assert_eq!(back.layers[0].channels, vec!["Y".to_owned()]);
}

#[test]
fn exr_written_by_other_tools() {
    // A multi-part file with f16 channels and no order attribute, written with the exr
    // crate directly: layers come back named by the file, channels in R, G, B order.
    use exr::prelude::*;
    let dir = temp_dir("exr-other");
    let path = dir.join("other.exr");
    let size = (4usize, 2usize);
    let ch = |name: &str, v: f32| AnyChannel::new(name, FlatSamples::F16(vec![f16::from_f32(v); 8]));
    let beauty = exr::prelude::Layer::new(
        size,
        LayerAttributes::named("beauty"),
        Encoding::FAST_LOSSLESS,
        AnyChannels::sort(SmallVec::from_vec(vec![ch("B", 3.0), ch("G", 2.0), ch("R", 1.0), ch("A", 0.5)])),
    );
    let aux = exr::prelude::Layer::new(
        size,
        LayerAttributes::named("aux"),
        Encoding::UNCOMPRESSED,
        AnyChannels::sort(SmallVec::from_vec(vec![
            AnyChannel::new("normal.Z", FlatSamples::F32(vec![0.25; 8])),
            AnyChannel::new("normal.X", FlatSamples::F32(vec![-1.0; 8])),
            AnyChannel::new("id", FlatSamples::U32(vec![7; 8])),
        ])),
    );
    Image::from_layers(
        ImageAttributes::new(IntegerBounds::from_dimensions(size)),
        SmallVec::from_vec(vec![beauty, aux]),
    )
    .write()
    .to_file(&path)
    .unwrap();
    let back = read_exr(&path).unwrap();
    assert_eq!((back.width, back.height), (4, 2));
    let names: Vec<Option<&str>> = back.layers.iter().map(|l| l.name.as_deref()).collect();
    assert_eq!(names, vec![Some("beauty"), Some("aux"), Some("aux.normal")]);
    let beauty = back.layer(Some("beauty")).unwrap();
    assert_eq!(beauty.channels, vec!["R", "G", "B", "A"]);
    assert_eq!(&beauty.data[..4], &[1.0, 2.0, 3.0, 0.5]);
    let normal = back.layer(Some("aux.normal")).unwrap();
    assert_eq!(normal.channels, vec!["X", "Z"]);
    assert_eq!(&normal.data[..2], &[-1.0, 0.25]);
    assert_eq!(back.layer(Some("aux")).unwrap().data, vec![7.0; 8]);
}

#[test]
fn exr_rejects_bad_input_without_panicking() {
    let dir = temp_dir("exr-bad");
    let path = dir.join("bad.exr");
    let bad = |layers: Vec<Layer>, w: u32, h: u32| {
        let err = write_exr(&path, &ImageF32 { width: w, height: h, layers }).unwrap_err();
        assert!(format!("{err:#}").contains("writing"), "{err:#}");
    };
    bad(vec![Layer::new(None, &["R", "G", "B"], vec![0.0; 7 * 3 * 3 - 1])], 7, 3);
    bad(vec![Layer::new(None, &["R"], vec![])], 0, 3);
    bad(vec![], 2, 2);
    bad(vec![Layer::new(None, &[], vec![])], 1, 1);
    bad(vec![Layer::new(None, &["R"], vec![0.0]), Layer::new(None, &["R"], vec![0.0])], 1, 1);
    bad(vec![Layer::new(None, &["a.b"], vec![0.0])], 1, 1);
    bad(vec![Layer::new(Some("é"), &["R"], vec![0.0])], 1, 1);
    assert!(entries(&dir).is_empty(), "nothing written on error");
    // Unwritable destination and unreadable input are errors too.
    let missing = dir.join("no/such/dir/x.exr");
    let ok = ImageF32 { width: 1, height: 1, layers: vec![Layer::new(None, &["R"], vec![1.0])] };
    let err = write_exr(&missing, &ok).unwrap_err();
    assert!(format!("{err:#}").contains(&missing.display().to_string()));
    // A missing, a foreign and a truncated file are the user's to fix (exit 2), each named.
    let input = |p: &std::path::Path| {
        let e = read_exr(p).unwrap_err();
        assert!(e.is::<crate::error::InputError>() && format!("{e:#}").contains(&p.display().to_string()), "{e:#}");
        format!("{e:#}")
    };
    assert!(input(&missing).contains("no such file"));
    write_exr(&path, &ok).unwrap();
    let whole = std::fs::read(&path).unwrap();
    std::fs::write(&path, &whole[..whole.len() - 8]).unwrap();
    assert!(input(&path).contains("not a readable OpenEXR file"));
    std::fs::write(&path, b"not an exr").unwrap();
    assert!(input(&path).contains("not a readable OpenEXR file"));
}

/// A header that claims a huge image (its `dataWindow` patched to 1,000,000² pixels) is refused
/// by the header check, naming the file, before the exr crate allocates the pixels.
#[test]
fn exr_header_claiming_a_huge_image_is_refused_before_reading_pixels() {
    let dir = temp_dir("exr-huge");
    let path = dir.join("huge.exr");
    let ok = ImageF32 { width: 2, height: 2, layers: vec![Layer::new(None, &["R"], vec![1.0; 4])] };
    write_exr(&path, &ok).unwrap();
    let mut bytes = std::fs::read(&path).unwrap();
    let key = b"dataWindow\0box2i\0";
    let at = bytes.windows(key.len()).position(|w| w == key).expect("a dataWindow attribute") + key.len();
    // Size (16), then xMin, yMin, xMax, yMax as little-endian i32.
    assert_eq!(&bytes[at..at + 4], &16i32.to_le_bytes());
    for (k, v) in [0i32, 0, 999_999, 999_999].iter().enumerate() {
        bytes[at + 4 + 4 * k..at + 8 + 4 * k].copy_from_slice(&v.to_le_bytes());
    }
    std::fs::write(&path, &bytes).unwrap();
    let err = format!("{:#}", read_exr(&path).unwrap_err());
    assert!(err.contains("huge.exr") && err.contains("1000000x1000000") && err.contains("claims"), "{err}");
}

/// B44, B44A, DWAA and DWAB files are refused by the header check, naming the file and the
/// compression, even well-formed ones (their decoders abort the process on damaged blocks,
/// `fuzz_regressions/exr/`); the lossless ones are read.
#[test]
fn exr_lossy_b44_and_dwa_compression_is_refused_lossless_is_read() {
    use exr::prelude::*;
    let dir = temp_dir("exr-lossy");
    let size = (16usize, 16usize);
    for (name, compression, read) in [
        ("b44", Compression::B44, false),
        ("b44a", Compression::B44A, false),
        ("dwaa", Compression::DWAA(None), false),
        ("dwab", Compression::DWAB(None), false),
        ("piz", Compression::PIZ, true),
        ("zip", Compression::ZIP16, true),
        ("rle", Compression::RLE, true),
    ] {
        let path = dir.join(format!("{name}.exr"));
        let encoding = Encoding { compression, ..Encoding::UNCOMPRESSED };
        let channel = AnyChannel::new("R", FlatSamples::F16(vec![f16::from_f32(0.5); 256]));
        let layer = exr::prelude::Layer::new(
            size,
            LayerAttributes::default(),
            encoding,
            AnyChannels::sort(SmallVec::from_vec(vec![channel])),
        );
        Image::from_layer(layer).write().to_file(&path).unwrap();
        match read_exr(&path) {
            Ok(img) => {
                assert!(read, "{name}: read, should be refused");
                assert_eq!(img.layers[0].data, vec![0.5; 256], "{name}");
            }
            Err(e) => {
                let e = format!("{e:#}");
                assert!(!read, "{name}: refused, should be read: {e}");
                assert!(e.contains(&format!("{name}.exr")) && e.contains(&format!("{name} compression")), "{e}");
            }
        }
    }
}

/// Independent ACES (Narkowicz) + sRGB in f64, for expected codes.
fn expected_code(linear: f64) -> u8 {
    let x = linear;
    let t = ((x * (2.51 * x + 0.03)) / (x * (2.43 * x + 0.59) + 0.14)).clamp(0.0, 1.0);
    let s = if t <= 0.0031308 { 12.92 * t } else { 1.055 * t.powf(1.0 / 2.4) - 0.055 };
    (s * 255.0).round() as u8
}

fn decode_png(path: &Path) -> (u32, u32, Vec<u8>) {
    let decoder = png::Decoder::new(File::open(path).unwrap());
    let mut reader = decoder.read_info().unwrap();
    let mut buf = vec![0; reader.output_buffer_size()];
    let info = reader.next_frame(&mut buf).unwrap();
    assert_eq!(info.color_type, png::ColorType::Rgb);
    assert_eq!(info.bit_depth, png::BitDepth::Eight);
    buf.truncate(info.buffer_size());
    (info.width, info.height, buf)
}

#[test]
fn png_gradient_tonemapped() {
    let dir = temp_dir("png");
    let (w, h) = (64u32, 3u32);
    // Row 0: gradient 0..8 in R=G=B. Row 1: special values. Row 2: constant 0.18.
    let mut rgb = Vec::new();
    for x in 0..w {
        let v = x as f32 / (w - 1) as f32 * 8.0;
        rgb.extend([v, v, v]);
    }
    let specials = [f32::NAN, f32::INFINITY, f32::NEG_INFINITY, -1.0, -0.0, 0.0, f32::MAX];
    for x in 0..w as usize {
        rgb.extend([specials[x % specials.len()], 0.0, 0.0]);
    }
    for _ in 0..w {
        rgb.extend([0.18, 0.5, 0.045]);
    }
    let exposure = 2.0;
    let path = dir.join("img.png");
    write_png_tonemapped(&path, w, h, &rgb, exposure).unwrap();
    assert_eq!(entries(&dir), vec!["img.png".to_owned()]);
    let (dw, dh, px) = decode_png(&path);
    assert_eq!((dw, dh), (w, h));
    assert_eq!(px.len(), (w * h * 3) as usize);
    let at = |x: u32, y: u32, c: u32| px[((y * w + x) * 3 + c) as usize];
    // 0 -> 0, monotonic non-decreasing, strictly brighter at the end.
    assert_eq!(at(0, 0, 0), 0);
    for x in 1..w {
        assert!(at(x, 0, 0) >= at(x - 1, 0, 0));
        assert_eq!(at(x, 0, 0), at(x, 0, 1));
    }
    assert!(at(w - 1, 0, 0) > 240);
    // Known codes, from the independent formula.
    for (c, v) in [0.18f64, 0.5, 0.045].iter().enumerate() {
        let v32 = [0.18f32, 0.5, 0.045][c];
        assert_eq!(at(5, 2, c as u32), expected_code(v32 as f64 * exposure as f64), "channel {c} ({v})");
    }
    // 0.18 * 2 = 0.36 -> ACES 0.3361/0.6673 = 0.5037 -> sRGB 0.7378 -> 188.1 -> 188.
    assert_eq!(expected_code(0.36), 188);
    assert_eq!(at(5, 2, 0), 188);
    // NaN, inf, negatives -> 0; f32::MAX * exposure (overflow) saturates.
    for x in 0..w {
        let s = specials[x as usize % specials.len()];
        let want = if s == f32::MAX { 255 } else { 0 };
        assert_eq!(at(x, 1, 0), want, "special {s}");
    }
}

#[test]
fn png_rejects_bad_input() {
    let dir = temp_dir("png-bad");
    let path = dir.join("x.png");
    assert!(write_png_tonemapped(&path, 2, 2, &[0.0; 11], 1.0).is_err());
    assert!(write_png_tonemapped(&path, 0, 2, &[], 1.0).is_err());
    assert!(write_png_tonemapped(&path, 1, 1, &[0.0; 3], f32::NAN).is_err());
    assert!(write_png_tonemapped(&dir.join("missing/x.png"), 1, 1, &[0.0; 3], 1.0).is_err());
    assert!(entries(&dir).is_empty());
}

#[test]
fn output_dir_commit() {
    let root = temp_dir("outdir");
    let final_dir = root.join("run1");
    let out = OutputDir::create(&final_dir).unwrap();
    let staging = out.staging_dir().to_path_buf();
    assert!(staging.starts_with(&root) && staging.is_dir());
    write_file_atomically(&out.path("a.txt"), b"alpha").unwrap();
    let img = ImageF32 { width: 2, height: 1, layers: vec![Layer::new(None, &["R"], vec![1.0, 2.0])] };
    write_exr(&out.path("b.exr"), &img).unwrap();
    std::fs::create_dir_all(out.path("sub")).unwrap();
    write_file_atomically(&out.path("sub/c.txt"), b"gamma").unwrap();
    assert!(!final_dir.exists(), "nothing visible before commit");
    out.commit().unwrap();
    assert_eq!(entries(&final_dir), vec!["a.txt", "b.exr", "sub"]);
    assert_eq!(std::fs::read(final_dir.join("sub/c.txt")).unwrap(), b"gamma");
    assert_eq!(read_exr(&final_dir.join("b.exr")).unwrap(), img);
    assert!(!staging.exists());
    assert_eq!(entries(&root), vec!["run1"]);

    // Committing into an existing directory: same-named files are replaced, others kept.
    std::fs::write(final_dir.join("keep.txt"), b"keep").unwrap();
    let out = OutputDir::create(&final_dir).unwrap();
    write_file_atomically(&out.path("a.txt"), b"alpha2").unwrap();
    std::fs::create_dir_all(out.path("sub")).unwrap();
    write_file_atomically(&out.path("sub/d.txt"), b"delta").unwrap();
    assert_eq!(std::fs::read(final_dir.join("a.txt")).unwrap(), b"alpha", "old content until commit");
    out.commit().unwrap();
    assert_eq!(std::fs::read(final_dir.join("a.txt")).unwrap(), b"alpha2");
    assert_eq!(std::fs::read(final_dir.join("keep.txt")).unwrap(), b"keep");
    assert_eq!(entries(&final_dir.join("sub")), vec!["c.txt", "d.txt"]);
    assert_eq!(entries(&root), vec!["run1"]);

    // Nested final directory whose parents don't exist yet.
    let nested = root.join("x/y/run2");
    let out = OutputDir::create(&nested).unwrap();
    write_file_atomically(&out.path("f"), b"1").unwrap();
    out.commit().unwrap();
    assert_eq!(entries(&nested), vec!["f"]);
}

#[test]
fn output_dir_dropped_uncommitted_leaves_nothing() {
    let root = temp_dir("outdir-drop");
    let final_dir = root.join("run");
    {
        let out = OutputDir::create(&final_dir).unwrap();
        write_file_atomically(&out.path("a.txt"), b"alpha").unwrap();
        write_png_tonemapped(&out.path("b.png"), 1, 1, &[1.0, 1.0, 1.0], 1.0).unwrap();
        assert!(out.staging_dir().is_dir());
        // Dropped here, as on an early `?` return.
    }
    assert!(!final_dir.exists());
    assert!(entries(&root).is_empty(), "staging removed: {:?}", entries(&root));

    // A panicking run also leaves nothing.
    let fd = final_dir.clone();
    let r = std::panic::catch_unwind(move || {
        let out = OutputDir::create(&fd).unwrap();
        write_file_atomically(&out.path("a.txt"), b"alpha").unwrap();
        panic!("render failed");
    });
    assert!(r.is_err());
    assert!(!final_dir.exists());
    assert!(entries(&root).is_empty());
}

#[test]
#[cfg(target_os = "linux")]
fn output_dir_removes_only_staging_whose_lock_nobody_holds() {
    let root = temp_dir("outdir-stale");
    let staging = |name: &str| root.join(name);
    let lock_of = |d: &std::path::Path| d.with_file_name(format!("{}.lock", d.file_name().unwrap().to_str().unwrap()));
    let dead = staging(".run.partial-4242-0");
    let live = staging(".run.partial-4243-0");
    let unlocked_other = staging(".other.partial-4242-0");
    let no_lock = staging(".run.partial-4244-0");
    let not_staging = staging(".run.partial-4242-x");
    for d in [&dead, &live, &unlocked_other, &no_lock, &not_staging] {
        std::fs::create_dir_all(d).unwrap();
        std::fs::write(d.join("final.exr"), b"half").unwrap();
    }
    for d in [&dead, &live, &unlocked_other, &not_staging] {
        std::fs::write(lock_of(d), b"").unwrap();
    }
    // A live run holds its lock (here, this process through another open file description).
    let held = std::fs::File::open(lock_of(&live)).unwrap();
    held.lock().unwrap();
    let out = OutputDir::create(&root.join("run")).unwrap();
    assert!(!dead.exists() && !lock_of(&dead).exists(), "a killed run's staging directory and lock are removed");
    assert!(live.join("final.exr").is_file(), "a live run's staging directory is kept");
    assert!(unlocked_other.is_dir(), "another output's staging directory is not ours to remove");
    assert!(no_lock.is_dir(), "without a lock file nothing says the run is gone");
    assert!(not_staging.is_dir(), "only `<pid>-<n>` names are staging directories");
    let own_lock = lock_of(out.staging_dir());
    assert!(own_lock.is_file(), "the new run holds a lock beside its staging directory");
    let probe = std::fs::OpenOptions::new().write(true).open(&own_lock).unwrap();
    assert!(probe.try_lock().is_err(), "the new run's lock is held");
    drop(probe);
    drop(out);
    assert!(!own_lock.exists(), "dropping the OutputDir removes its lock file");
    assert!(live.join("final.exr").is_file(), "dropping the new OutputDir removes only its own staging");
}

#[test]
fn output_dir_over_a_file_is_an_input_error_before_anything_is_created() {
    let root = temp_dir("outdir-file");
    let file = root.join("out");
    std::fs::write(&file, b"not a directory").unwrap();
    for target in [file.clone(), file.join("sub")] {
        let err = OutputDir::create(&target).unwrap_err();
        assert!(err.chain().any(|c| c.downcast_ref::<crate::InputError>().is_some()), "{err:#}");
        let msg = format!("{err:#}");
        assert!(msg.contains(&target.display().to_string()) && msg.contains("not a directory"), "{msg}");
    }
    assert_eq!(entries(&root), vec!["out"], "no staging directory beside it");
    assert_eq!(std::fs::read(&file).unwrap(), b"not a directory");
    assert!(check_output_dir(&root.join("new/dir")).is_ok());
}
