//! The Semantic Refinement Tool, rule-based: for each failed constraint, the smallest pose change
//! that satisfies it without breaking another constraint of the same object; among moves as
//! good, in a room with a door, one that walls nothing in (itself included) that a person could
//! reach before. A place the plan asks for (a zone, a wall's role, the far corner, under a
//! window, by the entrance) is repaired like a relation: the nearest pose that meets it.

use async_trait::async_trait;
use glam::DVec2;

use disco_core::geometry::{Footprint, Wall, nearest_wall};
use disco_core::layout::{Layout, PlacedObject};
use disco_core::metrics::{REACH_CELL_CM, ReachMap};
use disco_core::placement::{Pose, facing_rotation, relation_poses, snap90};
use disco_core::plan::Place;
use disco_core::relations::{ConstraintKind, check_one, constraints_of, placed_as_asked_in};
use disco_core::roles::{Output, RoleResult, SemanticRefiner, SrtRequest};

/// Repairs failed constraints with minimal moves and turns.
pub struct RuleSrt;

impl RuleSrt {
    /// The objects it moves, with their new poses.
    pub fn repair(&self, req: &SrtRequest) -> Vec<PlacedObject> {
        let mut layout = req.layout.clone();
        layout.plan = std::sync::Arc::clone(&req.ctx.plan);
        let mut changed: Vec<String> = Vec::new();
        for (q, _) in &req.failed {
            let (Some(subject), Some(kind)) = (&q.subject, &q.constraint) else {
                continue;
            };
            if !req.movable.contains(subject) || check_one(&layout, subject, kind) {
                continue;
            }
            // A member of a formation keeps its place in it: moving one alone would break the
            // shape the designer laid out as a whole.
            if layout.plan.formation_of(subject).is_some() {
                continue;
            }
            let Some(obj) = layout.object(subject).cloned() else {
                continue;
            };
            // A piece off the floor (on a top, on a wall) is the designer's to pose and the
            // PRT's to hold up: it is not moved about the floor.
            if !obj.on_floor() || layout.plan.support_of(subject).is_some() {
                continue;
            }
            let cands = candidates(&layout, &obj, kind);
            let unmet_now = unmet(&layout, subject);
            let mut ranked: Vec<(usize, bool, f64, Pose)> = cands
                .into_iter()
                .map(|p| {
                    let mut trial = layout.clone();
                    set_pose(&mut trial, subject, p);
                    let fp = trial.object(subject).map(PlacedObject::footprint);
                    let collides = fp.is_some_and(|fp| {
                        !fp.inside(&trial.room)
                            || trial.objects.iter().any(|o| {
                                o.name != *subject
                                    && o.on_floor()
                                    && !o.is_flat()
                                    && !obj.is_flat()
                                    && o.footprint().collides(&fp)
                            })
                    });
                    let cost = DVec2::from(obj.position).distance(p.center)
                        + angle_between(obj.rotation, p.rotation) * 0.5;
                    (unmet(&trial, subject), collides, cost, p)
                })
                .filter(|(after, ..)| *after < unmet_now)
                .collect();
            ranked.sort_by(|a, b| (a.0, a.1).cmp(&(b.0, b.1)).then(a.2.total_cmp(&b.2)));
            // The best move, and among moves as good as it (as many constraints met, colliding
            // or not alike), the cheapest that walls nothing in (the reach is measured only when
            // a move would help).
            let best = ranked.first().map(|r| (r.0, r.1));
            let mut reach: Option<SubjectReach> = None;
            // Only in a room with a door: without one the reach rule counts the largest free
            // region, and the SRT keeps its plain choice there.
            let has_door = !layout.room.doors.is_empty();
            let mut equals = ranked
                .iter()
                .take_while(|r| has_door && Some((r.0, r.1)) == best);
            let chosen = equals
                .find(|&&(.., p)| {
                    reach
                        .get_or_insert_with(|| SubjectReach::new(&layout, &obj))
                        .keeps(&obj, p)
                })
                .or(ranked.first())
                .map(|&(.., p)| p);
            if let Some(p) = chosen {
                set_pose(&mut layout, subject, p);
                if !changed.contains(subject) {
                    changed.push(subject.clone());
                }
            }
        }
        changed
            .iter()
            .filter_map(|n| layout.object(n).cloned())
            .collect()
    }
}

/// The reach of a layout around one object that may move: the map of every other solid object,
/// and how many objects are unreachable with the object where it stands.
struct SubjectReach {
    others: ReachMap,
    now: usize,
}

impl SubjectReach {
    /// The reach of `layout` around `obj` (one of its objects), on the metric's raster.
    fn new(layout: &Layout, obj: &PlacedObject) -> Self {
        let others: Vec<PlacedObject> = layout
            .objects
            .iter()
            .filter(|o| o.name != obj.name)
            .cloned()
            .collect();
        let others = ReachMap::new(&layout.room, &others, REACH_CELL_CM);
        let now = others.unreachable_with(obj);
        SubjectReach { others, now }
    }

    /// Whether moving `obj` to `pose` leaves no more objects unreachable than now.
    fn keeps(&self, obj: &PlacedObject, pose: Pose) -> bool {
        let moved = PlacedObject {
            position: [pose.center.x, pose.center.y],
            rotation: pose.rotation,
            ..obj.clone()
        };
        self.others.unreachable_with(&moved) <= self.now
    }
}

fn angle_between(a: f64, b: f64) -> f64 {
    let d = (a - b).rem_euclid(360.0);
    d.min(360.0 - d)
}

fn unmet(layout: &Layout, subject: &str) -> usize {
    constraints_of(&layout.plan, subject)
        .iter()
        .filter(|k| !check_one(layout, subject, k))
        .count()
}

fn set_pose(layout: &mut Layout, name: &str, p: Pose) {
    if let Some(o) = layout.objects.iter_mut().find(|o| o.name == name) {
        o.position = [p.center.x, p.center.y];
        o.rotation = p.rotation;
    }
}

/// Poses that satisfy `kind` for `obj`, nearest first by construction of each family.
fn candidates(layout: &Layout, obj: &PlacedObject, kind: &ConstraintKind) -> Vec<Pose> {
    let fp = obj.footprint();
    let [w, d, _] = obj.size;
    let wants_face = layout
        .plan
        .constraints
        .get(&obj.name)
        .and_then(|c| c.facing.clone());
    match kind {
        ConstraintKind::Facing { target } => {
            let Some(t) = layout.target_footprint(target) else {
                return Vec::new();
            };
            let exact = facing_rotation(fp.center, t.center);
            vec![
                Pose {
                    center: fp.center,
                    rotation: snap90(exact),
                },
                Pose {
                    center: fp.center,
                    rotation: exact,
                },
            ]
        }
        ConstraintKind::AgainstWall => {
            let wall = nearest_wall(&layout.room, fp.center);
            let turned = fp.with_pose(fp.center, wall.inward_rotation());
            let Some(slot) = wall.slot(&layout.room, turned.half, fp.height) else {
                return Vec::new();
            };
            let c = slot.point(slot.clamp(slot.along(fp.center)));
            vec![Pose {
                center: c,
                rotation: wall.inward_rotation(),
            }]
        }
        ConstraintKind::Relation { relation, target } => {
            let Some(t) = layout.target_footprint(target) else {
                return Vec::new();
            };
            let face = wants_face.as_deref() == Some(target.as_str());
            relation_poses(w, d, *relation, &t, &layout.room, 10.0, face)
        }
        ConstraintKind::Place(place) => place_candidates(layout, obj, place),
    }
}

/// Step (cm) of the places tried for a place constraint, along walls and over the floor.
const PLACE_STEP_CM: f64 = 10.0;

/// Floor (cm) a free-standing piece moved for its place keeps from every wall, all round.
const FREE_MARGIN_CM: f64 = 60.0;

/// Most poses kept for a place constraint, nearest first: each is then tried on a copy of the
/// layout.
const PLACE_CANDIDATES: usize = 120;

/// Poses of `obj` that meet `place` (a zone, a wall's role, the far corner, under a window, by
/// the entrance), nearest its pose first: flush against each wall's free stretch (turned into
/// the room), and, unless the plan puts it against a wall, over the floor in its own turn and
/// the four right angles. Clear of the other pieces first; then, for a piece that stands free
/// and whose place names no wall, [`FREE_MARGIN_CM`] clear of the walls first.
fn place_candidates(layout: &Layout, obj: &PlacedObject, place: &Place) -> Vec<Pose> {
    let room = &layout.room;
    let analysis = room.analysis();
    let fp = obj.footprint();
    // Each pose, and whether it is cramped: flush on a wall, or within [`FREE_MARGIN_CM`] of
    // one, for a piece that stands free (a counter by the entrance, a table in a zone) and whose
    // place names no wall. Roomy poses are tried first.
    let mut poses: Vec<(bool, Pose)> = Vec::new();
    // A piece the plan puts against a wall keeps that: only the poses flush on a wall.
    let flush_only = layout.plan.wants_wall(&obj.name);
    let walls_too = flush_only || place.wall.is_some() || place.under_window || place.far_corner;
    for wall in Wall::all(room) {
        let rotation = wall.inward_rotation();
        let turned = fp.with_pose(fp.center, rotation);
        let Some(slot) = wall.slot(room, turned.half, fp.height) else {
            continue;
        };
        for &(lo, hi) in &slot.stretches {
            let mut t = lo;
            while t < hi {
                poses.push((
                    !walls_too,
                    Pose {
                        center: slot.point(t),
                        rotation,
                    },
                ));
                t += PLACE_STEP_CM;
            }
            poses.push((
                !walls_too,
                Pose {
                    center: slot.point(hi),
                    rotation,
                },
            ));
        }
    }
    let mut y = PLACE_STEP_CM / 2.0;
    while y < room.depth && !flush_only {
        let mut x = PLACE_STEP_CM / 2.0;
        while x < room.width {
            for rotation in [obj.rotation, 0.0, 90.0, 180.0, 270.0] {
                let center = DVec2::new(x, y);
                let roomy = Footprint::new(
                    center,
                    2.0 * fp.half.x + 2.0 * FREE_MARGIN_CM,
                    2.0 * fp.half.y + 2.0 * FREE_MARGIN_CM,
                    rotation,
                );
                poses.push((!walls_too && !roomy.inside(room), Pose { center, rotation }));
            }
            x += PLACE_STEP_CM;
        }
        y += PLACE_STEP_CM;
    }
    // Poses clear of the other pieces first (the nearest of those that meet the place may all
    // stand on something), then the nearest.
    let others: Vec<Footprint> = layout
        .objects
        .iter()
        .filter(|o| o.name != obj.name && o.on_floor() && !o.is_flat() && !obj.is_flat())
        .map(PlacedObject::footprint)
        .collect();
    let mut keep: Vec<(bool, bool, f64, Pose)> = poses
        .into_iter()
        .filter_map(|(cramped, p)| {
            let at = fp.with_pose(p.center, p.rotation);
            (at.inside(room) && placed_as_asked_in(&at, room, &analysis, place)).then(|| {
                let blocked = others.iter().any(|b| b.collides(&at));
                let cost = fp.center.distance(p.center) + angle_between(obj.rotation, p.rotation);
                (blocked, cramped, cost, p)
            })
        })
        .collect();
    keep.sort_by(|a, b| a.0.cmp(&b.0).then(a.1.cmp(&b.1)).then(a.2.total_cmp(&b.2)));
    keep.truncate(PLACE_CANDIDATES);
    keep.into_iter().map(|(.., p)| p).collect()
}

#[async_trait]
impl SemanticRefiner for RuleSrt {
    async fn refine(&self, req: &SrtRequest) -> RoleResult<Vec<PlacedObject>> {
        Ok(Output::free(self.repair(req)))
    }
}

#[cfg(test)]
mod tests;
