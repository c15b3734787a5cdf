//! The room: its floor outline (a rectangle or any simple polygon), its walls (the outline's
//! edges) and the openings in them (doors and windows), with the zones those openings keep clear
//! (docs/formats.md, "Rooms").
//!
//! A rectangle `{"width": W, "depth": D}` is the polygon (0,0), (W,0), (W,D), (0,D); its walls are
//! 0 bottom, 1 right, 2 top, 3 left. A scene without a polygon or openings reads and writes exactly
//! as before they existed.

pub mod analysis;
mod validate;

use glam::DVec2;
use serde::{Deserialize, Deserializer, Serialize, Serializer};

pub use crate::polygon::{distance_to_segment, point_in_polygon, signed_area};
pub use validate::validate_room;

/// How deep (cm) into the room a door's keep-clear rectangle reaches.
pub const DOOR_CLEARANCE_CM: f64 = 80.0;

/// How deep (cm) from the wall a window's zone reaches: an object taller than the sill may not
/// stand with its footprint in it.
pub const WINDOW_CLEARANCE_CM: f64 = 40.0;

/// The room's floor: its bounding extent, its outline when it is not a plain rectangle, and the
/// openings in its walls.
///
/// `width` and `depth` are the extent of the floor along x and y (for a polygon, of its bounding
/// box, whose bottom-left corner is the origin). Build one with [`Room::rect`] or
/// [`Room::from_polygon`].
#[derive(Debug, Clone, PartialEq)]
pub struct Room {
    /// Extent along x, in cm.
    pub width: f64,
    /// Extent along y, in cm.
    pub depth: f64,
    /// The outline, counter-clockwise, when the floor is not the `width` x `depth` rectangle.
    pub polygon: Option<Vec<[f64; 2]>>,
    /// Doors, each on one wall.
    pub doors: Vec<Door>,
    /// Windows, each on one wall.
    pub windows: Vec<Window>,
}

/// How a door's leaf moves.
#[derive(
    Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize, Default, schemars::JsonSchema,
)]
#[serde(rename_all = "lowercase")]
pub enum Swing {
    /// The leaf sweeps a quarter circle of radius `width` into the room.
    #[default]
    In,
    /// The leaf opens away from the room: no sweep inside.
    Out,
    /// The leaf slides along the wall: no sweep.
    Sliding,
}

/// The side of a door its hinge is on, seen from inside the room.
#[derive(
    Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize, Default, schemars::JsonSchema,
)]
#[serde(rename_all = "lowercase")]
pub enum Hinge {
    /// On the left, seen from inside.
    #[default]
    Left,
    /// On the right, seen from inside.
    Right,
}

/// A door in wall `wall`, centred `at` cm from the wall's start vertex.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize, schemars::JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct Door {
    /// Index of the wall (the polygon edge from vertex `wall` to vertex `wall + 1`).
    pub wall: usize,
    /// Distance along the wall from its start vertex to the door's centre, in cm.
    pub at: f64,
    /// Clear width of the opening, in cm.
    pub width: f64,
    /// How the leaf moves (default `in`).
    #[serde(default)]
    pub swing: Swing,
    /// Hinge side seen from inside (default `left`).
    #[serde(default)]
    pub hinge: Hinge,
}

impl Door {
    /// A door `width` cm wide centred `at` cm along wall `wall`, with the defaults of the file
    /// format: swinging in, hinged on the left.
    pub fn new(wall: usize, at: f64, width: f64) -> Door {
        Door {
            wall,
            at,
            width,
            swing: Swing::default(),
            hinge: Hinge::default(),
        }
    }
}

/// A window in wall `wall`, centred `at` cm from the wall's start vertex.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize, schemars::JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct Window {
    /// Index of the wall.
    pub wall: usize,
    /// Distance along the wall from its start vertex to the window's centre, in cm.
    pub at: f64,
    /// Width of the opening, in cm.
    pub width: f64,
    /// Height of the sill above the floor, in cm.
    pub sill: f64,
    /// Height of the opening, in cm.
    pub height: f64,
}

/// One wall: an edge of the outline, from `start` to `end`, with the room on its left.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Edge {
    /// The wall's index (its start vertex).
    pub index: usize,
    /// Start vertex.
    pub start: DVec2,
    /// End vertex.
    pub end: DVec2,
}

impl Edge {
    /// Length in cm.
    pub fn length(&self) -> f64 {
        self.start.distance(self.end)
    }

    /// Unit vector from `start` to `end`.
    pub fn direction(&self) -> DVec2 {
        (self.end - self.start).normalize_or_zero()
    }

    /// Unit vector pointing from the wall into the room (the left of a counter-clockwise edge).
    pub fn inward_normal(&self) -> DVec2 {
        self.direction().perp()
    }

    /// The rotation (degrees, clockwise from +y) that turns an object's front into the room, its
    /// back to this wall.
    pub fn inward_rotation(&self) -> f64 {
        let n = self.inward_normal();
        crate::units::normalize_degrees(n.x.atan2(n.y).to_degrees())
    }

    /// The point `along` cm from the start.
    pub fn point(&self, along: f64) -> DVec2 {
        self.start + self.direction() * along
    }

    /// How far along the wall the projection of `p` falls (may be outside `0..length`).
    pub fn along(&self, p: DVec2) -> f64 {
        (p - self.start).dot(self.direction())
    }

    /// Signed distance from the wall's line to `p`, positive on the room's side.
    pub fn offset(&self, p: DVec2) -> f64 {
        (p - self.start).dot(self.inward_normal())
    }
}

/// Why a zone must stay clear.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum ZoneKind {
    /// The keep-clear zone of door `i` (its sweep and walkway): nothing but a floor covering.
    Door(usize),
    /// The zone in front of window `i`: nothing taller than its sill.
    Window(usize),
}

/// A convex area of floor that objects must keep out of.
#[derive(Debug, Clone, PartialEq)]
pub struct KeepClear {
    /// Whose zone it is.
    pub kind: ZoneKind,
    /// Its corners, counter-clockwise.
    pub corners: [DVec2; 4],
    /// Objects at most this tall (cm) may enter: the sill for a window; for a door, the
    /// floor-covering height.
    pub max_height: f64,
}

impl KeepClear {
    /// Whether an object of `height` cm must stay out of this zone.
    pub fn applies_to(&self, height: f64) -> bool {
        height > self.max_height
    }
}

impl Room {
    /// The `width` x `depth` rectangle without openings.
    pub const fn rect(width: f64, depth: f64) -> Room {
        Room {
            width,
            depth,
            polygon: None,
            doors: Vec::new(),
            windows: Vec::new(),
        }
    }

    /// A room with the given outline (counter-clockwise, bottom-left of its bounding box at the
    /// origin) and no openings. `width` and `depth` are the outline's largest x and y.
    pub fn from_polygon(points: Vec<[f64; 2]>) -> Room {
        let width = points.iter().map(|p| p[0]).fold(0.0, f64::max);
        let depth = points.iter().map(|p| p[1]).fold(0.0, f64::max);
        Room {
            width,
            depth,
            polygon: Some(points),
            doors: Vec::new(),
            windows: Vec::new(),
        }
    }

    /// True when the floor is the plain `width` x `depth` rectangle (openings aside).
    pub fn is_rectangle(&self) -> bool {
        self.polygon.is_none()
    }

    /// True when the room has doors or windows.
    pub fn has_openings(&self) -> bool {
        !self.doors.is_empty() || !self.windows.is_empty()
    }

    /// The outline's vertices, counter-clockwise (a rectangle's four corners from the origin).
    pub fn outline(&self) -> Vec<DVec2> {
        match &self.polygon {
            Some(points) => points.iter().map(|p| DVec2::new(p[0], p[1])).collect(),
            None => vec![
                DVec2::ZERO,
                DVec2::new(self.width, 0.0),
                DVec2::new(self.width, self.depth),
                DVec2::new(0.0, self.depth),
            ],
        }
    }

    /// The walls, in order: wall `i` runs from vertex `i` to vertex `i + 1`.
    pub fn walls(&self) -> Vec<Edge> {
        let v = self.outline();
        (0..v.len())
            .map(|i| Edge {
                index: i,
                start: v[i],
                end: v[(i + 1) % v.len()],
            })
            .collect()
    }

    /// Floor area in cm².
    pub fn area(&self) -> f64 {
        match &self.polygon {
            None => self.width * self.depth,
            Some(_) => signed_area(&self.outline()).abs(),
        }
    }

    /// Whether `p` lies inside the floor or on its boundary (within `slack` cm).
    pub fn contains_point(&self, p: DVec2, slack: f64) -> bool {
        if self.polygon.is_none() {
            return p.x >= -slack
                && p.y >= -slack
                && p.x <= self.width + slack
                && p.y <= self.depth + slack;
        }
        let v = self.outline();
        if self
            .walls()
            .iter()
            .any(|e| distance_to_segment(p, e.start, e.end) <= slack)
        {
            return true;
        }
        point_in_polygon(p, &v)
    }

    /// Where opening `(wall, at, width)` lies: its two ends on the wall, start side first.
    pub fn opening_ends(&self, wall: usize, at: f64, width: f64) -> Option<(DVec2, DVec2)> {
        let edge = *self.walls().get(wall)?;
        Some((edge.point(at - width / 2.0), edge.point(at + width / 2.0)))
    }

    /// The zones openings keep clear: for each door, a rectangle its width wide reaching
    /// [`DOOR_CLEARANCE_CM`] into the room, or the leaf's width when it swings in and is wider
    /// (the square that holds its sweep); for each window, a rectangle along its span reaching
    /// [`WINDOW_CLEARANCE_CM`] into the room, binding objects taller than its sill.
    pub fn keep_clear(&self) -> Vec<KeepClear> {
        let walls = self.walls();
        let mut zones = Vec::new();
        for (i, d) in self.doors.iter().enumerate() {
            let Some(edge) = walls.get(d.wall) else {
                continue;
            };
            let reach = match d.swing {
                Swing::In => DOOR_CLEARANCE_CM.max(d.width),
                Swing::Out | Swing::Sliding => DOOR_CLEARANCE_CM,
            };
            zones.push(KeepClear {
                kind: ZoneKind::Door(i),
                corners: band(edge, d.at, d.width, reach),
                max_height: crate::units::FLAT_HEIGHT_CM,
            });
        }
        for (i, w) in self.windows.iter().enumerate() {
            let Some(edge) = walls.get(w.wall) else {
                continue;
            };
            zones.push(KeepClear {
                kind: ZoneKind::Window(i),
                corners: band(edge, w.at, w.width, WINDOW_CLEARANCE_CM),
                max_height: w.sill,
            });
        }
        zones
    }

    /// The middle of the doorway of door `index` on its wall; `None` when there is no such door.
    pub fn door_middle(&self, index: usize) -> Option<DVec2> {
        let door = self.doors.get(index)?;
        let (a, b) = self.opening_ends(door.wall, door.at, door.width)?;
        Some((a + b) / 2.0)
    }

    /// Where a door's leaf sweeps when it swings in: the hinge point, the leaf's closed end and
    /// its radius; `None` for doors that do not swing into the room.
    pub fn door_sweep(&self, door: &Door) -> Option<(DVec2, DVec2, f64)> {
        if door.swing != Swing::In {
            return None;
        }
        let (a, b) = self.opening_ends(door.wall, door.at, door.width)?;
        // Seen from inside the room (facing the wall, i.e. looking along -inward normal) the
        // wall's start vertex is on the right: a counter-clockwise wall runs right to left.
        let (hinge, free) = match door.hinge {
            Hinge::Right => (a, b),
            Hinge::Left => (b, a),
        };
        Some((hinge, free, door.width))
    }

    /// The openings on `wall` that a piece `height` cm tall must keep its back clear of, as
    /// `(start, end)` distances along it: every door, and every window whose sill is lower than
    /// the piece (a desk no taller than the sill may stand under the window).
    pub fn openings_blocking(&self, wall: usize, height: f64) -> Vec<(f64, f64)> {
        let doors = self.doors.iter().map(|d| (d.wall, d.at, d.width));
        let windows = self
            .windows
            .iter()
            .filter(|w| height > w.sill)
            .map(|w| (w.wall, w.at, w.width));
        doors
            .chain(windows)
            .filter(|(w, _, _)| *w == wall)
            .map(|(_, at, width)| (at - width / 2.0, at + width / 2.0))
            .collect()
    }

    /// Every opening on `wall` as `(start, end)` distances along it.
    pub fn openings_on(&self, wall: usize) -> Vec<(f64, f64)> {
        let doors = self.doors.iter().map(|d| (d.wall, d.at, d.width));
        let windows = self.windows.iter().map(|w| (w.wall, w.at, w.width));
        doors
            .chain(windows)
            .filter(|(w, _, _)| *w == wall)
            .map(|(_, at, width)| (at - width / 2.0, at + width / 2.0))
            .collect()
    }
}

/// The rectangle `width` wide centred `at` along `edge`, reaching `reach` cm into the room.
fn band(edge: &Edge, at: f64, width: f64, reach: f64) -> [DVec2; 4] {
    let a = edge.point(at - width / 2.0);
    let b = edge.point(at + width / 2.0);
    let n = edge.inward_normal() * reach;
    [a, b, b + n, a + n]
}

/// The room as written in files: either `width` and `depth` or `polygon`, with optional openings.
#[derive(Serialize, Deserialize, schemars::JsonSchema)]
#[serde(deny_unknown_fields)]
#[schemars(rename = "Room")]
struct RoomFile {
    /// Extent along x in cm (a rectangle; not with `polygon`).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    width: Option<f64>,
    /// Extent along y in cm (a rectangle; not with `polygon`).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    depth: Option<f64>,
    /// The floor outline in cm, counter-clockwise, lowest x and y at 0 (instead of width and
    /// depth).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    polygon: Option<Vec<[f64; 2]>>,
    /// Doors, each on one wall.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    doors: Vec<Door>,
    /// Windows, each on one wall.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    windows: Vec<Window>,
}

/// On the wire a room is its file form: `width` and `depth`, or `polygon`; openings beside.
impl schemars::JsonSchema for Room {
    fn schema_name() -> std::borrow::Cow<'static, str> {
        RoomFile::schema_name()
    }

    fn json_schema(generator: &mut schemars::SchemaGenerator) -> schemars::Schema {
        RoomFile::json_schema(generator)
    }
}

impl Serialize for Room {
    fn serialize<S: Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        let rect = self.polygon.is_none();
        RoomFile {
            width: rect.then_some(self.width),
            depth: rect.then_some(self.depth),
            polygon: self.polygon.clone(),
            doors: self.doors.clone(),
            windows: self.windows.clone(),
        }
        .serialize(s)
    }
}

impl<'de> Deserialize<'de> for Room {
    fn deserialize<D: Deserializer<'de>>(d: D) -> Result<Room, D::Error> {
        use serde::de::Error;
        let file = RoomFile::deserialize(d)?;
        let mut room = match (file.width, file.depth, file.polygon) {
            (Some(width), Some(depth), None) => Room::rect(width, depth),
            (None, None, Some(points)) => Room::from_polygon(points),
            (_, _, Some(_)) => {
                return Err(D::Error::custom(
                    "give the room either as `width` and `depth` or as a `polygon`, not both",
                ));
            }
            (None, _, None) => return Err(D::Error::missing_field("width")),
            (_, None, None) => return Err(D::Error::missing_field("depth")),
        };
        room.doors = file.doors;
        room.windows = file.windows;
        Ok(room)
    }
}

#[cfg(test)]
mod tests;
