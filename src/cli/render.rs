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
    /// Draws the layout, writes the PNG and says what it wrote (unless `quiet`).
    pub fn run(self, quiet: bool) -> Result<()> {
        let layout = Layout::load(&self.layout)?;
        let options = RenderOptions {
            long_side_px: self.size,
            ..RenderOptions::default()
        };
        let png = render_png(&layout, &options)?;
        super::create_parents([self.output.as_path()])?;
        io::write_atomic(&self.output, &png)?;
        if !quiet {
            println!(
                "{}: {} drawn, {} px on the long side",
                self.output.display(),
                super::count(layout.objects.len(), "object"),
                self.size
            );
        }
        Ok(())
    }
}
