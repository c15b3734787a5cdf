//! The rule-based designer: constructive placement, group by group.
//!
//! Anchors go on the best free stretch of wall (beds and sofas centred, storage towards corners),
//! leaving room in front and beside them for what depends on them; free-standing anchors (tables,
//! islands) go where they keep the most clearance. Dependents are arranged about their target with
//! the relation's own poses (nightstands on both sides, chairs evenly around, the TV across).

use std::collections::HashMap;
use std::sync::Arc;

use async_trait::async_trait;
use glam::DVec2;

use super::placement::{Pose, around_slots, relation_poses, wall_poses};
use crate::agents::knowledge::{Kind, Knowledge, words};
use crate::geometry::{Aabb, Footprint};
use crate::layout::PlacedObject;
use crate::plan::{Plan, Relation};
use crate::roles::{DesignRequest, Designer, Output, RoleResult};
use crate::scene::{Asset, Room};

/// Depth (cm) kept free in front of every object of an earlier group, so people can reach it.
const MIN_ACCESS_CM: f64 = 45.0;

/// Places a group by the furniture knowledge and the plan.
pub struct RuleDesigner {
    knowledge: Arc<Knowledge>,
}

impl RuleDesigner {
    /// A designer over the built-in knowledge.
    pub fn new() -> Self {
        RuleDesigner {
            knowledge: Knowledge::builtin(),
        }
    }
}

impl Default for RuleDesigner {
    fn default() -> Self {
        Self::new()
    }
}

/// What is on the floor so far.
struct Floor<'a> {
    room: &'a Room,
    solid: Vec<Footprint>,
    flat: Vec<Footprint>,
    /// Zones people need in front of objects, which new objects should keep clear of.
    keep_clear: Vec<Aabb>,
}

impl Floor<'_> {
    fn fits(&self, fp: &Footprint, flat: bool) -> bool {
        let others = if flat { &self.flat } else { &self.solid };
        fp.inside(self.room) && !others.iter().any(|o| o.collides(fp))
    }

    fn blocks_clearance(&self, fp: &Footprint) -> bool {
        let b = fp.aabb();
        self.keep_clear.iter().any(|z| z.overlap_area(&b) > 1.0)
    }

    /// Adds a footprint of the group being placed. Its clearance zone is not added: the group's
    /// own dependents stand in it by design (chairs at a desk, a coffee table before a sofa).
    fn add(&mut self, fp: Footprint, flat: bool) {
        if flat {
            self.flat.push(fp);
        } else {
            self.solid.push(fp);
        }
    }

    /// Free distance around `b`: to the walls and to every solid object.
    fn clearance_of(&self, b: &Aabb) -> f64 {
        let walls = b
            .min
            .x
            .min(b.min.y)
            .min(self.room.width - b.max.x)
            .min(self.room.depth - b.max.y);
        self.solid
            .iter()
            .map(|o| o.aabb().gap(b))
            .fold(walls, f64::min)
    }
}

impl RuleDesigner {
    /// Poses for the group, synchronously.
    pub fn design_group(
        &self,
        room: &Room,
        plan: &Plan,
        assets: &[&Asset],
        placed: &[PlacedObject],
    ) -> Vec<PlacedObject> {
        let mut floor = Floor {
            room,
            solid: placed
                .iter()
                .filter(|o| !o.is_flat())
                .map(|o| o.footprint())
                .collect(),
            flat: placed
                .iter()
                .filter(|o| o.is_flat())
                .map(|o| o.footprint())
                .collect(),
            keep_clear: Vec::new(),
        };
        // Earlier groups keep the floor in front of them free: their kind's clearance, and at
        // least room for a person to reach them.
        for o in placed.iter().filter(|o| !o.is_flat()) {
            let clearance = self
                .knowledge
                .kind_of(&as_asset(o))
                .clearance
                .max(MIN_ACCESS_CM);
            let fp = o.footprint();
            let z = Footprint::new(
                fp.front_center() + fp.front * (clearance / 2.0),
                fp.half.x * 2.0,
                clearance,
                fp.rotation,
            );
            floor.keep_clear.push(z.aabb());
        }
        let mut where_is: HashMap<String, Footprint> = placed
            .iter()
            .map(|o| (o.name.clone(), o.footprint()))
            .collect();

        // Targets before their dependents.
        let mut order: Vec<&Asset> = Vec::new();
        let mut pending: Vec<&Asset> = assets.to_vec();
        while !pending.is_empty() {
            let before = pending.len();
            pending.retain(|a| {
                let ready = target_of(plan, &a.name).is_none_or(|(_, t)| {
                    where_is.contains_key(t)
                        || order.iter().any(|o| o.name == t)
                        || !assets.iter().any(|x| x.name == t)
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

        // Seats for chairs around each table, assigned in order.
        let mut seats: HashMap<String, Vec<Pose>> = HashMap::new();
        let mut out = Vec::new();
        for asset in order {
            let kind = self.knowledge.kind_of(asset);
            let c = plan.constraints.get(&asset.name);
            let [w, d, _] = asset.size;
            let flat = asset.is_flat();
            let target = target_of(plan, &asset.name)
                .and_then(|(rel, t)| where_is.get(t).map(|fp| (rel, t, *fp)));
            let pose = match target {
                Some((Relation::Around, t, tfp)) => {
                    let list = seats.entry(t.to_string()).or_insert_with(|| {
                        let n = assets
                            .iter()
                            .filter(|a| target_of(plan, &a.name) == Some((Relation::Around, t)))
                            .count();
                        let round = placed
                            .iter()
                            .chain(out.iter())
                            .find(|o| o.name == t)
                            .is_some_and(|o| {
                                words(&o.category).contains("round")
                                    || (o.size[0] - o.size[1]).abs() < 1.0
                            });
                        around_slots(&tfp, round, w, d, n, gap(&kind))
                            .into_iter()
                            .rev()
                            .collect()
                    });
                    let seat = list.pop();
                    let mut cands: Vec<Pose> = seat.into_iter().collect();
                    cands.extend(relation_poses(
                        w,
                        d,
                        Relation::Around,
                        &tfp,
                        room,
                        gap(&kind),
                        true,
                    ));
                    self.first_fitting(&floor, w, d, flat, &cands)
                }
                Some((rel, _, tfp)) => {
                    let face = c.is_some_and(|c| c.facing.is_some());
                    let cands = relation_poses(w, d, rel, &tfp, room, gap(&kind), face);
                    self.first_fitting(&floor, w, d, flat, &cands)
                }
                None if flat => self.place_flat(&floor, w, d),
                None if c.is_some_and(|c| c.against_wall) => {
                    self.place_on_wall(&floor, asset, &kind, plan, assets)
                }
                None => self.place_free(&floor, w, d, kind.clearance),
            };
            let fp = Footprint::new(pose.center, w, d, pose.rotation);
            floor.add(fp, flat);
            where_is.insert(asset.name.clone(), fp);
            out.push(PlacedObject {
                name: asset.name.clone(),
                category: asset.category.clone(),
                size: asset.size,
                position: [round1(pose.center.x), round1(pose.center.y)],
                rotation: round1(pose.rotation),
            });
        }
        out
    }

    /// The first candidate that fits without collision, preferring ones that leave others'
    /// clearance free; otherwise the first candidate pulled inside the room.
    fn first_fitting(&self, floor: &Floor<'_>, w: f64, d: f64, flat: bool, cands: &[Pose]) -> Pose {
        let fps: Vec<(Pose, Footprint)> = cands
            .iter()
            .map(|p| (*p, Footprint::new(p.center, w, d, p.rotation)))
            .collect();
        fps.iter()
            .find(|(_, fp)| floor.fits(fp, flat) && !floor.blocks_clearance(fp))
            .or_else(|| fps.iter().find(|(_, fp)| floor.fits(fp, flat)))
            .map(|(p, _)| *p)
            .unwrap_or_else(|| {
                let p = cands.first().copied().unwrap_or(Pose {
                    center: DVec2::new(floor.room.width / 2.0, floor.room.depth / 2.0),
                    rotation: 0.0,
                });
                let h = Footprint::new(p.center, w, d, p.rotation).aabb_half();
                let max = (DVec2::new(floor.room.width, floor.room.depth) - h).max(h);
                Pose {
                    center: p.center.clamp(h, max),
                    rotation: p.rotation,
                }
            })
    }

    /// The best wall stretch for an anchor, with room beside it for its side dependents and in
    /// front for its clearance.
    fn place_on_wall(
        &self,
        floor: &Floor<'_>,
        asset: &Asset,
        kind: &Kind,
        plan: &Plan,
        group: &[&Asset],
    ) -> Pose {
        let [w, d, _] = asset.size;
        // Width its dependents need beside it: on both sides (side_of), or on one side (near).
        let need = |rel: Relation| {
            group
                .iter()
                .filter(|a| target_of(plan, &a.name) == Some((rel, asset.name.as_str())))
                .map(|a| a.size[0].max(a.size[1]) + 10.0)
                .fold(0.0, f64::max)
        };
        let (both_sides, one_side) = (need(Relation::SideOf), need(Relation::Near));
        let centred = kind.priority >= 90;
        let mut best: Option<(f64, Pose)> = None;
        for (wall, pose) in wall_poses(floor.room, w, d, 10.0) {
            let fp = Footprint::new(pose.center, w, d, pose.rotation);
            if !floor.fits(&fp, false) {
                continue;
            }
            let mut score = 0.0;
            if floor.blocks_clearance(&fp) {
                score -= 500.0;
            }
            let free = |lateral: f64, extra: f64| {
                let env = Footprint::new(
                    fp.center + fp.front * (kind.clearance / 2.0) + fp.right * lateral,
                    w + extra,
                    d + kind.clearance,
                    fp.rotation,
                )
                .aabb();
                let room_box = Aabb {
                    min: DVec2::ZERO,
                    max: DVec2::new(floor.room.width, floor.room.depth),
                };
                env.overlap_area(&room_box) >= env.area() - 1.0
                    && !floor
                        .solid
                        .iter()
                        .any(|o| o.aabb().overlap_area(&env) > 1.0)
            };
            let env_free = free(0.0, 2.0 * both_sides)
                && (one_side == 0.0
                    || free(one_side / 2.0, one_side)
                    || free(-one_side / 2.0, one_side));
            if !env_free {
                score -= 200.0;
            }
            let len = wall.length(floor.room);
            let along = if matches!(
                wall,
                crate::geometry::Wall::Bottom | crate::geometry::Wall::Top
            ) {
                pose.center.x
            } else {
                pose.center.y
            };
            let from_mid = (along - len / 2.0).abs();
            if centred {
                score -= from_mid;
                score += len * 0.2;
            } else {
                // Towards a corner or flush with a neighbour: compact, leaving open floor.
                let to_end = (len / 2.0 - from_mid) - w / 2.0;
                let neighbour = floor
                    .solid
                    .iter()
                    .map(|o| o.aabb().gap(&fp.aabb()))
                    .fold(f64::INFINITY, f64::min);
                score -= to_end.min(neighbour);
            }
            if best.is_none_or(|(s, _)| score > s) {
                best = Some((score, pose));
            }
        }
        best.map(|(_, p)| p)
            .unwrap_or_else(|| self.place_free(floor, w, d, kind.clearance))
    }

    /// The spot that keeps the most clearance around a free-standing anchor, long side along the
    /// room's long side.
    fn place_free(&self, floor: &Floor<'_>, w: f64, d: f64, clearance: f64) -> Pose {
        let room = floor.room;
        let rotation = if (room.width >= room.depth) == (w >= d) {
            0.0
        } else {
            90.0
        };
        let probe = Footprint::new(DVec2::ZERO, w, d, rotation);
        let h = probe.aabb_half();
        let step = (room.width.max(room.depth) / 80.0).max(10.0);
        let centre = DVec2::new(room.width / 2.0, room.depth / 2.0);
        let mut best: Option<(f64, Pose)> = None;
        let mut y = h.y;
        while y <= room.depth - h.y + 1e-9 {
            let mut x = h.x;
            while x <= room.width - h.x + 1e-9 {
                let c = DVec2::new(x, y);
                let fp = probe.with_pose(c, rotation);
                if floor.fits(&fp, false) {
                    let free = floor.clearance_of(&fp.aabb()).min(clearance * 1.5);
                    let score = free
                        - 0.01 * c.distance(centre)
                        - if floor.blocks_clearance(&fp) {
                            100.0
                        } else {
                            0.0
                        };
                    if best.is_none_or(|(s, _)| score > s) {
                        best = Some((
                            score,
                            Pose {
                                center: c,
                                rotation,
                            },
                        ));
                    }
                }
                x += step;
            }
            y += step;
        }
        best.map(|(_, p)| p).unwrap_or(Pose {
            center: centre,
            rotation,
        })
    }

    /// A floor covering: the room's centre if free, else the nearest free spot.
    fn place_flat(&self, floor: &Floor<'_>, w: f64, d: f64) -> Pose {
        let room = floor.room;
        let rotation = if (room.width >= room.depth) == (w >= d) {
            0.0
        } else {
            90.0
        };
        let centre = DVec2::new(room.width / 2.0, room.depth / 2.0);
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
        self.first_fitting(floor, w, d, true, &cands)
    }
}

fn round1(v: f64) -> f64 {
    (v * 10.0).round() / 10.0
}

fn gap(kind: &Kind) -> f64 {
    kind.relate.as_ref().map_or(10.0, |r| r.gap)
}

fn as_asset(o: &PlacedObject) -> Asset {
    Asset {
        name: o.name.clone(),
        category: o.category.clone(),
        size: o.size,
        mesh: None,
        description: None,
    }
}

/// The first relation of `name` in the plan, as (relation, target).
fn target_of<'p>(plan: &'p Plan, name: &str) -> Option<(Relation, &'p str)> {
    plan.constraints
        .get(name)
        .and_then(|c| c.relations.first())
        .map(|r| (r.relation, r.target.as_str()))
}

#[async_trait]
impl Designer for RuleDesigner {
    async fn design(&self, req: &DesignRequest) -> RoleResult<Vec<PlacedObject>> {
        let scene = &req.ctx.scene;
        let assets: Vec<&Asset> = req.group.iter().filter_map(|n| scene.asset(n)).collect();
        Ok(Output::free(self.design_group(
            &scene.room,
            &req.ctx.plan,
            &assets,
            &req.placed,
        )))
    }
}
