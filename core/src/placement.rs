//! Candidate poses that put an object in a given relation to a target: shared by the rule-based
//! designer (to place) and the Semantic Refinement Tool (to repair).

use glam::DVec2;

use crate::geometry::{Footprint, Wall, normalize_degrees};
use crate::plan::Relation;
use crate::scene::Room;

/// A pose on the floor.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Pose {
    /// Footprint centre.
    pub center: DVec2,
    /// Degrees clockwise.
    pub rotation: f64,
}

/// The rotation whose front points from `from` towards `to`.
pub fn facing_rotation(from: DVec2, to: DVec2) -> f64 {
    let d = to - from;
    normalize_degrees(d.x.atan2(d.y).to_degrees())
}

/// `rotation` snapped to the nearest multiple of 90°.
pub fn snap90(rotation: f64) -> f64 {
    normalize_degrees((rotation / 90.0).round() * 90.0)
}

/// Distance from `p` along the unit vector `dir` to the room's boundary.
pub fn distance_to_boundary(room: &Room, p: DVec2, dir: DVec2) -> f64 {
    let mut t = f64::INFINITY;
    if dir.x > 1e-9 {
        t = t.min((room.width - p.x) / dir.x);
    } else if dir.x < -1e-9 {
        t = t.min(-p.x / dir.x);
    }
    if dir.y > 1e-9 {
        t = t.min((room.depth - p.y) / dir.y);
    } else if dir.y < -1e-9 {
        t = t.min(-p.y / dir.y);
    }
    t.max(0.0)
}

/// Poses for a `width` x `depth` object in `relation` to `target`, best first.
///
/// `gap` is the distance to aim for; `face` turns the object towards the target where the
/// relation leaves its rotation free.
pub fn relation_poses(
    width: f64,
    depth: f64,
    relation: Relation,
    target: &Footprint,
    room: &Room,
    gap: f64,
    face: bool,
) -> Vec<Pose> {
    let about = About {
        t: target,
        hw: width / 2.0,
        hd: depth / 2.0,
        gap,
        face,
    };
    match relation {
        Relation::SideOf => about.beside().to_vec(),
        Relation::InFrontOf => about.in_front(),
        Relation::Around => about.around(),
        Relation::Near => {
            let mut out = about.beside().to_vec();
            out.extend(about.at_front_corners());
            let c = about.straight_ahead();
            out.push(Pose {
                center: c,
                rotation: about.toward(c),
            });
            out
        }
        Relation::Opposite => about.across(room),
        Relation::AlignedWith => {
            let mut out = about.beside().to_vec();
            out.push(Pose {
                center: about.straight_ahead(),
                rotation: target.rotation,
            });
            out
        }
        // Seen from above: in the middle of the target's top, turned as it is.
        Relation::On => vec![Pose {
            center: target.center,
            rotation: target.rotation,
        }],
        // Seen from above: centred on the target, its back where the target's back is.
        Relation::Above => vec![Pose {
            center: target.back_center() + target.front * about.hd,
            rotation: target.rotation,
        }],
        Relation::BackToBack => vec![about.behind()],
    }
}

/// An object of half-width `hw` and half-depth `hd` to stand `gap` from target `t`, turned
/// towards it (`face`) where the relation leaves that free: the poses each relation is made of.
struct About<'t> {
    t: &'t Footprint,
    hw: f64,
    hd: f64,
    gap: f64,
    face: bool,
}

impl About<'_> {
    /// The rotation of the object standing at `c` where its relation leaves it free: towards
    /// the target when it should face it, else the target's own.
    fn toward(&self, c: DVec2) -> f64 {
        if self.face {
            snap_if_facing(c, self.t)
        } else {
            self.t.rotation
        }
    }

    /// Behind the target, `gap` from its back edge, turned the other way: back to back.
    fn behind(&self) -> Pose {
        let t = self.t;
        Pose {
            center: t.center
                - t.front * (t.half.y + self.gap.min(crate::relations::BACK_GAP_CM) + self.hd),
            rotation: crate::geometry::normalize_degrees(t.rotation + 180.0),
        }
    }

    /// Beside the target on its right, then its left, back edges on one line.
    fn beside(&self) -> [Pose; 2] {
        let t = self.t;
        [1.0, -1.0].map(|side| {
            let c = t.center
                + t.right * side * (t.half.x + self.gap + self.hw)
                + t.front * (self.hd - t.half.y);
            Pose {
                center: c,
                rotation: self.toward(c),
            }
        })
    }

    /// In front of the target: centred, then 20 cm to its right and left; turned back towards
    /// it when facing, else the same way.
    fn in_front(&self) -> Vec<Pose> {
        let t = self.t;
        [0.0, 20.0, -20.0]
            .into_iter()
            .map(|lateral| {
                let c = t.front_center() + t.front * (self.gap + self.hd) + t.right * lateral;
                let own = if self.face {
                    t.rotation + 180.0
                } else {
                    t.rotation
                };
                Pose {
                    center: c,
                    rotation: normalize_degrees(own),
                }
            })
            .collect()
    }

    /// At the middle of each side of the target (front, back, right, left), facing its centre.
    fn around(&self) -> Vec<Pose> {
        let t = self.t;
        [t.front, -t.front, t.right, -t.right]
            .into_iter()
            .map(|n| {
                let half_n = if n.dot(t.front).abs() > 0.5 {
                    t.half.y
                } else {
                    t.half.x
                };
                let c = t.center + n * (half_n + self.gap + self.hd);
                Pose {
                    center: c,
                    rotation: facing_rotation(c, t.center),
                }
            })
            .collect()
    }

    /// At the target's front corners, right then left.
    fn at_front_corners(&self) -> [Pose; 2] {
        let t = self.t;
        [1.0, -1.0].map(|side| {
            let c = t.front_center()
                + t.right * side * (t.half.x + self.hw)
                + t.front * (self.gap + self.hd);
            Pose {
                center: c,
                rotation: self.toward(c),
            }
        })
    }

    /// The centre `gap` straight out from the target's front edge.
    fn straight_ahead(&self) -> DVec2 {
        self.t.front_center() + self.t.front * (self.gap + self.hd)
    }

    /// Across the room in front of the target, turned back towards it: against the wall it
    /// faces when that is within reach, else 2.5 m away (then closer).
    fn across(&self, room: &Room) -> Vec<Pose> {
        let (t, hd) = (self.t, self.hd);
        let to_wall = distance_to_boundary(room, t.front_center(), t.front);
        let mut dists = vec![];
        if to_wall.is_finite() && to_wall <= 450.0 {
            dists.push(to_wall - hd);
        }
        dists.extend([250.0 + hd, 180.0 + hd, 120.0 + hd]);
        dists
            .into_iter()
            .map(|d| Pose {
                center: t.front_center() + t.front * d,
                rotation: normalize_degrees(t.rotation + 180.0),
            })
            .collect()
    }
}

/// The rotation towards `t` from `c`: the nearest right angle when that still faces `t`.
fn snap_if_facing(c: DVec2, t: &Footprint) -> f64 {
    let exact = facing_rotation(c, t.center);
    let square = snap90(exact);
    let probe = Footprint::new(c, 1.0, 1.0, square);
    if probe.front_ray_hit(t).is_some() {
        square
    } else {
        exact
    }
}

/// Seats for `n` chairs of `width` x `depth` around `table`: along the long sides first, then the
/// ends; evenly by angle around round tables. Each faces the table.
pub fn around_slots(
    table: &Footprint,
    round: bool,
    width: f64,
    depth: f64,
    n: usize,
    gap: f64,
) -> Vec<Pose> {
    let t = table;
    let hd = depth / 2.0;
    if n == 0 {
        return Vec::new();
    }
    if round {
        let r = t.half.x.max(t.half.y) + gap + hd;
        return (0..n)
            .map(|i| {
                let a = (t.rotation + 360.0 * i as f64 / n as f64).to_radians();
                let c = t.center + DVec2::new(a.sin(), a.cos()) * r;
                Pose {
                    center: c,
                    rotation: facing_rotation(c, t.center),
                }
            })
            .collect();
    }
    // Sides as (outward normal, half-length of the side, half-depth to the side).
    let long_is_x = t.half.x >= t.half.y;
    let (long_n, long_len, long_off, end_n, end_len, end_off) = if long_is_x {
        (t.front, t.half.x, t.half.y, t.right, t.half.y, t.half.x)
    } else {
        (t.right, t.half.y, t.half.x, t.front, t.half.x, t.half.y)
    };
    // Comfortable spacing first; when that seats too few, close ranks and let the outer chairs
    // overhang the table's corners a little.
    let seats_on = |len: f64, pitch: f64| ((2.0 * len) / pitch).floor().max(1.0) as usize;
    let (mut pitch, mut long_len, mut end_len) = (width + 10.0, long_len, end_len);
    if 2 * seats_on(long_len, pitch) + 2 * seats_on(end_len, pitch) < n {
        pitch = width + 1.0;
        long_len += width / 4.0;
        end_len += width / 4.0;
    }
    let per_long = seats_on(long_len, pitch);
    let per_end = seats_on(end_len, pitch);
    // Fill the two long sides evenly, then the two ends.
    let long_total = n.min(2 * per_long);
    let end_total = (n - long_total).min(2 * per_end);
    let mut seats = Vec::new();
    let mut side = |normal: DVec2, half_len: f64, off: f64, count: usize| {
        let tangent = DVec2::new(-normal.y, normal.x);
        for k in 0..count {
            let s = (k as f64 + 0.5) / count as f64 * 2.0 - 1.0;
            let c = t.center + normal * (off + gap + hd) + tangent * s * half_len;
            seats.push(Pose {
                center: c,
                rotation: normalize_degrees(facing_rotation(c, c - normal)),
            });
        }
    };
    side(long_n, long_len, long_off, long_total.div_ceil(2));
    side(-long_n, long_len, long_off, long_total / 2);
    side(end_n, end_len, end_off, end_total.div_ceil(2));
    side(-end_n, end_len, end_off, end_total / 2);
    seats
}

/// Poses with the back on a wall, front into the room, sampled every `step` cm along each wall,
/// for a piece `width` x `depth` and `height` tall (a low piece may stand under a window).
pub fn wall_poses(
    room: &Room,
    width: f64,
    depth: f64,
    height: f64,
    step: f64,
) -> Vec<(Wall, Pose)> {
    let mut out = Vec::new();
    for wall in Wall::all(room) {
        let rot = wall.inward_rotation();
        let Some(slot) = wall.slot(room, DVec2::new(width, depth) / 2.0, height) else {
            continue;
        };
        let mut push = |v: f64| {
            out.push((
                wall,
                Pose {
                    center: slot.point(v),
                    rotation: rot,
                },
            ))
        };
        for &(lo, hi) in &slot.stretches {
            let mut v = lo;
            while v < hi {
                push(v);
                v += step;
            }
            push(hi);
            push((lo + hi) / 2.0);
        }
    }
    out
}

/// Walkway (cm) between neighbouring desks of a row, and between a row's chairs and the next row.
pub const ROW_AISLE_CM: f64 = 45.0;

/// Poses for `n` desks of `width` x `depth` in rows facing `board`, as a classroom has them.
///
/// Each desk turns its back to the board (its front, where the student sits, faces away), with
/// `behind` cm kept free in front of it for the chair. The first row starts `start` cm out from
/// the board's front edge; rows are centred on the board and kept `ROW_AISLE_CM` from the side
/// walls. Desks are numbered in a snake (left to right, then right to left) so each one is in line
/// with the one before it: beside it in the same row, or behind it at a row's end.
pub fn row_poses(
    board: &Footprint,
    room: &Room,
    width: f64,
    depth: f64,
    behind: f64,
    n: usize,
    start: f64,
) -> Vec<Pose> {
    if n == 0 {
        return Vec::new();
    }
    let b = board;
    let origin = b.front_center();
    let left = distance_to_boundary(room, origin, -b.right) - ROW_AISLE_CM;
    let right = distance_to_boundary(room, origin, b.right) - ROW_AISLE_CM;
    let deep = distance_to_boundary(room, origin, b.front) - start;
    let span = (left + right).max(width);
    let row_pitch = depth + behind + ROW_AISLE_CM;
    // Wide aisles between desks when the rows fit the room's depth, narrower ones otherwise.
    let grid = |col_pitch: f64| {
        let cols = (((span + col_pitch - width) / col_pitch).floor() as usize).clamp(1, n);
        let rows = n.div_ceil(cols);
        (
            col_pitch,
            rows,
            rows as f64 * row_pitch - ROW_AISLE_CM <= deep,
        )
    };
    let (wide, narrow) = (grid(width + ROW_AISLE_CM), grid(width + ROW_AISLE_CM / 2.0));
    let (col_pitch, rows, _) = if wide.2 || !narrow.2 { wide } else { narrow };
    // Even rows: as few columns as the row count allows.
    let cols = n.div_ceil(rows);
    let grid_width = (cols - 1) as f64 * col_pitch;
    // Centred on the board, shifted to stay within the walls.
    let (lo, hi) = (
        -left + grid_width / 2.0 + width / 2.0,
        right - grid_width / 2.0 - width / 2.0,
    );
    let shift = if lo <= hi {
        0.0f64.clamp(lo, hi)
    } else {
        (lo + hi) / 2.0
    };
    (0..n)
        .map(|k| {
            let (row, mut col) = (k / cols, k % cols);
            if row % 2 == 1 {
                col = cols - 1 - col;
            }
            let lateral = shift + col as f64 * col_pitch - grid_width / 2.0;
            let out = start + row as f64 * row_pitch + depth / 2.0;
            Pose {
                center: origin + b.front * out + b.right * lateral,
                rotation: b.rotation,
            }
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::relations;

    const ROOM: Room = Room::rect(500.0, 400.0);

    #[test]
    fn facing_rotation_follows_the_convention() {
        assert_eq!(facing_rotation(DVec2::ZERO, DVec2::new(0.0, 5.0)), 0.0);
        assert_eq!(facing_rotation(DVec2::ZERO, DVec2::new(5.0, 0.0)), 90.0);
        assert_eq!(facing_rotation(DVec2::ZERO, DVec2::new(0.0, -5.0)), 180.0);
        assert_eq!(facing_rotation(DVec2::ZERO, DVec2::new(-5.0, 0.0)), 270.0);
    }

    #[test]
    fn first_pose_meets_each_relation() {
        let sofa = Footprint::new(DVec2::new(250.0, 47.5), 220.0, 95.0, 0.0);
        for (relation, face) in [
            (Relation::SideOf, false),
            (Relation::InFrontOf, false),
            (Relation::Around, true),
            (Relation::Near, true),
            (Relation::Opposite, true),
            (Relation::AlignedWith, false),
        ] {
            let p = relation_poses(60.0, 40.0, relation, &sofa, &ROOM, 10.0, face)[0];
            let fp = Footprint::new(p.center, 60.0, 40.0, p.rotation);
            assert!(relation.holds(&fp, &sofa), "{relation}: {p:?}");
            if face {
                assert!(relations::facing(&fp, &sofa), "{relation} faces: {p:?}");
            }
        }
    }

    #[test]
    fn seats_around_a_table_face_it_and_do_not_touch() {
        let table = Footprint::new(DVec2::new(250.0, 200.0), 180.0, 90.0, 0.0);
        for n in [1, 4, 6, 8, 10] {
            let seats = around_slots(&table, false, 45.0, 50.0, n, 5.0);
            assert_eq!(seats.len(), n);
            let fps: Vec<Footprint> = seats
                .iter()
                .map(|p| Footprint::new(p.center, 45.0, 50.0, p.rotation))
                .collect();
            for (i, f) in fps.iter().enumerate() {
                assert!(relations::around(f, &table), "{n} seats, seat {i}");
                assert!(!f.collides(&table));
                for g in &fps[i + 1..] {
                    assert!(!f.collides(g), "{n} seats overlap");
                }
            }
        }
        let round = Footprint::new(DVec2::new(250.0, 200.0), 180.0, 180.0, 0.0);
        let seats = around_slots(&round, true, 45.0, 50.0, 8, 5.0);
        assert!(
            seats.iter().all(|p| relations::around(
                &Footprint::new(p.center, 45.0, 50.0, p.rotation),
                &round
            ))
        );
    }

    #[test]
    fn rows_face_away_from_the_board_in_a_snake() {
        let room = Room::rect(700.0, 600.0);
        let board = Footprint::new(DVec2::new(350.0, 5.0), 240.0, 10.0, 0.0);
        let poses = row_poses(&board, &room, 70.0, 50.0, 50.0, 9, 150.0);
        assert_eq!(poses.len(), 9);
        for (k, p) in poses.iter().enumerate() {
            assert_eq!(p.rotation, 0.0, "desk {k} turns its back to the board");
            let fp = Footprint::new(p.center, 70.0, 50.0, p.rotation);
            assert!(fp.inside(&room), "desk {k} inside the room");
            assert!(
                p.center.y - 25.0 >= 160.0 - 1e-9,
                "desk {k} behind the start line"
            );
        }
        // Consecutive desks are in line (same row, or same column at a row's end).
        for pair in poses.windows(2) {
            let a = Footprint::new(pair[1].center, 70.0, 50.0, 0.0);
            let b = Footprint::new(pair[0].center, 70.0, 50.0, 0.0);
            assert!(crate::relations::aligned_with(&a, &b));
        }
        // Nothing overlaps, with room for a chair in front of every desk.
        for (i, p) in poses.iter().enumerate() {
            for q in &poses[i + 1..] {
                let a = Footprint::new(p.center + DVec2::new(0.0, 25.0), 70.0, 100.0, 0.0);
                let b = Footprint::new(q.center + DVec2::new(0.0, 25.0), 70.0, 100.0, 0.0);
                assert!(!a.collides(&b));
            }
        }
    }
}
