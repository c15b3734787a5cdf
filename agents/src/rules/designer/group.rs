//! One design of a group: its objects placed in dependency order, the anchor at a chosen
//! alternative pose, and what the result costs.

use std::collections::{HashMap, HashSet};

use glam::DVec2;

use super::agent::RuleDesigner;
use super::brief::{GroupBrief, target_of};
use super::choice::options;
use super::draft::{Draft, Seats};
use super::floor::Floor;
use disco_core::geometry::Footprint;
use disco_core::layout::PlacedObject;
use disco_core::placement::Pose;
use disco_core::plan::Plan;
use disco_core::relations::constraints_of;
use disco_core::scene::Asset;

/// How many poses of a group's anchor are tried when the first leaves the group short.
pub(super) const ANCHOR_ALTERNATIVES: usize = 6;

/// What every attempt at one group starts from, made once for all of them.
pub(super) struct Start<'a> {
    /// The floor of [`Floor::for_group`].
    pub(super) floor: Floor<'a>,
    /// Footprint of each object earlier groups placed that a constraint of the group names (the
    /// only ones the group looks up), by name.
    pub(super) where_is: HashMap<&'a str, Footprint>,
    /// The group in placement order.
    pub(super) order: Vec<&'a Asset>,
    /// The anchor's candidate poses when it comes first in `order`: every attempt then asks
    /// for them on the same floor, so they are worked out once (by the first attempt).
    pub(super) anchor_cands: Option<Vec<Pose>>,
    /// The anchor's alternative poses from those candidates, best first, as many as there
    /// are attempts: the first of them is the first attempt's own choice, so they are worked
    /// out once, by the second attempt.
    pub(super) anchor_options: Option<Vec<PlacedObject>>,
}

impl<'a> Start<'a> {
    /// The start of the brief's group on `floor`.
    pub(super) fn new(brief: &GroupBrief<'a>, floor: Floor<'a>) -> Self {
        // Not the whole room: a big one has thousands of objects and a group looks up a few.
        let named: HashSet<&str> = brief
            .group
            .iter()
            .filter_map(|a| brief.plan.constraints.get(&a.name))
            .flat_map(|c| {
                c.relations
                    .iter()
                    .map(|r| r.target.as_str())
                    .chain(c.facing.as_deref())
            })
            .collect();
        let where_is: HashMap<&'a str, Footprint> = brief
            .placed
            .iter()
            .filter(|o| named.contains(o.name.as_str()))
            .map(|o| (o.name.as_str(), o.footprint()))
            .collect();
        let order = placement_order(brief.plan, brief.group, &where_is);
        Start {
            floor,
            where_is,
            order,
            anchor_cands: None,
            anchor_options: None,
        }
    }
}

impl RuleDesigner {
    /// One design of the group with the anchor at its `alternative`-th pose, and its cost:
    /// unmet constraints of the group plus three per object newly walled in. `None` when the
    /// anchor has no such alternative.
    /// `start` is made once for all the attempts; the first keeps the anchor's candidates there.
    /// The attempt places its objects on the start's floor in a trial, taken back at its end.
    pub(super) fn attempt<'a>(
        &self,
        brief: &GroupBrief<'a>,
        start: &mut Start<'a>,
        alternative: usize,
    ) -> Option<(usize, Vec<PlacedObject>)> {
        start.floor.begin_trial();
        let out = self.attempt_in_trial(brief, start, alternative);
        start.floor.roll_back();
        out
    }

    /// [`attempt`](Self::attempt), on the start's floor in a trial.
    fn attempt_in_trial<'a>(
        &self,
        brief: &GroupBrief<'a>,
        start: &mut Start<'a>,
        alternative: usize,
    ) -> Option<(usize, Vec<PlacedObject>)> {
        let floor = &mut start.floor;
        let walled_in_before = floor.unreachable;
        let rows = self.row_layout(floor, brief);
        let mut draft = Draft {
            floor,
            where_is: start.where_is.clone(),
            rows,
            seats: Seats::default(),
            formation: HashMap::new(),
            formations_bent: 0,
            formations_failed: HashSet::new(),
            out: Vec::new(),
        };
        let mut anchor_done = false;
        for &asset in &start.order {
            let target = target_of(brief.plan, &asset.name)
                .and_then(|(rel, t)| draft.where_is.get(t).map(|fp| (rel, t, *fp)));
            let is_anchor = target.is_none() && !asset.is_flat() && !anchor_done;
            let lead_of_formation =
                is_anchor && alternative == 0 && brief.plan.formation_of(&asset.name).is_some();
            let in_formation = if lead_of_formation {
                self.formation_pose(brief, &mut draft, asset)
                    .filter(|p| draft.floor.fits_pose(p, asset.size))
            } else {
                None
            };
            let obj = if let Some(p) = in_formation {
                // The first desk of pods leads its block to where the block fits.
                anchor_done = true;
                placed_at(asset, p)
            } else if is_anchor {
                anchor_done = true;
                // Nothing of the group stands yet when the anchor comes first: its candidates
                // are the same in every attempt.
                let first = draft.out.is_empty();
                if !first || start.anchor_cands.is_none() {
                    let cands = self.candidates(brief, &mut draft, asset, target);
                    let obj = options(draft.floor, asset, &cands, alternative + 1)
                        .into_iter()
                        .nth(alternative);
                    if first {
                        start.anchor_cands = Some(cands);
                    }
                    obj?
                } else {
                    let cands = start.anchor_cands.as_deref().unwrap_or_default();
                    let alternatives = start.anchor_options.get_or_insert_with(|| {
                        options(draft.floor, asset, cands, ANCHOR_ALTERNATIVES)
                    });
                    alternatives.get(alternative)?.clone()
                }
            } else if alternative > 0 && !anchor_done {
                return None;
            } else if let Some(p) = self
                .formation_pose(brief, &mut draft, asset)
                .filter(|p| draft.floor.fits_pose(p, asset.size))
            {
                // A member of a formation takes its place in it whenever that place is free.
                placed_at(asset, p)
            } else {
                let cands = self.candidates(brief, &mut draft, asset, target);
                options(draft.floor, asset, &cands, 1).remove(0)
            };
            draft.where_is.insert(asset.name.as_str(), obj.footprint());
            draft.floor.add(obj.clone());
            draft.out.push(obj);
        }
        if alternative > 0 && !anchor_done {
            return None;
        }
        Some((cost(brief, &draft, walled_in_before), draft.out))
    }
}

/// `asset` at pose `p`.
fn placed_at(asset: &Asset, p: Pose) -> PlacedObject {
    PlacedObject {
        name: asset.name.clone(),
        category: asset.category.clone(),
        size: asset.size,
        position: [p.center.x, p.center.y],
        rotation: disco_core::geometry::normalize_degrees(p.rotation),
        ..Default::default()
    }
}

/// The group in placement order: every target before its dependents. A target counts as ready
/// when it is already on the floor (`placed`), ordered before, or not in the group at all; what a
/// cycle leaves over keeps the group's order.
fn placement_order<'g>(
    plan: &Plan,
    group: &[&'g Asset],
    placed: &HashMap<&str, Footprint>,
) -> Vec<&'g Asset> {
    let mut order: Vec<&Asset> = Vec::new();
    let mut pending: Vec<&Asset> = group.to_vec();
    while !pending.is_empty() {
        let before = pending.len();
        pending.retain(|a| {
            let ready = target_of(plan, &a.name).is_none_or(|(_, t)| {
                placed.contains_key(t)
                    || order.iter().any(|o| o.name == t)
                    || !group.iter().any(|x| x.name == t)
            });
            if ready {
                order.push(a);
            }
            !ready
        });
        if pending.len() == before {
            order.append(&mut pending);
        }
    }
    order
}

/// What a finished design costs: the constraints of its objects left unmet, plus three per
/// object it walled in beyond the `walled_in_before` the floor had.
fn cost(brief: &GroupBrief<'_>, draft: &Draft<'_, '_>, walled_in_before: usize) -> usize {
    let find = |n: &str| draft.where_is.get(n).copied();
    let unmet = draft
        .out
        .iter()
        .flat_map(|o| {
            let fp = o.footprint();
            constraints_of(brief.plan, &o.name)
                .into_iter()
                .filter(move |k| !k.holds(&fp, brief.room, find))
        })
        .count();
    let walled_in = draft.floor.unreachable.saturating_sub(walled_in_before);
    // A member of a formation the room did not let stand in it counts like an unmet constraint.
    let off_formation = draft
        .out
        .iter()
        .filter(|o| {
            draft
                .formation
                .get(&o.name)
                .is_some_and(|p| DVec2::from(o.position).distance(p.center) > 1.0)
        })
        .count();
    unmet + 3 * walled_in + off_formation + draft.formations_bent
}
