//! `disco bench merge`: the shard folders of a split benchmark run into one set of tables.

use std::path::PathBuf;

use anyhow::Result;
use disco_layout::bench::merge::merge_shards;

use super::{ScenesFailed, print_json};

/// The arguments of `disco bench merge`.
#[derive(clap::Args)]
pub struct Merge {
    /// Where the merged tables, results and layouts go.
    out: PathBuf,
    /// The `--out` folders of the shards (`disco bench --shard I/N`), every shard once.
    #[arg(required = true)]
    shards: Vec<PathBuf>,
    /// Print the merged results and table as JSON instead of Markdown.
    #[arg(long)]
    json: bool,
}

impl Merge {
    /// Merges the shards, prints the table, and fails with exit code 4 if a scene failed (as
    /// the single run would have); overlapping or missing scenes are refused (exit 1).
    pub fn run(&self, quiet: bool) -> Result<()> {
        let run = merge_shards(&self.out, &self.shards)?;
        if self.json {
            print_json(&run)?;
        } else if !quiet {
            out!("{}", run.table.to_markdown());
        }
        let failed = run.results.iter().filter(|r| r.failure.is_some()).count();
        ScenesFailed::check(failed, run.results.len())
    }
}
