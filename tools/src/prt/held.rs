//! Objects off the floor in the PRT: what stands on another object (`on`) or hangs on a wall
//! (`wall`). They are not floor obstacles: the floor is refined without them, then each is
//! checked against the predicates of `disco_core::geometry3d`, supports before what stands on
//! them.
//!
//! - A valid one stays where it is; one whose support moved is carried along with it.
//! - An object on a surface that does not stand properly is put back on its support: the
//!   nearest free spot of its top (with the support's turn, then its own). With no room left
//!   there, or no usable support, it stands on the floor, with a note.
//! - A wall object that does not hang properly moves to the nearest free stretch of wall at its
//!   height (its own wall first). With none, it is dropped with the reason: reported, never
//!   stacked.

use std::collections::HashMap;

use glam::DVec2;

use disco_core::geometry::{Footprint, Wall, normalize_degrees};
use disco_core::geometry3d::{self, is_seat, opening_problem, surface_problem, wall_problem};
use disco_core::layout::{Dropped, PlacedObject};
use disco_core::roles::{Move, Refined};
use disco_core::scene::Room;

use super::coords::Settled;
use super::{Item, PhysicalRefiner};

/// How deep a stack of objects on objects may go before the rest counts as unsupported.
const MAX_STACK: usize = 16;

/// Settles the held objects `held` (indices into `objects`, the caller's list) around the floor
/// `refined` already settled; appends their poses, moves, notes and drops to it.
pub(super) fn settle_held(
    refiner: &PhysicalRefiner,
    room: &Room,
    objects: &[PlacedObject],
    held: &[usize],
    refined: &mut Refined,
) {
    let given: HashMap<&str, &PlacedObject> =
        objects.iter().map(|o| (o.name.as_str(), o)).collect();
    let mut now: HashMap<String, PlacedObject> = refined
        .objects
        .iter()
        .map(|o| (o.name.clone(), o.clone()))
        .collect();
    // The floor as the fallback sees it: every settled solid footprint, held ones as they come.
    let mut floor = Settled::new(room);
    for o in refined.objects.iter().filter(|o| !o.is_flat()) {
        floor.push(o.footprint());
    }
    // Those that hold where they are (their support where it was, nothing on the floor in their
    // way) are settled first, supports before what stands on them, so that one that must move
    // finds the others in their places rather than taking one of them.
    let sound = |o: &PlacedObject| {
        let support_stayed =
            o.on.as_deref()
                .is_none_or(|s| match (given.get(s), now.get(s)) {
                    (Some(a), Some(b)) => a.position == b.position && a.rotation == b.rotation,
                    _ => false,
                });
        support_stayed
            && geometry3d::support_problem(o, &given, room).is_none()
            && o.wall.is_none_or(|w| opening_problem(o, room, w).is_none())
            && clear_of(o, &now)
    };
    let mut order: Vec<(bool, usize, usize)> = held
        .iter()
        .map(|&i| (!sound(&objects[i]), depth(&objects[i], &given), i))
        .collect();
    order.sort();
    let order: Vec<usize> = order.into_iter().map(|(_, _, i)| i).collect();
    for i in order {
        let o = &objects[i];
        let outcome = match (&o.on, o.wall) {
            (Some(on), _) => on_surface(refiner, room, o, on, &given, &now, &floor),
            (None, Some(w)) => on_walls(refiner, room, o, w, &now).ok_or_else(|| {
                format!(
                    "no free stretch of wall at {:.0} cm fits it (every wall was tried)",
                    o.elevation
                )
            }),
            // Not held: the caller settles it on the floor.
            (None, None) => continue,
        };
        match outcome {
            Ok((placed, note)) => {
                refined.moves.push(Move {
                    name: o.name.clone(),
                    displacement_cm: distance(o, &placed),
                    rotated: (normalize_degrees(placed.rotation) - normalize_degrees(o.rotation))
                        .abs()
                        > 1e-9,
                });
                if let Some(note) = note {
                    refined.notes.push(format!("{}: {note}", o.name));
                }
                floor.push(placed.footprint());
                now.insert(placed.name.clone(), placed.clone());
                refined.objects.push(placed);
            }
            Err(reason) => refined.dropped.push(Dropped {
                name: o.name.clone(),
                reason,
            }),
        }
    }
}

/// How many objects down the `on` chain from `o` to the floor or a wall (capped at
/// [`MAX_STACK`], which a chain coming back round to itself reaches).
fn depth(o: &PlacedObject, given: &HashMap<&str, &PlacedObject>) -> usize {
    let mut at = o;
    for d in 0..MAX_STACK {
        match at.on.as_deref().and_then(|n| given.get(n)) {
            Some(next) => at = next,
            None => return d,
        }
    }
    MAX_STACK
}

fn distance(a: &PlacedObject, b: &PlacedObject) -> f64 {
    DVec2::from(a.position).distance(DVec2::from(b.position))
}

/// Whether `cand` may be where it is among `now` (itself left out): no 3D collision.
fn clear_of(cand: &PlacedObject, now: &HashMap<String, PlacedObject>) -> bool {
    now.values()
        .filter(|o| o.name != cand.name && !o.is_flat())
        .all(|o| !geometry3d::collide(cand, o))
}

/// Where `o`, standing on `on`, ends: on its support's top, or on the floor with a note; the
/// reason it is dropped when the floor has no place either.
fn on_surface(
    refiner: &PhysicalRefiner,
    room: &Room,
    o: &PlacedObject,
    on: &str,
    given: &HashMap<&str, &PlacedObject>,
    now: &HashMap<String, PlacedObject>,
    floor: &Settled,
) -> Result<(PlacedObject, Option<String>), String> {
    let why = match now.get(on) {
        None => format!("{on}, which it stood on, is not placed"),
        Some(s) if s.is_flat() || is_seat(&s.category) => {
            format!("{on} holds nothing (a floor covering or a seat)")
        }
        Some(support) => {
            if let Some(spot) = on_top(refiner, room, o, support, given.get(on), now, floor) {
                return Ok((spot, None));
            }
            format!("no room left on top of {on}")
        }
    };
    let down = PlacedObject {
        elevation: 0.0,
        on: None,
        wall: None,
        ..o.clone()
    };
    match on_floor(refiner, room, &down, floor) {
        Some(fp) => Ok((
            PlacedObject {
                position: [fp.center.x, fp.center.y],
                rotation: fp.rotation,
                ..down
            },
            Some(format!("{why}; it stands on the floor")),
        )),
        None => Err(format!("{why}, and no place is left on the floor")),
    }
}

/// The nearest free spot for `o` on top of `support` (which stood at `before` when `o` was
/// posed): where it was carried along with its support, else the top's grid points, nearest
/// first, with the support's turn and then its own.
fn on_top(
    refiner: &PhysicalRefiner,
    room: &Room,
    o: &PlacedObject,
    support: &PlacedObject,
    before: Option<&&PlacedObject>,
    now: &HashMap<String, PlacedObject>,
    floor: &Settled,
) -> Option<PlacedObject> {
    let carried = match before {
        Some(b) => carry(o, b, support),
        None => o.clone(),
    };
    let at = |centre: DVec2, rotation: f64| PlacedObject {
        position: [centre.x, centre.y],
        rotation: normalize_degrees(rotation),
        elevation: support.top(),
        ..o.clone()
    };
    let fits = |c: &PlacedObject| {
        surface_problem(c, support).is_none()
            && clear_of(c, now)
            && floor_ok(room, floor, &c.footprint(), c.top())
    };
    let first = at(DVec2::from(carried.position), carried.rotation);
    if fits(&first) {
        return Some(first);
    }
    let top = support.footprint();
    let step = refiner.config.grid_step_cm;
    let own = top.to_local(DVec2::from(carried.position));
    // Turned as the support first (a TV faces as its stand), then as it was.
    for rotation in [support.rotation, carried.rotation] {
        let fp = Footprint::new(
            DVec2::ZERO,
            o.size[0],
            o.size[1],
            rotation - support.rotation,
        );
        let room_left = top.half - fp.aabb_half();
        if room_left.x < -1e-9 || room_left.y < -1e-9 {
            continue;
        }
        let axis = |half: f64| {
            let n = (half / step).floor() as i64;
            let mut v: Vec<f64> = (-n..=n).map(|k| k as f64 * step).collect();
            v.extend([-half, half]);
            v
        };
        let mut spots: Vec<DVec2> = axis(room_left.x.max(0.0))
            .into_iter()
            .flat_map(|x| {
                axis(room_left.y.max(0.0))
                    .into_iter()
                    .map(move |y| DVec2::new(x, y))
            })
            .collect();
        spots.sort_by(|a, b| {
            a.distance_squared(own)
                .total_cmp(&b.distance_squared(own))
                .then(a.x.total_cmp(&b.x))
                .then(a.y.total_cmp(&b.y))
        });
        for l in spots {
            let centre = top.center + top.right * l.x + top.front * l.y;
            let cand = at(centre, rotation);
            if fits(&cand) {
                return Some(cand);
            }
        }
    }
    None
}

/// `o` carried along with its support from `from` to `to`: the same place and turn on its top.
fn carry(o: &PlacedObject, from: &PlacedObject, to: &PlacedObject) -> PlacedObject {
    let local = from.footprint().to_local(DVec2::from(o.position));
    let after = to.footprint();
    let centre = after.center + after.right * local.x + after.front * local.y;
    PlacedObject {
        position: [centre.x, centre.y],
        rotation: normalize_degrees(o.rotation + to.rotation - from.rotation),
        ..o.clone()
    }
}

/// Whether a footprint whose top is `top` cm high stands inside the room, out of the zones that
/// bind it.
fn floor_ok(room: &Room, floor: &Settled, fp: &Footprint, top: f64) -> bool {
    fp.inside(room) && floor.fits_room(fp, top)
}

/// The nearest free floor pose for `o` (now a floor object) among the `floor` footprints.
fn on_floor(
    refiner: &PhysicalRefiner,
    room: &Room,
    o: &PlacedObject,
    floor: &Settled,
) -> Option<Footprint> {
    let item = Item {
        index: 0,
        given: o.footprint(),
        height: o.size[2],
        wants_wall: false,
        settled_first: false,
    };
    refiner.place_one(room, &item, floor).map(|p| p.footprint)
}

/// Where wall object `o`, given on wall `w`, ends: where it is when it hangs properly, else the
/// nearest free stretch at its height, its own wall first; `None` when no wall has one.
fn on_walls(
    refiner: &PhysicalRefiner,
    room: &Room,
    o: &PlacedObject,
    w: usize,
    now: &HashMap<String, PlacedObject>,
) -> Option<(PlacedObject, Option<String>)> {
    let hangs = |c: &PlacedObject, wall: usize| {
        wall_problem(c, room, wall).is_none()
            && opening_problem(c, room, wall).is_none()
            && clear_of(c, now)
            && c.footprint().inside(room)
    };
    if hangs(o, w) {
        return Some((o.clone(), None));
    }
    let origin = DVec2::from(o.position);
    let mut walls = Wall::all(room);
    walls.sort_by(|a, b| {
        (a.index() != w).cmp(&(b.index() != w)).then(
            a.segment_distance(origin)
                .total_cmp(&b.segment_distance(origin)),
        )
    });
    let step = refiner.config.grid_step_cm;
    let (half_w, half_d) = (o.size[0] / 2.0, o.size[1] / 2.0);
    for wall in walls {
        let len = wall.length();
        if len < 2.0 * half_w {
            continue;
        }
        let own = wall.along(origin).clamp(half_w, len - half_w);
        let n = (len / step).ceil() as i64;
        let mut ts: Vec<f64> = (0..=n)
            .map(|k| (k as f64 * step).clamp(half_w, len - half_w))
            .collect();
        ts.push(own);
        ts.sort_by(|a, b| {
            (a - own)
                .abs()
                .total_cmp(&(b - own).abs())
                .then(a.total_cmp(b))
        });
        ts.dedup();
        for t in ts {
            let centre = wall.edge.start + wall.direction() * t + wall.inward_normal() * half_d;
            let cand = PlacedObject {
                position: [centre.x, centre.y],
                rotation: wall.inward_rotation(),
                wall: Some(wall.index()),
                ..o.clone()
            };
            if hangs(&cand, wall.index()) {
                let note = (wall.index() != w).then(|| {
                    format!(
                        "no free stretch on wall {w}; moved to the {} wall",
                        wall.name()
                    )
                });
                return Some((cand, note));
            }
        }
    }
    None
}
