//! What a relation may name as its target: an object of the layout, or a part of the room.
//!
//! Requests name walls, doors and windows as often as furniture ("the armchair facing the
//! window", "the printer near the door", "the sofa opposite window 1"), so a plan's relation or
//! `facing` target may be `door-N`, `window-N` or `wall-N` (indices as in the scene: wall `i`
//! runs from vertex `i` to vertex `i + 1`; doors and windows in the order the scene lists them).
//! An asset of that name always wins: a part is only looked up when no object has the name.
//!
//! A part is a thin footprint lying on its wall: as wide as the opening (or the wall), 2 cm
//! deep, its back on the wall line and its front into the room. So the relations' predicates
//! read it as they read a piece flat on that wall: *near* is the gap to the opening's span,
//! *faces* the line out of the subject's front meeting that span, *opposite* across the room and
//! facing it (the part's front looks into the room), *in front of* within its span and
//! 150 cm (the relations' `FRONT_GAP_CM`) of it; *beside* means next to its span along its wall
//! (the relations' `beside_part`).

use glam::DVec2;

use crate::geometry::Footprint;
use crate::room::{Edge, Room};

/// How deep (cm) a room part's footprint is.
pub const PART_DEPTH_CM: f64 = 2.0;

/// A part of the room a relation can name.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum RoomPart {
    /// Door `i` of the scene.
    Door(usize),
    /// Window `i` of the scene.
    Window(usize),
    /// Wall `i` (from vertex `i` to vertex `i + 1`).
    Wall(usize),
}

impl RoomPart {
    /// Reads `door-0`, `window-2`, `wall-1` (also with a space or an underscore, any case);
    /// `None` for anything else.
    pub fn parse(name: &str) -> Option<RoomPart> {
        let lower = name.trim().to_ascii_lowercase();
        let (kind, index) = lower.rsplit_once(['-', '_', ' '])?;
        let i: usize = index.parse().ok()?;
        match kind.trim() {
            "door" => Some(RoomPart::Door(i)),
            "window" => Some(RoomPart::Window(i)),
            "wall" => Some(RoomPart::Wall(i)),
            _ => None,
        }
    }

    /// The part's canonical name (`door-0`).
    pub fn name(self) -> String {
        match self {
            RoomPart::Door(i) => format!("door-{i}"),
            RoomPart::Window(i) => format!("window-{i}"),
            RoomPart::Wall(i) => format!("wall-{i}"),
        }
    }

    /// The part's footprint in `room`: on its wall, across its span, front into the room;
    /// `None` when the room has no such part.
    pub fn footprint(self, room: &Room) -> Option<Footprint> {
        let walls = room.walls();
        let span = |wall: usize, at: f64, width: f64| -> Option<Footprint> {
            let edge: &Edge = walls.get(wall)?;
            let (s, e) = room.opening_ends(wall, at, width)?;
            Some(strip(edge, s, e))
        };
        match self {
            RoomPart::Door(i) => {
                let d = room.doors.get(i)?;
                span(d.wall, d.at, d.width)
            }
            RoomPart::Window(i) => {
                let w = room.windows.get(i)?;
                span(w.wall, w.at, w.width)
            }
            RoomPart::Wall(i) => {
                let edge = walls.get(i)?;
                Some(strip(edge, edge.start, edge.end))
            }
        }
    }
}

/// A strip from `s` to `e` on `edge`, [`PART_DEPTH_CM`] deep, its back on the wall line.
fn strip(edge: &Edge, s: DVec2, e: DVec2) -> Footprint {
    let center = (s + e) / 2.0 + edge.inward_normal() * (PART_DEPTH_CM / 2.0);
    Footprint::new(center, s.distance(e), PART_DEPTH_CM, edge.inward_rotation())
}

/// Whether `name` is a part of `room` a relation may target (and not taken by an asset: the
/// caller checks that).
pub fn is_room_part(room: &Room, name: &str) -> bool {
    RoomPart::parse(name).is_some_and(|p| p.footprint(room).is_some())
}

/// The canonical name (`window-1`) of the room part `written` names (`Window 1`), if `room`
/// has it.
pub fn room_part_name(room: &Room, written: &str) -> Option<String> {
    RoomPart::parse(written)
        .filter(|p| p.footprint(room).is_some())
        .map(RoomPart::name)
}

/// The names of every part of `room` a relation may target: its doors, windows and walls, in
/// that order.
pub fn room_parts(room: &Room) -> Vec<String> {
    let doors = (0..room.doors.len()).map(RoomPart::Door);
    let windows = (0..room.windows.len()).map(RoomPart::Window);
    let walls = (0..room.walls().len()).map(RoomPart::Wall);
    doors
        .chain(windows)
        .chain(walls)
        .map(RoomPart::name)
        .collect()
}

/// Whether `relation` can take a room part as its target: every relation of the floor; not
/// `on` (a wall has no top) nor `above` (its target is a floor piece).
pub fn takes_room_part(relation: crate::plan::Relation) -> bool {
    !relation.off_floor()
}

/// The footprint of the room part `name`, if `name` is one of `room`'s.
pub fn room_part_footprint(room: &Room, name: &str) -> Option<Footprint> {
    RoomPart::parse(name)?.footprint(room)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::room::{Door, Window};

    fn room() -> Room {
        // 500 x 400, a door on the bottom wall at x = 100, a window on the top wall (wall 2
        // runs from (500, 400) to (0, 400)) 150 cm from its start, so centred at x = 350.
        let mut r = Room::rect(500.0, 400.0);
        r.doors.push(Door::new(0, 100.0, 90.0));
        r.windows.push(Window {
            wall: 2,
            at: 150.0,
            width: 120.0,
            sill: 90.0,
            height: 120.0,
        });
        r
    }

    #[test]
    fn names_are_read_in_any_spelling_and_checked_against_the_room() {
        assert_eq!(RoomPart::parse("door-0"), Some(RoomPart::Door(0)));
        assert_eq!(RoomPart::parse("Window 1"), Some(RoomPart::Window(1)));
        assert_eq!(RoomPart::parse("wall_3"), Some(RoomPart::Wall(3)));
        assert_eq!(RoomPart::parse("sofa-0"), None);
        assert_eq!(RoomPart::parse("door"), None);
        let r = room();
        assert!(is_room_part(&r, "door-0") && is_room_part(&r, "window-0"));
        assert!(is_room_part(&r, "wall-3"));
        assert!(!is_room_part(&r, "door-1"), "the room has one door");
        assert!(!is_room_part(&r, "wall-4"), "a rectangle has four walls");
        assert_eq!(
            room_parts(&r),
            ["door-0", "window-0", "wall-0", "wall-1", "wall-2", "wall-3"]
        );
        assert_eq!(room_part_name(&r, "Window 0").as_deref(), Some("window-0"));
        assert_eq!(room_part_name(&r, "window-1"), None);
    }

    #[test]
    fn a_window_lies_on_its_wall_facing_into_the_room() {
        let w = room_part_footprint(&room(), "window-0").unwrap();
        assert!((w.center.x - 350.0).abs() < 1e-6, "{:?}", w.center);
        assert!((w.center.y - 399.0).abs() < 1e-6, "{:?}", w.center);
        assert!(
            (w.front.y + 1.0).abs() < 1e-9,
            "front into the room: {:?}",
            w.front
        );
        assert!((w.half.x - 60.0).abs() < 1e-9);
    }
}
