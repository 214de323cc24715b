//! TOML text -> serde structs (scene files, and the bench crate's configs), mapping toml's
//! errors (which carry a byte span) to the dotted key path (`objects[1].radius`) and line they
//! concern.

use super::schema;
use crate::input_error;
use serde::de::DeserializeOwned;
use std::path::Path;

/// TOML text -> scene schema, with errors that name the file, the key path and the line.
pub fn parse(path: &Path, text: &str) -> anyhow::Result<schema::SceneFile> {
    parse_toml(path, text)
}

/// TOML text -> `T`. Every error is an input error naming `path`, and, where toml's span falls
/// on a key or value, its dotted path and line: ``x.toml: key `run.measurd_frames` (line 21): …``.
pub fn parse_toml<T: DeserializeOwned>(path: &Path, text: &str) -> anyhow::Result<T> {
    let line_col = |offset: usize| {
        let before = &text[..offset.min(text.len())];
        let line = before.matches('\n').count() + 1;
        let col = before.len() - before.rfind('\n').map_or(0, |i| i + 1) + 1;
        (line, col)
    };
    let doc = match toml_edit::ImDocument::parse(text) {
        Ok(doc) => doc,
        Err(e) => {
            let (line, col) = line_col(e.span().map_or(0, |s| s.start));
            return Err(anyhow::Error::new(input_error!(
                "{}: TOML syntax error at line {line}, column {col}: {}",
                path.display(),
                e.message().trim_end().replace('\n', "; ")
            )));
        }
    };
    toml::from_str::<T>(text).map_err(|e| {
        let mut span = e.span();
        let msg = e.message().trim_end().replace('\n', "; ");
        // An error raised inside a flattened table (a bench `[[technique]]`) spans the whole
        // table: find the key it is about there, by its name or by its value.
        if let Some((_, start)) = span.clone().and_then(|s| named_in(doc.as_table(), &s, "", &msg)) {
            span = Some(start..start + 1);
        }
        let key = span.as_ref().and_then(|s| key_at(doc.as_table(), s.start, ""));
        let err = match (key, span) {
            (Some(key), Some(s)) => {
                let (line, _) = line_col(s.start);
                input_error!("{}: key `{key}` (line {line}): {msg}", path.display())
            }
            (None, Some(s)) if s.start > 0 => {
                let (line, col) = line_col(s.start);
                input_error!("{}: line {line}, column {col}: {msg}", path.display())
            }
            _ => input_error!("{}: {msg}", path.display()),
        };
        anyhow::Error::new(err)
    })
}

/// The key inside `span` that `msg` names: ``unknown field `X` `` names key X, ``unknown variant
/// `V` `` the key whose value is the string V. (key path, start of the key) of the first.
fn named_in(
    table: &dyn toml_edit::TableLike,
    span: &std::ops::Range<usize>,
    prefix: &str,
    msg: &str,
) -> Option<(String, usize)> {
    let quoted = |lead: &str| msg.strip_prefix(lead).and_then(|r| r.split('`').next()).map(str::to_string);
    let (field, variant) = (quoted("unknown field `"), quoted("unknown variant `"));
    if field.is_none() && variant.is_none() {
        return None;
    }
    let mut found = None;
    visit(table, prefix, &mut |path, key, value| {
        let Some(start) = key.span().map(|s| s.start) else { return };
        if found.is_some() || !span.contains(&start) {
            return;
        }
        let by_name = field.as_deref() == Some(key.get());
        let by_value = variant.is_some() && value.and_then(|v| v.as_str()) == variant.as_deref();
        if by_name || by_value {
            found = Some((path.to_string(), start));
        }
    });
    found
}

/// Calls `f(path, key, value)` for every key of `table` and of the tables below it.
fn visit(
    table: &dyn toml_edit::TableLike,
    prefix: &str,
    f: &mut dyn FnMut(&str, &toml_edit::Key, Option<&toml_edit::Value>),
) {
    use toml_edit::Item;
    for (k, item) in table.iter() {
        let path = join(prefix, k);
        if let Some((key, _)) = table.get_key_value(k) {
            f(&path, key, item.as_value());
        }
        match item {
            Item::Table(t) => visit(t, &path, f),
            Item::ArrayOfTables(a) => {
                for (i, t) in a.iter().enumerate() {
                    visit(t, &format!("{path}[{i}]"), f);
                }
            }
            Item::Value(toml_edit::Value::InlineTable(t)) => visit(t, &path, f),
            _ => {}
        }
    }
}

fn contains(span: Option<std::ops::Range<usize>>, offset: usize) -> bool {
    span.is_some_and(|s| s.start <= offset && offset < s.end.max(s.start + 1))
}

fn join(prefix: &str, key: &str) -> String {
    if prefix.is_empty() {
        key.to_string()
    } else {
        format!("{prefix}.{key}")
    }
}

/// The dotted key path (`objects[1].radius`) of the deepest key or value covering `offset`.
fn key_at(table: &dyn toml_edit::TableLike, offset: usize, prefix: &str) -> Option<String> {
    for (k, item) in table.iter() {
        let path = join(prefix, k);
        if let Some((key, _)) = table.get_key_value(k) {
            if contains(key.span(), offset) {
                return Some(path);
            }
        }
        if let Some(found) = key_in_item(item, offset, &path) {
            return Some(found);
        }
    }
    None
}

fn key_in_item(item: &toml_edit::Item, offset: usize, path: &str) -> Option<String> {
    use toml_edit::Item;
    let inner = match item {
        Item::Table(t) => key_at(t, offset, path),
        Item::ArrayOfTables(a) => a.iter().enumerate().find_map(|(i, t)| {
            key_at(t, offset, &format!("{path}[{i}]"))
                .or_else(|| contains(t.span(), offset).then(|| format!("{path}[{i}]")))
        }),
        Item::Value(v) => key_in_value(v, offset, path),
        Item::None => None,
    };
    inner.or_else(|| contains(item.span(), offset).then(|| path.to_string()))
}

fn key_in_value(v: &toml_edit::Value, offset: usize, path: &str) -> Option<String> {
    use toml_edit::Value;
    let inner = match v {
        Value::Array(a) => a.iter().enumerate().find_map(|(i, v)| key_in_value(v, offset, &format!("{path}[{i}]"))),
        Value::InlineTable(t) => key_at(t, offset, path),
        _ => None,
    };
    inner.or_else(|| contains(v.span(), offset).then(|| path.to_string()))
}
