//! Reads the dependencies between the modules of a crate's source tree (its `crate::`, `super::`
//! and `self::` paths, and paths through the names its `use` items bring in) and checks them
//! against the layers of `caustics` (see `main.rs`). A small reader, not a Rust parser: it
//! blanks comments, strings and `#[cfg(test)]` items, then follows paths.

use std::collections::{BTreeMap, BTreeSet};
use std::path::Path;

/// The technique folders under `techniques/`: the papers' and `photon_trace` (beyond them).
pub const PAPERS: &[&str] =
    &["shah2007", "trendall_stewart2000", "wyman2008", "wyman_davis2006", "wyman_nichols2009", "photon_trace"];

/// One dependency: the part `from` names an item of the part `to` (maybe itself) at `at`
/// (file:line).
#[derive(Debug, Clone)]
pub struct Dep {
    pub from: String,
    pub to: String,
    pub at: String,
    pub file: String,
    pub path: Vec<String>,
}

/// Every `.rs` file under `src`, by its path relative to `src` with `/` separators.
pub fn read_tree(src: &Path) -> BTreeMap<String, String> {
    let mut out = BTreeMap::new();
    let mut stack = vec![src.to_path_buf()];
    while let Some(dir) = stack.pop() {
        for e in std::fs::read_dir(&dir).unwrap_or_else(|e| panic!("reading {}: {e}", dir.display())) {
            let p = e.unwrap().path();
            if p.is_dir() {
                stack.push(p);
            } else if p.extension().is_some_and(|x| x == "rs") {
                let rel = p.strip_prefix(src).unwrap().to_string_lossy().replace('\\', "/");
                out.insert(rel, std::fs::read_to_string(&p).unwrap());
            }
        }
    }
    out
}

/// The module path of a file: `a/b.rs` and `a/b/mod.rs` are `[a, b]`, `lib.rs` is `[]`.
fn module_of(rel: &str) -> Vec<String> {
    let mut segs: Vec<String> = rel.trim_end_matches(".rs").split('/').map(str::to_string).collect();
    if matches!(segs.last().map(String::as_str), Some("mod" | "lib" | "main")) {
        segs.pop();
    }
    segs
}

/// Modules of the settings layer besides the `settings` ones: the pure arithmetic that the
/// settings' validation runs (the adaptive batch plan and the photon layout it sizes).
const SETTINGS_ARITHMETIC: &[&[&str]] = &[
    &["techniques", "wyman_nichols2009", "adaptive", "batches"],
    &["techniques", "wyman_nichols2009", "adaptive", "photon"],
];

/// The part of the crate a module path belongs to (the nodes of the cycle check).
pub fn part(path: &[String], top_level: &BTreeSet<String>) -> String {
    let s: Vec<&str> = path.iter().map(String::as_str).collect();
    let folder = |x: &str| PAPERS.contains(&x) || x == "shared";
    match s.as_slice() {
        ["techniques", "settings" | "technique" | "value_enum", ..] => "settings".into(),
        ["techniques", f, "settings", ..] if folder(f) => "settings".into(),
        _ if SETTINGS_ARITHMETIC.iter().any(|m| s.starts_with(m)) => "settings".into(),
        ["techniques", f, ..] if folder(f) => format!("techniques::{f}"),
        [first, ..] if top_level.contains(*first) => first.to_string(),
        // The crate root's own items (`InputError`, the `input_error!` macro) are `error`'s.
        _ => "error".into(),
    }
}

/// Blanks comments, string and char literals (keeping lines), so only code is read.
fn blank(src: &str) -> String {
    let c: Vec<char> = src.chars().collect();
    let mut out = String::with_capacity(src.len());
    let keep = |out: &mut String, ch: char| out.push(if ch == '\n' { '\n' } else { ' ' });
    let mut i = 0;
    while i < c.len() {
        if c[i] == '/' && c.get(i + 1) == Some(&'/') {
            while i < c.len() && c[i] != '\n' {
                keep(&mut out, c[i]);
                i += 1;
            }
        } else if c[i] == '/' && c.get(i + 1) == Some(&'*') {
            let mut depth = 0;
            loop {
                if i >= c.len() {
                    break;
                }
                if c[i] == '/' && c.get(i + 1) == Some(&'*') {
                    depth += 1;
                    out.push_str("  ");
                    i += 2;
                } else if c[i] == '*' && c.get(i + 1) == Some(&'/') {
                    depth -= 1;
                    out.push_str("  ");
                    i += 2;
                    if depth == 0 {
                        break;
                    }
                } else {
                    keep(&mut out, c[i]);
                    i += 1;
                }
            }
        } else if c[i] == 'r'
            && (c.get(i + 1) == Some(&'"') || c.get(i + 1) == Some(&'#'))
            && (i == 0 || !is_ident(c[i - 1]))
        {
            // Raw string r"..." or r#"..."#.
            let mut j = i + 1;
            let mut hashes = 0;
            while c.get(j) == Some(&'#') {
                hashes += 1;
                j += 1;
            }
            if c.get(j) != Some(&'"') {
                out.push(c[i]);
                i += 1;
                continue;
            }
            let close: String = std::iter::once('"').chain(std::iter::repeat_n('#', hashes)).collect();
            let rest: String = c[j + 1..].iter().collect();
            let len = rest.find(&close).map(|k| rest[..k].chars().count()).unwrap_or(c.len() - j - 1);
            let end = (j + 1 + len + close.chars().count()).min(c.len());
            for &ch in &c[i..end] {
                keep(&mut out, ch);
            }
            i = end;
        } else if c[i] == '"' {
            i = blank_quoted(&c, i, '"', &mut out);
        } else if c[i] == '\'' && (c.get(i + 2) == Some(&'\'') || c.get(i + 1) == Some(&'\\')) {
            // A char literal ('x', '\n', '\u{..}'), not a lifetime.
            i = blank_quoted(&c, i, '\'', &mut out);
        } else {
            out.push(c[i]);
            i += 1;
        }
    }
    out
}

/// Blanks the literal that opens with `quote` at `c[i]` (escapes skipped, an unclosed one
/// running to the end) into `out`; returns the index after it.
fn blank_quoted(c: &[char], mut i: usize, quote: char, out: &mut String) -> usize {
    let mut keep = |ch: char| out.push(if ch == '\n' { '\n' } else { ' ' });
    keep(c[i]);
    i += 1;
    while i < c.len() && c[i] != quote {
        if c[i] == '\\' && i + 1 < c.len() {
            keep(c[i]);
            i += 1;
        }
        keep(c[i]);
        i += 1;
    }
    if i < c.len() {
        keep(c[i]);
        i += 1;
    }
    i
}

fn is_ident(ch: char) -> bool {
    ch.is_alphanumeric() || ch == '_'
}

/// Blanks every `#[cfg(test)]` item of (blanked) code; returns the test modules declared out of
/// line (`#[cfg(test)] mod tests;`).
fn drop_test_items(code: &mut String) -> Vec<String> {
    let mut test_mods = vec![];
    while let Some(at) = code.find("#[cfg(test)]") {
        let semi = code[at..].find(';').map(|k| at + k);
        let brace = code[at..].find('{').map(|k| at + k);
        let end = match (semi, brace) {
            (Some(s), b) if b.is_none_or(|b| s < b) => {
                let item = &code[at + "#[cfg(test)]".len()..s];
                if let Some(name) = item.split_whitespace().skip_while(|w| *w != "mod").nth(1) {
                    test_mods.push(name.to_string());
                }
                s + 1
            }
            (_, Some(b)) => {
                let mut depth = 0;
                let mut end = code.len();
                for (k, ch) in code[b..].char_indices() {
                    match ch {
                        '{' => depth += 1,
                        '}' => {
                            depth -= 1;
                            if depth == 0 {
                                end = b + k + 1;
                                break;
                            }
                        }
                        _ => {}
                    }
                }
                end
            }
            _ => code.len(),
        };
        let blanked: String = code[at..end].chars().map(|ch| if ch == '\n' { '\n' } else { ' ' }).collect();
        code.replace_range(at..end, &blanked);
    }
    test_mods
}

/// The paths of a `use` tree (`a::{b, c::{d as e}, self}`), each with the name it brings in.
fn use_paths(tree: &str, prefix: &[String], out: &mut Vec<(Vec<String>, Option<String>)>) {
    let tree = tree.trim().trim_start_matches("::");
    if let Some(open) = tree.find('{') {
        let mut segs = prefix.to_vec();
        segs.extend(tree[..open].split("::").map(str::trim).filter(|s| !s.is_empty()).map(str::to_string));
        let inner = &tree[open + 1..tree.rfind('}').unwrap_or(tree.len())];
        let (mut depth, mut start) = (0, 0);
        for (k, ch) in inner.char_indices() {
            match ch {
                '{' => depth += 1,
                '}' => depth -= 1,
                ',' if depth == 0 => {
                    use_paths(&inner[start..k], &segs, out);
                    start = k + 1;
                }
                _ => {}
            }
        }
        use_paths(&inner[start..], &segs, out);
        return;
    }
    if tree.is_empty() {
        return;
    }
    let (path, alias) = match tree.split_once(" as ") {
        Some((p, a)) => (p.trim(), Some(a.trim().to_string())),
        None => (tree, None),
    };
    let mut segs = prefix.to_vec();
    segs.extend(path.split("::").map(str::trim).filter(|s| !s.is_empty()).map(str::to_string));
    match segs.last().map(String::as_str) {
        Some("*") => {
            segs.pop();
            out.push((segs, None));
        }
        Some("self") => {
            segs.pop();
            let name = alias.or_else(|| segs.last().cloned());
            out.push((segs, name));
        }
        Some(last) => {
            let name = alias.unwrap_or_else(|| last.to_string());
            out.push((segs, (name != "_").then_some(name)));
        }
        None => {}
    }
}

struct FileReader<'a> {
    module: Vec<String>,
    modules: &'a BTreeSet<Vec<String>>,
    aliases: BTreeMap<String, Vec<String>>,
}

impl FileReader<'_> {
    /// The crate path a written path names, or `None` for another crate's.
    fn resolve(&self, segs: &[String]) -> Option<Vec<String>> {
        let (head, rest) = segs.split_first()?;
        let mut base = match head.as_str() {
            "crate" => vec![],
            "self" => self.module.clone(),
            "super" => {
                let mut b = self.module.clone();
                b.pop();
                let mut rest = rest;
                while rest.first().map(String::as_str) == Some("super") {
                    b.pop();
                    rest = &rest[1..];
                }
                b.extend(rest.iter().cloned());
                return Some(b);
            }
            name => {
                let mut child = self.module.clone();
                child.push(name.to_string());
                if self.modules.contains(&child) {
                    child
                } else {
                    self.aliases.get(name)?.clone()
                }
            }
        };
        base.extend(rest.iter().cloned());
        Some(base)
    }
}

/// Every dependency between parts of the crate in `files` (path relative to `src` -> source).
pub fn dependencies(files: &BTreeMap<String, String>) -> Vec<Dep> {
    let mut code: BTreeMap<String, String> = files.iter().map(|(p, s)| (p.clone(), blank(s))).collect();
    let modules: BTreeSet<Vec<String>> = files.keys().map(|p| module_of(p)).collect();
    let top_level: BTreeSet<String> = modules.iter().filter(|m| m.len() == 1).map(|m| m[0].clone()).collect();
    let mut test_modules = vec![];
    for (path, text) in code.iter_mut() {
        for name in drop_test_items(text) {
            let mut m = module_of(path);
            m.push(name);
            test_modules.push(m);
        }
    }
    let mut deps = vec![];
    for (rel, text) in &code {
        let module = module_of(rel);
        if test_modules.iter().any(|t| module.starts_with(t)) {
            continue;
        }
        let from = part(&module, &top_level);
        let mut reader = FileReader { module: module.clone(), modules: &modules, aliases: BTreeMap::new() };
        let line = |at: usize| text[..at].matches('\n').count() + 1;
        let mut found: Vec<(Vec<String>, usize)> = vec![];
        // `use` items first: they bring names in (an alias of a module is followed where used).
        let mut use_spans = vec![];
        let mut search = 0;
        while let Some(k) = text[search..].find("use ").map(|k| search + k) {
            search = k + 4;
            let before = text[..k].trim_end();
            // `pub`, `pub(crate)`, `pub(super)`, `pub(in path)` before it: a re-export.
            let visibility = before.rfind("pub").filter(|&p| {
                let v = &before[p..];
                v == "pub" || v.starts_with("pub(") && v.ends_with(')') && !v.contains([';', '{', '}'])
            });
            let item_start = visibility.map_or(before, |p| before[..p].trim_end());
            let starts_item = item_start.is_empty() || item_start.ends_with([';', '{', '}', ']']);
            if !starts_item || k > 0 && is_ident(text[..k].chars().last().unwrap()) {
                continue;
            }
            let Some(end) = text[k..].find(';').map(|e| k + e) else { continue };
            use_spans.push(k..end);
            let mut paths = vec![];
            use_paths(&text[k + 4..end], &[], &mut paths);
            for (segs, name) in paths {
                let Some(abs) = reader.resolve(&segs) else { continue };
                // A module brought in is followed where it is used; one re-exported is a
                // dependency itself.
                if !modules.contains(&abs) || name.is_none() || visibility.is_some() {
                    found.push((abs.clone(), k));
                }
                if let Some(name) = name {
                    reader.aliases.insert(name, abs);
                }
            }
        }
        // Paths written in the code: `crate::a::b`, `super::x`, `alias::y` (not the path of a
        // `pub(in path)` visibility, which names where an item is seen, not what it uses).
        let visibility_paths: Vec<std::ops::Range<usize>> =
            text.match_indices("pub(in ").map(|(p, _)| p..text[p..].find(')').map_or(text.len(), |e| p + e)).collect();
        let chars: Vec<(usize, char)> = text.char_indices().collect();
        let mut i = 0;
        while i < chars.len() {
            let (at, ch) = chars[i];
            let prev_ok = i == 0 || {
                let p = chars[i - 1].1;
                !is_ident(p) && p != ':'
            };
            if !(prev_ok && is_ident(ch)) || use_spans.iter().chain(&visibility_paths).any(|s| s.contains(&at)) {
                i += 1;
                continue;
            }
            let mut segs = vec![];
            let mut j = i;
            loop {
                let start = j;
                while j < chars.len() && is_ident(chars[j].1) {
                    j += 1;
                }
                segs.push(chars[start..j].iter().map(|c| c.1).collect::<String>());
                let colons = j + 1 < chars.len() && chars[j].1 == ':' && chars[j + 1].1 == ':';
                if colons && j + 2 < chars.len() && is_ident(chars[j + 2].1) {
                    j += 2;
                } else {
                    break;
                }
            }
            if segs.len() > 1 {
                if let Some(abs) = reader.resolve(&segs) {
                    found.push((abs, at));
                }
            }
            i = j.max(i + 1);
        }
        // Every dependency, within a part too: the paper rule applies between settings modules.
        for (abs, at) in found {
            let to = part(&abs, &top_level);
            deps.push(Dep { from: from.clone(), to, at: format!("{rel}:{}", line(at)), file: rel.clone(), path: abs });
        }
    }
    deps
}

/// What breaks the layers: a paper importing another paper or `shared` importing one, and
/// every cycle between parts (each with one place for each of its dependencies).
pub fn problems(deps: &[Dep]) -> Vec<String> {
    let mut out = vec![];
    for d in deps {
        let folder = d.file.strip_prefix("techniques/").and_then(|f| f.split_once('/')).map(|(f, _)| f);
        let target = match d.path.as_slice() {
            [t, p, ..] if t == "techniques" && PAPERS.contains(&p.as_str()) => Some(p.as_str()),
            _ => None,
        };
        match (folder, target) {
            (Some("shared"), Some(p)) => {
                out.push(format!("{}: shared imports a paper: {} ({p})", d.at, d.path.join("::")))
            }
            (Some(f), Some(p)) if f != p && PAPERS.contains(&f) => {
                out.push(format!("{}: {f} imports another paper: {}", d.at, d.path.join("::")))
            }
            _ => {}
        }
    }
    let mut graph: BTreeMap<&str, BTreeMap<&str, &str>> = BTreeMap::new();
    for d in deps.iter().filter(|d| d.from != d.to) {
        graph.entry(&d.from).or_default().entry(&d.to).or_insert(&d.at);
        graph.entry(&d.to).or_default();
    }
    for scc in strongly_connected(&graph) {
        if scc.len() < 2 {
            continue;
        }
        let mut edges = vec![];
        for a in &scc {
            for (b, at) in &graph[a] {
                if scc.contains(b) {
                    edges.push(format!("  {a} -> {b} at {at}"));
                }
            }
        }
        out.push(format!("cycle between {}:\n{}", scc.join(", "), edges.join("\n")));
    }
    out
}

/// Every dependency on a part of the same or a higher layer (`layers`, from the bottom up), and
/// every part in no layer.
pub fn out_of_order(deps: &[Dep], layers: &[&[&str]]) -> Vec<String> {
    let rank = |p: &str| layers.iter().position(|l| l.contains(&p));
    let mut out = vec![];
    for d in deps.iter().filter(|d| d.from != d.to) {
        match (rank(&d.from), rank(&d.to)) {
            (Some(a), Some(b)) if b < a => {}
            (Some(a), Some(b)) if a == b && d.from.starts_with("techniques::") => {} // see problems()
            (Some(_), Some(_)) => out.push(format!("{}: {} imports {}, a higher layer", d.at, d.from, d.to)),
            (None, _) => out.push(format!("{}: {} is in no layer", d.at, d.from)),
            (_, None) => out.push(format!("{}: {} is in no layer", d.at, d.to)),
        }
    }
    out
}

/// Tarjan's strongly connected components.
fn strongly_connected<'a>(graph: &BTreeMap<&'a str, BTreeMap<&'a str, &'a str>>) -> Vec<Vec<&'a str>> {
    struct State<'a> {
        index: BTreeMap<&'a str, usize>,
        low: BTreeMap<&'a str, usize>,
        stack: Vec<&'a str>,
        on_stack: BTreeSet<&'a str>,
        out: Vec<Vec<&'a str>>,
    }
    fn visit<'a>(v: &'a str, g: &BTreeMap<&'a str, BTreeMap<&'a str, &'a str>>, s: &mut State<'a>) {
        let n = s.index.len();
        s.index.insert(v, n);
        s.low.insert(v, n);
        s.stack.push(v);
        s.on_stack.insert(v);
        for &w in g[v].keys() {
            if !s.index.contains_key(w) {
                visit(w, g, s);
                let lw = s.low[w];
                let lv = s.low.get_mut(v).unwrap();
                *lv = (*lv).min(lw);
            } else if s.on_stack.contains(w) {
                let iw = s.index[w];
                let lv = s.low.get_mut(v).unwrap();
                *lv = (*lv).min(iw);
            }
        }
        if s.low[v] == s.index[v] {
            let mut scc = vec![];
            while let Some(w) = s.stack.pop() {
                s.on_stack.remove(w);
                scc.push(w);
                if w == v {
                    break;
                }
            }
            scc.sort();
            s.out.push(scc);
        }
    }
    let mut s =
        State { index: BTreeMap::new(), low: BTreeMap::new(), stack: vec![], on_stack: BTreeSet::new(), out: vec![] };
    for &v in graph.keys() {
        if !s.index.contains_key(v) {
            visit(v, graph, &mut s);
        }
    }
    s.out
}
