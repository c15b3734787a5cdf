//! `disco`: the command-line face of disco-layout. It parses arguments, sets up logging, hands the
//! subcommand to its module in [`cli`] and turns an error into the documented exit code.
//! Nothing is printed with `eprintln!` (a stderr whose reader is gone would make it panic):
//! messages go through `disco_core::io::to_stderr`.
#![deny(clippy::print_stdout, clippy::print_stderr)]

mod cli;

use std::process::ExitCode;

use clap::Parser;

use cli::Cli;

fn main() -> ExitCode {
    let cli = Cli::parse();
    init_logging(cli.quiet, cli.verbose);
    exit_on_signal();
    let code = match cli.run() {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            disco_core::io::to_stderr(&format!("error: {}\n", cli::error_text(&e)));
            ExitCode::from(cli::exit_code(&e))
        }
    };
    // No agent outlives disco, whatever path the run took.
    disco_runtime::external::group::kill_all();
    code
}

/// On SIGTERM (what Slurm and Kubernetes send) or SIGINT (Ctrl-C), from a thread of its own:
/// kill every agent process group, let the writes in progress finish (no temporary file stays;
/// what is finished is written whole, what is not is not written), and exit 143 or 130.
#[cfg(unix)]
fn exit_on_signal() {
    use tokio::signal::unix::{SignalKind, signal};
    let watch = || {
        let runtime = tokio::runtime::Builder::new_current_thread()
            .enable_io()
            .build()
            .ok()?;
        runtime.block_on(async {
            let mut term = signal(SignalKind::terminate()).ok()?;
            let mut int = signal(SignalKind::interrupt()).ok()?;
            tokio::select! {
                _ = term.recv() => Some(("SIGTERM", 143)),
                _ = int.recv() => Some(("SIGINT", 130)),
            }
        })
    };
    let spawned = std::thread::Builder::new()
        .name("disco-signals".into())
        .spawn(move || {
            let Some((name, code)) = watch() else {
                return;
            };
            let agents = disco_runtime::external::group::kill_all();
            disco_core::io::stop_writes();
            disco_core::io::to_stderr(&format!(
                "error: stopped by {name}: {agents} agent process group(s) killed; finished \
                 outputs are written, unfinished ones are not\n"
            ));
            std::process::exit(code);
        });
    if let Err(e) = spawned {
        tracing::warn!("cannot watch for SIGTERM/SIGINT: {e}");
    }
}

/// Signals are Unix's; elsewhere the default handling stays.
#[cfg(not(unix))]
fn exit_on_signal() {}

/// Log lines on stderr: errors only with `-q`, then warnings, info (`-v`), debug (`-vv`);
/// `RUST_LOG` overrides the level.
fn init_logging(quiet: bool, verbose: u8) {
    let level = match (quiet, verbose) {
        (true, _) => "error",
        (false, 0) => "warn",
        (false, 1) => "info",
        _ => "debug",
    };
    // `Targets` reads `RUST_LOG`'s `target=level,level` form without a regex engine.
    let filter = std::env::var("RUST_LOG")
        .ok()
        .and_then(|s| s.parse::<tracing_subscriber::filter::Targets>().ok())
        .unwrap_or_else(|| level.parse().expect("a level name"));
    use tracing_subscriber::layer::SubscriberExt;
    use tracing_subscriber::util::SubscriberInitExt;
    tracing_subscriber::registry()
        .with(
            tracing_subscriber::fmt::layer()
                .with_writer(std::io::stderr)
                .with_ansi(std::io::IsTerminal::is_terminal(&std::io::stderr())),
        )
        .with(filter)
        .init();
}
