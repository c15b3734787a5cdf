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
//! board; `formation` lays out a plan's formations; `choice` picks among the candidates;
//! `floor` is what the floor holds meanwhile and `draft` a design in progress. What they all
//! share (the group's brief, the plan's lookups, the room's middle) is in `brief`, and the
//! designer itself in `agent`: both import no other part, so the parts' imports form no circle
//! (this file uses the parts; no part uses this file).

mod agent;
mod brief;
mod candidates;
mod choice;
mod draft;
mod floor;
mod formation;
mod free;
mod group;
mod held;
mod letter;
mod place;
mod reach_cache;
mod rows;
mod wall;
mod wishes;

#[cfg(test)]
mod tests;

use std::borrow::Cow;

use async_trait::async_trait;

use crate::arrangement::{names_u_shape, run_slots};
use disco_core::layout::PlacedObject;
use disco_core::plan::Plan;
use disco_core::roles::{DesignRequest, Designer, Output, RoleResult};
use disco_core::scene::{Asset, Room, SceneSpec};

pub use agent::RuleDesigner;
use brief::{GroupBrief, room_centre};
use group::ANCHOR_ALTERNATIVES;

impl RuleDesigner {
    /// Poses for the group, synchronously: its floor pieces first, then what the plan takes off
    /// the floor, on their supports' tops and on the walls.
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
        let loads = held::load_heights(plan, scene, &on_floor);
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
            if let Some(a) = on_floor.iter().find(|a| a.name == o.name) {
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
        // A group whose anchor, or a piece gathered round it, is wished in the middle ("two
        // armchairs in the middle of the room with a table between them") aims there.
        let aim = if assets.iter().any(|a| wishes.centre.contains(&a.name)) {
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
            centred_on_wall: &wishes.centred_on_wall,
            window_by_door: &wishes.window_by_door,
            runs: &runs,
            u_shape: names_u_shape(&scene.prompt, &scene.room),
            analysis: &analysis,
            rows_wall: &wishes.rows_wall,
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
