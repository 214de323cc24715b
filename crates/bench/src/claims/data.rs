//! Measurements that are not a bench table: the CSV a script writes beside its page (the CPU
//! reference's photon rate, criterion's medians, the soak's memory, the quality tables of
//! `scripts/quality_table.sh`). A claim reads such a file as it reads a table.
//!
//! Each row of the CSV is an entry per value column: a column whose every cell is a number (or
//! empty) is a value column, any other is a label; the first column is always a label (the
//! row's name, a frame number). The value's column is the entry's `column` axis:
//!
//! ```text
//! scene,fresnel,cpu_mphotons,cpu_lo,cpu_hi          <!--claims cpu = results/photon_trace.csv -->
//! sphere_on_plane,on,0.712,0.682,0.734              0.712<!--= cpu{scene=sphere_on_plane fresnel=on column=cpu_mphotons} -->
//! ```
//!
//! Quoted fields (`"hcm (compute, combine last)"`, with `""` for a quote) are read as RFC 4180
//! writes them. A data file has no spreads, flags or paper values: a script that wants a number
//! flagged writes it in a column of its own.

use crate::table::Entry;
use anyhow::{bail, Context as _, Result};
use std::collections::BTreeMap;
use std::path::Path;

/// The axis that names an entry's value column.
pub const COLUMN_AXIS: &str = "column";

/// The fields of one CSV line.
pub fn fields(line: &str) -> Result<Vec<String>> {
    let mut out = vec![];
    let mut field = String::new();
    let mut chars = line.chars().peekable();
    let mut quoted = false;
    let mut was_quoted = false;
    while let Some(c) = chars.next() {
        match (quoted, c) {
            (true, '"') if chars.peek() == Some(&'"') => {
                chars.next();
                field.push('"');
            }
            (true, '"') => quoted = false,
            (true, c) => field.push(c),
            (false, '"') if field.is_empty() && !was_quoted => {
                quoted = true;
                was_quoted = true;
            }
            (false, ',') => {
                out.push(std::mem::take(&mut field));
                was_quoted = false;
            }
            (false, '"') => bail!("a quote inside an unquoted field (quote the whole field, `\"\"` for a quote)"),
            (false, c) if was_quoted => bail!("`{c}` after a field's closing quote"),
            (false, c) => field.push(c),
        }
    }
    if quoted {
        bail!("a quoted field is not closed");
    }
    out.push(field);
    Ok(out)
}

/// The entries of a CSV file (see the module's doc).
pub fn read(path: &Path) -> Result<Vec<Entry>> {
    let text = std::fs::read_to_string(path).with_context(|| format!("reading {}", path.display()))?;
    parse(&text).with_context(|| format!("{}", path.display()))
}

pub fn parse(text: &str) -> Result<Vec<Entry>> {
    let mut lines = text.lines().enumerate().filter(|(_, l)| !l.trim().is_empty());
    let Some((_, head)) = lines.next() else { bail!("empty: a data file starts with a header line") };
    let header = fields(head).context("line 1")?;
    for (i, h) in header.iter().enumerate() {
        if h.trim().is_empty() {
            bail!("line 1: column {} has no name", i + 1);
        }
        if header[..i].contains(h) {
            bail!("line 1: two columns named `{h}`");
        }
        if h == COLUMN_AXIS {
            bail!("line 1: `{COLUMN_AXIS}` is the axis that names a value's column; rename that column");
        }
    }
    let mut rows = vec![];
    for (n, line) in lines {
        let row = fields(line).with_context(|| format!("line {}", n + 1))?;
        if row.len() != header.len() {
            bail!("line {}: {} fields, the header has {}", n + 1, row.len(), header.len());
        }
        rows.push(row);
    }
    if rows.is_empty() {
        bail!("no rows below the header");
    }
    let number = |s: &str| s.trim().parse::<f64>().ok().filter(|v| v.is_finite());
    // A value column: every cell a number or empty, and at least one a number; the first column
    // names the row.
    let value: Vec<bool> = (0..header.len())
        .map(|c| {
            c > 0
                && rows.iter().all(|r| r[c].trim().is_empty() || number(&r[c]).is_some())
                && rows.iter().any(|r| number(&r[c]).is_some())
        })
        .collect();
    let mut out = vec![];
    let mut seen = std::collections::BTreeSet::new();
    for row in &rows {
        let labels: BTreeMap<String, String> =
            (0..header.len()).filter(|&c| !value[c]).map(|c| (header[c].clone(), row[c].trim().to_string())).collect();
        if !seen.insert(labels.clone()) {
            let l: Vec<String> = labels.iter().map(|(a, k)| format!("{a}={k}")).collect();
            bail!("two rows with the same labels ({}): a claim could not tell them apart", l.join(" "));
        }
        for c in (0..header.len()).filter(|&c| value[c]) {
            let mut keys = labels.clone();
            keys.insert(COLUMN_AXIS.to_string(), header[c].clone());
            out.push(Entry {
                keys,
                ours: number(&row[c]),
                spread: None,
                paper: None,
                kind: "data".into(),
                not_run: false,
                missing: false,
                implausible: false,
                unmeasured: None,
                busy: false,
                remeasured: false,
            });
        }
    }
    Ok(out)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn keys(e: &Entry) -> String {
        e.keys.iter().map(|(a, k)| format!("{a}={k}")).collect::<Vec<_>>().join(" ")
    }

    #[test]
    fn quoted_fields_keep_their_commas_and_quotes() {
        assert_eq!(fields(r#"a,"b, c","say ""hi""",,d"#).unwrap(), ["a", "b, c", "say \"hi\"", "", "d"]);
        assert!(fields(r#"a,"b"#).is_err(), "an open quote");
        assert!(fields(r#"a,b"c"#).is_err(), "a quote inside a field");
        // A quoted part after a field's first characters is not a quoted field: `b"c"` is refused,
        // not read as `bc`.
        let inside = fields(r#"a,b"c",d"#).expect_err("a quoted part inside a field");
        assert!(inside.to_string().contains("inside an unquoted field"), "{inside}");
        assert!(fields(r#""b"c,d"#).is_err(), "text after the closing quote");
    }

    #[test]
    fn number_columns_are_values_and_the_rest_label_them() {
        let e = parse("frame,seconds,note,bytes\n500,29.9,warm,10\n1000,57.0,,\n").unwrap();
        // frame is the first column: a label though numeric; note has text: a label; bytes has
        // an empty cell: still a value column, its entry reads no number.
        let all: Vec<String> = e.iter().map(|e| format!("{} = {:?}", keys(e), e.ours)).collect();
        assert_eq!(
            all,
            [
                "column=seconds frame=500 note=warm = Some(29.9)",
                "column=bytes frame=500 note=warm = Some(10.0)",
                "column=seconds frame=1000 note= = Some(57.0)",
                "column=bytes frame=1000 note= = None",
            ]
        );
    }

    #[test]
    fn a_file_a_claim_could_misread_is_refused() {
        for (text, why) in [
            ("", "empty"),
            ("a,b\n", "no rows"),
            ("a,,c\n1,2,3\n", "no name"),
            ("a,b,a\n1,2,3\n", "two columns named `a`"),
            ("a,column\nx,1\n", "rename that column"),
            ("a,b\nx,1,2\n", "3 fields, the header has 2"),
            ("a,b\nx,1\nx,2\n", "same labels"),
        ] {
            let e = parse(text).err().unwrap_or_else(|| panic!("{text:?} was read"));
            assert!(format!("{e:#}").contains(why), "{text:?}: {e:#}");
        }
    }
}
