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

use crate::hints::{Hint, read_hints};
use crate::knowledge::{Kind, Knowledge, words};
use disco_core::geometry::{Aabb, Footprint};
use disco_core::layout::PlacedObject;
use disco_core::metrics::unreachable_objects;
use disco_core::placement::{Pose, around_slots, relation_poses, row_poses, wall_poses};
use disco_core::plan::{Plan, Relation};
use disco_core::relations::constraints_of;
use disco_core::roles::{DesignRequest, Designer, Output, RoleResult};
use disco_core::scene::{Asset, Room, SceneSpec};

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

/// Raster (cm) of the reach test run on candidate poses: coarser than the metric's, for speed.
const REACH_TEST_CELL_CM: f64 = 10.0;

/// Least distance (cm) from a board to the first row of desks.
const ROW_START_MIN_CM: f64 = 150.0;

/// Free depth (cm) kept between what stands before a board and the first row of desks.
const ROW_START_CLEAR_CM: f64 = 45.0;

/// How many poses of a group's anchor are tried when the first leaves the group short.
const ANCHOR_ALTERNATIVES: usize = 6;

/// How many fitting candidates a placement tests for reach before settling for less.
const REACH_TESTS: usize = 12;

/// What is on the floor so far.
struct Floor<'a> {
    room: &'a Room,
    solid: Vec<Footprint>,
    flat: Vec<Footprint>,
    /// Zones people need in front of objects, which new objects should keep clear of.
    keep_clear: Vec<Aabb>,
    /// Every solid object placed so far, for the reach test.
    objects: Vec<PlacedObject>,
    /// How many of `objects` an agent cannot reach now.
    unreachable: usize,
    /// Where a free-standing anchor of this group should go: its share of the room when several
    /// (tables in a hall) spread over the floor.
    aim: DVec2,
    /// Objects the prompt wants in a corner.
    in_corner: Vec<String>,
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

    /// Adds an object of the group being placed. Its clearance zone is not added: the group's
    /// own dependents stand in it by design (chairs at a desk, a coffee table before a sofa).
    fn add(&mut self, obj: PlacedObject) {
        if obj.is_flat() {
            self.flat.push(obj.footprint());
        } else {
            self.solid.push(obj.footprint());
            self.objects.push(obj);
            self.unreachable =
                unreachable_objects(self.room, &self.objects, REACH_TEST_CELL_CM).len();
        }
    }

    /// Whether `obj` can stand there without walling anything in, itself included.
    fn keeps_reach(&self, obj: PlacedObject) -> bool {
        if obj.is_flat() {
            return true;
        }
        let mut all = self.objects.clone();
        all.push(obj);
        unreachable_objects(self.room, &all, REACH_TEST_CELL_CM).len() <= self.unreachable
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
        let hints = read_hints(scene, &self.knowledge);
        let spot = |want: &Hint| -> Vec<String> {
            hints
                .iter()
                .filter(|h| h.hint == *want)
                .flat_map(|h| h.subjects.iter().map(|&i| scene.assets[i].name.clone()))
                .collect()
        };
        let in_corner = spot(&Hint::Corner);
        let centre_wanted = spot(&Hint::Centre);
        let aim = if assets
            .first()
            .is_some_and(|a| centre_wanted.contains(&a.name))
        {
            DVec2::new(room.width / 2.0, room.depth / 2.0)
        } else {
            spread_aim(scene, plan, assets)
        };
        let mut best: Option<(usize, Vec<PlacedObject>)> = None;
        for alternative in 0..ANCHOR_ALTERNATIVES {
            let Some((cost, out)) =
                self.attempt(room, (aim, &in_corner), plan, assets, placed, alternative)
            else {
                break;
            };
            if best.as_ref().is_none_or(|(c, _)| cost < *c) {
                best = Some((cost, out));
            }
            if cost == 0 {
                break;
            }
        }
        best.map(|(_, out)| out).unwrap_or_default()
    }

    /// One design of the group with the anchor at its `alternative`-th pose, and its cost:
    /// unmet constraints of the group plus three per object newly walled in. `None` when the
    /// anchor has no such alternative.
    fn attempt(
        &self,
        room: &Room,
        (aim, in_corner): (DVec2, &[String]),
        plan: &Plan,
        assets: &[&Asset],
        placed: &[PlacedObject],
        alternative: usize,
    ) -> Option<(usize, Vec<PlacedObject>)> {
        let solid: Vec<PlacedObject> = placed.iter().filter(|o| !o.is_flat()).cloned().collect();
        let mut floor = Floor {
            room,
            solid: solid.iter().map(|o| o.footprint()).collect(),
            flat: placed
                .iter()
                .filter(|o| o.is_flat())
                .map(|o| o.footprint())
                .collect(),
            keep_clear: Vec::new(),
            unreachable: unreachable_objects(room, &solid, REACH_TEST_CELL_CM).len(),
            objects: solid,
            aim,
            in_corner: in_corner.to_vec(),
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
        let walled_in_before = floor.unreachable;
        let mut anchor_done = false;
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

        let rows = self.row_layout(&floor, plan, assets, placed);
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
            let pose: Vec<Pose> = match (rows.get(&asset.name), target) {
                (Some(seat), _) => {
                    let mut cands = vec![*seat];
                    cands.extend(self.place_free(&floor, w, d, kind.clearance, 0.0));
                    cands
                }
                (None, target) => match target {
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
                        cands
                    }
                    Some((rel, _, tfp)) => {
                        let face = c.is_some_and(|c| c.facing.is_some());
                        relation_poses(w, d, rel, &tfp, room, gap(&kind), face)
                    }
                    None if flat => self.place_flat(room, w, d),
                    None if c.is_some_and(|c| c.against_wall) => {
                        self.place_on_wall(&floor, asset, &kind, plan, assets)
                    }
                    None => {
                        // Room for the chairs around it.
                        let ring = assets
                            .iter()
                            .filter(|a| {
                                target_of(plan, &a.name) == Some((Relation::Around, &asset.name))
                            })
                            .map(|a| a.size[1] + gap(&self.knowledge.kind_of(a)))
                            .fold(0.0, f64::max);
                        self.place_free(&floor, w, d, kind.clearance, ring)
                    }
                },
            };
            let is_anchor = target.is_none() && !flat && !anchor_done;
            let obj = if is_anchor {
                anchor_done = true;
                options(&floor, asset, &pose, alternative + 1)
                    .into_iter()
                    .nth(alternative)?
            } else if alternative > 0 && !anchor_done {
                return None;
            } else {
                options(&floor, asset, &pose, 1).remove(0)
            };
            where_is.insert(asset.name.clone(), obj.footprint());
            floor.add(obj.clone());
            out.push(obj);
        }
        if alternative > 0 && !anchor_done {
            return None;
        }
        let find = |n: &str| where_is.get(n).copied();
        let unmet = out
            .iter()
            .flat_map(|o| {
                let fp = o.footprint();
                constraints_of(plan, &o.name)
                    .into_iter()
                    .filter(move |k| !k.holds(&fp, room, find))
            })
            .count();
        let walled_in = floor.unreachable.saturating_sub(walled_in_before);
        Some((unmet + 3 * walled_in, out))
    }

    /// Poses of the group's desks that stand in rows facing a board already placed, by name;
    /// empty when the group has no such desks or the board is not there.
    fn row_layout(
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
            let a = as_asset(o);
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
        // The first row starts beyond whatever already stands before the board (a teacher's
        // desk), with room to walk.
        let origin = b.front_center();
        let start = floor
            .solid
            .iter()
            .filter(|fp| fp.center.distance(b.center) > 1.0)
            .filter_map(|fp| {
                let f: Vec<f64> = fp
                    .corners()
                    .iter()
                    .map(|c| (*c - origin).dot(b.front))
                    .collect();
                let l: Vec<f64> = fp
                    .corners()
                    .iter()
                    .map(|c| (*c - origin).dot(b.right))
                    .collect();
                let (f_lo, f_hi) = (
                    f.iter().copied().fold(f64::INFINITY, f64::min),
                    f.iter().copied().fold(f64::NEG_INFINITY, f64::max),
                );
                let l_lo = l.iter().copied().fold(f64::INFINITY, f64::min);
                let l_hi = l.iter().copied().fold(f64::NEG_INFINITY, f64::max);
                let before_board = f_hi > 0.0
                    && f_lo < 300.0
                    && l_hi > -b.half.x - 100.0
                    && l_lo < b.half.x + 100.0;
                before_board.then_some(f_hi + ROW_START_CLEAR_CM)
            })
            .fold(ROW_START_MIN_CM, f64::max);
        let poses = row_poses(&b, floor.room, w, d, behind, desks.len(), start);
        desks
            .iter()
            .zip(poses)
            .map(|((a, _), p)| (a.name.clone(), p))
            .collect()
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
    ) -> Vec<Pose> {
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
        let in_corner = floor.in_corner.contains(&asset.name);
        let centred = kind.centred && !in_corner;
        let mut scored: Vec<(f64, Pose)> = Vec::new();
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
                disco_core::geometry::Wall::Bottom | disco_core::geometry::Wall::Top
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
                score -= if in_corner {
                    // The prompt asked for a corner: nothing else will do.
                    10.0 * to_end
                } else {
                    to_end.min(neighbour)
                };
            }
            scored.push((score, pose));
        }
        if scored.is_empty() {
            return self.place_free(floor, w, d, kind.clearance, 0.0);
        }
        ranked(scored)
    }

    /// Spots for a free-standing anchor, best first: room all round for a `ring` of chairs,
    /// clearance, closeness to the group's aim; long side along the room's long side.
    fn place_free(
        &self,
        floor: &Floor<'_>,
        w: f64,
        d: f64,
        clearance: f64,
        ring: f64,
    ) -> Vec<Pose> {
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
        let mut scored: Vec<(f64, Pose)> = Vec::new();
        let mut y = h.y;
        while y <= room.depth - h.y + 1e-9 {
            let mut x = h.x;
            while x <= room.width - h.x + 1e-9 {
                let c = DVec2::new(x, y);
                let fp = probe.with_pose(c, rotation);
                if floor.fits(&fp, false) {
                    let free = floor.clearance_of(&fp.aabb()).min(clearance * 1.5);
                    let envelope = Footprint::new(c, w + 2.0 * ring, d + 2.0 * ring, rotation);
                    let penalty = if floor.blocks_clearance(&fp) {
                        100.0
                    } else {
                        0.0
                    } + if ring > 0.0 && !floor.fits(&envelope, false) {
                        300.0
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
                center: centre,
                rotation,
            }];
        }
        ranked(scored)
    }

    /// A floor covering: the room's centre if free, else the nearest free spot.
    fn place_flat(&self, room: &Room, w: f64, d: f64) -> Vec<Pose> {
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
        cands
    }
}

/// Score lost per cm a free-standing anchor stands from its aim.
const AIM_WEIGHT: f64 = 0.1;

/// Where the group's free-standing anchor should go. Free-standing anchors (tables, islands:
/// no wall, no relation) share the room as a grid of equal cells, one each in plan order, so
/// several tables spread over a hall instead of crowding its middle; a lone one aims at the
/// centre.
fn spread_aim(scene: &SceneSpec, plan: &Plan, group: &[&Asset]) -> DVec2 {
    let room = &scene.room;
    let centre = DVec2::new(room.width / 2.0, room.depth / 2.0);
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
        return centre;
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

/// Poses by descending score.
fn ranked(mut scored: Vec<(f64, Pose)>) -> Vec<Pose> {
    scored.sort_by(|a, b| b.0.total_cmp(&a.0));
    scored.into_iter().map(|(_, p)| p).collect()
}

/// Up to `limit` poses for `asset` from `cands` (best first), in order of preference: poses that
/// fit, leave earlier objects' clearance free and wall nothing in; then ones that fit and wall
/// nothing in; then ones that merely fit. When none fits, the first candidate pulled inside the
/// room, for the PRT to settle. Never empty.
fn options(floor: &Floor<'_>, asset: &Asset, cands: &[Pose], limit: usize) -> Vec<PlacedObject> {
    let [w, d, _] = asset.size;
    let flat = asset.is_flat();
    let at = |p: &Pose| PlacedObject {
        name: asset.name.clone(),
        category: asset.category.clone(),
        size: asset.size,
        position: [round1(p.center.x), round1(p.center.y)],
        rotation: round1(p.rotation),
    };
    let fitting: Vec<(&Pose, bool)> = cands
        .iter()
        .filter_map(|p| {
            let fp = Footprint::new(p.center, w, d, p.rotation);
            floor
                .fits(&fp, flat)
                .then(|| (p, !floor.blocks_clearance(&fp)))
        })
        .collect();
    fn take<'c>(picked: &mut Vec<&'c Pose>, p: &'c Pose, limit: usize) {
        if picked.len() < limit && !picked.iter().any(|q| std::ptr::eq(*q, p)) {
            picked.push(p);
        }
    }
    let mut picked: Vec<&Pose> = Vec::new();
    for want_clear in [true, false] {
        for (p, _) in fitting
            .iter()
            .filter(|(_, clear)| *clear || !want_clear)
            .take(REACH_TESTS)
        {
            if picked.len() < limit && floor.keeps_reach(at(p)) {
                take(&mut picked, p, limit);
            }
        }
    }
    for want_clear in [true, false] {
        for (p, _) in fitting.iter().filter(|(_, clear)| *clear || !want_clear) {
            take(&mut picked, p, limit);
        }
    }
    if !picked.is_empty() {
        return picked.into_iter().map(at).collect();
    }
    let p = cands.first().copied().unwrap_or(Pose {
        center: DVec2::new(floor.room.width / 2.0, floor.room.depth / 2.0),
        rotation: 0.0,
    });
    let h = Footprint::new(p.center, w, d, p.rotation).aabb_half();
    let max = (DVec2::new(floor.room.width, floor.room.depth) - h).max(h);
    vec![at(&Pose {
        center: p.center.clamp(h, max),
        rotation: p.rotation,
    })]
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
            scene,
            &req.ctx.plan,
            &assets,
            &req.placed,
        )))
    }
}
