//! `disco render`: draw a layout from above as a PNG, or, with `--walls`, its walls unrolled
//! with everything against them at its height.

use std::path::PathBuf;

use anyhow::Result;
use disco_layout::render::{
    ElevationOptions, RenderOptions, render_png, render_walls_png, sheet_geometry,
};
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
    /// Pixels on the long side (with `--walls`: the sheet's width) [default: 1024; 1280 with
    /// `--walls`]
    #[arg(long, value_parser = clap::value_parser!(u32).range(16..=16384))]
    size: Option<u32>,
    /// Draw the wall elevation sheet instead of the view from above: each wall unrolled as seen
    /// from inside the room, with its doors and windows, the pieces standing against it, what
    /// stands on them and what hangs on it, at their heights.
    #[arg(long)]
    walls: bool,
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
        let (png, said) = if self.walls {
            let defaults = ElevationOptions::default();
            let options = ElevationOptions {
                width_px: self.size.unwrap_or(defaults.width_px),
                ..defaults
            };
            let sheet = sheet_geometry(&layout, &options);
            let said = format!(
                "{} of {} drawn, {} x {} px",
                super::count(sheet.strips.len(), "wall"),
                super::count(layout.objects.len(), "object"),
                sheet.width,
                sheet.height
            );
            (render_walls_png(&layout, &options)?, said)
        } else {
            let defaults = RenderOptions::default();
            let options = RenderOptions {
                long_side_px: self.size.unwrap_or(defaults.long_side_px),
                ..defaults
            };
            let said = format!(
                "{} drawn, {} px on the long side",
                super::count(layout.objects.len(), "object"),
                options.long_side_px
            );
            (render_png(&layout, &options)?, said)
        };
        super::create_parents([self.output.as_path()])?;
        io::write_atomic(&self.output, &png)?;
        if !quiet {
            outln!("{}: {said}", self.output.display());
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
