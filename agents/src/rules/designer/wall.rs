//! Where an anchor goes on a wall: the stretch that leaves room beside it for its side
//! dependents and in front for its clearance, centred or tucked towards a corner by its kind.

use super::brief::dependents;
use super::choice::ranked;
use super::floor::Floor;
use super::free::place_free;
use crate::arrangement::RunSlot;
use crate::knowledge::Kind;
use disco_core::geometry::{Footprint, Wall};
use disco_core::placement::{Pose, wall_poses};
use disco_core::plan::{FormationShape, Plan, Relation};
use disco_core::scene::Asset;

/// Score lost by a wall spot that stands in the zone kept clear before an earlier object.
const BLOCKS_ACCESS_PENALTY: f64 = 500.0;

/// Score lost by a wall spot without room beside and before it for the anchor's dependents.
const CRAMPED_PENALTY: f64 = 200.0;

/// Score lost per cm between an anchor the prompt wants by a window and the nearest window: more
/// than a corner or a neighbour's side is worth, so the window wins.
const WINDOW_PULL: f64 = 5.0;

/// The best wall stretches for an anchor, best first; the open floor's best spots when no wall
/// has room for it. A piece of a `run` (a galley, an L, a one-wall run) keeps to the run's walls
/// and packs towards its end, unless no spot there has room.
pub(super) fn place_on_wall(
    floor: &Floor<'_>,
    asset: &Asset,
    kind: &Kind,
    plan: &Plan,
    group: &[&Asset],
    run: Option<&RunSlot>,
) -> Vec<Pose> {
    let [w, d, h] = asset.size;
    // Width its dependents need beside it: on both sides (side_of), or on one side (near).
    let need = |rel: Relation| {
        dependents(plan, group, rel, &asset.name)
            .map(|a| a.size[0].max(a.size[1]) + 10.0)
            .fold(0.0, f64::max)
    };
    let in_corner = floor.in_corner.contains(&asset.name);
    // What a seat faces from across the room (the TV a sofa is opposite, the screen rows
    // face) takes the middle of its wall, so the seats have the room's width before them
    // rather than a corner's. (An arc closed round the middle of a wall would wall its focus
    // in.)
    let faced_across = dependents(plan, group, Relation::Opposite, &asset.name)
        .next()
        .is_some()
        || plan.formations.iter().any(|f| {
            f.shape == FormationShape::Rows && f.focus.as_deref() == Some(asset.name.as_str())
        });
    // What an arc faces stands a quarter of the way along its wall: out of the corner, where
    // the arc would have no room, and off the middle, where the arc would close round it.
    let arc_focus = plan
        .formations
        .iter()
        .any(|f| f.shape == FormationShape::Arc && f.focus.as_deref() == Some(asset.name.as_str()));
    let spot = WallSpot {
        floor,
        name: &asset.name,
        w,
        d,
        h,
        clearance: kind.clearance,
        both_sides: need(Relation::SideOf),
        one_side: need(Relation::Near),
        in_corner,
        centred: (kind.centred || faced_across || floor.centred_on_wall.contains(&asset.name))
            && !in_corner,
        arc_focus: arc_focus && !in_corner,
        by_window: floor.by_window.contains(&asset.name),
        run,
    };
    let poses = wall_poses(floor.room, w, d, asset.size[2], 10.0);
    let mut scored: Vec<(f64, Pose)> = poses
        .iter()
        .filter_map(|(wall, pose)| spot.score(*wall, pose).map(|s| (s, *pose)))
        .collect();
    if scored.is_empty() && run.is_some() {
        let anywhere = WallSpot { run: None, ..spot };
        scored = poses
            .iter()
            .filter_map(|(wall, pose)| anywhere.score(*wall, pose).map(|s| (s, *pose)))
            .collect();
    }
    if scored.is_empty() {
        return place_free(floor, asset.size, kind.clearance, 0.0);
    }
    ranked(scored)
}

/// What scoring a wall spot for one anchor needs to know.
struct WallSpot<'f, 'a> {
    floor: &'f Floor<'a>,
    /// The anchor's name.
    name: &'f str,
    /// The anchor's width, depth and height.
    w: f64,
    d: f64,
    h: f64,
    /// Free depth its kind needs in front.
    clearance: f64,
    /// Width needed on each side for `side_of` dependents.
    both_sides: f64,
    /// Width needed on one side for `near` dependents.
    one_side: f64,
    /// The prompt wants it in a corner.
    in_corner: bool,
    /// It takes the middle of its wall.
    centred: bool,
    /// An arc faces it: it stands a quarter of the way along its wall.
    arc_focus: bool,
    /// The prompt wants it by a window.
    by_window: bool,
    /// The run it belongs to, if the prompt names one.
    run: Option<&'f RunSlot>,
}

impl WallSpot<'_, '_> {
    /// The score of the anchor at `pose` on `wall`, `None` where it does not fit. Spots lose for
    /// blocking an earlier object's access and for cramping the dependents; then centred kinds
    /// prefer the middle of long walls, the others a corner or a neighbour's side.
    fn score(&self, wall: Wall, pose: &Pose) -> Option<f64> {
        if self.run.is_some_and(|r| !r.walls.contains(&wall)) {
            return None;
        }
        let fp = Footprint::new(pose.center, self.w, self.d, pose.rotation);
        if !self.floor.fits(&fp, self.h) {
            return None;
        }
        let mut score = 0.0;
        if self.floor.blocks_clearance(&fp, self.name) {
            score -= BLOCKS_ACCESS_PENALTY;
        }
        if !self.room_for_dependents(&fp) {
            // A run the furniture forms by itself never cramps a piece to stay closed: the
            // piece stands where its dependents fit (a dishwasher beside the sink).
            if self.run.is_some_and(|r| r.joined) {
                return None;
            }
            score -= CRAMPED_PENALTY;
        }
        let len = wall.length();
        let mid = wall.coordinate((wall.edge.start + wall.edge.end) / 2.0);
        let from_mid = (wall.coordinate(pose.center) - mid).abs();
        if self.by_window
            && let Some(gap) = fp.gap_to_window(self.floor.room)
        {
            score -= WINDOW_PULL * gap;
        }
        if let Some(run) = self.run {
            let b = fp.aabb();
            score -= run.pull() * run.towards.clamp(b.min, b.max).distance(run.towards);
        } else if self.centred {
            score -= from_mid;
            score += len * 0.2;
        } else if self.arc_focus {
            score -= (from_mid - len / 4.0).abs();
            score += len * 0.2;
        } else {
            score -= self.off_compact(&fp, len, from_mid);
        }
        Some(score)
    }

    /// Whether the floor before the anchor at `fp` is free for its clearance and its
    /// dependents: both sides widened for `side_of` ones, and one side or the other for `near`.
    fn room_for_dependents(&self, fp: &Footprint) -> bool {
        self.free_before(fp, 0.0, 2.0 * self.both_sides)
            && (self.one_side == 0.0
                || self.free_before(fp, self.one_side / 2.0, self.one_side)
                || self.free_before(fp, -self.one_side / 2.0, self.one_side))
    }

    /// Whether the envelope of the anchor at `fp` with its clearance in front, shifted
    /// `lateral` cm to its right and widened by `extra`, lies in the room clear of solid objects.
    fn free_before(&self, fp: &Footprint, lateral: f64, extra: f64) -> bool {
        let env = Footprint::new(
            fp.center + fp.front * (self.clearance / 2.0) + fp.right * lateral,
            self.w + extra,
            self.d + self.clearance,
            fp.rotation,
        )
        .aabb();
        self.floor.holds_box(&env) && !self.floor.solid_overlaps(&env, 1.0)
    }

    /// How far a non-centred anchor at `fp` stands from being compact, leaving open floor: from
    /// the nearer end of its wall (of length `len`; `from_mid` from its middle) or a neighbour,
    /// whichever is closer; ten times the distance to the wall's end when the prompt asked for a
    /// corner, as nothing else will do.
    fn off_compact(&self, fp: &Footprint, len: f64, from_mid: f64) -> f64 {
        let to_end = (len / 2.0 - from_mid) - self.w / 2.0;
        if self.in_corner {
            return 10.0 * to_end;
        }
        // Only a neighbour nearer than the wall's end can matter.
        to_end.min(self.floor.nearest_solid_gap(&fp.aabb(), to_end))
    }
}
