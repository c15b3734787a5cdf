//! Walls as the edges of the room's outline (docs/formats.md, "Rooms"): which wall an object
//! stands against, which wall is nearest, and where along a wall an object can stand flush,
//! outside the wall's openings.
//!
//! Wall `i` runs from outline vertex `i` to vertex `i + 1`, the room on its left. A rectangle's
//! walls are 0 bottom, 1 right, 2 top, 3 left. Axis-aligned walls measure positions along them
//! by the world coordinate (x for a horizontal wall, y for a vertical one), exactly as the
//! rectangle-only code did; a slanted wall measures them as the distance from its start vertex.

use glam::DVec2;

use super::{Footprint, WALL_ANGLE_DEG, WALL_GAP_CM};
use crate::room::Room;
use crate::room::{Edge, distance_to_segment};

/// Names of a rectangle's walls, by index.
const RECTANGLE_NAMES: [&str; 4] = ["bottom", "right", "top", "left"];

/// One wall of the room: an edge of its outline.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Wall {
    /// The edge: wall `edge.index` from vertex `index` to vertex `index + 1`.
    pub edge: Edge,
    /// Whether the room is a plain rectangle (its walls then have names).
    rectangle: bool,
}

/// How positions along a wall are measured.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Along {
    /// By the world x coordinate (a horizontal wall).
    X,
    /// By the world y coordinate (a vertical wall).
    Y,
    /// By the distance from the wall's start vertex (a slanted wall).
    Edge,
}

impl Wall {
    /// Every wall of `room`, in order.
    pub fn all(room: &Room) -> Vec<Wall> {
        let rectangle = room.is_rectangle();
        room.walls()
            .into_iter()
            .map(|edge| Wall { edge, rectangle })
            .collect()
    }

    /// Wall `index` of `room`, if it has one.
    pub fn get(room: &Room, index: usize) -> Option<Wall> {
        Wall::all(room).get(index).copied()
    }

    /// The wall's index in the outline.
    pub fn index(&self) -> usize {
        self.edge.index
    }

    /// How positions along this wall are measured.
    pub fn along_axis(&self) -> Along {
        let d = self.edge.end - self.edge.start;
        if d.y == 0.0 {
            Along::X
        } else if d.x == 0.0 {
            Along::Y
        } else {
            Along::Edge
        }
    }

    /// The rotation that puts an object's back on this wall, its front towards the room (exact
    /// multiples of 90° for axis-aligned walls).
    pub fn inward_rotation(&self) -> f64 {
        let n = self.inward_normal();
        match (n.x, n.y) {
            (x, y) if x == 0.0 && y > 0.0 => 0.0,
            (x, y) if y == 0.0 && x > 0.0 => 90.0,
            (x, y) if x == 0.0 && y < 0.0 => 180.0,
            (x, y) if y == 0.0 && x < 0.0 => 270.0,
            _ => self.edge.inward_rotation(),
        }
    }

    /// Unit vector from the wall's start to its end (exact for axis-aligned walls).
    pub fn direction(&self) -> DVec2 {
        let d = self.edge.end - self.edge.start;
        match self.along_axis() {
            Along::X => DVec2::new(d.x.signum(), 0.0),
            Along::Y => DVec2::new(0.0, d.y.signum()),
            Along::Edge => self.edge.direction(),
        }
    }

    /// Unit vector pointing from this wall into the room (exact for axis-aligned walls).
    pub fn inward_normal(&self) -> DVec2 {
        self.direction().perp()
    }

    /// Distance from `p` to this wall's line.
    pub fn distance(&self, p: DVec2) -> f64 {
        (p - self.edge.start).dot(self.inward_normal()).abs()
    }

    /// How far along the wall, from its start vertex, the projection of `p` falls.
    pub fn along(&self, p: DVec2) -> f64 {
        (p - self.edge.start).dot(self.direction())
    }

    /// Distance from `p` to the wall itself (the segment between its vertices).
    pub fn segment_distance(&self, p: DVec2) -> f64 {
        distance_to_segment(p, self.edge.start, self.edge.end)
    }

    /// Length of the wall (cm).
    pub fn length(&self) -> f64 {
        self.edge.length()
    }

    /// The wall's name for messages and prompts: `bottom`, `right`, `top` or `left` in a
    /// rectangle, `wall i` otherwise.
    pub fn name(&self) -> String {
        match self.rectangle {
            true => RECTANGLE_NAMES[self.index() % 4].to_string(),
            false => format!("wall {}", self.index()),
        }
    }

    /// Where `p` lies along this wall, measured as [`along_axis`](Self::along_axis) says.
    pub fn coordinate(&self, p: DVec2) -> f64 {
        match self.along_axis() {
            Along::X => p.x,
            Along::Y => p.y,
            Along::Edge => self.along(p),
        }
    }

    /// The parts of the wall where a piece `height` cm tall may put its back: outside its doors
    /// and the windows whose sill is lower than the piece (see [`Room::openings_blocking`]), as
    /// `(start, end)` distances from its start vertex, in order.
    pub fn free_stretches(&self, room: &Room, height: f64) -> Vec<(f64, f64)> {
        let mut openings = room.openings_blocking(self.index(), height);
        openings.sort_by(|a, b| a.0.total_cmp(&b.0));
        let mut out = Vec::new();
        let mut from = 0.0;
        for (a, b) in openings {
            if a > from {
                out.push((from, a));
            }
            from = f64::max(from, b);
        }
        if self.length() > from {
            out.push((from, self.length()));
        }
        out
    }

    /// Whether the segment `a`-`b` (the back edge of a piece `height` cm tall on this wall) lies
    /// on the wall itself, between its vertices (within [`WALL_GAP_CM`]), and clear of the
    /// openings that bind that piece (doors, and windows whose sill is lower than it).
    pub fn holds(&self, room: &Room, a: DVec2, b: DVec2, height: f64) -> bool {
        let (ta, tb) = (self.along(a), self.along(b));
        let (lo, hi) = (ta.min(tb), ta.max(tb));
        let eps = 1e-6;
        if !room.is_rectangle() && (lo < -WALL_GAP_CM || hi > self.length() + WALL_GAP_CM) {
            return false;
        }
        room.openings_blocking(self.index(), height)
            .iter()
            .all(|&(s, e)| hi <= s + eps || lo >= e - eps)
    }

    /// Where an object with local half extents `half` (half width, half depth) and `height`,
    /// turned to this wall's [`inward_rotation`](Self::inward_rotation), can stand with its back
    /// flush on the wall; `None` when it cannot stand against this wall at all.
    pub fn slot(&self, room: &Room, half: DVec2, height: f64) -> Option<WallSlot> {
        let (hw, hd) = (half.x, half.y);
        let len = self.length();
        let n = self.inward_normal();
        let axis = self.along_axis();
        let (s, e) = (self.edge.start, self.edge.end);
        // The centre's range along the wall, and its coordinate across it.
        let (lo, hi, fixed, across_room) = match axis {
            Along::X => (
                s.x.min(e.x) + hw,
                s.x.max(e.x) - hw,
                s.y + n.y * hd,
                room.depth,
            ),
            Along::Y => (
                s.y.min(e.y) + hw,
                s.y.max(e.y) - hw,
                s.x + n.x * hd,
                room.width,
            ),
            Along::Edge => (hw, len - hw, 0.0, f64::INFINITY),
        };
        let fits = hi >= lo - 1e-9 && 2.0 * hw <= len + 1e-9 && 2.0 * hd <= across_room + 1e-9;
        if !fits {
            return None;
        }
        let hi = hi.max(lo);
        // The stretches where the back stays clear of every opening, in the slot's measure.
        let to_measure = |t: f64| match axis {
            Along::X => s.x + (e.x - s.x).signum() * t,
            Along::Y => s.y + (e.y - s.y).signum() * t,
            Along::Edge => t,
        };
        let mut stretches = Vec::new();
        if room.has_openings() {
            for (a, b) in self.free_stretches(room, height) {
                let (ta, tb) = (a + hw, b - hw);
                if tb < ta - 1e-9 {
                    continue;
                }
                let (ma, mb) = (to_measure(ta), to_measure(tb.max(ta)));
                let (ma, mb) = (ma.min(mb).max(lo), ma.max(mb).min(hi));
                if mb >= ma - 1e-9 {
                    stretches.push((ma, mb.max(ma)));
                }
            }
            stretches.sort_by(|x, y| x.0.total_cmp(&y.0));
            if stretches.is_empty() {
                return None;
            }
        } else {
            stretches.push((lo, hi));
        }
        Some(WallSlot {
            wall: *self,
            axis,
            fixed,
            depth_half: hd,
            lo,
            hi,
            stretches,
        })
    }
}

/// Where a footprint can stand with its back flush on one wall: its centre's position across
/// the wall is fixed, the one along it ranges over `stretches` (within `[lo, hi]`).
#[derive(Debug, Clone, PartialEq)]
pub struct WallSlot {
    /// The wall.
    pub wall: Wall,
    /// How positions along the wall are measured.
    pub axis: Along,
    /// For an axis-aligned wall, the centre's world coordinate across it.
    pub fixed: f64,
    /// The object's half depth: how far from the wall its centre stands.
    pub depth_half: f64,
    /// Smallest centre position along the wall.
    pub lo: f64,
    /// Largest centre position along the wall.
    pub hi: f64,
    /// The ranges of centre positions whose back stays clear of the wall's openings, in order
    /// (the whole `[lo, hi]` on a wall without openings).
    pub stretches: Vec<(f64, f64)>,
}

impl WallSlot {
    /// Whether positions are the world x coordinate (a horizontal wall).
    pub fn along_x(&self) -> bool {
        self.axis == Along::X
    }

    /// The centre at position `along` on this wall.
    pub fn point(&self, along: f64) -> DVec2 {
        match self.axis {
            Along::X => DVec2::new(along, self.fixed),
            Along::Y => DVec2::new(self.fixed, along),
            Along::Edge => {
                let w = &self.wall;
                w.edge.start + w.direction() * along + w.inward_normal() * self.depth_half
            }
        }
    }

    /// The position of `p` along this wall.
    pub fn along(&self, p: DVec2) -> f64 {
        self.wall.coordinate(p)
    }

    /// The allowed position nearest `v` (the lower stretch on a tie).
    pub fn clamp(&self, v: f64) -> f64 {
        let mut best = self.lo;
        let mut best_d = f64::INFINITY;
        for &(a, b) in &self.stretches {
            let c = v.clamp(a, b);
            if (c - v).abs() < best_d {
                best = c;
                best_d = (c - v).abs();
            }
        }
        best
    }

    /// Whether position `v` is allowed (within a stretch, to 1e-9 cm).
    pub fn allows(&self, v: f64) -> bool {
        self.stretches
            .iter()
            .any(|&(a, b)| v >= a - 1e-9 && v <= b + 1e-9)
    }
}

/// The wall nearest to `p` (ties broken in outline order): by the distance to the wall's line in
/// a rectangle, to the wall's segment in a polygon.
pub fn nearest_wall(room: &Room, p: DVec2) -> Wall {
    let walls = Wall::all(room);
    let dist = |w: &Wall| match room.is_rectangle() {
        true => w.distance(p),
        false => w.segment_distance(p),
    };
    let mut best = walls[0];
    for w in &walls[1..] {
        if dist(w) < dist(&best) {
            best = *w;
        }
    }
    best
}

impl Footprint {
    /// The wall this object stands against (back edge within [`WALL_GAP_CM`] of the wall and on
    /// it, clear of the openings that bind its height, front into the room within
    /// [`WALL_ANGLE_DEG`]), if any.
    pub fn against_wall(&self, room: &Room) -> Option<Wall> {
        let cos_tol = WALL_ANGLE_DEG.to_radians().cos();
        let (bl, br) = self.back_edge();
        Wall::all(room).into_iter().find(|w| {
            self.front.dot(w.inward_normal()) >= cos_tol
                && w.distance(bl) < WALL_GAP_CM
                && w.distance(br) < WALL_GAP_CM
                && w.holds(room, bl, br, self.height)
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::room::{Door, Window};

    fn l_room() -> Room {
        crate::synth::l_shaped_room()
    }

    #[test]
    fn rectangle_walls_keep_their_names_and_rotations() {
        let room = Room::rect(400.0, 300.0);
        let walls = Wall::all(&room);
        let names: Vec<String> = walls.iter().map(Wall::name).collect();
        assert_eq!(names, ["bottom", "right", "top", "left"]);
        let rots: Vec<f64> = walls.iter().map(Wall::inward_rotation).collect();
        assert_eq!(rots, [0.0, 270.0, 180.0, 90.0]);
        assert_eq!(walls[2].distance(DVec2::new(10.0, 280.0)), 20.0);
        assert_eq!(Wall::get(&room, 3).unwrap().name(), "left");
    }

    #[test]
    fn rectangle_slots_measure_by_world_coordinates() {
        let room = Room::rect(400.0, 300.0);
        let top = Wall::get(&room, 2).unwrap();
        let slot = top
            .slot(&room, DVec2::new(50.0, 20.0), f64::INFINITY)
            .unwrap();
        assert!(slot.along_x());
        assert_eq!((slot.lo, slot.hi, slot.fixed), (50.0, 350.0, 280.0));
        assert_eq!(slot.point(100.0), DVec2::new(100.0, 280.0));
        assert!(
            top.slot(&room, DVec2::new(201.0, 20.0), f64::INFINITY)
                .is_none()
        );
    }

    #[test]
    fn slanted_wall_slot_stands_flush_and_inside() {
        // A pentagon with its top-right corner cut by a 45-degree wall.
        let room = Room::from_polygon(vec![
            [0.0, 0.0],
            [500.0, 0.0],
            [500.0, 200.0],
            [300.0, 400.0],
            [0.0, 400.0],
        ]);
        let wall = Wall::get(&room, 2).unwrap();
        assert_eq!(wall.along_axis(), Along::Edge);
        assert!((wall.inward_rotation() - 225.0).abs() < 1e-9);
        let half = DVec2::new(40.0, 25.0);
        let slot = wall.slot(&room, half, f64::INFINITY).unwrap();
        for v in [slot.lo, (slot.lo + slot.hi) / 2.0, slot.hi] {
            let fp = Footprint::new(slot.point(v), 80.0, 50.0, wall.inward_rotation());
            assert!(fp.inside(&room), "{v}");
            assert_eq!(fp.against_wall(&room).map(|w| w.index()), Some(2));
        }
    }

    #[test]
    fn a_piece_no_taller_than_the_sill_stands_under_the_window() {
        let mut room = Room::rect(400.0, 300.0);
        room.windows.push(Window {
            wall: 0,
            at: 200.0,
            width: 140.0,
            sill: 90.0,
            height: 120.0,
        });
        // A 75 cm desk under the window is against the wall; a 180 cm shelf there is not.
        let desk = Footprint::new(DVec2::new(200.0, 30.0), 120.0, 60.0, 0.0).with_height(75.0);
        assert_eq!(desk.against_wall(&room).map(|w| w.index()), Some(0));
        let shelf = desk.with_height(180.0);
        assert!(shelf.against_wall(&room).is_none());
        // Its slot on that wall runs under the window too, the tall piece's stops at it.
        let bottom = Wall::get(&room, 0).unwrap();
        let low = bottom.slot(&room, DVec2::new(60.0, 30.0), 75.0).unwrap();
        assert!(low.allows(200.0));
        let tall = bottom.slot(&room, DVec2::new(60.0, 30.0), 180.0).unwrap();
        assert!(!tall.allows(200.0));
    }

    #[test]
    fn openings_split_the_slot_and_refuse_against_wall() {
        let mut room = l_room();
        room.doors.push(Door::new(0, 300.0, 90.0));
        room.windows.push(Window {
            wall: 5,
            at: 200.0,
            width: 100.0,
            sill: 90.0,
            height: 120.0,
        });
        let bottom = Wall::get(&room, 0).unwrap();
        let slot = bottom
            .slot(&room, DVec2::new(50.0, 30.0), f64::INFINITY)
            .unwrap();
        assert_eq!(slot.stretches, vec![(50.0, 205.0), (395.0, 550.0)]);
        assert_eq!(slot.clamp(290.0), 205.0);
        assert_eq!(slot.clamp(310.0), 395.0);
        let in_door = Footprint::new(DVec2::new(300.0, 30.0), 100.0, 60.0, 0.0);
        assert!(in_door.against_wall(&room).is_none());
        let beside = Footprint::new(DVec2::new(150.0, 30.0), 100.0, 60.0, 0.0);
        assert_eq!(beside.against_wall(&room).map(|w| w.index()), Some(0));
        // Wall 5 runs down from (0,450) to the origin: the window spans y 200..300.
        let left = Wall::get(&room, 5).unwrap();
        let slot = left
            .slot(&room, DVec2::new(40.0, 30.0), f64::INFINITY)
            .unwrap();
        assert_eq!(slot.stretches, vec![(40.0, 160.0), (340.0, 410.0)]);
    }

    #[test]
    fn against_wall_needs_the_back_on_the_wall_segment() {
        let room = l_room();
        // Back on the line y = 300 of wall 2 (600,300)-(350,300), but left of x = 350 where
        // the room goes on upwards: not against a wall.
        let off = Footprint::new(DVec2::new(200.0, 270.0), 100.0, 60.0, 180.0);
        assert!(off.against_wall(&room).is_none());
        let on = Footprint::new(DVec2::new(450.0, 270.0), 100.0, 60.0, 180.0);
        assert_eq!(on.against_wall(&room).map(|w| w.index()), Some(2));
        assert_eq!(nearest_wall(&room, DVec2::new(200.0, 30.0)).index(), 0);
        // By the segments, not their lines: the line of wall 2 passes 10 cm away, the top
        // wall 140 cm, wall 2 itself 150 cm.
        assert_eq!(nearest_wall(&room, DVec2::new(200.0, 310.0)).index(), 4);
        assert_eq!(nearest_wall(&room, DVec2::new(340.0, 420.0)).index(), 3);
    }
}
