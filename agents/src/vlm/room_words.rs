//! A room's outline and openings in words, for the prompts: the corners, each wall with its
//! length and the side the room lies on, then the doors and windows with what they keep clear.
//! A plain rectangle without openings has no such text, so its prompts stay as they were.

use std::fmt::Write as _;

use glam::DVec2;

use disco_core::room::{DOOR_CLEARANCE_CM, Hinge, Room, Swing, WINDOW_CLEARANCE_CM};

/// The room's shape and openings in words, `None` for a rectangle without doors or windows.
pub fn describe_room(room: &Room) -> Option<String> {
    if room.is_rectangle() && !room.has_openings() {
        return None;
    }
    let walls = room.walls();
    let mut out = String::new();
    if room.is_rectangle() {
        out.push_str("The floor is the whole rectangle. Its walls:\n");
    } else {
        let corners: Vec<String> = room.outline().into_iter().map(point).collect();
        let _ = writeln!(
            out,
            "The floor is not a rectangle: its outline runs counter-clockwise through the corners {}. Only the floor inside this outline is part of the room; every object must stand inside it. Its walls (wall i runs from corner i to the next one):",
            corners.join(", ")
        );
    }
    out.push_str(&wall_lines(room));
    for (i, d) in room.doors.iter().enumerate() {
        let Some(e) = walls.get(d.wall) else {
            continue;
        };
        let reach = match d.swing {
            Swing::In => DOOR_CLEARANCE_CM.max(d.width),
            Swing::Out | Swing::Sliding => DOOR_CLEARANCE_CM,
        };
        let how = match (d.swing, d.hinge) {
            (Swing::In, Hinge::Left) => "opens into the room, hinged on the left seen from inside",
            (Swing::In, Hinge::Right) => {
                "opens into the room, hinged on the right seen from inside"
            }
            (Swing::Out, _) => "opens outwards",
            (Swing::Sliding, _) => "slides",
        };
        let _ = writeln!(
            out,
            "- door {i} in wall {}: {} cm wide, centred at {}; it {how}. Keep the {} x {} cm in front of it free of everything but rugs and mats, and leave a walkway from it to every piece.",
            d.wall,
            number(d.width),
            point(e.point(d.at)),
            number(d.width),
            number(reach)
        );
    }
    for (i, w) in room.windows.iter().enumerate() {
        let Some(e) = walls.get(w.wall) else {
            continue;
        };
        let _ = writeln!(
            out,
            "- window {i} in wall {}: {} cm wide, centred at {}, its sill {} cm above the floor. Nothing taller than {} cm may stand within {} cm of the wall along it; a piece no taller may stand against the wall under it.",
            w.wall,
            number(w.width),
            point(e.point(w.at)),
            number(w.sill),
            number(w.sill),
            number(WINDOW_CLEARANCE_CM)
        );
    }
    let analysis = room.analysis();
    if analysis.zones.len() > 1 || analysis.main_door.is_some() {
        out.push_str("Its zones and the roles of its walls (plans may name them):\n");
        for line in analysis.describe() {
            let _ = writeln!(out, "- {line}");
        }
    }
    Some(out.trim_end().to_string())
}

/// The walls of a plain rectangle without openings, by index, for prompts where a model names a
/// wall (a painting on wall 2): the rectangle has no other text ([`describe_room`] is `None`),
/// and a room with an outline or openings lists its walls already.
pub fn describe_walls(room: &Room) -> String {
    let mut out = String::from("The floor is the whole rectangle. Its walls:\n");
    out.push_str(&wall_lines(room));
    out.trim_end().to_string()
}

/// One line per wall: its index, its ends, its length and the side the room lies on.
fn wall_lines(room: &Room) -> String {
    let mut out = String::new();
    for e in &room.walls() {
        let r = e.inward_rotation().round();
        let slant = if r % 90.0 == 0.0 {
            String::new()
        } else {
            format!("; a piece with its back on it is turned {}", number(r))
        };
        let _ = writeln!(
            out,
            "- wall {}: from {} to {}, {} cm long, {}{slant}",
            e.index,
            point(e.start),
            point(e.end),
            number(e.length()),
            side_words(e.inward_normal())
        );
    }
    out
}

/// What the room's windows mean for a piece `height` cm tall, in one clause (each window's rule
/// is stated once, with the room): the windows it fits under (no taller than the sill), and
/// those it is too tall for, whose wall it keeps 40 cm clear of along the window; `None` in a
/// room without windows.
pub fn window_rules(room: &Room, height: f64) -> Option<String> {
    type Sills = Vec<(usize, f64)>;
    let (under, over): (Sills, Sills) = room
        .windows
        .iter()
        .enumerate()
        .map(|(i, w)| (i, w.sill))
        .partition(|&(_, sill)| height <= sill);
    let list = |ws: &[(usize, f64)]| {
        let names: Vec<String> = ws.iter().map(|(i, _)| i.to_string()).collect();
        let sills: Vec<String> = ws.iter().map(|(_, s)| number(*s)).collect();
        let plural = if ws.len() > 1 { "s" } else { "" };
        (
            format!("window{plural} {}", names.join(", ")),
            format!("sill{plural} {} cm", sills.join(", ")),
        )
    };
    let mut parts = Vec::new();
    if !under.is_empty() {
        let (w, s) = list(&under);
        parts.push(format!("it may stand under {w} ({s})"));
    }
    if !over.is_empty() {
        let (w, s) = list(&over);
        parts.push(format!(
            "it is too tall for under {w} ({s}): keep it {} cm clear",
            number(WINDOW_CLEARANCE_CM)
        ));
    }
    (!parts.is_empty()).then(|| parts.join("; "))
}

/// Which side of a wall the room lies on, by the wall's inward normal `n`: "the room lies above
/// it (+y)", or for a slanted wall, towards the upper left and so on.
fn side_words(n: DVec2) -> String {
    let axis = |v: f64, pos: &'static str, neg: &'static str| {
        if v > 0.2 {
            Some(pos)
        } else if v < -0.2 {
            Some(neg)
        } else {
            None
        }
    };
    let vertical = axis(n.y, "above", "below");
    let horizontal = axis(n.x, "right", "left");
    match (vertical, horizontal) {
        (Some(v), None) => format!("the room lies {v} it"),
        (None, Some(h)) => format!("the room lies to its {h}"),
        (Some(v), Some(h)) => {
            let up = if v == "above" { "upper" } else { "lower" };
            format!("slanted, the room lies to its {up} {h}")
        }
        (None, None) => "the room lies beside it".to_string(),
    }
}

/// A point as `(x, y)` in whole centimetres where they are whole.
fn point(p: DVec2) -> String {
    format!("({}, {})", number(p.x), number(p.y))
}

/// A length rounded to a millimetre, without a fraction when it is whole.
fn number(v: f64) -> String {
    let r = (v * 10.0).round() / 10.0;
    if r.fract() == 0.0 {
        format!("{}", r as i64)
    } else {
        format!("{r}")
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use disco_core::room::{Door, Window};

    #[test]
    fn a_plain_rectangle_has_no_words_but_can_name_its_walls() {
        let room = Room::rect(400.0, 300.0);
        assert_eq!(describe_room(&room), None);
        let walls = describe_walls(&room);
        assert!(
            walls
                .contains("- wall 0: from (0, 0) to (400, 0), 400 cm long, the room lies above it"),
            "{walls}"
        );
        assert!(
            walls.ends_with(
                "- wall 3: from (0, 300) to (0, 0), 300 cm long, the room lies to its right"
            ),
            "{walls}"
        );
    }

    #[test]
    fn an_l_shaped_room_with_a_door_and_a_window() {
        let mut room = Room::from_polygon(vec![
            [0.0, 0.0],
            [480.0, 0.0],
            [480.0, 280.0],
            [320.0, 280.0],
            [320.0, 420.0],
            [0.0, 420.0],
        ]);
        room.doors.push(Door {
            wall: 0,
            at: 400.0,
            width: 80.0,
            swing: Swing::In,
            hinge: Hinge::Right,
        });
        room.windows.push(Window {
            wall: 5,
            at: 210.0,
            width: 140.0,
            sill: 90.0,
            height: 120.0,
        });
        let text = describe_room(&room).unwrap();
        assert!(text.contains("(320, 280)"), "{text}");
        assert!(
            text.contains(
                "- wall 2: from (480, 280) to (320, 280), 160 cm long, the room lies below it"
            ),
            "{text}"
        );
        assert!(
            text.contains(
                "- wall 5: from (0, 420) to (0, 0), 420 cm long, the room lies to its right"
            ),
            "{text}"
        );
        assert!(
            text.contains("- door 0 in wall 0: 80 cm wide, centred at (400, 0)"),
            "{text}"
        );
        assert!(
            text.contains("- window 0 in wall 5: 140 cm wide, centred at (0, 210)"),
            "{text}"
        );
    }

    #[test]
    fn a_slanted_wall_says_which_way_the_room_lies() {
        let room = Room::from_polygon(vec![
            [0.0, 0.0],
            [400.0, 0.0],
            [400.0, 240.0],
            [260.0, 360.0],
            [0.0, 360.0],
        ]);
        let text = describe_room(&room).unwrap();
        assert!(
            text.contains("wall 2: from (400, 240) to (260, 360), 184.4 cm long, slanted, the room lies to its lower left"),
            "{text}"
        );
    }
}
