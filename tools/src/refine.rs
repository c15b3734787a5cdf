//! Refining a layout made elsewhere (by hand, by another tool): complete it from its scene, then
//! run the Physical Refinement Tool.

use std::collections::HashSet;

use crate::prt::{PhysicalRefiner, PrtConfig};
use disco_core::layout::{Dropped, Layout, PlacedObject};
use disco_core::scene::SceneSpec;

/// Runs the PRT on `layout` (resolved against `scene`). Assets named in `missing` start at the room
/// centre and are placed by the PRT. Every asset of the scene ends in `objects` or `dropped`.
pub fn refine_layout(
    scene: &SceneSpec,
    mut layout: Layout,
    missing: &[String],
    config: PrtConfig,
) -> Layout {
    let centre = [scene.room.width / 2.0, scene.room.depth / 2.0];
    for name in missing {
        if let Some(a) = scene.asset(name) {
            layout.objects.push(PlacedObject {
                name: a.name.clone(),
                category: a.category.clone(),
                size: a.size,
                position: centre,
                rotation: 0.0,
                ..Default::default()
            });
        }
    }
    let refined = PhysicalRefiner::new(config).refine(&scene.room, &layout.objects, &layout.plan);
    let stats = refined.stats();
    let placed: HashSet<&str> = refined.objects.iter().map(|o| o.name.as_str()).collect();
    let mut dropped: Vec<Dropped> = layout
        .dropped
        .into_iter()
        .filter(|d| !placed.contains(d.name.as_str()))
        .collect();
    dropped.extend(refined.dropped);
    layout.objects = refined.objects;
    layout.dropped = dropped;
    layout.stats.prt = Some(stats);
    layout
}
