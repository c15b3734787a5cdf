//! `disco render`: draw a layout from above as a PNG.

use std::path::PathBuf;

use anyhow::Result;
use disco_layout::render::{RenderOptions, render_png};
use disco_layout::{Layout, SceneSpec, io};

/// The arguments of `disco render`.
#[derive(clap::Args)]
pub struct Render {
    /// The layout (JSON). With `--scene`, a draft is enough: objects need only `name`,
    /// `position` and `rotation`, as for `disco refine`.
    layout: PathBuf,
    /// Where to write the PNG.
    #[arg(short, long)]
    output: PathBuf,
    /// The scene the layout belongs to: the room, sizes and categories come from it, so a
    /// hand-made or broken layout can be drawn before it is refined.
    #[arg(long)]
    scene: Option<PathBuf>,
    /// Pixels on the long side.
    #[arg(long, default_value_t = 1024, value_parser = clap::value_parser!(u32).range(16..=16384))]
    size: u32,
}

impl Render {
    /// Draws the layout, writes the PNG and says what it wrote (unless `quiet`).
    pub fn run(self, quiet: bool) -> Result<()> {
        let mut inputs = vec![io::NamedPath::new("LAYOUT", &self.layout)];
        inputs.extend(
            self.scene
                .as_deref()
                .map(|p| io::NamedPath::new("--scene", p)),
        );
        io::refuse_clobbering(&inputs, &[io::NamedPath::new("-o", &self.output)], &[])?;
        let layout = self.load()?;
        let options = RenderOptions {
            long_side_px: self.size,
            ..RenderOptions::default()
        };
        let png = render_png(&layout, &options)?;
        super::create_parents([self.output.as_path()])?;
        io::write_atomic(&self.output, &png)?;
        if !quiet {
            outln!(
                "{}: {} drawn, {} px on the long side",
                self.output.display(),
                super::count(layout.objects.len(), "object"),
                self.size
            );
        }
        Ok(())
    }

    /// The layout to draw ([`disco_layout::commands::drawable_layout`]): completed from
    /// `--scene` when given; else the file as a complete layout, where an object without a
    /// `category` takes it from its name.
    fn load(&self) -> Result<Layout> {
        let scene = self.scene.as_deref().map(SceneSpec::load).transpose()?;
        let text = io::read_text(&self.layout)?;
        Ok(disco_layout::commands::drawable_layout(
            &self.layout,
            &text,
            scene.as_ref(),
        )?)
    }
}
