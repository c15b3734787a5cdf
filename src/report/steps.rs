//! The steps of a run, read back from its trace's snapshots: the layout after each group's
//! design, after each SRT and PRT round, and after the final PRT; drawn one PNG per step plus a
//! contact sheet of the whole sequence. A step whose layout has objects off the floor also gets
//! its sheet of walls (see [`crate::render::render_walls`]).

use std::path::{Path, PathBuf};

use crate::error::{Error, Result};
use crate::layout::{Dropped, Layout, PlacedObject};
use crate::render::{
    ElevationOptions, RenderOptions, contact_sheet, encode_png, has_objects_off_the_floor, render,
    render_walls,
};
use crate::runtime::batch::file_safe;
use crate::trace::{TraceEvent, TraceKind};

/// One step of the loop and the layout it left.
#[derive(Debug, Clone)]
pub struct Step {
    /// `design`, a refiner's stage name (`srt`, `prt`, ...), or `final prt`.
    pub stage: String,
    /// The group (1-based); 0 for the final pass.
    pub group: usize,
    /// The evaluate-and-refine round (0 for the design itself).
    pub round: u32,
    /// The layout after the step (the final layout's plan and room).
    pub layout: Layout,
}

impl Step {
    /// A short caption: `group 2 · srt (round 1)`.
    pub fn caption(&self) -> String {
        match (self.group, self.round) {
            (0, _) => self.stage.clone(),
            (g, 0) => format!("group {g} · {}", self.stage),
            (g, r) => format!("group {g} · {} (round {r})", self.stage),
        }
    }
}

impl Step {
    /// A file-name part: `group2-srt-r1`, `group1-design`, `final-prt`.
    pub fn file_stem(&self) -> String {
        let stage = file_safe(&self.stage.replace(' ', "-"));
        match (self.group, self.round) {
            (0, _) => stage,
            (g, 0) => format!("group{g}-{stage}"),
            (g, r) => format!("group{g}-{stage}-r{r}"),
        }
    }
}

/// The steps of scene `layout.id` in `events`, in order.
pub fn steps(events: &[TraceEvent], layout: &Layout) -> Vec<Step> {
    events
        .iter()
        .filter(|e| e.kind == TraceKind::Snapshot && e.scene == layout.id)
        .filter_map(|e| {
            let d = &e.detail;
            let objects: Vec<PlacedObject> = serde_json::from_value(d["objects"].clone()).ok()?;
            let dropped: Vec<Dropped> =
                serde_json::from_value(d["dropped"].clone()).unwrap_or_default();
            Some(Step {
                stage: d["step"].as_str().unwrap_or("step").to_string(),
                group: d["group"].as_u64().unwrap_or(0) as usize,
                round: d["round"].as_u64().unwrap_or(0) as u32,
                layout: Layout {
                    objects,
                    dropped,
                    stats: Default::default(),
                    ..layout.clone()
                },
            })
        })
        .collect()
}

/// One render per step, `long_side_px` wide, titled with the scene and the step's caption;
/// below 800 px (thumbnails) without axes and title, which would not be legible.
pub fn render_steps(steps: &[Step], long_side_px: u32) -> Result<Vec<tiny_skia::Pixmap>> {
    steps
        .iter()
        .map(|s| {
            render(
                &s.layout,
                &RenderOptions {
                    long_side_px,
                    title: Some(format!("{} · {}", s.layout.id, s.caption())),
                    axes: long_side_px >= 800,
                    ..RenderOptions::default()
                },
            )
        })
        .collect()
}

/// The sheet of walls of `step`, `width_px` wide and titled like its render, when its layout has
/// objects off the floor (`None` otherwise: a floor-only step has nothing to show there).
pub fn render_step_walls(step: &Step, width_px: u32) -> Result<Option<tiny_skia::Pixmap>> {
    if !has_objects_off_the_floor(&step.layout) {
        return Ok(None);
    }
    let options = ElevationOptions {
        width_px,
        title: Some(format!("{} · {}", step.layout.id, step.caption())),
        ..ElevationOptions::default()
    };
    render_walls(&step.layout, &options).map(Some)
}

/// Writes `DIR/<id>/NN-<caption>.png` per step and the contact sheet `DIR/<id>-steps.png`, and
/// for each step with objects off the floor its sheet of walls, `DIR/<id>-walls/NN-<caption>.png`
/// (a folder of its own, so the steps' folder holds one picture per step); returns the contact
/// sheet's path (`None` when there are no steps).
pub fn write_step_renders(steps: &[Step], dir: &Path) -> Result<Option<PathBuf>> {
    let Some(first) = steps.first() else {
        return Ok(None);
    };
    let id = file_safe(&first.layout.id);
    let folder = dir.join(&id);
    std::fs::create_dir_all(&folder).map_err(|source| Error::Write {
        path: folder.clone(),
        source,
    })?;
    let walls_folder = dir.join(format!("{id}-walls"));
    for (i, (step, pixmap)) in steps.iter().zip(render_steps(steps, 1024)?).enumerate() {
        let name = format!("{:02}-{}.png", i + 1, step.file_stem());
        crate::io::write_atomic(&folder.join(&name), &encode_png(&pixmap)?)?;
        if let Some(walls) = render_step_walls(step, ElevationOptions::default().width_px)? {
            std::fs::create_dir_all(&walls_folder).map_err(|source| Error::Write {
                path: walls_folder.clone(),
                source,
            })?;
            crate::io::write_atomic(&walls_folder.join(&name), &encode_png(&walls)?)?;
        }
    }
    let tiles: Vec<(String, tiny_skia::Pixmap)> = steps
        .iter()
        .map(Step::caption)
        .zip(render_steps(steps, 420)?)
        .collect();
    let sheet = contact_sheet(&tiles, 4)?;
    let path = dir.join(format!("{id}-steps.png"));
    crate::io::write_atomic(&path, &encode_png(&sheet)?)?;
    Ok(Some(path))
}

#[cfg(test)]
pub(crate) mod tests {
    use std::sync::Arc;

    use super::*;
    use crate::config::GraphConfig;
    use crate::registry::Registry;
    use crate::runtime::Runtime;
    use crate::scene::SceneSpec;
    use crate::trace::Trace;

    /// The synthetic bedroom through the default graph with the noisy designer (so the
    /// refiners have work), its trace keeping snapshots: the runtime, the layout, the events.
    pub(crate) async fn noisy_bedroom_run() -> (Runtime, Layout, Vec<crate::trace::TraceEvent>) {
        let (scene, _) = crate::synth::bedroom();
        let graph = GraphConfig::load(None, &["agents.designer.impl=noisy".into()]).unwrap();
        let runtime = Runtime::new(graph, Registry::builtin()).unwrap();
        let trace = Arc::new(Trace::with_snapshots());
        let layout = runtime.generate(scene, Arc::clone(&trace)).await.unwrap();
        (runtime, layout, trace.events())
    }

    /// The synthetic bedroom with a lamp on a nightstand and a painting on the wall above the
    /// bed (the top wall, wall 2), in the scene and in the layout.
    pub(crate) fn raised_bedroom() -> (SceneSpec, Layout) {
        use crate::layout::PlacedObject;
        use crate::scene::Asset;
        let (mut scene, mut layout) = crate::synth::bedroom();
        let nightstand = layout.object("nightstand-0").unwrap().clone();
        let raised = [
            PlacedObject {
                name: "lamp-0".into(),
                category: "table lamp".into(),
                size: [30.0, 30.0, 45.0],
                position: nightstand.position,
                rotation: nightstand.rotation,
                elevation: nightstand.top(),
                on: Some(nightstand.name.clone()),
                wall: None,
            },
            PlacedObject {
                name: "painting-0".into(),
                category: "painting".into(),
                size: [90.0, 4.0, 60.0],
                position: [200.0, 348.0],
                rotation: 180.0,
                elevation: 130.0,
                on: None,
                wall: Some(2),
            },
        ];
        for o in raised {
            scene.assets.push(Asset::new(&o.name, &o.category, o.size));
            layout.objects.push(o);
        }
        (scene, layout)
    }

    #[test]
    fn steps_with_objects_off_the_floor_get_their_walls_in_a_folder_of_their_own() {
        let (_, raised) = raised_bedroom();
        let (_, plain) = crate::synth::bedroom();
        let step = |stage: &str, group: usize, layout: &Layout| Step {
            stage: stage.into(),
            group,
            round: 0,
            layout: layout.clone(),
        };
        let all = [step("design", 1, &plain), step("final prt", 0, &raised)];
        assert!(render_step_walls(&all[0], 800).unwrap().is_none());
        let walls = render_step_walls(&all[1], 800).unwrap().unwrap();
        assert_eq!(walls.width(), 800);
        let dir = tempfile::tempdir().unwrap();
        write_step_renders(&all, dir.path()).unwrap().unwrap();
        let names = |folder: &str| -> Vec<String> {
            let mut v: Vec<String> = std::fs::read_dir(dir.path().join(folder))
                .unwrap()
                .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
                .collect();
            v.sort();
            v
        };
        let id = &raised.id;
        assert_eq!(names(id), ["01-group1-design.png", "02-final-prt.png"]);
        assert_eq!(names(&format!("{id}-walls")), ["02-final-prt.png"]);
        let png =
            tiny_skia::Pixmap::load_png(dir.path().join(format!("{id}-walls/02-final-prt.png")))
                .unwrap();
        assert_eq!(png.width(), ElevationOptions::default().width_px);
    }

    #[tokio::test]
    async fn every_group_leaves_a_design_step_and_refinements_leave_theirs() {
        let (runtime, layout, events) = noisy_bedroom_run().await;
        let all = steps(&events, &layout);
        let designs = all.iter().filter(|s| s.stage == "design").count();
        assert_eq!(designs, layout.plan.groups.len());
        assert!(
            all.iter().any(|s| s.stage == "prt"),
            "the noise gives the PRT work"
        );
        let last = all.last().unwrap();
        assert_eq!(last.stage, "final prt");
        let names = |l: &Layout| {
            let mut v: Vec<(String, [f64; 2])> = l
                .objects
                .iter()
                .map(|o| (o.name.clone(), o.position))
                .collect();
            v.sort_by(|a, b| a.0.cmp(&b.0));
            v
        };
        assert_eq!(names(&last.layout), names(&layout));
        // Each design step adds its group's objects to what was there.
        let first = all.iter().find(|s| s.stage == "design").unwrap();
        assert_eq!(first.layout.objects.len(), layout.plan.groups[0].len());

        let dir = tempfile::tempdir().unwrap();
        let sheet = write_step_renders(&all, dir.path()).unwrap().unwrap();
        let pngs = std::fs::read_dir(dir.path().join(&layout.id))
            .unwrap()
            .count();
        assert_eq!(pngs, all.len());
        let decoded = tiny_skia::Pixmap::load_png(&sheet).unwrap();
        let cols = all.len().min(4) as u32;
        assert!(decoded.width() >= cols * 420, "{}", decoded.width());
        // A plain trace keeps no snapshots.
        let plain = Arc::new(Trace::default());
        let (scene, _) = crate::synth::bedroom();
        runtime.generate(scene, Arc::clone(&plain)).await.unwrap();
        assert!(steps(&plain.events(), &layout).is_empty());
    }

    #[test]
    fn a_step_render_shows_each_object_in_its_colour_at_its_centre() {
        let (_, layout) = crate::synth::bedroom();
        let step = Step {
            stage: "design".into(),
            group: 1,
            round: 0,
            layout: layout.clone(),
        };
        let pixmap = &render_steps(&[step], 800).unwrap()[0];
        assert_eq!(pixmap.width().max(pixmap.height()), 800);
        let (_, _, view) = crate::render::view_for(&layout, 800);
        for o in layout.objects.iter().filter(|o| !o.is_flat()) {
            // Towards a corner: the name is written across the centre itself.
            let fp = o.footprint();
            let p = view.to_px(fp.center + (fp.corners()[0] - fp.center) * 0.75);
            let c = pixmap.pixel(p.x as u32, p.y as u32).unwrap();
            let want = crate::render::object_colour(&layout, o);
            let got = [c.red(), c.green(), c.blue()];
            let near = got
                .iter()
                .zip(want)
                .all(|(a, b)| (*a as i32 - b as i32).abs() <= 40);
            assert!(near, "{}: {got:?} vs {want:?}", o.name);
        }
    }
}
