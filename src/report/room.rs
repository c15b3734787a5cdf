//! The room of a report in words: its size, a polygon's corners, and each door and window.

use crate::scene::Room;
use disco_core::room::{Hinge, Swing};

/// The room's size in words: a rectangle's sides, else its walls, bounding box and area.
pub(super) fn room_size(room: &Room) -> String {
    if room.is_rectangle() {
        return format!("{} × {} cm", room.width, room.depth);
    }
    format!(
        "{} walls in {} × {} cm, {:.1} m²",
        room.walls().len(),
        room.width,
        room.depth,
        room.area() / 10_000.0
    )
}

/// A polygon room's outline as its corners, in order (wall `i` from corner `i` to the next);
/// `None` for a rectangle.
pub(super) fn outline_words(room: &Room) -> Option<String> {
    let points = room.polygon.as_ref()?;
    Some(
        points
            .iter()
            .map(|[x, y]| format!("({x}, {y})"))
            .collect::<Vec<_>>()
            .join(", "),
    )
}

/// Each door and window in words: its wall, where along it, how wide, and how it opens.
pub(super) fn opening_words(room: &Room) -> Vec<String> {
    let swing = |s: Swing| match s {
        Swing::In => "swings in",
        Swing::Out => "swings out",
        Swing::Sliding => "slides",
    };
    let hinge = |h: Hinge| match h {
        Hinge::Left => "hinge on the left",
        Hinge::Right => "hinge on the right",
    };
    let doors = room.doors.iter().map(|d| {
        let how = match d.swing {
            Swing::In | Swing::Out => format!("{}, {}", swing(d.swing), hinge(d.hinge)),
            Swing::Sliding => swing(d.swing).to_string(),
        };
        format!(
            "door on wall {} at {} cm, {} cm wide, {how}",
            d.wall, d.at, d.width
        )
    });
    let windows = room.windows.iter().map(|w| {
        format!(
            "window on wall {} at {} cm, {} cm wide, sill at {} cm, {} cm high",
            w.wall, w.at, w.width, w.sill, w.height
        )
    });
    doors.chain(windows).collect()
}
