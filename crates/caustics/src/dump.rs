//! The intermediate buffers `--dump` writes (`<name>.exr`), each declared once, as a
//! `static` [`Dump`], by the module that writes and reads it: the eye render's in
//! `render::dumps`, deferred refraction's in `techniques::wyman_nichols2009::deferred_refraction`,
//! the shared light-space buffers in `techniques::shared::settings`, each paper's own in its
//! folder's `settings.rs`. A dump is routed by what it is (`d == &HIERARCHY`: the same
//! declaration), never by its name; a name is read once, at the edge (`render::dumps::named`,
//! for `--dump`, the viewer's dump key). `render::dumps::all` lists every declaration;
//! docs/dumps.md describes each one's layers and channels (its unit tests check that the page
//! names every declared dump and no other), and the conformance suite that a render writes
//! exactly the dumps its settings declare. This module is the type alone, below every layer
//! that declares one.

use std::fmt;

/// Where a dump's pixels are.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Space {
    /// The eye's view (or the receiver map's rectangle, or the shadow maps' cube faces).
    Eye,
    /// A light's view, an image with a layer per light (`light<l>`).
    LightLayers,
    /// A light's view in buffers that every light uses in turn, dumped light by light (each
    /// light recorded again alone where there are several): layers `light<l>.<layer>`.
    LightInTurn,
    /// The pool's textures (Trendall & Stewart 2000).
    Pool,
}

/// How a dump's pixels are laid out.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Format {
    /// Images: a texel per pixel.
    Image,
    /// Lists of records, a record per pixel in row-major order (a `valid` channel marks them).
    Records,
}

/// One intermediate buffer, declared by its owner. Two dumps are the same when they are the
/// same declaration (its address), so a dump is matched by what it is, not by its name.
#[derive(Debug)]
pub struct Dump {
    /// The `--dump` name and the file's stem.
    pub name: &'static str,
    /// The module that declares, writes and reads it.
    pub owner: &'static str,
    pub space: Space,
    pub format: Format,
}

impl Dump {
    pub const fn new(name: &'static str, owner: &'static str, space: Space, format: Format) -> Dump {
        Dump { name, owner, space, format }
    }
}

impl PartialEq for Dump {
    fn eq(&self, other: &Self) -> bool {
        std::ptr::eq(self, other)
    }
}

impl Eq for Dump {}

/// The dump of `dumps` called `name` (a `--dump` name read against declarations).
pub fn named_in(dumps: &[&'static Dump], name: &str) -> Option<&'static Dump> {
    dumps.iter().copied().find(|d| d.name == name)
}

impl fmt::Display for Dump {
    fn fmt(&self, f: &mut fmt::Formatter) -> fmt::Result {
        f.write_str(self.name)
    }
}
