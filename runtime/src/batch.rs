//! Many scenes at once: a bounded number in flight, a progress bar, outputs written atomically
//! as `OUT/<id>.json`, finished scenes skipped on a rerun, one failing scene reported while the
//! rest finish.

use std::path::{Path, PathBuf};
use std::sync::Arc;
use std::time::Instant;

use futures::StreamExt;
use indicatif::{ProgressBar, ProgressDrawTarget, ProgressStyle};
use serde::Serialize;

use super::Runtime;
use crate::trace::Trace;
use disco_core::error::{Error, Result};
use disco_core::layout::Layout;
use disco_core::metrics::{Metrics, measure};
use disco_core::scene::SceneSpec;

/// How a batch runs.
#[derive(Debug, Clone)]
pub struct BatchOptions {
    /// Scenes in flight at once.
    pub jobs: usize,
    /// Where `<id>.json` outputs go.
    pub out_dir: PathBuf,
    /// Draw a progress bar (only shown on a terminal).
    pub progress: bool,
}

/// What happened to one scene.
#[derive(Debug, Clone, PartialEq, Serialize)]
#[serde(tag = "status", rename_all = "snake_case")]
pub enum Outcome {
    /// Generated and written.
    Done,
    /// Its output already existed and was valid.
    Skipped,
    /// It could not be generated; the reason.
    Failed {
        /// Why.
        reason: String,
    },
}

/// One scene of a batch.
#[derive(Debug, Clone, Serialize)]
pub struct SceneReport {
    /// The scene file.
    pub input: PathBuf,
    /// The scene's id (the file stem when the file could not be read).
    pub id: String,
    /// The scene's room type (`None` when the file could not be read).
    pub room_type: Option<String>,
    /// What happened.
    #[serde(flatten)]
    pub outcome: Outcome,
    /// Metrics of the written (or existing) layout.
    pub metrics: Option<Metrics>,
    /// Time spent on it, in milliseconds.
    pub wall_ms: u64,
}

/// The scene files named by `inputs`: files as given, folders expanded to their `*.json` files
/// (sorted, layouts `*.layout.json` left out).
pub fn collect_scenes(inputs: &[PathBuf]) -> Result<Vec<PathBuf>> {
    let mut out = Vec::new();
    for input in inputs {
        if input.is_dir() {
            let entries = std::fs::read_dir(input).map_err(|source| Error::Read {
                path: input.clone(),
                source,
            })?;
            let mut files: Vec<PathBuf> = entries
                .filter_map(|e| e.ok().map(|e| e.path()))
                .filter(|p| {
                    let name = p
                        .file_name()
                        .map(|n| n.to_string_lossy().into_owned())
                        .unwrap_or_default();
                    name.ends_with(".json") && !name.ends_with(".layout.json")
                })
                .collect();
            files.sort();
            out.extend(files);
        } else {
            out.push(input.clone());
        }
    }
    Ok(out)
}

/// Runs every scene of `inputs` with at most `options.jobs` in flight.
pub async fn run_batch(
    runtime: &Runtime,
    inputs: &[PathBuf],
    options: &BatchOptions,
    trace: Arc<Trace>,
) -> Vec<SceneReport> {
    let bar = if options.progress {
        ProgressBar::with_draw_target(Some(inputs.len() as u64), ProgressDrawTarget::stderr())
    } else {
        ProgressBar::hidden()
    };
    bar.set_style(
        ProgressStyle::with_template(
            "{spinner} [{elapsed_precise}] {bar:30} {pos}/{len} scenes {msg}",
        )
        .unwrap_or_else(|_| ProgressStyle::default_bar()),
    );
    let mut reports: Vec<SceneReport> = futures::stream::iter(inputs.iter().cloned())
        .map(|path| {
            let trace = Arc::clone(&trace);
            let bar = bar.clone();
            async move {
                let report = run_one(runtime, &path, &options.out_dir, trace).await;
                if let Outcome::Failed { reason } = &report.outcome {
                    let line = format!("failed: {}: {reason}", path.display());
                    // A hidden bar swallows println; failures must still be heard.
                    if bar.is_hidden() {
                        eprintln!("{line}");
                    } else {
                        bar.println(line);
                    }
                }
                bar.inc(1);
                report
            }
        })
        .buffer_unordered(options.jobs.max(1))
        .collect()
        .await;
    bar.finish_and_clear();
    reports.sort_by(|a, b| a.input.cmp(&b.input));
    reports
}

async fn run_one(runtime: &Runtime, path: &Path, out_dir: &Path, trace: Arc<Trace>) -> SceneReport {
    let t0 = Instant::now();
    let stem = path
        .file_stem()
        .map(|s| s.to_string_lossy().into_owned())
        .unwrap_or_default();
    let report = |id: String, outcome: Outcome, metrics: Option<Metrics>| SceneReport {
        input: path.to_path_buf(),
        room_type: None,
        id,
        outcome,
        metrics,
        wall_ms: t0.elapsed().as_millis() as u64,
    };
    let scene = match SceneSpec::load(path) {
        Ok(s) => s,
        Err(e) => {
            return report(
                stem,
                Outcome::Failed {
                    reason: e.to_string(),
                },
                None,
            );
        }
    };
    let id = scene.id.clone();
    let room_type = Some(scene.room_type.clone());
    let report = |id: String, outcome: Outcome, metrics: Option<Metrics>| SceneReport {
        room_type: room_type.clone(),
        ..report(id, outcome, metrics)
    };
    let out = out_dir.join(format!("{}.json", file_safe(&id)));
    if let Ok(existing) = Layout::load(&out) {
        let m = measure(&existing);
        return report(id, Outcome::Skipped, Some(m));
    }
    match runtime.generate(scene, trace).await {
        Ok(layout) => match disco_core::io::write_json(&out, &layout) {
            Ok(()) => report(id, Outcome::Done, Some(measure(&layout))),
            Err(e) => report(
                id,
                Outcome::Failed {
                    reason: e.to_string(),
                },
                None,
            ),
        },
        Err(e) => report(
            id,
            Outcome::Failed {
                reason: e.to_string(),
            },
            None,
        ),
    }
}

/// `id` with path separators and other awkward characters replaced, for a file name.
pub fn file_safe(id: &str) -> String {
    id.chars()
        .map(|c| {
            if c.is_alphanumeric() || "-_.".contains(c) {
                c
            } else {
                '_'
            }
        })
        .collect()
}

/// A plain-text table of the reports: one row per scene, the mean of the measured ones, and a
/// total.
pub fn summary_table(reports: &[SceneReport]) -> String {
    let mut s = format!(
        "{:<28} {:<8} {:>7} {:>6} {:>6} {:>7} {:>6} {:>8}\n",
        "scene", "status", "placed", "Col%", "OOB%", "constr%", "reach%", "ms"
    );
    for r in reports {
        let status = match &r.outcome {
            Outcome::Done => "done",
            Outcome::Skipped => "skipped",
            Outcome::Failed { .. } => "FAILED",
        };
        match &r.metrics {
            Some(m) => s.push_str(&format!(
                "{:<28} {:<8} {:>7} {:>6.1} {:>6.2} {:>7.1} {:>6.1} {:>8}\n",
                truncate(&r.id, 28),
                status,
                format!("{}/{}", m.placed, m.assets),
                m.collision_pct,
                m.oob_pct,
                m.constraint_pct,
                m.reach_pct,
                r.wall_ms
            )),
            None => s.push_str(&format!("{:<28} {:<8}\n", truncate(&r.id, 28), status)),
        }
    }
    let done = reports
        .iter()
        .filter(|r| r.outcome == Outcome::Done)
        .count();
    let skipped = reports
        .iter()
        .filter(|r| r.outcome == Outcome::Skipped)
        .count();
    let failed = reports.len() - done - skipped;
    let measured: Vec<_> = reports.iter().filter_map(|r| r.metrics.as_ref()).collect();
    if !measured.is_empty() {
        let n = measured.len() as f64;
        let mean = |f: fn(&disco_core::metrics::Metrics) -> f64| {
            measured.iter().map(|m| f(m)).sum::<f64>() / n
        };
        s.push_str(&format!(
            "{:<28} {:<8} {:>7} {:>6.1} {:>6.2} {:>7.1} {:>6.1}\n",
            "mean",
            "",
            "",
            mean(|m| m.collision_pct),
            mean(|m| m.oob_pct),
            mean(|m| m.constraint_pct),
            mean(|m| m.reach_pct),
        ));
    }
    s.push_str(&format!(
        "{} scenes: {done} done, {skipped} skipped, {failed} failed\n",
        reports.len()
    ));
    s
}

fn truncate(s: &str, n: usize) -> String {
    if s.chars().count() <= n {
        s.to_string()
    } else {
        s.chars().take(n - 1).collect::<String>() + "…"
    }
}
