//! Validity in three dimensions (docs/formats.md, "Objects off the floor"): one set of predicates
//! for what stands on what and what hangs where, used by the metrics, the PRT and the tests.
//!
//! - Two objects **collide** when their footprints collide and their height ranges overlap, so a
//!   lamp on a nightstand does not collide with it and a painting hangs above a sofa.
//! - An object **on a surface** stands at exactly its support's top
//!   ([`ELEVATION_TOL_CM`]), its footprint within the support's top ([`SURFACE_MARGIN_CM`]);
//!   nothing stands on a floor covering or a seat.
//! - An object **on a wall** has its back on that wall's segment, facing into the room, and does
//!   not cover a door below the door's top ([`DOOR_HEIGHT_CM`]) nor a window's opening.
//! - An object held by neither stands on the floor: its elevation is 0.

use std::collections::HashMap;

use glam::DVec2;

use crate::geometry::{WALL_ANGLE_DEG, WALL_GAP_CM, Wall};
use crate::layout::PlacedObject;
use crate::room::Room;
use crate::units::normalize_degrees;

/// How far (cm) an object's bottom may be from the height it should stand at (the floor, or its
/// support's top) and still stand there.
pub const ELEVATION_TOL_CM: f64 = 0.5;

/// How far (cm) an object's footprint may reach past the edge of the top it stands on.
pub const SURFACE_MARGIN_CM: f64 = 1.0;

/// The height (cm) of a door's opening: a wall object whose bottom is lower may not hang over it.
pub const DOOR_HEIGHT_CM: f64 = 210.0;

/// Height ranges closer than this (cm) do not overlap: a lamp's bottom meets its table's top.
const HEIGHT_EPS_CM: f64 = 1e-6;

/// Words of the categories nothing may stand on (matched inside the category name).
const SEAT_WORDS: [&str; 5] = ["chair", "stool", "sofa", "couch", "seat"];

/// Whether a category names something people sit on (nothing may stand on it).
pub fn is_seat(category: &str) -> bool {
    let c = category.to_lowercase();
    SEAT_WORDS.iter().any(|w| c.contains(w))
}

/// Whether the height ranges `[elevation, top]` of `a` and `b` overlap (touching does not).
pub fn heights_overlap(a: &PlacedObject, b: &PlacedObject) -> bool {
    a.elevation < b.top() - HEIGHT_EPS_CM && b.elevation < a.top() - HEIGHT_EPS_CM
}

/// Whether `a` and `b` collide in 3D: their footprints collide and their heights overlap. For
/// objects on the floor this is the footprint test alone.
pub fn collide(a: &PlacedObject, b: &PlacedObject) -> bool {
    heights_overlap(a, b) && a.footprint().collides(&b.footprint())
}

/// Whether `o` stands on the floor (its bottom within [`ELEVATION_TOL_CM`] of it): only such
/// objects block the way across the floor.
pub fn reaches_floor(o: &PlacedObject) -> bool {
    o.elevation <= ELEVATION_TOL_CM
}

/// Why `o` does not stand properly on `support`, if it does not: a floor covering or a seat holds
/// nothing, `o` must stand at the support's top and within it.
pub fn surface_problem(o: &PlacedObject, support: &PlacedObject) -> Option<String> {
    if support.is_flat() {
        return Some(format!(
            "stands on {}, a floor covering, which holds nothing",
            support.name
        ));
    }
    if is_seat(&support.category) {
        return Some(format!(
            "stands on {}, a seat, which holds nothing",
            support.name
        ));
    }
    if (o.elevation - support.top()).abs() > ELEVATION_TOL_CM {
        return Some(format!(
            "its bottom is at {:.1} cm, not on the top of {} at {:.1} cm",
            o.elevation,
            support.name,
            support.top()
        ));
    }
    let top = support.footprint();
    let limit = top.half + DVec2::splat(SURFACE_MARGIN_CM);
    let outside = o.footprint().corners().iter().any(|&c| {
        let l = top.to_local(c);
        l.x.abs() > limit.x || l.y.abs() > limit.y
    });
    outside.then(|| format!("reaches past the top of {}", support.name))
}

/// Where along wall `w` the back edge of `o` lies: (lowest, highest) distance from its start.
fn span_along(o: &PlacedObject, w: &Wall) -> (f64, f64) {
    let (bl, br) = o.footprint().back_edge();
    let (a, b) = (w.along(bl), w.along(br));
    (a.min(b), a.max(b))
}

/// Why `o` does not hang properly on wall `index` of `room`, if it does not: its back on the
/// wall's segment (within [`WALL_GAP_CM`]), its front into the room (within
/// [`WALL_ANGLE_DEG`]).
pub fn wall_problem(o: &PlacedObject, room: &Room, index: usize) -> Option<String> {
    let Some(w) = Wall::get(room, index) else {
        return Some(format!(
            "hangs on wall {index}, which the room does not have"
        ));
    };
    let turn = normalize_degrees(o.rotation - w.inward_rotation());
    if turn.min(360.0 - turn) > WALL_ANGLE_DEG {
        return Some(format!(
            "does not face into the room from the {} wall",
            w.name()
        ));
    }
    let (bl, br) = o.footprint().back_edge();
    if w.distance(bl) >= WALL_GAP_CM || w.distance(br) >= WALL_GAP_CM {
        return Some(format!("its back is not on the {} wall", w.name()));
    }
    let (lo, hi) = span_along(o, &w);
    if lo < -WALL_GAP_CM || hi > w.length() + WALL_GAP_CM {
        return Some(format!("reaches past the end of the {} wall", w.name()));
    }
    None
}

/// Why `o`, hanging on wall `index`, covers an opening of that wall, if it does: a door below the
/// door's top ([`DOOR_HEIGHT_CM`]), or a window's opening (from its sill to its top).
pub fn opening_problem(o: &PlacedObject, room: &Room, index: usize) -> Option<String> {
    let w = Wall::get(room, index)?;
    let (lo, hi) = span_along(o, &w);
    let across = |at: f64, width: f64| lo < at + width / 2.0 && hi > at - width / 2.0;
    for (k, d) in room.doors.iter().enumerate() {
        if d.wall == index && across(d.at, d.width) && o.elevation < DOOR_HEIGHT_CM {
            return Some(format!(
                "hangs over door {k} below its top ({DOOR_HEIGHT_CM} cm)"
            ));
        }
    }
    for (k, win) in room.windows.iter().enumerate() {
        if win.wall == index
            && across(win.at, win.width)
            && o.elevation < win.sill + win.height
            && o.top() > win.sill
        {
            return Some(format!("hangs over window {k}'s opening"));
        }
    }
    None
}

/// Why `o` is not held where it is, if it is not, among `placed` (by name): an object on another
/// must stand on its top ([`surface_problem`]), one on a wall must hang on it
/// ([`wall_problem`]), any other must stand on the floor.
pub fn support_problem(
    o: &PlacedObject,
    placed: &HashMap<&str, &PlacedObject>,
    room: &Room,
) -> Option<String> {
    match (&o.on, o.wall) {
        (Some(on), _) => match placed.get(on.as_str()) {
            Some(support) => surface_problem(o, support),
            None => Some(format!("stands on {on}, which is not placed")),
        },
        (None, Some(w)) => wall_problem(o, room, w),
        (None, None) => (!reaches_floor(o)).then(|| {
            format!(
                "floats {:.1} cm above the floor with nothing under it",
                o.elevation
            )
        }),
    }
}

/// Every object of `objects` that is not held where it is, as `name: why`, in their order.
pub fn unsupported(objects: &[PlacedObject], room: &Room) -> Vec<String> {
    let placed: HashMap<&str, &PlacedObject> =
        objects.iter().map(|o| (o.name.as_str(), o)).collect();
    objects
        .iter()
        .filter_map(|o| support_problem(o, &placed, room).map(|why| format!("{}: {why}", o.name)))
        .collect()
}

/// Every wall object of `objects` that covers an opening of its wall, as `name: why`.
pub fn over_openings(objects: &[PlacedObject], room: &Room) -> Vec<String> {
    objects
        .iter()
        .filter_map(|o| {
            let w = o.wall?;
            opening_problem(o, room, w).map(|why| format!("{}: {why}", o.name))
        })
        .collect()
}

#[cfg(test)]
mod tests;
