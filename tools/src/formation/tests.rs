//! Formation properties: counts, gaps (measured exactly, in f64), facing, determinism, and
//! invariance under turning and moving the input; plus one worked example per request kind.

use disco_core::geometry::Footprint;
use disco_core::placement::{Pose, facing_rotation};
use glam::DVec2;
use proptest::prelude::*;

use super::*;

const EPS: f64 = 1e-6;

fn fp(x: f64, y: f64, w: f64, d: f64, r: f64) -> Footprint {
    Footprint::new(DVec2::new(x, y), w, d, r)
}

/// How far `f` reaches from its centre along the unit vector `n`.
fn reach(f: &Footprint, n: DVec2) -> f64 {
    f.half.x * f.right.dot(n).abs() + f.half.y * f.front.dot(n).abs()
}

fn segment_distance(p: DVec2, a: DVec2, b: DVec2) -> f64 {
    let ab = b - a;
    let t = ((p - a).dot(ab) / ab.length_squared()).clamp(0.0, 1.0);
    (a + ab * t - p).length()
}

/// The exact distance between two footprints; negative (by the least separating overlap) when
/// their interiors meet. Separating axes first, then corner-to-edge distances, all in f64.
fn gap(a: &Footprint, b: &Footprint) -> f64 {
    let sep = [a.right, a.front, b.right, b.front]
        .into_iter()
        .map(|n| (b.center - a.center).dot(n).abs() - reach(a, n) - reach(b, n))
        .fold(f64::NEG_INFINITY, f64::max);
    if sep < 0.0 {
        return sep;
    }
    let (ca, cb) = (a.corners(), b.corners());
    let mut d = f64::INFINITY;
    for i in 0..4 {
        let j = (i + 1) % 4;
        for k in 0..4 {
            d = d.min(segment_distance(cb[k], ca[i], ca[j]));
            d = d.min(segment_distance(ca[k], cb[i], cb[j]));
        }
    }
    d
}

/// The least gap between any two of `fps`.
fn least_gap(fps: &[Footprint]) -> f64 {
    let mut least = f64::INFINITY;
    for (i, a) in fps.iter().enumerate() {
        for b in &fps[i + 1..] {
            least = least.min(gap(a, b));
        }
    }
    least
}

fn faces(member: &Footprint, target: &Footprint) -> bool {
    member.front_ray_hit(target).is_some()
}

fn angle_diff(a: f64, b: f64) -> f64 {
    let d = (a - b).rem_euclid(360.0);
    d.min(360.0 - d)
}

/// Turning clockwise by `theta` degrees about `pivot`, then moving by `shift`.
#[derive(Debug, Clone, Copy)]
struct Motion {
    pivot: DVec2,
    theta: f64,
    shift: DVec2,
}

impl Motion {
    fn point(&self, p: DVec2) -> DVec2 {
        let (s, c) = self.theta.to_radians().sin_cos();
        let d = p - self.pivot;
        self.pivot + DVec2::new(d.x * c + d.y * s, -d.x * s + d.y * c) + self.shift
    }

    fn vector(&self, v: DVec2) -> DVec2 {
        self.point(self.pivot + v) - self.point(self.pivot)
    }

    fn footprint(&self, f: &Footprint) -> Footprint {
        Footprint::new(
            self.point(f.center),
            2.0 * f.half.x,
            2.0 * f.half.y,
            f.rotation + self.theta,
        )
    }

    fn pose(&self, p: &Pose) -> Pose {
        Pose {
            center: self.point(p.center),
            rotation: p.rotation + self.theta,
        }
    }
}

/// `moved` is `original` turned and moved by `m`, pose by pose.
fn assert_moved(
    original: &[Pose],
    moved: &[Pose],
    m: Motion,
) -> std::result::Result<(), TestCaseError> {
    prop_assert_eq!(original.len(), moved.len());
    for (i, (o, n)) in original.iter().zip(moved).enumerate() {
        let want = m.pose(o);
        let off = (want.center - n.center).length();
        prop_assert!(
            off < 1e-6,
            "member {i}: {n:?} should be {want:?} ({off} cm off)"
        );
        let turn = angle_diff(want.rotation, n.rotation);
        prop_assert!(turn < 1e-6, "member {i} turned {turn}° off");
    }
    Ok(())
}

fn any_rotation() -> impl Strategy<Value = f64> {
    prop_oneof![0.0..360.0, (0..4u8).prop_map(|k| f64::from(k) * 90.0)]
}

fn focus() -> impl Strategy<Value = Footprint> {
    (
        -300.0..300.0,
        -300.0..300.0,
        20.0..300.0,
        5.0..150.0,
        any_rotation(),
    )
        .prop_map(|(x, y, w, d, r)| fp(x, y, w, d, r))
}

fn seat() -> impl Strategy<Value = Size> {
    (30.0..90.0, 30.0..90.0).prop_map(|(w, d)| Size::new(w, d))
}

fn motion() -> impl Strategy<Value = Motion> {
    (
        -200.0..200.0,
        -200.0..200.0,
        any_rotation(),
        -300.0..300.0,
        -300.0..300.0,
    )
        .prop_map(|(px, py, theta, sx, sy)| Motion {
            pivot: DVec2::new(px, py),
            theta,
            shift: DVec2::new(sx, sy),
        })
}

fn rows_spec() -> impl Strategy<Value = RowsSpec> {
    (
        (0usize..16, 1usize..5, seat()),
        (0.0..300.0, 0.0..40.0, 0.0..80.0),
        (proptest::option::of(0.0..360.0), any::<bool>()),
    )
        .prop_map(
            |((count, rows, seat), (first_row, spacing, aisle), (direction, curved))| RowsSpec {
                count,
                rows,
                seat,
                first_row,
                spacing,
                aisle,
                direction,
                curved,
            },
        )
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(200))]

    #[test]
    fn rows_keep_their_gaps_and_face_the_focus(focus in focus(), spec in rows_spec(), m in motion()) {
        let poses = rows(&focus, &spec).unwrap();
        prop_assert_eq!(poses.len(), spec.count);
        prop_assert_eq!(&rows(&focus, &spec).unwrap(), &poses, "deterministic");
        let fps = footprints(&poses, spec.seat);
        prop_assert!(least_gap(&fps) >= spec.spacing.min(spec.aisle) - EPS);
        let u = spec.direction.map_or(focus.front, |d| Footprint::new(DVec2::ZERO, 1.0, 1.0, d).front);
        let v = DVec2::new(u.y, -u.x);
        for (i, f) in fps.iter().enumerate() {
            prop_assert!(gap(f, &focus) >= spec.first_row - EPS, "seat {i} too close to the focus");
            if spec.curved {
                prop_assert!(faces(f, &focus), "seat {i} faces the focus");
                prop_assert!(angle_diff(f.rotation, facing_rotation(f.center, focus.center)) < 1e-6);
            } else {
                prop_assert!(f.front.dot(-u) > 1.0 - 1e-9, "seat {i} faces back along the line");
                let lateral = (f.center - focus.center).dot(v).abs();
                let shadow = reach(&focus, v);
                if lateral < shadow - 0.5 {
                    prop_assert!(faces(f, &focus), "seat {i}, in front of the focus, faces it");
                }
                if lateral > shadow + 0.5 {
                    prop_assert!(!faces(f, &focus));
                }
            }
        }
        let moved = RowsSpec { direction: spec.direction.map(|d| d + m.theta), ..spec.clone() };
        assert_moved(&poses, &rows(&m.footprint(&focus), &moved).unwrap(), m)?;
    }

    #[test]
    fn desk_rows_put_each_chair_behind_its_desk(
        focus in focus(),
        spec in rows_spec(),
        desk in seat(),
        chair_gap in 0.0..30.0,
        m in motion(),
    ) {
        let units = desk_rows(&focus, &spec, desk, chair_gap).unwrap();
        prop_assert_eq!(units.desks.len(), spec.count);
        prop_assert_eq!(units.chairs.len(), spec.count);
        prop_assert_eq!(&desk_rows(&focus, &spec, desk, chair_gap).unwrap(), &units);
        let desks = footprints(&units.desks, desk);
        let chairs = footprints(&units.chairs, spec.seat);
        let mut all = desks.clone();
        all.extend(chairs.iter().copied());
        prop_assert!(least_gap(&all) >= spec.spacing.min(spec.aisle).min(chair_gap) - EPS);
        for (i, (d, c)) in desks.iter().zip(&chairs).enumerate() {
            prop_assert!((gap(d, c) - chair_gap).abs() < EPS, "chair {i} {chair_gap} cm from its desk");
            prop_assert!(faces(c, d) && faces(d, c), "desk {i} and its chair face each other");
            prop_assert!(gap(d, &focus) >= spec.first_row - EPS);
            let outwards = (c.center - d.center).dot(d.center - focus.center);
            prop_assert!(outwards > 0.0, "chair {i} behind its desk, seen from the focus");
            if spec.curved {
                prop_assert!(faces(c, &focus), "chair {i} faces the focus");
            }
        }
        let moved = RowsSpec { direction: spec.direction.map(|d| d + m.theta), ..spec.clone() };
        let turned = desk_rows(&m.footprint(&focus), &moved, desk, chair_gap).unwrap();
        assert_moved(&units.desks, &turned.desks, m)?;
        assert_moved(&units.chairs, &turned.chairs, m)?;
    }

    #[test]
    fn arcs_are_equidistant_turned_to_the_focus_and_apart(
        focus in focus(),
        (count, seat) in (0usize..14, seat()),
        span in prop_oneof![10.0..360.0, Just(180.0), Just(360.0)],
        (spacing, clearance, min_radius) in (0.0..40.0, 0.0..120.0, prop_oneof![Just(0.0), 0.0..500.0]),
        direction in proptest::option::of(0.0..360.0),
        m in motion(),
    ) {
        let spec = ArcSpec { count, seat, span, spacing, clearance, min_radius, direction };
        let poses = arc(&focus, &spec).unwrap();
        prop_assert_eq!(poses.len(), count);
        prop_assert_eq!(&arc(&focus, &spec).unwrap(), &poses);
        let fps = footprints(&poses, seat);
        prop_assert!(least_gap(&fps) >= spacing - EPS);
        let radius = poses.first().map_or(0.0, |p| (p.center - focus.center).length());
        prop_assert!(count == 0 || radius >= min_radius - EPS);
        for (i, (p, f)) in poses.iter().zip(&fps).enumerate() {
            prop_assert!(((p.center - focus.center).length() - radius).abs() < 1e-6, "seat {i} on the circle");
            prop_assert!(angle_diff(p.rotation, facing_rotation(p.center, focus.center)) < 0.5);
            prop_assert!(faces(f, &focus));
            prop_assert!(gap(f, &focus) >= clearance - EPS, "seat {i} clear of the focus");
        }
        // Centred on the direction: the middle of the first and last seat's angles.
        if count >= 2 && span <= 180.0 {
            let middle = direction.unwrap_or(focus.rotation);
            let ends = [poses[0], poses[count - 1]].map(|p| facing_rotation(focus.center, p.center));
            let half = angle_diff(ends[0], ends[1]) / 2.0;
            prop_assert!((angle_diff(ends[0], middle) - half).abs() < 1e-6);
            prop_assert!((angle_diff(ends[1], middle) - half).abs() < 1e-6);
        }
        let moved = ArcSpec { direction: direction.map(|d| d + m.theta), ..spec.clone() };
        assert_moved(&poses, &arc(&m.footprint(&focus), &moved).unwrap(), m)?;
    }

    #[test]
    fn rings_seat_everyone_clear_of_the_piece_and_facing_it(
        piece in focus(),
        (count, seat, round) in (0usize..16, seat(), any::<bool>()),
        (gap_cm, spacing) in (0.0..30.0, 0.0..40.0),
        m in motion(),
    ) {
        // A round piece's footprint is the square around it.
        let piece = if round {
            Footprint::new(piece.center, 2.0 * piece.half.x, 2.0 * piece.half.x, piece.rotation)
        } else {
            piece
        };
        let spec = RingSpec { count, seat, round, gap: gap_cm, spacing };
        let poses = ring(&piece, &spec).unwrap();
        prop_assert_eq!(poses.len(), count);
        prop_assert_eq!(&ring(&piece, &spec).unwrap(), &poses);
        let fps = footprints(&poses, seat);
        prop_assert!(least_gap(&fps) >= spacing - EPS);
        let fit = |half: f64| ((2.0 * half + spacing) / (seat.width + spacing)).floor() as usize;
        let comfortable = count <= 2 * fit(piece.half.x) + 2 * fit(piece.half.y);
        for (i, f) in fps.iter().enumerate() {
            prop_assert!(gap(f, &piece) >= gap_cm - EPS, "seat {i} clear of the piece");
            if round || comfortable || beside_a_side(f, &piece) {
                prop_assert!(faces(f, &piece), "seat {i} faces the piece");
            }
        }
        assert_moved(&poses, &ring(&m.footprint(&piece), &spec).unwrap(), m)?;
    }

    #[test]
    fn per_side_puts_k_down_each_long_side_evenly(
        table in focus(),
        (k, ends, seat) in (0usize..8, any::<bool>(), seat()),
        (gap_cm, spacing) in (0.0..30.0, 0.0..40.0),
        m in motion(),
    ) {
        let poses = per_side(&table, seat, k, ends, gap_cm, spacing).unwrap();
        prop_assert_eq!(poses.len(), 2 * k + 2 * usize::from(ends));
        prop_assert_eq!(&per_side(&table, seat, k, ends, gap_cm, spacing).unwrap(), &poses);
        let fps = footprints(&poses, seat);
        prop_assert!(least_gap(&fps) >= spacing - EPS);
        let (long_normal, end_normal) = if table.half.x >= table.half.y {
            (table.front, table.right)
        } else {
            (table.right, table.front)
        };
        for (i, f) in fps.iter().enumerate() {
            prop_assert!(gap(f, &table) >= gap_cm - EPS);
            if beside_a_side(f, &table) {
                prop_assert!(faces(f, &table), "seat {i} faces the table");
            }
            // The first k on one long side, the next k on the other, facing across the table.
            let normal = match i {
                _ if i < k => long_normal,
                _ if i < 2 * k => -long_normal,
                _ if i == 2 * k => end_normal,
                _ => -end_normal,
            };
            prop_assert!(f.front.dot(-normal) > 1.0 - 1e-9, "seat {i} on its side");
        }
        // Evenly: the same step between neighbours on a side.
        for side in [&poses[..k], &poses[k..2 * k]] {
            let steps: Vec<f64> = side.windows(2).map(|w| (w[1].center - w[0].center).length()).collect();
            prop_assert!(steps.windows(2).all(|s| (s[0] - s[1]).abs() < 1e-6));
        }
        let turned = per_side(&m.footprint(&table), seat, k, ends, gap_cm, spacing).unwrap();
        assert_moved(&poses, &turned, m)?;
    }

    #[test]
    fn pods_pair_desks_back_to_back_with_an_aisle_between_pods(
        anchor in (-300.0..300.0, -300.0..300.0).prop_map(|(x, y)| DVec2::new(x, y)),
        rotation in any_rotation(),
        (count, per_pod) in (0usize..4, 0usize..9),
        (desk, chair) in (seat(), seat()),
        (chair_gap, desk_gap, aisle) in (0.0..30.0, prop_oneof![Just(0.0), 0.0..20.0], 0.0..150.0),
        m in motion(),
    ) {
        let spec = PodsSpec { pods: count, per_pod, desk, chair, chair_gap, desk_gap, aisle };
        let w = pods(anchor, rotation, &spec).unwrap();
        prop_assert_eq!(w.desks.len(), count * per_pod);
        prop_assert_eq!(w.chairs.len(), count * per_pod);
        prop_assert_eq!(&pods(anchor, rotation, &spec).unwrap(), &w);
        let desks = footprints(&w.desks, desk);
        let chairs = footprints(&w.chairs, chair);
        let cols = per_pod.div_ceil(2);
        for p in 0..count {
            let base = p * per_pod;
            for i in 0..per_pod / 2 {
                let (a, b) = (&desks[base + i], &desks[base + cols + i]);
                prop_assert!((a.back_center() - b.back_center()).length() < 1e-6, "pair {i} backs touch");
                prop_assert!(a.front.dot(b.front) < -1.0 + 1e-9, "pair {i} faces opposite ways");
            }
        }
        for (i, (d, c)) in desks.iter().zip(&chairs).enumerate() {
            prop_assert!((gap(d, c) - chair_gap).abs() < 1e-6, "chair {i} at its desk");
            prop_assert!(faces(c, d), "chair {i} faces its desk");
        }
        // Nothing overlaps; members of different pods keep the aisle.
        let all: Vec<(usize, Footprint)> = desks.iter().chain(&chairs).enumerate()
            .map(|(i, f)| ((i % (count * per_pod).max(1)) / per_pod.max(1), *f))
            .collect();
        for (i, (pa, a)) in all.iter().enumerate() {
            for (pb, b) in &all[i + 1..] {
                let least = if pa == pb { -1e-6 } else { aisle - 1e-6 };
                prop_assert!(gap(a, b) >= least, "pods {pa} and {pb}: {} cm", gap(a, b));
            }
        }
        let turned = pods(m.point(anchor), rotation + m.theta, &spec).unwrap();
        assert_moved(&w.desks, &turned.desks, m)?;
        assert_moved(&w.chairs, &turned.chairs, m)?;
    }

    #[test]
    fn members_along_a_front_face_the_piece(
        piece in focus(),
        (count, member) in (0usize..10, seat()),
        (gap_cm, spacing) in (0.0..30.0, 0.0..40.0),
        m in motion(),
    ) {
        let poses = along_front(&piece, member, count, gap_cm, spacing).unwrap();
        prop_assert_eq!(poses.len(), count);
        prop_assert_eq!(&along_front(&piece, member, count, gap_cm, spacing).unwrap(), &poses);
        let fps = footprints(&poses, member);
        prop_assert!(least_gap(&fps) >= spacing - EPS);
        let fits = count as f64 * (member.width + spacing) <= 2.0 * piece.half.x + spacing;
        for (i, f) in fps.iter().enumerate() {
            let out = piece.to_local(f.front_center()).y - piece.half.y;
            prop_assert!((out - gap_cm).abs() < 1e-6, "member {i} {gap_cm} cm out");
            prop_assert!(gap(f, &piece) >= gap_cm - EPS);
            prop_assert!(piece.to_local(f.center).y > piece.half.y, "member {i} in front");
            if fits || piece.to_local(f.center).x.abs() < piece.half.x - 0.5 {
                prop_assert!(faces(f, &piece), "member {i} faces the piece");
            }
        }
        let turned = along_front(&m.footprint(&piece), member, count, gap_cm, spacing).unwrap();
        assert_moved(&poses, &turned, m)?;
    }

    #[test]
    fn a_flanking_pair_stands_level_with_the_anchor(
        anchor in focus(),
        member in seat(),
        gap_cm in 0.0..30.0,
        m in motion(),
    ) {
        let poses = flanking_pair(&anchor, member, gap_cm).unwrap();
        prop_assert_eq!(poses.len(), 2);
        prop_assert_eq!(&flanking_pair(&anchor, member, gap_cm).unwrap(), &poses);
        let fps = footprints(&poses, member);
        for (side, f) in [-1.0, 1.0].into_iter().zip(&fps) {
            prop_assert!((gap(f, &anchor) - gap_cm).abs() < 1e-6);
            prop_assert!(angle_diff(f.rotation, anchor.rotation) < 1e-9, "facing the anchor's way");
            prop_assert!((anchor.to_local(f.back_center()).y + anchor.half.y).abs() < 1e-6, "backs in line");
            prop_assert!(anchor.to_local(f.center).x * side > 0.0, "left first, then right");
        }
        prop_assert!(gap(&fps[0], &fps[1]) > 0.0);
        assert_moved(&poses, &flanking_pair(&m.footprint(&anchor), member, gap_cm).unwrap(), m)?;
    }

    #[test]
    fn one_item_stands_in_front_of_each_member(
        focus in focus(),
        (count, seat, item) in (0usize..10, seat(), seat()),
        distance in 0.0..60.0,
        m in motion(),
    ) {
        let members = arc(&focus, &ArcSpec::new(count, seat)).unwrap();
        let items = one_per_member(&members, seat, item, distance).unwrap();
        prop_assert_eq!(items.len(), count);
        prop_assert_eq!(&one_per_member(&members, seat, item, distance).unwrap(), &items);
        for (i, (s, t)) in footprints(&members, seat).iter().zip(footprints(&items, item)).enumerate() {
            prop_assert!((gap(s, &t) - distance).abs() < 1e-6, "item {i} {distance} cm in front");
            prop_assert!(faces(&t, s) && faces(s, &t), "item {i} and its member face each other");
        }
        let moved: Vec<Pose> = members.iter().map(|p| m.pose(p)).collect();
        assert_moved(&items, &one_per_member(&moved, seat, item, distance).unwrap(), m)?;
    }

    #[test]
    fn an_l_workstation_fits_its_corner(
        corner in (-300.0..300.0, -300.0..300.0).prop_map(|(x, y)| DVec2::new(x, y)),
        (wall, angle) in (any_rotation(), prop_oneof![Just(90.0), 50.0..150.0]),
        (desk_a, desk_b, chair) in (seat(), seat(), seat()),
        chair_gap in 0.0..30.0,
        m in motion(),
    ) {
        let (desk_a, desk_b) = (Size::new(desk_a.width * 2.0, desk_a.depth), Size::new(desk_b.width * 2.0, desk_b.depth));
        let a = Footprint::new(DVec2::ZERO, 1.0, 1.0, wall).front;
        let b = Footprint::new(DVec2::ZERO, 1.0, 1.0, wall + angle).front;
        let spec = LSpec { desk_a, desk_b, chair, chair_gap };
        let w = l_workstation(corner, a, b, &spec).unwrap();
        prop_assert_eq!(&l_workstation(corner, a, b, &spec).unwrap(), &w);
        prop_assert_eq!((w.desks.len(), w.chairs.len()), (2, 1));
        let da = Footprint::new(w.desks[0].center, desk_a.width, desk_a.depth, w.desks[0].rotation);
        let db = Footprint::new(w.desks[1].center, desk_b.width, desk_b.depth, w.desks[1].rotation);
        let c = Footprint::new(w.chairs[0].center, chair.width, chair.depth, w.chairs[0].rotation);
        prop_assert!(gap(&da, &db) >= -1e-6, "the desks do not overlap");
        prop_assert!(gap(&da, &c) >= chair_gap - 1e-6 && gap(&db, &c) >= chair_gap - 1e-6);
        // Each desk's back on its wall (on the wall's side of the corner), all inside the corner.
        for (d, wall_dir) in [(&da, a), (&db, b)] {
            let (p, q) = d.back_edge();
            for e in [p, q] {
                prop_assert!((e - corner).perp_dot(wall_dir).abs() < 1e-6, "back on its wall");
                prop_assert!((e - corner).dot(wall_dir) > -1e-6);
            }
            for x in d.corners().into_iter().chain(c.corners()) {
                prop_assert!(a.perp_dot(x - corner) * a.perp_dot(b) >= -1e-6, "inside the corner");
                prop_assert!(b.perp_dot(x - corner) * b.perp_dot(a) >= -1e-6, "inside the corner");
            }
        }
        prop_assert!(angle_diff(c.rotation, facing_rotation(c.center, corner)) < 1e-6, "chair faces the corner");
        if angle == 90.0 {
            // Facing the corner, its ray crosses desk A when desk B is shallower than A is wide.
            if desk_b.depth < desk_a.width {
                prop_assert!(faces(&c, &da), "chair faces desk A");
            }
            prop_assert!(gap(&da, &db).abs() < 1e-6, "the desks meet");
        }
        let turned = l_workstation(m.point(corner), m.vector(a), m.vector(b), &spec).unwrap();
        assert_moved(&w.desks, &turned.desks, m)?;
        assert_moved(&w.chairs, &turned.chairs, m)?;
    }

    #[test]
    fn a_run_along_a_wall_has_its_backs_on_the_wall(
        (from, heading, length) in ((-300.0..300.0, -300.0..300.0), any_rotation(), 50.0..800.0),
        (count, member, spacing) in (0usize..10, seat(), 0.0..40.0),
        m in motion(),
    ) {
        let from = DVec2::new(from.0, from.1);
        let to = from + Footprint::new(DVec2::ZERO, 1.0, 1.0, heading).front * length;
        let poses = along_wall(from, to, member, count, spacing).unwrap();
        prop_assert_eq!(poses.len(), count);
        prop_assert_eq!(&along_wall(from, to, member, count, spacing).unwrap(), &poses);
        let fps = footprints(&poses, member);
        prop_assert!(least_gap(&fps) >= spacing - EPS);
        let d = (to - from).normalize();
        let fits = count as f64 * (member.width + spacing) <= length + spacing;
        for (i, f) in fps.iter().enumerate() {
            let (a, b) = f.back_edge();
            prop_assert!(d.perp_dot(a - from).abs() < 1e-6 && d.perp_dot(b - from).abs() < 1e-6, "member {i} back on the wall");
            prop_assert!(d.perp_dot(f.center - from) > 0.0, "member {i} on the room's side");
            if fits {
                prop_assert!((a - from).dot(d) >= -1e-6 && (b - from).dot(d) <= length + 1e-6, "member {i} within the wall");
            }
        }
        prop_assert!(poses.windows(2).all(|w| (w[1].center - w[0].center).dot(d) > 0.0), "from `from` to `to`");
        let turned = along_wall(m.point(from), m.point(to), member, count, spacing).unwrap();
        assert_moved(&poses, &turned, m)?;
    }

    #[test]
    fn a_u_workstation_seats_its_chair_inside(
        anchor in (-300.0..300.0, -300.0..300.0).prop_map(|(x, y)| DVec2::new(x, y)),
        rotation in any_rotation(),
        (main_width, main_depth, side, chair) in (100.0..240.0, 40.0..90.0, seat(), seat()),
        chair_gap in 0.0..30.0,
        m in motion(),
    ) {
        let spec = USpec { main: Size::new(main_width, main_depth), side: Size::new(side.width * 2.0, side.depth), chair, chair_gap };
        let Ok(w) = u_workstation(anchor, rotation, &spec) else {
            prop_assert!(chair.width + 2.0 * chair_gap > main_width - 2.0 * side.depth, "refused only when too narrow");
            return Ok(());
        };
        prop_assert_eq!(&u_workstation(anchor, rotation, &spec).unwrap(), &w);
        prop_assert_eq!((w.desks.len(), w.chairs.len()), (3, 1));
        let main = footprints(&w.desks[..1], spec.main)[0];
        let sides = footprints(&w.desks[1..], spec.side);
        let c = footprints(&w.chairs, chair)[0];
        prop_assert!((gap(&main, &c) - chair_gap).abs() < 1e-6);
        prop_assert!(faces(&c, &main), "the chair faces the main desk");
        for s in &sides {
            prop_assert!(gap(s, &main).abs() < 1e-6, "each side desk meets the main desk");
            prop_assert!(gap(s, &c) >= chair_gap - EPS, "the chair clear of the side desks");
            prop_assert!(s.front.dot(main.front).abs() < 1e-9, "side desks across the main one");
            prop_assert!(faces(s, &c) || s.front.dot(c.center - s.center) > 0.0, "side desks face into the U");
        }
        prop_assert!(gap(&sides[0], &sides[1]) > 0.0);
        prop_assert!(sides[0].front.dot(sides[1].front) < -1.0 + 1e-9, "the sides face each other");
        let turned = u_workstation(m.point(anchor), rotation + m.theta, &spec).unwrap();
        assert_moved(&w.desks, &turned.desks, m)?;
        assert_moved(&w.chairs, &turned.chairs, m)?;
    }
}

/// `f` stands out from one side of `piece`, its centre within that side's length (so a seat
/// facing straight at the side meets it).
fn beside_a_side(f: &Footprint, piece: &Footprint) -> bool {
    let l = piece.to_local(f.center);
    (l.x.abs() < piece.half.x - 0.5 && l.y.abs() > piece.half.y)
        || (l.y.abs() < piece.half.y - 0.5 && l.x.abs() > piece.half.x)
}

// ---------------------------------------------------------------------------------------------
// The requests of issue 25, one worked example each.

#[test]
fn two_rows_of_five_facing_the_instructor() {
    let board = fp(300.0, 5.0, 240.0, 10.0, 0.0);
    let poses = rows(&board, &RowsSpec::new(10, 2, Size::new(50.0, 50.0))).unwrap();
    assert_eq!(poses.len(), 10);
    // Five per row, the first row 200 cm from the board, the second one aisle further.
    let first = 10.0 + FIRST_ROW_CM + 25.0;
    for (i, p) in poses.iter().enumerate() {
        let row_y = if i < 5 {
            first
        } else {
            first + 50.0 + ROW_AISLE_CM
        };
        assert!(
            (p.center.y - row_y).abs() < 1e-9,
            "seat {i} in its row: {p:?}"
        );
        assert_eq!(p.rotation, 180.0, "seat {i} faces the board");
    }
    // Left to right as the board sees the room, centred on it.
    assert_eq!(poses[0].center.x, 300.0 - 2.0 * 60.0);
    assert_eq!(poses[4].center.x, 300.0 + 2.0 * 60.0);
}

#[test]
fn curved_rows_turn_each_seat_to_the_screen() {
    let screen = fp(0.0, 0.0, 200.0, 10.0, 90.0);
    let spec = RowsSpec {
        curved: true,
        ..RowsSpec::new(8, 2, Size::new(70.0, 80.0))
    };
    let poses = rows(&screen, &spec).unwrap();
    let fps = footprints(&poses, spec.seat);
    for f in &fps {
        assert!(faces(f, &screen));
        assert!(f.center.x > 0.0, "in front of the screen (it faces +x)");
    }
    assert!(
        poses[0].rotation != poses[1].rotation,
        "free angles, not one facing"
    );
    assert!(least_gap(&fps) >= SEAT_SPACING_CM - EPS);
}

#[test]
fn six_chairs_in_a_semicircle_facing_the_piano() {
    let piano = fp(200.0, 60.0, 150.0, 60.0, 0.0);
    let seat = Size::new(45.0, 50.0);
    let poses = arc(&piano, &ArcSpec::new(6, seat)).unwrap();
    assert_eq!(poses.len(), 6);
    // The ends at the piano's left and right (a semicircle), all turned to its centre.
    assert!((poses[0].rotation - 90.0).abs() < 1e-9, "{:?}", poses[0]);
    assert!((poses[5].rotation - 270.0).abs() < 1e-9, "{:?}", poses[5]);
    let fps = footprints(&poses, seat);
    let least = fps
        .iter()
        .map(|f| gap(f, &piano))
        .fold(f64::INFINITY, f64::min);
    assert!(least >= ARC_CLEARANCE_CM - EPS);
    // A small focus: the neighbours set the radius, and then they stand exactly `spacing` apart.
    let stool = fp(0.0, 0.0, 10.0, 10.0, 0.0);
    let spec = ArcSpec {
        clearance: 0.0,
        ..ArcSpec::new(9, seat)
    };
    let fps = footprints(&arc(&stool, &spec).unwrap(), seat);
    assert!((least_gap(&fps) - SEAT_SPACING_CM).abs() < 1e-6);
}

#[test]
fn eight_around_a_round_table_clear_its_square_footprint() {
    let table = fp(250.0, 200.0, 180.0, 180.0, 0.0);
    let seat = Size::new(45.0, 50.0);
    let poses = ring(&table, &RingSpec::new(8, seat, true)).unwrap();
    let fps = footprints(&poses, seat);
    assert_eq!(poses[0].rotation, 180.0, "the first in front of the table");
    let least = fps
        .iter()
        .map(|f| gap(f, &table))
        .fold(f64::INFINITY, f64::min);
    assert!(
        (least - TABLE_GAP_CM).abs() < 1e-6,
        "the diagonal seats touch the gap: {least}"
    );
    assert!(fps.iter().all(|f| faces(f, &table)));
}

#[test]
fn five_chairs_down_each_long_side_and_one_at_each_end() {
    let table = fp(300.0, 200.0, 90.0, 300.0, 0.0);
    let seat = Size::new(45.0, 50.0);
    let poses = per_side(&table, seat, 5, true, TABLE_GAP_CM, SEAT_SPACING_CM).unwrap();
    assert_eq!(poses.len(), 12);
    // The table is deeper than wide: its long sides are its right and left.
    assert!(
        poses[..5]
            .iter()
            .all(|p| p.rotation == 270.0 && p.center.x > 345.0)
    );
    assert!(
        poses[5..10]
            .iter()
            .all(|p| p.rotation == 90.0 && p.center.x < 255.0)
    );
    assert_eq!(poses[10].rotation, 180.0);
    assert_eq!(poses[11].rotation, 0.0);
    assert!(footprints(&poses, seat).iter().all(|f| faces(f, &table)));
}

#[test]
fn two_pods_of_four_desks_two_pairs_back_to_back() {
    let desk = Size::new(120.0, 60.0);
    let chair = Size::new(50.0, 50.0);
    let w = pods(
        DVec2::new(400.0, 300.0),
        0.0,
        &PodsSpec::new(2, 4, desk, chair),
    )
    .unwrap();
    assert_eq!(w.desks.len(), 8);
    let facing: Vec<f64> = w.desks.iter().map(|p| p.rotation).collect();
    assert_eq!(facing, [0.0, 0.0, 180.0, 180.0, 0.0, 0.0, 180.0, 180.0]);
    // The pods' inner desks are the aisle apart; the block is centred on the anchor.
    let inner = w.desks[4].center.x - w.desks[1].center.x - desk.width;
    assert!((inner - POD_AISLE_CM).abs() < 1e-9);
    let mean = w.desks.iter().map(|p| p.center).sum::<DVec2>() / 8.0;
    assert!((mean - DVec2::new(400.0, 300.0)).length() < 1e-9);
}

#[test]
fn four_bar_stools_along_the_island_front() {
    let island = fp(300.0, 250.0, 240.0, 100.0, 180.0);
    let stool = Size::new(40.0, 40.0);
    let poses = along_front(&island, stool, 4, TABLE_GAP_CM, SEAT_SPACING_CM).unwrap();
    // The island faces -y: the stools stand below it, facing up, left to right as it sees them.
    assert!(
        poses
            .iter()
            .all(|p| p.rotation == 0.0 && p.center.y < 200.0)
    );
    assert!(poses.windows(2).all(|w| w[0].center.x > w[1].center.x));
    assert!((poses[0].center.x - poses[1].center.x - 60.0).abs() < 1e-9);
}

#[test]
fn a_nightstand_on_each_side_of_the_bed() {
    let bed = fp(200.0, 105.0, 160.0, 210.0, 0.0);
    let stand = Size::new(45.0, 40.0);
    let poses = flanking_pair(&bed, stand, FLANK_GAP_CM).unwrap();
    assert_eq!(poses[0].center, DVec2::new(200.0 - 80.0 - 5.0 - 22.5, 20.0));
    assert_eq!(poses[1].center, DVec2::new(200.0 + 80.0 + 5.0 + 22.5, 20.0));
}

#[test]
fn a_music_stand_in_front_of_each_chair() {
    let chairs = [Pose {
        center: DVec2::new(100.0, 100.0),
        rotation: 90.0,
    }];
    let stands = one_per_member(
        &chairs,
        Size::new(45.0, 50.0),
        Size::new(50.0, 30.0),
        STAND_DISTANCE_CM,
    )
    .unwrap();
    assert!((stands[0].center - DVec2::new(100.0 + 25.0 + 30.0 + 15.0, 100.0)).length() < 1e-9);
    assert_eq!(stands[0].rotation, 270.0);
}

#[test]
fn an_l_workstation_in_the_bottom_left_corner() {
    let spec = LSpec {
        desk_a: Size::new(140.0, 70.0),
        desk_b: Size::new(120.0, 60.0),
        chair: Size::new(50.0, 50.0),
        chair_gap: CHAIR_GAP_CM,
    };
    let w = l_workstation(DVec2::ZERO, DVec2::X, DVec2::Y, &spec).unwrap();
    // Desk A on the bottom wall from the corner, facing up; desk B on the left wall above it.
    assert_eq!(w.desks[0].center, DVec2::new(70.0, 35.0));
    assert_eq!(w.desks[0].rotation, 0.0);
    assert!((w.desks[1].center - DVec2::new(30.0, 70.0 + 60.0)).length() < 1e-9);
    assert!((w.desks[1].rotation - 90.0).abs() < 1e-9);
    let chair = w.chairs[0];
    assert!(
        chair.center.x > 60.0 && chair.center.y > 70.0,
        "in the crook"
    );
    assert!((chair.rotation - facing_rotation(chair.center, DVec2::ZERO)).abs() < 1e-9);
}

#[test]
fn bad_input_is_refused_with_the_formation_and_the_reason() {
    let focus = fp(0.0, 0.0, 100.0, 50.0, 0.0);
    let nan_seat = RowsSpec::new(4, 2, Size::new(f64::NAN, 50.0));
    let err = rows(&focus, &nan_seat).unwrap_err().to_string();
    assert!(err.contains("rows") && err.contains("seat size"), "{err}");
    let no_rows = RowsSpec::new(4, 0, Size::new(50.0, 50.0));
    assert!(rows(&focus, &no_rows).is_err());
    let zero_span = ArcSpec {
        span: 0.0,
        ..ArcSpec::new(3, Size::new(50.0, 50.0))
    };
    assert!(
        arc(&focus, &zero_span)
            .unwrap_err()
            .to_string()
            .contains("span")
    );
    let too_many = RingSpec::new(MAX_MEMBERS + 1, Size::new(50.0, 50.0), true);
    assert!(ring(&focus, &too_many).is_err());
    let negative = along_front(&focus, Size::new(40.0, 40.0), 3, -5.0, 10.0);
    assert!(negative.unwrap_err().to_string().contains("gap"));
    let spec = LSpec {
        desk_a: Size::new(140.0, 70.0),
        desk_b: Size::new(120.0, 60.0),
        chair: Size::new(50.0, 50.0),
        chair_gap: 5.0,
    };
    let parallel = l_workstation(DVec2::ZERO, DVec2::X, DVec2::new(3.0, 0.0), &spec);
    assert!(parallel.unwrap_err().to_string().contains("walls"));
    let huge = pods(
        DVec2::ZERO,
        0.0,
        &PodsSpec::new(usize::MAX, 4, spec.chair, spec.chair),
    );
    assert!(huge.is_err());
}

#[test]
fn footprints_match_the_poses() {
    let poses = [Pose {
        center: DVec2::new(10.0, 20.0),
        rotation: 30.0,
    }];
    let f = footprints(&poses, Size::new(40.0, 50.0));
    assert_eq!(f, vec![fp(10.0, 20.0, 40.0, 50.0, 30.0)]);
}

#[test]
fn a_run_of_three_bookcases_along_the_top_wall() {
    // The top wall of a 400 x 300 room, walked counter-clockwise: right to left.
    let poses = along_wall(
        DVec2::new(400.0, 300.0),
        DVec2::new(0.0, 300.0),
        Size::new(80.0, 35.0),
        3,
        SEAT_SPACING_CM,
    )
    .unwrap();
    let xs: Vec<f64> = poses.iter().map(|p| p.center.x).collect();
    assert!(
        xs.iter()
            .zip([333.333, 200.0, 66.667])
            .all(|(x, want)| (x - want).abs() < 1e-3)
    );
    assert!(
        poses
            .iter()
            .all(|p| p.rotation == 180.0 && (p.center.y - 282.5).abs() < 1e-9)
    );
}

#[test]
fn a_u_workstation_too_narrow_for_its_chair_is_refused() {
    let spec = USpec {
        main: Size::new(160.0, 70.0),
        side: Size::new(120.0, 60.0),
        chair: Size::new(50.0, 50.0),
        chair_gap: CHAIR_GAP_CM,
    };
    let err = u_workstation(DVec2::ZERO, 0.0, &spec)
        .unwrap_err()
        .to_string();
    assert!(
        err.contains("U workstation") && err.contains("does not fit"),
        "{err}"
    );
    let wide = USpec {
        main: Size::new(200.0, 70.0),
        ..spec
    };
    let w = u_workstation(DVec2::new(100.0, 0.0), 0.0, &wide).unwrap();
    assert_eq!(
        w.desks[1].rotation, 90.0,
        "the left side desk faces right, into the U"
    );
    assert_eq!(w.desks[2].rotation, 270.0);
    assert!((w.chairs[0].center - DVec2::new(100.0, 70.0 + 5.0 + 25.0)).length() < 1e-9);
}

proptest! {
    /// Aisles: the asked count, no two units overlapping, the asked aisle clear before every
    /// unit's front, and every front but the outer lines' facing another unit's front across
    /// the aisle (never a back).
    #[test]
    fn aisles_keep_every_front_clear_and_facing_a_front(
        count in 1usize..24,
        lines in 1usize..6,
        w in 60.0f64..300.0,
        d in 30.0f64..120.0,
        aisle in 60.0f64..200.0,
        gap_cm in 0.0f64..40.0,
        rotation in 0.0f64..360.0,
        x in -500.0f64..500.0,
        y in -500.0f64..500.0,
    ) {
        let spec = AislesSpec { count, lines, unit: Size::new(w, d), aisle, gap: gap_cm };
        let poses = aisles(DVec2::new(x, y), rotation, &spec).unwrap();
        prop_assert_eq!(poses.len(), count);
        let fps = footprints(&poses, spec.unit);
        prop_assert!(least_gap(&fps) >= -EPS, "units overlap");
        for (i, a) in fps.iter().enumerate() {
            // The strip before its front, the aisle deep, is clear of every other unit.
            let strip = Footprint::new(
                a.front_center() + a.front * (aisle / 2.0),
                2.0 * a.half.x - 2.0 * EPS,
                aisle - 2.0 * EPS,
                a.rotation,
            );
            for (j, b) in fps.iter().enumerate() {
                if i != j {
                    prop_assert!(gap(&strip, b) >= -EPS, "unit {j} stands in unit {i}'s aisle");
                }
            }
            // Whatever stands straight across the aisle faces back at it.
            for b in &fps {
                let across = (b.center - a.center).dot(a.front);
                let sideways = (b.center - a.center).dot(a.right).abs();
                if across > EPS && sideways < a.half.x && across - d <= aisle + EPS {
                    prop_assert!(b.front.dot(a.front) < -0.99, "a front faces a back");
                }
            }
        }
    }
}

#[test]
fn four_gondolas_in_four_lines_make_two_aisles() {
    let spec = AislesSpec::new(4, 4, Size::new(240.0, 90.0));
    let poses = aisles(DVec2::ZERO, 0.0, &spec).unwrap();
    let ys: Vec<f64> = poses.iter().map(|p| p.center.y).collect();
    // Line 0 faces up across a 120 cm aisle to line 1; lines 1 and 2 back to back; line 3
    // across the second aisle. The block is centred on the anchor.
    let expect = [-255.0, -45.0, 45.0, 255.0];
    for (y, e) in ys.iter().zip(expect) {
        assert!((y - e).abs() < 1e-9, "{ys:?}");
    }
    let turns: Vec<f64> = poses.iter().map(|p| p.rotation).collect();
    assert_eq!(turns, vec![0.0, 180.0, 0.0, 180.0]);
}

#[test]
fn tables_split_over_a_u_with_a_base_and_two_arms() {
    assert_eq!(u_split(2), None);
    assert_eq!(u_split(3), Some((1, 1)));
    assert_eq!(u_split(4), Some((1, 2)));
    assert_eq!(u_split(6), Some((2, 2)));
    assert_eq!(u_split(7), Some((3, 1)));
    assert_eq!(u_split(9), Some((3, 3)));
}

proptest! {
    /// A U of tables: the asked seats exactly, nothing overlapping, every seat facing its own
    /// table from outside the U (farther from the U's middle line than its table, or behind
    /// the base), every table's front outwards; moving and turning the input moves the output
    /// alike; the open end stays open (nothing stands ahead of the anchor).
    #[test]
    fn a_u_of_tables_keeps_its_seats_outside_facing_in(
        n in 3usize..10,
        per in 0usize..3,
        tw in 120.0f64..180.0,
        td in 60.0f64..90.0,
        sw in 40.0f64..60.0,
        m in motion(),
    ) {
        let spec = UTablesSpec::new(Size::new(tw, td), Size::new(sw, sw), vec![per; n]);
        let u = u_tables(DVec2::ZERO, 0.0, &spec).unwrap();
        prop_assert_eq!(u.tables.len(), n);
        prop_assert_eq!(u.seats.len(), n * per);
        let tables = footprints(&u.tables, spec.table);
        let seats = footprints(&u.seats, spec.seat);
        let all: Vec<Footprint> = tables.iter().chain(&seats).copied().collect();
        prop_assert!(least_gap(&all) >= -EPS, "members overlap");
        for (k, s) in seats.iter().enumerate() {
            let t = &tables[k / per.max(1)];
            prop_assert!(faces(s, t), "seat {k} does not face its table");
            // Outside: the seat stands on its table's front side.
            prop_assert!(t.to_local(s.center).y > t.half.y - EPS);
        }
        for t in &tables {
            // Every table's front points away from the U's inside.
            let arm = u_split(n).unwrap().0 as f64 * tw;
            let inside = DVec2::new(0.0, -arm / 2.0);
            prop_assert!(t.front.dot(t.center - inside) > 0.0);
            prop_assert!(t.center.y < 0.0);
        }
        for t in &tables {
            prop_assert!(t.corners().iter().all(|c| c.y <= EPS && c.y >= -u.depth - EPS));
        }
        for s in &seats {
            prop_assert!(s.center.y <= EPS && s.center.y >= -u.depth);
        }
        for a in &all {
            prop_assert!(a.corners().iter().all(|c| c.x.abs() <= u.width / 2.0 + EPS));
        }
        let moved = u_tables(m.point(DVec2::ZERO), m.theta, &spec).unwrap();
        assert_moved(&u.tables, &moved.tables, m)?;
        assert_moved(&u.seats, &moved.seats, m)?;
    }
}

#[test]
fn a_stool_behind_each_easel_stands_on_its_far_side_turned_the_same_way() {
    let easels = [
        Pose {
            center: DVec2::new(100.0, 100.0),
            rotation: 0.0,
        },
        Pose {
            center: DVec2::new(300.0, 100.0),
            rotation: 90.0,
        },
    ];
    let stools =
        one_behind_each(&easels, Size::new(70.0, 60.0), Size::new(40.0, 40.0), 30.0).unwrap();
    // 30 (half the easel) + 30 + 20 (half the stool) behind each easel's back.
    assert!((stools[0].center - DVec2::new(100.0, 20.0)).length() < 1e-9);
    assert!((stools[1].center - DVec2::new(220.0, 100.0)).length() < 1e-9);
    assert_eq!(stools[0].rotation, 0.0);
    assert_eq!(stools[1].rotation, 90.0);
    // Each stool faces its easel.
    for (s, e) in stools.iter().zip(&easels) {
        let fp = Footprint::new(e.center, 70.0, 60.0, e.rotation);
        assert!(disco_core::relations::facing(
            &Footprint::new(s.center, 40.0, 40.0, s.rotation),
            &fp
        ));
    }
}

#[test]
fn a_circle_about_a_point_is_even_facing_in_and_spaced() {
    let seat = Size::new(50.0, 52.0);
    let centre = DVec2::new(360.0, 300.0);
    let poses = circle_about(centre, 0.0, 10, seat, SEAT_SPACING_CM, 119.0).unwrap();
    assert_eq!(poses.len(), 10);
    let r0 = poses[0].center.distance(centre);
    assert!((r0 - 119.0).abs() < 1e-6 || r0 > 119.0);
    let fps = footprints(&poses, seat);
    for (i, p) in poses.iter().enumerate() {
        assert!((p.center.distance(centre) - r0).abs() < 1e-6, "one radius");
        let turn = normalize_degrees(p.rotation - facing_rotation(p.center, centre));
        assert!(turn.min(360.0 - turn) < 1e-6, "faces the centre");
        for b in &fps[i + 1..] {
            assert!(gap(&fps[i], b) >= SEAT_SPACING_CM - 1e-6, "spaced");
        }
    }
    // Few seats: the least radius is the one asked.
    let two = circle_about(centre, 0.0, 2, seat, SEAT_SPACING_CM, 150.0).unwrap();
    assert!((two[0].center.distance(centre) - 150.0).abs() < 1e-9);
}
