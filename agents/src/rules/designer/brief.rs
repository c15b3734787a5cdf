//! What every part of the designer works from: the brief of the group being designed, the plan's
//! lookups (an object's target, a target's dependents, the gap a dependent keeps) and the room's
//! middle and long side. A leaf: it uses no other part of the designer, so the parts can share
//! it without importing one another in a circle.

use std::collections::HashMap;

use glam::DVec2;

use crate::arrangement::RunSlot;
use crate::knowledge::Kind;
use disco_core::layout::PlacedObject;
use disco_core::plan::{Plan, Relation};
use disco_core::room::analysis::{RoomAnalysis, WallRole};
use disco_core::scene::{Asset, Room};

/// What every design of one group works from; the same for each alternative tried.
pub(super) struct GroupBrief<'a> {
    /// The room.
    pub(super) room: &'a Room,
    /// The scene's plan.
    pub(super) plan: &'a Plan,
    /// The group's assets, anchor first.
    pub(super) group: &'a [&'a Asset],
    /// What earlier groups placed.
    pub(super) placed: &'a [PlacedObject],
    /// Where a free-standing anchor of the group should go.
    pub(super) aim: DVec2,
    /// Objects the prompt wants in a corner.
    pub(super) in_corner: &'a [String],
    /// Objects the prompt wants in the middle of the room, free of the walls.
    pub(super) centre: &'a [String],
    /// Objects the prompt wants by a window.
    pub(super) by_window: &'a [String],
    /// Objects the prompt wants in the middle of their wall.
    pub(super) centred_on_wall: &'a [String],
    /// Objects the prompt wants at the window nearest the main door.
    pub(super) window_by_door: &'a [String],
    /// The run each wall piece belongs to, when the prompt names a galley, an L or a one-wall run.
    pub(super) runs: &'a HashMap<String, RunSlot>,
    /// Desks that would stand in rows before a board form a U open to it instead.
    pub(super) u_shape: bool,
    /// The room's zones, wall roles and corners.
    pub(super) analysis: &'a RoomAnalysis,
    /// Members of rows turned to a wall with nothing on it to face, and that wall's role.
    pub(super) rows_wall: &'a HashMap<String, WallRole>,
}

/// The distance (cm) a dependent of `kind` keeps from its target.
pub(super) fn gap(kind: &Kind) -> f64 {
    kind.relate.as_ref().map_or(10.0, |r| r.gap)
}

/// The first relation of `name` in the plan, as (relation, target).
pub(super) fn target_of<'p>(plan: &'p Plan, name: &str) -> Option<(Relation, &'p str)> {
    plan.constraints
        .get(name)
        .and_then(|c| c.relations.first())
        .map(|r| (r.relation, r.target.as_str()))
}

/// The members of `group` whose first relation in the plan is `relation` to `target`.
pub(super) fn dependents<'a>(
    plan: &'a Plan,
    group: &'a [&'a Asset],
    relation: Relation,
    target: &'a str,
) -> impl Iterator<Item = &'a Asset> {
    group
        .iter()
        .copied()
        .filter(move |a| target_of(plan, &a.name) == Some((relation, target)))
}

/// The middle of the room's floor: a rectangle's centre; a polygon's centroid when it lies on
/// the floor (an L's may not), else its bounding box's centre.
pub(super) fn room_centre(room: &Room) -> DVec2 {
    let middle = DVec2::new(room.width / 2.0, room.depth / 2.0);
    if room.is_rectangle() {
        return middle;
    }
    match disco_core::polygon::centroid(&room.outline()) {
        Some(c) if room.contains_point(c, 0.0) => c,
        _ => middle,
    }
}

/// The rotation (0 or 90) that lays a `w` x `d` object's long side along the room's long side.
pub(super) fn long_side_rotation(room: &Room, w: f64, d: f64) -> f64 {
    if (room.width >= room.depth) == (w >= d) {
        0.0
    } else {
        90.0
    }
}
