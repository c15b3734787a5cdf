//! The `grid-search` designer: the Holodeck-shaped baseline, inside our runtime.
//!
//! Holodeck places floor objects with a constraint solver: every object, one at a time in order,
//! is tried at the cells of a grid over the room in four rotations; candidates that leave the room
//! or overlap what is placed are refused (hard constraints), the rest are scored on the soft
//! constraints (distance, direction, alignment to the objects they relate to), and the best one
//! is kept. Objects that must stand against a wall are only tried along the walls, facing in.
//! The search has a time budget; what it has not placed when the budget runs out is left out,
//! and the runtime drops it (or parks it for a PRT, if the graph has one).
//!
//! This is our own greedy reading of that shape, not Holodeck's code: no backtracking, and the
//! constraints are the plan's, checked with the same predicates as the metrics.
//!
//! ```toml
//! [agents.designer]
//! impl = "grid-search"
//! options = { cell_cm = 25, time_limit_ms = 2000, seed = 0 }
//! ```

use std::collections::HashMap;
use std::time::{Duration, Instant};

use async_trait::async_trait;
use glam::DVec2;

use disco_core::geometry::{Footprint, Wall};
use disco_core::layout::PlacedObject;
use disco_core::plan::{Plan, Relation};
use disco_core::relations::{ConstraintKind, constraints_of};
use disco_core::roles::{DesignRequest, Designer, Output, RoleResult};
use disco_core::scene::{Asset, Room, SceneSpec};

/// Score of one met constraint.
const MET: f64 = 1.0;
/// Bonus for a centre aligned with a related object's, on either axis.
const ALIGNED: f64 = 0.2;
/// Weight of closeness to related objects (per room diagonal).
const CLOSE: f64 = 0.5;

/// Object-by-object grid search with constraint scoring.
pub struct GridSearchDesigner {
    cell_cm: f64,
    time_limit: Duration,
    seed: u64,
}

impl GridSearchDesigner {
    /// The keys its `options` table may hold.
    pub const OPTIONS: &'static [&'static str] = &["cell_cm", "time_limit_ms", "seed"];

    /// A designer with `cell_cm` (default 25), `time_limit_ms` per design call (default 2000) and
    /// `seed` (default 0, shuffles ties) from the agent's `options`.
    pub fn from_options(options: &toml::Table) -> Result<Self, String> {
        use super::options::{number, only_known};
        only_known(options, Self::OPTIONS)?;
        Ok(GridSearchDesigner {
            cell_cm: number(options, "cell_cm", 25.0, 1.0)?,
            time_limit: Duration::from_millis(number(options, "time_limit_ms", 2000.0, 0.0)? as u64),
            seed: number(options, "seed", 0.0, 0.0)? as u64,
        })
    }

    /// Poses for `group`, given what is already `placed`; objects it finds no cell for (or has
    /// no time left for) are missing from the answer.
    pub fn search(
        &self,
        scene: &SceneSpec,
        plan: &Plan,
        group: &[String],
        placed: &[PlacedObject],
    ) -> Vec<PlacedObject> {
        let started = Instant::now();
        let room = &scene.room;
        let mut rng = fastrand::Rng::with_seed(self.seed);
        let mut at: HashMap<String, Footprint> = placed
            .iter()
            .map(|o| (o.name.clone(), o.footprint()))
            .collect();
        let mut solid: Vec<Footprint> = placed
            .iter()
            .filter(|o| !o.is_flat())
            .map(|o| o.footprint())
            .collect();
        let mut flat: Vec<Footprint> = placed
            .iter()
            .filter(|o| o.is_flat())
            .map(|o| o.footprint())
            .collect();
        let mut out = Vec::new();
        for asset in search_order(scene, plan, group) {
            if started.elapsed() >= self.time_limit {
                break;
            }
            let wants_wall = plan.wants_wall(&asset.name);
            let mut candidates = self.candidates(room, asset, wants_wall);
            rng.shuffle(&mut candidates);
            let others = if asset.is_flat() { &flat } else { &solid };
            let kinds = constraints_of(plan, &asset.name);
            let best = candidates
                .into_iter()
                .filter(|fp| fp.area_outside(room) < 1.0)
                .filter(|fp| {
                    let bb = fp.aabb();
                    !others
                        .iter()
                        .any(|o| o.aabb().interiors_meet(&bb) && fp.collides(o))
                })
                .map(|fp| (score(&fp, room, &kinds, &at), fp))
                .max_by(|a, b| a.0.total_cmp(&b.0));
            let Some((_, fp)) = best else { continue };
            if asset.is_flat() {
                flat.push(fp);
            } else {
                solid.push(fp);
            }
            at.insert(asset.name.clone(), fp);
            out.push(PlacedObject {
                name: asset.name.clone(),
                category: asset.category.clone(),
                size: asset.size,
                position: [fp.center.x, fp.center.y],
                rotation: fp.rotation,
                ..Default::default()
            });
        }
        out
    }

    /// Against-wall objects: along each wall, facing in. Others: every grid cell, four rotations.
    fn candidates(&self, room: &Room, asset: &Asset, wants_wall: bool) -> Vec<Footprint> {
        let [w, d, h] = asset.size;
        let step = self.cell_cm;
        let mut out = Vec::new();
        if wants_wall {
            for wall in Wall::all(room) {
                let rot = wall.inward_rotation();
                let Some(slot) = wall.slot(room, DVec2::new(w, d) / 2.0, h) else {
                    continue;
                };
                for &(lo, hi) in &slot.stretches {
                    let mut along = lo;
                    while along <= hi + 1e-9 {
                        out.push(Footprint::new(slot.point(along), w, d, rot));
                        along += step;
                    }
                }
            }
            return out;
        }
        for rot in [0.0, 90.0, 180.0, 270.0] {
            let half = Footprint::new(DVec2::ZERO, w, d, rot).aabb_half();
            let mut y = half.y;
            while y <= room.depth - half.y + 1e-9 {
                let mut x = half.x;
                while x <= room.width - half.x + 1e-9 {
                    out.push(Footprint::new(DVec2::new(x, y), w, d, rot));
                    x += step;
                }
                y += step;
            }
        }
        out
    }
}

/// The group's assets, each after the objects it relates to (when those are in the group), the
/// larger first among the ready ones: big pieces claim space before small ones fill it.
fn search_order<'s>(scene: &'s SceneSpec, plan: &Plan, group: &[String]) -> Vec<&'s Asset> {
    let mut pending: Vec<&Asset> = group.iter().filter_map(|n| scene.asset(n)).collect();
    pending.sort_by(|a, b| (b.size[0] * b.size[1]).total_cmp(&(a.size[0] * a.size[1])));
    let targets = |a: &Asset| -> Vec<String> {
        constraints_of(plan, &a.name)
            .into_iter()
            .filter_map(|k| match k {
                ConstraintKind::Relation { target, .. } | ConstraintKind::Facing { target } => {
                    Some(target)
                }
                ConstraintKind::AgainstWall | ConstraintKind::Place(_) => None,
            })
            .collect()
    };
    let mut order: Vec<&Asset> = Vec::new();
    while !pending.is_empty() {
        let ready = pending.iter().position(|a| {
            targets(a).iter().all(|t| {
                order.iter().any(|o| &o.name == t) || !pending.iter().any(|p| &p.name == t)
            })
        });
        // A cycle of relations: take the largest and go on.
        order.push(pending.remove(ready.unwrap_or(0)));
    }
    order
}

/// Soft score of a candidate: met constraints, closeness to and alignment with related objects.
fn score(
    fp: &Footprint,
    room: &Room,
    kinds: &[ConstraintKind],
    at: &HashMap<String, Footprint>,
) -> f64 {
    let diagonal = room.width.hypot(room.depth);
    let find = |n: &str| at.get(n).copied();
    let mut s = 0.0;
    for kind in kinds {
        if kind.holds(fp, room, find) {
            s += MET;
        }
        let target = match kind {
            ConstraintKind::Relation { relation, target } if *relation != Relation::Opposite => {
                target
            }
            ConstraintKind::Facing { target } => target,
            _ => continue,
        };
        if let Some(t) = find(target) {
            s -= CLOSE * fp.gap(&t) / diagonal;
            let d = fp.center - t.center;
            if d.x.abs() < 1.0 || d.y.abs() < 1.0 {
                s += ALIGNED;
            }
        }
    }
    s
}

#[async_trait]
impl Designer for GridSearchDesigner {
    async fn design(&self, req: &DesignRequest) -> RoleResult<Vec<PlacedObject>> {
        let scene = std::sync::Arc::clone(&req.ctx.scene);
        let plan = std::sync::Arc::clone(&req.ctx.plan);
        let group = req.group.clone();
        let placed = req.placed.clone();
        let me = GridSearchDesigner {
            cell_cm: self.cell_cm,
            time_limit: self.time_limit,
            seed: self.seed,
        };
        // Seconds of CPU: off the async workers.
        let poses = tokio::task::spawn_blocking(move || me.search(&scene, &plan, &group, &placed))
            .await
            .map_err(|e| {
                disco_core::roles::RoleError::Failed(format!("grid search panicked: {e}"))
            })?;
        Ok(Output::free(poses))
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use disco_core::layout::Layout;
    use disco_core::plan::{ObjectConstraints, RelationSpec};

    fn scene() -> SceneSpec {
        serde_json::from_str(
            r#"{"id": "t", "prompt": "a dining room", "room_type": "dining room",
                "room": {"width": 400, "depth": 300},
                "assets": [{"name": "table", "category": "table", "size": [160, 90, 75]},
                           {"name": "chair", "category": "chair", "size": [45, 50, 90]},
                           {"name": "cabinet", "category": "cabinet", "size": [120, 45, 90]}]}"#,
        )
        .unwrap()
    }

    fn plan() -> Plan {
        let mut plan = Plan::default();
        plan.constraints.insert(
            "chair".into(),
            ObjectConstraints {
                relations: vec![RelationSpec {
                    relation: Relation::Around,
                    target: "table".into(),
                }],
                facing: Some("table".into()),
                ..Default::default()
            },
        );
        plan.constraints.insert(
            "cabinet".into(),
            ObjectConstraints {
                against_wall: true,
                ..Default::default()
            },
        );
        plan.groups = vec![vec!["chair".into(), "table".into(), "cabinet".into()]];
        plan
    }

    #[test]
    fn places_everything_inside_without_overlap_and_meets_the_constraints() {
        let scene = scene();
        let plan = plan();
        let designer = GridSearchDesigner::from_options(&toml::Table::new()).unwrap();
        let objects = designer.search(&scene, &plan, &plan.groups[0], &[]);
        assert_eq!(objects.len(), 3);
        let layout = Layout {
            id: "t".into(),
            room: scene.room,
            objects,
            dropped: vec![],
            plan: plan.into(),
            stats: Default::default(),
        };
        let m = disco_core::metrics::measure(&layout);
        assert_eq!(m.collision_pct, 0.0);
        assert_eq!(m.oob_pct, 0.0);
        assert_eq!(m.constraint_pct, 100.0, "unmet: {:?}", m.unmet);
    }

    #[test]
    fn leaves_out_what_fits_nowhere_and_stops_at_the_time_limit() {
        let mut scene = scene();
        // A second table as big as the free floor: no cell is left for it.
        scene.assets.push(Asset {
            size: [390.0, 200.0, 75.0],
            ..scene.assets[0].clone()
        });
        scene.assets[3].name = "huge".into();
        let plan = plan();
        let group: Vec<String> = scene.assets.iter().map(|a| a.name.clone()).collect();
        let designer = GridSearchDesigner::from_options(&toml::Table::new()).unwrap();
        let objects = designer.search(&scene, &plan, &group, &[]);
        assert!(objects.len() < 4, "everything was placed: {objects:?}");
        let mut options = toml::Table::new();
        options.insert("time_limit_ms".into(), toml::Value::Integer(0));
        let out_of_time = GridSearchDesigner::from_options(&options).unwrap();
        assert!(
            out_of_time
                .search(&scene, &plan, &plan.groups[0], &[])
                .is_empty()
        );
        assert!(GridSearchDesigner::from_options(&toml::from_str("cells = 3").unwrap()).is_err());
    }
}
