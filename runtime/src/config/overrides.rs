//! `--set dotted.key=value` overrides: applied to the graph's TOML text before it is read, and
//! remembered, so a mistake typed in one is reported at the `--set` argument rather than at the
//! line of the file it was written into.

use std::path::{Path, PathBuf};

use disco_core::error::{Error, Result};

/// One `--set` argument, as typed.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Override {
    /// The dotted key it sets, e.g. `run.max_rounds`.
    pub key: String,
    /// The argument as typed, e.g. `run.max_rounds=2`.
    pub arg: String,
    /// The outermost table the override brought into being (e.g. `agents.desinger` for
    /// `agents.desinger.impl=noisy`), when the graph had no such table.
    pub created_table: Option<String>,
}

impl Override {
    /// The label errors name in place of a file: `--set run.max_rounds=2`.
    pub fn label(&self) -> PathBuf {
        PathBuf::from(format!("--set {}", self.arg))
    }

    /// Whether a mistake at dotted `key` is this override's: it set that very key (or a table
    /// holding it), or it created the table `key` lies in.
    pub fn explains(&self, key: &str) -> bool {
        let within = |outer: &str| key == outer || key.starts_with(&format!("{outer}."));
        within(&self.key) || self.created_table.as_deref().is_some_and(within)
    }
}

/// The override among `overrides` that explains a mistake at `key` (the last one typed wins,
/// as it does for the value).
pub fn origin<'a>(overrides: &'a [Override], key: &str) -> Option<&'a Override> {
    overrides.iter().rev().find(|o| o.explains(key))
}

/// Applies `key=value` overrides to the TOML text (values parse as TOML, else as strings).
pub fn apply(source: &Path, text: &str, sets: &[String]) -> Result<(String, Vec<Override>)> {
    if sets.is_empty() {
        return Ok((text.to_string(), Vec::new()));
    }
    let mut doc: toml_edit::DocumentMut = text.parse().map_err(|e: toml_edit::TomlError| {
        Error::invalid(source, "(document)", e.message().to_string())
    })?;
    let mut overrides = Vec::with_capacity(sets.len());
    for set in sets {
        overrides.push(apply_one(&mut doc, set)?);
    }
    Ok((doc.to_string(), overrides))
}

/// Applies one `key=value` to `doc`.
fn apply_one(doc: &mut toml_edit::DocumentMut, set: &str) -> Result<Override> {
    let malformed = |reason: String| Error::invalid(Path::new("--set"), set, reason);
    let (key, value) = set
        .split_once('=')
        .ok_or_else(|| malformed("expected dotted.key=value".into()))?;
    let value: toml_edit::Value = value
        .trim()
        .parse()
        .unwrap_or_else(|_| toml_edit::Value::from(value.trim()));
    let parts: Vec<&str> = key.trim().split('.').map(str::trim).collect();
    let (last, tables) = parts
        .split_last()
        .filter(|(l, t)| !l.is_empty() && t.iter().all(|t| !t.is_empty()))
        .ok_or_else(|| malformed("expected dotted.key=value".into()))?;
    let mut created_table = None;
    // Tables and inline tables (`options = { ... }`) alike.
    let mut table: &mut dyn toml_edit::TableLike = doc.as_table_mut();
    for (depth, t) in tables.iter().enumerate() {
        if created_table.is_none() && !table.contains_key(t) {
            created_table = Some(tables[..=depth].join("."));
        }
        let entry = table.entry(t).or_insert_with(|| {
            let mut t = toml_edit::Table::new();
            t.set_implicit(true);
            toml_edit::Item::Table(t)
        });
        table = entry
            .as_table_like_mut()
            .ok_or_else(|| malformed(format!("{} is not a table", tables[..=depth].join("."))))?;
    }
    table.insert(last, toml_edit::Item::Value(value));
    Ok(Override {
        key: parts.join("."),
        arg: set.trim().to_string(),
        created_table,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn an_override_explains_its_key_and_the_tables_it_created() {
        let text = "[run]\nmax_rounds = 3\n[agents.designer]\nimpl = \"rules\"\n";
        let sets = [
            "run.max_roundz=2".to_string(),
            "agents.desinger.impl=noisy".to_string(),
            "agents.designer.options.bogus=1".to_string(),
        ];
        let (out, overrides) = apply(Path::new("g.toml"), text, &sets).unwrap();
        assert!(out.contains("max_roundz = 2"), "{out}");
        assert_eq!(origin(&overrides, "run.max_roundz").unwrap().arg, sets[0]);
        assert!(origin(&overrides, "run.max_rounds").is_none());
        assert_eq!(
            origin(&overrides, "agents.desinger.role").unwrap().arg,
            sets[1]
        );
        assert!(origin(&overrides, "agents.designer.impl").is_none());
        let bogus = origin(&overrides, "agents.designer.options.bogus").unwrap();
        assert_eq!(
            bogus.label(),
            PathBuf::from("--set agents.designer.options.bogus=1")
        );
    }

    #[test]
    fn a_malformed_override_is_named() {
        let e = apply(Path::new("g.toml"), "", &["run.".into()]).unwrap_err();
        assert!(e.to_string().starts_with("--set: run.: expected"), "{e}");
        let e = apply(Path::new("g.toml"), "run = 1\n", &["run.x=1".into()]).unwrap_err();
        assert!(e.to_string().contains("run is not a table"), "{e}");
    }
}
