//! `disco`: the command-line face of disco-layout. It parses arguments and calls the library.

use std::path::PathBuf;
use std::process::ExitCode;

use anyhow::{Context, Result};
use clap::{Parser, Subcommand};
use disco_layout::layout::DraftLayout;
use disco_layout::render::{RenderOptions, render_png};
use disco_layout::{Layout, PrtConfig, SceneSpec, io, metrics, refine};

/// Furnished rooms from a sentence and an asset list (DisCo-Layout).
///
/// Exit codes: 0 success; 1 the input was refused or a file could not be read or written;
/// 2 the command line itself was wrong.
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

#[derive(Subcommand)]
enum Command {
    /// Check a scene spec; exit 0 if it is valid, else print what is wrong and exit 1.
    Validate {
        /// The scene spec (JSON).
        scene: PathBuf,
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
            ExitCode::from(1)
        }
    }
}

fn run(cli: Cli) -> Result<()> {
    let quiet = cli.quiet;
    match cli.command {
        Command::Validate { scene } => {
            let spec = SceneSpec::load(&scene)?;
            for w in spec.warnings() {
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
            if !quiet {
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
