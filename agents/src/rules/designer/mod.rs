//! The rule-based designer: constructive placement, group by group.
//!
//! Anchors go on the best free stretch of wall (beds and sofas centred, storage towards corners),
//! leaving room in front and beside them for what depends on them; free-standing anchors (tables,
//! islands) go where they keep the most clearance. Dependents are arranged about their target with
//! the relation's own poses (nightstands on both sides, chairs evenly around, the TV across).
//!
//! The work is split by the decision each part makes: `group` designs one attempt at a group
//! and prices it; `candidates` says which poses each object may take; `wall` and `free`
//! rank the spots of an anchor on a wall or on open floor; `rows` lines desks up before a
//! board; `choice` picks among the candidates; `floor` is what the floor holds meanwhile.

mod candidates;
mod choice;
mod floor;
mod formation;
mod free;
mod group;
mod held;
mod place;
mod reach_cache;
mod rows;
mod wall;
mod wishes;

#[cfg(test)]
mod tests;

use std::borrow::Cow;
use std::sync::Arc;

use async_trait::async_trait;
use glam::DVec2;

use crate::arrangement::{names_u_shape, run_slots};
use crate::knowledge::{Kind, Knowledge};
use disco_core::layout::PlacedObject;
use disco_core::plan::{Plan, Relation};
use disco_core::roles::{DesignRequest, Designer, Output, RoleResult};
use disco_core::scene::{Asset, Room, SceneSpec};

use group::GroupBrief;
use reach_cache::ReachCache;
use wishes::WishCache;

/// How many poses of a group's anchor are tried when the first leaves the group short.
const ANCHOR_ALTERNATIVES: usize = 6;

/// Places a group by the furniture knowledge and the plan.
pub struct RuleDesigner {
    knowledge: Arc<Knowledge>,
    /// The prompt's wishes of the scenes designed lately, read once per scene.
    wishes: WishCache,
    /// The reach of what earlier groups placed, kept for the next group.
    reach: ReachCache,
}

impl RuleDesigner {
    /// A designer over the built-in knowledge.
    pub fn new() -> Self {
        RuleDesigner {
            knowledge: Knowledge::builtin(),
            wishes: WishCache::default(),
            reach: ReachCache::default(),
        }
    }
}

impl Default for RuleDesigner {
    fn default() -> Self {
        Self::new()
    }
}

impl RuleDesigner {
    /// Poses for the group, synchronously: its floor pieces first
    /// ([`design_floor`](Self::design_floor)), then what the plan takes off the floor, on their
    /// supports' tops and on the walls ([`held::place_held`]).
    pub fn design_group(
        &self,
        scene: &SceneSpec,
        plan: &Plan,
        assets: &[&Asset],
        placed: &[PlacedObject],
    ) -> Vec<PlacedObject> {
        let (held, on_floor): (Vec<&Asset>, Vec<&Asset>) = assets
            .iter()
            .partition(|a| plan.support_of(&a.name).is_some());
        let loads = held::load_heights(plan, scene);
        if held.is_empty()
            && loads.is_empty()
            && placed.iter().all(|o| plan.support_of(&o.name).is_none())
        {
            // A room with nothing off the floor (but what the knowledge lifts).
            let mut out = self.design_floor(scene, plan, assets, placed);
            self.lift_onto_walls(&scene.room, &mut out);
            return out;
        }
        // Nothing the plan takes off the floor stands in the floor's way (a whiteboard lifted
        // onto its wall still does: it was placed as a floor piece, with room before it).
        let on_floor_plan = |o: &PlacedObject| plan.support_of(&o.name).is_none();
        let floor_placed: Cow<'_, [PlacedObject]> = if placed.iter().all(on_floor_plan) {
            Cow::Borrowed(placed)
        } else {
            Cow::Owned(
                placed
                    .iter()
                    .filter(|o| on_floor_plan(o))
                    .cloned()
                    .collect(),
            )
        };
        // A piece that will hold others is placed as tall as it will stand with them (a stand
        // with its TV does not go under a window), and keeps its own size.
        let loaded: Vec<Asset> = on_floor
            .iter()
            .map(|a| {
                let mut a = (*a).clone();
                a.size[2] += loads.get(a.name.as_str()).copied().unwrap_or(0.0);
                a
            })
            .collect();
        let loaded_refs: Vec<&Asset> = loaded.iter().collect();
        let mut out = if on_floor.is_empty() {
            Vec::new()
        } else {
            self.design_floor(scene, plan, &loaded_refs, &floor_placed)
        };
        for o in &mut out {
            if let Some(a) = scene.asset(&o.name) {
                o.size = a.size;
            }
        }
        self.lift_onto_walls(&scene.room, &mut out);
        if held.is_empty() {
            return out;
        }
        let mut all: Vec<PlacedObject> = placed.to_vec();
        all.extend(out.iter().cloned());
        out.extend(held::place_held(
            &self.knowledge,
            &scene.room,
            plan,
            &held,
            &all,
        ));
        out
    }

    /// Hangs on its wall each thin piece of `out` whose kind lifts it ([`Kind::lifts`]) and that
    /// stands against a wall: placed like a floor piece (a whiteboard the rows face), it hangs
    /// with its centre at the kind's height.
    fn lift_onto_walls(&self, room: &Room, out: &mut [PlacedObject]) {
        for o in out.iter_mut() {
            let asset = disco_core::scene::Asset::new(&o.name, &o.category, o.size);
            let Some(centre) = self.knowledge.kind_of(&asset).lifts(&asset) else {
                continue;
            };
            if let Some(w) = o.footprint().against_wall(room) {
                o.elevation = (centre - o.size[2] / 2.0).max(0.0);
                o.wall = Some(w.index());
            }
        }
    }

    /// Poses for the floor pieces of a group.
    ///
    /// The group's anchor takes its best pose first; when that leaves a dependent's relation
    /// unmet or walls something in, the next few poses of the anchor are tried and the group
    /// that costs least is kept.
    fn design_floor(
        &self,
        scene: &SceneSpec,
        plan: &Plan,
        assets: &[&Asset],
        placed: &[PlacedObject],
    ) -> Vec<PlacedObject> {
        let room = &scene.room;
        let wishes = self.wishes.get(scene, &self.knowledge);
        let aim = if assets
            .first()
            .is_some_and(|a| wishes.centre.contains(&a.name))
        {
            room_centre(room)
        } else {
            free::spread_aim(scene, plan, assets)
        };
        let runs = run_slots(scene, plan);
        let analysis = room.analysis();
        let brief = GroupBrief {
            room,
            plan,
            group: assets,
            placed,
            aim,
            in_corner: &wishes.in_corner,
            centre: &wishes.centre,
            by_window: &wishes.by_window,
            runs: &runs,
            u_shape: names_u_shape(&scene.prompt, &scene.room),
            analysis: &analysis,
        };
        let (reach, made_of) = self
            .reach
            .take(room, placed, floor::reach_test_cell(room), |o| {
                floor::access_zone(&self.knowledge, o)
            });
        let floor = floor::Floor::for_group(&brief, reach, made_of.access.clone());
        let mut start = group::Start::new(&brief, floor);
        let mut best: Option<(usize, Vec<PlacedObject>)> = None;
        for alternative in 0..ANCHOR_ALTERNATIVES {
            let Some((cost, out)) = self.attempt(&brief, &mut start, alternative) else {
                break;
            };
            if best.as_ref().is_none_or(|(c, _)| cost < *c) {
                best = Some((cost, out));
            }
            if cost == 0 {
                break;
            }
        }
        self.reach.put_back(start.floor.into_reach(), made_of);
        best.map(|(_, out)| out).unwrap_or_default()
    }
}

/// The distance (cm) a dependent of `kind` keeps from its target.
fn gap(kind: &Kind) -> f64 {
    kind.relate.as_ref().map_or(10.0, |r| r.gap)
}

/// The first relation of `name` in the plan, as (relation, target).
fn target_of<'p>(plan: &'p Plan, name: &str) -> Option<(Relation, &'p str)> {
    plan.constraints
        .get(name)
        .and_then(|c| c.relations.first())
        .map(|r| (r.relation, r.target.as_str()))
}

/// The members of `group` whose first relation in the plan is `relation` to `target`.
fn dependents<'a>(
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
fn room_centre(room: &Room) -> DVec2 {
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
fn long_side_rotation(room: &Room, w: f64, d: f64) -> f64 {
    if (room.width >= room.depth) == (w >= d) {
        0.0
    } else {
        90.0
    }
}

#[async_trait]
impl Designer for RuleDesigner {
    async fn design(&self, req: &DesignRequest) -> RoleResult<Vec<PlacedObject>> {
        let scene = &req.ctx.scene;
        let assets: Vec<&Asset> = req.group.iter().filter_map(|n| scene.asset(n)).collect();
        Ok(Output::free(self.design_group(
            scene,
            &req.ctx.plan,
            &assets,
            &req.placed,
        )))
    }
}
