//! Keeping people's way to the furniture. When, once everything stands, something is walled
//! in, objects are moved again, one at a time, to the valid pose that leaves fewest objects
//! walled in and none of the plan's constraints on the object newly unmet (the fewest unmet,
//! then the nearest, among equals). The order ([`suspects`]): those the placement moved,
//! furthest first; those walled in, largest first; the blockers, whose absence would free
//! walled-in ones; their neighbours; and of all these, the objects being placed now before those
//! earlier groups settled. A few passes run while they help. Last, a piece still
//! walled in may leave its wall, keeping its relations to the others (a nightstand beside the
//! bed under a window, rather than boxed in behind its twin).
//!
//! The placement settles objects one at a time and cannot know whether a pose walls something
//! in before everything stands; and a designer's layout can be valid yet seal a corner (a table
//! 30 cm off the bed's corner). So the repair runs once everything stands, on the metric's own
//! raster ([`REACH_CELL_CM`]) and reach rule ([`ReachMap`]). It moves objects only to poses valid
//! among all the others (inside the room, out of the keep-clear zones, colliding with nothing):
//! the PRT's guarantees hold as before, and nothing is dropped. An object standing on the wall
//! it wants is only tried on the walls, but in the last resort. A layout where everything is
//! reachable is left alone. The work is bounded: at most [`MAX_REPLACED`] objects are tried,
//! each at no more than [`REACH_TESTS`] poses, and rooms without a door (where the reach rule
//! counts the largest free region) and halls over [`MAX_AREA_CM2`] are left as placed: the PRT
//! on a small doorless bedroom stays a matter of microseconds.

use std::collections::HashMap;

use glam::DVec2;

use super::coords::Settled;
use super::{Item, PhysicalRefiner, Placement};
use disco_core::geometry::{Footprint, Wall};
use disco_core::layout::PlacedObject;
use disco_core::metrics::{REACH_CELL_CM, ReachMap, unreachable_objects};
use disco_core::plan::Plan;
use disco_core::relations::{ConstraintKind, constraints_of};
use disco_core::scene::Room;

/// How many moved objects one repair tries to re-place at most.
const MAX_REPLACED: usize = 12;

/// How many valid poses of one object are tested for reach at most.
const REACH_TESTS: usize = 160;

/// The least distance (cm) between two poses of one object tested for reach: the tests spread
/// over about a metre around the object rather than a few centimetres.
const TEST_SPACING_CM: f64 = 10.0;

/// The floor area (cm², bounding box) above which the repair is not tried: 200 m², more than
/// any room of the benchmark sets; a big hall's raster costs most of a scene's time.
const MAX_AREA_CM2: f64 = 200.0 * 10_000.0;

/// How near (cm) to a walled-in object another must stand to be tried as the one walling it in:
/// a passage narrower than the agent (40 cm).
const NEIGHBOUR_GAP_CM: f64 = 40.0;

/// How far (cm) an object must have been moved or how much turned to count as moved.
const MOVED_CM: f64 = 1e-6;

/// How many times the walled-in objects are looked for again after a round of re-placements
/// that helped: a blocker moved out of the way can leave a walled-in piece a better pose.
const PASSES: usize = 3;

/// The layout under repair: what stays fixed while objects are re-placed.
struct Repairing<'a> {
    room: &'a Room,
    objects: &'a [PlacedObject],
    items: &'a [Item],
    plan: &'a Plan,
    /// The solid objects that stand somewhere, by index into `objects`.
    solid: Vec<usize>,
}

/// Which of the plan's constraints on an object a re-placement must keep (none may end unmet
/// that is met where the object stands).
#[derive(Clone, Copy, PartialEq, Eq)]
enum Keep {
    /// All of them: against the wall, relations and facing.
    Everything,
    /// Its relations to the others and facing; it may leave its wall.
    Relations,
}

/// What re-placing one object came to.
enum Repair {
    /// Everything is reachable now.
    Done,
    /// Fewer objects are walled in.
    Improved,
    /// It stays where it stood.
    Unchanged,
}

impl Repairing<'_> {
    /// Object `i` where `placements` put it.
    fn posed(&self, placements: &[Option<Placement>], i: usize) -> Option<PlacedObject> {
        let fp = placements[i].as_ref()?.footprint;
        Some(posed_at(&self.objects[i], &fp))
    }

    /// The names of the solid objects walled in where `placements` put them.
    fn walled_in(&self, placements: &[Option<Placement>]) -> Vec<String> {
        unreachable_objects(self.room, &self.all_but(placements, None), REACH_CELL_CM)
    }

    /// Every solid object where `placements` put it, but `except`.
    fn all_but(
        &self,
        placements: &[Option<Placement>],
        except: Option<usize>,
    ) -> Vec<PlacedObject> {
        self.solid
            .iter()
            .filter(|&&i| Some(i) != except)
            .filter_map(|&i| self.posed(placements, i))
            .collect()
    }
}

impl PhysicalRefiner {
    /// In a room with a door, while some solid object is unreachable, re-places objects one at
    /// a time (see [`suspects`]) where that walls fewer in (`placements` against `items`, both
    /// by the caller's index into `objects`; `plan` says what each must keep).
    pub(super) fn keep_reach(
        &self,
        room: &Room,
        objects: &[PlacedObject],
        items: &[Item],
        plan: &Plan,
        placements: &mut [Option<Placement>],
    ) {
        if room.doors.is_empty() || room.width * room.depth > MAX_AREA_CM2 {
            return;
        }
        let scene = Repairing {
            room,
            objects,
            items,
            plan,
            solid: (0..objects.len())
                .filter(|&i| !objects[i].is_flat() && placements[i].is_some())
                .collect(),
        };
        let mut tried = 0;
        for _ in 0..PASSES {
            let walled_in = scene.walled_in(placements);
            if walled_in.is_empty() {
                return;
            }
            let mut improved = false;
            for s in suspects(&scene, placements, &walled_in) {
                if tried >= MAX_REPLACED {
                    return;
                }
                tried += 1;
                match self.re_place(&scene, placements, s, Keep::Everything) {
                    Repair::Done => return,
                    Repair::Improved => improved = true,
                    Repair::Unchanged => {}
                }
            }
            if !improved {
                break;
            }
        }
        // Last, a piece still walled in may leave its wall, if that frees it and it keeps its
        // ties to the others: a nightstand at the bed's side beneath a window rather than
        // boxed in behind its twin.
        let walled_in = scene.walled_in(placements);
        for s in stuck(&scene, &walled_in, &[]) {
            if let Repair::Done = self.re_place(&scene, placements, s, Keep::Relations) {
                return;
            }
        }
    }

    /// Moves object `s` to the valid pose that walls fewest in, when that is fewer than where
    /// it stands (see [`reaching_pose`](Self::reaching_pose)).
    fn re_place(
        &self,
        scene: &Repairing<'_>,
        placements: &mut [Option<Placement>],
        s: usize,
        keep: Keep,
    ) -> Repair {
        let room = scene.room;
        let others = scene.all_but(placements, Some(s));
        let map = ReachMap::new(room, &others, REACH_CELL_CM);
        let Some(here) = scene.posed(placements, s) else {
            return Repair::Unchanged;
        };
        let now = map.unreachable_with(&here);
        if now == 0 {
            return Repair::Done;
        }
        if now <= map.unreachable() {
            // Walls nothing in and is reached: moving it cannot help.
            return Repair::Unchanged;
        }
        let mut settled = Settled::new(room);
        for o in &others {
            settled.push(o.footprint());
        }
        let footprints: HashMap<&str, Footprint> = scene
            .objects
            .iter()
            .zip(placements.iter())
            .filter_map(|(o, p)| Some((o.name.as_str(), p.as_ref()?.footprint)))
            .collect();
        let ties = Ties::new(scene.plan, room, &scene.objects[s].name, footprints);
        let item = &scene.items[s];
        let on_wall = keep == Keep::Everything
            && item.wants_wall
            && placements[s].as_ref().is_some_and(|p| p.note.is_none());
        let search = PoseSearch {
            item,
            obj: &here,
            on_wall,
            keep,
            settled: &settled,
            map: &map,
            ties: &ties,
        };
        match self.reaching_pose(room, &search) {
            Some((count, fp)) if count < now => {
                if let Some(p) = placements[s].as_mut() {
                    p.footprint = fp;
                }
                match count {
                    0 => Repair::Done,
                    _ => Repair::Improved,
                }
            }
            _ => Repair::Unchanged,
        }
    }

    /// The valid pose of the searched object that leaves the fewest objects unreachable, with no
    /// more of the plan's constraints on it unmet than where it stands (the fewest among equals,
    /// then the nearest to where it was asked for), with that count. `None` when no pose is
    /// valid.
    fn reaching_pose(&self, room: &Room, search: &PoseSearch<'_>) -> Option<(usize, Footprint)> {
        let PoseSearch {
            item,
            obj,
            on_wall,
            keep,
            settled,
            map,
            ties,
        } = *search;
        let placed = obj.footprint();
        let unmet_now = ties.unmet(&placed, keep);
        let mut poses = match on_wall {
            true => self.wall_poses(room, &placed),
            false => self.floor_poses(room, &placed),
        };
        let o = item.given.center;
        poses.sort_by(|a, b| {
            let (da, db) = (a.center.distance(o), b.center.distance(o));
            da.total_cmp(&db)
                .then(a.center.x.total_cmp(&b.center.x))
                .then(a.center.y.total_cmp(&b.center.y))
        });
        let floor = map.unreachable();
        let mut best: Option<(usize, usize, Footprint)> = None;
        let mut tested: Vec<DVec2> = Vec::new();
        let valid = poses
            .into_iter()
            .filter(|fp| {
                in_box(room, fp) && !settled.collides(fp) && settled.fits_room(fp, item.height)
            })
            .filter(|fp| ties.unmet(fp, keep) <= unmet_now);
        for fp in valid {
            if tested.len() >= REACH_TESTS {
                break;
            }
            if tested
                .iter()
                .any(|t| t.distance(fp.center) < TEST_SPACING_CM)
            {
                continue;
            }
            tested.push(fp.center);
            let count = map.unreachable_with(&posed_at(obj, &fp));
            let unmet = ties.unmet(&fp, Keep::Everything);
            if best.is_none_or(|(c, u, _)| (count, unmet) < (c, u)) {
                best = Some((count, unmet, fp));
            }
            if count <= floor && unmet == 0 {
                break;
            }
        }
        best.map(|(count, _, fp)| (count, fp))
    }

    /// Poses of `fp` with its back on some wall, front into the room: every grid point of every
    /// free stretch, and the stretches' ends.
    fn wall_poses(&self, room: &Room, fp: &Footprint) -> Vec<Footprint> {
        let step = self.config.grid_step_cm;
        let mut out = Vec::new();
        for wall in Wall::all(room) {
            let turned = fp.with_pose(fp.center, wall.inward_rotation());
            let Some(slot) = wall.slot(room, turned.half, fp.height) else {
                continue;
            };
            for &(a, b) in &slot.stretches {
                let first = (a / step).ceil() as i64;
                let last = (b / step).floor() as i64;
                let grid = (first..=last).map(|k| k as f64 * step);
                for t in [a, b].into_iter().chain(grid) {
                    out.push(turned.with_pose(slot.point(t), turned.rotation));
                }
            }
        }
        out
    }

    /// Poses of `fp`, turned as it is, at every grid point where its box lies in the room's.
    fn floor_poses(&self, room: &Room, fp: &Footprint) -> Vec<Footprint> {
        let step = self.config.grid_step_cm;
        let h = fp.aabb_half();
        let axis = |half: f64, size: f64| -> Vec<f64> {
            let first = (half / step).ceil() as i64;
            let last = ((size - half) / step).floor() as i64;
            (first..=last).map(|k| k as f64 * step).collect()
        };
        let (xs, ys) = (axis(h.x, room.width), axis(h.y, room.depth));
        let mut out = Vec::with_capacity(xs.len() * ys.len());
        for &x in &xs {
            for &y in &ys {
                out.push(fp.with_pose(DVec2::new(x, y), fp.rotation));
            }
        }
        out
    }
}

/// The objects to try re-placing, in order, by index into the scene's objects: those the
/// placement moved, furthest first (a piece pushed far from where it was asked for is the
/// likeliest to have landed in a passage); then those `walled_in`, largest first; then the
/// blockers, those whose absence would free walled-in ones (most freed first, then smallest);
/// then the neighbours of walled-in ones, nearest first.
fn suspects(
    scene: &Repairing<'_>,
    placements: &[Option<Placement>],
    walled_in: &[String],
) -> Vec<usize> {
    let Repairing { objects, items, .. } = *scene;
    let solid = &scene.solid;
    let mut moved: Vec<(f64, usize)> = solid
        .iter()
        .filter_map(|&i| {
            let fp = placements[i].as_ref()?.footprint;
            let given = items[i].given;
            let d = fp.center.distance(given.center);
            let turned = (fp.rotation - given.rotation).abs() > MOVED_CM;
            (d > MOVED_CM || turned).then_some((d, i))
        })
        .collect();
    moved.sort_by(|a, b| b.0.total_cmp(&a.0).then(a.1.cmp(&b.1)));
    let mut suspects: Vec<usize> = moved.into_iter().map(|(_, i)| i).collect();
    suspects.extend(stuck(scene, walled_in, &suspects));
    let area = |i: usize| items[i].given.area();
    let mut blockers: Vec<(usize, usize)> = solid
        .iter()
        .copied()
        .filter(|i| !suspects.contains(i))
        .filter_map(|i| {
            let without = unreachable_objects(
                scene.room,
                &scene.all_but(placements, Some(i)),
                REACH_CELL_CM,
            );
            let freed = walled_in.iter().filter(|n| !without.contains(n)).count();
            (freed > 0).then_some((freed, i))
        })
        .collect();
    blockers.sort_by(|a, b| {
        b.0.cmp(&a.0)
            .then(area(a.1).total_cmp(&area(b.1)))
            .then(a.1.cmp(&b.1))
    });
    suspects.extend(blockers.into_iter().map(|(_, i)| i));
    // Then the neighbours, nearest first: what stands in front of a walled-in piece.
    let placed_box = |i: usize| placements[i].as_ref().map(|p| p.footprint.aabb());
    let stuck_boxes: Vec<_> = solid
        .iter()
        .filter(|&&i| walled_in.contains(&objects[i].name))
        .filter_map(|&i| placed_box(i))
        .collect();
    let mut next_to: Vec<(f64, usize)> = solid
        .iter()
        .copied()
        .filter(|i| !suspects.contains(i))
        .filter_map(|i| {
            let b = placed_box(i)?;
            let gap = stuck_boxes
                .iter()
                .map(|k| k.gap(&b))
                .fold(f64::INFINITY, f64::min);
            (gap < NEIGHBOUR_GAP_CM).then_some((gap, i))
        })
        .collect();
    next_to.sort_by(|a, b| a.0.total_cmp(&b.0).then(a.1.cmp(&b.1)));
    suspects.extend(next_to.into_iter().map(|(_, i)| i));
    // What is being placed now moves before what earlier groups settled: a stool set in the way
    // of a nightstand placed before it moves, not the nightstand to the bed's other side.
    let (fresh, settled): (Vec<usize>, Vec<usize>) =
        suspects.into_iter().partition(|&i| !items[i].settled_first);
    fresh.into_iter().chain(settled).collect()
}

/// The solid objects `walled_in`, but those in `except`, largest first, by index into the
/// scene's objects.
fn stuck(scene: &Repairing<'_>, walled_in: &[String], except: &[usize]) -> Vec<usize> {
    let mut stuck: Vec<usize> = scene
        .solid
        .iter()
        .copied()
        .filter(|&i| walled_in.contains(&scene.objects[i].name) && !except.contains(&i))
        .collect();
    let area = |i: usize| scene.items[i].given.area();
    stuck.sort_by(|&a, &b| area(b).total_cmp(&area(a)).then(a.cmp(&b)));
    stuck
}

/// One object's search for a pose that walls less in.
#[derive(Clone, Copy)]
struct PoseSearch<'a> {
    /// The object as the placement was asked to place it.
    item: &'a Item,
    /// The object where the placement put it.
    obj: &'a PlacedObject,
    /// Whether it stands on the wall it wants: then only wall poses are tried.
    on_wall: bool,
    /// Which of its constraints a new pose must keep.
    keep: Keep,
    /// Every other solid object.
    settled: &'a Settled,
    /// The reach of every other solid object.
    map: &'a ReachMap,
    /// The plan's constraints that involve it.
    ties: &'a Ties<'a>,
}

/// The plan's constraints on one object, as subject or as target, and where everything else
/// stands: to count how many a pose of that object leaves unmet.
struct Ties<'a> {
    room: &'a Room,
    name: &'a str,
    checks: Vec<(String, ConstraintKind)>,
    footprints: HashMap<&'a str, Footprint>,
}

impl<'a> Ties<'a> {
    /// The constraints of `plan` that involve `name`, with everything's `footprints` by name.
    fn new(
        plan: &Plan,
        room: &'a Room,
        name: &'a str,
        footprints: HashMap<&'a str, Footprint>,
    ) -> Self {
        let checks = plan
            .constraints
            .keys()
            .flat_map(|subject| {
                constraints_of(plan, subject)
                    .into_iter()
                    .map(move |kind| (subject.clone(), kind))
            })
            .filter(|(subject, kind)| subject == name || kind.target() == Some(name))
            .collect();
        Ties {
            room,
            name,
            checks,
            footprints,
        }
    }

    /// How many of the constraints that `keep` names are unmet with the object at `fp`.
    fn unmet(&self, fp: &Footprint, keep: Keep) -> usize {
        let find = |n: &str| match n == self.name {
            true => Some(*fp),
            false => self.footprints.get(n).copied(),
        };
        self.checks
            .iter()
            .filter(|(_, kind)| keep == Keep::Everything || *kind != ConstraintKind::AgainstWall)
            .filter(|(subject, kind)| {
                !find(subject).is_some_and(|a| kind.holds(&a, self.room, find))
            })
            .count()
    }
}

/// `obj` standing at `fp`.
fn posed_at(obj: &PlacedObject, fp: &Footprint) -> PlacedObject {
    PlacedObject {
        position: [fp.center.x, fp.center.y],
        rotation: fp.rotation,
        ..obj.clone()
    }
}

/// Whether `fp`'s box lies in the room's bounding box (the outline and zones are
/// [`Settled::fits_room`]'s).
fn in_box(room: &Room, fp: &Footprint) -> bool {
    let b = fp.aabb();
    let eps = 1e-6;
    b.min.x >= -eps && b.min.y >= -eps && b.max.x <= room.width + eps && b.max.y <= room.depth + eps
}

#[cfg(test)]
mod tests;
