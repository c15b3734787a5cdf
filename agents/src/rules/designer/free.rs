//! Where objects go on the open floor: free-standing anchors (tables, islands) where they keep
//! the most clearance near their share of the room, floor coverings in the middle.

use glam::DVec2;

use super::brief::{long_side_rotation, room_centre};
use super::choice::ranked;
use super::floor::Floor;
use disco_core::geometry::{Footprint, Wall};
use disco_core::placement::Pose;
use disco_core::plan::Plan;
use disco_core::room::analysis::RoomAnalysis;
use disco_core::scene::{Asset, Room, SceneSpec};

/// Score lost per cm a free-standing anchor stands from its aim.
const AIM_WEIGHT: f64 = 0.1;

/// Score lost by a free spot that stands in the zone kept clear before an earlier object.
const BLOCKS_ACCESS_PENALTY: f64 = 100.0;

/// Score lost by a free spot without room all round for the anchor's ring of chairs.
const NO_RING_PENALTY: f64 = 300.0;

/// Spots for a free-standing anchor of `size` (width, depth, height), best first: room all
/// round for a `ring` of chairs, clearance, closeness to the group's aim; long side along the
/// room's long side. The room's centre when nothing fits.
pub(super) fn place_free(
    floor: &Floor<'_>,
    size: [f64; 3],
    clearance: f64,
    ring: f64,
) -> Vec<Pose> {
    let rotation = long_side_rotation(floor.room, size[0], size[1]);
    place_free_turned(floor, size, clearance, ring, rotation)
}

/// [`place_free`] with the anchor turned to `rotation`.
pub(super) fn place_free_turned(
    floor: &Floor<'_>,
    size: [f64; 3],
    clearance: f64,
    ring: f64,
    rotation: f64,
) -> Vec<Pose> {
    let [w, d, height] = size;
    let room = floor.room;
    let probe = Footprint::new(DVec2::ZERO, w, d, rotation);
    let h = probe.aabb_half();
    let step = (room.width.max(room.depth) / 80.0).max(10.0);
    let mut scored: Vec<(f64, Pose)> = Vec::new();
    let mut y = h.y;
    while y <= room.depth - h.y + 1e-9 {
        let mut x = h.x;
        while x <= room.width - h.x + 1e-9 {
            let c = DVec2::new(x, y);
            let fp = probe.with_pose(c, rotation);
            if floor.fits(&fp, height) {
                let free = floor.clearance_of(&fp.aabb(), clearance * 1.5);
                let envelope = Footprint::new(c, w + 2.0 * ring, d + 2.0 * ring, rotation);
                let penalty = if floor.blocks_clearance(&fp, "") {
                    BLOCKS_ACCESS_PENALTY
                } else {
                    0.0
                } + if ring > 0.0 && !floor.fits(&envelope, height) {
                    NO_RING_PENALTY
                } else {
                    0.0
                };
                let score = free - AIM_WEIGHT * c.distance(floor.aim) - penalty;
                scored.push((
                    score,
                    Pose {
                        center: c,
                        rotation,
                    },
                ));
            }
            x += step;
        }
        y += step;
    }
    if scored.is_empty() {
        return vec![Pose {
            center: room_centre(room),
            rotation,
        }];
    }
    ranked(scored)
}

/// Poses for a floor covering: the room's centre, then spots further out in the four axis
/// directions, 20 cm at a time; the first free one is taken.
pub(super) fn place_flat(room: &Room, w: f64, d: f64) -> Vec<Pose> {
    let rotation = long_side_rotation(room, w, d);
    let centre = room_centre(room);
    let mut cands = vec![Pose {
        center: centre,
        rotation,
    }];
    for r in 1..20 {
        for (dx, dy) in [(1.0, 0.0), (-1.0, 0.0), (0.0, 1.0), (0.0, -1.0)] {
            cands.push(Pose {
                center: centre + DVec2::new(dx, dy) * (r as f64 * 20.0),
                rotation,
            });
        }
    }
    cands
}

/// Poses for a floor covering `d` deep just inside the room's main door (an entrance mat):
/// centred on the doorway, its width along the wall. None when the room has no door.
pub(super) fn inside_main_door(room: &Room, analysis: &RoomAnalysis, d: f64) -> Vec<Pose> {
    let Some(i) = analysis.main_door else {
        return Vec::new();
    };
    let (Some(mid), Some(wall)) = (
        room.door_middle(i),
        room.doors.get(i).and_then(|d| Wall::get(room, d.wall)),
    ) else {
        return Vec::new();
    };
    [DOORSTEP_GAP_CM, 2.0 * DOORSTEP_GAP_CM]
        .into_iter()
        .map(|gap| Pose {
            center: mid + wall.inward_normal() * (d / 2.0 + gap),
            rotation: wall.inward_rotation(),
        })
        .filter(|p| room.contains_point(p.center, 0.0))
        .collect()
}

/// How far (cm) inside the doorway an entrance mat lies.
const DOORSTEP_GAP_CM: f64 = 5.0;

/// Where the group's free-standing anchor should go. Free-standing anchors (tables, islands:
/// no wall, no relation) share the room as a grid of equal cells, one each in plan order, so
/// several tables spread over a hall instead of crowding its middle; a lone one aims at the
/// centre.
pub(super) fn spread_aim(scene: &SceneSpec, plan: &Plan, group: &[&Asset]) -> DVec2 {
    let room = &scene.room;
    let free_standing = |name: &str| {
        scene.asset(name).is_some_and(|a| !a.is_flat())
            && plan
                .constraints
                .get(name)
                .is_none_or(|c| !c.against_wall && c.relations.is_empty())
    };
    let anchors: Vec<&str> = plan
        .groups
        .iter()
        .filter_map(|g| g.first().map(String::as_str))
        .filter(|n| free_standing(n))
        .collect();
    let Some(k) = group
        .first()
        .and_then(|a| anchors.iter().position(|n| *n == a.name))
    else {
        return room_centre(room);
    };
    let n = anchors.len();
    let cols = ((n as f64 * room.width / room.depth).sqrt().round() as usize).clamp(1, n);
    let rows = n.div_ceil(cols);
    let (col, row) = (k % cols, k / cols);
    DVec2::new(
        (col as f64 + 0.5) * room.width / cols as f64,
        (row as f64 + 0.5) * room.depth / rows as f64,
    )
}

/// Poses for a free-standing anchor the prompt wants in a corner: in each corner of the room,
/// both ways round, with a `ring` (its chairs' depth) kept free between it and the walls.
pub(super) fn place_in_corner(room: &Room, w: f64, d: f64, ring: f64) -> Vec<Pose> {
    let mut out = Vec::new();
    for rotation in [
        long_side_rotation(room, w, d),
        90.0 - long_side_rotation(room, w, d),
    ] {
        let h = Footprint::new(DVec2::ZERO, w, d, rotation).aabb_half() + DVec2::splat(ring);
        for (x, y) in [
            (h.x, h.y),
            (room.width - h.x, h.y),
            (h.x, room.depth - h.y),
            (room.width - h.x, room.depth - h.y),
        ] {
            out.push(Pose {
                center: DVec2::new(x, y),
                rotation,
            });
        }
    }
    out
}
