//! Shader hot reload: the viewer polls the shader folder's files (their modification times) a
//! few times a second; the files that changed, appeared or went are forgotten by the shader
//! compiler (`ShaderCompiler::forget`, with every variant that includes them) and the
//! renderers are built again at the next frame, beside the running ones: a pipeline whose SPIR-V
//! came out as before is the running one, shared (`vkcore`'s shared pipelines), so only the
//! pipelines that use an edited file are made. A renderer that fails to build (a compile error,
//! reported as `file:line: message`) leaves the last good one running.

use std::collections::BTreeMap;
use std::path::{Path, PathBuf};
use std::time::{Duration, Instant, SystemTime};

/// How often the folder is looked at.
const EVERY: Duration = Duration::from_millis(250);

pub struct Watcher {
    root: PathBuf,
    files: BTreeMap<String, SystemTime>,
    last: Instant,
}

/// Every file under `root` with its modification time, by root-relative `/`-separated path.
fn scan(root: &Path) -> BTreeMap<String, SystemTime> {
    let mut out = BTreeMap::new();
    let mut dirs = vec![root.to_path_buf()];
    while let Some(dir) = dirs.pop() {
        let Ok(entries) = std::fs::read_dir(&dir) else { continue };
        for e in entries.flatten() {
            let path = e.path();
            match e.file_type() {
                Ok(t) if t.is_dir() => dirs.push(path),
                Ok(_) => {
                    let modified = e.metadata().and_then(|m| m.modified()).unwrap_or(SystemTime::UNIX_EPOCH);
                    if let Ok(rel) = path.strip_prefix(root) {
                        let rel: Vec<String> =
                            rel.components().map(|c| c.as_os_str().to_string_lossy().into_owned()).collect();
                        out.insert(rel.join("/"), modified);
                    }
                }
                Err(_) => {}
            }
        }
    }
    out
}

/// Every file under `root` (root-relative, `/`-separated): what the reload key forgets.
pub fn all_files(root: &Path) -> Vec<String> {
    scan(root).into_keys().collect()
}

impl Watcher {
    pub fn new(root: &Path) -> Watcher {
        Watcher { root: root.to_path_buf(), files: scan(root), last: Instant::now() }
    }

    /// The files that changed since the last call that found any (none between polls).
    pub fn changed(&mut self) -> Vec<String> {
        if self.last.elapsed() < EVERY {
            return vec![];
        }
        self.last = Instant::now();
        self.changed_now()
    }

    /// [`Watcher::changed`] without waiting for the next poll.
    pub fn changed_now(&mut self) -> Vec<String> {
        let now = scan(&self.root);
        let mut changed: Vec<String> = now
            .iter()
            .filter(|(f, t)| self.files.get(*f) != Some(*t))
            .map(|(f, _)| f.clone())
            .chain(self.files.keys().filter(|f| !now.contains_key(*f)).cloned())
            .collect();
        changed.sort();
        changed.dedup();
        self.files = now;
        changed
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn sees_edits_new_files_and_removals() {
        let root = caustics::scratch::ScratchDir::new("causticlab", "watch");
        std::fs::create_dir_all(root.join("eye")).expect("temp dir");
        std::fs::write(root.join("eye/a.frag"), "1").expect("write");
        let mut w = Watcher::new(&root);
        assert!(w.changed_now().is_empty());
        // Modification times can be coarse: set one explicitly.
        let f = std::fs::File::options().write(true).open(root.join("eye/a.frag")).expect("open");
        f.set_modified(SystemTime::now() + Duration::from_secs(5)).expect("set mtime");
        std::fs::write(root.join("b.glsl"), "2").expect("write");
        assert_eq!(w.changed_now(), vec!["b.glsl".to_string(), "eye/a.frag".to_string()]);
        std::fs::remove_file(root.join("b.glsl")).expect("remove");
        assert_eq!(w.changed_now(), vec!["b.glsl".to_string()]);
    }
}
