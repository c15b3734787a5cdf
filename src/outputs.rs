//! Everything one run leaves on disk beside the runtime's own state: the layout as JSON, the trace
//! as JSON lines, top-down PNGs (the result, every step and a contact sheet of them), a
//! self-contained HTML report and a binary glTF. `disco generate` writes what its flags ask for
//! through [`write_outputs`]; a program embedding the library can do the same.
//!
//! This module only decides what goes where; the pictures come from [`crate::report`] and
//! [`crate::render`], the glTF from [`crate::export`], the writing from [`crate::io`].

use std::collections::HashMap;
use std::path::{Path, PathBuf};

use crate::error::{Error, Result};
use crate::export::{ExportOptions, export_glb};
use crate::io;
use crate::layout::Layout;
use crate::render::{
    ElevationOptions, RenderOptions, has_objects_off_the_floor, render_png, render_walls_png,
};
use crate::report;
use crate::runtime::batch::file_safe;
use crate::scene::SceneSpec;
use crate::trace::Trace;

/// Which outputs to write, and where. Every path is optional: `None` skips that output.
#[derive(Debug, Clone, Default)]
pub struct OutputOptions {
    /// The layout, as JSON.
    pub layout: Option<PathBuf>,
    /// Every message between supervisor and roles, as JSON lines.
    pub trace: Option<PathBuf>,
    /// A folder for the top-down PNGs: the result (`<id>.png`), every step
    /// (`<id>/NN-groupK-STAGE.png`) and a contact sheet of the sequence (`<id>-steps.png`).
    pub renders: Option<PathBuf>,
    /// The self-contained HTML report of the run.
    pub report: Option<PathBuf>,
    /// The room as a binary glTF (`.glb`).
    pub glb: Option<PathBuf>,
    /// Walls and floor of the glTF.
    pub export: ExportOptions,
    /// Mesh files by object name for the glTF, as [`crate::export::meshes_of`] reads them from
    /// the scene; objects without one are boxes.
    pub meshes: HashMap<String, PathBuf>,
}

impl OutputOptions {
    /// Whether the run's trace must keep layout snapshots: the step renders and the report
    /// draw every step from them.
    pub fn needs_snapshots(&self) -> bool {
        self.renders.is_some() || self.report.is_some()
    }

    /// An empty trace for the run, keeping snapshots only when [`Self::needs_snapshots`], and
    /// nothing at all when no output reads it.
    pub fn new_trace(&self) -> Trace {
        if self.needs_snapshots() {
            Trace::with_snapshots()
        } else if self.trace.is_some() {
            Trace::default()
        } else {
            Trace::discarding()
        }
    }
}

impl OutputOptions {
    /// Refuses, before the run, outputs that would replace one of `inputs` (the scene, the
    /// graph file, the meshes...) or each other, by path, through a link or as hard links
    /// ([`io::refuse_clobbering`]); the mesh files of [`Self::meshes`] count as inputs.
    /// `id` is the scene's, which names the files `--renders` writes.
    pub fn refuse_clobbering(&self, id: &str, inputs: &[io::NamedPath]) -> Result<()> {
        let stem = file_safe(id);
        let render_files = self.renders.as_ref().map(|dir| {
            (
                [
                    dir.join(format!("{stem}.png")),
                    dir.join(format!("{stem}-steps.png")),
                    dir.join(format!("{stem}-walls.png")),
                ],
                [dir.join(&stem), dir.join(format!("{stem}-walls"))],
            )
        });
        let mut outputs: Vec<io::NamedPath> = [
            ("-o", &self.layout),
            ("--glb", &self.glb),
            ("--report", &self.report),
            ("--trace", &self.trace),
        ]
        .into_iter()
        .filter_map(|(flag, path)| Some(io::NamedPath::new(flag, path.as_deref()?)))
        .collect();
        let mut folders = Vec::new();
        if let Some((files, dirs)) = &render_files {
            outputs.extend(files.iter().map(|f| io::NamedPath::new("--renders", f)));
            folders.extend(dirs.iter().map(|d| io::NamedPath::new("--renders", d)));
        }
        let mut all_inputs = inputs.to_vec();
        let mut meshes: Vec<_> = self.meshes.values().collect();
        meshes.sort();
        all_inputs.extend(meshes.into_iter().map(|m| io::NamedPath::new("mesh", m)));
        io::refuse_clobbering(&all_inputs, &outputs, &folders)
    }
}

/// Writes the outputs `options` asks for after a successful run of `scene` that produced
/// `layout`, recording into `events` (made with [`OutputOptions::new_trace`]). In this order:
/// the trace, the layout, the renders, the report, the glTF; the first failure stops the rest.
/// Each file is written atomically.
pub fn write_outputs(
    scene: &SceneSpec,
    layout: &Layout,
    events: &Trace,
    options: &OutputOptions,
) -> Result<()> {
    write_trace(events, options)?;
    if let Some(path) = &options.layout {
        io::write_json(path, layout)?;
    }
    // Only the renders and the report read the events back.
    let events = if options.needs_snapshots() {
        events.events()
    } else {
        Vec::new()
    };
    if let Some(dir) = &options.renders {
        write_renders(layout, &report::steps(&events, layout), dir)?;
    }
    if let Some(path) = &options.report {
        let html = report::html::scene_report(scene, layout, &events)?;
        io::write_atomic(path, html.as_bytes())?;
    }
    if let Some(path) = &options.glb {
        io::write_atomic(path, &export_glb(layout, &options.meshes, &options.export)?)?;
    }
    Ok(())
}

/// Writes the trace alone, if `options` asks for one: all a failed run leaves, and the way to
/// see why it failed.
pub fn write_trace(events: &Trace, options: &OutputOptions) -> Result<()> {
    match &options.trace {
        Some(path) => events.write_jsonl(path),
        None => Ok(()),
    }
}

/// The result as `DIR/<id>.png` (and its walls as `DIR/<id>-walls.png` when something is off
/// the floor), then the steps and their contact sheet ([`report::write_step_renders`]).
fn write_renders(layout: &Layout, steps: &[report::Step], dir: &Path) -> Result<()> {
    std::fs::create_dir_all(dir).map_err(|source| Error::Write {
        path: dir.to_path_buf(),
        source,
    })?;
    let png = dir.join(format!("{}.png", file_safe(&layout.id)));
    io::write_atomic(&png, &render_png(layout, &RenderOptions::default())?)?;
    if has_objects_off_the_floor(layout) {
        let walls = dir.join(format!("{}-walls.png", file_safe(&layout.id)));
        io::write_atomic(
            &walls,
            &render_walls_png(layout, &ElevationOptions::default())?,
        )?;
    }
    report::write_step_renders(steps, dir)?;
    Ok(())
}

#[cfg(test)]
mod tests {
    use std::sync::Arc;

    use super::*;
    use crate::config::GraphConfig;
    use crate::registry::Registry;
    use crate::runtime::Runtime;

    async fn bedroom_run(options: &OutputOptions) -> (SceneSpec, Layout, Arc<Trace>) {
        let (scene, _) = crate::synth::bedroom();
        let runtime =
            Runtime::new(GraphConfig::load(None, &[]).unwrap(), Registry::builtin()).unwrap();
        let events = Arc::new(options.new_trace());
        let layout = runtime
            .generate(scene.clone(), Arc::clone(&events))
            .await
            .unwrap();
        (scene, layout, events)
    }

    #[tokio::test]
    async fn every_asked_output_is_written_and_readable() {
        let dir = tempfile::tempdir().unwrap();
        let at = |name: &str| Some(dir.path().join(name));
        let options = OutputOptions {
            layout: at("room.json"),
            trace: at("trace.jsonl"),
            renders: at("renders"),
            report: at("room.html"),
            glb: at("room.glb"),
            ..OutputOptions::default()
        };
        let (scene, layout, events) = bedroom_run(&options).await;
        write_outputs(&scene, &layout, &events, &options).unwrap();

        let read_back = Layout::load(&dir.path().join("room.json")).unwrap();
        assert_eq!(read_back.objects.len(), layout.objects.len());
        let trace = std::fs::read_to_string(dir.path().join("trace.jsonl")).unwrap();
        assert_eq!(trace.lines().count(), events.events().len());
        let renders = dir.path().join("renders");
        let id = file_safe(&layout.id);
        assert!(renders.join(format!("{id}.png")).is_file());
        assert!(renders.join(format!("{id}-steps.png")).is_file());
        let steps = std::fs::read_dir(renders.join(&id)).unwrap().count();
        assert_eq!(steps, report::steps(&events.events(), &layout).len());
        assert!(steps > 0, "a snapshot trace leaves steps");
        let html = std::fs::read_to_string(dir.path().join("room.html")).unwrap();
        assert!(html.starts_with("<!doctype html>"));
        let glb = std::fs::read(dir.path().join("room.glb")).unwrap();
        assert_eq!(&glb[..4], b"glTF");
    }

    #[test]
    fn the_walls_are_drawn_only_when_something_is_off_the_floor() {
        let dir = tempfile::tempdir().unwrap();
        let (_, plain) = crate::synth::bedroom();
        write_renders(&plain, &[], dir.path()).unwrap();
        let walls = dir
            .path()
            .join(format!("{}-walls.png", file_safe(&plain.id)));
        assert!(dir.path().join(format!("{}.png", plain.id)).is_file());
        assert!(!walls.exists());
        let (_, raised) = report::steps::tests::raised_bedroom();
        write_renders(&raised, &[], dir.path()).unwrap();
        let png = tiny_skia::Pixmap::load_png(&walls).unwrap();
        assert_eq!(png.width(), ElevationOptions::default().width_px);
        // The sheet of walls is an output `--renders` may not write over an input.
        let options = OutputOptions {
            renders: Some(dir.path().to_path_buf()),
            ..OutputOptions::default()
        };
        let input = io::NamedPath::new("SCENE", &walls);
        assert!(options.refuse_clobbering(&raised.id, &[input]).is_err());
    }

    #[tokio::test]
    async fn only_what_is_asked_is_written_and_a_glb_alone_keeps_no_snapshots() {
        let dir = tempfile::tempdir().unwrap();
        let options = OutputOptions {
            glb: Some(dir.path().join("room.glb")),
            ..OutputOptions::default()
        };
        assert!(!options.needs_snapshots());
        let (scene, layout, events) = bedroom_run(&options).await;
        assert!(report::steps(&events.events(), &layout).is_empty());
        write_outputs(&scene, &layout, &events, &options).unwrap();
        let written: Vec<_> = std::fs::read_dir(dir.path())
            .unwrap()
            .map(|e| e.unwrap().file_name())
            .collect();
        assert_eq!(written, ["room.glb"]);
    }
}
