//! Checks a room against docs/formats.md, "Rooms": sides and outline, then openings. Each
//! refusal names the file, the field and the reason.

use std::path::Path;

use glam::DVec2;

use super::{Room, distance_to_segment, signed_area};
use crate::error::{Error, Result};
use crate::polygon::TurnedRect;
use crate::units::{MAX_ROOM_SIDE_CM, MIN_ROOM_SIDE_CM, show_number};

/// Shortest wall accepted, in cm: shorter edges are almost surely typing slips.
const MIN_WALL_CM: f64 = 1.0;

/// Most vertices of a room's outline. Every placement test walks the outline, so a room of
/// thousands of walls validates but cannot be furnished in reasonable time (a 5,000-vertex
/// round room missed the designer's deadline); 256 walls is more than any real floor plan.
const MAX_OUTLINE_VERTICES: usize = 256;

/// Checks a room: finite, positive sides of at least [`MIN_ROOM_SIDE_CM`] and at most
/// [`MAX_ROOM_SIDE_CM`]; a polygon that is simple, counter-clockwise and starts its bounding box
/// at the origin; openings that lie wholly on their wall, do not overlap, and (for doors) keep a
/// clear zone inside the room.
pub fn validate_room(path: &Path, field: &str, room: &Room) -> Result<()> {
    if let Some(points) = &room.polygon {
        validate_polygon(path, &format!("{field}.polygon"), points)?;
    }
    validate_sides(path, field, room)?;
    validate_openings(path, field, room)
}

fn validate_sides(path: &Path, field: &str, room: &Room) -> Result<()> {
    if room.width > 0.0
        && room.depth > 0.0
        && (room.width < MIN_ROOM_SIDE_CM || room.depth < MIN_ROOM_SIDE_CM)
    {
        return Err(Error::invalid(
            path,
            field,
            format!(
                "a {} x {} cm room is too small to be real: sizes are in centimetres (did you mean {} x {}?)",
                show_number(room.width),
                show_number(room.depth),
                show_number(room.width * 100.0),
                show_number(room.depth * 100.0)
            ),
        ));
    }
    for (name, v) in [("width", room.width), ("depth", room.depth)] {
        let field = if room.polygon.is_some() {
            format!("{field}.polygon (its {name})")
        } else {
            format!("{field}.{name}")
        };
        if !v.is_finite() {
            return Err(Error::invalid(
                path,
                field,
                format!("must be a finite number, got {}", show_number(v)),
            ));
        }
        if v <= 0.0 {
            return Err(Error::invalid(
                path,
                field,
                format!("must be positive, got {} cm", show_number(v)),
            ));
        }
        if v > MAX_ROOM_SIDE_CM {
            return Err(Error::invalid(
                path,
                field,
                format!(
                    "{} cm is over the {MAX_ROOM_SIDE_CM} cm (100 m) limit; sizes are in centimetres",
                    show_number(v)
                ),
            ));
        }
    }
    Ok(())
}

fn validate_polygon(path: &Path, field: &str, points: &[[f64; 2]]) -> Result<()> {
    if points.len() < 3 {
        return Err(Error::invalid(
            path,
            field,
            format!("needs at least 3 vertices, got {}", points.len()),
        ));
    }
    if points.len() > MAX_OUTLINE_VERTICES {
        return Err(Error::invalid(
            path,
            field,
            format!(
                "has {} vertices; an outline may have at most {MAX_OUTLINE_VERTICES} (simplify the curve: a wall every few degrees is enough)",
                points.len()
            ),
        ));
    }
    for (i, p) in points.iter().enumerate() {
        if !p[0].is_finite() || !p[1].is_finite() {
            return Err(Error::invalid(
                path,
                format!("{field}[{i}]"),
                "coordinates must be finite numbers",
            ));
        }
    }
    let v: Vec<DVec2> = points.iter().map(|p| DVec2::new(p[0], p[1])).collect();
    let (min_x, min_y) = v.iter().fold((f64::INFINITY, f64::INFINITY), |(x, y), p| {
        (x.min(p.x), y.min(p.y))
    });
    if min_x != 0.0 || min_y != 0.0 {
        return Err(Error::invalid(
            path,
            field,
            format!(
                "the outline's lowest x and y must be 0 (the origin is the room's bottom-left), got {} and {}: shift every vertex by ({}, {})",
                show_number(min_x),
                show_number(min_y),
                show_number(-min_x),
                show_number(-min_y)
            ),
        ));
    }
    let n = v.len();
    for i in 0..n {
        let len = v[i].distance(v[(i + 1) % n]);
        if len < MIN_WALL_CM {
            return Err(Error::invalid(
                path,
                format!("{field}[{i}]"),
                format!(
                    "wall {i} (vertex {i} to vertex {}) is {} cm long: repeated or nearly repeated vertex (do not repeat the first vertex at the end)",
                    (i + 1) % n,
                    show_number(len)
                ),
            ));
        }
    }
    if let Some((a, b)) = crossing_walls(&v) {
        return Err(Error::invalid(
            path,
            field,
            format!("the outline crosses itself: wall {a} meets wall {b}"),
        ));
    }
    let area = signed_area(&v);
    if area.abs() < 1.0 {
        return Err(Error::invalid(
            path,
            field,
            "the outline encloses no area (degenerate polygon)",
        ));
    }
    if area < 0.0 {
        return Err(Error::invalid(
            path,
            field,
            "the vertices run clockwise; list them counter-clockwise (walls are numbered from the first vertex)",
        ));
    }
    Ok(())
}

/// The first pair of non-adjacent walls that touch, or adjacent walls that fold back on each
/// other, if any.
fn crossing_walls(v: &[DVec2]) -> Option<(usize, usize)> {
    let n = v.len();
    for i in 0..n {
        let (a, b) = (v[i], v[(i + 1) % n]);
        for j in i + 1..n {
            let (c, d) = (v[j], v[(j + 1) % n]);
            let adjacent = j == i + 1 || (i == 0 && j == n - 1);
            if adjacent {
                // Adjacent walls share one vertex; they fold back if the far end of one lies
                // on the other.
                let (far_i, far_j) = if j == i + 1 { (a, d) } else { (b, c) };
                if distance_to_segment(far_j, a, b) < 1e-6
                    || distance_to_segment(far_i, c, d) < 1e-6
                {
                    return Some((i, j));
                }
            } else if segments_touch(a, b, c, d) {
                return Some((i, j));
            }
        }
    }
    None
}

fn segments_touch(a: DVec2, b: DVec2, c: DVec2, d: DVec2) -> bool {
    let o = |p: DVec2, q: DVec2, r: DVec2| (q - p).perp_dot(r - p);
    let (d1, d2, d3, d4) = (o(c, d, a), o(c, d, b), o(a, b, c), o(a, b, d));
    if ((d1 > 0.0) != (d2 > 0.0)) && ((d3 > 0.0) != (d4 > 0.0)) && d1 != 0.0 && d2 != 0.0 {
        return true;
    }
    let eps = 1e-6;
    distance_to_segment(a, c, d) < eps
        || distance_to_segment(b, c, d) < eps
        || distance_to_segment(c, a, b) < eps
        || distance_to_segment(d, a, b) < eps
}

fn validate_openings(path: &Path, field: &str, room: &Room) -> Result<()> {
    let walls = room.walls();
    // (field, wall, start, end) of every opening, to check overlaps.
    let mut spans: Vec<(String, usize, f64, f64)> = Vec::new();
    let doors = room.doors.iter().map(|d| (d.wall, d.at, d.width, None));
    let windows = room
        .windows
        .iter()
        .map(|w| (w.wall, w.at, w.width, Some((w.sill, w.height))));
    for (k, (wall, at, width, window)) in doors.chain(windows).enumerate() {
        let (kind, i) = if k < room.doors.len() {
            ("doors", k)
        } else {
            ("windows", k - room.doors.len())
        };
        let here = format!("{field}.{kind}[{i}]");
        let Some(edge) = walls.get(wall) else {
            return Err(Error::invalid(
                path,
                format!("{here}.wall"),
                format!(
                    "there is no wall {wall}: the room has walls 0 to {}",
                    walls.len() - 1
                ),
            ));
        };
        validate_opening_numbers(path, &here, at, width, window)?;
        let (lo, hi) = (at - width / 2.0, at + width / 2.0);
        let len = edge.length();
        if lo < -1e-6 || hi > len + 1e-6 {
            return Err(Error::invalid(
                path,
                here,
                format!(
                    "spans {} to {} cm along wall {wall}, which is {} cm long: an opening must lie wholly on its wall",
                    show_number(lo),
                    show_number(hi),
                    show_number(len)
                ),
            ));
        }
        if let Some((other, ..)) = spans
            .iter()
            .find(|(_, w, a, b)| *w == wall && lo < *b - 1e-6 && *a < hi - 1e-6)
        {
            return Err(Error::invalid(
                path,
                here,
                format!("overlaps {other} on wall {wall}"),
            ));
        }
        spans.push((here, wall, lo, hi));
    }
    validate_door_zones(path, field, room)
}

/// An opening's numbers: `at` finite, `width` finite and positive, a window's `sill` finite and
/// not negative, its `height` finite and positive.
fn validate_opening_numbers(
    path: &Path,
    here: &str,
    at: f64,
    width: f64,
    window: Option<(f64, f64)>,
) -> Result<()> {
    let (sill, height) = window.map_or((None, None), |(s, h)| (Some(s), Some(h)));
    let checks = [
        ("at", Some(at), false),
        ("width", Some(width), true),
        ("sill", sill, false),
        ("height", height, true),
    ];
    for (name, value, positive) in checks {
        let Some(v) = value else { continue };
        let bad = !v.is_finite() || (positive && v <= 0.0) || (name == "sill" && v < 0.0);
        if bad {
            let wanted = if name == "sill" {
                "a finite number of cm >= 0"
            } else {
                "a finite positive number of cm"
            };
            return Err(Error::invalid(
                path,
                format!("{here}.{name}"),
                format!("must be {wanted}, got {}", show_number(v)),
            ));
        }
    }
    Ok(())
}

/// A door's keep-clear zone must lie in the room: someone has to be able to walk in. The zone
/// is tested exactly, as the rectangle it is, the way an object's footprint is
/// ([`TurnedRect::inside`]): every corner in the room, no corner of the outline strictly inside
/// the zone and no wall crossing it, however thin the notch.
fn validate_door_zones(path: &Path, field: &str, room: &Room) -> Result<()> {
    for zone in room.keep_clear() {
        let super::ZoneKind::Door(i) = zone.kind else {
            continue;
        };
        if !zone_rect(&zone.corners).inside(&room.outline()) {
            return Err(Error::invalid(
                path,
                format!("{field}.doors[{i}]"),
                format!(
                    "its keep-clear zone (the leaf's sweep and {} cm of walkway) leaves the room or is cut by a wall: move the door away from the corner or make it slide",
                    super::DOOR_CLEARANCE_CM
                ),
            ));
        }
    }
    Ok(())
}

/// The rectangle with corners `c` (`[a, b, b + n, a + n]`: a side on the wall, reaching `n`
/// into the room).
fn zone_rect(c: &[DVec2; 4]) -> TurnedRect {
    let along = c[1] - c[0];
    let reach = c[3] - c[0];
    TurnedRect {
        center: (c[0] + c[1] + c[2] + c[3]) / 4.0,
        half: DVec2::new(along.length(), reach.length()) / 2.0,
        right: along.normalize_or_zero(),
        front: reach.normalize_or_zero(),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::room::Door;

    fn check(room: &Room) -> Result<()> {
        validate_room(Path::new("s.json"), "room", room)
    }

    #[test]
    fn a_wall_notch_across_a_door_zone_is_refused_however_thin() {
        // A 1 cm slit from the left wall runs right across the door's zone (x 155..245,
        // y 0..90) and ends beyond it: no vertex of the outline lies in the zone.
        let mut notched = Room::from_polygon(vec![
            [0.0, 0.0],
            [400.0, 0.0],
            [400.0, 400.0],
            [0.0, 400.0],
            [0.0, 41.0],
            [300.0, 41.0],
            [300.0, 40.0],
            [0.0, 40.0],
        ]);
        check(&notched).unwrap();
        notched.doors.push(Door::new(0, 200.0, 90.0));
        let e = check(&notched).unwrap_err().to_string();
        assert!(e.contains("room.doors[0]: its keep-clear zone"), "{e}");
        // The same door with the slit above its zone is fine.
        let mut clear = notched.clone();
        clear.polygon = Some(vec![
            [0.0, 0.0],
            [400.0, 0.0],
            [400.0, 400.0],
            [0.0, 400.0],
            [0.0, 201.0],
            [300.0, 201.0],
            [300.0, 200.0],
            [0.0, 200.0],
        ]);
        check(&clear).unwrap();
    }

    #[test]
    fn a_door_zone_on_a_slanted_wall_is_tested_as_its_rectangle() {
        // A room with a slanted wall 2, from (600, 600) to (0, 300).
        let mut room =
            Room::from_polygon(vec![[0.0, 0.0], [600.0, 0.0], [600.0, 600.0], [0.0, 300.0]]);
        room.doors.push(Door::new(2, 335.0, 90.0));
        check(&room).unwrap();
        // Beside the acute corner at (600, 600), the zone pokes through wall 1.
        room.doors[0] = Door::new(2, 30.0, 50.0);
        assert!(check(&room).is_err());
    }

    #[test]
    fn an_outline_of_too_many_vertices_is_refused_with_the_limit() {
        let round = |n: usize| {
            let mut points: Vec<[f64; 2]> = (0..n)
                .map(|k| {
                    let a = std::f64::consts::TAU * k as f64 / n as f64;
                    [300.0 + 300.0 * a.cos(), 300.0 + 300.0 * a.sin()]
                })
                .collect();
            let min_x = points.iter().map(|p| p[0]).fold(f64::INFINITY, f64::min);
            let min_y = points.iter().map(|p| p[1]).fold(f64::INFINITY, f64::min);
            for p in &mut points {
                p[0] -= min_x;
                p[1] -= min_y;
            }
            Room::from_polygon(points)
        };
        check(&round(MAX_OUTLINE_VERTICES)).unwrap();
        let e = check(&round(5_000)).unwrap_err().to_string();
        assert!(
            e.contains("room.polygon: has 5000 vertices; an outline may have at most 256"),
            "{e}"
        );
    }
}
