//! `disco perf`: re-measure the speed figures.

use anyhow::Result;
use disco_layout::bench::perf::{self, PerfOptions};

use super::{print_json, tokio_runtime};

/// The arguments of `disco perf`.
#[derive(clap::Args)]
pub struct Perf {
    /// Scenes in the throughput run.
    #[arg(long, default_value_t = 300)]
    scenes: usize,
    /// The largest scene of the growth curve, in objects (10, 30, 100, 300, 1000, 3000 up to
    /// this; 0 leaves the curve out).
    #[arg(long, default_value_t = 3000)]
    max_objects: usize,
    /// Print JSON instead of a Markdown table.
    #[arg(long)]
    json: bool,
}

impl Perf {
    /// Measures every figure and prints them (also with `-q`: they are the command's result).
    pub fn run(self) -> Result<()> {
        let rt = tokio_runtime()?;
        let options = PerfOptions {
            throughput_scenes: self.scenes,
            max_objects: self.max_objects,
            ..PerfOptions::default()
        };
        let report = rt.block_on(perf::measure(&options))?;
        if self.json {
            print_json(&report)?;
        } else {
            out!("{}", report.to_markdown());
        }
        Ok(())
    }
}
