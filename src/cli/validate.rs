//! `disco validate`: check a scene spec.

use std::path::PathBuf;

use anyhow::Result;
use disco_layout::SceneSpec;
use disco_layout::scene::Room;
use serde::Serialize;

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

/// The verdict printed with `--json` (an invalid scene is an error instead, exit code 1).
#[derive(Serialize)]
struct Verdict<'a> {
    /// Always true: an invalid scene never gets this far.
    valid: bool,
    id: &'a str,
    /// The number of assets.
    assets: usize,
    room: &'a Room,
    room_type: &'a str,
    warnings: Vec<WarningJson>,
}

/// One non-fatal problem of the scene.
#[derive(Serialize)]
struct WarningJson {
    /// Where, as a JSON path (e.g. `assets[3]`).
    field: String,
    /// What, in words.
    message: String,
}

impl Validate {
    /// Loads the scene (its errors are the command's) and prints the verdict and the warnings.
    pub fn run(self, quiet: bool) -> Result<()> {
        let spec = SceneSpec::load(&self.scene)?;
        if self.json {
            let warnings = spec
                .warnings()
                .into_iter()
                .map(|w| WarningJson {
                    field: w.field,
                    message: w.message,
                })
                .collect();
            return print_json(&Verdict {
                valid: true,
                id: &spec.id,
                assets: spec.assets.len(),
                room: &spec.room,
                room_type: &spec.room_type,
                warnings,
            });
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
