//! `disco refine`: make any layout physically valid with the Physical Refinement Tool.

use std::path::{Path, PathBuf};

use anyhow::Result;
use disco_layout::layout::{DraftLayout, PrtStats};
use disco_layout::render::{RenderOptions, render_png};
use disco_layout::{Dropped, Layout, PrtConfig, SceneSpec, io, refine};
use serde::Serialize;

use super::print_json;

/// The arguments of `disco refine`.
#[derive(clap::Args)]
pub struct Refine {
    /// The scene spec the layout belongs to.
    scene: PathBuf,
    /// The layout to refine (objects need only name, position and rotation).
    layout: PathBuf,
    /// Where to write the refined layout.
    #[arg(short, long)]
    output: PathBuf,
    /// Grid step of the search, in cm.
    #[arg(long, default_value_t = 5.0, value_parser = super::grid_step_cm)]
    grid_step: f64,
    /// Also draw the refined layout to this PNG.
    #[arg(long)]
    render: Option<PathBuf>,
    /// Print the summary as JSON.
    #[arg(long)]
    json: bool,
}

/// The summary printed with `--json`.
#[derive(Serialize)]
struct Summary<'a> {
    /// Where the refined layout went.
    output: &'a Path,
    /// Objects in the refined layout.
    placed: usize,
    /// What the PRT moved, and by how much.
    prt: PrtStats,
    /// What it could not place, and why.
    dropped: &'a [Dropped],
}

impl Refine {
    /// Resolves the draft against the scene, refines it, writes it (and its picture) and
    /// prints a summary.
    pub fn run(self, quiet: bool) -> Result<()> {
        let spec = SceneSpec::load(&self.scene)?;
        let mut outputs = vec![io::NamedPath::new("-o", &self.output)];
        outputs.extend(
            self.render
                .as_deref()
                .map(|p| io::NamedPath::new("--render", p)),
        );
        io::refuse_clobbering(
            &[
                io::NamedPath::new("SCENE", &self.scene),
                io::NamedPath::new("LAYOUT", &self.layout),
            ],
            &outputs,
            &[],
        )?;
        let (draft, missing) = DraftLayout::load(&self.layout)?.resolve(&self.layout, &spec)?;
        let config = PrtConfig {
            grid_step_cm: self.grid_step,
            ..PrtConfig::default()
        };
        let refined = refine::refine_layout(&spec, draft, &missing, config);
        super::create_parents(
            [&self.output]
                .into_iter()
                .chain(&self.render)
                .map(PathBuf::as_path),
        )?;
        io::write_json(&self.output, &refined)?;
        if let Some(png) = &self.render {
            io::write_atomic(png, &render_png(&refined, &RenderOptions::default())?)?;
        }
        let prt = refined.stats.prt.clone().unwrap_or_default();
        if self.json {
            print_json(&Summary {
                output: &self.output,
                placed: refined.objects.len(),
                prt,
                dropped: &refined.dropped,
            })?;
        } else if !quiet {
            self.print(&refined, &prt);
        }
        Ok(())
    }

    /// One line of figures, then the PRT's notes and the drops.
    fn print(&self, refined: &Layout, prt: &PrtStats) {
        outln!(
            "{}: {} placed ({} moved, mean {:.1} cm, max {:.1} cm), {} dropped",
            self.output.display(),
            refined.objects.len(),
            prt.moved,
            prt.mean_displacement_cm,
            prt.max_displacement_cm,
            refined.dropped.len()
        );
        for note in &prt.notes {
            outln!("  note: {note}");
        }
        for d in &refined.dropped {
            outln!("  dropped {}: {}", d.name, d.reason);
        }
    }
}
