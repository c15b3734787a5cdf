//! Desks in rows: where a group's desks stand when they face a board placed by an earlier group.

use std::collections::HashMap;

use glam::DVec2;

use super::agent::RuleDesigner;
use super::brief::{GroupBrief, gap, target_of};
use super::floor::Floor;
use crate::arrangement::u_runs;
use crate::knowledge::{Kind, Knowledge};
use disco_core::geometry::{Footprint, normalize_degrees};
use disco_core::placement::{Pose, distance_to_boundary, row_poses};
use disco_core::plan::Relation;
use disco_core::scene::Asset;

/// Least distance (cm) from a board to the first row of desks.
const ROW_START_MIN_CM: f64 = 150.0;

/// Least distance (cm) from a board to the ends of a U's arms.
const U_START_MIN_CM: f64 = 60.0;

/// Free width (cm) kept between the chairs of a U's arms and the side walls, to walk to them.
const U_WALKWAY_CM: f64 = 70.0;

/// Free depth (cm) kept between what stands before a board and the first row of desks.
const ROW_START_CLEAR_CM: f64 = 45.0;

/// How far (cm) out from a board an object counts as standing before it.
const BEFORE_BOARD_DEPTH_CM: f64 = 300.0;

/// How far (cm) beyond a board's ends an object counts as standing before it.
const BEFORE_BOARD_MARGIN_CM: f64 = 100.0;

impl RuleDesigner {
    /// Poses of the group's desks that stand in rows facing a board already placed, by name;
    /// empty when the group has no such desks or the board is not there.
    pub(super) fn row_layout(
        &self,
        floor: &Floor<'_>,
        brief: &GroupBrief<'_>,
    ) -> HashMap<String, Pose> {
        let (plan, assets, placed) = (brief.plan, brief.group, brief.placed);
        let desks: Vec<(&Asset, Kind)> = assets
            .iter()
            .map(|a| (*a, self.knowledge.kind_of(a)))
            .filter(|(_, k)| !k.rows.is_empty())
            .collect();
        let Some((_, desk_kind)) = desks.first() else {
            return HashMap::new();
        };
        let Some(board) = placed.iter().find(|o| {
            let a = Asset::new(&o.name, &o.category, o.size);
            Knowledge::target_rank(&a, &self.knowledge.kind_of(&a), &desk_kind.rows).is_some()
        }) else {
            return HashMap::new();
        };
        let b = board.footprint();
        let (w, d) = desks.iter().fold((0.0f64, 0.0f64), |(w, d), (a, _)| {
            (w.max(a.size[0]), d.max(a.size[1]))
        });
        // Free depth each desk needs in front for its chair.
        let behind = assets
            .iter()
            .filter(|a| {
                matches!(target_of(plan, &a.name), Some((Relation::InFrontOf, t))
                    if desks.iter().any(|(x, _)| x.name == t))
            })
            .map(|a| a.size[1] + gap(&self.knowledge.kind_of(a)))
            .fold(0.0, f64::max);
        let start = first_row_start(floor, &b);
        let poses = match brief.u_shape {
            true => u_poses(&b, floor.room, [w, d, behind], desks.len(), start),
            false => None,
        }
        .unwrap_or_else(|| row_poses(&b, floor.room, w, d, behind, desks.len(), start));
        // Seats in rows face the board; desks turn their backs to it.
        let turn = if desk_kind.seat { 180.0 } else { 0.0 };
        desks
            .iter()
            .zip(poses)
            .map(|((a, _), p)| {
                let rotation = normalize_degrees(p.rotation + turn);
                (a.name.clone(), Pose { rotation, ..p })
            })
            .collect()
    }
}

/// How far out from the front of board `b` the first row starts: beyond whatever already stands
/// before the board (a teacher's desk), with room to walk, and at least [`ROW_START_MIN_CM`].
fn first_row_start(floor: &Floor<'_>, b: &Footprint) -> f64 {
    let origin = b.front_center();
    floor
        .solid
        .iter()
        .filter(|fp| fp.center.distance(b.center) > 1.0)
        .filter_map(|fp| {
            let (f_lo, f_hi) = extent(fp, origin, b.front);
            let (l_lo, l_hi) = extent(fp, origin, b.right);
            let before_board = f_hi > 0.0
                && f_lo < BEFORE_BOARD_DEPTH_CM
                && l_hi > -b.half.x - BEFORE_BOARD_MARGIN_CM
                && l_lo < b.half.x + BEFORE_BOARD_MARGIN_CM;
            before_board.then_some(f_hi + ROW_START_CLEAR_CM)
        })
        .fold(ROW_START_MIN_CM, f64::max)
}

/// The lowest and highest coordinate of `fp`'s corners along `axis`, measured from `origin`.
fn extent(fp: &Footprint, origin: DVec2, axis: DVec2) -> (f64, f64) {
    let along = fp.corners().map(|c| (c - origin).dot(axis));
    (
        along.iter().copied().fold(f64::INFINITY, f64::min),
        along.iter().copied().fold(f64::NEG_INFINITY, f64::max),
    )
}

/// Poses for `n` desks (`[width, depth, behind]`: their size and the free depth their chairs
/// need in front) in a U open to `board`: a run down each side and one across the far end, every
/// desk's front (where its user sits) turned out of the U, so the seats face into it and the board.
/// The arms start `start` cm out from the board. `None` when the U does not fit the room.
fn u_poses(
    board: &Footprint,
    room: &disco_core::scene::Room,
    size: [f64; 3],
    n: usize,
    start: f64,
) -> Option<Vec<Pose>> {
    let [w, d, behind] = size;
    let b = board;
    let origin = b.front_center();
    let (side, across) = u_runs(n)?;
    let left = distance_to_boundary(room, origin, -b.right);
    let right = distance_to_boundary(room, origin, b.right);
    // The arms close the U at the far end's ends, unless the side walls (with the chairs
    // behind the arms and a walkway behind them) leave less room.
    let closed = across as f64 * w / 2.0 + d / 2.0;
    let arm = closed.min(left.min(right) - behind - d / 2.0 - U_WALKWAY_CM);
    // The arms may start nearer the board than rows would (the U is open to it) when the room
    // is too shallow for them to start at `start`.
    let depth = distance_to_boundary(room, origin, b.front);
    let start = start.min(depth - side as f64 * w - d - behind);
    let far = start + side as f64 * w + d / 2.0;
    let fits = arm * 2.0 >= across as f64 * w + d && start >= U_START_MIN_CM;
    if !fits {
        return None;
    }
    let at = |lateral: f64, out: f64, turn: f64| Pose {
        center: origin + b.right * lateral + b.front * out,
        rotation: normalize_degrees(b.rotation + turn),
    };
    // In a snake, so each desk lines up with the one before it along its run: down the left
    // arm, across the far end, back up the right arm.
    let arm_out = |k: usize| start + w / 2.0 + k as f64 * w;
    let down = (0..side).map(|k| at(-arm, arm_out(k), -90.0));
    let base = (0..across).map(|j| at((j as f64 - (across as f64 - 1.0) / 2.0) * w, far, 0.0));
    let up = (0..side).rev().map(|k| at(arm, arm_out(k), 90.0));
    Some(down.chain(base).chain(up).collect())
}
