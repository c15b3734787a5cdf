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
mod place;
mod reach_cache;
mod rows;
mod wall;
mod wishes;

#[cfg(test)]
mod tests;

use async_trait::async_trait;

use crate::arrangement::{names_u_shape, run_slots};
use disco_core::layout::PlacedObject;
use disco_core::plan::Plan;
use disco_core::roles::{DesignRequest, Designer, Output, RoleResult};
use disco_core::scene::{Asset, SceneSpec};

pub use agent::RuleDesigner;
use brief::{GroupBrief, room_centre};
use group::ANCHOR_ALTERNATIVES;

impl RuleDesigner {
    /// Poses for the group, synchronously.
    ///
    /// The group's anchor takes its best pose first; when that leaves a dependent's relation
    /// unmet or walls something in, the next few poses of the anchor are tried and the group
    /// that costs least is kept.
    pub fn design_group(
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
