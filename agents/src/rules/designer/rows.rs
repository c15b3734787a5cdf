//! Desks in rows: where a group's desks stand when they face a board placed by an earlier group.

use std::collections::HashMap;

use glam::DVec2;

use super::floor::Floor;
use super::{RuleDesigner, gap, target_of};
use crate::knowledge::{Kind, Knowledge};
use disco_core::geometry::Footprint;
use disco_core::layout::PlacedObject;
use disco_core::placement::{Pose, row_poses};
use disco_core::plan::{Plan, Relation};
use disco_core::scene::Asset;

/// Least distance (cm) from a board to the first row of desks.
const ROW_START_MIN_CM: f64 = 150.0;

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
        plan: &Plan,
        assets: &[&Asset],
        placed: &[PlacedObject],
    ) -> HashMap<String, Pose> {
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
        let poses = row_poses(&b, floor.room, w, d, behind, desks.len(), start);
        desks
            .iter()
            .zip(poses)
            .map(|((a, _), p)| (a.name.clone(), p))
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
