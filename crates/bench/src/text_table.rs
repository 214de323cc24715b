//! Aligned text tables, as Markdown (pipes, padded so the raw file reads as a table too) or plain
//! text (the terminal summary). A table wider than the width is wrapped into blocks of whole
//! columns, each repeating the row labels, the way a printed table continues below itself.

/// Markdown or plain text.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Style {
    Markdown,
    Plain,
}

/// The widest a line may be: a 120-column terminal.
pub const WIDTH: usize = 120;

/// Row labels (the stub, one column per row axis) and value columns.
#[derive(Debug, Clone, Default)]
pub struct TextTable {
    pub stub_headers: Vec<String>,
    pub headers: Vec<String>,
    /// (stub labels, cells): one stub label per stub header, one cell per header.
    pub rows: Vec<(Vec<String>, Vec<String>)>,
}

/// `text` broken at spaces into lines of at most `width` characters (a longer word keeps its
/// own line).
pub fn wrap(text: &str, width: usize) -> String {
    let mut lines: Vec<String> = vec![];
    for word in text.split(' ') {
        match lines.last_mut() {
            Some(l) if chars(l) + 1 + chars(word) <= width => {
                l.push(' ');
                l.push_str(word);
            }
            _ => lines.push(word.to_string()),
        }
    }
    lines.join("\n")
}

fn chars(s: &str) -> usize {
    s.chars().count()
}

fn pad(s: &str, w: usize, right: bool) -> String {
    let fill = " ".repeat(w.saturating_sub(chars(s)));
    if right {
        format!("{fill}{s}")
    } else {
        format!("{s}{fill}")
    }
}

impl TextTable {
    /// Blanks a stub label that repeats the one above it in the same column (and every column
    /// before it), so grouped rows read like the paper's.
    pub fn group_stub(&mut self) {
        let mut prev: Vec<String> = vec![];
        for (stub, _) in &mut self.rows {
            let shown = stub.clone();
            for i in 0..stub.len().saturating_sub(1) {
                if prev.get(..=i) == shown.get(..=i) {
                    stub[i] = String::new();
                }
            }
            prev = shown;
        }
    }

    /// The table as lines no wider than `width` (unless one column alone is wider).
    pub fn render(&self, style: Style, width: usize) -> String {
        let width_of = |header: &str, cells: &mut dyn Iterator<Item = &String>| {
            cells.map(|c| chars(c)).max().unwrap_or(0).max(chars(header))
        };
        let stub_w: Vec<usize> = (0..self.stub_headers.len())
            .map(|i| width_of(&self.stub_headers[i], &mut self.rows.iter().map(|r| &r.0[i])))
            .collect();
        let val_w: Vec<usize> = (0..self.headers.len())
            .map(|i| width_of(&self.headers[i], &mut self.rows.iter().map(|r| &r.1[i])))
            .collect();
        // Markdown: "| a | b |" is 1 + (w + 3) per column; plain: columns two spaces apart.
        let cost = |w: usize| if style == Style::Markdown { w + 3 } else { w + 2 };
        let stub_cost: usize = stub_w.iter().map(|&w| cost(w)).sum::<usize>() + 1;
        let mut blocks: Vec<Vec<usize>> = vec![];
        let mut used = stub_cost;
        for (i, &w) in val_w.iter().enumerate() {
            match blocks.last_mut() {
                Some(b) if used + cost(w) <= width => b.push(i),
                _ => {
                    blocks.push(vec![i]);
                    used = stub_cost;
                }
            }
            used += cost(w);
        }
        let mut out = String::new();
        for (bi, block) in blocks.iter().enumerate() {
            if bi > 0 {
                out.push('\n');
            }
            let line = |stub: &[String], cells: &[&str]| -> String {
                let mut parts: Vec<String> = stub.iter().zip(&stub_w).map(|(s, &w)| pad(s, w, false)).collect();
                parts.extend(block.iter().zip(cells).map(|(&i, c)| pad(c, val_w[i], true)));
                match style {
                    Style::Markdown => format!("| {} |", parts.join(" | ")),
                    Style::Plain => parts.join("  ").trim_end().to_string(),
                }
            };
            let headers: Vec<&str> = block.iter().map(|&i| self.headers[i].as_str()).collect();
            out.push_str(&line(&self.stub_headers, &headers));
            out.push('\n');
            let rule: Vec<String> = match style {
                Style::Markdown => {
                    let mut r: Vec<String> = stub_w.iter().map(|&w| "-".repeat(w.max(3))).collect();
                    r.extend(block.iter().map(|&i| format!("{}:", "-".repeat(val_w[i].max(3) - 1))));
                    vec![format!("| {} |", r.join(" | "))]
                }
                Style::Plain => {
                    let total = stub_w.iter().chain(block.iter().map(|&i| &val_w[i])).map(|w| w + 2).sum::<usize>();
                    vec!["─".repeat(total.saturating_sub(2))]
                }
            };
            out.push_str(&rule.join(""));
            out.push('\n');
            for (stub, cells) in &self.rows {
                let cells: Vec<&str> = block.iter().map(|&i| cells[i].as_str()).collect();
                out.push_str(&line(stub, &cells));
                out.push('\n');
            }
        }
        out
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn table(columns: usize) -> TextTable {
        TextTable {
            stub_headers: vec!["photons".into()],
            headers: (0..columns).map(|i| format!("technique {i}")).collect(),
            rows: ["256²", "4096²"]
                .iter()
                .map(|p| (vec![p.to_string()], (0..columns).map(|i| format!("{i}1329.5 ±12%! (777.4)")).collect()))
                .collect(),
        }
    }

    #[test]
    fn markdown_is_aligned_and_wraps_into_blocks_of_whole_columns() {
        let md = table(10).render(Style::Markdown, WIDTH);
        let lines: Vec<&str> = md.lines().collect();
        assert!(lines.iter().all(|l| l.chars().count() <= WIDTH), "{md}");
        // Every line of one block is equally wide, and every block repeats the row labels.
        let blocks: Vec<&str> = md.split("\n\n").collect();
        assert!(blocks.len() >= 2, "{md}");
        for b in &blocks {
            let widths: Vec<usize> = b.lines().map(|l| l.chars().count()).collect();
            assert!(widths.windows(2).all(|w| w[0] == w[1]), "{b}");
            assert!(b.starts_with("| photons |") && b.contains("| 4096²   |"), "{b}");
        }
        // Each column appears once, whole.
        for i in 0..10 {
            assert_eq!(md.matches(&format!("technique {i} ")).count(), 1, "{md}");
        }
        // A narrow table is one block.
        assert_eq!(table(2).render(Style::Markdown, WIDTH).split("\n\n").count(), 1);
    }

    #[test]
    fn prose_wraps_at_spaces() {
        let w = wrap("aaa bbb ccc ddd", 7);
        assert_eq!(w, "aaa bbb\nccc ddd");
        assert_eq!(wrap("abcdefghij k", 4), "abcdefghij\nk");
    }

    #[test]
    fn plain_text_has_no_pipes_and_grouped_stubs_blank_repeats() {
        let mut t = TextTable {
            stub_headers: vec!["scene".into(), "photons".into()],
            headers: vec!["fps".into()],
            rows: vec![
                (vec!["ring".into(), "512²".into()], vec!["1.0".into()]),
                (vec!["ring".into(), "1024²".into()], vec!["2.0".into()]),
                (vec!["octahedron".into(), "512²".into()], vec!["3.0".into()]),
            ],
        };
        t.group_stub();
        let text = t.render(Style::Plain, WIDTH);
        assert!(!text.contains('|'), "{text}");
        let lines: Vec<&str> = text.lines().collect();
        assert!(lines[2].starts_with("ring") && lines[3].starts_with("    ") && lines[4].starts_with("octahedron"));
    }
}
