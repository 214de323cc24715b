//! The shared models (`shape = "obj"`) by their SHA-256: the files the committed tables were
//! made with (docs/scenes.md lists them, where they come from and what is known of how each was
//! made). A scene still loads a file that differs (a user's own copy of the bunny, a dragon
//! decimated another way): it warns once, naming both checksums, and the bench writes the
//! file's checksum into its table, whose header then says it was made with another model.

use serde::{Deserialize, Serialize};
use sha2::{Digest, Sha256};
use std::collections::BTreeSet;
use std::path::Path;
use std::sync::Mutex;

/// A model file the project's tables were made with.
pub struct Known {
    pub file: &'static str,
    pub sha256: &'static str,
    pub triangles: usize,
}

/// `../shared/models` as the tables used it (checksums by `sha256sum`, triangles as
/// `scene::obj::load_obj` triangulates the faces). docs/scenes.md's table is checked against this one.
pub const KNOWN: [Known; 7] = [
    Known {
        file: "stanford-bunny.obj",
        sha256: "1eb35d1e21ce99e5ce911353b6be278990713448dd9e8f5c9387f9de39b32205",
        triangles: 69_451,
    },
    Known {
        file: "stanford-dragon.obj",
        sha256: "20378bd52b9a111890201f5a13e7873dd3e56b0c8dc4c40c7fb1a10d9a12a815",
        triangles: 249_998,
    },
    Known {
        file: "ogre.obj",
        sha256: "b72e270246ec3bd91bd8e082c4acf462352680f09067813322903b4e1a3f6967",
        triangles: 124_008,
    },
    Known {
        file: "nefertiti.obj",
        sha256: "19e39748b145092878cc4faafd050505eb5991c5d3e497be2b4575673fa87968",
        triangles: 99_938,
    },
    Known {
        file: "beast.obj",
        sha256: "74c5fecd883b761bc1b2bb6c82fe94d3b3b450297ab561e83c0e63c7ed46abe8",
        // 32,364 faces, most of them quads: the count ../shared/models/README.md gives.
        triangles: 64_618,
    },
    Known {
        file: "teapot.obj",
        sha256: "1b5396fedd74b577e32cef41146582c2f2e1a050d5b4915193c0ac1ad4187ed4",
        triangles: 6_320,
    },
    Known {
        file: "spot.obj",
        sha256: "0738b5e8608fed74e5e8c7aa8dd0af97b4b74f9f6cbf7aac84cd7e40b2e44a75",
        triangles: 5_856,
    },
];

/// The model file a scene loaded.
#[derive(Debug, Clone, PartialEq, Eq, PartialOrd, Ord, Serialize, Deserialize)]
pub struct ModelFile {
    /// Its file name.
    pub file: String,
    pub sha256: String,
    /// The checksum [`KNOWN`] lists for a file of that name; `None` for a model it does not list.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub expected: Option<String>,
}

impl ModelFile {
    /// The file at `path`, whose contents are `bytes`.
    pub fn of(path: &Path, bytes: &[u8]) -> ModelFile {
        let file = path.file_name().map(|f| f.to_string_lossy().into_owned()).unwrap_or_default();
        let expected = KNOWN.iter().find(|k| k.file == file).map(|k| k.sha256.to_string());
        ModelFile { file, sha256: sha256_hex(bytes), expected }
    }

    /// A known model's name on a file with other contents.
    pub fn differs(&self) -> bool {
        self.expected.as_ref().is_some_and(|e| *e != self.sha256)
    }

    /// What a user is told when [`ModelFile::differs`].
    pub fn warning(&self) -> Option<String> {
        let expected = self.expected.as_ref().filter(|_| self.differs())?;
        Some(format!(
            "{}: SHA-256 {} is not the file the project's tables were made with ({expected}, docs/scenes.md): \
             loaded anyway; tables made with it say so",
            self.file, self.sha256
        ))
    }

    /// How a table's header names it.
    pub fn describe(&self) -> String {
        let short = &self.sha256[..self.sha256.len().min(12)];
        match &self.expected {
            Some(e) if *e != self.sha256 => {
                format!(
                    "{} (SHA-256 {short}…: NOT the file docs/scenes.md lists, {}…)",
                    self.file,
                    &e[..e.len().min(12)]
                )
            }
            Some(_) => format!("{} (SHA-256 {short}…, as docs/scenes.md lists)", self.file),
            None => format!("{} (SHA-256 {short}…, not a model docs/scenes.md lists)", self.file),
        }
    }
}

pub fn sha256_hex(bytes: &[u8]) -> String {
    Sha256::digest(bytes).iter().map(|b| format!("{b:02x}")).collect()
}

/// Warns on stderr, once per process for each differing file (a bench loads a scene per cell).
pub fn warn_once(m: &ModelFile) {
    static WARNED: Mutex<BTreeSet<String>> = Mutex::new(BTreeSet::new());
    if let Some(w) = m.warning() {
        let mut warned = WARNED.lock().unwrap_or_else(|e| e.into_inner());
        if warned.insert(m.sha256.clone()) {
            eprintln!("warning: {w}");
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn sha256_is_the_standard_digest() {
        // FIPS 180-2's examples.
        assert_eq!(sha256_hex(b"abc"), "ba7816bf8f01cfea414140de5dae2223b00361a396177a9cb410ff61f20015ad");
        assert_eq!(sha256_hex(b""), "e3b0c44298fc1c149afbf4c8996fb92427ae41e4649b934ca495991b7852b855");
    }

    #[test]
    fn a_known_name_with_other_contents_differs_and_says_both_checksums() {
        let m = ModelFile::of(Path::new("/x/stanford-dragon.obj"), b"v 0 0 0\n");
        assert!(m.differs());
        let w = m.warning().expect("a warning");
        assert!(w.contains(&m.sha256) && w.contains(KNOWN[1].sha256), "{w}");
        assert!(m.describe().contains("NOT the file"), "{}", m.describe());
        // Another name is no known model: nothing to compare with, no warning.
        let other = ModelFile::of(Path::new("mine.obj"), b"v 0 0 0\n");
        assert!(!other.differs() && other.warning().is_none() && other.expected.is_none());
        assert!(other.describe().contains("not a model docs/scenes.md lists"));
    }

    #[test]
    fn docs_scenes_md_lists_each_known_model_with_its_checksum_and_size() {
        let text = std::fs::read_to_string(concat!(env!("CARGO_MANIFEST_DIR"), "/../../docs/scenes.md")).unwrap();
        let rows: Vec<&str> = text.lines().filter(|l| l.starts_with("| `") && l.contains(".obj`")).collect();
        assert_eq!(rows.len(), KNOWN.len(), "{rows:#?}");
        for k in &KNOWN {
            let row =
                rows.iter().find(|r| r.starts_with(&format!("| `{}`", k.file))).unwrap_or_else(|| panic!("{}", k.file));
            let triangles = k.triangles.to_string();
            let with_commas = if triangles.len() > 3 {
                format!("{},{}", &triangles[..triangles.len() - 3], &triangles[triangles.len() - 3..])
            } else {
                triangles
            };
            assert!(row.contains(&format!("`{}`", k.sha256)), "{}: {row}", k.file);
            assert!(
                row.contains(&format!("| {with_commas} |")) || row.contains(&format!("| {with_commas} (")),
                "{}: {row}",
                k.file
            );
        }
    }

    #[test]
    fn every_shared_model_is_the_listed_file() {
        let dir = std::path::PathBuf::from(concat!(env!("CARGO_MANIFEST_DIR"), "/../../../shared/models"));
        if !dir.is_dir() {
            assert!(
                std::env::var_os("CI").is_none(),
                "CI always has ../shared/models, but {} is missing",
                dir.display()
            );
            eprintln!("{} is missing: not checked", dir.display());
            return;
        }
        for k in &KNOWN {
            let path = dir.join(k.file);
            let m = ModelFile::of(&path, &std::fs::read(&path).unwrap_or_else(|e| panic!("{}: {e}", path.display())));
            assert!(!m.differs(), "{}", m.describe());
            let mesh = crate::scene::obj::load_obj(&path).unwrap();
            assert_eq!(mesh.indices.len() / 3, k.triangles, "{}", k.file);
        }
    }
}
