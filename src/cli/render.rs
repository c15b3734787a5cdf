//! `disco render`: draw a layout from above as a PNG.

use std::path::PathBuf;

use anyhow::Result;
use disco_layout::render::{RenderOptions, render_png};
use disco_layout::{Layout, io};

/// The arguments of `disco render`.
#[derive(clap::Args)]
pub struct Render {
    /// The layout (JSON).
    layout: PathBuf,
    /// Where to write the PNG.
    #[arg(short, long)]
    output: PathBuf,
    /// Pixels on the long side.
    #[arg(long, default_value_t = 1024, value_parser = clap::value_parser!(u32).range(16..=16384))]
    size: u32,
}

impl Render {
    /// Draws the layout and writes the PNG; prints nothing.
    pub fn run(self) -> Result<()> {
        let layout = Layout::load(&self.layout)?;
        let options = RenderOptions {
            long_side_px: self.size,
            ..RenderOptions::default()
        };
        io::write_atomic(&self.output, &render_png(&layout, &options)?)?;
        Ok(())
    }
}
