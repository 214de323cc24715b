//! Runtime GLSL -> SPIR-V with shaderc: `#include` resolved against the shader folder, defines
//! for variants, errors as `file:line: message`, and every (file, defines) variant compiled once.

use crate::error::{Result, VkError};
use std::collections::HashMap;
use std::path::{Path, PathBuf};
use std::sync::{Arc, Mutex};

/// Pipeline stage, from the file extension.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Stage {
    Vertex,
    Geometry,
    Fragment,
    Compute,
}

impl Stage {
    pub fn from_path(path: &str) -> Option<Stage> {
        match Path::new(path).extension()?.to_str()? {
            "vert" => Some(Stage::Vertex),
            "geom" => Some(Stage::Geometry),
            "frag" => Some(Stage::Fragment),
            "comp" => Some(Stage::Compute),
            _ => None,
        }
    }
    fn kind(self) -> shaderc::ShaderKind {
        match self {
            Stage::Vertex => shaderc::ShaderKind::Vertex,
            Stage::Geometry => shaderc::ShaderKind::Geometry,
            Stage::Fragment => shaderc::ShaderKind::Fragment,
            Stage::Compute => shaderc::ShaderKind::Compute,
        }
    }
}

/// A compiled shader: SPIR-V words plus where it came from.
#[derive(Debug, Clone)]
pub struct Spirv {
    pub file: String,
    pub stage: Stage,
    pub words: Arc<Vec<u32>>,
}

type Key = (String, Vec<(String, String)>);

/// Compiles GLSL files under `root`. Thread-safe; caches by (file, defines).
pub struct ShaderCompiler {
    root: PathBuf,
    compiler: Mutex<shaderc::Compiler>,
    /// Each variant with the files it was made from (itself and what it includes, relative to
    /// the root).
    cache: Mutex<HashMap<Key, (Spirv, Vec<String>)>>,
    compiled: std::sync::atomic::AtomicUsize,
}

impl ShaderCompiler {
    pub fn new(root: &Path) -> Result<ShaderCompiler> {
        let compiler =
            shaderc::Compiler::new().ok_or_else(|| VkError::Shader("could not initialise shaderc".into()))?;
        Ok(ShaderCompiler {
            root: root.to_path_buf(),
            compiler: Mutex::new(compiler),
            cache: Mutex::new(HashMap::new()),
            compiled: Default::default(),
        })
    }

    pub fn root(&self) -> &Path {
        &self.root
    }

    /// How many distinct variants were compiled (cache misses).
    pub fn compiled_count(&self) -> usize {
        self.compiled.load(std::sync::atomic::Ordering::Relaxed)
    }

    /// Compiles `file` (relative to the root, e.g. `eye/shade.frag`) with `defines`.
    pub fn compile(&self, file: &str, defines: &[(&str, &str)]) -> Result<Spirv> {
        let mut defs: Vec<(String, String)> = defines.iter().map(|(k, v)| (k.to_string(), v.to_string())).collect();
        defs.sort();
        let key = (file.to_string(), defs.clone());
        if let Some(s) = self.cache.lock().ok().and_then(|c| c.get(&key).map(|(s, _)| s.clone())) {
            return Ok(s);
        }
        let stage = Stage::from_path(file).ok_or_else(|| {
            VkError::Shader(format!("{file}:1: unknown shader stage (expected .vert/.geom/.frag/.comp)"))
        })?;
        let path = self.root.join(file);
        let source = std::fs::read_to_string(&path)
            .map_err(|source| VkError::ShaderIo { path: path.display().to_string(), source })?;
        let mut options = shaderc::CompileOptions::new().ok_or_else(|| VkError::Shader("shaderc options".into()))?;
        options.set_target_env(shaderc::TargetEnv::Vulkan, shaderc::EnvVersion::Vulkan1_3 as u32);
        options.set_source_language(shaderc::SourceLanguage::GLSL);
        options.set_generate_debug_info();
        for (k, v) in &defs {
            options.add_macro_definition(k, Some(v));
        }
        let root = self.root.clone();
        let included = Arc::new(Mutex::new(vec![file.to_string()]));
        let included_by_callback = included.clone();
        options.set_include_callback(move |requested, kind, requester, _depth| {
            let base = match kind {
                shaderc::IncludeType::Relative => {
                    root.join(requester).parent().map(Path::to_path_buf).unwrap_or(root.clone())
                }
                shaderc::IncludeType::Standard => root.clone(),
            };
            let mut candidate = base.join(requested);
            if !candidate.exists() {
                candidate = root.join(requested);
            }
            let content = std::fs::read_to_string(&candidate)
                .map_err(|e| format!("cannot include `{requested}` (looked for {}): {e}", candidate.display()))?;
            let name = candidate.strip_prefix(&root).unwrap_or(&candidate).to_string_lossy().into_owned();
            if let Ok(mut files) = included_by_callback.lock() {
                files.push(name.clone());
            }
            Ok(shaderc::ResolvedInclude { resolved_name: name, content })
        });
        let result = {
            let compiler = self.compiler.lock().map_err(|_| VkError::Shader("shaderc lock poisoned".into()))?;
            compiler.compile_into_spirv(&source, stage.kind(), file, "main", Some(&options))
        };
        let artifact = result.map_err(|e| VkError::Shader(format_shaderc_error(&e.to_string(), &defs)))?;
        let spirv = Spirv { file: file.to_string(), stage, words: Arc::new(artifact.as_binary().to_vec()) };
        self.compiled.fetch_add(1, std::sync::atomic::Ordering::Relaxed);
        let files = included.lock().map(|f| f.clone()).unwrap_or_default();
        if let Ok(mut c) = self.cache.lock() {
            c.insert(key, (spirv.clone(), files));
        }
        Ok(spirv)
    }

    /// Forgets every compiled variant made from one of `changed` (paths relative to the root,
    /// `/`-separated: the file itself or anything it includes), so that the next `compile`
    /// reads them again (the viewer's shader hot reload). Returns how many were forgotten.
    pub fn forget(&self, changed: &[String]) -> usize {
        let Ok(mut cache) = self.cache.lock() else { return 0 };
        let before = cache.len();
        cache.retain(|_, (_, files)| !files.iter().any(|f| changed.iter().any(|c| same_file(f, c))));
        before - cache.len()
    }
}

/// Whether two root-relative paths name one file (`a/./b.glsl` and `a/b.glsl` alike).
fn same_file(a: &str, b: &str) -> bool {
    let norm = |p: &str| Path::new(p).components().filter(|c| *c != std::path::Component::CurDir).collect::<PathBuf>();
    norm(a) == norm(b)
}

/// shaderc reports `file:line: error: text`; keep those lines, drop the summary, and say which
/// variant failed.
fn format_shaderc_error(raw: &str, defines: &[(String, String)]) -> String {
    let mut lines: Vec<String> = raw
        .lines()
        .filter(|l| !l.trim().is_empty() && !l.ends_with("generated."))
        .map(|l| l.replacen(": error: ", ": ", 1).to_string())
        .collect();
    if !defines.is_empty() {
        let d: Vec<String> = defines.iter().map(|(k, v)| format!("{k}={v}")).collect();
        lines.push(format!("(variant: {})", d.join(" ")));
    }
    lines.join("\n")
}

#[cfg(test)]
mod tests {
    use super::*;

    fn temp_root(name: &str) -> PathBuf {
        let dir = std::env::temp_dir().join(format!("vkcore-shader-{name}-{}", std::process::id()));
        let _ = std::fs::remove_dir_all(&dir);
        std::fs::create_dir_all(dir.join("sub")).unwrap();
        dir
    }

    #[test]
    fn includes_defines_and_cache() {
        let root = temp_root("ok");
        std::fs::write(root.join("common.glsl"), "#define SCALE 2.0\n").unwrap();
        std::fs::write(
            root.join("sub/a.comp"),
            "#version 450\n#include \"common.glsl\"\nlayout(local_size_x = 1) in;\nlayout(std430, binding = 0) buffer B { float x[]; };\nvoid main() { x[0] = SCALE * float(VALUE); }\n",
        )
        .unwrap();
        let c = ShaderCompiler::new(&root).unwrap();
        let a = c.compile("sub/a.comp", &[("VALUE", "3")]).unwrap();
        assert_eq!(a.words[0], 0x0723_0203, "SPIR-V magic number");
        c.compile("sub/a.comp", &[("VALUE", "3")]).unwrap();
        assert_eq!(c.compiled_count(), 1, "same variant compiled once");
        c.compile("sub/a.comp", &[("VALUE", "4")]).unwrap();
        assert_eq!(c.compiled_count(), 2, "another define is another variant");
        // Without the define, VALUE is undeclared: a compile error.
        let err = c.compile("sub/a.comp", &[]).unwrap_err().to_string();
        assert!(err.contains("sub/a.comp:5:"), "error names file:line, got: {err}");
        // An edit of the included file forgets both variants; they compile again.
        assert_eq!(c.forget(&["other.glsl".to_string()]), 0);
        assert_eq!(c.forget(&["common.glsl".to_string()]), 2);
        c.compile("sub/a.comp", &[("VALUE", "3")]).unwrap();
        assert_eq!(c.compiled_count(), 3, "forgotten, so compiled again");
        std::fs::remove_dir_all(&root).unwrap();
    }

    #[test]
    fn errors_in_includes_name_the_included_file() {
        let root = temp_root("inc");
        std::fs::write(root.join("bad.glsl"), "\n\nfloat f() { return undefined_thing; }\n").unwrap();
        std::fs::write(root.join("x.frag"), "#version 450\n#include \"bad.glsl\"\nvoid main() {}\n").unwrap();
        let c = ShaderCompiler::new(&root).unwrap();
        let err = c.compile("x.frag", &[]).unwrap_err().to_string();
        assert!(err.contains("bad.glsl:3:"), "got: {err}");
        assert!(err.contains("undefined_thing"), "got: {err}");
        let err = c.compile("missing.frag", &[]).unwrap_err().to_string();
        assert!(err.contains("missing.frag"), "got: {err}");
        std::fs::remove_dir_all(&root).unwrap();
    }
}
