//! One geometric predicate per arrangement pattern. Each returns `Ok(())` when the pieces
//! stand in the pattern, or the first reason they do not, in words.
//!
//! "Local" coordinates are in the focal piece's frame: x along its width (to its right), y out
//! of its front, so for a board on a wall, y is the distance into the room.

use glam::DVec2;

use crate::geometry::{Aabb, Footprint, Wall};
use crate::layout::{Layout, PlacedObject};
use crate::scene::Room;

/// The outcome of a predicate: `Err` says what is wrong.
pub type Check = Result<(), String>;

/// Pieces whose positions along a run differ by at most this much are in the same row (cm).
pub const ROW_TOLERANCE_CM: f64 = 15.0;
/// The widest gap (cm) between neighbours of one run.
pub const RUN_GAP_CM: f64 = 30.0;
/// The farthest (cm) an L's runs may end from their shared corner.
pub const L_CORNER_REACH_CM: f64 = 100.0;
/// The widest gap (cm) between the two pieces of a work-zone pair.
pub const ADJACENT_GAP_CM: f64 = 10.0;
/// The farthest (cm) a seat or member may stand from the piece it is at.
pub const AT_GAP_CM: f64 = 60.0;
/// How far (cm) mirrored pieces may miss the mirror image of each other.
pub const MIRROR_TOLERANCE_CM: f64 = 10.0;
/// Objects at most this tall (cm) do not block a view.
pub const LOW_CM: f64 = 60.0;

fn fp(o: &PlacedObject) -> Footprint {
    o.footprint()
}

/// `p` in the frame of `f`: x to its right, y out of its front.
fn local(f: &Footprint, p: DVec2) -> DVec2 {
    let d = p - f.center;
    DVec2::new(d.dot(f.right), d.dot(f.front))
}

/// Whether `o`'s front points within `max_deg` of `p`.
fn faces_point(o: &Footprint, p: DVec2, max_deg: f64) -> bool {
    let to = (p - o.center).normalize_or_zero();
    to != DVec2::ZERO && o.front.dot(to) >= max_deg.to_radians().cos() - 1e-9
}

/// The wall `o` stands against, or why it stands against none.
fn wall_of(room: &Room, o: &PlacedObject) -> Result<Wall, String> {
    fp(o)
        .against_wall(room)
        .ok_or_else(|| format!("{} is not against a wall", o.name))
}

/// Every object stands against a wall.
pub fn all_on_walls(room: &Room, objects: &[&PlacedObject]) -> Check {
    objects
        .iter()
        .try_for_each(|o| wall_of(room, o).map(|_| ()))
}

/// Whether two walls meet at a corner.
fn adjacent(a: Wall, b: Wall) -> bool {
    a != b && a.inward_normal().dot(b.inward_normal()).abs() < 0.5
}

/// The interval an object covers along a wall (x for bottom/top, y for left/right).
fn along(w: Wall, b: &Aabb) -> (f64, f64) {
    if w.inward_normal().y != 0.0 {
        (b.min.x, b.max.x)
    } else {
        (b.min.y, b.max.y)
    }
}

/// The pieces on wall `w` form one run: sorted along it, no gap wider than [`RUN_GAP_CM`].
fn one_run(w: Wall, objects: &[&PlacedObject]) -> Check {
    let mut spans: Vec<(f64, f64)> = objects.iter().map(|o| along(w, &fp(o).aabb())).collect();
    spans.sort_by(|a, b| a.0.total_cmp(&b.0));
    for pair in spans.windows(2) {
        let gap = pair[1].0 - pair[0].1;
        if gap > RUN_GAP_CM {
            return Err(format!(
                "a {gap:.0} cm gap in the run on the {} wall",
                w.name()
            ));
        }
    }
    Ok(())
}

/// The pieces by the wall they stand against (every piece must stand against one).
fn by_wall<'a>(
    room: &Room,
    objects: &[&'a PlacedObject],
) -> Result<Vec<(Wall, Vec<&'a PlacedObject>)>, String> {
    let mut out: Vec<(Wall, Vec<&PlacedObject>)> = Vec::new();
    for o in objects {
        let w = wall_of(room, o)?;
        match out.iter_mut().find(|(x, _)| *x == w) {
            Some((_, v)) => v.push(o),
            None => out.push((w, vec![o])),
        }
    }
    Ok(out)
}

/// Rows facing a focal piece: all members out in front of it, squared to it, in at least two rows
/// of two or more; every seat turned squarely towards the focal wall.
pub fn rows(focal: &PlacedObject, members: &[&PlacedObject], seats: &[&PlacedObject]) -> Check {
    let f = fp(focal);
    let mut depths: Vec<f64> = Vec::new();
    for m in members {
        let mf = fp(m);
        let l = local(&f, mf.center);
        if l.y <= 0.0 {
            return Err(format!("{} is behind {}", m.name, focal.name));
        }
        if mf.front.dot(f.front).abs() < 0.99 {
            return Err(format!("{} is not squared to {}", m.name, focal.name));
        }
        depths.push(l.y);
    }
    depths.sort_by(f64::total_cmp);
    let mut rows: Vec<usize> = Vec::new();
    let mut last = f64::NEG_INFINITY;
    for y in depths {
        if y - last > ROW_TOLERANCE_CM {
            rows.push(0);
        }
        *rows.last_mut().expect("a row was opened") += 1;
        last = y;
    }
    if rows.iter().filter(|&&n| n >= 2).count() < 2 {
        return Err(format!("rows of {rows:?}: not two rows of two or more"));
    }
    for s in seats {
        if fp(s).front.dot(-f.front) < 0.99 {
            return Err(format!("{} does not face {}", s.name, focal.name));
        }
    }
    Ok(())
}

/// A U open to the focal piece: the members in three runs (left, right, and across the far end)
/// around an open space at least 150 cm wide, nothing inside it; each seat faces the focal piece
/// or the open space.
pub fn u_shape(focal: &PlacedObject, members: &[&PlacedObject], seats: &[&PlacedObject]) -> Check {
    const TOL: f64 = 40.0;
    let f = fp(focal);
    let pts: Vec<DVec2> = members.iter().map(|m| local(&f, fp(m).center)).collect();
    if pts.iter().any(|p| p.y <= 0.0) {
        return Err(format!("a member stands behind {}", focal.name));
    }
    let xmin = pts.iter().map(|p| p.x).fold(f64::INFINITY, f64::min);
    let xmax = pts.iter().map(|p| p.x).fold(f64::NEG_INFINITY, f64::max);
    let ymax = pts.iter().map(|p| p.y).fold(f64::NEG_INFINITY, f64::max);
    let (mut left, mut right, mut base) = (0, 0, 0);
    for (p, m) in pts.iter().zip(members) {
        let (l, r, b) = (p.x - xmin <= TOL, xmax - p.x <= TOL, ymax - p.y <= TOL);
        if !(l || r || b) {
            return Err(format!("{} stands inside the U", m.name));
        }
        left += usize::from(l);
        right += usize::from(r);
        base += usize::from(b && !l && !r);
    }
    if left < 2 || right < 2 || base < 1 || xmax - xmin < 150.0 {
        return Err(format!(
            "runs left {left}, right {right}, across {base}, {:.0} cm apart: not a U",
            xmax - xmin
        ));
    }
    let inside = f.center + f.right * (xmin + xmax) / 2.0 + f.front * ymax / 2.0;
    for s in seats {
        let sf = fp(s);
        if !faces_point(&sf, f.center, 75.0) && !faces_point(&sf, inside, 60.0) {
            return Err(format!("{} faces neither {} nor the U", s.name, focal.name));
        }
    }
    Ok(())
}

/// An L: every member against one of two adjacent walls, each wall's pieces one run that ends
/// within [`L_CORNER_REACH_CM`] of their shared corner.
pub fn l_shape(room: &Room, members: &[&PlacedObject]) -> Check {
    let walls = by_wall(room, members)?;
    let [(a, run_a), (b, run_b)] = walls.as_slice() else {
        return Err(format!("pieces on {} walls, not two", walls.len()));
    };
    if !adjacent(*a, *b) {
        return Err("the two runs are on opposite walls".into());
    }
    let corner = corner_of(room, *a, *b);
    for (w, run) in [(a, run_a), (b, run_b)] {
        one_run(*w, run)?;
        let reach = run
            .iter()
            .map(|o| {
                let (lo, hi) = along(*w, &fp(o).aabb());
                let c = if w.inward_normal().y != 0.0 {
                    corner.x
                } else {
                    corner.y
                };
                (lo - c).abs().min((hi - c).abs())
            })
            .fold(f64::INFINITY, f64::min);
        if reach > L_CORNER_REACH_CM {
            return Err(format!(
                "the {} run ends {reach:.0} cm from the corner",
                w.name()
            ));
        }
    }
    Ok(())
}

/// Where walls `a` and `b` (adjacent) meet: the vertex they share.
fn corner_of(_room: &Room, a: Wall, b: Wall) -> DVec2 {
    if a.edge.end.distance(b.edge.start) < 1e-9 {
        a.edge.end
    } else {
        a.edge.start
    }
}

/// An island: the focal piece off every wall by at least 60 cm, each seat within
/// [`AT_GAP_CM`] of it and facing it.
pub fn island(room: &Room, focal: &PlacedObject, seats: &[&PlacedObject]) -> Check {
    let margin = wall_margins(room, &fp(focal).aabb())
        .into_iter()
        .fold(f64::INFINITY, f64::min);
    if margin < 60.0 {
        return Err(format!("{} is {margin:.0} cm from a wall", focal.name));
    }
    seats_at(focal, seats)
}

/// Each seat stands within [`AT_GAP_CM`] of `focal` with its front pointing at it.
fn seats_at(focal: &PlacedObject, seats: &[&PlacedObject]) -> Check {
    let f = fp(focal);
    for s in seats {
        let sf = fp(s);
        if sf.gap(&f) > AT_GAP_CM {
            return Err(format!(
                "{} is {:.0} cm from {}",
                s.name,
                sf.gap(&f),
                focal.name
            ));
        }
        if sf.front_ray_hit(&f).is_none() {
            return Err(format!("{} does not face {}", s.name, focal.name));
        }
    }
    Ok(())
}

/// Distances of a box from the left, right, bottom and top walls.
fn wall_margins(room: &Room, b: &Aabb) -> [f64; 4] {
    [b.min.x, room.width - b.max.x, b.min.y, room.depth - b.max.y]
}

/// A galley: every member against one of two opposite walls, two or more on each, the runs
/// overlapping along the aisle.
pub fn galley(room: &Room, members: &[&PlacedObject]) -> Check {
    let walls = by_wall(room, members)?;
    let [(a, run_a), (b, run_b)] = walls.as_slice() else {
        return Err(format!("pieces on {} walls, not two", walls.len()));
    };
    if adjacent(*a, *b) || run_a.len() < 2 || run_b.len() < 2 {
        return Err(format!(
            "{} on the {} wall and {} on the {} wall: not two facing runs",
            run_a.len(),
            a.name(),
            run_b.len(),
            b.name()
        ));
    }
    let span = |w: Wall, run: &[&PlacedObject]| {
        run.iter()
            .map(|o| along(w, &fp(o).aabb()))
            .fold((f64::INFINITY, f64::NEG_INFINITY), |s, x| {
                (s.0.min(x.0), s.1.max(x.1))
            })
    };
    let (sa, sb) = (span(*a, run_a), span(*b, run_b));
    if sa.1.min(sb.1) <= sa.0.max(sb.0) {
        return Err("the two runs do not face each other".into());
    }
    Ok(())
}

/// A one-wall run: every member against the same wall, no wide gap between neighbours.
pub fn one_wall(room: &Room, members: &[&PlacedObject]) -> Check {
    let walls = by_wall(room, members)?;
    let [(w, run)] = walls.as_slice() else {
        return Err(format!("pieces on {} walls, not one", walls.len()));
    };
    one_run(*w, run)
}

/// A work zone: the pair (sink and dishwasher) side by side on one wall, at most
/// [`ADJACENT_GAP_CM`] apart; with a triangle (fridge, stove, sink), no leg over 300 cm and the
/// three under 800 cm in all.
pub fn work_zone(room: &Room, pair: &[&PlacedObject], triangle: &[&PlacedObject]) -> Check {
    let [a, b] = pair else {
        return Err("a work zone needs a pair".into());
    };
    if wall_of(room, a)? != wall_of(room, b)? {
        return Err(format!("{} and {} are on different walls", a.name, b.name));
    }
    let gap = fp(a).gap(&fp(b));
    if gap > ADJACENT_GAP_CM {
        return Err(format!("{} and {} are {gap:.0} cm apart", a.name, b.name));
    }
    if let [x, y, z] = triangle {
        let d = |p: &PlacedObject, q: &PlacedObject| fp(p).center.distance(fp(q).center);
        let legs = [d(x, y), d(y, z), d(z, x)];
        if legs.iter().any(|&l| l > 300.0) || legs.iter().sum::<f64>() > 800.0 {
            return Err(format!("work triangle legs {legs:.0?} cm"));
        }
    }
    Ok(())
}

/// Around a centre piece: each member within [`AT_GAP_CM`] of it, facing it, and (two or more
/// members) on at least two of its sides.
pub fn around(focal: &PlacedObject, members: &[&PlacedObject]) -> Check {
    seats_at(focal, members)?;
    let f = fp(focal);
    let mut sides: Vec<(i32, i32)> = members
        .iter()
        .map(|m| {
            let l = local(&f, fp(m).center);
            let (x, y) = (l.x / f.half.x.max(1.0), l.y / f.half.y.max(1.0));
            if x.abs() >= y.abs() {
                (x.signum() as i32, 0)
            } else {
                (0, y.signum() as i32)
            }
        })
        .collect();
    sides.sort();
    sides.dedup();
    if members.len() >= 2 && sides.len() < 2 {
        return Err(format!("every member on one side of {}", focal.name));
    }
    Ok(())
}

/// In a corner: the piece's footprint within `within` cm of two adjacent walls.
pub fn corner(room: &Room, focal: &PlacedObject, within: f64) -> Check {
    let [l, r, b, t] = wall_margins(room, &fp(focal).aabb());
    let near = |m: f64| m <= within;
    if (near(l) || near(r)) && (near(b) || near(t)) {
        Ok(())
    } else {
        Err(format!(
            "{} is {:.0} / {:.0} cm from the nearest side and end walls",
            focal.name,
            l.min(r),
            b.min(t)
        ))
    }
}

/// Centred: the piece against no wall, at least 20 cm off each, its centre within a fifth of
/// the room's width and depth of the room's centre.
pub fn centred(room: &Room, focal: &PlacedObject) -> Check {
    let f = fp(focal);
    let margin = wall_margins(room, &f.aabb())
        .into_iter()
        .fold(f64::INFINITY, f64::min);
    let off = f.center - DVec2::new(room.width, room.depth) / 2.0;
    if margin < 20.0 || off.x.abs() > room.width / 5.0 || off.y.abs() > room.depth / 5.0 {
        return Err(format!(
            "{} is {:.0} x {:.0} cm off the centre, {margin:.0} cm from a wall",
            focal.name, off.x, off.y
        ));
    }
    Ok(())
}

/// A symmetric pair: the two pieces on opposite sides of the focal piece's axis, each the
/// mirror image of the other within [`MIRROR_TOLERANCE_CM`].
pub fn symmetric_pair(focal: &PlacedObject, pair: &[&PlacedObject]) -> Check {
    let [a, b] = pair else {
        return Err("a symmetric pair needs two pieces".into());
    };
    let f = fp(focal);
    let (la, lb) = (local(&f, fp(a).center), local(&f, fp(b).center));
    if la.x * lb.x >= 0.0 {
        return Err(format!(
            "{} and {} are on one side of {}",
            a.name, b.name, focal.name
        ));
    }
    if (la.x + lb.x).abs() > MIRROR_TOLERANCE_CM || (la.y - lb.y).abs() > MIRROR_TOLERANCE_CM {
        return Err(format!(
            "{} and {} are not mirrored ({la:.0} vs {lb:.0})",
            a.name, b.name
        ));
    }
    Ok(())
}

/// A conversation set: every seat's front points at the focus (within 30 degrees of its
/// centre, or its front ray meets it); two or more seats include a pair turned to each other;
/// with a screen, nothing taller than [`LOW_CM`] stands between any seat and the screen.
pub fn conversation(
    layout: &Layout,
    focus: &PlacedObject,
    seats: &[&PlacedObject],
    screen: Option<&PlacedObject>,
) -> Check {
    let f = fp(focus);
    for s in seats {
        let sf = fp(s);
        if !faces_point(&sf, f.center, 30.0) && sf.front_ray_hit(&f).is_none() {
            return Err(format!("{} does not face {}", s.name, focus.name));
        }
    }
    let fronts: Vec<DVec2> = seats.iter().map(|s| fp(s).front).collect();
    let opposed = fronts
        .iter()
        .enumerate()
        .any(|(i, a)| fronts[i + 1..].iter().any(|b| a.dot(*b) <= -0.5));
    if seats.len() >= 2 && !opposed {
        return Err("no two seats face each other".into());
    }
    if let Some(screen) = screen {
        for s in seats {
            if let Some(b) = blocker(layout, s, screen) {
                return Err(format!(
                    "{b} blocks the view from {} to {}",
                    s.name, screen.name
                ));
            }
        }
    }
    Ok(())
}

/// The first object taller than [`LOW_CM`] on the line from `from`'s front to `to`'s centre.
fn blocker<'a>(layout: &'a Layout, from: &PlacedObject, to: &PlacedObject) -> Option<&'a str> {
    let (a, b) = (fp(from).front_center(), fp(to).center);
    let steps = (a.distance(b) / 5.0).ceil().max(1.0) as usize;
    layout
        .objects
        .iter()
        .filter(|o| o.name != from.name && o.name != to.name && o.size[2] > LOW_CM)
        .find(|o| {
            let of = fp(o);
            (0..=steps).any(|i| {
                let p = local(&of, a.lerp(b, i as f64 / steps as f64));
                p.x.abs() < of.half.x && p.y.abs() < of.half.y
            })
        })
        .map(|o| o.name.as_str())
}
