//! `disco render`: draw a layout from above as a PNG.

use std::path::{Path, PathBuf};

use anyhow::Result;
use disco_layout::layout::{DraftLayout, PlacedObject};
use disco_layout::render::{RenderOptions, render_png};
use disco_layout::{Layout, SceneSpec, io};

/// The category given to an object a layout names without one, when its name says nothing
/// either.
const UNKNOWN_CATEGORY: &str = "unknown";

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

    /// The layout to draw: completed from `--scene` when given; else the file as a complete
    /// layout, where an object without a `category` takes it from its name.
    fn load(&self) -> Result<Layout> {
        if let Some(scene) = &self.scene {
            let spec = SceneSpec::load(scene)?;
            let (layout, _) = DraftLayout::load(&self.layout)?.resolve(&self.layout, &spec)?;
            return Ok(layout);
        }
        let complete = match Layout::load(&self.layout) {
            Ok(layout) => return Ok(layout),
            Err(e) => e,
        };
        let Ok(draft) = DraftLayout::load(&self.layout) else {
            return Err(complete.into());
        };
        match without_categories(draft, &self.layout)? {
            Some(layout) => Ok(layout),
            None => Err(anyhow::anyhow!(
                "{complete} (a draft layout of names and positions is drawn with its scene: add --scene SCENE.json)"
            )),
        }
    }
}

/// A draft with a room and every object's size, its missing categories taken from the objects'
/// names (`floor lamp-0` is a `floor lamp`); `None` when the room or a size is missing.
fn without_categories(draft: DraftLayout, path: &Path) -> Result<Option<Layout>> {
    let Some(room) = draft.room else {
        return Ok(None);
    };
    let mut objects = Vec::with_capacity(draft.objects.len());
    for d in draft.objects {
        let Some(size) = d.size else {
            return Ok(None);
        };
        let category = d.category.unwrap_or_else(|| category_of(&d.name));
        objects.push(PlacedObject {
            name: d.name,
            category,
            size,
            position: d.position,
            rotation: d.rotation,
        });
    }
    let layout = Layout {
        id: draft.id.unwrap_or_else(|| {
            path.file_stem()
                .map(|s| s.to_string_lossy().into_owned())
                .unwrap_or_default()
        }),
        room,
        objects,
        dropped: draft.dropped,
        plan: std::sync::Arc::new(draft.plan),
        stats: draft.stats,
    };
    layout.validate(path)?;
    Ok(Some(layout))
}

/// An asset's category from its name: the name without a trailing `-N` instance number, or
/// [`UNKNOWN_CATEGORY`] when nothing is left.
fn category_of(name: &str) -> String {
    let base = match name.rsplit_once('-') {
        Some((stem, n)) if !n.is_empty() && n.chars().all(|c| c.is_ascii_digit()) => stem,
        _ => name,
    };
    let base = base.trim();
    if base.is_empty() {
        UNKNOWN_CATEGORY.to_string()
    } else {
        base.to_string()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_category_comes_from_the_name() {
        assert_eq!(category_of("floor lamp-0"), "floor lamp");
        assert_eq!(category_of("bed"), "bed");
        assert_eq!(category_of("x-ray-12"), "x-ray");
        assert_eq!(category_of("-3"), UNKNOWN_CATEGORY);
    }
}
