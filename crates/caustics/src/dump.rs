//! The intermediate buffers `--dump` writes (`<name>.exr`), each declared once, as a
//! `static` [`Dump`], by the module that writes and reads it: the eye render's in
//! `render::dumps`, deferred refraction's in `techniques::wyman_nichols2009::deferred_refraction`,
//! the shared light-space buffers in `techniques::shared::settings`, each paper's own in its
//! folder's `settings.rs`. A dump is routed by what it is (`d == &HIERARCHY`: the same
//! declaration), never by its name; a name is read once, at the edge (`render::dumps::named`,
//! for `--dump`, the viewer's dump key). `render::dumps::all` lists every declaration;
//! docs/dumps.md describes each one's layers and channels (its unit tests check that the page
//! names every declared dump and no other), and the conformance suite that a render writes
//! exactly the dumps its settings declare. Each declaration also lists the layers and channels
//! its file holds ([`LayerDecl`]): every dump a render returns is checked against it
//! ([`Dump::check`]), and docs/dumps.md's "layers and channels" cells are its rendering
//! ([`Dump::layers_markdown`], checked by a test). This module is the type alone, below every
//! layer that declares one.

use crate::image_io::ImageF32;
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

/// One layer of a dump's file: its name, a pattern (`""`: the main, unnamed layer; `<face>`: a
/// cube face, `px` .. `nz`; any other `<x>`: a decimal index, a light's `<l>`, an object's
/// `<k>`, ...), its channels in order, and when the file has it (None: always).
#[derive(Debug, Clone, Copy)]
pub struct LayerDecl {
    pub name: &'static str,
    pub channels: &'static [&'static str],
    pub when: Option<&'static str>,
}

/// A layer every file of its dump has.
pub const fn layer(name: &'static str, channels: &'static [&'static str]) -> LayerDecl {
    LayerDecl { name, channels, when: None }
}

/// A layer a file of its dump has only `when` (a condition for readers: "`--precision unorm8`").
pub const fn layer_when(name: &'static str, channels: &'static [&'static str], when: &'static str) -> LayerDecl {
    LayerDecl { name, channels, when: Some(when) }
}

/// The cube faces of `<face>`, in the shadow map's layer order.
pub const FACES: [&str; 6] = ["px", "nx", "py", "ny", "pz", "nz"];

/// Whether the layer name `name` matches the pattern `pattern` (see [`LayerDecl`]).
pub fn matches(pattern: &str, name: &str) -> bool {
    match pattern.find('<') {
        None => pattern == name,
        Some(open) => {
            let Some(close) = pattern[open..].find('>').map(|c| open + c) else { return pattern == name };
            let (head, hole, tail) = (&pattern[..open], &pattern[open + 1..close], &pattern[close + 1..]);
            let Some(rest) = name.strip_prefix(head) else { return false };
            if hole == "face" {
                return FACES.iter().any(|f| rest.strip_prefix(f).is_some_and(|r| matches(tail, r)));
            }
            let digits = rest.bytes().take_while(u8::is_ascii_digit).count();
            (1..=digits).any(|n| matches(tail, &rest[n..]))
        }
    }
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
    /// The layers and channels its file holds.
    pub layers: &'static [LayerDecl],
}

impl Dump {
    pub const fn new(
        name: &'static str,
        owner: &'static str,
        space: Space,
        format: Format,
        layers: &'static [LayerDecl],
    ) -> Dump {
        Dump { name, owner, space, format, layers }
    }

    /// Whether `image` is what this dump declares: each layer a declared one (its name matching
    /// a declared pattern, with exactly that declaration's channels), and every layer declared
    /// without a condition there. An error here is a bug in the module that read the dump.
    pub fn check(&self, image: &ImageF32) -> anyhow::Result<()> {
        let shown = |n: &Option<String>| n.as_deref().map_or("the main layer".to_string(), |n| format!("layer `{n}`"));
        for l in &image.layers {
            let name = l.name.as_deref().unwrap_or("");
            let same_name: Vec<&LayerDecl> = self.layers.iter().filter(|d| matches(d.name, name)).collect();
            anyhow::ensure!(
                !same_name.is_empty(),
                "dump `{self}` ({}) has {}, which its declaration does not list",
                self.owner,
                shown(&l.name)
            );
            anyhow::ensure!(
                same_name.iter().any(|d| d.channels.iter().copied().eq(l.channels.iter().map(String::as_str))),
                "dump `{self}` ({}): {} has channels {:?}, declared {:?}",
                self.owner,
                shown(&l.name),
                l.channels,
                same_name.iter().map(|d| d.channels).collect::<Vec<_>>()
            );
        }
        for d in self.layers.iter().filter(|d| d.when.is_none()) {
            anyhow::ensure!(
                image.layers.iter().any(|l| matches(d.name, l.name.as_deref().unwrap_or(""))),
                "dump `{self}` ({}) has no layer `{}`, which its declaration says every file has",
                self.owner,
                d.name
            );
        }
        Ok(())
    }

    /// The declared layers as docs/dumps.md's "layers and channels" cell: runs of layers with
    /// the same channels as `` `a`, `b`: `X`, `Y` ``, joined by `; `; the layers a file has
    /// only under a condition after it, a line per condition (`<br>when: ...`).
    pub fn layers_markdown(&self) -> String {
        let mut conditions: Vec<Option<&str>> = vec![None];
        for d in self.layers {
            if !conditions.contains(&d.when) {
                conditions.push(d.when);
            }
        }
        let quoted = |v: &[&str]| v.iter().map(|c| format!("`{c}`")).collect::<Vec<_>>().join(", ");
        let runs = |when: Option<&str>| {
            let mut groups: Vec<(Vec<&str>, &[&str])> = vec![];
            for d in self.layers.iter().filter(|d| d.when == when) {
                match groups.last_mut() {
                    Some((names, channels)) if *channels == d.channels => names.push(d.name),
                    _ => groups.push((vec![d.name], d.channels)),
                }
            }
            let named = |n: &&str| if n.is_empty() { "main layer".to_string() } else { format!("`{n}`") };
            groups
                .iter()
                .map(|(names, channels)| {
                    format!("{}: {}", names.iter().map(named).collect::<Vec<_>>().join(", "), quoted(channels))
                })
                .collect::<Vec<_>>()
                .join("; ")
        };
        conditions
            .into_iter()
            .map(|when| (when, runs(when)))
            .filter(|(_, text)| !text.is_empty())
            .map(|(when, text)| match when {
                None => text,
                Some(w) => format!("{w}: {text}"),
            })
            .collect::<Vec<_>>()
            .join("<br>")
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

impl Dump {
    /// `header` with this dump's [`crate::image_io::header::DUMP`] attribute: what a `--dump`
    /// file's EXR header holds.
    pub fn header(&self, header: &[(&'static str, String)]) -> Vec<(&'static str, String)> {
        let mut h = header.to_vec();
        h.push((crate::image_io::header::DUMP, format!("{} ({})", self.name, self.owner)));
        h
    }
}

impl fmt::Display for Dump {
    fn fmt(&self, f: &mut fmt::Formatter) -> fmt::Result {
        f.write_str(self.name)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::image_io::Layer;

    #[test]
    fn a_pattern_matches_indices_and_faces_and_nothing_else() {
        assert!(matches("", ""));
        assert!(!matches("", "light0"));
        assert!(matches("light<l>", "light0") && matches("light<l>", "light12"));
        assert!(
            !matches("light<l>", "light") && !matches("light<l>", "lightx") && !matches("light<l>", "light0.power")
        );
        assert!(matches("light<l>.level<k>.power", "light1.level3.power"));
        assert!(!matches("light<l>.level<k>.power", "light1.level3.position"));
        assert!(matches("light<l>_<face>", "light0_nz") && !matches("light<l>_<face>", "light0_qz"));
        assert!(matches("light<l>_level<i>", "light10_level2"));
    }

    static TWO: Dump = Dump::new(
        "two",
        module_path!(),
        Space::Eye,
        Format::Image,
        &[
            layer("", &["R", "G"]),
            layer("light<l>", &["x"]),
            layer_when("extra", &["x"], "with `--extra`"),
            layer_when("more", &["x"], "with `--extra`"),
        ],
    );

    fn image(layers: Vec<Layer>) -> ImageF32 {
        ImageF32 { width: 1, height: 1, layers }
    }

    #[test]
    fn a_dump_is_checked_against_its_declared_layers_and_channels() {
        let main = || Layer::new(None, &["R", "G"], vec![0.0; 2]);
        let light = |l: &str| Layer::new(Some(l), &["x"], vec![0.0]);
        TWO.check(&image(vec![main(), light("light0"), light("light1")])).unwrap();
        TWO.check(&image(vec![main(), light("light0"), light("extra")])).unwrap();
        // An undeclared layer, channels out of order, a required layer missing.
        let e = TWO.check(&image(vec![main(), light("light0"), light("lights")])).unwrap_err().to_string();
        assert!(e.contains("layer `lights`"), "{e}");
        let swapped = Layer::new(None, &["G", "R"], vec![0.0; 2]);
        let e = TWO.check(&image(vec![swapped, light("light0")])).unwrap_err().to_string();
        assert!(e.contains("channels [\"G\", \"R\"]"), "{e}");
        let e = TWO.check(&image(vec![main()])).unwrap_err().to_string();
        assert!(e.contains("no layer `light<l>`"), "{e}");
    }

    #[test]
    fn the_markdown_groups_layers_of_the_same_channels() {
        assert_eq!(
            TWO.layers_markdown(),
            "main layer: `R`, `G`; `light<l>`: `x`<br>with `--extra`: `extra`, `more`: `x`"
        );
    }
}
