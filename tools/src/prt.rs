//! The Physical Refinement Tool: grid matching that makes a layout physically valid.
//!
//! Given any layout, it returns one with no collisions and nothing outside the room, moving as
//! little as it can. It follows the paper's grid matching (wall alignment, out-of-bounds
//! correction, collision resolution by moving the smaller object to the nearest valid grid point),
//! with these differences:
//!
//! - **Placement to a fixpoint.** Objects are settled one at a time, largest first (earlier
//!   "settled" objects, such as groups already placed, before all others). Each keeps its pose if
//!   that pose is valid among the objects settled before it, else moves to the nearest valid pose.
//!   Settled objects never move again, so the result has no collision by construction.
//! - **Nearest valid point, searched outward.** Candidates are the grid points (default every
//!   5 cm), the room's edges and the positions flush against each settled object; they are visited
//!   in rings around the object's own (clamped) position and the search stops as soon as no
//!   unvisited ring can be nearer than the best valid point found.
//! - **Never drop while a place exists.** An against-wall object tries every wall (nearest first by
//!   displacement), then anywhere with its own rotation (reporting the unmet wall requirement), then
//!   turned by 90°, then squared to the nearest axis-aligned rotations. If objects remain without a place, the pass is repeated with them settled first.
//!   Only then is an object dropped, with the reason.
//! - **Nothing walled in.** Once everything stands, an object the placement moved that walls
//!   something in is moved again, to the nearest valid pose that keeps more reachable (`reach`).
//! - **Floor coverings** (height <= 3 cm) form their own layer: inside the room, not overlapping one
//!   another, free to lie under furniture.
//! - **Objects off the floor** (on another object, or on a wall) are no floor obstacles; once the
//!   floor stands they are kept, carried with their supports or put back on them (`held`).
//!
//! The result is deterministic: same input, same output.

use std::collections::{HashMap, HashSet};

use glam::DVec2;

use coords::Settled;
use disco_core::geometry::{Along, Footprint, Wall};
use disco_core::layout::{Dropped, PlacedObject};
use disco_core::plan::Plan;
use disco_core::roles::{Move, Refined};
use disco_core::scene::Room;
use search::{WallSearch, kept_in_place, recheck_full_stretch, ring, ring_axis_bound};

/// Settings of the Physical Refinement Tool.
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize, serde::Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct PrtConfig {
    /// Spacing of the candidate grid, in cm.
    pub grid_step_cm: f64,
    /// Extra passes, settling the homeless objects first, before anything is dropped.
    pub repair_passes: usize,
}

impl Default for PrtConfig {
    fn default() -> Self {
        PrtConfig {
            grid_step_cm: 5.0,
            repair_passes: 3,
        }
    }
}

/// Wall pieces hung lower than this (cm) keep the floor under them in the PRT's floor pass.
pub const LOW_WALL_CM: f64 = 100.0;

/// The Physical Refinement Tool.
#[derive(Debug, Clone, Copy, Default)]
pub struct PhysicalRefiner {
    config: PrtConfig,
}

/// One object being placed.
struct Item {
    /// Position in the caller's list.
    index: usize,
    /// The footprint as given (position made finite).
    given: Footprint,
    /// Its height (cm): window zones bind objects taller than the sill.
    height: f64,
    wants_wall: bool,
    settled_first: bool,
}

/// Where an object ended and what could not be honoured.
#[derive(Clone)]
struct Placement {
    footprint: Footprint,
    note: Option<String>,
}

impl PhysicalRefiner {
    /// A refiner with the given settings (a non-positive or non-finite grid step falls back to 5 cm).
    pub fn new(mut config: PrtConfig) -> Self {
        if !(config.grid_step_cm.is_finite() && config.grid_step_cm > 0.0) {
            config.grid_step_cm = PrtConfig::default().grid_step_cm;
        }
        PhysicalRefiner { config }
    }

    /// Makes `objects` physically valid in `room`; `plan` says which must stand against a wall.
    pub fn refine(&self, room: &Room, objects: &[PlacedObject], plan: &Plan) -> Refined {
        self.refine_settled(room, objects, plan, &HashSet::new())
    }

    /// As [`refine`](Self::refine), but the objects named in `settled` (for example the groups
    /// placed in earlier rounds) take precedence: newcomers move out of their way.
    ///
    /// Objects on other objects or on walls are no floor obstacles: the floor is refined without
    /// them, then each is kept, carried along with its support or put back on it (`held`). An
    /// object above the floor that nothing holds is set down on it, with a note.
    pub fn refine_settled(
        &self,
        room: &Room,
        objects: &[PlacedObject],
        plan: &Plan,
        settled: &HashSet<String>,
    ) -> Refined {
        let floating = |o: &PlacedObject| o.on_floor() && o.elevation != 0.0;
        if objects.iter().all(|o| o.on_floor() && !floating(o)) {
            return self.refine_floor(room, objects, plan, settled, &HashMap::new());
        }
        // A piece with others on its top stands as tall as the tallest of them reaches: the
        // window rules bind it so (a stand with its TV may not stand under a window).
        let mut loads: HashMap<&str, f64> = HashMap::new();
        for o in objects {
            if let Some(on) = o.on.as_deref() {
                let e = loads.entry(on).or_insert(0.0);
                *e = e.max(o.size[2]);
            }
        }
        let (floor, held): (Vec<usize>, Vec<usize>) =
            (0..objects.len()).partition(|&i| objects[i].on_floor());
        let mut notes = Vec::new();
        let on_floor: Vec<PlacedObject> = floor
            .iter()
            .map(|&i| {
                let o = &objects[i];
                if floating(o) {
                    notes.push(format!(
                        "{}: nothing held it {} cm above the floor; it stands on the floor",
                        o.name,
                        disco_core::units::show_number(o.elevation)
                    ));
                }
                PlacedObject {
                    elevation: 0.0,
                    ..o.clone()
                }
            })
            .collect();
        // A wall piece hung low (a whiteboard, its bottom under `LOW_WALL_CM`) keeps the floor
        // under it: it takes part in the floor's refinement as a settled piece, so a plant is
        // not pushed under it, then is settled on its wall like the others.
        let low: Vec<PlacedObject> = held
            .iter()
            .map(|&i| &objects[i])
            .filter(|o| o.wall.is_some() && o.elevation < LOW_WALL_CM)
            .map(|o| PlacedObject {
                elevation: 0.0,
                wall: None,
                ..o.clone()
            })
            .collect();
        let mut refined = if low.is_empty() {
            self.refine_floor(room, &on_floor, plan, settled, &loads)
        } else {
            let mut with_low = on_floor.clone();
            with_low.extend(low.iter().cloned());
            let mut keep = settled.clone();
            keep.extend(low.iter().map(|o| o.name.clone()));
            let mut r = self.refine_floor(room, &with_low, plan, &keep, &loads);
            let is_low = |n: &str| low.iter().any(|o| o.name == n);
            r.objects.retain(|o| !is_low(&o.name));
            r.moves.retain(|m| !is_low(&m.name));
            r.dropped.retain(|d| !is_low(&d.name));
            r
        };
        refined.notes.splice(0..0, notes);
        held::settle_held(self, room, objects, &held, &mut refined);
        // Back in the caller's order.
        let rank: std::collections::HashMap<&str, usize> = objects
            .iter()
            .enumerate()
            .map(|(i, o)| (o.name.as_str(), i))
            .collect();
        let key = |name: &str| rank.get(name).copied().unwrap_or(usize::MAX);
        refined.objects.sort_by_key(|o| key(&o.name));
        refined.moves.sort_by_key(|m| key(&m.name));
        refined.dropped.sort_by_key(|d| key(&d.name));
        refined
    }

    /// Refines objects that all stand on the floor (the algorithm of the module's docs).
    /// `loads` says how much higher than itself a piece stands with what is on its top.
    fn refine_floor(
        &self,
        room: &Room,
        objects: &[PlacedObject],
        plan: &Plan,
        settled: &HashSet<String>,
        loads: &HashMap<&str, f64>,
    ) -> Refined {
        let centre = DVec2::new(room.width / 2.0, room.depth / 2.0);
        let items: Vec<Item> = objects
            .iter()
            .enumerate()
            .map(|(index, o)| {
                let mut given = o.footprint();
                if !given.center.is_finite() {
                    given.center = centre;
                }
                Item {
                    index,
                    given,
                    height: o.size[2] + loads.get(o.name.as_str()).copied().unwrap_or(0.0),
                    wants_wall: plan.wants_wall(&o.name),
                    settled_first: settled.contains(&o.name),
                }
            })
            .collect();
        let (flat, solid): (Vec<&Item>, Vec<&Item>) =
            items.iter().partition(|it| objects[it.index].is_flat());

        let mut placements: Vec<Option<Placement>> = vec![None; objects.len()];
        for layer in [solid, flat] {
            for (item, placement) in self.place_layer(room, &layer) {
                placements[item] = placement;
            }
        }
        self.keep_reach(room, objects, &items, plan, &mut placements);

        let mut refined = Refined {
            objects: Vec::new(),
            dropped: Vec::new(),
            moves: Vec::new(),
            notes: Vec::new(),
        };
        for ((o, placement), item) in objects.iter().zip(placements).zip(&items) {
            match placement {
                Some(p) => {
                    let before = item.given;
                    let rotated = (p.footprint.rotation - before.rotation).abs() > 1e-9;
                    refined.moves.push(Move {
                        name: o.name.clone(),
                        displacement_cm: p.footprint.center.distance(before.center),
                        rotated,
                    });
                    if let Some(note) = p.note {
                        refined.notes.push(format!("{}: {note}", o.name));
                    }
                    refined.objects.push(PlacedObject {
                        position: [p.footprint.center.x, p.footprint.center.y],
                        rotation: p.footprint.rotation,
                        ..o.clone()
                    });
                }
                None => refined.dropped.push(Dropped {
                    name: o.name.clone(),
                    reason: drop_reason(o, room),
                }),
            }
        }
        refined
    }

    /// Places one layer (solid furniture, or floor coverings), returning (caller index, placement).
    fn place_layer(&self, room: &Room, layer: &[&Item]) -> Vec<(usize, Option<Placement>)> {
        let mut order: Vec<usize> = (0..layer.len()).collect();
        order.sort_by(|&a, &b| {
            let (a, b) = (layer[a], layer[b]);
            b.settled_first
                .cmp(&a.settled_first)
                .then(b.given.area().total_cmp(&a.given.area()))
                .then(a.index.cmp(&b.index))
        });
        let mut best = self.place_in_order(room, layer, &order);
        for _ in 0..self.config.repair_passes {
            let homeless: Vec<usize> = order
                .iter()
                .copied()
                .filter(|&i| best[i].is_none())
                .collect();
            if homeless.is_empty() {
                break;
            }
            // Settle the homeless first, then everyone else in the former order.
            let mut retry = homeless.clone();
            retry.extend(order.iter().copied().filter(|i| !homeless.contains(i)));
            let attempt = self.place_in_order(room, layer, &retry);
            if score(layer, &attempt) < score(layer, &best) {
                best = attempt;
            }
            order = retry;
        }
        layer.iter().map(|it| it.index).zip(best).collect()
    }

    fn place_in_order(
        &self,
        room: &Room,
        layer: &[&Item],
        order: &[usize],
    ) -> Vec<Option<Placement>> {
        let mut settled = Settled::new(room);
        let mut out = vec![None; layer.len()];
        for &i in order {
            let placement = self.place_one(room, layer[i], &settled);
            if let Some(p) = &placement {
                settled.push(p.footprint);
            }
            out[i] = placement;
        }
        out
    }

    /// The nearest valid pose for `item` among the `settled` footprints, or `None`.
    fn place_one(&self, room: &Room, item: &Item, settled: &Settled) -> Option<Placement> {
        let given = item.given;
        let mut note = None;
        if item.wants_wall {
            if let Some(fp) = self.nearest_on_walls(room, given, item.height, settled) {
                return Some(Placement {
                    footprint: fp,
                    note: None,
                });
            }
            note = Some("no free stretch of wall fits it; placed away from the walls".to_string());
        }
        // Its own rotation, then a quarter turn, then the nearest axis-aligned turns (a tilted
        // object's bounding box wastes room).
        let own = given.rotation;
        let square = (own / 90.0).round() * 90.0;
        let mut tried: Vec<f64> = Vec::with_capacity(4);
        for rotation in [own, own + 90.0, square, square + 90.0] {
            let rotation = disco_core::geometry::normalize_degrees(rotation);
            if tried.iter().any(|t| (t - rotation).abs() < 1e-9) {
                continue;
            }
            tried.push(rotation);
            if let Some(fp) = self.nearest_free(room, given, rotation, item.height, settled) {
                let turned = (rotation - own).abs() > 1e-9;
                let note = match (note, turned) {
                    (Some(n), true) => Some(format!("{n}, and turned to {rotation}° to fit")),
                    (None, true) => Some(format!("turned to {rotation}° to fit")),
                    (n, false) => n,
                };
                return Some(Placement {
                    footprint: fp,
                    note,
                });
            }
        }
        None
    }

    /// The nearest valid pose with the back on some wall, front into the room, for an object
    /// `height` cm tall.
    fn nearest_on_walls(
        &self,
        room: &Room,
        given: Footprint,
        height: f64,
        settled: &Settled,
    ) -> Option<Footprint> {
        let o = given.center;
        let mut walls = Wall::all(room);
        walls.sort_by(|a, b| a.distance(o).total_cmp(&b.distance(o)));
        let mut best: Option<(f64, Footprint)> = None;
        for wall in walls {
            let fp = given.with_pose(o, wall.inward_rotation());
            // The position across the wall is fixed (back flush); the one along it is searched.
            let Some(slot) = wall.slot(room, fp.half, height) else {
                continue;
            };
            let across = slot.point(slot.along(o)).distance(o);
            if best.is_some_and(|(d, _)| across >= d) {
                continue;
            }
            let search = WallSearch {
                slot: &slot,
                fp,
                o,
                height,
                settled,
            };
            if slot.axis == Along::Edge {
                self.nearest_on_slanted(&search, &mut best);
                continue;
            }
            for (k, &stretch) in slot.stretches.iter().enumerate() {
                self.nearest_on_stretch(&search, k, stretch, &mut best);
            }
        }
        best.map(|(_, fp)| fp)
    }

    /// Searches stretch `k` (`lo..hi`) of an axis-aligned wall, outward from the object's own
    /// position, for a valid pose nearer than `best`.
    fn nearest_on_stretch(
        &self,
        s: &WallSearch<'_>,
        k: usize,
        (lo, hi): (f64, f64),
        best: &mut Option<(f64, Footprint)>,
    ) {
        let (slot, fp, o, settled) = (s.slot, s.fp, s.o, s.settled);
        let valid = |cand: &Footprint| settled.fits_room(cand, s.height);
        let along_is_x = slot.along_x();
        let h = fp.aabb_half();
        let o_along = slot.along(o);
        let shape = (
            slot.wall.index(),
            k,
            fp.half.x.to_bits(),
            fp.half.y.to_bits(),
            settled.height_key(s.height),
        );
        if let Some(since) = settled.full_since(shape) {
            let h_along = if along_is_x { h.x } else { h.y };
            recheck_full_stretch(s, shape, since, (lo, hi), h_along, best);
            return;
        }
        let step = self.config.grid_step_cm;
        let own = o_along.clamp(lo, hi);
        let mut line = match along_is_x {
            true => settled.line_x(lo, hi, own, step, h.x),
            false => settled.line_y(lo, hi, own, step, h.y),
        };
        // The candidates by distance from the object's own position, the lower of two as
        // near first.
        let mut up = line.partition(o_along);
        let mut down = up - 1;
        // The last object met on each side: along a crowded wall the next candidate on
        // that side mostly hits it again, which one test shows.
        let mut blockers: [Option<usize>; 2] = [None, None];
        loop {
            let (v, side) = match (line.get(down), line.get(up)) {
                (Some(a), Some(b)) if (a - o_along).abs() <= (b - o_along).abs() => {
                    down -= 1;
                    (a, 0)
                }
                (_, Some(b)) => {
                    up += 1;
                    (b, 1)
                }
                (Some(a), None) => {
                    down -= 1;
                    (a, 0)
                }
                (None, None) => {
                    // Every candidate collided.
                    settled.mark_full(shape);
                    break;
                }
            };
            let centre = slot.point(v);
            let d = centre.distance(o);
            if best.is_some_and(|(bd, _)| d >= bd) {
                break;
            }
            let cand = fp.with_pose(centre, fp.rotation);
            let b = cand.aabb();
            if blockers
                .iter()
                .flatten()
                .any(|&i| settled.collides_with(i, &cand, &b))
            {
                continue;
            }
            match settled.first_collision(&cand) {
                Some(i) => blockers[side] = Some(i),
                None if valid(&cand) => {
                    *best = Some((d, cand));
                    break;
                }
                None => {}
            }
        }
    }

    /// Searches a slanted wall for a valid pose nearer than `best`: its grid points (every grid
    /// step from its start), its stretches' ends, the object's own position and the positions
    /// flush against each settled footprint, nearest first.
    fn nearest_on_slanted(&self, s: &WallSearch<'_>, best: &mut Option<(f64, Footprint)>) {
        let (slot, fp, o, settled) = (s.slot, s.fp, s.o, s.settled);
        let own = slot.along(o);
        let step = self.config.grid_step_cm;
        let hw = fp.half.x;
        let mut ts: Vec<f64> = Vec::new();
        for &(a, b) in &slot.stretches {
            ts.extend([a, b, own.clamp(a, b)]);
            let first = (a / step).ceil() as i64;
            let last = (b / step).floor() as i64;
            ts.extend((first..=last).map(|k| k as f64 * step));
            for other in settled.footprints() {
                let along = other.corners().map(|c| slot.wall.along(c));
                let lo = along.iter().copied().fold(f64::INFINITY, f64::min) - hw;
                let hi = along.iter().copied().fold(f64::NEG_INFINITY, f64::max) + hw;
                ts.extend([lo, hi].into_iter().filter(|t| *t >= a && *t <= b));
            }
        }
        ts.sort_by(|a, b| {
            (a - own)
                .abs()
                .total_cmp(&(b - own).abs())
                .then(a.total_cmp(b))
        });
        ts.dedup();
        for t in ts {
            let centre = slot.point(t);
            let d = centre.distance(o);
            if best.is_some_and(|(bd, _)| d >= bd) {
                return;
            }
            let cand = fp.with_pose(centre, fp.rotation);
            if !settled.collides(&cand) && settled.fits_room(&cand, s.height) {
                *best = Some((d, cand));
                return;
            }
        }
    }

    /// The nearest valid pose with the given rotation anywhere in the room.
    fn nearest_free(
        &self,
        room: &Room,
        given: Footprint,
        rotation: f64,
        height: f64,
        settled: &Settled,
    ) -> Option<Footprint> {
        let o = given.center;
        let fp = given.with_pose(o, rotation);
        let h = fp.aabb_half();
        if 2.0 * h.x > room.width + 1e-9 || 2.0 * h.y > room.depth + 1e-9 {
            return None;
        }
        let lo = h;
        let hi = (DVec2::new(room.width, room.depth) - h).max(lo);
        // The nearest in-bounds position: the out-of-bounds correction with the least movement.
        let c = o.clamp(lo, hi);
        if c == o
            && let Some(kept) = kept_in_place(&fp, height, settled)
        {
            return Some(kept);
        }
        let step = self.config.grid_step_cm;
        let mut xs = settled.line_x(lo.x, hi.x, c.x, step, h.x);
        let mut ys = settled.line_y(lo.y, hi.y, c.y, step, h.y);
        let (Some(i0), Some(j0)) = (xs.nearest(c.x), ys.nearest(c.y)) else {
            return None;
        };
        let clamp_sq = o.distance_squared(c);

        let mut best: Option<(f64, Footprint)> = None;
        for k in 0.. {
            // Every point of ring k is at least `m` from c along one axis, and |p - o|² >= |p - c|² + |c - o|²
            // because c is o's projection onto the feasible box.
            let m = ring_axis_bound(&mut xs, i0, k, c.x).min(ring_axis_bound(&mut ys, j0, k, c.y));
            if !m.is_finite() {
                break;
            }
            let bound = (m * m + clamp_sq).sqrt();
            if best.is_some_and(|(d, _)| bound >= d) {
                break;
            }
            for (i, j) in ring(i0, j0, k) {
                let (Some(x), Some(y)) = (xs.get(i), ys.get(j)) else {
                    continue;
                };
                let centre = DVec2::new(x, y);
                let d = centre.distance(o);
                if best.is_some_and(|(bd, _)| d >= bd) {
                    continue;
                }
                let cand = fp.with_pose(centre, fp.rotation);
                if !settled.collides(&cand) && settled.fits_room(&cand, height) {
                    best = Some((d, cand));
                }
            }
        }
        best.map(|(_, fp)| fp)
    }
}

/// The PRT as a role of the runtime (`impl = "grid"`).
pub struct GridPrt {
    refiner: PhysicalRefiner,
}

impl GridPrt {
    /// A role over a refiner with `config`.
    pub fn new(config: PrtConfig) -> Self {
        GridPrt {
            refiner: PhysicalRefiner::new(config),
        }
    }
}

#[async_trait::async_trait]
impl disco_core::roles::PhysicalRefinerRole for GridPrt {
    async fn refine(
        &self,
        req: &disco_core::roles::PrtRequest,
    ) -> disco_core::roles::RoleResult<Refined> {
        let r = self.refiner.refine_settled(
            &req.ctx.scene.room,
            &req.layout.objects,
            &req.layout.plan,
            &req.settled,
        );
        Ok(disco_core::roles::Output::free(r))
    }
}

/// Fewer homeless objects first, then less total movement.
fn score(layer: &[&Item], placements: &[Option<Placement>]) -> (usize, u64) {
    let homeless = placements.iter().filter(|p| p.is_none()).count();
    let moved: f64 = layer
        .iter()
        .zip(placements)
        .filter_map(|(it, p)| {
            p.as_ref()
                .map(|p| p.footprint.center.distance(it.given.center))
        })
        .sum();
    (homeless, (moved * 1000.0) as u64)
}

fn drop_reason(o: &PlacedObject, room: &Room) -> String {
    if let Some(why) = disco_core::scene::misfit(o.size, room) {
        why
    } else if o.is_flat() {
        "no place left on the floor that does not overlap another floor covering".to_string()
    } else {
        "no collision-free place left in the room (every wall stretch and grid point was tried, in up to four rotations)"
            .to_string()
    }
}

mod coords;
mod held;
mod reach;
mod search;

#[cfg(test)]
mod held_tests;
#[cfg(test)]
mod polygon_tests;
#[cfg(test)]
pub(crate) mod tests;
