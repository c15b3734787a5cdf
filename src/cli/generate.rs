//! `disco generate`: furnish one room and write what the flags ask for.

use std::path::PathBuf;
use std::sync::Arc;

use anyhow::Result;
use disco_layout::export::{self, ExportOptions};
use disco_layout::outputs::{self, OutputOptions};
use disco_layout::{Layout, SceneSpec, io};

use super::progress::SceneProgress;
use super::{GraphArgs, tokio_runtime, warn_about};

/// The arguments of `disco generate`.
#[derive(clap::Args)]
pub struct Generate {
    /// The scene spec (JSON).
    scene: PathBuf,
    /// Where to write the layout.
    #[arg(short, long)]
    output: PathBuf,
    #[command(flatten)]
    graph: GraphArgs,
    /// Write top-down PNGs into this folder: the result (`<id>.png`), every step
    /// (`<id>/NN-groupK-STAGE.png`) and a contact sheet of the sequence (`<id>-steps.png`).
    #[arg(long)]
    renders: Option<PathBuf>,
    /// Also write the room as a binary glTF (floor, walls, every object).
    #[arg(long)]
    glb: Option<PathBuf>,
    /// Wall height in the glTF, in cm (0 for no walls).
    #[arg(long, default_value_t = 250.0, value_parser = super::wall_height_cm)]
    wall_height: f64,
    /// Write every message between supervisor and roles as JSON lines.
    #[arg(long)]
    trace: Option<PathBuf>,
    /// Write a self-contained HTML report of the run: renders, metrics, plan, each group's
    /// steps, the evaluator's questions and answers, model calls, drops.
    #[arg(long)]
    report: Option<PathBuf>,
    /// Print the metrics as JSON instead of text.
    #[arg(long)]
    json: bool,
}

impl Generate {
    /// Loads the scene, runs the graph on it (with a live progress line on a terminal, unless
    /// `quiet` or `verbose` logs take its place), writes the outputs and prints the metrics.
    pub fn run(self, quiet: bool, verbose: u8) -> Result<()> {
        let spec = SceneSpec::load(&self.scene)?;
        warn_about(&spec, &self.scene);
        let options = self.output_options(&spec);
        let mut inputs = vec![io::NamedPath::new("SCENE", &self.scene)];
        inputs.extend(
            self.graph
                .config_file()
                .map(|c| io::NamedPath::new("--config", c)),
        );
        options.refuse_clobbering(&spec.id, &inputs)?;
        let rt = tokio_runtime()?;
        let runtime = self.graph.runtime(&rt)?;
        let files = [&self.output]
            .into_iter()
            .chain(&self.glb)
            .chain(&self.report);
        super::create_parents(files.chain(&self.trace).map(PathBuf::as_path))?;
        let shown = super::progress_wanted(quiet) && verbose == 0;
        let progress = Arc::new(SceneProgress::new(&spec.id, shown));
        let mut trace = options.new_trace();
        let listener = Arc::clone(&progress);
        trace.set_listener(move |e| listener.observe(e));
        let events = Arc::new(trace);
        let result = rt.block_on(runtime.generate(spec.clone(), Arc::clone(&events)));
        progress.finish();
        let layout = match result {
            Ok(layout) => layout,
            Err(e) => {
                outputs::write_trace(&events, &options)?;
                return Err(e.into());
            }
        };
        outputs::write_outputs(&spec, &layout, &events, &options)?;
        self.print(&spec, &layout, quiet)?;
        super::Degraded::check(&self.output, &layout)
    }

    /// The files to write, from the flags; meshes come from the scene's assets.
    fn output_options(&self, spec: &SceneSpec) -> OutputOptions {
        OutputOptions {
            layout: Some(self.output.clone()),
            trace: self.trace.clone(),
            renders: self.renders.clone(),
            report: self.report.clone(),
            glb: self.glb.clone(),
            export: ExportOptions {
                wall_height_cm: self.wall_height,
                ..ExportOptions::default()
            },
            meshes: export::meshes_of(spec, Some(&self.scene)),
        }
    }

    /// The metrics as JSON, or a summary with any fallbacks and notes of the run.
    fn print(&self, spec: &SceneSpec, layout: &Layout, quiet: bool) -> Result<()> {
        if self.json {
            super::print_measured(spec, layout, true)?;
        } else if !quiet {
            outln!(
                "{}: {} in {} ms",
                self.output.display(),
                layout.id,
                layout.stats.wall_ms
            );
            super::print_measured(spec, layout, false)?;
            for note in layout.stats.fallbacks.iter().chain(&layout.stats.notes) {
                outln!("note: {note}");
            }
        }
        Ok(())
    }
}
