//! `disco config`: the agent graphs built into the binary, listed or written out, so an
//! installed `disco` needs no source tree (`disco config show local-llm > my.toml`).

use anyhow::Result;
use disco_layout::config::{PRESETS, Preset};

/// The arguments of `disco config`.
#[derive(clap::Args)]
pub struct Config {
    #[command(subcommand)]
    action: Action,
}

/// What to do with the built-in graphs.
#[derive(clap::Subcommand)]
enum Action {
    /// The built-in agent graphs: each name (usable as `--config NAME`) and what it is for.
    List,
    /// Print a built-in agent graph's TOML, comments and all, to edit a copy of it.
    Show {
        /// The graph's name, as `disco config list` prints it.
        name: String,
    },
}

impl Config {
    /// Lists the presets or prints one.
    pub fn run(self) -> Result<()> {
        match self.action {
            Action::List => {
                let width = PRESETS.iter().map(|p| p.name.len()).max().unwrap_or(0);
                for p in PRESETS {
                    outln!("{:width$}  {}", p.name, p.description());
                }
            }
            Action::Show { name } => {
                let preset = Preset::lookup(&name).map_err(anyhow::Error::msg)?;
                out!("{}", preset.text);
            }
        }
        Ok(())
    }
}
