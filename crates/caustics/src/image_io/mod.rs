//! Writing (and reading back) every buffer the renderer dumps, atomically.
//!
//! * [`write_exr`] / [`read_exr`]: f32 OpenEXR with named layers. Our files are one
//!   part (ZIP16 scanlines) whose channels are named `layer.channel` (`R` for the
//!   unnamed main layer); the original channel order is kept in a `causticlab.channels`
//!   string-vector attribute, since EXR stores channels sorted by name; [`header`] names the
//!   text attributes that say what made the image.
//! * [`write_png_tonemapped`]: linear RGB -> exposure -> ACES (Narkowicz fit) ->
//!   sRGB 8-bit PNG.
//! * [`OutputDir`]: a directory whose files appear only when the whole run succeeded.
//!
//! Single files are written to a temporary file in the destination directory, flushed
//! to disk and renamed over the destination, so a reader never sees a partial file.

pub mod header;

use std::fs::File;
use std::io::{BufWriter, Write};
use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicU64, Ordering};

use anyhow::{bail, ensure, Context, Result};

/// Attribute holding the full channel names of our files in their original order.
const CHANNEL_ORDER_ATTRIBUTE: &str = "causticlab.channels";

/// One named layer of an image: channel names (e.g. `["R","G","B"]`, `["X","Y","Z"]`,
/// `["distance"]`) and interleaved f32 pixels, row 0 = top row of the image as stored
/// in the EXR (the caller decides orientation).
#[derive(Clone, Debug, PartialEq)]
pub struct Layer {
    /// `None` = unnamed main layer.
    pub name: Option<String>,
    pub channels: Vec<String>,
    /// `width * height * channels.len()` values, interleaved per pixel.
    pub data: Vec<f32>,
}

impl Layer {
    pub fn new(name: Option<&str>, channels: &[&str], data: Vec<f32>) -> Layer {
        Layer { name: name.map(str::to_owned), channels: channels.iter().map(|&c| c.to_owned()).collect(), data }
    }

    /// Channel `c` of pixel `(x, y)` for an image `width` wide.
    pub fn sample(&self, width: u32, x: u32, y: u32, c: usize) -> f32 {
        self.data[(y as usize * width as usize + x as usize) * self.channels.len() + c]
    }
}

#[derive(Clone, Debug, PartialEq)]
pub struct ImageF32 {
    pub width: u32,
    pub height: u32,
    pub layers: Vec<Layer>,
}

impl ImageF32 {
    /// The layer with this name (`None` = the unnamed main layer).
    pub fn layer(&self, name: Option<&str>) -> Option<&Layer> {
        self.layers.iter().find(|l| l.name.as_deref() == name)
    }
}

static TEMP_COUNTER: AtomicU64 = AtomicU64::new(0);

fn unique_suffix() -> String {
    format!("{}-{}", std::process::id(), TEMP_COUNTER.fetch_add(1, Ordering::Relaxed))
}

/// Writes `path` through a temporary file in the same directory, synced and renamed
/// into place; on any error the temporary file is removed and `path` is untouched.
fn write_atomically(path: &Path, write: impl FnOnce(&mut BufWriter<File>) -> Result<()>) -> Result<()> {
    let file_name = path.file_name().with_context(|| format!("{} has no file name", path.display()))?;
    let dir = match path.parent() {
        Some(p) if !p.as_os_str().is_empty() => p.to_path_buf(),
        _ => PathBuf::from("."),
    };
    let tmp = dir.join(format!(".{}.tmp-{}", file_name.to_string_lossy(), unique_suffix()));
    let result = (|| -> Result<()> {
        let file = File::create(&tmp).with_context(|| format!("creating {}", tmp.display()))?;
        let mut w = BufWriter::new(file);
        write(&mut w)?;
        let file = w.into_inner().map_err(|e| e.into_error())?;
        file.sync_all()?;
        drop(file);
        std::fs::rename(&tmp, path).with_context(|| format!("renaming {} to {}", tmp.display(), path.display()))?;
        Ok(())
    })();
    if result.is_err() {
        let _ = std::fs::remove_file(&tmp);
    }
    result.with_context(|| format!("writing {}", path.display()))
}

fn validate(image: &ImageF32) -> Result<Vec<String>> {
    ensure!(
        image.width > 0 && image.height > 0,
        "image is {}x{}: both sizes must be positive",
        image.width,
        image.height
    );
    ensure!(!image.layers.is_empty(), "image has no layers");
    let pixels = image.width as usize * image.height as usize;
    let mut full_names = Vec::new();
    for layer in &image.layers {
        let lname = layer.name.as_deref().unwrap_or("<main>");
        if let Some(n) = &layer.name {
            ensure!(!n.is_empty() && !n.starts_with('.') && !n.ends_with('.'), "invalid layer name {n:?}");
        }
        ensure!(!layer.channels.is_empty(), "layer {lname} has no channels");
        ensure!(
            layer.data.len() == pixels * layer.channels.len(),
            "layer {lname}: {} values for {}x{} pixels x {} channels (expected {})",
            layer.data.len(),
            image.width,
            image.height,
            layer.channels.len(),
            pixels * layer.channels.len()
        );
        for c in &layer.channels {
            ensure!(
                !c.is_empty() && !c.contains('.'),
                "layer {lname}: invalid channel name {c:?} (empty or contains '.')"
            );
            let full = match &layer.name {
                Some(n) => format!("{n}.{c}"),
                None => c.clone(),
            };
            ensure!(full.is_ascii(), "channel name {full:?} is not ASCII");
            ensure!(!full_names.contains(&full), "duplicate channel {full:?}");
            full_names.push(full);
        }
    }
    Ok(full_names)
}

/// Writes all layers as f32 channels into one EXR file (one part, channels named
/// `layer.channel`), atomically. Size mismatches and bad names are errors.
pub fn write_exr(path: &Path, image: &ImageF32) -> Result<()> {
    write_exr_with(path, image, &[])
}

/// The text attributes of an EXR file's first header (what [`write_exr_with`] wrote there).
pub fn exr_text_attributes(path: &Path) -> Result<std::collections::BTreeMap<String, String>> {
    let meta = exr::meta::MetaData::read_from_file(path, false)
        .map_err(|e| crate::input_error!("{}: not a readable OpenEXR file: {e}", path.display()))?;
    let mut out = std::collections::BTreeMap::new();
    if let Some(header) = meta.headers.first() {
        for (k, v) in &header.own_attributes.other {
            if let exr::meta::attribute::AttributeValue::Text(t) = v {
                out.insert(k.to_string(), t.to_string());
            }
        }
    }
    Ok(out)
}

/// [`write_exr`] with extra string attributes in the header (`causticlab render` records what
/// made the image there: technique, photons, commit, device), readable with any OpenEXR tool.
pub fn write_exr_with(path: &Path, image: &ImageF32, header: &[(&str, String)]) -> Result<()> {
    use exr::prelude::{
        AnyChannel, AnyChannels, AttributeValue, Encoding, FlatSamples, LayerAttributes, Text, WritableImage,
    };

    let full_names = validate(image).with_context(|| format!("writing {}", path.display()))?;
    let pixels = image.width as usize * image.height as usize;
    let mut channels = Vec::with_capacity(full_names.len());
    let mut names = full_names.iter();
    for layer in &image.layers {
        let nc = layer.channels.len();
        for c in 0..nc {
            let samples: Vec<f32> = (0..pixels).map(|p| layer.data[p * nc + c]).collect();
            channels.push(AnyChannel::new(Text::from(names.next().unwrap().as_str()), FlatSamples::F32(samples)));
        }
    }
    let mut attributes = LayerAttributes::default();
    attributes.other.insert(
        Text::from(CHANNEL_ORDER_ATTRIBUTE),
        AttributeValue::TextVector(full_names.iter().map(|n| Text::from(n.as_str())).collect()),
    );
    for (key, value) in header {
        attributes.other.insert(Text::from(*key), AttributeValue::Text(Text::from(value.as_str())));
    }
    let layer = exr::prelude::Layer::new(
        (image.width as usize, image.height as usize),
        attributes,
        Encoding::SMALL_LOSSLESS,
        AnyChannels::sort(channels.into_iter().collect()),
    );
    let exr_image = exr::prelude::Image::from_layer(layer);
    write_atomically(path, |w| {
        exr_image.write().to_buffered(w)?;
        Ok(())
    })
}

/// Order for channels of files without our order attribute: grouped by layer, then
/// R, G, B, A, X, Y, Z first within a layer, then by name.
fn default_channel_rank(full: &str) -> (String, u8, String) {
    let (prefix, base) = split_channel(full);
    let rank = ["R", "G", "B", "A", "X", "Y", "Z"].iter().position(|&c| c == base).unwrap_or(7) as u8;
    (prefix.unwrap_or("").to_owned(), rank, base.to_owned())
}

fn split_channel(full: &str) -> (Option<&str>, &str) {
    match full.rsplit_once('.') {
        Some((prefix, base)) => (Some(prefix), base),
        None => (None, full),
    }
}

/// Reads every layer (all parts, channel-name prefixes) and channel as f32. Layer names
/// come from the file: a part's `name` attribute and/or a `layer.` channel prefix,
/// joined with '.'. Files written by [`write_exr`] come back exactly as written
/// (layer order, channel order and bit-exact values). All parts must share one size.
///
/// A file that is missing, damaged, truncated or of a kind this reader refuses is an
/// [`InputError`](crate::error::InputError) naming it (the user's to fix, exit code 2); a
/// failure of the file system itself (a permission, a disk error) is not.
pub fn read_exr(path: &Path) -> Result<ImageF32> {
    read_exr_inner(path).map_err(|e| match io_failure(&e) {
        Some(std::io::ErrorKind::NotFound) => crate::input_error!("{}: no such file", path.display()).into(),
        Some(_) => e.context(format!("reading {}", path.display())),
        None => crate::input_error!("{}: not a readable OpenEXR file: {e:#}", path.display()).into(),
    })
}

/// The kind of a failure to read from the file system, or None where the reader refused the
/// file's contents. (The exr crate already turns a short read, a truncated file, into
/// `Error::Invalid`; the filter keeps that so should a bare `UnexpectedEof` reach here.)
fn io_failure(e: &anyhow::Error) -> Option<std::io::ErrorKind> {
    let io = e.downcast_ref::<std::io::Error>().or(match e.downcast_ref::<exr::error::Error>() {
        Some(exr::error::Error::Io(io)) => Some(io),
        _ => None,
    });
    io.map(std::io::Error::kind)
        .filter(|k| !matches!(k, std::io::ErrorKind::UnexpectedEof | std::io::ErrorKind::InvalidData))
}

/// The most samples (pixels times channels, over every part) [`read_exr`] reads: 2^28, 1 GiB
/// of f32. A header that claims more is refused before any pixel is read: the exr crate would
/// try to allocate them all, and an allocation that fails aborts the process.
pub const MAX_EXR_SAMPLES: u64 = 1 << 28;

/// Reads the headers alone and refuses sizes beyond [`MAX_EXR_SAMPLES`] and the lossy
/// compressions B44, B44A, DWAA and DWAB: on malformed blocks the exr crate's decoders for
/// these panic in a worker thread (B44) or allocate gigabytes (DWA), and either aborts the
/// process (found by fuzzing, `fuzz/README.md`). causticlab writes lossless ZIP.
fn check_exr_header(path: &Path) -> Result<()> {
    use exr::compression::Compression;
    let meta = exr::meta::MetaData::read_from_file(path, false)?;
    let mut samples: u64 = 0;
    for h in meta.headers.iter() {
        if let Compression::B44 | Compression::B44A | Compression::DWAA(_) | Compression::DWAB(_) = h.compression {
            bail!(
                "its {} is lossy: this reader refuses B44 and DWA compression (their decoder can crash on a \
                 damaged file); save it without compression or with RLE, ZIP, PIZ or PXR24",
                h.compression
            );
        }
        let (w, ht) = (h.layer_size.width() as u64, h.layer_size.height() as u64);
        let channels = h.channels.list.len() as u64;
        let part = w.saturating_mul(ht).saturating_mul(channels);
        ensure!(
            part <= MAX_EXR_SAMPLES,
            "its header claims a {w}x{ht} part of {channels} channels ({part} samples), more than the {MAX_EXR_SAMPLES} \
             this reader reads"
        );
        samples = samples.saturating_add(part);
    }
    ensure!(
        samples <= MAX_EXR_SAMPLES,
        "its header claims {samples} samples over {} parts, more than the {MAX_EXR_SAMPLES} this reader reads",
        meta.headers.len()
    );
    Ok(())
}

fn read_exr_inner(path: &Path) -> Result<ImageF32> {
    use exr::prelude::{read, AttributeValue, ReadChannels, ReadLayers};

    check_exr_header(path)?;
    let file = File::open(path)?;
    let image = read()
        .no_deep_data()
        .largest_resolution_level()
        .all_channels()
        .all_layers()
        .all_attributes()
        .from_buffered(std::io::BufReader::new(file))?;

    let mut size: Option<(usize, usize)> = None;
    let mut layers: Vec<Layer> = Vec::new();
    for part in &image.layer_data {
        let (w, h) = (part.size.0, part.size.1);
        match size {
            None => size = Some((w, h)),
            Some(s) => ensure!(s == (w, h), "parts of different sizes ({}x{} and {w}x{h}) are not supported", s.0, s.1),
        }
        let part_name = part.attributes.layer_name.as_ref().map(|t| t.to_string());
        let list = &part.channel_data.list;
        let names: Vec<String> = list.iter().map(|c| c.name.to_string()).collect();

        // Channel order: ours if the attribute matches this part's channels exactly.
        let mut order: Vec<usize> = (0..list.len()).collect();
        let stored = match part.attributes.other.get(&exr::prelude::Text::from(CHANNEL_ORDER_ATTRIBUTE)) {
            Some(AttributeValue::TextVector(v)) => Some(v.iter().map(|t| t.to_string()).collect::<Vec<_>>()),
            _ => None,
        };
        let mut sorted_stored = stored.clone().unwrap_or_default();
        sorted_stored.sort();
        let mut sorted_names = names.clone();
        sorted_names.sort();
        if let (Some(stored), true) = (&stored, sorted_stored == sorted_names) {
            order = stored.iter().map(|s| names.iter().position(|n| n == s).unwrap()).collect();
        } else {
            order.sort_by_key(|&i| default_channel_rank(&names[i]));
        }

        // Group into layers in order of first appearance.
        let first_layer = layers.len();
        let mut columns: Vec<Vec<Vec<f32>>> = Vec::new();
        for &i in &order {
            let (prefix, base) = split_channel(&names[i]);
            let lname = match (&part_name, prefix) {
                (Some(p), Some(q)) => Some(format!("{p}.{q}")),
                (Some(p), None) => Some(p.clone()),
                (None, Some(q)) => Some(q.to_owned()),
                (None, None) => None,
            };
            let k = match layers[first_layer..].iter().position(|l| l.name == lname) {
                Some(k) => k,
                None => {
                    layers.push(Layer { name: lname, channels: Vec::new(), data: Vec::new() });
                    columns.push(Vec::new());
                    layers.len() - 1 - first_layer
                }
            };
            layers[first_layer + k].channels.push(base.to_owned());
            let samples: Vec<f32> = list[i].sample_data.values_as_f32().collect();
            ensure!(samples.len() == w * h, "channel {} has {} samples for {w}x{h}", names[i], samples.len());
            columns[k].push(samples);
        }
        for (layer, cols) in layers[first_layer..].iter_mut().zip(columns) {
            let nc = cols.len();
            layer.data = vec![0.0; w * h * nc];
            for (c, col) in cols.iter().enumerate() {
                for (p, &v) in col.iter().enumerate() {
                    layer.data[p * nc + c] = v;
                }
            }
        }
    }
    let Some((w, h)) = size else { bail!("file has no layers") };
    Ok(ImageF32 { width: u32::try_from(w)?, height: u32::try_from(h)?, layers })
}

/// ACES filmic tone curve, Narkowicz 2015 fit, clamped to [0, 1].
pub fn tonemap_aces(x: f32) -> f32 {
    if x >= 1.0e6 {
        // The curve reaches 1 at x ~ 7.24; avoid inf/inf for huge x.
        return 1.0;
    }
    let (a, b, c, d, e) = (2.51f32, 0.03f32, 2.43f32, 0.59f32, 0.14f32);
    ((x * (a * x + b)) / (x * (c * x + d) + e)).clamp(0.0, 1.0)
}

/// sRGB-encoded [0, 1] -> linear [0, 1] (IEC 61966-2-1): a PNG's codes as `k / 255`, and FLIP's
/// LDR input.
pub fn srgb_decode(c: f32) -> f32 {
    if c <= 0.04045 {
        c / 12.92
    } else {
        ((c + 0.055) / 1.055).powf(2.4)
    }
}

/// Linear [0, 1] -> sRGB-encoded [0, 1] (IEC 61966-2-1).
pub fn srgb_encode(x: f32) -> f32 {
    if x <= 0.003_130_8 {
        12.92 * x
    } else {
        1.055 * x.powf(1.0 / 2.4) - 0.055
    }
}

/// One linear radiance value (already multiplied by exposure) -> 8-bit sRGB code.
/// NaN, infinities and negative values become 0.
pub fn tonemap_to_srgb8(x: f32) -> u8 {
    if !(x.is_finite() && x > 0.0) {
        return 0;
    }
    (srgb_encode(tonemap_aces(x)) * 255.0).round().clamp(0.0, 255.0) as u8
}

/// Writes linear RGB radiance (`width*height*3`, row 0 = top) as an 8-bit sRGB PNG:
/// `value * exposure` -> [`tonemap_aces`] -> [`srgb_encode`]. Non-finite and negative
/// inputs become black; a finite input that overflows after exposure saturates. Atomic.
pub fn write_png_tonemapped(path: &Path, width: u32, height: u32, rgb: &[f32], exposure: f32) -> Result<()> {
    let check = || -> Result<()> {
        ensure!(width > 0 && height > 0, "image is {width}x{height}: both sizes must be positive");
        let expected = width as usize * height as usize * 3;
        ensure!(rgb.len() == expected, "{} values for {width}x{height} RGB (expected {expected})", rgb.len());
        ensure!(exposure.is_finite() && exposure >= 0.0, "exposure {exposure} must be finite and non-negative");
        Ok(())
    };
    check().with_context(|| format!("writing {}", path.display()))?;
    let bytes: Vec<u8> = rgb
        .iter()
        .map(|&v| if v.is_finite() && v > 0.0 { tonemap_to_srgb8((v * exposure).min(f32::MAX)) } else { 0 })
        .collect();
    write_rgb8_png(path, width, height, &bytes)
}

/// Writes 8-bit sRGB pixels (`width*height*3` bytes, row 0 = top) as a PNG. Atomic.
pub fn write_rgb8_png(path: &Path, width: u32, height: u32, rgb: &[u8]) -> Result<()> {
    ensure!(
        width > 0 && height > 0 && rgb.len() == width as usize * height as usize * 3,
        "writing {}: {} bytes for {width}x{height} RGB",
        path.display(),
        rgb.len()
    );
    write_atomically(path, |w| {
        let mut encoder = png::Encoder::new(w, width, height);
        encoder.set_color(png::ColorType::Rgb);
        encoder.set_depth(png::BitDepth::Eight);
        encoder.set_source_srgb(png::SrgbRenderingIntent::Perceptual);
        let mut writer = encoder.write_header()?;
        writer.write_image_data(rgb)?;
        writer.finish()?;
        Ok(())
    })
}

/// Writes one value per pixel (`width*height`, row 0 = top) as an 8-bit grey PNG, 0 black and
/// `white` white, linearly (for relative irradiance maps: E/E0 = 1 is mid-grey with `white` 2).
/// Non-finite values become black. Atomic.
pub fn write_png_grey(path: &Path, width: u32, height: u32, values: &[f32], white: f32) -> Result<()> {
    ensure!(
        values.len() == width as usize * height as usize && white > 0.0,
        "writing {}: {} values for {width}x{height}",
        path.display(),
        values.len()
    );
    let bytes: Vec<u8> = values
        .iter()
        .map(|&v| if v.is_finite() { (v / white * 255.0).round().clamp(0.0, 255.0) as u8 } else { 0 })
        .collect();
    write_atomically(path, |w| {
        let mut encoder = png::Encoder::new(w, width, height);
        encoder.set_color(png::ColorType::Grayscale);
        encoder.set_depth(png::BitDepth::Eight);
        let mut writer = encoder.write_header()?;
        writer.write_image_data(&bytes)?;
        writer.finish()?;
        Ok(())
    })
}

/// An output directory whose files appear only when the whole run succeeded.
///
/// Files are written into a staging directory beside the final one
/// (`.<name>.partial-<pid>-<n>`); [`OutputDir::commit`] moves them in. Dropping an
/// uncommitted `OutputDir` (error, panic unwinding) removes the staging directory. While it
/// lives, it holds an exclusive lock on `.<name>.partial-<pid>-<n>.lock` beside it: a killed run
/// cannot clean up, but the kernel drops its lock, and the next run into the same folder
/// removes what it left (see [`remove_stale_staging`]).
/// When the final directory does not exist yet, commit is a single atomic rename;
/// otherwise each file is renamed in (each file atomic, overwriting same-named files).
#[derive(Debug)]
pub struct OutputDir {
    final_dir: PathBuf,
    staging: PathBuf,
    /// Held locked while the run lives (removed with the staging directory).
    lock: Option<(PathBuf, std::fs::File)>,
    committed: bool,
}

/// The lock file of staging directory `staging`.
fn lock_path(staging: &Path) -> PathBuf {
    let mut name = staging.file_name().unwrap_or_default().to_os_string();
    name.push(".lock");
    staging.with_file_name(name)
}

impl OutputDir {
    /// Fails with an input error, before anything is created, when `final_dir` or one of its
    /// ancestors is not a directory (see [`check_output_dir`]).
    pub fn create(final_dir: &Path) -> Result<OutputDir> {
        check_output_dir(final_dir)?;
        let run = || -> Result<OutputDir> {
            let final_dir = match final_dir.file_name() {
                Some(_) => final_dir.to_path_buf(),
                // "." / ".." / "dir/..": name the directory through its absolute path.
                None => final_dir.canonicalize()?,
            };
            let name = final_dir.file_name().context("output directory has no name")?.to_string_lossy().into_owned();
            remove_stale_staging(&final_dir, &name);
            let staging = final_dir.with_file_name(format!(".{name}.partial-{}", unique_suffix()));
            if staging.exists() {
                std::fs::remove_dir_all(&staging)?;
            }
            if let Some(parent) = staging.parent().filter(|p| !p.as_os_str().is_empty()) {
                std::fs::create_dir_all(parent).with_context(|| format!("creating {}", parent.display()))?;
            }
            // Locked before the directory exists: a directory whose lock can be taken is stale.
            let lock = lock_path(&staging);
            let file = std::fs::File::create(&lock).with_context(|| format!("creating {}", lock.display()))?;
            file.lock().with_context(|| format!("locking {}", lock.display()))?;
            let lock = Some((lock, file));
            std::fs::create_dir_all(&staging).with_context(|| format!("creating {}", staging.display()))?;
            Ok(OutputDir { final_dir, staging, lock, committed: false })
        };
        run().with_context(|| format!("creating output directory {}", final_dir.display()))
    }

    /// Path of `file` inside the staging directory (subdirectories are the caller's
    /// to create, e.g. with `create_dir_all(out.path("sub"))`).
    pub fn path(&self, file: &str) -> PathBuf {
        self.staging.join(file)
    }

    pub fn final_dir(&self) -> &Path {
        &self.final_dir
    }

    pub fn staging_dir(&self) -> &Path {
        &self.staging
    }

    /// Moves every staged file into the final directory (created if needed;
    /// same-named files are replaced), then removes the staging directory.
    pub fn commit(mut self) -> Result<()> {
        let result = (|| -> Result<()> {
            if !self.final_dir.exists() {
                if let Some(parent) = self.final_dir.parent().filter(|p| !p.as_os_str().is_empty()) {
                    std::fs::create_dir_all(parent).with_context(|| format!("creating {}", parent.display()))?;
                }
                if std::fs::rename(&self.staging, &self.final_dir).is_ok() {
                    return Ok(());
                }
                // Lost a race with another creator, or a filesystem without directory
                // renames: fall back to moving files one by one.
                std::fs::create_dir_all(&self.final_dir)
                    .with_context(|| format!("creating {}", self.final_dir.display()))?;
            }
            move_contents(&self.staging, &self.final_dir)?;
            std::fs::remove_dir_all(&self.staging).with_context(|| format!("removing {}", self.staging.display()))?;
            Ok(())
        })();
        // On error, Drop removes whatever is still staged.
        self.committed = result.is_ok();
        result.with_context(|| format!("committing output directory {}", self.final_dir.display()))
    }
}

/// An input error when `dir`, or the nearest ancestor of it that exists, is not a directory:
/// otherwise a run would do all its work and only fail when it moves its files in. Commands call
/// it before they open the device.
pub fn check_output_dir(dir: &Path) -> Result<()> {
    let existing = dir.ancestors().find(|a| !a.as_os_str().is_empty() && a.exists());
    match existing {
        Some(a) if !a.is_dir() => Err(crate::input_error!(
            "output directory {}: {} exists and is not a directory",
            dir.display(),
            if a == dir { "it".to_string() } else { a.display().to_string() }
        )
        .into()),
        _ => Ok(()),
    }
}

/// Removes the staging directories of `final_dir` that killed runs left behind
/// (`.<name>.partial-<pid>-<n>`): those whose lock file (`<dir>.lock`) nobody holds. A killed
/// process cannot clean up after itself, and nothing else would; a live one, in this PID
/// namespace or another, on this host or (where the filesystem passes locks on) another, holds
/// its lock. A directory without a lock file is not known to be stale, and is left.
fn remove_stale_staging(final_dir: &Path, name: &str) {
    let parent = match final_dir.parent() {
        Some(p) if !p.as_os_str().is_empty() => p,
        _ => Path::new("."),
    };
    let Ok(entries) = std::fs::read_dir(parent) else { return };
    let prefix = format!(".{name}.partial-");
    for entry in entries.flatten().filter(|e| e.file_type().is_ok_and(|t| t.is_dir())) {
        let file = entry.file_name();
        if file.to_str().and_then(|f| f.strip_prefix(&prefix)).and_then(staging_pid).is_none() {
            continue;
        }
        let lock = lock_path(&entry.path());
        let Ok(lock_file) = std::fs::OpenOptions::new().write(true).open(&lock) else { continue };
        if lock_file.try_lock().is_err() {
            continue;
        }
        if let Err(e) = std::fs::remove_dir_all(entry.path()) {
            log::warn!("could not remove the stale staging directory {}: {e}", entry.path().display());
            continue;
        }
        let _ = std::fs::remove_file(&lock);
    }
}

/// `<pid>-<n>` (the staging suffix) -> pid.
fn staging_pid(suffix: &str) -> Option<u32> {
    let (pid, n) = suffix.split_once('-')?;
    let digits = |s: &str| !s.is_empty() && s.bytes().all(|b| b.is_ascii_digit());
    (digits(pid) && digits(n)).then(|| pid.parse().ok()).flatten()
}

fn move_contents(from: &Path, to: &Path) -> Result<()> {
    let mut entries: Vec<_> = std::fs::read_dir(from)
        .with_context(|| format!("listing {}", from.display()))?
        .collect::<std::io::Result<Vec<_>>>()?;
    entries.sort_by_key(|e| e.file_name());
    for entry in entries {
        let src = entry.path();
        let dst = to.join(entry.file_name());
        let is_dir = entry.file_type()?.is_dir();
        if is_dir && dst.is_dir() {
            move_contents(&src, &dst)?;
        } else {
            ensure!(!dst.is_dir(), "{} is a directory; cannot replace it with a file", dst.display());
            std::fs::rename(&src, &dst).with_context(|| format!("moving {} to {}", src.display(), dst.display()))?;
        }
    }
    Ok(())
}

impl Drop for OutputDir {
    fn drop(&mut self) {
        if !self.committed && self.staging.exists() {
            if let Err(e) = std::fs::remove_dir_all(&self.staging) {
                log::warn!("could not remove staging directory {}: {e}", self.staging.display());
            }
        }
        // The staging directory is gone (moved in or removed): so is the need for its lock.
        if let Some((path, _file)) = self.lock.take() {
            let _ = std::fs::remove_file(path);
        }
    }
}

/// Writes arbitrary bytes (JSON, CSV, ...) with the same atomic temp-file-and-rename
/// behaviour as the image writers.
pub fn write_file_atomically(path: &Path, contents: &[u8]) -> Result<()> {
    write_atomically(path, |w| {
        w.write_all(contents)?;
        Ok(())
    })
}

#[cfg(test)]
mod tests;

/// The largest side [`read_png_rgba`] decodes: textures are resampled far below it, and a
/// small file can claim 2^31 pixels a side.
pub const MAX_PNG_SIDE: u32 = 16384;

/// Decodes a PNG into linear RGBA in [0, 1] (sRGB decoded), for projected spot-light textures.
/// A file that is not a PNG, or larger than [`MAX_PNG_SIDE`] a side, is an input error.
pub fn read_png_rgba(path: &Path) -> Result<(u32, u32, Vec<f32>)> {
    let file = std::fs::File::open(path).with_context(|| format!("opening {}", path.display()))?;
    let mut decoder = png::Decoder::new(std::io::BufReader::new(file));
    decoder.set_transformations(png::Transformations::EXPAND | png::Transformations::STRIP_16);
    let mut reader =
        decoder.read_info().map_err(|e| crate::input_error!("{}: not a readable PNG: {e}", path.display()))?;
    let (w, h) = (reader.info().width, reader.info().height);
    if w > MAX_PNG_SIDE || h > MAX_PNG_SIDE {
        return Err(crate::input_error!("{}: {w} x {h} pixels, more than {MAX_PNG_SIDE} a side", path.display()).into());
    }
    let mut buf = vec![0u8; reader.output_buffer_size()];
    let info =
        reader.next_frame(&mut buf).map_err(|e| crate::input_error!("{}: not a readable PNG: {e}", path.display()))?;
    let channels = info.color_type.samples();
    let (w, h) = (info.width, info.height);
    let to_linear = |v: u8| srgb_decode(v as f32 / 255.0);
    let mut out = Vec::with_capacity(w as usize * h as usize * 4);
    for px in buf[..info.buffer_size()].chunks(channels) {
        let (r, g, b, a) = match channels {
            1 => (px[0], px[0], px[0], 255),
            2 => (px[0], px[0], px[0], px[1]),
            3 => (px[0], px[1], px[2], 255),
            _ => (px[0], px[1], px[2], px[3]),
        };
        out.extend_from_slice(&[to_linear(r), to_linear(g), to_linear(b), a as f32 / 255.0]);
    }
    Ok((w, h, out))
}
