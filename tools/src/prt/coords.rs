//! What the PRT searches over: the footprints settled so far, and the candidate coordinates of
//! one axis (the grid, the room's edges, the object's own position and every position flush
//! against a settled object), produced lazily outward from the object's position.
//!
//! A big layout has thousands of settled objects, hence thousands of flush positions per axis,
//! but the search rarely looks more than a few candidates away: the edges of the settled boxes
//! are kept sorted, so the candidates near a position come in order without sorting them all,
//! and collisions are tested only against the settled boxes nearby.

use std::cell::RefCell;
use std::cmp::Ordering;
use std::collections::btree_set;
use std::collections::{BTreeSet, HashMap};
use std::iter::{Peekable, Rev};
use std::ops::Bound;

use disco_core::geometry::{Aabb, BoxBuckets, Footprint};
use disco_core::room::KeepClear;
use disco_core::scene::Room;

/// An `f64` ordered by [`f64::total_cmp`], for sorted sets of coordinates.
#[derive(Debug, Clone, Copy)]
struct Coord(f64);

impl PartialEq for Coord {
    fn eq(&self, other: &Self) -> bool {
        self.0.total_cmp(&other.0) == Ordering::Equal
    }
}

impl Eq for Coord {}

impl PartialOrd for Coord {
    fn partial_cmp(&self, other: &Self) -> Option<Ordering> {
        Some(self.cmp(other))
    }
}

impl Ord for Coord {
    fn cmp(&self, other: &Self) -> Ordering {
        self.0.total_cmp(&other.0)
    }
}

/// The low and high edges of the settled boxes along one axis, sorted.
#[derive(Default)]
struct Edges {
    low: BTreeSet<Coord>,
    high: BTreeSet<Coord>,
}

/// A wall stretch searched for one shape: the wall's index, the stretch's index on it, the
/// shape's half width and depth (as bits, exactly), and the height when zones bind by height.
pub(super) type WallShape = (usize, usize, u64, u64, u64);

/// What the room forbids beyond its bounding box: leaving a polygon's outline, and entering the
/// zones its doors and windows keep clear.
struct RoomLimits {
    room: Room,
    zones: Vec<KeepClear>,
}

/// The footprints settled so far, with their boxes filed by place and their edges sorted.
pub(super) struct Settled {
    footprints: Vec<Footprint>,
    aabbs: Vec<Aabb>,
    near: BoxBuckets,
    x: Edges,
    y: Edges,
    /// Wall stretches found full: for a shape, how many footprints were settled when every
    /// candidate on the wall (grid points, both ends, flush positions against those
    /// footprints) was seen to collide. Settling more only adds collisions, so afterwards only
    /// an object's own position and the flush positions against later footprints can be free.
    full_walls: RefCell<HashMap<WallShape, usize>>,
    /// `None` for a plain rectangle without openings, whose bounding box is all there is.
    limits: Option<RoomLimits>,
}

impl Settled {
    /// Nothing settled yet in `room`.
    pub(super) fn new(room: &Room) -> Self {
        let limits = (!room.is_rectangle() || room.has_openings()).then(|| RoomLimits {
            room: room.clone(),
            zones: room.keep_clear(),
        });
        let (mut x, mut y) = (Edges::default(), Edges::default());
        if let Some(l) = &limits {
            // The outline's corners and the zones' corners are edges to stand flush against,
            // as a settled box's are.
            let corners = l.zones.iter().flat_map(|z| z.corners);
            for p in l.room.outline().into_iter().chain(corners) {
                x.low.insert(Coord(p.x));
                x.high.insert(Coord(p.x));
                y.low.insert(Coord(p.y));
                y.high.insert(Coord(p.y));
            }
        }
        Settled {
            footprints: Vec::new(),
            aabbs: Vec::new(),
            near: BoxBuckets::new(room),
            x,
            y,
            full_walls: RefCell::new(HashMap::new()),
            limits,
        }
    }

    /// Whether an object `height` cm tall may stand at `cand` as far as the room goes: inside its
    /// outline, out of every zone that binds it. (The bounding box is the caller's.)
    pub(super) fn fits_room(&self, cand: &Footprint, height: f64) -> bool {
        let Some(l) = &self.limits else {
            return true;
        };
        (l.room.is_rectangle() || cand.inside(&l.room))
            && l.zones.iter().all(|z| !cand.intrudes(z, height))
    }

    /// The height to file wall stretches under: zones bind by height when the room has any.
    pub(super) fn height_key(&self, height: f64) -> u64 {
        match &self.limits {
            Some(l) if !l.zones.is_empty() => height.to_bits(),
            _ => 0,
        }
    }

    /// The settled footprints, in the order they were settled.
    pub(super) fn footprints(&self) -> &[Footprint] {
        &self.footprints
    }

    /// How many footprints are settled.
    pub(super) fn len(&self) -> usize {
        self.footprints.len()
    }

    /// Since how many settled footprints the wall stretch of `shape` is known to be full.
    pub(super) fn full_since(&self, shape: WallShape) -> Option<usize> {
        self.full_walls.borrow().get(&shape).copied()
    }

    /// Records that every candidate for `shape` on its wall collides with the footprints
    /// settled now.
    pub(super) fn mark_full(&self, shape: WallShape) {
        self.full_walls.borrow_mut().insert(shape, self.len());
    }

    /// The flush positions along x (`along_x`) or y for an object of half extent `half` against
    /// the footprints settled from index `since` on.
    pub(super) fn contacts_since(
        &self,
        since: usize,
        along_x: bool,
        half: f64,
    ) -> impl Iterator<Item = f64> + '_ {
        self.aabbs[since..].iter().flat_map(move |b| match along_x {
            true => [b.min.x - half, b.max.x + half],
            false => [b.min.y - half, b.max.y + half],
        })
    }

    /// Settles `fp`.
    pub(super) fn push(&mut self, fp: Footprint) {
        let b = fp.aabb();
        self.near.insert(&b);
        self.x.low.insert(Coord(b.min.x));
        self.x.high.insert(Coord(b.max.x));
        self.y.low.insert(Coord(b.min.y));
        self.y.high.insert(Coord(b.max.y));
        self.aabbs.push(b);
        self.footprints.push(fp);
    }

    /// Whether `cand` collides with a settled footprint.
    pub(super) fn collides(&self, cand: &Footprint) -> bool {
        self.first_collision(cand).is_some()
    }

    /// A settled footprint `cand` collides with, by index, if any.
    pub(super) fn first_collision(&self, cand: &Footprint) -> Option<usize> {
        let b = cand.aabb();
        let mut hit = None;
        self.near.any(&b, |i| {
            let meets = self.collides_with(i, cand, &b);
            if meets {
                hit = Some(i);
            }
            meets
        });
        hit
    }

    /// Whether `cand` (whose box is `b`) collides with settled footprint `i`.
    pub(super) fn collides_with(&self, i: usize, cand: &Footprint, b: &Aabb) -> bool {
        self.aabbs[i].interiors_meet(b) && self.footprints[i].collides(cand)
    }

    /// The candidate coordinates along x for an object of half extent `half` whose centre may
    /// range over `[lo, hi]`, split at `own` (its clamped position).
    pub(super) fn line_x(&self, lo: f64, hi: f64, own: f64, step: f64, half: f64) -> Line<'_> {
        Line::new(Axis {
            lo,
            hi,
            own,
            step,
            half,
            edges: &self.x,
        })
    }

    /// As [`line_x`](Self::line_x), along y.
    pub(super) fn line_y(&self, lo: f64, hi: f64, own: f64, step: f64, half: f64) -> Line<'_> {
        Line::new(Axis {
            lo,
            hi,
            own,
            step,
            half,
            edges: &self.y,
        })
    }
}

/// Rounds to 1/10000 cm so that sums such as `a + b - c` land on one value.
pub(super) fn tidy(v: f64) -> f64 {
    (v * 10_000.0).round() / 10_000.0
}

/// What one axis's candidates are made of.
struct Axis<'s> {
    lo: f64,
    hi: f64,
    own: f64,
    step: f64,
    half: f64,
    edges: &'s Edges,
}

/// A stream of raw coordinates, in one direction.
type Stream<'s> = Peekable<Box<dyn Iterator<Item = f64> + 's>>;

/// The candidate coordinates of one axis as one sorted list without repeats: the grid points
/// in `[lo, hi]`, `lo`, `hi`, `own`, and the flush positions (a settled box's low edge minus
/// the half extent, its high edge plus it) that lie in `[lo, hi]`; each rounded by `tidy` and
/// clamped to `[lo, hi]`. It is read by index relative to `own`'s: 0 is the first value made from
/// a raw coordinate at or above `own`, -1 the one below it; values are made as they are read.
pub(super) struct Line<'s> {
    lo: f64,
    hi: f64,
    /// Values at indices 0, 1, 2, ...
    above: Vec<f64>,
    /// Values at indices -1, -2, ...
    below: Vec<f64>,
    up: Vec<Stream<'s>>,
    down: Vec<Stream<'s>>,
}

impl<'s> Line<'s> {
    fn new(a: Axis<'s>) -> Self {
        let (lo, hi, own, step, half) = (a.lo, a.hi, a.own, a.step, a.half);
        let first = (lo / step).ceil() as i64;
        let last = (hi / step).floor() as i64;
        // Grid indices around `own`, a little wide: the exact split is by value below.
        let mid = ((own / step).floor() as i64).clamp(first, last.max(first));
        let grid_up = (mid - 1).max(first)..=last;
        let grid_down = (first..=(mid + 1).min(last)).rev();
        let extras = {
            let mut e = [lo, hi, own];
            e.sort_by(f64::total_cmp);
            e
        };
        // Edges whose flush position could be at or above `own`, and below it (a margin wide).
        let from = |shift: f64| Bound::Included(Coord(own - shift - 1.0));
        let until = |shift: f64| Bound::Included(Coord(own - shift + 1.0));
        let low_up = a.edges.low.range((from(-half), Bound::Unbounded));
        let high_up = a.edges.high.range((from(half), Bound::Unbounded));
        let low_down: Rev<btree_set::Range<'s, Coord>> =
            a.edges.low.range((Bound::Unbounded, until(-half))).rev();
        let high_down = a.edges.high.range((Bound::Unbounded, until(half))).rev();
        let at_or_above = move |v: &f64| *v >= own;
        let below = move |v: &f64| *v < own;
        let up: Vec<Stream<'s>> = vec![
            stream(grid_up.map(move |k| k as f64 * step).filter(at_or_above)),
            stream(extras.into_iter().filter(at_or_above)),
            stream(
                low_up
                    .map(move |c| c.0 - half)
                    .filter(at_or_above)
                    .take_while(move |v| *v <= hi),
            ),
            stream(
                high_up
                    .map(move |c| c.0 + half)
                    .filter(at_or_above)
                    .take_while(move |v| *v <= hi),
            ),
        ];
        let down: Vec<Stream<'s>> = vec![
            stream(grid_down.map(move |k| k as f64 * step).filter(below)),
            stream(extras.into_iter().rev().filter(below)),
            stream(
                low_down
                    .map(move |c| c.0 - half)
                    .filter(below)
                    .take_while(move |v| *v >= lo),
            ),
            stream(
                high_down
                    .map(move |c| c.0 + half)
                    .filter(below)
                    .take_while(move |v| *v >= lo),
            ),
        ];
        Line {
            lo,
            hi,
            above: Vec::new(),
            below: Vec::new(),
            up,
            down,
        }
    }

    /// The value at index `i` (relative to `own`'s), if the list reaches that far.
    pub(super) fn get(&mut self, i: i64) -> Option<f64> {
        if i >= 0 {
            let i = i as usize;
            while self.above.len() <= i {
                let v = self.next_up()?;
                self.above.push(v);
            }
            Some(self.above[i])
        } else {
            let i = (-i - 1) as usize;
            while self.below.len() <= i {
                let v = self.next_down()?;
                self.below.push(v);
            }
            Some(self.below[i])
        }
    }

    /// The index of the value nearest `x` (the lower of two as near), as the sorted list's
    /// `partition_point` would find it; `None` for an empty list.
    pub(super) fn nearest(&mut self, x: f64) -> Option<i64> {
        let p = self.partition(x);
        match (self.get(p - 1), self.get(p)) {
            (Some(a), Some(b)) if (x - a).abs() <= (b - x).abs() => Some(p - 1),
            (Some(_), None) => Some(p - 1),
            (_, Some(_)) => Some(p),
            (None, None) => None,
        }
    }

    /// The index of the first value not below `x` (one past the end when all are below), as
    /// the sorted list's `partition_point` would find it.
    pub(super) fn partition(&mut self, x: f64) -> i64 {
        let mut p = 0i64;
        while self.get(p - 1).is_some_and(|v| v >= x) {
            p -= 1;
        }
        while self.get(p).is_some_and(|v| v < x) {
            p += 1;
        }
        p
    }

    /// The next value above the ones made so far.
    fn next_up(&mut self) -> Option<f64> {
        let last = self.above.last().copied();
        loop {
            let raw = pop_extreme(&mut self.up, |a, b| a < b)?;
            let v = tidy(raw).clamp(self.lo, self.hi);
            if last != Some(v) {
                return Some(v);
            }
        }
    }

    /// The next value below the ones made so far.
    fn next_down(&mut self) -> Option<f64> {
        let first_above = self.get(0);
        let last = self.below.last().copied().or(first_above);
        loop {
            let raw = pop_extreme(&mut self.down, |a, b| a > b)?;
            let v = tidy(raw).clamp(self.lo, self.hi);
            if last != Some(v) {
                return Some(v);
            }
        }
    }
}

/// A boxed, peekable stream.
fn stream<'s>(it: impl Iterator<Item = f64> + 's) -> Stream<'s> {
    let boxed: Box<dyn Iterator<Item = f64> + 's> = Box::new(it);
    boxed.peekable()
}

/// Takes the first value of the stream whose next value comes first by `before`.
fn pop_extreme(streams: &mut [Stream<'_>], before: impl Fn(f64, f64) -> bool) -> Option<f64> {
    let mut best: Option<(usize, f64)> = None;
    for (i, s) in streams.iter_mut().enumerate() {
        if let Some(&v) = s.peek()
            && best.is_none_or(|(_, b)| before(v, b))
        {
            best = Some((i, v));
        }
    }
    let (i, _) = best?;
    streams[i].next()
}

#[cfg(test)]
mod tests {
    use super::*;
    use glam::DVec2;

    /// The list the PRT used to build in full: every candidate, sorted, without repeats.
    fn full_list(lo: f64, hi: f64, own: f64, step: f64, contacts: &[f64]) -> Vec<f64> {
        let mut v = Vec::new();
        let first = (lo / step).ceil() as i64;
        let last = (hi / step).floor() as i64;
        v.extend((first..=last).map(|k| k as f64 * step));
        v.extend([lo, hi, own]);
        v.extend(contacts.iter().copied().filter(|c| *c >= lo && *c <= hi));
        let mut v: Vec<f64> = v.into_iter().map(|x| tidy(x).clamp(lo, hi)).collect();
        v.sort_by(f64::total_cmp);
        v.dedup();
        v
    }

    #[test]
    fn the_lazy_line_reads_as_the_full_sorted_list() {
        let room = Room::rect(900.0, 600.0);
        let mut rng = fastrand::Rng::with_seed(11);
        for _ in 0..40 {
            let mut settled = Settled::new(&room);
            for _ in 0..rng.usize(0..60) {
                let c = DVec2::new(rng.f64() * 900.0, rng.f64() * 600.0);
                let rot = 90.0 * rng.usize(0..4) as f64;
                settled.push(Footprint::new(c, 20.0 + rng.f64() * 99.7, 30.0, rot));
            }
            let half = 10.0 + rng.f64() * 50.0;
            let (lo, hi) = (half, 900.0 - half);
            let own = (rng.f64() * 1000.0 - 50.0).clamp(lo, hi);
            let step = [5.0, 7.3, 100.0][rng.usize(0..3)];
            let contacts: Vec<f64> = settled
                .aabbs
                .iter()
                .flat_map(|b| [b.min.x - half, b.max.x + half])
                .collect();
            let full = full_list(lo, hi, own, step, &contacts);
            let mut line = settled.line_x(lo, hi, own, step, half);
            let at = full.partition_point(|v| *v < own) as i64;
            let zero = full
                .iter()
                .position(|v| *v == line.get(0).unwrap())
                .unwrap() as i64;
            for (k, v) in full.iter().enumerate() {
                assert_eq!(line.get(k as i64 - zero), Some(*v), "index {k}");
            }
            assert_eq!(line.get(full.len() as i64 - zero), None);
            assert_eq!(line.get(-zero - 1), None);
            let nearest = line.nearest(own).unwrap() + zero;
            assert!((nearest - at).abs() <= 1);
            assert_eq!(
                full[nearest as usize],
                *full
                    .iter()
                    .min_by(|a, b| (*a - own).abs().total_cmp(&(*b - own).abs()))
                    .unwrap()
            );
        }
    }
}
