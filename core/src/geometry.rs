//! Floor geometry: oriented footprints, overlap, containment, gaps, walls and facing.
//!
//! Conventions (docs/formats.md): centimetres; x to the right, y up, origin at the room's bottom-left
//! corner; rotation in degrees clockwise seen from above, 0 facing +y and 90 facing +x. An object's
//! local x axis ("right", when you face its front) spans its width; local y ("front") its depth.
//!
//! Axis-aligned footprints (rotation a multiple of 90°) take exact fast paths; other rotations
//! use polygon clipping, and parry2d's distance and ray-cast queries.

use glam::DVec2;
use parry2d::math::{Pose, Vector};
use parry2d::query::{Ray, RayCast};
use parry2d::shape::Cuboid;

use crate::room::Room;
pub use crate::units::normalize_degrees;

pub mod buckets;
mod walls;
pub use buckets::BoxBuckets;
pub use walls::{Along, Wall, WallSlot, nearest_wall};

/// Two footprints collide when they share more than this area (cm²). Used by the PRT, the
/// evaluator and the Col metric alike.
pub const COLLISION_AREA_CM2: f64 = 1.0;

/// An object is "against a wall" when its back edge is closer than this to the wall (cm).
pub const WALL_GAP_CM: f64 = 1.0;

/// Largest angle (degrees) between an object's front and a wall's inward normal that still counts
/// as facing into the room for "against a wall".
pub const WALL_ANGLE_DEG: f64 = 1.0;

/// Slack (cm) for "inside the room": below this, an edge touching a wall is inside.
pub const CONTAINMENT_EPS_CM: f64 = 1e-6;

/// An axis-aligned box on the floor.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Aabb {
    /// Bottom-left corner.
    pub min: DVec2,
    /// Top-right corner.
    pub max: DVec2,
}

impl Aabb {
    /// The box's area.
    pub fn area(&self) -> f64 {
        let s = (self.max - self.min).max(DVec2::ZERO);
        s.x * s.y
    }

    /// The area both boxes cover.
    pub fn overlap_area(&self, other: &Aabb) -> f64 {
        let w = self.max.x.min(other.max.x) - self.min.x.max(other.min.x);
        let h = self.max.y.min(other.max.y) - self.min.y.max(other.min.y);
        if w > 0.0 && h > 0.0 { w * h } else { 0.0 }
    }

    /// Whether the interiors of the boxes meet (touching edges do not count).
    pub fn interiors_meet(&self, other: &Aabb) -> bool {
        self.min.x < other.max.x
            && other.min.x < self.max.x
            && self.min.y < other.max.y
            && other.min.y < self.max.y
    }

    /// The shortest distance between the boxes (0 when they touch or overlap).
    pub fn gap(&self, other: &Aabb) -> f64 {
        let dx = (other.min.x - self.max.x)
            .max(self.min.x - other.max.x)
            .max(0.0);
        let dy = (other.min.y - self.max.y)
            .max(self.min.y - other.max.y)
            .max(0.0);
        dx.hypot(dy)
    }
}

/// An object's oriented rectangle on the floor.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Footprint {
    /// Centre (cm).
    pub center: DVec2,
    /// Half width and half depth (cm).
    pub half: DVec2,
    /// Rotation in degrees clockwise, normalised to `[0, 360)`.
    pub rotation: f64,
    /// Unit vector of the object's local x (its right-hand side).
    pub right: DVec2,
    /// Unit vector of the object's local y (where its front points).
    pub front: DVec2,
    /// Height (cm), for the rules that depend on it (a window binds only what is taller than its
    /// sill). [`Footprint::new`] leaves it unknown, which counts as taller than any sill.
    pub height: f64,
}

impl Footprint {
    /// The footprint of a `width` x `depth` object centred at `center`, turned `rotation` degrees clockwise.
    pub fn new(center: DVec2, width: f64, depth: f64, rotation: f64) -> Self {
        let rotation = normalize_degrees(rotation);
        let quarter = rotation / 90.0;
        let (right, front) = if (quarter - quarter.round()).abs() < 1e-9 {
            // Exact unit vectors for the four axis-aligned turns: no trigonometric round-off.
            match (quarter.round() as i64).rem_euclid(4) {
                0 => (DVec2::X, DVec2::Y),
                1 => (DVec2::NEG_Y, DVec2::X),
                2 => (DVec2::NEG_X, DVec2::NEG_Y),
                _ => (DVec2::Y, DVec2::NEG_X),
            }
        } else {
            let (s, c) = rotation.to_radians().sin_cos();
            (DVec2::new(c, -s), DVec2::new(s, c))
        };
        Footprint {
            center,
            half: DVec2::new(width / 2.0, depth / 2.0),
            rotation,
            right,
            front,
            height: f64::INFINITY,
        }
    }

    /// The same footprint with a known `height` (cm).
    pub fn with_height(mut self, height: f64) -> Footprint {
        self.height = height;
        self
    }

    /// True when the rotation is a multiple of 90°.
    pub fn is_axis_aligned(&self) -> bool {
        (self.right.x == 0.0 || self.right.y == 0.0) && (self.front.x == 0.0 || self.front.y == 0.0)
    }

    /// Area in cm².
    pub fn area(&self) -> f64 {
        4.0 * self.half.x * self.half.y
    }

    /// Corners counter-clockwise: back-left, back-right, front-right, front-left.
    pub fn corners(&self) -> [DVec2; 4] {
        let r = self.right * self.half.x;
        let f = self.front * self.half.y;
        [
            self.center - r - f,
            self.center + r - f,
            self.center + r + f,
            self.center - r + f,
        ]
    }

    /// Half extents of the axis-aligned box around the footprint.
    pub fn aabb_half(&self) -> DVec2 {
        let r = self.right.abs() * self.half.x;
        let f = self.front.abs() * self.half.y;
        r + f
    }

    /// The axis-aligned box around the footprint.
    pub fn aabb(&self) -> Aabb {
        let h = self.aabb_half();
        Aabb {
            min: self.center - h,
            max: self.center + h,
        }
    }

    /// The back edge, from back-left to back-right.
    pub fn back_edge(&self) -> (DVec2, DVec2) {
        let c = self.corners();
        (c[0], c[1])
    }

    /// The front edge, from front-left to front-right.
    pub fn front_edge(&self) -> (DVec2, DVec2) {
        let c = self.corners();
        (c[3], c[2])
    }

    /// Midpoint of the back edge.
    pub fn back_center(&self) -> DVec2 {
        self.center - self.front * self.half.y
    }

    /// Midpoint of the front edge.
    pub fn front_center(&self) -> DVec2 {
        self.center + self.front * self.half.y
    }

    /// `p` in this object's frame: x towards its right, y towards its front, origin at its centre.
    pub fn to_local(&self, p: DVec2) -> DVec2 {
        let d = p - self.center;
        DVec2::new(d.dot(self.right), d.dot(self.front))
    }

    /// The same footprint moved to `center` and turned to `rotation`.
    pub fn with_pose(&self, center: DVec2, rotation: f64) -> Footprint {
        Footprint::new(center, self.half.x * 2.0, self.half.y * 2.0, rotation)
            .with_height(self.height)
    }

    fn parry_shape(&self) -> (Pose, Cuboid) {
        // parry measures angles counter-clockwise; ours turn clockwise.
        let pose = Pose::new(
            Vector::new(self.center.x as f32, self.center.y as f32),
            -(self.rotation.to_radians() as f32),
        );
        (
            pose,
            Cuboid::new(Vector::new(self.half.x as f32, self.half.y as f32)),
        )
    }

    /// The area (cm²) this footprint shares with `other`.
    pub fn overlap_area(&self, other: &Footprint) -> f64 {
        let (a, b) = (self.aabb(), other.aabb());
        if !a.interiors_meet(&b) {
            return 0.0;
        }
        if self.is_axis_aligned() && other.is_axis_aligned() {
            return a.overlap_area(&b);
        }
        convex_intersection_area(&self.corners(), &other.corners())
    }

    /// Whether the two footprints collide (share more than [`COLLISION_AREA_CM2`]).
    pub fn collides(&self, other: &Footprint) -> bool {
        self.overlap_area(other) > COLLISION_AREA_CM2
    }

    /// Whether an object `height` cm tall standing on this footprint intrudes on `zone`: the
    /// zone binds objects that tall and they share more than [`COLLISION_AREA_CM2`].
    pub fn intrudes(&self, zone: &crate::room::KeepClear, height: f64) -> bool {
        if !zone.applies_to(height) {
            return false;
        }
        let z = &zone.corners;
        let zone_box = Aabb {
            min: z[0].min(z[1]).min(z[2]).min(z[3]),
            max: z[0].max(z[1]).max(z[2]).max(z[3]),
        };
        if !self.aabb().interiors_meet(&zone_box) {
            return false;
        }
        convex_intersection_area(&self.corners(), z) > COLLISION_AREA_CM2
    }

    /// The shortest distance between the two footprints (0 when they touch or overlap).
    pub fn gap(&self, other: &Footprint) -> f64 {
        if self.is_axis_aligned() && other.is_axis_aligned() {
            return self.aabb().gap(&other.aabb());
        }
        let (p1, s1) = self.parry_shape();
        let (p2, s2) = other.parry_shape();
        parry2d::query::distance(&p1, &s1, &p2, &s2)
            .map(|d| f64::from(d.distance))
            .unwrap_or_else(|_| self.aabb().gap(&other.aabb()))
    }

    /// The least distance (cm) from a corner of this footprint to a window of `room` (the
    /// window's span on its wall); `None` when the room has no window.
    pub fn gap_to_window(&self, room: &Room) -> Option<f64> {
        let corners = self.corners();
        room.windows
            .iter()
            .filter_map(|w| room.opening_ends(w.wall, w.at, w.width))
            .flat_map(|(a, b)| {
                corners
                    .iter()
                    .map(move |&c| crate::room::distance_to_segment(c, a, b))
            })
            .min_by(f64::total_cmp)
    }

    /// The area (cm²) of this footprint that lies outside `room` (its outline, for a polygon).
    pub fn area_outside(&self, room: &Room) -> f64 {
        if self.inside(room) {
            return 0.0; // exactly, without clipping round-off
        }
        if room.polygon.is_some() {
            let mut clip = self.corners();
            if crate::room::signed_area(&clip) < 0.0 {
                clip.reverse();
            }
            let inside = convex_intersection_area(&room.outline(), &clip);
            return (self.area() - inside).max(0.0);
        }
        let room_box = Aabb {
            min: DVec2::ZERO,
            max: DVec2::new(room.width, room.depth),
        };
        let inside = if self.is_axis_aligned() {
            self.aabb().overlap_area(&room_box)
        } else {
            let r = [
                DVec2::ZERO,
                DVec2::new(room.width, 0.0),
                DVec2::new(room.width, room.depth),
                DVec2::new(0.0, room.depth),
            ];
            convex_intersection_area(&self.corners(), &r)
        };
        (self.area() - inside).max(0.0)
    }

    /// Whether the whole footprint lies inside `room` (touching a wall counts as inside).
    pub fn inside(&self, room: &Room) -> bool {
        let b = self.aabb();
        let e = CONTAINMENT_EPS_CM;
        let in_box = b.min.x >= -e
            && b.min.y >= -e
            && b.max.x <= room.width + e
            && b.max.y <= room.depth + e;
        match &room.polygon {
            None => in_box,
            Some(_) => in_box && self.inside_outline(&room.outline()),
        }
    }

    /// Whether the footprint lies inside the simple polygon `outline` (see
    /// [`TurnedRect::inside`](crate::polygon::TurnedRect::inside)).
    fn inside_outline(&self, outline: &[DVec2]) -> bool {
        crate::polygon::TurnedRect {
            center: self.center,
            half: self.half,
            right: self.right,
            front: self.front,
        }
        .inside(outline)
    }

    /// Where the ray from this footprint's centre along its front first meets `other`, as a
    /// distance in cm; `None` when the front does not point at `other` at all.
    pub fn front_ray_hit(&self, other: &Footprint) -> Option<f64> {
        let (pose, shape) = other.parry_shape();
        let ray = Ray::new(
            Vector::new(self.center.x as f32, self.center.y as f32),
            Vector::new(self.front.x as f32, self.front.y as f32),
        );
        shape.cast_ray(&pose, &ray, f32::MAX, true).map(f64::from)
    }
}

/// Area of the intersection of two convex counter-clockwise polygons.
///
/// Sutherland–Hodgman clipping in f64. (parry2d's `convex_polygons_intersection_points` returns
/// no points when a vertex lies exactly on the other polygon's edge, as happens whenever an object
/// touches a wall, so we clip ourselves.)
fn convex_intersection_area(subject: &[DVec2], clip: &[DVec2]) -> f64 {
    let mut poly: Vec<DVec2> = subject.to_vec();
    let mut next = Vec::with_capacity(8);
    for i in 0..clip.len() {
        let (a, b) = (clip[i], clip[(i + 1) % clip.len()]);
        let edge = b - a;
        // Inside = left of the edge (counter-clockwise clip polygon).
        let side = |p: DVec2| edge.perp_dot(p - a);
        next.clear();
        for j in 0..poly.len() {
            let (p, q) = (poly[j], poly[(j + 1) % poly.len()]);
            let (sp, sq) = (side(p), side(q));
            if sp >= 0.0 {
                next.push(p);
            }
            if (sp >= 0.0) != (sq >= 0.0) {
                next.push(p + (q - p) * (sp / (sp - sq)));
            }
        }
        std::mem::swap(&mut poly, &mut next);
        if poly.len() < 3 {
            return 0.0;
        }
    }
    crate::polygon::signed_area(&poly).abs()
}

#[cfg(test)]
mod tests {
    use super::*;

    fn l_room() -> Room {
        crate::synth::l_shaped_room()
    }

    #[test]
    fn containment_and_oob_follow_the_polygon() {
        let room = l_room();
        // In the lower arm, flush with the inner wall y = 300: inside.
        let a = fp(500.0, 250.0, 100.0, 100.0, 0.0);
        assert!(a.inside(&room));
        assert_eq!(a.area_outside(&room), 0.0);
        // Straddling the inner corner's wall x = 350 above y = 300: half out.
        let b = fp(350.0, 400.0, 100.0, 50.0, 0.0);
        assert!(!b.inside(&room));
        assert!((b.area_outside(&room) - 2500.0).abs() < 1e-6);
        // Centred on the inner corner: one quarter out.
        let c = fp(350.0, 300.0, 50.0, 50.0, 0.0);
        assert!(!c.inside(&room));
        assert!((c.area_outside(&room) - 625.0).abs() < 1e-6);
        // Turned 45 degrees across the inner corner.
        let d = fp(350.0, 300.0, 60.0, 60.0, 45.0);
        assert!(!d.inside(&room));
        assert!((d.area_outside(&room) - 900.0).abs() < 1e-3);
    }

    #[test]
    fn a_wall_through_a_footprint_with_no_vertex_inside_is_caught() {
        // A thin notch: the outline's walls cross a long object without a corner inside it.
        let room = Room::from_polygon(vec![
            [0.0, 0.0],
            [400.0, 0.0],
            [400.0, 300.0],
            [210.0, 300.0],
            [205.0, 100.0],
            [195.0, 300.0],
            [0.0, 300.0],
        ]);
        let long = fp(200.0, 200.0, 300.0, 40.0, 0.0);
        assert!(!long.inside(&room));
        assert!(long.area_outside(&room) > 100.0);
    }

    #[test]
    fn door_zones_bind_furniture_but_not_rugs() {
        let mut room = Room::rect(400.0, 300.0);
        room.doors.push(crate::room::Door {
            wall: 0,
            at: 100.0,
            width: 90.0,
            swing: crate::room::Swing::Out,
            hinge: crate::room::Hinge::Left,
        });
        let zone = &room.keep_clear()[0];
        let chair = fp(100.0, 60.0, 50.0, 50.0, 0.0);
        assert!(chair.intrudes(zone, 90.0));
        assert!(!chair.intrudes(zone, 1.0), "a rug may lie there");
        let beside = fp(200.0, 60.0, 50.0, 50.0, 0.0);
        assert!(!beside.intrudes(zone, 90.0));
    }

    fn fp(x: f64, y: f64, w: f64, d: f64, r: f64) -> Footprint {
        Footprint::new(DVec2::new(x, y), w, d, r)
    }

    const ROOM: Room = Room::rect(400.0, 300.0);

    #[test]
    fn rotation_convention_matches_design() {
        assert_eq!(fp(0.0, 0.0, 1.0, 1.0, 0.0).front, DVec2::Y);
        assert_eq!(fp(0.0, 0.0, 1.0, 1.0, 90.0).front, DVec2::X);
        assert_eq!(fp(0.0, 0.0, 1.0, 1.0, 180.0).front, DVec2::NEG_Y);
        assert_eq!(fp(0.0, 0.0, 1.0, 1.0, 270.0).front, DVec2::NEG_X);
        assert_eq!(fp(0.0, 0.0, 1.0, 1.0, -90.0).rotation, 270.0);
        let f = fp(0.0, 0.0, 1.0, 1.0, 45.0).front;
        assert!((f - DVec2::new(1.0, 1.0).normalize()).length() < 1e-12);
    }

    #[test]
    fn turned_footprint_swaps_extents() {
        let b = fp(100.0, 100.0, 160.0, 40.0, 90.0).aabb();
        assert_eq!(b.min, DVec2::new(80.0, 20.0));
        assert_eq!(b.max, DVec2::new(120.0, 180.0));
    }

    #[test]
    fn corners_are_counter_clockwise_back_first() {
        let c = fp(0.0, 0.0, 2.0, 4.0, 0.0).corners();
        assert_eq!(c[0], DVec2::new(-1.0, -2.0));
        assert_eq!(c[2], DVec2::new(1.0, 2.0));
        let (b0, b1) = fp(0.0, 0.0, 2.0, 4.0, 180.0).back_edge();
        assert_eq!((b0.y, b1.y), (2.0, 2.0));
    }

    #[test]
    fn overlap_area_axis_aligned_and_rotated() {
        let a = fp(0.0, 0.0, 100.0, 100.0, 0.0);
        assert_eq!(a.overlap_area(&fp(50.0, 50.0, 100.0, 100.0, 0.0)), 2500.0);
        assert_eq!(
            a.overlap_area(&fp(100.0, 0.0, 100.0, 100.0, 0.0)),
            0.0,
            "touching is not overlapping"
        );
        // A square turned 45° about the same centre: the octagon's area is 2(√2-1)·s².
        let rot = a.overlap_area(&fp(0.0, 0.0, 100.0, 100.0, 45.0));
        let expected = 2.0 * (2f64.sqrt() - 1.0) * 10_000.0;
        assert!((rot - expected).abs() < 1.0, "{rot} vs {expected}");
        assert!(!a.collides(&fp(100.5, 0.0, 100.0, 100.0, 0.0)));
        assert!(a.collides(&fp(99.0, 0.0, 100.0, 100.0, 0.0)));
    }

    #[test]
    fn gap_between_footprints() {
        let a = fp(0.0, 0.0, 100.0, 100.0, 0.0);
        assert_eq!(a.gap(&fp(130.0, 0.0, 100.0, 100.0, 0.0)), 30.0);
        assert_eq!(a.gap(&fp(130.0, 140.0, 100.0, 100.0, 0.0)), 50.0);
        assert_eq!(a.gap(&fp(50.0, 0.0, 100.0, 100.0, 0.0)), 0.0);
        // Diamond whose left tip sits 20 cm right of a's right edge.
        let half_diag = 50.0 * 2f64.sqrt();
        let g = a.gap(&fp(50.0 + 20.0 + half_diag, 0.0, 100.0, 100.0, 45.0));
        assert!((g - 20.0).abs() < 0.01, "{g}");
    }

    #[test]
    fn containment_and_area_outside() {
        assert!(fp(50.0, 50.0, 100.0, 100.0, 0.0).inside(&ROOM));
        assert!(!fp(40.0, 50.0, 100.0, 100.0, 0.0).inside(&ROOM));
        assert_eq!(fp(0.0, 50.0, 100.0, 100.0, 0.0).area_outside(&ROOM), 5000.0);
        assert_eq!(
            fp(-500.0, 50.0, 100.0, 100.0, 0.0).area_outside(&ROOM),
            10_000.0
        );
        // A diamond whose top and bottom vertices lie exactly on the left wall: half is outside.
        let diamond = fp(0.0, 150.0, 100.0, 100.0, 45.0).area_outside(&ROOM);
        assert!((diamond - 5000.0).abs() < 1e-6, "{diamond}");
        let tip_to_tip = 100.0 * 2f64.sqrt();
        let touching =
            fp(0.0, 0.0, 100.0, 100.0, 45.0).overlap_area(&fp(tip_to_tip, 0.0, 100.0, 100.0, 45.0));
        assert!(
            touching.abs() < 1e-6,
            "vertex-to-vertex contact has no area: {touching}"
        );
    }

    #[test]
    fn nearest_wall_and_against_wall() {
        let name = |w: Option<Wall>| w.map(|w| w.name());
        assert_eq!(nearest_wall(&ROOM, DVec2::new(10.0, 150.0)).name(), "left");
        assert_eq!(nearest_wall(&ROOM, DVec2::new(200.0, 290.0)).name(), "top");
        // A bed whose head is on the top wall faces down (180°).
        assert_eq!(
            name(fp(200.0, 195.0, 160.0, 210.0, 180.0).against_wall(&ROOM)).as_deref(),
            Some("top")
        );
        assert_eq!(
            name(fp(200.0, 105.0, 160.0, 210.0, 0.0).against_wall(&ROOM)).as_deref(),
            Some("bottom")
        );
        assert_eq!(
            name(fp(20.0, 150.0, 80.0, 40.0, 90.0).against_wall(&ROOM)).as_deref(),
            Some("left")
        );
        assert_eq!(
            name(fp(380.0, 150.0, 80.0, 40.0, 270.0).against_wall(&ROOM)).as_deref(),
            Some("right")
        );
        // Back on the wall but facing the wall: not against it.
        assert_eq!(fp(20.0, 150.0, 80.0, 40.0, 270.0).against_wall(&ROOM), None);
        // Two centimetres off the wall: not against it.
        assert_eq!(fp(22.0, 150.0, 80.0, 40.0, 90.0).against_wall(&ROOM), None);
        assert_eq!(Wall::get(&ROOM, 3).unwrap().inward_rotation(), 90.0);
    }

    #[test]
    fn front_ray() {
        let chair = fp(100.0, 50.0, 40.0, 40.0, 0.0);
        let table = fp(100.0, 150.0, 120.0, 80.0, 0.0);
        assert!((chair.front_ray_hit(&table).unwrap() - 60.0).abs() < 1e-3);
        assert!(
            fp(100.0, 50.0, 40.0, 40.0, 180.0)
                .front_ray_hit(&table)
                .is_none()
        );
        assert!(
            fp(100.0, 50.0, 40.0, 40.0, 90.0)
                .front_ray_hit(&table)
                .is_none()
        );
    }
}
