//! `disco`: the command-line face of disco-layout. It parses arguments and calls the library.

use std::path::PathBuf;
use std::process::ExitCode;

use anyhow::{Context, Result};
use clap::{Parser, Subcommand};
use disco_layout::layout::DraftLayout;
use disco_layout::render::{RenderOptions, render_png};
use std::sync::Arc;

use disco_layout::bench::perf::{self, PerfOptions};
use disco_layout::bench::suite::{Suite, run_suite};
use disco_layout::bench::{self, BenchOptions};
use disco_layout::config::GraphConfig;
use disco_layout::export::{self, ExportOptions};
use disco_layout::registry::Registry;
use disco_layout::report;
use disco_layout::runtime::batch::{self, BatchOptions, Outcome};
use disco_layout::trace::Trace;
use disco_layout::{Layout, PrtConfig, Runtime, SceneSpec, io, metrics, refine};

/// Furnished rooms from a sentence and an asset list (DisCo-Layout).
///
/// Exit codes: 0 success; 1 the input was refused or a file could not be read or written;
/// 2 the command line itself was wrong; 3 a model server could not be used (unreachable, refused
/// the key, or its answers were unusable); 4 some scenes of a batch or benchmark failed (the others
/// were written).
#[derive(Parser)]
#[command(name = "disco", version, about, long_about = None)]
struct Cli {
    /// More log output (-v info, -vv debug).
    #[arg(short, long, action = clap::ArgAction::Count, global = true)]
    verbose: u8,
    /// Only errors.
    #[arg(short, long, global = true)]
    quiet: bool,
    #[command(subcommand)]
    command: Command,
}

/// Which agent graph to run.
#[derive(clap::Args)]
struct GraphArgs {
    /// The agent graph (TOML); the built-in offline default when absent.
    #[arg(long)]
    config: Option<PathBuf>,
    /// Override one value of the graph, e.g. `--set agents.designer.impl=noisy` (repeatable).
    #[arg(long = "set", value_name = "KEY=VALUE")]
    sets: Vec<String>,
    /// Record every model answer in this folder, and replay recorded ones instead of asking
    /// again: a run can be reproduced, and re-run without the server.
    #[arg(long)]
    cache: Option<PathBuf>,
}

impl GraphArgs {
    fn graph(&self) -> Result<GraphConfig> {
        let mut graph = GraphConfig::load(self.config.as_deref(), &self.sets)?;
        if let Some(dir) = &self.cache {
            graph.run.cache = Some(dir.to_string_lossy().into_owned());
        }
        Ok(graph)
    }

    /// The runtime, after checking that its model servers answer.
    fn runtime(&self, rt: &tokio::runtime::Runtime) -> Result<Runtime> {
        let runtime = Runtime::new(self.graph()?, Registry::builtin())?;
        rt.block_on(runtime.preflight())?;
        Ok(runtime)
    }
}

/// Progress bars only for a person watching: not with `-q`, not when stderr is not a terminal.
fn progress_wanted(quiet: bool) -> bool {
    use std::io::IsTerminal;
    !quiet && std::io::stderr().is_terminal()
}

fn tokio_runtime() -> Result<tokio::runtime::Runtime> {
    tokio::runtime::Builder::new_multi_thread()
        .enable_all()
        .build()
        .context("cannot start the async runtime")
}

#[derive(Subcommand)]
enum Command {
    /// Furnish a room: plan, design group by group, evaluate and refine.
    Generate {
        /// The scene spec (JSON).
        scene: PathBuf,
        /// Where to write the layout.
        #[arg(short, long)]
        output: PathBuf,
        #[command(flatten)]
        graph: GraphArgs,
        /// Write top-down PNGs into this folder: the result (`<id>.png`), every step
        /// (`<id>/NN-group-K-stage.png`) and a contact sheet of the sequence (`<id>-steps.png`).
        #[arg(long)]
        renders: Option<PathBuf>,
        /// Also write the room as a binary glTF (floor, walls, every object).
        #[arg(long)]
        glb: Option<PathBuf>,
        /// Wall height in the glTF, in cm (0 for no walls).
        #[arg(long, default_value_t = 250.0)]
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
    },
    /// Furnish many rooms at once; finished scenes are skipped on a rerun.
    Batch {
        /// Scene files, or folders of them.
        #[arg(required = true)]
        scenes: Vec<PathBuf>,
        /// Output folder (`<id>.json` per scene).
        #[arg(long)]
        out: PathBuf,
        /// Scenes in flight at once.
        #[arg(long, default_value_t = 4)]
        jobs: usize,
        #[command(flatten)]
        graph: GraphArgs,
        /// Write every message of every scene as JSON lines.
        #[arg(long)]
        trace: Option<PathBuf>,
        /// Print the reports as JSON instead of a table.
        #[arg(long)]
        json: bool,
    },
    /// Benchmark a method over scene folders: a table per room category (Col, OOB, constraints,
    /// reach, dropped, calls, tokens, time), as Markdown and JSON; or, with `--suite`, several
    /// methods into the comparison tables of `RESULTS.md`.
    Bench {
        /// Scene files or folders (repeatable).
        #[arg(long = "scenes", required_unless_present = "suite")]
        scenes: Vec<PathBuf>,
        /// A suite file (methods and tables, see bench/suite.toml) instead of one method.
        #[arg(long, conflicts_with_all = ["scenes", "judge", "config", "sets"])]
        suite: Option<PathBuf>,
        #[command(flatten)]
        graph: GraphArgs,
        /// Output folder: layouts, per-scene results, tables.
        #[arg(long)]
        out: PathBuf,
        /// Scenes in flight at once (a suite's own `jobs` otherwise).
        #[arg(long)]
        jobs: Option<usize>,
        /// Also score every layout with this graph's VLM judge.
        #[arg(long)]
        judge: Option<PathBuf>,
        /// Regenerate every scene instead of reusing layouts already in the output folder.
        #[arg(long)]
        fresh: bool,
        /// Write one self-contained HTML report over all scenes (table, renders, metrics, drops).
        #[arg(long, conflicts_with = "suite")]
        report: Option<PathBuf>,
        /// Print the tables as JSON instead of Markdown.
        #[arg(long)]
        json: bool,
    },
    /// Re-measure the speed figures: PRT, renderer, runtime overhead, batch throughput.
    Perf {
        /// Scenes in the throughput run.
        #[arg(long, default_value_t = 300)]
        scenes: usize,
        /// Print JSON instead of a Markdown table.
        #[arg(long)]
        json: bool,
    },
    /// Check a scene spec; exit 0 if it is valid, else print what is wrong and exit 1.
    Validate {
        /// The scene spec (JSON).
        scene: PathBuf,
        /// Print the verdict as JSON.
        #[arg(long)]
        json: bool,
    },
    /// Make any layout physically valid with the Physical Refinement Tool.
    Refine {
        /// The scene spec the layout belongs to.
        scene: PathBuf,
        /// The layout to refine (objects need only name, position and rotation).
        layout: PathBuf,
        /// Where to write the refined layout.
        #[arg(short, long)]
        output: PathBuf,
        /// Grid step of the search, in cm.
        #[arg(long, default_value_t = 5.0)]
        grid_step: f64,
        /// Also draw the refined layout to this PNG.
        #[arg(long)]
        render: Option<PathBuf>,
        /// Print the summary as JSON.
        #[arg(long)]
        json: bool,
    },
    /// Write a layout as a binary glTF (.glb) for Blender, three.js or a game engine.
    Export {
        /// The layout (JSON).
        layout: PathBuf,
        /// Where to write the .glb.
        #[arg(short, long)]
        output: PathBuf,
        /// The scene spec, to use its assets' `mesh` files instead of boxes.
        #[arg(long)]
        scene: Option<PathBuf>,
        /// Wall height, in cm (0 for no walls).
        #[arg(long, default_value_t = 250.0)]
        wall_height: f64,
        /// Print the summary as JSON.
        #[arg(long)]
        json: bool,
    },
    /// Draw a layout from above as a PNG.
    Render {
        /// The layout (JSON).
        layout: PathBuf,
        /// Where to write the PNG.
        #[arg(short, long)]
        output: PathBuf,
        /// Pixels on the long side.
        #[arg(long, default_value_t = 1024)]
        size: u32,
    },
    /// Score a layout's positional and rotational coherency (0-100) with a model looking at its
    /// render, as in the paper's evaluation protocol. The model is `[agents.judge]`'s, else the
    /// designer's, of the graph.
    Judge {
        /// The scene spec.
        scene: PathBuf,
        /// The layout (JSON).
        layout: PathBuf,
        #[command(flatten)]
        graph: GraphArgs,
        /// Print JSON instead of text.
        #[arg(long)]
        json: bool,
    },
    /// Measure a layout: collisions, out of bounds, constraints, reach, dropped.
    Metrics {
        /// The scene spec.
        scene: PathBuf,
        /// The layout (JSON).
        layout: PathBuf,
        /// Print JSON instead of text.
        #[arg(long)]
        json: bool,
    },
}

fn main() -> ExitCode {
    let cli = Cli::parse();
    let level = match (cli.quiet, cli.verbose) {
        (true, _) => "error",
        (false, 0) => "warn",
        (false, 1) => "info",
        _ => "debug",
    };
    tracing_subscriber::fmt()
        .with_env_filter(
            tracing_subscriber::EnvFilter::try_from_default_env()
                .unwrap_or_else(|_| tracing_subscriber::EnvFilter::new(level)),
        )
        .with_writer(std::io::stderr)
        .init();
    match run(cli) {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("error: {e:#}");
            ExitCode::from(exit_code(&e))
        }
    }
}

/// Some scenes of a batch or benchmark failed; the rest were written.
#[derive(Debug, thiserror::Error)]
#[error("{failed} of {total} scenes failed")]
struct ScenesFailed {
    failed: usize,
    total: usize,
}

/// The documented exit code for an error (see `Cli`).
fn exit_code(e: &anyhow::Error) -> u8 {
    if e.downcast_ref::<ScenesFailed>().is_some() {
        4
    } else if matches!(
        e.downcast_ref::<disco_layout::Error>(),
        Some(disco_layout::Error::Model { .. })
    ) {
        3
    } else {
        1
    }
}

fn run(cli: Cli) -> Result<()> {
    let quiet = cli.quiet;
    match cli.command {
        Command::Generate {
            scene,
            output,
            graph,
            renders,
            glb,
            wall_height,
            trace,
            report,
            json,
        } => {
            let spec = SceneSpec::load(&scene)?;
            let meshes = export::meshes_of(&spec, Some(&scene));
            for w in spec.warnings() {
                eprintln!("warning: {}: {}: {}", scene.display(), w.field, w.message);
            }
            let rt = tokio_runtime()?;
            let runtime = graph.runtime(&rt)?;
            let events = Arc::new(if renders.is_some() || report.is_some() {
                Trace::with_snapshots()
            } else {
                Trace::default()
            });
            let result = rt.block_on(runtime.generate(spec.clone(), Arc::clone(&events)));
            if let Some(path) = &trace {
                events.write_jsonl(path)?;
            }
            let layout = result?;
            io::write_json(&output, &layout)?;
            if let Some(dir) = renders {
                std::fs::create_dir_all(&dir)
                    .with_context(|| format!("{}: cannot create the folder", dir.display()))?;
                let png = dir.join(format!("{}.png", batch::file_safe(&layout.id)));
                io::write_atomic(&png, &render_png(&layout, &RenderOptions::default())?)?;
                report::write_step_renders(&report::steps(&events.events(), &layout), &dir)?;
            }
            if let Some(path) = &report {
                let html = report::html::scene_report(&spec, &layout, &events.events())?;
                io::write_atomic(path, html.as_bytes())?;
            }
            if let Some(path) = &glb {
                let options = ExportOptions {
                    wall_height_cm: wall_height,
                    ..ExportOptions::default()
                };
                io::write_atomic(path, &export::export_glb(&layout, &meshes, &options)?)?;
            }
            let m = metrics::measure(&layout);
            if json {
                println!("{}", serde_json::to_string_pretty(&m)?);
            } else if !quiet {
                println!(
                    "{}: {} in {} ms",
                    output.display(),
                    layout.id,
                    layout.stats.wall_ms
                );
                print!("{m}");
                for note in layout.stats.fallbacks.iter().chain(&layout.stats.notes) {
                    println!("note: {note}");
                }
            }
        }
        Command::Batch {
            scenes,
            out,
            jobs,
            graph,
            trace,
            json,
        } => {
            let rt = tokio_runtime()?;
            let runtime = graph.runtime(&rt)?;
            let inputs = batch::collect_scenes(&scenes)?;
            std::fs::create_dir_all(&out)
                .with_context(|| format!("{}: cannot create the folder", out.display()))?;
            let events = Arc::new(Trace::default());
            let options = BatchOptions {
                jobs,
                out_dir: out,
                progress: progress_wanted(quiet),
            };
            let reports = rt.block_on(batch::run_batch(
                &runtime,
                &inputs,
                &options,
                Arc::clone(&events),
            ));
            if let Some(path) = &trace {
                events.write_jsonl(path)?;
            }
            if json {
                println!("{}", serde_json::to_string_pretty(&reports)?);
            } else if !quiet {
                print!("{}", batch::summary_table(&reports));
            }
            let failed = reports
                .iter()
                .filter(|r| matches!(r.outcome, Outcome::Failed { .. }))
                .count();
            if failed > 0 {
                return Err(ScenesFailed {
                    failed,
                    total: reports.len(),
                }
                .into());
            }
        }
        Command::Bench {
            scenes,
            suite,
            graph,
            out,
            jobs,
            judge,
            fresh,
            report,
            json,
        } => {
            let rt = tokio_runtime()?;
            let mut options = BenchOptions {
                jobs: jobs.unwrap_or(2),
                progress: progress_wanted(quiet),
                fresh,
            };
            if let Some(path) = suite {
                let suite = Suite::load(&path)?;
                options.jobs = jobs.unwrap_or(suite.jobs);
                let report = rt.block_on(run_suite(
                    &suite,
                    &path,
                    &out,
                    &Registry::builtin(),
                    &options,
                ))?;
                if json {
                    println!("{}", serde_json::to_string_pretty(&report)?);
                } else if !quiet {
                    println!("{}", std::fs::read_to_string(out.join("RESULTS.md"))?);
                }
                return Ok(());
            }
            let runtime = graph.runtime(&rt)?;
            let judge = judge
                .map(|p| GraphConfig::load(Some(&p), &[]))
                .transpose()?;
            let inputs = batch::collect_scenes(&scenes)?;
            let run = rt.block_on(bench::run_scenes(
                &runtime,
                &inputs,
                &out,
                &options,
                judge.as_ref(),
                Arc::new(Trace::default()),
            ))?;
            if let Some(path) = &report {
                let html = report::html::bench_report(
                    &format!("Benchmark: {}", out.display()),
                    &run.table,
                    &bench::load_outputs(&inputs, &out, &run.results),
                )?;
                io::write_atomic(path, html.as_bytes())?;
            }
            if json {
                println!("{}", serde_json::to_string_pretty(&run)?);
            } else if !quiet {
                print!("{}", run.table.to_markdown());
            }
            let failed = run.results.iter().filter(|r| r.failure.is_some()).count();
            if failed > 0 {
                return Err(ScenesFailed {
                    failed,
                    total: run.results.len(),
                }
                .into());
            }
        }
        Command::Perf { scenes, json } => {
            let rt = tokio_runtime()?;
            let options = PerfOptions {
                throughput_scenes: scenes,
                ..PerfOptions::default()
            };
            let report = rt.block_on(perf::measure(&options))?;
            if json {
                println!("{}", serde_json::to_string_pretty(&report)?);
            } else {
                print!("{}", report.to_markdown());
            }
        }
        Command::Validate { scene, json } => {
            let spec = SceneSpec::load(&scene)?;
            let warnings = spec.warnings();
            if json {
                let warnings: Vec<_> = warnings
                    .iter()
                    .map(|w| serde_json::json!({"field": w.field, "message": w.message}))
                    .collect();
                println!(
                    "{}",
                    serde_json::to_string_pretty(&serde_json::json!({
                        "valid": true,
                        "id": spec.id,
                        "assets": spec.assets.len(),
                        "room": spec.room,
                        "room_type": spec.room_type,
                        "warnings": warnings,
                    }))?
                );
                return Ok(());
            }
            for w in warnings {
                eprintln!("warning: {}: {}: {}", scene.display(), w.field, w.message);
            }
            if !quiet {
                println!(
                    "{}: valid scene {:?}: {} assets in a {} x {} cm {}",
                    scene.display(),
                    spec.id,
                    spec.assets.len(),
                    spec.room.width,
                    spec.room.depth,
                    spec.room_type
                );
            }
        }
        Command::Refine {
            scene,
            layout,
            output,
            grid_step,
            render,
            json,
        } => {
            let spec = SceneSpec::load(&scene)?;
            let (draft, missing) = DraftLayout::load(&layout)?.resolve(&layout, &spec)?;
            let config = PrtConfig {
                grid_step_cm: grid_step,
                ..PrtConfig::default()
            };
            let refined = refine::refine_layout(&spec, draft, &missing, config);
            io::write_json(&output, &refined)?;
            if let Some(png) = render {
                io::write_atomic(&png, &render_png(&refined, &RenderOptions::default())?)?;
            }
            if json {
                let prt = refined.stats.prt.clone().unwrap_or_default();
                println!(
                    "{}",
                    serde_json::to_string_pretty(&serde_json::json!({
                        "output": output,
                        "placed": refined.objects.len(),
                        "prt": prt,
                        "dropped": refined.dropped,
                    }))?
                );
            } else if !quiet {
                let prt = refined.stats.prt.clone().unwrap_or_default();
                println!(
                    "{}: {} placed ({} moved, mean {:.1} cm, max {:.1} cm), {} dropped",
                    output.display(),
                    refined.objects.len(),
                    prt.moved,
                    prt.mean_displacement_cm,
                    prt.max_displacement_cm,
                    refined.dropped.len()
                );
                for note in &prt.notes {
                    println!("  note: {note}");
                }
                for d in &refined.dropped {
                    println!("  dropped {}: {}", d.name, d.reason);
                }
            }
        }
        Command::Export {
            layout,
            output,
            scene,
            wall_height,
            json,
        } => {
            let l = Layout::load(&layout)?;
            let meshes = match &scene {
                Some(path) => {
                    let spec = SceneSpec::load(path)?;
                    check_belongs(&spec, &l, &layout)?;
                    export::meshes_of(&spec, Some(path))
                }
                None => Default::default(),
            };
            let options = ExportOptions {
                wall_height_cm: wall_height,
                ..ExportOptions::default()
            };
            let glb = export::export_glb(&l, &meshes, &options)?;
            io::write_atomic(&output, &glb)?;
            if json {
                println!(
                    "{}",
                    serde_json::to_string_pretty(&serde_json::json!({
                        "output": output,
                        "objects": l.objects.len(),
                        "meshes": meshes.len(),
                        "wall_height_cm": wall_height,
                        "bytes": glb.len(),
                    }))?
                );
            } else if !quiet {
                println!(
                    "{}: {} objects, {} cm walls",
                    output.display(),
                    l.objects.len(),
                    wall_height
                );
            }
        }
        Command::Render {
            layout,
            output,
            size,
        } => {
            let l = Layout::load(&layout)?;
            let png = render_png(
                &l,
                &RenderOptions {
                    long_side_px: size,
                    ..RenderOptions::default()
                },
            )?;
            io::write_atomic(&output, &png)?;
        }
        Command::Judge {
            scene,
            layout,
            graph,
            json,
        } => {
            let spec = SceneSpec::load(&scene)?;
            let l = Layout::load(&layout)?;
            check_belongs(&spec, &l, &layout)?;
            let graph = graph.graph()?;
            let rt = tokio_runtime()?;
            let scores = rt.block_on(disco_layout::judge::judge_layout(&graph, &spec, &l))?;
            if json {
                println!("{}", serde_json::to_string_pretty(&scores)?);
            } else {
                println!(
                    "positional {:.0}/100, rotational {:.0}/100 ({} model calls, {} tokens)",
                    scores.positional,
                    scores.rotational,
                    scores.usage.calls,
                    scores.usage.prompt_tokens + scores.usage.completion_tokens
                );
                if !scores.comment.is_empty() {
                    println!("{}", scores.comment);
                }
            }
        }
        Command::Metrics {
            scene,
            layout,
            json,
        } => {
            let spec = SceneSpec::load(&scene)?;
            let l = Layout::load(&layout)?;
            check_belongs(&spec, &l, &layout)?;
            let m = metrics::measure(&l);
            if json {
                println!("{}", serde_json::to_string_pretty(&m)?);
            } else {
                print!("{m}");
            }
        }
    }
    Ok(())
}

/// Refuses a layout whose objects are not the scene's assets: metrics over the wrong pair mislead.
fn check_belongs(spec: &SceneSpec, layout: &Layout, path: &std::path::Path) -> Result<()> {
    for name in layout
        .objects
        .iter()
        .map(|o| &o.name)
        .chain(layout.dropped.iter().map(|d| &d.name))
    {
        spec.asset(name).with_context(|| {
            format!(
                "{}: object {name:?} is not an asset of scene {:?}",
                path.display(),
                spec.id
            )
        })?;
    }
    let listed = layout.objects.len() + layout.dropped.len();
    if listed != spec.assets.len() {
        eprintln!(
            "warning: {}: lists {listed} of the scene's {} assets; the missing ones count as neither placed nor dropped",
            path.display(),
            spec.assets.len()
        );
    }
    Ok(())
}
