//! `disco bench`: one method over scene folders into per-category tables, or a suite of methods
//! into the comparison tables of `RESULTS.md`.

use std::path::{Path, PathBuf};
use std::sync::Arc;

use anyhow::Result;
use disco_layout::bench::suite::{Suite, run_suite};
use disco_layout::bench::{self, BenchOptions, merge};
use disco_layout::config::GraphConfig;
use disco_layout::registry::Registry;
use disco_layout::runtime::batch;
use disco_layout::runtime::shard::Shard;
use disco_layout::trace::Trace;
use disco_layout::{io, report};

use super::bench_merge::Merge;
use super::{GraphArgs, ScenesFailed, print_json, progress_wanted, tokio_runtime};

/// The arguments of `disco bench`.
#[derive(clap::Args)]
#[command(args_conflicts_with_subcommands = true, subcommand_negates_reqs = true)]
pub struct Bench {
    #[command(subcommand)]
    action: Option<BenchAction>,
    /// Scene files or folders (repeatable).
    #[arg(long = "scenes", required_unless_present = "suite")]
    scenes: Vec<PathBuf>,
    /// A suite file (methods and tables, see bench/suite.toml) instead of one method.
    #[arg(long, conflicts_with_all = ["scenes", "judge", "config", "sets"])]
    suite: Option<PathBuf>,
    #[command(flatten)]
    graph: GraphArgs,
    /// Output folder: layouts, per-scene results, tables.
    // Required without a subcommand; an `Option` only because `merge` does without it.
    #[arg(long, required = true)]
    out: Option<PathBuf>,
    /// Run only shard I of N (numbered from 0): the scenes whose id hashes there (FNV-1a 64).
    /// Give each shard its own `--out`; `disco bench merge` joins them into one table.
    #[arg(long, value_name = "I/N", conflicts_with = "suite")]
    shard: Option<Shard>,
    /// Scenes in flight at once (a suite's own `jobs` otherwise).
    #[arg(long)]
    jobs: Option<usize>,
    /// Also score every layout with this graph's VLM judge.
    #[arg(long)]
    judge: Option<PathBuf>,
    /// Regenerate every scene instead of reusing layouts already in the output folder.
    #[arg(long)]
    fresh: bool,
    /// Write one self-contained HTML report over all scenes (table, renders, metrics, drops).
    #[arg(long, conflicts_with = "suite")]
    report: Option<PathBuf>,
    /// Print the tables as JSON instead of Markdown.
    #[arg(long)]
    json: bool,
}

/// What `disco bench` can do besides running a method.
#[derive(clap::Subcommand)]
enum BenchAction {
    /// Merge the output folders of a run split with `--shard I/N` into the `table.md`,
    /// `table.json`, `results.json` and `layouts/` one process would have written. Refuses a
    /// scene found in two shards and, naming them, scenes no shard has finished.
    Merge(Merge),
}

impl Bench {
    /// Runs the suite or the one method, prints the tables, and fails with exit code 4 if a
    /// scene of the one method failed.
    pub fn run(self, quiet: bool) -> Result<()> {
        if let Some(BenchAction::Merge(m)) = &self.action {
            return m.run(quiet);
        }
        let rt = tokio_runtime()?;
        let mut options = BenchOptions {
            jobs: self.jobs.unwrap_or(2),
            progress: progress_wanted(quiet),
            fresh: self.fresh,
        };
        if let Some(path) = &self.suite {
            let suite = Suite::load(path)?;
            options.jobs = self.jobs.unwrap_or(suite.jobs);
            return self.run_suite(&rt, &suite, path, &options, quiet);
        }
        self.run_method(&rt, &options, quiet)
    }

    /// The `--out` folder (clap requires it whenever no subcommand is given).
    fn out(&self) -> Result<&Path> {
        self.out
            .as_deref()
            .ok_or_else(|| anyhow::anyhow!("--out is required"))
    }

    /// Every method of `suite` over its scenes; prints `RESULTS.md` (or its data as JSON).
    fn run_suite(
        &self,
        rt: &tokio::runtime::Runtime,
        suite: &Suite,
        path: &Path,
        options: &BenchOptions,
        quiet: bool,
    ) -> Result<()> {
        refuse_out_over_scenes(&suite.scenes, self.out()?)?;
        let report = rt.block_on(run_suite(
            suite,
            path,
            self.out()?,
            &Registry::builtin(),
            options,
        ))?;
        if self.json {
            print_json(&report)?;
        } else if !quiet {
            outln!(
                "{}",
                std::fs::read_to_string(self.out()?.join("RESULTS.md"))?
            );
        }
        Ok(())
    }

    /// The graph of `--config` over `--scenes`, judged with `--judge`'s graph when given.
    fn run_method(
        &self,
        rt: &tokio::runtime::Runtime,
        options: &BenchOptions,
        quiet: bool,
    ) -> Result<()> {
        let runtime = self.graph.runtime(rt)?;
        let judge = self
            .judge
            .as_ref()
            .map(|p| GraphConfig::load(Some(p), &[]))
            .transpose()?;
        refuse_out_over_scenes(&self.scenes, self.out()?)?;
        let mut inputs = batch::collect_scenes(&self.scenes)?;
        if let Some(report) = &self.report {
            let scenes: Vec<_> = inputs
                .iter()
                .map(|p| io::NamedPath::new("--scenes", p))
                .collect();
            io::refuse_clobbering(&scenes, &[io::NamedPath::new("--report", report)], &[])?;
        }
        if let Some(shard) = self.shard {
            inputs = merge::prepare_shard(self.out()?, shard, &inputs)?;
        }
        let run = rt.block_on(bench::run_scenes(
            &runtime,
            &inputs,
            self.out()?,
            options,
            judge.as_ref(),
            Arc::new(Trace::default()),
        ))?;
        if let Some(path) = &self.report {
            let html = report::html::bench_report(
                &format!("Benchmark: {}", self.out()?.display()),
                &run.table,
                &bench::load_outputs(&inputs, self.out()?, &run.results),
            )?;
            io::write_atomic(path, html.as_bytes())?;
        }
        if self.json {
            print_json(&run)?;
        } else if !quiet {
            out!("{}", run.table.to_markdown());
        }
        let failed = run.results.iter().filter(|r| r.failure.is_some()).count();
        ScenesFailed::check(failed, run.results.len())
    }
}

/// Refuses an `--out` folder that is a scene folder or file, lies inside a scene folder, or
/// holds one (by path or through a link), before anything runs: the tables, results and layouts
/// written there would mix with the scenes and be read as scenes by the next run.
fn refuse_out_over_scenes(scenes: &[PathBuf], out: &Path) -> Result<()> {
    let inputs: Vec<_> = scenes
        .iter()
        .map(|p| io::NamedPath::new("--scenes", p))
        .collect();
    io::refuse_folder_over_inputs(&inputs, &io::NamedPath::new("--out", out))?;
    Ok(())
}
