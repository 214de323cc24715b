//! Where `shape = "obj"` files are looked for.

use std::path::{Path, PathBuf};

/// An ordered list of directories searched for model files; the first hit wins.
#[derive(Debug, Clone, Default, PartialEq, Eq)]
pub struct ModelSearchPath {
    pub dirs: Vec<PathBuf>,
}

impl ModelSearchPath {
    /// The default search path for a scene file:
    /// 1. the scene file's folder, 2. `<scene folder>/models`,
    /// 3. each entry of `$CAUSTICLAB_MODELS` (colon separated),
    /// 4. `../shared/models` relative to the current directory,
    /// 5. `../shared/models` relative to the workspace root (the nearest ancestor of the scene
    ///    file holding a `Cargo.toml` with a `[workspace]` table).
    pub fn for_scene(scene_file: &Path) -> Self {
        let scene_dir = match scene_file.parent() {
            Some(p) if !p.as_os_str().is_empty() => p.to_path_buf(),
            _ => PathBuf::from("."),
        };
        let mut dirs = vec![scene_dir.clone(), scene_dir.join("models")];
        if let Some(var) = std::env::var_os("CAUSTICLAB_MODELS") {
            dirs.extend(std::env::split_paths(&var).filter(|p| !p.as_os_str().is_empty()));
        }
        if let Ok(cwd) = std::env::current_dir() {
            dirs.push(shared_models_beside(&cwd));
        }
        if let Some(root) = workspace_root(&scene_dir) {
            dirs.push(shared_models_beside(&root));
        }
        let mut unique: Vec<PathBuf> = Vec::with_capacity(dirs.len());
        for d in dirs {
            if !unique.contains(&d) {
                unique.push(d);
            }
        }
        Self { dirs: unique }
    }

    /// The first `dir/file` that is a file. An absolute `file` is used as is.
    pub fn find(&self, file: &str) -> Option<PathBuf> {
        let f = Path::new(file);
        if f.is_absolute() {
            return f.is_file().then(|| f.to_path_buf());
        }
        self.dirs.iter().map(|d| d.join(f)).find(|p| p.is_file())
    }

    /// The directories as a comma-separated list, for error messages.
    pub fn describe(&self) -> String {
        let v: Vec<String> = self.dirs.iter().map(|d| d.display().to_string()).collect();
        v.join(", ")
    }
}

/// `<parent of dir>/shared/models` (i.e. `dir/../shared/models` without the `..`).
fn shared_models_beside(dir: &Path) -> PathBuf {
    match dir.parent() {
        Some(parent) => parent.join("shared").join("models"),
        None => dir.join("..").join("shared").join("models"),
    }
}

/// The nearest ancestor of `start` (inclusive) with a `Cargo.toml` containing `[workspace]`.
fn workspace_root(start: &Path) -> Option<PathBuf> {
    // Canonical, so that `..` components do not confuse `parent()`.
    let abs = std::fs::canonicalize(start).or_else(|_| std::path::absolute(start)).ok()?;
    abs.ancestors()
        .find(|dir| {
            std::fs::read_to_string(dir.join("Cargo.toml"))
                .map(|text| text.lines().any(|l| l.trim() == "[workspace]"))
                .unwrap_or(false)
        })
        .map(Path::to_path_buf)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn default_path_order_and_workspace_root() {
        let manifest = Path::new(env!("CARGO_MANIFEST_DIR"));
        let scene = manifest.join("../../scenes/x.toml");
        let sp = ModelSearchPath::for_scene(&scene);
        assert_eq!(sp.dirs[0], manifest.join("../../scenes"));
        assert_eq!(sp.dirs[1], manifest.join("../../scenes/models"));
        // The workspace root is two levels above this crate; its sibling `shared/models`
        // is on the path (even when it does not exist).
        let root = std::fs::canonicalize(manifest.join("../..")).unwrap();
        let expect = root.parent().unwrap().join("shared").join("models");
        assert!(sp.dirs.contains(&expect), "{:?} lacks {expect:?}", sp.dirs);
    }

    #[test]
    fn find_uses_the_first_hit() {
        let base = crate::scratch::ScratchDir::new("causticlab-sp", "find");
        let (a, b) = (base.join("a"), base.join("b"));
        std::fs::create_dir_all(&a).unwrap();
        std::fs::create_dir_all(&b).unwrap();
        std::fs::write(b.join("m.obj"), "").unwrap();
        let sp = ModelSearchPath { dirs: vec![a.clone(), b.clone()] };
        assert_eq!(sp.find("m.obj"), Some(b.join("m.obj")));
        std::fs::write(a.join("m.obj"), "").unwrap();
        assert_eq!(sp.find("m.obj"), Some(a.join("m.obj")));
        assert_eq!(sp.find("none.obj"), None);
    }
}
