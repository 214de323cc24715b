//! Every published value of every config in `bench_configs/` (`[[paper]]`) against the paper's
//! plain text in `../shared/papers` (beside the repository; its README.md names each paper's
//! file), at the place the entry's `source` cites (`bench::paper::citations`):
//!
//! - `Table N, row R`: the table's rows are the lines next to its caption (`Table N:` below them,
//!   as in the Wyman papers' text, or `**Table N.**` above them, as in Trendall & Stewart's);
//!   the row is the first of them labelled R (labels compared as words, `2048 <sup>2</sup>`,
//!   `$2048^2$`, `2048^2`, `2048²` and `20482`, a superscript the extraction lost, alike), and
//!   the value must be a whole number on it (`9.8` is not found in `39.8` nor in `9.85`);
//! - `Sec. X, paragraph 'words'`: the section's heading, and the value a whole number in the
//!   paragraph after it that holds the words; `Sec. X` alone: the value anywhere in the paper;
//! - `read from Fig. N`: the paper has a Figure N; the value is not checkable, and counted.
//!
//! Without `../shared/papers` the test says so and passes, except under CI (the variable `CI`
//! set), which always has it.

use bench::config::PaperEntry;
use bench::paper::{Citation, Place};
use std::path::{Path, PathBuf};

fn root() -> PathBuf {
    let root = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../..");
    root.canonicalize().unwrap_or(root)
}

/// A paper's text, split as the checks read it.
struct Paper {
    /// The file's name, for messages.
    name: String,
    lines: Vec<String>,
}

/// Markup the text extraction left in labels and numbers, made plain: `2048 <sup>2</sup>`,
/// `$2048^2$` and `2048^2` become `2048²`, `$128 \times 128$` becomes `128 × 128`.
fn normalise(s: &str) -> String {
    let mut s = s
        .replace("<sup>2</sup>", "²")
        .replace("<sup>", "^")
        .replace("</sup>", "")
        .replace("<sub>", " ")
        .replace("</sub>", " ")
        .replace("\\times", "×")
        .replace("^2", "²")
        .replace(['$', '*'], "");
    while s.contains(" ²") {
        s = s.replace(" ²", "²");
    }
    s
}

/// The words of a line or label: split at white space, without the punctuation around them.
fn words(s: &str) -> Vec<String> {
    normalise(s)
        .split_whitespace()
        .map(|w| w.trim_matches(|c: char| "()[]{},;:\"'".contains(c)).trim_end_matches('.').to_string())
        .filter(|w| !w.is_empty())
        .collect()
}

/// A word as a number: `37.9`, `178`, `65,656` (thousands separated), `26%`.
fn number(w: &str) -> Option<f64> {
    let w = w.strip_suffix('%').unwrap_or(w);
    let groups: Vec<&str> = w.split(',').collect();
    let thousands = groups.len() > 1
        && (1..=3).contains(&groups[0].len())
        && groups[1..].iter().all(|g| g.len() == 3 && g.chars().all(|c| c.is_ascii_digit()));
    let plain = if thousands { w.replace(',', "") } else { w.to_string() };
    if plain.is_empty() || !plain.chars().all(|c| c.is_ascii_digit() || c == '.') {
        return None;
    }
    plain.parse().ok()
}

fn same(a: f64, b: f64) -> bool {
    (a - b).abs() <= 1e-9 * b.abs().max(1.0)
}

/// Does word `w` of the text read as label word `l`? `5122` reads as `512²`: the extraction of
/// W&D 2006 and W&N 2009 dropped the superscript.
fn reads_as(w: &str, l: &str) -> bool {
    w.eq_ignore_ascii_case(l) || l.strip_suffix('²').is_some_and(|base| w == format!("{base}2"))
}

/// Where the words of `label` stand in `line`'s words, from `from` on: the first match.
fn find_label(line: &[String], label: &[String]) -> Option<std::ops::Range<usize>> {
    if label.is_empty() || label.len() > line.len() {
        return None;
    }
    (0..=line.len() - label.len())
        .find(|&i| label.iter().enumerate().all(|(k, l)| reads_as(&line[i + k], l)))
        .map(|i| i..i + label.len())
}

impl Paper {
    fn new(name: &str, text: &str) -> Paper {
        Paper { name: name.into(), lines: text.lines().map(str::to_string).collect() }
    }

    /// Is line `i` a caption, of a table or a figure?
    fn is_caption(&self, i: usize) -> bool {
        let l = self.lines[i].trim().trim_start_matches('*');
        l.starts_with("Table ") || figure_caption(l).is_some()
    }

    /// A row of a table: cells separated by tabs, or mostly numbers (W&D 2006's and W&N
    /// 2009's tables lost their tabs).
    fn is_row(&self, i: usize) -> bool {
        let l = &self.lines[i];
        if l.contains('\t') {
            return true;
        }
        let w = words(l);
        let numbers = w.iter().filter(|w| number(w).is_some()).count();
        numbers >= 2 && 2 * numbers >= w.len()
    }

    /// The lines of Table `n`'s rows (blank ones left out), next to its caption: above it, or
    /// below it where no rows are above.
    fn table(&self, n: &str) -> Result<Vec<usize>, String> {
        let captions: Vec<usize> = (0..self.lines.len())
            .filter(|&i| {
                let l = self.lines[i].trim();
                l.starts_with(&format!("Table {n}:")) || l.starts_with(&format!("**Table {n}.**"))
            })
            .collect();
        let caption = match captions[..] {
            [c] => c,
            [] => return Err(format!("{} has no caption `Table {n}:`", self.name)),
            _ => return Err(format!("{} has {} captions of Table {n}", self.name, captions.len())),
        };
        let collect = |range: &mut dyn Iterator<Item = usize>| -> Vec<usize> {
            let mut rows = vec![];
            for i in range {
                if self.lines[i].trim().is_empty() {
                    continue;
                }
                if self.is_caption(i) || !self.is_row(i) {
                    break;
                }
                rows.push(i);
            }
            rows
        };
        let mut above = collect(&mut (0..caption).rev());
        above.reverse();
        let rows = if above.is_empty() { collect(&mut (caption + 1..self.lines.len())) } else { above };
        if rows.is_empty() {
            return Err(format!("{}: no rows next to the caption of Table {n} (line {})", self.name, caption + 1));
        }
        Ok(rows)
    }

    /// The line of Table `n`'s row labelled `row` (outermost label first), and the words of it
    /// that are labels.
    fn row(&self, n: &str, row: &[String]) -> Result<(usize, Vec<usize>), String> {
        let block = self.table(n)?;
        let mut at = 0;
        let mut label_words = vec![];
        let mut line = None;
        for label in row {
            let want = words(label);
            let found = block[at..]
                .iter()
                .enumerate()
                .find_map(|(k, &i)| find_label(&words(&self.lines[i]), &want).map(|r| (at + k, i, r)));
            let Some((k, i, r)) = found else {
                return Err(format!(
                    "Table {n} of {} has no row labelled `{label}`{}",
                    self.name,
                    if at > 0 { format!(" after the row of `{}`", row[0]) } else { String::new() }
                ));
            };
            if line != Some(i) {
                label_words.clear();
            }
            label_words.extend(r);
            at = k;
            line = Some(i);
        }
        Ok((line.expect("a row has a label"), label_words))
    }

    /// The line of Sec. `x`'s heading: `## 5.2 Correctness`, `5. Results and Discussion`.
    fn section(&self, x: &str) -> Result<usize, String> {
        (0..self.lines.len())
            .find(|&i| {
                let l = self.lines[i].trim().trim_start_matches('#').trim();
                let Some(title) = l.strip_prefix(x).and_then(|t| t.strip_prefix('.').or(Some(t))) else {
                    return false;
                };
                let title = title.strip_prefix(' ').unwrap_or("");
                title.starts_with(|c: char| c.is_uppercase())
                    && !title.contains([',', ':', ';'])
                    && !title.ends_with(['.', '-'])
            })
            .ok_or_else(|| format!("{} has no heading of Sec. {x}", self.name))
    }

    /// The paragraphs (runs of lines between blank lines) from line `from` on that hold
    /// `words`, white space made single; with their words.
    fn paragraphs(&self, from: usize, quote: &str) -> Vec<Vec<String>> {
        let quote = quote.split_whitespace().collect::<Vec<_>>().join(" ");
        let mut out = vec![];
        let mut para: Vec<&str> = vec![];
        for l in self.lines[from..].iter().map(String::as_str).chain([""]) {
            if !l.trim().is_empty() {
                para.push(l);
                continue;
            }
            let text = para.join(" ").split_whitespace().collect::<Vec<_>>().join(" ");
            if text.contains(&quote) {
                out.push(words(&text));
            }
            para.clear();
        }
        out
    }

    fn has_figure(&self, n: &str) -> bool {
        self.lines.iter().any(|l| figure_caption(l).as_deref() == Some(n))
    }
}

/// The number of the figure whose caption `line` is: `Figure 7: ...` (after any prefix the
/// extraction left).
fn figure_caption(line: &str) -> Option<String> {
    let at = line.find("Figure ")?;
    let rest = &line[at + "Figure ".len()..];
    let n: String = rest.chars().take_while(|c| c.is_ascii_digit()).collect();
    (!n.is_empty() && rest[n.len()..].starts_with([':', '.'])).then_some(n)
}

/// The outcome of checking one value.
enum Checked {
    Found,
    /// Read from a chart: the paper has the figure, the value no text.
    FromFigure,
}

/// Is `value` at `c`'s place in `paper`?
fn check(paper: &Paper, c: &Citation, value: f64) -> Result<Checked, String> {
    let has = |ws: &[String], skip: &[usize]| {
        ws.iter().enumerate().any(|(k, w)| !skip.contains(&k) && number(w).is_some_and(|v| same(v, value)))
    };
    match &c.place {
        Place::Table { number: n, row } => {
            let (line, labels) = paper.row(n, row)?;
            if has(&words(&paper.lines[line]), &labels) {
                Ok(Checked::Found)
            } else {
                Err(format!(
                    "not on row `{}` of Table {n} (line {}: `{}`)",
                    row.join(" / "),
                    line + 1,
                    paper.lines[line].replace('\t', " | ")
                ))
            }
        }
        Place::Section { number: x, paragraph } => {
            let heading = paper.section(x)?;
            match paragraph {
                Some(quote) => {
                    let found = paper.paragraphs(heading, quote);
                    if found.is_empty() {
                        Err(format!("no paragraph of Sec. {x} (from line {}) holds `{quote}`", heading + 1))
                    } else if found.iter().any(|p| has(p, &[])) {
                        Ok(Checked::Found)
                    } else {
                        Err(format!("not in the paragraph of Sec. {x} that holds `{quote}`"))
                    }
                }
                None if paper.lines.iter().any(|l| has(&words(l), &[])) => Ok(Checked::Found),
                None => Err("not in the paper's text".into()),
            }
        }
        Place::Figure { number: n } if paper.has_figure(n) => Ok(Checked::FromFigure),
        Place::Figure { number: n } => Err(format!("{} has no Figure {n}", paper.name)),
    }
}

/// The file in `dir` of the paper a config names (`table.paper`: "Wyman 2008, Hierarchical
/// caustic maps"): the row of `dir/README.md` whose paper holds the title and the year.
fn paper_file(dir: &Path, paper: &str) -> Result<PathBuf, String> {
    let readme =
        std::fs::read_to_string(dir.join("README.md")).map_err(|e| format!("{}/README.md: {e}", dir.display()))?;
    let (authors, title) =
        paper.split_once(", ").ok_or_else(|| format!("`{paper}`: expected `Authors Year, Title`"))?;
    let year = authors.split_whitespace().last().unwrap_or("");
    let rows: Vec<&str> = readme
        .lines()
        .filter_map(|l| {
            let cells: Vec<&str> = l.split('|').map(str::trim).collect();
            let (file, who) = (cells.get(1)?, cells.get(2)?);
            let hit =
                file.ends_with(".txt") && who.to_lowercase().contains(&title.to_lowercase()) && who.contains(year);
            hit.then_some(*file)
        })
        .collect();
    match rows[..] {
        [f] => Ok(dir.join(f)),
        _ => Err(format!("{}/README.md has {} rows for `{paper}`, not one", dir.display(), rows.len())),
    }
}

/// What checking the configs found.
#[derive(Default)]
struct Tally {
    configs: usize,
    entries: usize,
    checked: usize,
    from_figures: usize,
    failures: Vec<String>,
}

/// Checks every `[[paper]]` value of the configs in `configs` against the papers in `papers`.
fn check_configs(configs: &Path, papers: &Path) -> Tally {
    let mut t = Tally::default();
    let mut files: Vec<PathBuf> = std::fs::read_dir(configs)
        .expect("bench_configs/")
        .map(|e| e.expect("entry").path())
        .filter(|p| p.extension().is_some_and(|x| x == "toml"))
        .collect();
    files.sort();
    for path in files {
        let name = path.file_name().unwrap().to_string_lossy().to_string();
        let lc = match bench::LoadedConfig::load(&path) {
            Ok(lc) => lc,
            Err(e) => {
                t.failures.push(format!("{name}: {e:#}"));
                continue;
            }
        };
        let c = &lc.config;
        if c.paper.is_empty() {
            continue;
        }
        t.configs += 1;
        let paper = match paper_file(papers, &c.table.paper).and_then(|f| {
            let text = std::fs::read_to_string(&f).map_err(|e| format!("{}: {e}", f.display()))?;
            Ok(Paper::new(&f.file_name().unwrap().to_string_lossy(), &text))
        }) {
            Ok(p) => p,
            Err(e) => {
                t.failures.push(format!("{name}: {e}"));
                continue;
            }
        };
        for (i, e) in c.paper.iter().enumerate() {
            t.entries += 1;
            check_entry(&mut t, &name, i, e, &paper);
        }
    }
    t
}

fn check_entry(t: &mut Tally, config: &str, i: usize, e: &PaperEntry, paper: &Paper) {
    let entry = format!("{config}: paper[{i}] ({})", bench::paper::describe(e));
    let citations = match bench::paper::citations(e) {
        Ok(c) => c,
        Err(m) => {
            t.failures.push(format!("{entry}: source: {m}"));
            return;
        }
    };
    for c in &citations {
        for key in &c.keys {
            let value = e.values[key];
            match check(paper, c, value) {
                Ok(Checked::Found) => t.checked += 1,
                Ok(Checked::FromFigure) => t.from_figures += 1,
                Err(why) => t.failures.push(format!("{entry}: `{key}` = {value}: {why} (source: {})", c.text)),
            }
        }
    }
}

#[test]
fn every_paper_value_is_in_the_paper_where_its_source_says() {
    let papers = root().parent().expect("the repository is in a folder").join("shared/papers");
    if !papers.join("README.md").is_file() {
        let why = format!("{} is missing (the papers' plain text beside the repository)", papers.display());
        assert!(std::env::var_os("CI").is_none(), "CI always has ../shared/papers, but {why}");
        eprintln!("paper_sources: skipping: {why}");
        return;
    }
    let t = check_configs(&root().join("bench_configs"), &papers);
    println!(
        "paper_sources: {} configs, {} [[paper]] entries: {} values found in the papers' text, \
         {} read from figures (not checkable)",
        t.configs, t.entries, t.checked, t.from_figures
    );
    assert!(
        t.failures.is_empty(),
        "{} values not where their source says:\n{}",
        t.failures.len(),
        t.failures.join("\n")
    );
    assert!(
        t.entries > 100 && t.checked > 300,
        "found too few entries to check: {} entries, {} values",
        t.entries,
        t.checked
    );
}

/// The checks themselves, on a made-up paper with both layouts of tables.
#[test]
fn the_checks_find_rows_whole_numbers_paragraphs_and_figures() {
    let paper = Paper::new(
        "made_up.txt",
        "## 5 Results\n\nIntro with 7 and 2.5 in it.\n\n# Photons\tHier\tOther\n256 <sup>2</sup>\t1.3 ms\t39.8 ms\n\
         $2048^2$\t9.85 ms\t12.0 ms\n\nTable 3: Costs. Table 1 is elsewhere.\n\n**Table 4.** Rates.\n\n\
         Size\tA\tB\n$128 \\times 128$\t37.9\t2.56\n\n### 5.1 Rates\n\nThe height field runs at 178 frames\n\
         per second, and 64 at 256.\n\nScene Photons A B\nBall & Dragon 5122 73.2 30.6\n\
         (251,000 triangles) 10242 40.2 10.3\n\n20482 3.9 n/a\nBeethoven 5122 123.1 29.7\n\nTable 1: Fps.\n\nFigure 8: A chart.\n",
    );
    let cite = |source: &str| -> Citation {
        let e: PaperEntry = toml::from_str(&format!("values = {{ v = 1.0 }}\nsource = \"{source}\"")).expect("entry");
        bench::paper::citations(&e).expect("parses").remove(0)
    };
    let found = |source: &str, v: f64| matches!(check(&paper, &cite(source), v), Ok(Checked::Found));
    // A whole number on its row: not inside another, not in another row.
    assert!(found("Table 3, row 256²", 1.3));
    assert!(found("Table 3, row 256²", 39.8));
    assert!(!found("Table 3, row 256²", 9.8), "9.8 is not 39.8");
    assert!(!found("Table 3, row 2048²", 9.8), "9.8 is not 9.85");
    assert!(!found("Table 3, row 256²", 256.0), "a row's label is not its value");
    assert!(found("Table 3, row 2048^2", 12.0));
    // Rows below their caption; labels in LaTeX.
    assert!(found("Table 4, row 128 × 128", 2.56));
    let err = check(&paper, &cite("Table 4, row 256 × 256"), 1.0).err().expect("no such row");
    assert!(err.contains("no row labelled `256 × 256`"), "{err}");
    // Two labels: the row of the second after the first; a lost superscript; thousands.
    assert!(found("Table 1, row Ball & Dragon / 2048²", 3.9));
    assert!(!found("Table 1, row Beethoven / 2048²", 3.9), "Beethoven has no 2048² row after it");
    assert!(found("Table 1, row Ball & Dragon / 1024²", 10.3));
    assert!(!found("Table 1, row Ball & Dragon / 1024²", 73.2));
    assert!(found("Table 1, row '(251,000 triangles)'", 40.2), "a label with a comma, quoted");
    assert_eq!((number("65,656"), number("1,048,576"), number("26%")), (Some(65656.0), Some(1048576.0), Some(26.0)));
    assert_eq!((number("5,09"), number("n/a"), number("316k")), (None, None, None));
    // Sections: the quoted paragraph only, across its line breaks.
    assert!(found("Sec. 5.1, paragraph 'runs at 178 frames per second'", 64.0));
    assert!(!found("Sec. 5.1, paragraph 'runs at 178 frames per second'", 7.0));
    assert!(found("Sec. 5", 7.0));
    assert!(!found("Sec. 5", 17.0));
    assert!(check(&paper, &cite("Sec. 6, paragraph 'Intro'"), 7.0).is_err(), "no Sec. 6");
    // Figures: there, or not.
    assert!(matches!(check(&paper, &cite("read from Fig. 8"), 0.3), Ok(Checked::FromFigure)));
    assert!(check(&paper, &cite("read from Fig. 9"), 0.3).is_err());
    assert!(check(&paper, &cite("Table 2, row 256²"), 1.3).is_err(), "no Table 2");
}

/// A `[[paper]]` entry without a `source`, or with one that cites nothing it can check, is a
/// config error naming the file, the entry and what is wrong.
#[test]
fn a_paper_entry_without_a_source_is_a_config_error_naming_it() {
    let dir = caustics::scratch::ScratchDir::new("causticlab", "paper-sources");
    let scene = root().join("scenes/sphere_on_plane.toml");
    let config = |entry: &str| {
        format!(
            "[table]\npaper = \"Wyman 2008, Hierarchical caustic maps\"\nnumber = \"3\"\ncaption = \"c\"\n\n\
             [matrix]\nscenes = [\"{}\"]\nphotons = [256, 512]\n\n\
             [[technique]]\nlabel = \"hier\"\ntechnique = \"hcm\"\n\n\
             [[metric]]\nlabel = \"Gather\"\nkind = \"pass_ms\"\npasses = [\"splat.*\"]\n\n\
             [layout]\nrows = [\"photons\"]\ncolumns = [\"technique\"]\n\n\
             [[paper]]\nphotons = 256\nvalues = {{ hier = 1.3 }}\nsource = \"Table 3, row 256²\"\n\n\
             [[paper]]\nphotons = 512\n{entry}\n",
            scene.display()
        )
    };
    let load = |name: &str, entry: &str| {
        let path = dir.join(name);
        std::fs::write(&path, config(entry)).expect("write the config");
        bench::LoadedConfig::load(&path).map(|_| ()).map_err(|e| format!("{e:#}"))
    };
    load("cited.toml", "values = { hier = 1.6 }\nsource = \"Table 3, row 512²\"").expect("a cited entry loads");
    for (name, entry, says) in [
        ("missing.toml", "values = { hier = 1.6 }", "missing: say where in the paper"),
        ("empty.toml", "values = { hier = 1.6 }\nsource = \" \"", "must not be empty"),
        ("no_row.toml", "values = { hier = 1.6 }\nsource = \"Table 3\"", "names its row"),
        ("unknown.toml", "values = { hier = 1.6 }\nsource = \"Fig. 3\"", "a citation is `Table N, row R`"),
        ("open_quote.toml", "values = { hier = 1.6 }\nsource = \"Sec. 5, paragraph 'words\"", "not closed"),
        ("wrong_key.toml", "values = { hier = 1.6 }\nsource = \"Table 3, row 512²; flat: Sec. 5\"", "not a key"),
    ] {
        let err = load(name, entry).expect_err(name);
        for want in [name, "paper[1].source", "the entry photons = 512", says] {
            assert!(err.contains(want), "{name}: `{want}` not in: {err}");
        }
    }
}
