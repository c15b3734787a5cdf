//! `disco metrics`: measure a layout against its scene.

use std::path::PathBuf;

use anyhow::Result;
use disco_layout::{Layout, SceneSpec};

use super::check_belongs;

/// The arguments of `disco metrics`.
#[derive(clap::Args)]
pub struct Metrics {
    /// The scene spec.
    scene: PathBuf,
    /// The layout (JSON).
    layout: PathBuf,
    /// Print JSON instead of text.
    #[arg(long)]
    json: bool,
}

impl Metrics {
    /// Checks the layout belongs to the scene, then prints its metrics.
    pub fn run(self) -> Result<()> {
        let spec = SceneSpec::load(&self.scene)?;
        let layout = Layout::load(&self.layout)?;
        check_belongs(&spec, &layout, &self.layout)?;
        super::print_measured(&spec, &layout, self.json)
    }
}
