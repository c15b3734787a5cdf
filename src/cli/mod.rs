//! The `disco` command line: the argument types, one module per subcommand, and the mapping from
//! errors to the documented exit codes. Each subcommand's module holds its arguments and a `run`
//! that calls the library and prints the result. Output on stdout goes through [`out`]'s
//! macros, never `println!`, and messages on stderr through `errln!`, never `eprintln!`: a closed
//! pipe must end them quietly, not panic.
#![deny(clippy::print_stdout, clippy::print_stderr)]

#[macro_use]
mod out;

mod batch;
mod bench;
mod bench_merge;
mod config;
mod export;
mod generate;
mod judge;
mod metrics;
mod perf;
mod progress;
mod refine;
mod render;
mod validate;

use std::path::{Path, PathBuf};

use anyhow::{Context, Result};
use clap::{Parser, Subcommand};
use disco_layout::config::GraphConfig;
use disco_layout::registry::Registry;
use disco_layout::{Layout, Runtime, SceneSpec};
use serde::Serialize;

/// Furnished rooms from a sentence and an asset list (DisCo-Layout).
///
/// Exit codes: 0 success; 1 the input was refused or a file could not be read or written;
/// 2 the command line itself was wrong; 3 a model server could not be used (unreachable, refused
/// the key, or its answers were unusable; when fallbacks finished the scene, its layout is still
/// written); 4 some scenes of a batch or benchmark failed (the others were written); 5 the scene
/// missed its deadline (its layout, finished by fallbacks, is written).
#[derive(Parser)]
#[command(name = "disco", version, about, long_about = None)]
pub struct Cli {
    /// More log output (-v info, -vv debug).
    #[arg(short, long, action = clap::ArgAction::Count, global = true)]
    pub verbose: u8,
    /// Only errors.
    #[arg(short, long, global = true)]
    pub quiet: bool,
    #[command(subcommand)]
    command: Command,
}

/// The subcommands; each variant's arguments live in the subcommand's own module.
#[derive(Subcommand)]
enum Command {
    /// Furnish a room: plan, design group by group, evaluate and refine.
    Generate(generate::Generate),
    /// Furnish many rooms at once; finished scenes are skipped on a rerun.
    Batch(batch::Batch),
    /// Benchmark a method over scene folders: a table per room category (Col, OOB, constraints,
    /// reach, dropped, calls, tokens, time), as Markdown and JSON; or, with `--suite`, several
    /// methods into the comparison tables of `RESULTS.md`.
    Bench(bench::Bench),
    /// Re-measure the speed figures: PRT, renderer, runtime overhead, batch throughput.
    Perf(perf::Perf),
    /// Check a scene spec; exit 0 if it is valid, else print what is wrong and exit 1.
    Validate(validate::Validate),
    /// Make any layout physically valid with the Physical Refinement Tool.
    Refine(refine::Refine),
    /// Write a layout as a binary glTF (.glb) for Blender, three.js or a game engine.
    Export(export::Export),
    /// Draw a layout from above as a PNG, or with `--walls` every wall unrolled with what stands
    /// against it and hangs on it, at their heights.
    Render(render::Render),
    /// Score a layout's positional and rotational coherency (0-100) with a model looking at its
    /// render, as in the paper's evaluation protocol. The model is `[judge]`'s, else the
    /// designer's, of the graph.
    Judge(judge::Judge),
    /// Measure a layout: collisions, out of bounds, constraints, reach, dropped.
    Metrics(metrics::Metrics),
    /// The agent graphs built into the binary: `list` them, `show NAME` to print one
    /// (`disco config show local-llm > my.toml`). `--config NAME` runs one by name.
    Config(config::Config),
}

impl Cli {
    /// Runs the chosen subcommand. `-q` silences the human-readable summaries, not `--json`.
    pub fn run(self) -> Result<()> {
        let quiet = self.quiet;
        match self.command {
            Command::Generate(c) => c.run(quiet, self.verbose),
            Command::Batch(c) => c.run(quiet),
            Command::Bench(c) => c.run(quiet),
            Command::Perf(c) => c.run(),
            Command::Validate(c) => c.run(quiet),
            Command::Refine(c) => c.run(quiet),
            Command::Export(c) => c.run(quiet),
            Command::Render(c) => c.run(quiet),
            Command::Judge(c) => c.run(),
            Command::Metrics(c) => c.run(),
            Command::Config(c) => c.run(),
        }
    }
}

/// Some scenes of a batch or benchmark failed; the rest were written.
#[derive(Debug, thiserror::Error)]
#[error("{failed} of {} failed", count(*total, "scene"))]
struct ScenesFailed {
    failed: usize,
    total: usize,
}

impl ScenesFailed {
    /// `Ok` when no scene failed, else the error that exits with code 4.
    fn check(failed: usize, total: usize) -> Result<()> {
        if failed > 0 {
            return Err(ScenesFailed { failed, total }.into());
        }
        Ok(())
    }
}

/// The layout was written, but not all of it was made the way the graph asked.
#[derive(Debug, thiserror::Error)]
enum Degraded {
    /// A model server failed and fallbacks made part of the layout (exit 3).
    #[error("{0}: written, but a model server failed and fallbacks made part of it: {1}")]
    ModelServer(PathBuf, String),
    /// The scene missed its deadline and fallbacks finished it (exit 5).
    #[error("{0}: written, but the scene missed its deadline and fallbacks finished it")]
    Deadline(PathBuf),
}

impl Degraded {
    /// `Ok` when `layout` (written to `path`) was made as the graph asked.
    fn check(path: &std::path::Path, layout: &disco_layout::Layout) -> Result<()> {
        if let Some(first) = layout.stats.model_failures.first() {
            return Err(Degraded::ModelServer(path.to_path_buf(), first.clone()).into());
        }
        if layout.stats.deadline_missed {
            return Err(Degraded::Deadline(path.to_path_buf()).into());
        }
        Ok(())
    }
}

/// A number within `min..=max` for a flag (an out-of-range value is a usage error, exit 2).
fn number_in(text: &str, min: f64, max: f64, unit: &str) -> std::result::Result<f64, String> {
    let v: f64 = text
        .trim()
        .parse()
        .map_err(|_| format!("{text:?} is not a number"))?;
    if !(v.is_finite() && (min..=max).contains(&v)) {
        return Err(format!("must be between {min} and {max} {unit}"));
    }
    Ok(v)
}

/// `--grid-step`: the PRT's grid step, as the agent graph bounds it.
fn grid_step_cm(text: &str) -> std::result::Result<f64, String> {
    number_in(text, 0.5, 100.0, "cm")
}

/// `--wall-height`: 0 (no walls) to 100 m.
fn wall_height_cm(text: &str) -> std::result::Result<f64, String> {
    number_in(text, 0.0, 10_000.0, "cm")
}

/// An error and its causes on one line, each cause once: the library's messages already end
/// with the operating system's words, so they are not repeated.
pub fn error_text(e: &anyhow::Error) -> String {
    let mut text = String::new();
    for cause in e.chain() {
        let part = cause.to_string();
        if text.contains(&part) {
            continue;
        }
        if !text.is_empty() {
            text.push_str(": ");
        }
        text.push_str(&part);
    }
    text
}

/// The documented exit code for an error (see [`Cli`]).
pub fn exit_code(e: &anyhow::Error) -> u8 {
    if e.downcast_ref::<ScenesFailed>().is_some() {
        4
    } else if let Some(d) = e.downcast_ref::<Degraded>() {
        match d {
            Degraded::ModelServer(..) => 3,
            Degraded::Deadline(_) => 5,
        }
    } else if matches!(
        e.downcast_ref::<disco_layout::Error>(),
        Some(disco_layout::Error::Model { .. })
    ) {
        3
    } else {
        1
    }
}

/// Which agent graph to run.
#[derive(clap::Args)]
struct GraphArgs {
    /// The agent graph: a TOML file, or the name of a built-in one (`disco config list`); the
    /// built-in offline default when absent.
    #[arg(long)]
    config: Option<PathBuf>,
    /// Override one value of the graph, e.g. `--set agents.designer.impl=noisy` (repeatable).
    #[arg(long = "set", value_name = "KEY=VALUE", value_parser = key_value)]
    sets: Vec<String>,
    /// Record every model answer in this folder, and replay recorded ones instead of asking
    /// again: a run can be reproduced, and re-run without the server.
    #[arg(long)]
    cache: Option<PathBuf>,
}

impl GraphArgs {
    /// The `--config` file, when it names a file (not a preset): an input of the command that
    /// no output may replace.
    fn config_file(&self) -> Option<&Path> {
        self.config.as_deref().filter(|p| p.is_file())
    }

    /// The graph file with the `--set` overrides and the `--cache` folder applied.
    fn graph(&self) -> Result<GraphConfig> {
        Ok(disco_layout::commands::load_graph(
            self.config.as_deref(),
            &self.sets,
            self.cache.as_deref(),
        )?)
    }

    /// The runtime, after checking that its model servers answer.
    fn runtime(&self, rt: &tokio::runtime::Runtime) -> Result<Runtime> {
        let graph = self.graph()?;
        self.warn_if_cache_unused(&graph);
        let runtime = Runtime::new(graph, Registry::builtin())?;
        rt.block_on(runtime.preflight())?;
        Ok(runtime)
    }

    /// `--cache` records model answers: with a graph whose agents call no model it does nothing,
    /// which the user should hear rather than find out later.
    fn warn_if_cache_unused(&self, graph: &GraphConfig) {
        if let Some(dir) = &self.cache
            && !graph.agents().values().any(|a| a.config().model.is_some())
        {
            errln!(
                "warning: --cache {}: no agent of this graph calls a model, so nothing is recorded or replayed",
                dir.display()
            );
        }
    }
}

/// `--set KEY=VALUE`: an argument without `=` is a usage error (exit 2), caught by the parser.
fn key_value(text: &str) -> std::result::Result<String, String> {
    match text.split_once('=') {
        Some((key, _)) if !key.trim().is_empty() => Ok(text.to_string()),
        _ => Err("expected KEY=VALUE, e.g. `--set run.max_rounds=2`".into()),
    }
}

/// Progress bars only for a person watching: not with `-q`, not when stderr is not a terminal.
fn progress_wanted(quiet: bool) -> bool {
    use std::io::IsTerminal;
    !quiet && std::io::stderr().is_terminal()
}

/// The multi-threaded async runtime the commands block on.
fn tokio_runtime() -> Result<tokio::runtime::Runtime> {
    tokio::runtime::Builder::new_multi_thread()
        .enable_all()
        .build()
        .context("cannot start the async runtime")
}

/// `1 scene`, `2 scenes`: a count with its noun (regular plurals only).
fn count(n: usize, noun: &str) -> String {
    match n {
        1 => format!("1 {noun}"),
        n => format!("{n} {noun}s"),
    }
}

/// Creates the folders the files of `paths` go into (as `--renders` creates its own), so that
/// `-o out/room.json` works in a fresh checkout.
fn create_parents<'a>(paths: impl IntoIterator<Item = &'a Path>) -> Result<()> {
    for path in paths {
        if let Some(dir) = path.parent().filter(|d| !d.as_os_str().is_empty()) {
            std::fs::create_dir_all(dir)
                .with_context(|| format!("{}: cannot create the folder", dir.display()))?;
        }
    }
    Ok(())
}

/// Prints `value` as pretty JSON on stdout: the `--json` output of every command.
fn print_json<T: Serialize + ?Sized>(value: &T) -> Result<()> {
    outln!("{}", serde_json::to_string_pretty(value)?);
    Ok(())
}

/// Prints a layout's metrics and the prompt's requests checked on it (the plan's constraint
/// score cannot see a request the planner dropped): as text, or as one JSON object with a
/// `prompt_requests` list beside the metrics.
fn print_measured(spec: &SceneSpec, layout: &Layout, json: bool) -> Result<()> {
    if json {
        return print_json(&disco_layout::commands::measured(spec, layout)?);
    }
    let m = disco_layout::metrics::measure(layout);
    let requests = disco_layout::agents::requests::check_requests(spec, layout);
    out!("{m}");
    if !requests.is_empty() {
        let met = requests.iter().filter(|r| r.met).count();
        outln!("prompt requests     {met} of {} met", requests.len());
        for r in requests.iter().filter(|r| !r.met) {
            outln!("missed request: {}", r.request);
        }
    }
    Ok(())
}

/// Prints the scene's warnings (assets too big for the room) on stderr, naming its file.
fn warn_about(spec: &SceneSpec, path: &Path) {
    for w in spec.warnings() {
        errln!("warning: {}: {}: {}", path.display(), w.field, w.message);
    }
}

/// Refuses a layout whose objects are not the scene's assets: metrics over the wrong pair
/// mislead ([`disco_layout::commands::check_belongs`]); a partial one is warned about.
fn check_belongs(spec: &SceneSpec, layout: &Layout, path: &Path) -> Result<()> {
    if let Some(warning) = disco_layout::commands::check_belongs(spec, layout, path)? {
        errln!("warning: {warning}");
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn an_os_error_is_said_once() {
        let missing = std::path::Path::new("/no/such/scene.json");
        let e: anyhow::Error = disco_layout::SceneSpec::load(missing).unwrap_err().into();
        let text = error_text(&e);
        assert_eq!(text.matches("os error 2").count(), 1, "{text}");
        let wrapped = e.context("reading the scene");
        assert!(error_text(&wrapped).starts_with("reading the scene: /no/such/scene.json"));
    }

    #[test]
    fn exit_codes_follow_the_documented_table() {
        assert_eq!(exit_code(&ScenesFailed::check(1, 3).unwrap_err()), 4);
        assert!(ScenesFailed::check(0, 3).is_ok());
        let model = disco_layout::Error::Model {
            name: "m".into(),
            reason: "unreachable".into(),
        };
        assert_eq!(exit_code(&model.into()), 3);
        assert_eq!(exit_code(&anyhow::anyhow!("bad input")), 1);
        let mut layout = disco_layout::synth::bedroom().1;
        assert!(Degraded::check("a.json".as_ref(), &layout).is_ok());
        layout.stats.deadline_missed = true;
        let late = Degraded::check("a.json".as_ref(), &layout).unwrap_err();
        assert_eq!(exit_code(&late), 5);
        layout.stats.model_failures = vec!["designer: model server \"m\": 401".into()];
        let down = Degraded::check("a.json".as_ref(), &layout).unwrap_err();
        assert_eq!(exit_code(&down), 3);
        assert!(down.to_string().contains("401"), "{down}");
    }

    #[test]
    fn counts_take_the_singular_for_one() {
        assert_eq!(count(1, "scene"), "1 scene");
        assert_eq!(count(0, "asset"), "0 assets");
        assert_eq!(
            ScenesFailed::check(1, 1).unwrap_err().to_string(),
            "1 of 1 scene failed"
        );
    }

    #[test]
    fn the_command_line_definition_is_consistent() {
        use clap::CommandFactory;
        Cli::command().debug_assert();
    }
}
