//! Plane polygon tests shared by the room (its outline, its keep-clear zones) and the objects'
//! footprints, in one place so both use the same edge rules: the signed area, point in polygon,
//! distance to a segment, and whether a turned rectangle lies inside an outline.
//!
//! A leaf module: it knows points and slices of points, nothing of rooms or objects.

use glam::DVec2;

/// Twice-halved shoelace area: positive for counter-clockwise vertices.
pub fn signed_area(v: &[DVec2]) -> f64 {
    let n = v.len();
    (0..n).map(|i| v[i].perp_dot(v[(i + 1) % n])).sum::<f64>() / 2.0
}

/// The centroid of a simple polygon, `None` when its area is zero.
pub fn centroid(v: &[DVec2]) -> Option<DVec2> {
    let n = v.len();
    let (mut twice_area, mut sum) = (0.0, DVec2::ZERO);
    for i in 0..n {
        let (a, b) = (v[i], v[(i + 1) % n]);
        let cross = a.perp_dot(b);
        twice_area += cross;
        sum += (a + b) * cross;
    }
    (twice_area.abs() > 0.0).then(|| sum / (3.0 * twice_area))
}

/// Even-odd point-in-polygon test.
pub fn point_in_polygon(p: DVec2, v: &[DVec2]) -> bool {
    let mut inside = false;
    let n = v.len();
    for i in 0..n {
        let (a, b) = (v[i], v[(i + 1) % n]);
        if (a.y > p.y) != (b.y > p.y) {
            let x = a.x + (p.y - a.y) / (b.y - a.y) * (b.x - a.x);
            if p.x < x {
                inside = !inside;
            }
        }
    }
    inside
}

/// Distance from `p` to the segment `a`-`b`.
pub fn distance_to_segment(p: DVec2, a: DVec2, b: DVec2) -> f64 {
    let ab = b - a;
    let t = if ab.length_squared() > 0.0 {
        ((p - a).dot(ab) / ab.length_squared()).clamp(0.0, 1.0)
    } else {
        0.0
    };
    p.distance(a + ab * t)
}

/// A rectangle on the plane: its centre, half extents and the unit vectors of its own axes.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct TurnedRect {
    /// Centre.
    pub center: DVec2,
    /// Half extents along `right` and `front`.
    pub half: DVec2,
    /// Unit vector of the rectangle's local x.
    pub right: DVec2,
    /// Unit vector of the rectangle's local y.
    pub front: DVec2,
}

impl TurnedRect {
    /// `p` in the rectangle's own frame.
    pub fn to_local(&self, p: DVec2) -> DVec2 {
        let d = p - self.center;
        DVec2::new(d.dot(self.right), d.dot(self.front))
    }

    /// The four corners.
    pub fn corners(&self) -> [DVec2; 4] {
        let (r, f) = (self.right * self.half.x, self.front * self.half.y);
        [
            self.center - r - f,
            self.center + r - f,
            self.center + r + f,
            self.center - r + f,
        ]
    }

    /// Whether the rectangle lies inside the simple polygon `outline`: its centre and every
    /// corner inside (or on a wall), no vertex of the outline strictly inside it, and no wall
    /// crossing it.
    pub fn inside(&self, outline: &[DVec2]) -> bool {
        let e = 1e-6;
        let corner_in = |c: &DVec2| {
            point_in_polygon(*c, outline)
                || (0..outline.len()).any(|i| {
                    distance_to_segment(*c, outline[i], outline[(i + 1) % outline.len()]) <= 1e-4
                })
        };
        if !point_in_polygon(self.center, outline) || !self.corners().iter().all(corner_in) {
            return false;
        }
        let strictly_inside = |p: DVec2| {
            let l = self.to_local(p);
            l.x.abs() < self.half.x - e && l.y.abs() < self.half.y - e
        };
        if outline.iter().any(|v| strictly_inside(*v)) {
            return false;
        }
        // A wall may still cut through the rectangle with both its ends outside.
        let shrunk = self.half - DVec2::splat(e);
        (0..outline.len()).all(|i| {
            let (a, b) = (outline[i], outline[(i + 1) % outline.len()]);
            !segment_enters_box(self.to_local(a), self.to_local(b), shrunk)
        })
    }
}

/// Whether the segment `a`-`b` (in a box's frame) passes through the open box of half extents
/// `half` centred at the origin.
fn segment_enters_box(a: DVec2, b: DVec2, half: DVec2) -> bool {
    if half.x <= 0.0 || half.y <= 0.0 {
        return false;
    }
    let d = b - a;
    let (mut t0, mut t1) = (0.0_f64, 1.0_f64);
    for (p, q) in [
        (-d.x, a.x + half.x),
        (d.x, half.x - a.x),
        (-d.y, a.y + half.y),
        (d.y, half.y - a.y),
    ] {
        if p == 0.0 {
            if q <= 0.0 {
                return false;
            }
        } else {
            let t = q / p;
            if p < 0.0 {
                t0 = t0.max(t);
            } else {
                t1 = t1.min(t);
            }
        }
    }
    t1 - t0 > 1e-9
}
