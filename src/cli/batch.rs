//! `disco batch`: furnish many rooms at once, skipping those already done.

use std::path::PathBuf;
use std::sync::Arc;

use anyhow::{Context, Result};
use disco_layout::io;
use disco_layout::runtime::batch::{self, BatchOptions, Outcome};
use disco_layout::runtime::shard::Shard;
use disco_layout::trace::Trace;

use super::{GraphArgs, ScenesFailed, print_json, progress_wanted, tokio_runtime};

/// The arguments of `disco batch`.
#[derive(clap::Args)]
pub struct Batch {
    /// Scene files, or folders of them.
    #[arg(required = true)]
    scenes: Vec<PathBuf>,
    /// Output folder (`<id>.json` per scene).
    #[arg(long)]
    out: PathBuf,
    /// Scenes in flight at once.
    #[arg(long, default_value_t = 4)]
    jobs: usize,
    /// Run only shard I of N (numbered from 0): the scenes whose id hashes there (FNV-1a 64).
    /// N processes with 0/N .. (N-1)/N cover every scene once and may share `--out`.
    #[arg(long, value_name = "I/N")]
    shard: Option<Shard>,
    #[command(flatten)]
    graph: GraphArgs,
    /// Write every message of every scene as JSON lines.
    #[arg(long)]
    trace: Option<PathBuf>,
    /// Print the reports as JSON instead of a table.
    #[arg(long)]
    json: bool,
}

impl Batch {
    /// Runs every scene, prints the reports, and fails with exit code 4 if any scene failed.
    pub fn run(self, quiet: bool) -> Result<()> {
        let rt = tokio_runtime()?;
        let runtime = self.graph.runtime(&rt)?;
        let mut inputs = batch::collect_scenes(&self.scenes)?;
        if let Some(shard) = self.shard {
            inputs = shard.select(&inputs);
        }
        if let Some(trace) = &self.trace {
            let scenes: Vec<_> = inputs
                .iter()
                .map(|p| io::NamedPath::new("SCENES", p))
                .collect();
            io::refuse_clobbering(&scenes, &[io::NamedPath::new("--trace", trace)], &[])?;
        }
        std::fs::create_dir_all(&self.out)
            .with_context(|| format!("{}: cannot create the folder", self.out.display()))?;
        let events = Arc::new(match self.trace {
            Some(_) => Trace::default(),
            None => Trace::discarding(),
        });
        let options = BatchOptions {
            jobs: self.jobs,
            out_dir: self.out,
            progress: progress_wanted(quiet),
        };
        let reports = rt.block_on(batch::run_batch(
            &runtime,
            &inputs,
            &options,
            Arc::clone(&events),
        ));
        if let Some(path) = &self.trace {
            events.write_jsonl(path)?;
        }
        if self.json {
            print_json(&reports)?;
        } else if !quiet {
            out!("{}", batch::summary_table(&reports));
        }
        let failed = reports
            .iter()
            .filter(|r| matches!(r.outcome, Outcome::Failed { .. }))
            .count();
        ScenesFailed::check(failed, reports.len())
    }
}
