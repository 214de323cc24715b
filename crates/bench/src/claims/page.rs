//! A page's claims: the HTML comments that tie a written number to its source, and the numbers
//! that look measured but have none.
//!
//! A claim follows the number it checks, on the same line, so the rendered page shows only the
//! number:
//!
//! ```text
//! <!--claims results/<device>/ -->          the folder of the tables the claims read (first: default)
//! <!--claims h100 = results/<device>/ -->   another folder, read as `h100:table{...}`
//! <!--claims cpu = results/photon_trace.csv -->   a script's data file, read as `cpu{...}`
//! <!--let t3 = wyman2008_table3{metric=Gather} -->   an alias for the page's later claims
//! 1.47-1.93x<!--= range(t3{technique=H} / t3{technique=D}) -->   the number (or range) before equals this
//! 89.3 ±4%<!--= t3{photons=2048 technique=D} -->  a value with its spread: both are checked
//! 12.8<!--=! ... -->                         the sentence says an entry it uses is flagged (`!`, `~`)
//! on every scene<!--? all(a < b) -->        the sentence is true of the tables
//! 9.8<!--paper wyman2008 Table 3, Hierarchical Gather, 2048² -->   a paper's value, found in its text
//! within 0.002<!--at-most max(abs(a - b)) -->   the written number bounds the computed ones
//! over 5x<!--at-least min(a / b) -->          (each entry of a set) from above or below
//! 10%<!--given the spread threshold -->      a number that is not a measurement (a setting, a bound)
//! ```
//!
//! The written number is matched at the precision it is written with: `1.93` is right for any
//! computed value in [1.925, 1.935].

use super::eval::{Cache, Scope, Val};
use super::expr::{parse, Expr};
use std::path::Path;

/// Something a page says that its source does not.
#[derive(Debug, Clone, PartialEq)]
pub struct Problem {
    pub line: usize,
    /// The number as the page writes it (or the claim's text, when there is no number).
    pub written: String,
    pub what: String,
}

/// The papers' plain-text copies in `../shared/papers`, by the key a `<!--paper -->` claim uses.
pub const PAPERS: [(&str, &str); 5] = [
    ("trendall2000", "004_c958c6bfba0d8482.txt"),
    ("wyman_davis2006", "002_56077c0cdf043e6f.txt"),
    ("shah", "003_a3efa02a5be6c8dc.txt"),
    ("wyman2008", "000_7c07a484f7a872bb.txt"),
    ("wyman_nichols2009", "001_703097990e1f01f3.txt"),
];

/// A number as written: `a`, `a-b`, or `a ±s%`; byte span in the line.
#[derive(Debug, Clone, PartialEq)]
pub struct Written {
    pub a: String,
    pub b: Option<String>,
    pub spread: Option<String>,
    pub start: usize,
}

impl Written {
    fn text(&self) -> String {
        match (&self.b, &self.spread) {
            (Some(b), _) => format!("{}-{b}", self.a),
            (None, Some(s)) => format!("{} ±{s}%", self.a),
            _ => self.a.clone(),
        }
    }
}

fn number_at(s: &[char], end: usize) -> Option<usize> {
    // The start of the number that ends just before `end` (digits, commas and one point).
    let mut i = end;
    while i > 0 && (s[i - 1].is_ascii_digit() || s[i - 1] == '.' || s[i - 1] == ',') {
        i -= 1;
    }
    while i < end && !s[i].is_ascii_digit() {
        i += 1;
    }
    (i < end).then_some(i)
}

/// The last number (or range, or value with spread) in `before`, with at most a unit between
/// it and the end.
pub fn written_before(before: &str) -> Option<Written> {
    let s: Vec<char> = before.chars().collect();
    // Skip a unit: anything but digits, at most 30 characters.
    let mut end = s.len();
    let mut skipped = 0;
    while end > 0 && !s[end - 1].is_ascii_digit() {
        if skipped == 30 || matches!(s[end - 1], '(' | '|' | '>') {
            return None;
        }
        end -= 1;
        skipped += 1;
    }
    let text = |a: usize, b: usize| -> String { s[a..b].iter().collect::<String>() };
    let mut a_start = number_at(&s, end)?;
    let mut a = text(a_start, end).trim_end_matches(['.', ',']).to_string();
    // `1.8e-7`, `3e5`: the mantissa before the exponent is part of the number.
    let sign = usize::from(a_start >= 1 && matches!(s[a_start - 1], '-' | '+'));
    if a_start > sign && s[a_start - sign - 1] == 'e' {
        if let Some(m) = number_at(&s, a_start - sign - 1) {
            a = text(m, end).trim_end_matches(['.', ',']).to_string();
            a_start = m;
        }
    }
    let mut spread = None;
    let mut b = None;
    // `v ±s%`: the last number is the spread.
    let mut j = a_start;
    while j > 0 && s[j - 1] == ' ' {
        j -= 1;
    }
    if j > 0 && s[j - 1] == '±' {
        let mut k = j - 1;
        while k > 0 && s[k - 1] == ' ' {
            k -= 1;
        }
        if let Some(v) = number_at(&s, k) {
            spread = Some(a);
            a = text(v, k);
            a_start = v;
        }
    } else if j > 0 {
        // `a-b`, `a–b`, `a to b`.
        let to = j >= 3 && s[j - 3..j].iter().collect::<String>() == " to";
        let cut = if s[j - 1] == '-' || s[j - 1] == '–' {
            Some(1)
        } else if to {
            Some(3)
        } else {
            None
        };
        if let Some(c) = cut {
            let mut k = j - c;
            while k > 0 && s[k - 1] == ' ' {
                k -= 1;
            }
            if let Some(v) = number_at(&s, k) {
                // Not a date or a label (`2026-11-27`, `x-1`).
                if v == 0 || !(s[v - 1].is_alphanumeric() || s[v - 1] == '-') {
                    b = Some(a);
                    a = text(v, k);
                    a_start = v;
                }
            }
        }
    }
    let start = s[..a_start].iter().collect::<String>().len();
    Some(Written { a, b, spread, start })
}

/// The power of ten of a written number's last digit, negated: 2 for `1.93`, 8 for `1.8e-7`.
fn decimals(s: &str) -> i32 {
    let (mantissa, exponent) = s.split_once('e').unwrap_or((s, "0"));
    mantissa.split_once('.').map(|(_, d)| d.len() as i32).unwrap_or(0) - exponent.parse::<i32>().unwrap_or(0)
}

fn parse_num(s: &str) -> Option<f64> {
    s.replace(',', "").parse().ok()
}

/// A written number and half a unit of its last written digit: `1.93` is (1.93, 0.005).
fn precise(written: &str) -> Option<(f64, f64)> {
    Some((parse_num(written)?, 0.5 * 10f64.powi(-decimals(written))))
}

/// Is `computed` what `written` says, at the precision it is written with?
pub fn agrees(written: &str, computed: f64) -> bool {
    let Some((w, half)) = precise(written) else { return false };
    (computed - w).abs() <= half * (1.0 + 1e-9) + 1e-12
}

fn shown(v: f64) -> String {
    crate::format::significant(v)
}

/// Checks a numeric claim's value against what is written.
fn compare(w: &Written, v: &Val) -> Option<String> {
    match (v, &w.b) {
        (Val::Range(lo, hi), Some(b)) => {
            (!agrees(&w.a, *lo) || !agrees(b, *hi)).then(|| format!("the tables give {}-{}", shown(*lo), shown(*hi)))
        }
        (Val::Range(lo, hi), None) => (!(agrees(&w.a, *lo) && agrees(&w.a, *hi)))
            .then(|| format!("the tables give a range, {}-{}, where one number is written", shown(*lo), shown(*hi))),
        (Val::Num(x), None) => (!agrees(&w.a, *x)).then(|| format!("the tables give {}", shown(*x))),
        (Val::Num(x), Some(b)) => {
            (!(agrees(&w.a, *x) && agrees(b, *x))).then(|| format!("the tables give one number, {}", shown(*x)))
        }
        (Val::Set(items, _), _) if items.len() == 1 => {
            let it = &items[0];
            let x = match &it.value {
                Ok(x) => *x,
                Err(why) => return Some(format!("{} reads `{why}`", it.describe())),
            };
            if w.b.is_some() {
                return Some(format!("{} is one number, {}", it.describe(), shown(x)));
            }
            if !agrees(&w.a, x) {
                return Some(format!("{} is {}", it.describe(), shown(x)));
            }
            match (&w.spread, it.spread) {
                (Some(s), Some(sp)) if !agrees(s, (100.0 * sp).round()) => {
                    Some(format!("{}'s spread is ±{:.0}%", it.describe(), 100.0 * sp))
                }
                (Some(_), None) => Some(format!("{} has no spread", it.describe())),
                _ => None,
            }
        }
        (Val::Set(items, _), _) => Some(format!(
            "the claim picks {} entries ({}, ...): pick more axes, or use range(), min(), max(), mean()",
            items.len(),
            items.iter().take(2).map(|i| i.describe()).collect::<Vec<_>>().join(", ")
        )),
        (Val::Truth(_), _) => Some("a comparison where a number is written: use `<!--? ... -->`".into()),
    }
}

/// A claim comment on a line: its kind (`=`, `=!`, `?`, `let`, `claims`, `paper`, `given`),
/// its text and its byte span.
struct Comment {
    kind: String,
    body: String,
    start: usize,
}

const KINDS: [&str; 9] = ["=!", "=", "?", "at-most ", "at-least ", "let ", "claims ", "paper ", "given"];

/// `line` with its code spans blanked (same byte offsets): a claim written in backticks is an
/// example, not a claim.
fn without_code(line: &str) -> String {
    let mut out = String::with_capacity(line.len());
    let mut in_code = false;
    let mut comment_end = 0;
    for (i, c) in line.char_indices() {
        if i < comment_end {
            out.push(c);
            continue;
        }
        if !in_code && line[i..].starts_with("<!--") {
            // A comment's text (a claim may name `a setting`) is kept whole.
            comment_end = line[i..].find("-->").map(|q| i + q + 3).unwrap_or(line.len());
            out.push(c);
        } else if c == '`' {
            in_code = !in_code;
            out.push(' ');
        } else if in_code {
            out.push_str(&" ".repeat(c.len_utf8()));
        } else {
            out.push(c);
        }
    }
    out
}

fn comments(line: &str) -> Vec<Comment> {
    let mut out = vec![];
    let mut from = 0;
    let bare = without_code(line);
    while let Some(p) = bare[from..].find("<!--") {
        let start = from + p;
        let Some(q) = bare[start + 4..].find("-->").map(|q| q + 4) else { break }; // `<!-->` closes nothing
        let end = start + q + 3;
        let inner = line[start + 4..start + q].trim_start();
        if let Some(k) = KINDS.iter().find(|k| inner.starts_with(**k)) {
            out.push(Comment { kind: k.trim().to_string(), body: inner[k.len()..].trim().to_string(), start });
        }
        from = end;
    }
    out
}

/// What one page's check found, and how many claims it checked.
#[derive(Debug, Default)]
pub struct PageReport {
    /// Does the page name its tables (`<!--claims DIR -->`)? Only such pages are held to their
    /// numbers; the others' measured-looking numbers are counted, not failed.
    pub enrolled: bool,
    pub claims: usize,
    pub problems: Vec<Problem>,
    /// Lines of `<!--paper -->` claims not checked because `../shared/papers` is missing.
    pub papers_missing: usize,
}

/// What is wrong with a bound (`at-most`, `at-least`): "within 0.002", "up to 9x", "more than
/// 5x": the written number bounds the computed one (each of a set's entries), at its written
/// precision.
fn beyond_bound(scope: &mut Scope, c: &Comment, w: &Written) -> Option<String> {
    let (bound, half) = precise(w.b.as_ref().unwrap_or(&w.a)).unwrap_or((f64::NAN, 0.0));
    scope.flagged.clear();
    let values = parse(&c.body).and_then(|e| scope.eval(&e)).and_then(|v| match v {
        Val::Num(x) => Ok(vec![x]),
        Val::Range(a, b) => Ok(vec![a, b]),
        Val::Set(items, _) => items.iter().map(|i| scope.used(i)).collect(),
        Val::Truth(_) => anyhow::bail!("a bound needs numbers, not a comparison"),
    });
    let xs = match values {
        Ok(xs) => xs,
        Err(e) => return Some(format!("{e:#}")),
    };
    let at_most = c.kind == "at-most";
    let x = xs.into_iter().find(|x| if at_most { *x > bound + half } else { *x < bound - half })?;
    let side = if at_most { "above" } else { "below" };
    Some(format!("the tables give {} ({side} the written bound)", shown(x)))
}

/// What is wrong with an equality (`=`, `=!`): the written number (range, value ±spread) against
/// the claim's value, and the flags of the entries it is built from against what the claim says.
fn unequal(scope: &mut Scope, c: &Comment, w: &Written) -> Option<String> {
    scope.flagged.clear();
    let v = match parse(&c.body).and_then(|e| scope.eval(&e)) {
        Ok(v) => v,
        Err(e) => return Some(format!("{e:#}")),
    };
    // A single entry quoted as it is goes through the same gate as arithmetic on entries: it
    // must read a number, carry no `?`, and its flags count.
    if let Val::Set(items, _) = &v {
        if let [it] = items.as_slice() {
            if let Err(e) = scope.used(it) {
                return Some(format!("{e:#}"));
            }
        }
    }
    if let Some(what) = compare(w, &v) {
        Some(what)
    } else if c.kind == "=" && !scope.flagged.is_empty() {
        Some(format!(
            "built from entries a reader should not rank by: {}; say so in the sentence and mark the claim `<!--=! ...-->`",
            scope.flagged.join(", ")
        ))
    } else if c.kind == "=!" && scope.flagged.is_empty() {
        Some("marked `=!` but built from no flagged entry".into())
    } else {
        None
    }
}

/// Checks every claim of `text` (a page under `root`) against the tables, and finds the
/// measured-looking numbers without one.
pub fn check_page(text: &str, root: &Path, cache: &mut Cache) -> PageReport {
    let mut scope = Scope::new(root, cache);
    let mut report = PageReport::default();
    let mut fenced = false;
    let papers = root.join("..").join("shared").join("papers");
    let (mut header, mut in_table) = (Vec::new(), false);
    for (n, line) in text.lines().enumerate() {
        let line_no = n + 1;
        if line.trim_start().starts_with("```") {
            fenced = !fenced;
            continue;
        }
        if fenced {
            continue;
        }
        let mut sourced: Vec<(usize, usize)> = vec![];
        let mut problem =
            |written: String, what: String| report.problems.push(Problem { line: line_no, written, what });
        for c in comments(line) {
            match c.kind.as_str() {
                "claims" => {
                    let (alias, dir) = match c.body.split_once('=') {
                        Some((a, d)) => (Some(a.trim().to_string()), d.trim()),
                        None => (None, c.body.as_str()),
                    };
                    if dir.ends_with(".csv") {
                        // One data file, read by its name: `<!--claims NAME = FILE.csv -->`.
                        match alias {
                            _ if !root.join(dir).is_file() => problem(c.body.clone(), format!("no data file `{dir}`")),
                            Some(name) if super::expr::is_bare_label(&name) => scope.files.push((name, dir.into())),
                            _ => problem(
                                c.body.clone(),
                                "`<!--claims NAME = FILE.csv -->`: a data file needs a name".into(),
                            ),
                        }
                    } else {
                        if !root.join(dir).is_dir() {
                            problem(c.body.clone(), format!("no table folder `{dir}`"));
                        }
                        scope.devices.push((alias, dir.into()));
                    }
                    report.enrolled = true;
                }
                "let" => match c.body.split_once('=').map(|(a, e)| (a.trim(), parse(e.trim()))) {
                    Some((name, Ok(e @ Expr::Entries { .. }))) => {
                        scope.aliases.insert(name.to_string(), e);
                    }
                    _ => problem(c.body.clone(), "`<!--let NAME = table{axis=label ...} -->` expected".into()),
                },
                "?" => {
                    report.claims += 1;
                    scope.flagged.clear();
                    match parse(&c.body).and_then(|e| scope.eval(&e)) {
                        Ok(Val::Truth(t)) => {
                            let wrong: Vec<&String> = t.iter().filter(|(b, _)| !b).map(|(_, d)| d).collect();
                            if !wrong.is_empty() {
                                let list: Vec<&str> = wrong.iter().take(3).map(|s| s.as_str()).collect();
                                problem(c.body.clone(), format!("not true of the tables: {}", list.join("; ")));
                            }
                        }
                        Ok(_) => problem(c.body.clone(), "`<!--? -->` needs a comparison".into()),
                        Err(e) => problem(c.body.clone(), format!("{e:#}")),
                    }
                }
                "at-most" | "at-least" | "=" | "=!" | "paper" | "given" => {
                    let Some(w) = written_before(&line[..c.start]) else {
                        problem(c.body.clone(), "no number just before the claim".into());
                        continue;
                    };
                    sourced.push((w.start, c.start));
                    if c.kind == "given" {
                        continue;
                    }
                    report.claims += 1;
                    let found = match c.kind.as_str() {
                        "paper" => match paper_has(&papers, &c.body, &w) {
                            Ok(true) => None,
                            Ok(false) => {
                                report.papers_missing += 1;
                                None
                            }
                            Err(e) => Some(e),
                        },
                        "at-most" | "at-least" => beyond_bound(&mut scope, &c, &w),
                        _ => unequal(&mut scope, &c, &w),
                    };
                    if let Some(what) = found {
                        problem(w.text(), what);
                    }
                }
                _ => {}
            }
        }
        let row = line.trim_start().starts_with('|');
        if row && !in_table {
            header = cells(line);
        }
        in_table = row;
        for (start, text) in unsourced(line) {
            // A column of section, equation or figure numbers holds labels.
            let label_column = row
                && header.get(column_at(line, start)).is_some_and(|h| {
                    let h = h.to_lowercase();
                    ["sec", "eq.", "fig"].iter().any(|w| h.contains(w))
                });
            if !label_column && !sourced.iter().any(|&(a, b)| start >= a && start < b) {
                report.problems.push(Problem {
                    line: line_no,
                    written: text,
                    what: "a measured number without a source: add a claim (`<!--= ... -->`, `<!--paper ... -->`) or `<!--given why -->`".into(),
                });
            }
        }
    }
    report
}

/// A Markdown table row's cells (escaped `\|` kept inside a cell).
fn cells(line: &str) -> Vec<String> {
    let mut out = vec![String::new()];
    let mut prev = ' ';
    for c in line.trim().trim_start_matches('|').chars() {
        if c == '|' && prev != '\\' {
            out.push(String::new());
        } else if let Some(last) = out.last_mut() {
            last.push(c);
        }
        prev = c;
    }
    out
}

/// The column (0-based) of byte `at` in a table row.
fn column_at(line: &str, at: usize) -> usize {
    let lead = line.len() - line.trim_start().len();
    let before = &line[lead..at];
    let bars = before.match_indices('|').filter(|(i, _)| *i == 0 || !before[..*i].ends_with('\\')).count();
    bars.saturating_sub(1)
}

/// Checks that a paper's text has the written number(s): `Ok(false)` when the papers are not
/// beside the repository.
fn paper_has(papers: &Path, body: &str, w: &Written) -> Result<bool, String> {
    let key = body.split_whitespace().next().unwrap_or("");
    let Some((_, file)) = PAPERS.iter().find(|(k, _)| *k == key) else {
        let keys: Vec<&str> = PAPERS.iter().map(|(k, _)| *k).collect();
        return Err(format!("`<!--paper KEY where -->`: no paper `{key}` (keys: {})", keys.join(", ")));
    };
    if body.split_whitespace().count() < 2 {
        return Err(format!("`<!--paper {key} -->` must say where in the paper (table, row, column; or section)"));
    }
    let Ok(text) = std::fs::read_to_string(papers.join(file)) else { return Ok(false) };
    for n in [Some(&w.a), w.b.as_ref()].into_iter().flatten() {
        if !has_token(&text, n) {
            return Err(format!("`{n}` does not occur in {key}'s text ({file})"));
        }
    }
    Ok(true)
}

fn has_token(text: &str, n: &str) -> bool {
    text.match_indices(n).any(|(i, _)| {
        let before = text[..i].chars().next_back();
        let after = text[i + n.len()..].chars().next();
        !before.is_some_and(|c| c.is_ascii_digit() || c == '.')
            && !after.is_some_and(|c| {
                c.is_ascii_digit() || (c == '.' && text[i + n.len() + 1..].starts_with(|d: char| d.is_ascii_digit()))
            })
    })
}

/// Units after which a number is a measurement (a size in memory is one too: a setting that
/// names one says so with `given`).
const UNITS: [&str; 22] = [
    "ms",
    "µs",
    "fps",
    "x",
    "×",
    "%",
    "GB/s",
    "MB/s",
    "GiB/s",
    "MiB/s",
    "M photons/s",
    "Mphotons/s",
    "times",
    "s",
    "seconds",
    "minutes",
    "min",
    "KiB",
    "MiB",
    "GiB",
    "MB",
    "GB",
];

/// Words before which a decimal is a label, not a measurement (`Sec. 3.3`, `Mesa 22.3`).
const LABEL_WORDS: [&str; 17] = [
    "sec.", "section", "sections", "fig.", "figs.", "figure", "eq.", "eqs.", "equation", "table", "tables", "mesa",
    "llvm", "vulkan", "version", "ch.", "§",
];

/// Masks what is not prose: code spans, comments and link targets.
fn prose(line: &str) -> Vec<char> {
    let mut s: Vec<char> = line.chars().collect();
    let mut i = 0;
    let blank = |s: &mut Vec<char>, a: usize, b: usize| (a..b.min(s.len())).for_each(|k| s[k] = ' ');
    while i < s.len() {
        let rest: String = s[i..s.len().min(i + 4)].iter().collect();
        if s[i] == '`' {
            let end = s[i + 1..].iter().position(|&c| c == '`').map(|p| i + 2 + p).unwrap_or(s.len());
            blank(&mut s, i, end);
            i = end;
        } else if rest.starts_with("<!--") {
            let tail: String = s[i..].iter().collect();
            let end = tail.find("-->").map(|p| i + tail[..p].chars().count() + 3).unwrap_or(s.len());
            blank(&mut s, i, end);
            i = end;
        } else if rest.starts_with("](") {
            let end = s[i..].iter().position(|&c| c == ')').map(|p| i + p + 1).unwrap_or(s.len());
            blank(&mut s, i, end);
            i = end;
        } else if rest.starts_with("http") {
            let end = s[i..].iter().position(|c| c.is_whitespace()).map(|p| i + p).unwrap_or(s.len());
            blank(&mut s, i, end);
            i = end;
        } else {
            i += 1;
        }
    }
    s
}

/// The measured-looking numbers of a line: (byte offset, text).
pub fn unsourced(line: &str) -> Vec<(usize, String)> {
    let s = prose(line);
    let byte = |i: usize| -> usize { line.chars().take(i).map(char::len_utf8).sum() };
    let mut out = vec![];
    let mut i = 0;
    while i < s.len() {
        // Not inside a word, a number or a name (`H100`, `Apache-2.0`).
        let starts = s[i].is_ascii_digit()
            && (i == 0 || !(s[i - 1].is_alphanumeric() || matches!(s[i - 1], '_' | '.' | ',')))
            && !(i > 1 && s[i - 1] == '-' && s[i - 2].is_alphabetic());
        if !starts {
            i += 1;
            continue;
        }
        let mut j = i;
        while j < s.len()
            && (s[j].is_ascii_digit()
                || ((s[j] == '.' || s[j] == ',') && s.get(j + 1).is_some_and(|c| c.is_ascii_digit())))
        {
            j += 1;
        }
        // Scientific notation (`1.8e-7`, `3e-7`): one number, read as far as its exponent.
        // Not a commit (`064e926`): no leading zero before a digit, an exponent of at most 3 digits.
        let mut sci = false;
        let leading_zero = s[i] == '0' && s.get(i + 1).is_some_and(|c| c.is_ascii_digit());
        if s.get(j) == Some(&'e') && !leading_zero {
            let k = j + 1 + usize::from(s.get(j + 1).is_some_and(|c| matches!(c, '-' | '+')));
            if s.get(k).is_some_and(|c| c.is_ascii_digit()) {
                j = k;
                while s.get(j).is_some_and(|c| c.is_ascii_digit()) {
                    j += 1;
                }
                sci = j - k <= 3 && !s.get(j).is_some_and(|c| c.is_alphanumeric());
            }
        }
        let token: String = s[i..j].iter().collect();
        let next = s.get(j).copied();
        // `4.19M` is a count in millions, not a label; `4M photons` (no decimal) stays a size.
        let magnitude =
            next.is_some_and(|c| matches!(c, 'k' | 'M' | 'G')) && !s.get(j + 1).is_some_and(|c| c.is_alphanumeric());
        let label = (token.matches('.').count() > 1 && !sci)
            || next
                .is_some_and(|c| matches!(c, '²' | '³' | '^' | '°') || (c.is_alphanumeric() && c != 'x' && !magnitude))
            || (next == Some('x') && s.get(j + 1).is_some_and(|c| c.is_alphanumeric()));
        let word: String = s[..i].iter().collect::<String>().trim_end().rsplit(' ').next().unwrap_or("").to_lowercase();
        let word = word.trim_start_matches(['(', '[', '*', '_']);
        let after: String = s[j..].iter().collect::<String>();
        let after = after.strip_prefix(' ').unwrap_or(&after);
        let unit = UNITS
            .iter()
            .any(|u| after.strip_prefix(u).is_some_and(|rest| !rest.starts_with(|c: char| c.is_alphanumeric())));
        let spread = i > 0 && s[..i].iter().rev().find(|c| **c != ' ') == Some(&'±');
        let measured = spread || unit || ((token.contains('.') || sci) && !LABEL_WORDS.contains(&word));
        if !label && measured {
            out.push((byte(i), token));
        }
        i = j.max(i + 1);
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    fn w(s: &str) -> (String, Option<String>, Option<String>) {
        let w = written_before(s).unwrap();
        (w.a, w.b, w.spread)
    }

    #[test]
    fn the_written_number_is_the_last_one_with_its_unit_range_or_spread() {
        assert_eq!(w("runs 1.47-1.93x"), ("1.47".into(), Some("1.93".into()), None));
        assert_eq!(w("| 89.3 ±4%"), ("89.3".into(), None, Some("4".into())));
        assert_eq!(w("0.065 against 0.095"), ("0.095".into(), None, None));
        assert_eq!(w("**7 to 12 times**"), ("7".into(), Some("12".into()), None));
        assert_eq!(w("60,350 clusters"), ("60,350".into(), None, None));
        assert_eq!(w("within 1.8e-7"), ("1.8e-7".into(), None, None));
        assert_eq!(w("0.5-3e-7 of it"), ("0.5".into(), Some("3e-7".into()), None));
        assert_eq!(w("on 2026-11-27"), ("27".into(), None, None));
        assert!(written_before("no number here").is_none());
        assert!(written_before("3 (a parenthesis between)").is_none());
    }

    #[test]
    fn ranges_spreads_and_units_at_their_edges() {
        // Spaces around a hyphen, an en dash, a range or a spread at the line's start.
        assert_eq!(w("from 3 - 5 ms"), ("3".into(), Some("5".into()), None));
        assert_eq!(w("1.47–1.93x"), ("1.47".into(), Some("1.93".into()), None));
        assert_eq!(w("- 5 ms"), ("5".into(), None, None));
        assert_eq!(w("3 -5 ms"), ("3".into(), Some("5".into()), None));
        assert_eq!(w("±4%"), ("4".into(), None, None));
        // A number's leading comma or point is not part of it.
        let lead = written_before("see ,12 ms").unwrap();
        assert_eq!((lead.a.as_str(), lead.start), ("12", 5));
        // At most 30 characters of unit between the number and the claim.
        assert_eq!(w(&format!("12{}", "x".repeat(30))), ("12".into(), None, None));
        assert!(written_before(&format!("12{}", "x".repeat(31))).is_none());
        // A problem shows the number as written, with its range or spread.
        let text = |s: &str| written_before(s).unwrap().text();
        assert_eq!((text("89.3 ±4%"), text("1-2 ms"), text("7 s")), ("89.3 ±4%".into(), "1-2".into(), "7".into()));
    }

    #[test]
    fn a_number_agrees_at_the_precision_it_is_written_with() {
        assert!(agrees("1.93", 1.9349));
        assert!(!agrees("1.93", 1.9351));
        assert!(agrees("1.93", 1.925));
        assert!(!agrees("2", 1.47));
        assert!(agrees("1,125", 1124.6));
        assert!(agrees("0.10", 0.0966));
        assert!(agrees("1.8e-7", 1.84e-7));
        assert!(!agrees("1.8e-7", 1.86e-7));
        assert!(agrees("3e5", 349_000.0));
        assert!(!agrees("0.10", 0.0949));
    }

    #[test]
    fn measured_looking_numbers_are_found_and_labels_are_not() {
        let found = |l: &str| unsourced(l).into_iter().map(|(_, t)| t).collect::<Vec<_>>();
        assert_eq!(found("takes 83.7 ms, 1.7x the 2048² run, ±4%"), vec!["83.7", "1.7", "4"]);
        assert_eq!(found("Sec. 3.3 on Mesa 22.3.6 at 1024² with `0.5 ms` in code"), Vec::<String>::new());
        assert_eq!(found("[t](results/a1.5.md) H100 4M photons 16x16 2026-11-27"), Vec::<String>::new());
        assert_eq!(found("relative error 0.065 (seed 2)"), vec!["0.065"]);
        assert_eq!(found("as the paper says (Sec. 4.3), **Table 2.1**"), Vec::<String>::new());
        assert_eq!(found("MIT OR Apache-2.0, at your option"), Vec::<String>::new());
        assert_eq!(found("shades 444.5M fragments with 4M photons and 16M3 labels"), vec!["444.5"]);
        // Scientific notation is one number, measured-looking; sizes in memory and durations too.
        assert_eq!(found("differ by 1.8e-7 and 3e-7, not 2e5x3 (e-7 alone)"), vec!["1.8e-7", "3e-7"]);
        assert_eq!(found("at 064e926, 1e5abc0 and 3e1234f"), Vec::<String>::new());
        assert_eq!(found("holds 450 MB, 2 MiB more, in 3 minutes or 0.5 µs; 64 MiBs"), vec!["450", "2", "3", "0.5"]);
    }

    #[test]
    fn code_comments_links_and_addresses_are_not_prose_wherever_they_sit() {
        let found = |l: &str| unsourced(l);
        let none: Vec<(usize, String)> = vec![];
        assert_eq!(found("see `x 12 ms` here"), none);
        assert_eq!(found("`a` 1.5 ms and `b 12 ms` 2.5 ms"), vec![(4, "1.5".to_string()), (25, "2.5".to_string())]);
        assert_eq!(found("<!--given 3.5 ms -->"), none);
        assert_eq!(found("a <!--given x 1.2--> b"), none);
        assert_eq!(found("[t](x/1.5/y) 2.5 ms"), vec![(13, "2.5".to_string())]);
        assert_eq!(found("see http://x/1.5 now 2.5 ms"), vec![(21, "2.5".to_string())]);
    }

    #[test]
    fn where_a_number_starts_and_ends_and_what_makes_it_a_label() {
        let found = |l: &str| unsourced(l).into_iter().map(|(_, t)| t).collect::<Vec<_>>();
        let none: Vec<String> = vec![];
        // Inside a name (`v1.5`, `ab-2.5`), a version (`1.2.3`), an angle, a 2.5D view: labels.
        assert_eq!(found("build v1.5 here"), none);
        assert_eq!(found("1 2 3 ab-2.5"), none);
        assert_eq!(found("at 1.2.3 now"), none);
        assert_eq!(found("a 2.5° turn"), none);
        assert_eq!(found("the 2.5d view"), none);
        // A leading minus, a full stop, thousands, exponents (not four digits of one).
        assert_eq!(unsourced("-1.5 ms"), vec![(1, "1.5".to_string())]);
        assert_eq!(found("takes 1.5. Then"), ["1.5"]);
        assert_eq!(found("60,350 ms"), ["60,350"]);
        assert_eq!(found("about 12e3 of them"), ["12e3"]);
        assert_eq!(found("about 0.5e3 of them"), ["0.5e3"]);
        assert_eq!(found("about 1e1234 of them"), none);
        // A spread is measured without a unit.
        assert_eq!(unsourced("varies ±4 between runs"), vec![(9, "4".to_string())]);
    }

    #[test]
    fn a_claim_in_backticks_is_an_example_and_a_claim_may_name_code() {
        let kinds = |l: &str| comments(l).into_iter().map(|c| c.kind).collect::<Vec<_>>();
        assert_eq!(kinds("write `<!--claims DIR -->` at the top"), Vec::<String>::new());
        assert_eq!(kinds("0.5<!--given a level of `[front] levels` --> and 1.2<!--= t{a=b} -->"), vec!["given", "="]);
        assert_eq!(kinds("0.5<!--given the ` quote --> then `code <!--= x -->`"), vec!["given"]);
        // Code spans at the line's start and right after a comment.
        assert_eq!(kinds("`x` 5<!--= y -->"), vec!["="]);
        assert_eq!(without_code("<!--x-->`a`b"), "<!--x-->   b");
        assert_eq!(kinds("2<!--= a -->`<!--= b -->`"), vec!["="]);
        // `<!-->` (which used to panic the check) opens a comment that the next `-->` closes.
        assert_eq!(kinds("a <!--> b 5<!--= y --> c"), Vec::<String>::new());
        assert_eq!(kinds("a <!--> b"), Vec::<String>::new());
    }

    #[test]
    fn float_noise_below_a_trillionth_is_equality() {
        // Written with 14 decimals, half a unit is 5e-15; the difference 5e-13 is float noise.
        assert!(agrees("0.00000000000000", 5e-13));
        assert!(!agrees("0.00000000000000", 2e-12));
    }
}
