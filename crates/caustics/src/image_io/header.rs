//! The text attributes `causticlab` writes into each EXR header, `causticlab:<key>`: what made
//! the image (tev and `exrheader` show them; `compare` reads the scene and Fresnel ones).
//! `render` writes all but [`WRITER`], `reference` [`TECHNIQUE`], [`PHOTONS`], [`FRESNEL`],
//! [`COMMIT`] and [`SCENE`], the viewer's saved frames all but [`PHOTONS`] and [`FRESNEL`]
//! with [`WRITER`]; a dump also [`DUMP`]. (The channel-order attribute, `causticlab.channels`, is older and kept as
//! spelt so that the files already written read back in their order.)

/// The technique, or `reference (exact CPU photon trace)`.
pub const TECHNIQUE: &str = "causticlab:technique";
/// Photons emitted per light (render: as counted by the frame).
pub const PHOTONS: &str = "causticlab:photons";
/// The photon buffer's layout, e.g. `512x512`.
pub const PHOTON_BUFFER: &str = "causticlab:photon_buffer";
/// `caustics.fresnel` in effect: `true` or `false`.
pub const FRESNEL: &str = "causticlab:fresnel";
/// The commit of the code, `<hash>` or `<hash>-dirty`.
pub const COMMIT: &str = "causticlab:commit";
/// The device and its driver.
pub const DEVICE: &str = "causticlab:device";
/// The scene file as given on the command line.
pub const SCENE: &str = "causticlab:scene";
/// A `--dump` file's buffer and the module that declares it, `<name> (<owner>)`
/// (`crate::dump::Dump`; its layers and channels were checked against that declaration).
pub const DUMP: &str = "causticlab:dump";
/// The program that wrote the file when it is not `render` or `reference`.
pub const WRITER: &str = "causticlab:writer";
