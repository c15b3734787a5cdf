//! `disco export`: write a layout as a binary glTF.

use std::path::{Path, PathBuf};

use anyhow::Result;
use disco_layout::export::{self, ExportOptions};
use disco_layout::{Layout, SceneSpec, io};
use serde::Serialize;

use super::{check_belongs, print_json};

/// The arguments of `disco export`.
#[derive(clap::Args)]
pub struct Export {
    /// The layout (JSON).
    layout: PathBuf,
    /// Where to write the .glb.
    #[arg(short, long)]
    output: PathBuf,
    /// The scene spec, to use its assets' `mesh` files instead of boxes.
    #[arg(long)]
    scene: Option<PathBuf>,
    /// Wall height, in cm (0 for no walls).
    #[arg(long, default_value_t = 250.0, value_parser = super::wall_height_cm)]
    wall_height: f64,
    /// Print the summary as JSON.
    #[arg(long)]
    json: bool,
}

/// The summary printed with `--json`.
#[derive(Serialize)]
struct Summary<'a> {
    /// Where the `.glb` went.
    output: &'a Path,
    /// Objects in the file.
    objects: usize,
    /// Objects drawn with their asset's mesh rather than a box.
    meshes: usize,
    wall_height_cm: f64,
    /// The file's size.
    bytes: usize,
}

impl Export {
    /// Reads the layout (and the scene, for meshes), writes the `.glb` and prints a summary.
    pub fn run(self, quiet: bool) -> Result<()> {
        let layout = Layout::load(&self.layout)?;
        let meshes: std::collections::HashMap<String, PathBuf> = match &self.scene {
            Some(path) => {
                let spec = SceneSpec::load(path)?;
                check_belongs(&spec, &layout, &self.layout)?;
                export::meshes_of(&spec, Some(path))
            }
            None => Default::default(),
        };
        let mut inputs = vec![io::NamedPath::new("LAYOUT", &self.layout)];
        inputs.extend(
            self.scene
                .as_deref()
                .map(|p| io::NamedPath::new("--scene", p)),
        );
        inputs.extend(meshes.values().map(|m| io::NamedPath::new("mesh", m)));
        io::refuse_clobbering(&inputs, &[io::NamedPath::new("-o", &self.output)], &[])?;
        let options = ExportOptions {
            wall_height_cm: self.wall_height,
            ..ExportOptions::default()
        };
        let glb = export::export_glb(&layout, &meshes, &options)?;
        super::create_parents([self.output.as_path()])?;
        io::write_atomic(&self.output, &glb)?;
        if self.json {
            print_json(&Summary {
                output: &self.output,
                objects: layout.objects.len(),
                meshes: meshes.len(),
                wall_height_cm: self.wall_height,
                bytes: glb.len(),
            })?;
        } else if !quiet {
            outln!(
                "{}: {}, {} cm walls",
                self.output.display(),
                super::count(layout.objects.len(), "object"),
                self.wall_height
            );
        }
        Ok(())
    }
}
