//! `disco judge`: score a layout's coherency with a model looking at its render.

use std::path::PathBuf;

use anyhow::Result;
use disco_layout::{Layout, SceneSpec};

use super::{GraphArgs, check_belongs, print_json, tokio_runtime};

/// The arguments of `disco judge`.
#[derive(clap::Args)]
pub struct Judge {
    /// The scene spec.
    scene: PathBuf,
    /// The layout (JSON).
    layout: PathBuf,
    #[command(flatten)]
    graph: GraphArgs,
    /// Print JSON instead of text.
    #[arg(long)]
    json: bool,
}

impl Judge {
    /// Asks the graph's judge (else designer) model for the two scores and prints them.
    pub fn run(self) -> Result<()> {
        let spec = SceneSpec::load(&self.scene)?;
        let layout = Layout::load(&self.layout)?;
        check_belongs(&spec, &layout, &self.layout)?;
        let graph = self.graph.graph()?;
        let rt = tokio_runtime()?;
        let scores = rt.block_on(disco_layout::judge::judge_layout(&graph, &spec, &layout))?;
        if self.json {
            return print_json(&scores);
        }
        outln!(
            "positional {:.0}/100, rotational {:.0}/100 ({} model calls, {} tokens)",
            scores.positional,
            scores.rotational,
            scores.usage.calls,
            scores.usage.prompt_tokens + scores.usage.completion_tokens
        );
        if !scores.comment.is_empty() {
            outln!("{}", scores.comment);
        }
        Ok(())
    }
}
