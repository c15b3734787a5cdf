//! The benchmark: run a method (an agent graph) over a folder of scenes and average its metrics
//! per room category ([`run_scenes`]); run several methods into the comparison tables of a suite
//! ([`suite`]); merge the outputs of a run split into shards ([`merge`]); and re-measure the
//! runtime's speed figures ([`perf`]).
//!
//! Every figure comes from the same [`crate::metrics`] used by tests and the evaluator, so a
//! table row and a `disco metrics` line of the same layout agree.

pub mod merge;
pub mod patterns;
pub mod perf;
pub mod suite;
pub mod table;

use std::path::{Path, PathBuf};
use std::sync::Arc;

use futures::StreamExt;
use serde::Serialize;

pub use table::{JudgeResult, OpeningsBlocked, Row, SceneResult, Table};

use crate::config::GraphConfig;
use crate::error::{Error, Result};
use crate::layout::Layout;
use crate::runtime::Runtime;
use crate::runtime::batch::{self, BatchOptions, Outcome};
use crate::scene::SceneSpec;
use crate::trace::Trace;

/// How a benchmark run goes.
#[derive(Debug, Clone)]
pub struct BenchOptions {
    /// Scenes in flight at once.
    pub jobs: usize,
    /// Draw a progress bar (only on a terminal).
    pub progress: bool,
    /// Regenerate every scene; otherwise layouts already in the output folder are reused, so an
    /// interrupted run resumes where it stopped.
    pub fresh: bool,
}

/// What a benchmark run of one method wrote and measured.
#[derive(Debug, Clone, Serialize)]
pub struct MethodRun {
    /// Per scene, in file order.
    pub results: Vec<SceneResult>,
    /// The per-category table.
    pub table: Table,
}

/// Runs `runtime` over `scenes` into `out_dir`: layouts in `out_dir/layouts/`, per-scene results
/// in `results.json`, the per-category table in `table.md` and `table.json`. With `judge`, every
/// layout is also scored by that graph's judge model.
pub async fn run_scenes(
    runtime: &Runtime,
    scenes: &[PathBuf],
    out_dir: &Path,
    options: &BenchOptions,
    judge: Option<&GraphConfig>,
    trace: Arc<Trace>,
) -> Result<MethodRun> {
    let layouts = out_dir.join("layouts");
    if options.fresh && layouts.exists() {
        std::fs::remove_dir_all(&layouts).map_err(|source| Error::Write {
            path: layouts.clone(),
            source,
        })?;
    }
    std::fs::create_dir_all(&layouts).map_err(|source| Error::Write {
        path: layouts.clone(),
        source,
    })?;
    let batch_options = BatchOptions {
        jobs: options.jobs,
        out_dir: layouts.clone(),
        progress: options.progress,
    };
    let reports = batch::run_batch(runtime, scenes, &batch_options, trace).await;
    let mut results: Vec<SceneResult> = reports
        .iter()
        .map(|r| {
            let category = r.room_type.clone().unwrap_or_else(|| "unreadable".into());
            let layout = match r.outcome {
                Outcome::Failed { .. } => None,
                _ => Layout::load(&layouts.join(format!("{}.json", batch::file_safe(&r.id)))).ok(),
            };
            let stats = layout.as_ref().map(|l| l.stats.clone()).unwrap_or_default();
            SceneResult {
                id: r.id.clone(),
                category,
                metrics: r.metrics.clone(),
                failure: match &r.outcome {
                    Outcome::Failed { reason } => Some(reason.clone()),
                    _ => None,
                },
                llm_calls: stats.llm_calls,
                tokens: stats.prompt_tokens + stats.completion_tokens,
                wall_ms: if layout.is_some() {
                    stats.wall_ms
                } else {
                    r.wall_ms
                },
                judge: None,
            }
        })
        .collect();
    if let Some(graph) = judge {
        judge_all(graph, scenes, &layouts, &mut results, options.jobs).await?;
    }
    let table = write_tables(out_dir, &results)?;
    Ok(MethodRun { results, table })
}

/// Writes `results` as `out_dir/results.json` and their per-category table as `table.json` and
/// `table.md` (the files a benchmark run ends with); returns the table.
pub fn write_tables(out_dir: &Path, results: &[SceneResult]) -> Result<Table> {
    let scenes = if results.len() == 1 {
        "scene"
    } else {
        "scenes"
    };
    let table = Table::by_category(&format!("{} {scenes}", results.len()), results);
    crate::io::write_json(&out_dir.join("results.json"), &results)?;
    crate::io::write_json(&out_dir.join("table.json"), &table)?;
    crate::io::write_atomic(&out_dir.join("table.md"), table.to_markdown().as_bytes())?;
    Ok(table)
}

/// Scores every generated layout with `graph`'s judge, `jobs` at a time. The first judge failure
/// (server down, no model configured) stops the run with that error.
async fn judge_all(
    graph: &GraphConfig,
    scenes: &[PathBuf],
    layouts: &Path,
    results: &mut [SceneResult],
    jobs: usize,
) -> Result<()> {
    let work: Vec<(usize, SceneSpec, Layout)> = scenes
        .iter()
        .filter_map(|p| SceneSpec::load(p).ok())
        .filter_map(|spec| {
            let i = results
                .iter()
                .position(|r| r.id == spec.id && r.metrics.is_some())?;
            let layout =
                Layout::load(&layouts.join(format!("{}.json", batch::file_safe(&spec.id)))).ok()?;
            Some((i, spec, layout))
        })
        .collect();
    let scores: Vec<(usize, Result<crate::agents::vlm::judge::Scores>)> =
        futures::stream::iter(work)
            .map(|(i, spec, layout)| async move {
                (i, crate::judge::judge_layout(graph, &spec, &layout).await)
            })
            .buffer_unordered(jobs.max(1))
            .collect()
            .await;
    for (i, s) in scores {
        let s = s?;
        results[i].judge = Some(JudgeResult {
            positional: s.positional,
            rotational: s.rotational,
        });
    }
    Ok(())
}

/// For a report: each result with its scene spec and layout, read back from `out_dir/layouts`
/// (either is `None` when it cannot be read: a failed scene has no layout).
pub fn load_outputs(
    scenes: &[PathBuf],
    out_dir: &Path,
    results: &[SceneResult],
) -> Vec<(SceneResult, Option<SceneSpec>, Option<Layout>)> {
    let specs: Vec<SceneSpec> = scenes
        .iter()
        .filter_map(|p| SceneSpec::load(p).ok())
        .collect();
    results
        .iter()
        .map(|r| {
            let spec = specs.iter().find(|s| s.id == r.id).cloned();
            let layout = r.metrics.as_ref().and_then(|_| {
                Layout::load(
                    &out_dir
                        .join("layouts")
                        .join(format!("{}.json", batch::file_safe(&r.id))),
                )
                .ok()
            });
            (r.clone(), spec, layout)
        })
        .collect()
}
