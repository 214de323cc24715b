//! The intermediate buffers `--dump` writes (`<name>.exr`), each declared once, as a
//! `static` [`Dump`], by the module that writes and reads it: the eye render's in
//! `render::dumps`, the deferred refraction's in `techniques::wyman_nichols2009`, the shared
//! light-space buffers in `techniques::shared`, each paper's own in its folder. A dump is
//! routed by what it is (`d == &HIERARCHY`: the same declaration), never by its name; a name
//! is read once, at the edge ([`named`], for `--dump`, the viewer's dump key, a bench metric).
//! docs/dumps.md describes each one's layers and channels; `tests/dumps.rs` checks that it names
//! every declared dump and no other, and that a render writes exactly the dumps its settings
//! declare.

use crate::techniques::CausticSettings;
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

impl fmt::Display for Dump {
    fn fmt(&self, f: &mut fmt::Formatter) -> fmt::Result {
        f.write_str(self.name)
    }
}

/// Every declared dump, owner by owner: the order of `--dump all`, and of every render's dumps
/// (`render::dumps_for` lists each render's in this order; the conformance suite checks it).
pub fn all() -> Vec<&'static Dump> {
    use crate::techniques::{shared, trendall_stewart2000, wyman2008, wyman_davis2006, wyman_nichols2009 as wn2009};
    [
        crate::render::dumps::EYE_DUMPS,
        shared::settings::DUMPS,
        wn2009::settings::DEFERRED_PHOTONS_DUMPS,
        wyman_davis2006::settings::DUMPS,
        wyman2008::DUMPS,
        wn2009::settings::ADAPTIVE_DUMPS,
        trendall_stewart2000::DUMPS,
    ]
    .concat()
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

/// The dump called `name` that a render with `settings` has (None: it has none of that name).
pub fn named(name: &str, settings: &CausticSettings) -> Option<&'static Dump> {
    crate::render::dumps_for(settings).into_iter().find(|d| d.name == name)
}

#[cfg(test)]
mod tests {
    use super::*;

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
        use crate::techniques::trendall_stewart2000::settings::RECEIVER as POOL_RECEIVER;
        let eye = &crate::render::dumps::RECEIVER;
        assert_eq!(eye.name, POOL_RECEIVER.name);
        assert!(eye != &POOL_RECEIVER && eye == &crate::render::dumps::RECEIVER);
        assert!(eye.owner.ends_with("render::dumps") && POOL_RECEIVER.owner.contains("trendall_stewart2000"));
        // Each render reads a name as the one declaration it has.
        let pool = CausticSettings { technique: crate::techniques::Technique::PoolConvolution, ..Default::default() };
        assert!(named("receiver", &pool) == Some(&POOL_RECEIVER));
        assert!(named("receiver", &CausticSettings::default()) == Some(eye));
        assert!(named("hierarchy", &CausticSettings::default()).is_none());
    }
}
