//! A benchmark suite: several methods (agent graphs) over the same scenes, compared in tables,
//! written as one Markdown document (`RESULTS.md`) with the command behind each table.
//!
//! ```toml
//! scenes = ["bench/scenes"]
//! jobs = 2
//! perf = true                      # append the speed figures of `disco perf`
//!
//! [[method]]
//! name = "DisCo (rules)"
//! config = "config/default.toml"
//! set = []                         # --set overrides
//!
//! [[table]]
//! title = "Table 1"
//! by = "category"                  # one method, a row per room category
//! methods = ["DisCo (rules)"]
//! ```
//!
//! Paths are relative to the directory the command runs in (the repository root).

use std::fmt::Write as _;
use std::path::{Path, PathBuf};
use std::sync::Arc;

use serde::{Deserialize, Serialize};

use super::perf::{PerfOptions, PerfReport};
use super::{BenchOptions, MethodRun, Table, run_scenes};
use crate::config::GraphConfig;
use crate::error::{Error, Result};
use crate::registry::Registry;
use crate::runtime::Runtime;
use crate::runtime::batch::collect_scenes;
use crate::trace::Trace;

/// A suite file.
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Suite {
    /// Scene files or folders, as `disco batch` takes them.
    pub scenes: Vec<PathBuf>,
    /// Scenes in flight at once.
    #[serde(default = "default_jobs")]
    pub jobs: usize,
    /// Append the speed figures of [`super::perf`].
    #[serde(default)]
    pub perf: bool,
    /// The methods.
    pub method: Vec<Method>,
    /// The tables.
    pub table: Vec<TableSpec>,
}

fn default_jobs() -> usize {
    2
}

/// One method: an agent graph and overrides.
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Method {
    /// Its name in the tables.
    pub name: String,
    /// The graph; the built-in default when absent.
    pub config: Option<PathBuf>,
    /// `--set` overrides.
    #[serde(default)]
    pub set: Vec<String>,
    /// Score its layouts with this graph's judge model.
    pub judge: Option<PathBuf>,
}

/// How a table groups rows.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Grouping {
    /// One method, a row per room category and the average.
    Category,
    /// A row per method, averaged over every scene.
    Method,
}

/// One table of the suite.
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct TableSpec {
    /// Heading.
    pub title: String,
    /// A paragraph under the heading.
    #[serde(default)]
    pub note: String,
    /// Rows per category or per method.
    pub by: Grouping,
    /// The methods it shows, by name.
    pub methods: Vec<String>,
}

impl Suite {
    /// Reads and checks a suite file: every table names known methods, a category table one.
    pub fn load(path: &Path) -> Result<Suite> {
        let text = std::fs::read_to_string(path).map_err(|source| Error::Read {
            path: path.to_path_buf(),
            source,
        })?;
        let suite: Suite = toml::from_str(&text)
            .map_err(|e| Error::invalid(path, "suite", e.to_string().trim().to_string()))?;
        for (i, t) in suite.table.iter().enumerate() {
            for m in &t.methods {
                if !suite.method.iter().any(|x| &x.name == m) {
                    return Err(Error::invalid(
                        path,
                        format!("table[{i}].methods"),
                        format!("no [[method]] named {m:?}"),
                    ));
                }
            }
            if t.by == Grouping::Category && t.methods.len() != 1 {
                return Err(Error::invalid(
                    path,
                    format!("table[{i}].methods"),
                    "a table by category shows exactly one method",
                ));
            }
        }
        Ok(suite)
    }
}

/// One table of a suite run, with what the reader needs to reproduce it.
#[derive(Debug, Clone, Serialize)]
pub struct SuiteTable {
    /// Heading.
    pub title: String,
    /// The paragraph under it.
    pub note: String,
    /// The `disco bench` command of each of its methods.
    pub commands: Vec<String>,
    /// The rows.
    pub table: Table,
}

/// What a suite run produced.
#[derive(Debug, Clone, Serialize)]
pub struct SuiteReport {
    /// The tables, in the suite's order.
    pub tables: Vec<SuiteTable>,
    /// The speed figures, when asked for.
    pub perf: Option<PerfReport>,
}

/// A method's folder name: lower case, words joined by `-` (`"w/o SRT"` -> `w-o-srt`).
pub fn slug(name: &str) -> String {
    name.to_lowercase()
        .split(|c: char| !c.is_alphanumeric())
        .filter(|w| !w.is_empty())
        .collect::<Vec<_>>()
        .join("-")
}

/// The `disco bench` command line that runs one method alone.
pub fn method_command(suite: &Suite, method: &Method, out: &Path) -> String {
    let mut cmd = String::from("disco bench");
    for s in &suite.scenes {
        let _ = write!(cmd, " --scenes {}", s.display());
    }
    if let Some(c) = &method.config {
        let _ = write!(cmd, " --config {}", c.display());
    }
    for s in &method.set {
        let _ = write!(cmd, " --set {s}");
    }
    if let Some(j) = &method.judge {
        let _ = write!(cmd, " --judge {}", j.display());
    }
    let _ = write!(
        cmd,
        " --jobs {} --out {}",
        suite.jobs,
        out.join(slug(&method.name)).display()
    );
    cmd
}

/// Runs every method of `suite` used by a table over its scenes into `out/<method>/`, builds the
/// tables, and writes `out/RESULTS.md` and `out/results.json`.
pub async fn run_suite(
    suite: &Suite,
    suite_path: &Path,
    out: &Path,
    registry: &Registry,
    options: &BenchOptions,
) -> Result<SuiteReport> {
    let scenes = collect_scenes(&suite.scenes)?;
    let mut runs: Vec<(String, MethodRun)> = Vec::new();
    for method in &suite.method {
        if !suite.table.iter().any(|t| t.methods.contains(&method.name)) {
            continue;
        }
        tracing::info!(method = %method.name, "benchmark method");
        let graph = GraphConfig::load(method.config.as_deref(), &method.set)?;
        let runtime = Runtime::new(graph, registry.clone())?;
        runtime.preflight().await?;
        let judge = match &method.judge {
            Some(p) => Some(GraphConfig::load(Some(p), &[])?),
            None => None,
        };
        let run = run_scenes(
            &runtime,
            &scenes,
            &out.join(slug(&method.name)),
            options,
            judge.as_ref(),
            Arc::new(Trace::default()),
        )
        .await?;
        runs.push((method.name.clone(), run));
    }
    let mut tables = Vec::new();
    for spec in &suite.table {
        let picked: Vec<(String, Vec<crate::bench::SceneResult>)> = spec
            .methods
            .iter()
            .filter_map(|m| runs.iter().find(|(n, _)| n == m))
            .map(|(n, r)| (n.clone(), r.results.clone()))
            .collect();
        let table = match spec.by {
            Grouping::Category => Table::by_category(&spec.title, &picked[0].1),
            Grouping::Method => Table::by_method(&spec.title, &picked),
        };
        let commands = spec
            .methods
            .iter()
            .filter_map(|m| suite.method.iter().find(|x| &x.name == m))
            .map(|m| method_command(suite, m, out))
            .collect();
        tables.push(SuiteTable {
            title: spec.title.clone(),
            note: spec.note.clone(),
            commands,
            table,
        });
    }
    let perf = if suite.perf {
        Some(super::perf::measure(&PerfOptions::default()).await?)
    } else {
        None
    };
    let report = SuiteReport { tables, perf };
    crate::io::write_atomic(
        &out.join("RESULTS.md"),
        results_markdown(&report, suite_path, out, scenes.len()).as_bytes(),
    )?;
    crate::io::write_json(&out.join("results.json"), &report)?;
    Ok(report)
}

/// The whole report as one Markdown document.
pub fn results_markdown(
    report: &SuiteReport,
    suite_path: &Path,
    out: &Path,
    scenes: usize,
) -> String {
    let mut s = String::from("# Benchmark results\n\n");
    let _ = writeln!(
        s,
        "Every table below was produced by one command, run from the repository root:\n\n```sh\ncargo run --release -- bench --suite {} --out {}\n```\n",
        suite_path.display(),
        out.display()
    );
    let _ = writeln!(
        s,
        "{scenes} scenes. Col, OOB, constraints, reach and dropped are means over scenes of the per-scene percentages defined in docs/formats.md (`disco metrics` prints the same figures for one layout). Constraints are checked against each method's own plan; all offline methods here share the rule planner, so they answer the same constraints. Seconds are wall time per scene with the stated number of scenes in flight.\n"
    );
    for SuiteTable {
        title,
        note,
        commands,
        table,
    } in &report.tables
    {
        let _ = writeln!(s, "## {title}\n");
        if !note.is_empty() {
            let _ = writeln!(s, "{note}\n");
        }
        s.push_str("Each method alone (`disco` is `target/release/disco`):\n\n```sh\n");
        for c in commands {
            let _ = writeln!(s, "{c}");
        }
        s.push_str("```\n\n");
        s.push_str(&table.to_markdown());
        s.push('\n');
    }
    if let Some(perf) = &report.perf {
        s.push_str("## Speed\n\nAlone: `cargo run --release -- perf`.\n\n");
        s.push_str(&perf.to_markdown());
    }
    s
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn slugs_are_plain_folder_names() {
        assert_eq!(slug("w/o SRT"), "w-o-srt");
        assert_eq!(slug("DisCo (full)"), "disco-full");
        assert_eq!(slug("DisCo, rule agents"), "disco-rule-agents");
    }

    #[test]
    fn a_suite_with_an_unknown_method_or_a_crowded_category_table_is_refused() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("suite.toml");
        let base = "scenes = [\"s\"]\n[[method]]\nname = \"a\"\n[[method]]\nname = \"b\"\n";
        std::fs::write(
            &path,
            format!("{base}[[table]]\ntitle = \"t\"\nby = \"method\"\nmethods = [\"a\", \"c\"]\n"),
        )
        .unwrap();
        let e = Suite::load(&path).unwrap_err().to_string();
        assert!(e.contains("table[0].methods") && e.contains("\"c\""), "{e}");
        std::fs::write(
            &path,
            format!(
                "{base}[[table]]\ntitle = \"t\"\nby = \"category\"\nmethods = [\"a\", \"b\"]\n"
            ),
        )
        .unwrap();
        let e = Suite::load(&path).unwrap_err().to_string();
        assert!(e.contains("exactly one method"), "{e}");
        std::fs::write(
            &path,
            format!("{base}[[table]]\ntitle = \"t\"\nby = \"method\"\nmethods = [\"a\", \"b\"]\n"),
        )
        .unwrap();
        let suite = Suite::load(&path).unwrap();
        assert_eq!(suite.jobs, 2);
        std::fs::write(&path, format!("{base}bogus = 1\n")).unwrap();
        assert!(Suite::load(&path).is_err());
    }
}
