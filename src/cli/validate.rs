//! `disco validate`: check a scene spec.

use std::path::PathBuf;

use anyhow::Result;
use disco_layout::SceneSpec;

use super::{print_json, warn_about};

/// The arguments of `disco validate`.
#[derive(clap::Args)]
pub struct Validate {
    /// The scene spec (JSON).
    scene: PathBuf,
    /// Print the verdict as JSON.
    #[arg(long)]
    json: bool,
}

impl Validate {
    /// Loads the scene (its errors are the command's) and prints the verdict and the warnings.
    pub fn run(self, quiet: bool) -> Result<()> {
        let spec = SceneSpec::load(&self.scene)?;
        if self.json {
            return print_json(&disco_layout::commands::verdict(&spec));
        }
        warn_about(&spec, &self.scene);
        if !quiet {
            outln!(
                "{}: valid scene {:?}: {} in a {} x {} cm {}",
                self.scene.display(),
                spec.id,
                super::count(spec.assets.len(), "asset"),
                spec.room.width,
                spec.room.depth,
                spec.room_type
            );
        }
        Ok(())
    }
}
