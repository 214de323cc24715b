//! A claim evaluated against the committed tables: the entries its picks select (read from
//! each table's JSON through the same grid the Markdown table is printed from, so an entry has
//! the labels a reader sees), and the arithmetic over them.
//!
//! Sets of entries combine entry by entry: in `a / b`, each entry of `a` is paired with the one
//! entry of `b` that has the same label on every axis neither side picked (the ratio of the
//! hierarchical gather to the dense one, photon count by photon count). A set used where a
//! number is written must hold one entry; `range`, `min`, `max`, `mean`, `median`, `sum` and
//! `count` turn a set into numbers.

use super::expr::{Expr, Op};
use crate::format::display;
use crate::table::Entry;
use anyhow::{anyhow, bail, Result};
use std::collections::{BTreeMap, BTreeSet, HashMap};
use std::path::{Path, PathBuf};

/// One table entry as a claim sees it.
#[derive(Debug, Clone)]
pub struct Item {
    pub keys: BTreeMap<String, String>,
    /// `Err(what the table prints instead)` for N/A, `not run`, `not measured (rule)`.
    pub value: std::result::Result<f64, String>,
    /// Interquartile range over the median, for times.
    pub spread: Option<f64>,
    /// Why a reader should not rank by this entry (`!`, `~`), if so.
    pub flag: Option<&'static str>,
    /// An unexplained plausibility finding (`?`): never citable.
    pub implausible: bool,
    /// Measured again for its spread (`spread_attempts`).
    pub remeasured: bool,
    /// The paper's value for the same cell (`[[paper]]`), as the table prints it in parentheses.
    pub paper: Option<f64>,
    pub table: String,
    /// The table's JSON, for the per-pass times and statistics of the entry's cell.
    pub source: PathBuf,
}

impl Item {
    pub fn describe(&self) -> String {
        let keys: Vec<String> = self.keys.iter().map(|(a, k)| format!("{a}={}", display(a, k))).collect();
        format!("{}{{{}}}", self.table, keys.join(" "))
    }
}

#[derive(Debug, Clone)]
pub enum Val {
    Num(f64),
    Range(f64, f64),
    /// Entries (or numbers derived from them, one per entry) and the axes their picks named.
    Set(Vec<Item>, BTreeSet<String>),
    /// Each comparison with what it compared.
    Truth(Vec<(bool, String)>),
}

/// The entries of one table, read once per check.
struct Table {
    entries: Vec<Entry>,
    axes: Vec<String>,
    /// For the per-pass columns of an entry's cell (`pass()`, `stat()`); none for a data file
    /// ([`super::data`]).
    results: Option<crate::results::Results>,
}

/// The tables a page's claims may read: its device folders (`<!--claims [ALIAS =] DIR -->`),
/// the first of them the default, its data files (`<!--claims NAME = FILE.csv -->`, read as
/// `NAME{...}`), and the aliases the page set.
pub struct Scope<'c> {
    pub root: PathBuf,
    pub devices: Vec<(Option<String>, PathBuf)>,
    pub files: Vec<(String, PathBuf)>,
    pub aliases: HashMap<String, Expr>,
    cache: &'c mut HashMap<PathBuf, Result<Table, String>>,
    /// Entries flagged `!` or `~` that a claim used.
    pub flagged: Vec<String>,
}

pub struct Cache(HashMap<PathBuf, Result<Table, String>>);

impl Cache {
    pub fn new() -> Self {
        Cache(HashMap::new())
    }
}

impl Default for Cache {
    fn default() -> Self {
        Self::new()
    }
}

fn load(path: &Path) -> Result<Table, String> {
    if path.extension().is_some_and(|x| x == "csv") {
        let entries = super::data::read(path).map_err(|e| format!("{e:#}"))?;
        return Ok(Table { axes: axes(&entries), entries, results: None });
    }
    let results = crate::results::read(path, "table").map_err(|e| format!("{e:#}"))?;
    let config: crate::config::Config = toml::from_str(&results.config.toml)
        .map_err(|e| format!("{}: the embedded config does not parse: {e}", path.display()))?;
    let grid = crate::table::grid(&config, &results);
    let entries: Vec<Entry> = grid.entries.into_iter().flatten().collect();
    Ok(Table { axes: axes(&entries), entries, results: Some(results) })
}

fn axes(entries: &[Entry]) -> Vec<String> {
    let mut axes: Vec<String> = entries.iter().flat_map(|e| e.keys.keys().cloned()).collect();
    axes.sort();
    axes.dedup();
    axes
}

impl<'c> Scope<'c> {
    pub fn new(root: &Path, cache: &'c mut Cache) -> Self {
        Scope {
            root: root.to_path_buf(),
            devices: vec![],
            files: vec![],
            aliases: HashMap::new(),
            cache: &mut cache.0,
            flagged: vec![],
        }
    }

    fn dir(&self, device: &Option<String>) -> Result<&Path> {
        match device {
            None => self.devices.first().map(|(_, d)| d.as_path()).ok_or_else(|| {
                anyhow!("the page names no table folder: put `<!--claims results/<device>/ -->` above its first claim")
            }),
            Some(alias) => self
                .devices
                .iter()
                .find(|(a, _)| a.as_deref() == Some(alias.as_str()))
                .map(|(_, d)| d.as_path())
                .ok_or_else(|| {
                    anyhow!("no folder `{alias}`: the page names it with `<!--claims {alias} = results/<device>/ -->`")
                }),
        }
    }

    fn entries(&mut self, device: &Option<String>, name: &str, pick: &[(String, String)]) -> Result<Val> {
        if device.is_none() {
            if let Some(Expr::Entries { device: d, name: n, pick: p }) = self.aliases.get(name).cloned() {
                let mut all = p.clone();
                all.extend(pick.iter().cloned());
                return self.entries(&d, &n, &all);
            }
        }
        let file = self.files.iter().find(|(n, _)| device.is_none() && n == name).map(|(_, f)| f.clone());
        let path = match file {
            Some(f) => self.root.join(f),
            None => {
                // A bench table, or else a data file of that name in the folder.
                let dir = self.root.join(self.dir(device)?);
                let json = crate::results::table_file(&dir, name)?;
                let csv = dir.join(format!("{name}.csv"));
                if !json.is_file() && csv.is_file() {
                    csv
                } else {
                    json
                }
            }
        };
        if !self.cache.contains_key(&path) {
            let t = load(&path);
            self.cache.insert(path.clone(), t);
        }
        let table = match &self.cache[&path] {
            Ok(t) => t,
            Err(e) => bail!("table `{name}`: {e}"),
        };
        for (axis, label) in pick {
            if !table.axes.contains(axis) {
                bail!("table `{name}` has no axis `{axis}` (its axes: {})", table.axes.join(", "));
            }
            let labels: BTreeSet<&String> = table.entries.iter().filter_map(|e| e.keys.get(axis)).collect();
            if !labels.iter().any(|k| label_matches(axis, k, label)) {
                let known: Vec<String> = labels.iter().map(|k| display(axis, k)).collect();
                bail!("table `{name}` has no {axis} `{label}` (it has: {})", known.join(", "));
            }
        }
        let items: Vec<Item> = table
            .entries
            .iter()
            .filter(|e| pick.iter().all(|(a, l)| e.keys.get(a).is_some_and(|k| label_matches(a, k, l))))
            .map(|e| item(name, &path, e))
            .collect();
        if items.is_empty() {
            bail!("`{name}` has no entry with {}", picks(pick));
        }
        Ok(Val::Set(items, pick.iter().map(|(a, _)| a.clone()).collect()))
    }

    pub fn eval(&mut self, e: &Expr) -> Result<Val> {
        match e {
            Expr::Num(v) => Ok(Val::Num(*v)),
            Expr::Str(t) => bail!("\"{t}\": quoted text is a pass name or a counter, for pass() and stat()"),
            Expr::Entries { device, name, pick } => self.entries(device, name, pick),
            Expr::Neg(x) => {
                let v = self.eval(x)?;
                self.binary(Op::Sub, Val::Num(0.0), v)
            }
            Expr::Bin(op, a, b) => {
                let (a, b) = (self.eval(a)?, self.eval(b)?);
                self.binary(*op, a, b)
            }
            Expr::Call(f, args) if f == "pass" || f == "stat" => self.per_pass(f, args),
            Expr::Call(f, args) => {
                let vals = args.iter().map(|a| self.eval(a)).collect::<Result<Vec<_>>>()?;
                self.call(f, vals)
            }
        }
    }

    /// Records the flags of entries a claim's number is built from.
    pub fn used(&mut self, it: &Item) -> Result<f64> {
        if it.implausible {
            bail!("{} is marked `?` (an unexplained plausibility finding): no sentence may cite it", it.describe());
        }
        let v = it.value.clone().map_err(|why| anyhow!("{} reads `{why}`, not a number", it.describe()))?;
        if let Some(f) = it.flag {
            let d = format!("{} ({f})", it.describe());
            if !self.flagged.contains(&d) {
                self.flagged.push(d);
            }
        }
        Ok(v)
    }

    fn numbers(&mut self, v: &Val, f: &str) -> Result<Vec<f64>> {
        match v {
            Val::Num(x) => Ok(vec![*x]),
            Val::Set(items, _) => items.iter().map(|it| self.used(it)).collect(),
            Val::Range(..) => bail!("{f}() of a range"),
            Val::Truth(_) => bail!("{f}() of a comparison"),
        }
    }

    fn call(&mut self, f: &str, mut args: Vec<Val>) -> Result<Val> {
        let one = |args: &mut Vec<Val>| -> Result<Val> {
            if args.len() != 1 {
                bail!("{f}() takes one argument, not {}", args.len());
            }
            Ok(args.remove(0))
        };
        let set = |v: Val| -> Result<(Vec<Item>, BTreeSet<String>)> {
            match v {
                Val::Set(items, pinned) => Ok((items, pinned)),
                _ => bail!("{f}() takes table entries"),
            }
        };
        match f {
            "min" | "max" | "mean" | "median" | "sum" | "range" => {
                let v = one(&mut args)?;
                let xs = self.numbers(&v, f)?;
                if xs.is_empty() {
                    bail!("{f}() of nothing");
                }
                let lo = xs.iter().cloned().fold(f64::INFINITY, f64::min);
                let hi = xs.iter().cloned().fold(f64::NEG_INFINITY, f64::max);
                Ok(match f {
                    "min" => Val::Num(lo),
                    "max" => Val::Num(hi),
                    "sum" => Val::Num(xs.iter().sum()),
                    "mean" => Val::Num(xs.iter().sum::<f64>() / xs.len() as f64),
                    "median" => Val::Num(crate::stats::median(&xs).unwrap_or(f64::NAN)),
                    _ => Val::Range(lo, hi),
                })
            }
            // The entries of several picks together (a range over two techniques).
            "union" => {
                let mut all = vec![];
                let mut pinned = BTreeSet::new();
                for a in args {
                    let (items, p) = set(a)?;
                    all.extend(items);
                    pinned.extend(p);
                }
                Ok(Val::Set(all, pinned))
            }
            "count" => match one(&mut args)? {
                Val::Set(items, _) => Ok(Val::Num(items.len() as f64)),
                Val::Truth(t) => Ok(Val::Num(t.iter().filter(|(b, _)| *b).count() as f64)),
                _ => bail!("count() takes table entries or a comparison"),
            },
            "abs" => {
                let v = one(&mut args)?;
                self.map(v, f64::abs)
            }
            // Entries that read a number (not N/A, `not run` or `not measured`).
            "measured" => {
                let (items, pinned) = set(one(&mut args)?)?;
                Ok(Val::Set(items.into_iter().filter(|i| i.value.is_ok()).collect(), pinned))
            }
            // Entries flagged for their spread (`!`), timed entries (those with a spread),
            // entries measured again for their spread, entries measured on a busy machine (`~`).
            "noisy" | "timed" | "remeasured" | "busy" | "marked" | "unmarked" => {
                let (items, pinned) = set(one(&mut args)?)?;
                let keep = |i: &Item| match f {
                    "noisy" => i.spread.is_some_and(crate::stats::is_noisy),
                    "remeasured" => i.remeasured,
                    "busy" => i.flag.is_some_and(|f| f.contains('~')),
                    // Marked `?` (to count them: their values stay uncitable), and the rest.
                    "marked" => i.implausible,
                    "unmarked" => !i.implausible,
                    _ => i.spread.is_some(),
                };
                Ok(Val::Set(items.into_iter().filter(keep).collect(), pinned))
            }
            // The spread as the table prints it: a percentage.
            "spread" => {
                let (items, pinned) = set(one(&mut args)?)?;
                let out = items
                    .into_iter()
                    .map(|mut i| {
                        let s = i.spread.ok_or_else(|| anyhow!("{} has no spread (not a time)", i.describe()))?;
                        i.value = Ok(100.0 * s);
                        i.flag = None;
                        Ok(i)
                    })
                    .collect::<Result<Vec<_>>>()?;
                Ok(Val::Set(out, pinned))
            }
            // The paper's value of each entry (the table's parentheses).
            "paper" => {
                let (items, pinned) = set(one(&mut args)?)?;
                let out = items
                    .into_iter()
                    .map(|mut i| {
                        i.value = i.paper.ok_or_else(|| "no paper value".to_string());
                        i.flag = None;
                        i.implausible = false;
                        i.spread = None;
                        i
                    })
                    .collect();
                Ok(Val::Set(out, pinned))
            }
            "all" | "any" => match one(&mut args)? {
                Val::Truth(t) => {
                    let ok = if f == "all" { t.iter().all(|(b, _)| *b) } else { t.iter().any(|(b, _)| *b) };
                    // What makes it so (`any`) or what breaks it (`all`).
                    let why = t
                        .iter()
                        .filter(|(b, _)| if f == "all" { !*b } else { *b || !ok })
                        .map(|(_, d)| d.clone())
                        .collect();
                    Ok(Val::Truth(vec![(ok, format!("{f}: {}", join(why)))]))
                }
                _ => bail!("{f}() takes a comparison"),
            },
            _ => bail!(
                "no function `{f}` (there are: min, max, mean, median, sum, range, count, union, abs, measured, noisy, timed, remeasured, busy, marked, unmarked, spread, paper, pass, stat, all, any)"
            ),
        }
    }

    /// `pass(entries, "glob")`: the median GPU time (ms) of the cell's passes whose names match,
    /// summed; `stat(entries, "glob", "counter")`: a pipeline-statistics counter of those passes
    /// (`fragment_invocations`, `compute_invocations`, ...), summed. Both read the JSON's
    /// `passes` of each entry's cell.
    fn per_pass(&mut self, f: &str, args: &[Expr]) -> Result<Val> {
        let want = if f == "pass" { 2 } else { 3 };
        if args.len() != want {
            bail!(
                "{f}() takes {} arguments",
                if f == "pass" {
                    "entries and a quoted pass name (`*` globs)"
                } else {
                    "entries, a quoted pass name and a quoted counter"
                }
            );
        }
        let text = |e: &Expr| match e {
            Expr::Entries { device: None, name, pick } if pick.is_empty() => Ok(name.clone()),
            Expr::Str(s) => Ok(s.clone()),
            _ => Err(anyhow!("{f}(): quote the pass name and the counter")),
        };
        let pattern = text(&args[1])?;
        let counter = if f == "stat" { Some(text(&args[2])?) } else { None };
        let Val::Set(items, pinned) = self.eval(&args[0])? else { bail!("{f}() takes table entries first") };
        let mut out = vec![];
        for mut it in items {
            let results = match self.cache.get(&it.source) {
                Some(Ok(Table { results: Some(r), .. })) => r,
                Some(Ok(_)) => bail!("{f}() reads a bench table's passes; {} is from a data file", it.describe()),
                _ => bail!("{}: its table is not loaded", it.describe()),
            };
            let cell = crate::table::find(results, &it.keys)
                .ok_or_else(|| anyhow!("{} has no cell in its table (not run)", it.describe()))?;
            let passes: Vec<&crate::record::Pass> =
                cell.passes.iter().filter(|p| crate::metrics::glob(&pattern, &p.name)).collect();
            if passes.is_empty() {
                let names: Vec<&str> = cell.passes.iter().map(|p| p.name.as_str()).take(12).collect();
                bail!("{}: no pass matches `{pattern}` (its passes: {}, ...)", it.describe(), names.join(", "));
            }
            let mut sum = 0.0;
            for p in passes {
                sum += match &counter {
                    None => p.median_ms,
                    Some(k) => {
                        let stats = p.pipeline_stats.as_ref().ok_or_else(|| {
                            anyhow!("{}: pass `{}` has no pipeline statistics", it.describe(), p.name)
                        })?;
                        let v = serde_json::to_value(stats)?;
                        v.get(k).and_then(|x| x.as_f64()).ok_or_else(|| {
                            let known: Vec<String> =
                                v.as_object().map(|o| o.keys().cloned().collect()).unwrap_or_default();
                            anyhow!("no counter `{k}` (there are: {})", known.join(", "))
                        })?
                    }
                };
            }
            it.value = Ok(sum);
            it.spread = None;
            it.flag = None;
            it.implausible = false;
            out.push(it);
        }
        Ok(Val::Set(out, pinned))
    }

    fn map(&mut self, v: Val, g: impl Fn(f64) -> f64) -> Result<Val> {
        Ok(match v {
            Val::Num(x) => Val::Num(g(x)),
            Val::Range(a, b) => Val::Range(g(a), g(b)),
            Val::Set(items, pinned) => {
                let mut out = vec![];
                for mut i in items {
                    let x = self.used(&i)?;
                    i.value = Ok(g(x));
                    out.push(i);
                }
                Val::Set(out, pinned)
            }
            Val::Truth(_) => bail!("arithmetic on a comparison"),
        })
    }

    fn binary(&mut self, op: Op, a: Val, b: Val) -> Result<Val> {
        let f = move |x: f64, y: f64| -> f64 {
            match op {
                Op::Add => x + y,
                Op::Sub => x - y,
                Op::Mul => x * y,
                Op::Div => x / y,
                _ => f64::NAN,
            }
        };
        let compare = matches!(op, Op::Lt | Op::Le | Op::Gt | Op::Ge | Op::Eq | Op::Ne);
        let test = move |x: f64, y: f64| -> bool {
            match op {
                Op::Lt => x < y,
                Op::Le => x <= y,
                Op::Gt => x > y,
                Op::Ge => x >= y,
                Op::Eq => x == y,
                _ => x != y,
            }
        };
        let sym = op.symbol();
        match (a, b) {
            (Val::Num(x), Val::Num(y)) if compare => Ok(Val::Truth(vec![(test(x, y), format!("{x} {sym} {y}"))])),
            (Val::Num(x), Val::Num(y)) => Ok(Val::Num(f(x, y))),
            (Val::Set(items, pinned), Val::Num(y)) => {
                let mut out = vec![];
                let mut truths = vec![];
                for mut i in items {
                    let x = self.used(&i)?;
                    if compare {
                        truths.push((test(x, y), format!("{} = {x} {sym} {y}", i.describe())));
                    } else {
                        i.value = Ok(f(x, y));
                        out.push(i);
                    }
                }
                Ok(if compare { Val::Truth(truths) } else { Val::Set(out, pinned) })
            }
            (Val::Num(x), Val::Set(items, pinned)) => {
                let flipped = match op {
                    Op::Lt => Op::Gt,
                    Op::Le => Op::Ge,
                    Op::Gt => Op::Lt,
                    Op::Ge => Op::Le,
                    o => o,
                };
                if compare || matches!(op, Op::Add | Op::Mul) {
                    return self.binary(flipped, Val::Set(items, pinned), Val::Num(x));
                }
                let mut out = vec![];
                for mut i in items {
                    let y = self.used(&i)?;
                    i.value = Ok(f(x, y));
                    out.push(i);
                }
                Ok(Val::Set(out, pinned))
            }
            (Val::Set(a, pa), Val::Set(b, pb)) => {
                let free: BTreeSet<String> = pa.union(&pb).cloned().collect();
                let mut out = vec![];
                let mut truths = vec![];
                for i in a {
                    let partners: Vec<&Item> = b.iter().filter(|j| paired(&i, j, &free)).collect();
                    let j = match partners.as_slice() {
                        [j] => *j,
                        [] => bail!("{} has no partner on the other side of `{sym}`", i.describe()),
                        many => bail!(
                            "{} pairs with {} entries on the other side of `{sym}` (pick more axes): {}",
                            i.describe(),
                            many.len(),
                            join(many.iter().take(3).map(|j| j.describe()).collect())
                        ),
                    };
                    let (x, y) = (self.used(&i)?, self.used(j)?);
                    if compare {
                        truths.push((test(x, y), format!("{} = {x} {sym} {} = {y}", i.describe(), j.describe())));
                    } else {
                        let mut k = i.clone();
                        k.value = Ok(f(x, y));
                        k.flag = None;
                        out.push(k);
                    }
                }
                Ok(if compare { Val::Truth(truths) } else { Val::Set(out, free) })
            }
            (Val::Range(..), _) | (_, Val::Range(..)) => bail!("`{sym}` on a range: take range() last"),
            _ => bail!("`{sym}` on a comparison"),
        }
    }
}

/// Same label on every axis that neither side picked.
fn paired(a: &Item, b: &Item, picked: &BTreeSet<String>) -> bool {
    a.keys.iter().filter(|(ax, _)| !picked.contains(*ax)).all(|(ax, k)| b.keys.get(ax) == Some(k))
}

/// `photons=2048` and `photons=2048²` both name the label `2048`; a scene may be named by its
/// file's stem.
fn label_matches(axis: &str, key: &str, written: &str) -> bool {
    key == written || display(axis, key) == written
}

fn item(table: &str, source: &Path, e: &Entry) -> Item {
    let value = if e.not_run {
        Err(crate::sections::NOT_RUN.to_string())
    } else if e.missing {
        Err(crate::sections::MISSING.to_string())
    } else if let Some(rule) = &e.unmeasured {
        Err(format!("{} ({rule})", crate::sections::UNMEASURED))
    } else {
        e.ours.ok_or_else(|| "–".to_string())
    };
    let flag = if e.noisy() {
        Some("spread over 10%, `!`")
    } else if e.busy {
        Some("measured on a busy machine, `~`")
    } else {
        None
    };
    Item {
        keys: e.keys.clone(),
        value,
        spread: e.spread,
        flag,
        implausible: e.implausible,
        remeasured: e.remeasured,
        paper: e.paper.as_ref().map(|p| p.value),
        table: table.to_string(),
        source: source.to_path_buf(),
    }
}

fn picks(pick: &[(String, String)]) -> String {
    pick.iter().map(|(a, l)| format!("{a}={l}")).collect::<Vec<_>>().join(" ")
}

fn join(v: Vec<String>) -> String {
    v.join("; ")
}
