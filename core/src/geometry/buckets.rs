//! A uniform grid of buckets over the room: which boxes lie near a place, without looking at
//! every box. Big scenes ask "what collides with this?" and "what stands within so many cm?"
//! thousands of times per object; each answer looks only at the buckets its box covers.
//!
//! A box is filed in every bucket its (closed) extent touches. Boxes beyond the room are filed
//! in the border buckets, so a query clamped the same way still meets them: two boxes that
//! overlap or touch always share a bucket.

use glam::DVec2;

use super::Aabb;
use crate::room::Room;

/// Smallest bucket side (cm): about one piece of furniture.
const MIN_BUCKET_CM: f64 = 100.0;

/// Most buckets along one side of the room.
const MAX_BUCKETS_PER_SIDE: f64 = 256.0;

/// Boxes filed by the buckets of a uniform grid over the room. Each box keeps the index it was
/// inserted with (0, 1, 2, ...), which is how queries name it.
#[derive(Debug, Clone)]
pub struct BoxBuckets {
    side: f64,
    nx: usize,
    ny: usize,
    buckets: Vec<Vec<u32>>,
    len: usize,
}

impl BoxBuckets {
    /// An empty grid over `room`, with buckets of about one piece of furniture (larger in a
    /// huge room, so the grid stays small).
    pub fn new(room: &Room) -> Self {
        let side = MIN_BUCKET_CM.max(room.width.max(room.depth) / MAX_BUCKETS_PER_SIDE);
        let count = |len: f64| ((len / side).ceil().max(1.0) as usize).min(4096);
        let (nx, ny) = (count(room.width), count(room.depth));
        BoxBuckets {
            side,
            nx,
            ny,
            buckets: vec![Vec::new(); nx * ny],
            len: 0,
        }
    }

    /// A grid over `room` holding `boxes`, indexed by their position in the iterator.
    pub fn with_boxes(room: &Room, boxes: impl IntoIterator<Item = Aabb>) -> Self {
        let mut grid = BoxBuckets::new(room);
        for b in boxes {
            grid.insert(&b);
        }
        grid
    }

    /// How many boxes were inserted.
    pub fn len(&self) -> usize {
        self.len
    }

    /// Whether no box was inserted.
    pub fn is_empty(&self) -> bool {
        self.len == 0
    }

    /// Files `b` under the next index, which it returns.
    pub fn insert(&mut self, b: &Aabb) -> usize {
        let index = self.len;
        let (i0, i1, j0, j1) = self.range(b);
        for j in j0..=j1 {
            for i in i0..=i1 {
                self.buckets[j * self.nx + i].push(index as u32);
            }
        }
        self.len += 1;
        index
    }

    /// Takes back the box inserted last, which was `b` (the same box, so the same buckets): the
    /// undo of [`insert`](Self::insert), for a trial that is rolled back.
    pub fn remove_last(&mut self, b: &Aabb) {
        let Some(index) = self.len.checked_sub(1) else {
            return;
        };
        let (i0, i1, j0, j1) = self.range(b);
        for j in j0..=j1 {
            for i in i0..=i1 {
                let bucket = &mut self.buckets[j * self.nx + i];
                debug_assert_eq!(bucket.last(), Some(&(index as u32)), "not the last box");
                if bucket.last() == Some(&(index as u32)) {
                    bucket.pop();
                }
            }
        }
        self.len = index;
    }

    /// Whether `test` holds for some box filed in a bucket that `area` touches. Every box that
    /// overlaps or touches `area` is offered (some more than once, some farther away).
    pub fn any(&self, area: &Aabb, mut test: impl FnMut(usize) -> bool) -> bool {
        let (i0, i1, j0, j1) = self.range(area);
        (j0..=j1).any(|j| {
            (i0..=i1).any(|i| {
                self.buckets[j * self.nx + i]
                    .iter()
                    .any(|&k| test(k as usize))
            })
        })
    }

    /// Calls `visit` for each box filed in a bucket that `area` touches: every box that overlaps
    /// or touches `area`, some more than once, some farther away.
    pub fn for_each_near(&self, area: &Aabb, mut visit: impl FnMut(usize)) {
        self.any(area, |k| {
            visit(k);
            false
        });
    }

    /// The indices of the boxes near `area` (as [`for_each_near`](Self::for_each_near)), sorted,
    /// each once.
    pub fn near(&self, area: &Aabb) -> Vec<usize> {
        let mut out = Vec::new();
        self.for_each_near(area, |k| out.push(k));
        out.sort_unstable();
        out.dedup();
        out
    }

    /// The bucket columns and rows `b` touches, clamped to the grid (a NaN lands in the first).
    fn range(&self, b: &Aabb) -> (usize, usize, usize, usize) {
        let cell = |v: f64, n: usize| ((v / self.side).floor().max(0.0) as usize).min(n - 1);
        let (lo, hi): (DVec2, DVec2) = (b.min, b.max);
        let (i0, i1) = (cell(lo.x, self.nx), cell(hi.x, self.nx));
        let (j0, j1) = (cell(lo.y, self.ny), cell(hi.y, self.ny));
        (i0.min(i1), i1.max(i0), j0.min(j1), j1.max(j0))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn b(x0: f64, y0: f64, x1: f64, y1: f64) -> Aabb {
        Aabb {
            min: DVec2::new(x0, y0),
            max: DVec2::new(x1, y1),
        }
    }

    #[test]
    fn a_query_meets_exactly_the_boxes_a_full_scan_finds() {
        let room = Room::rect(1000.0, 700.0);
        let mut rng = fastrand::Rng::with_seed(3);
        let boxes: Vec<Aabb> = (0..300)
            .map(|_| {
                let (x, y) = (rng.f64() * 1200.0 - 100.0, rng.f64() * 900.0 - 100.0);
                b(x, y, x + rng.f64() * 150.0, y + rng.f64() * 150.0)
            })
            .collect();
        let grid = BoxBuckets::with_boxes(&room, boxes.iter().copied());
        assert_eq!(grid.len(), 300);
        for _ in 0..200 {
            let (x, y) = (rng.f64() * 1200.0 - 100.0, rng.f64() * 900.0 - 100.0);
            let q = b(x, y, x + rng.f64() * 300.0, y + rng.f64() * 300.0);
            let scan: Vec<usize> = (0..boxes.len())
                .filter(|&k| boxes[k].overlap_area(&q) > 0.0)
                .collect();
            let near = grid.near(&q);
            let found: Vec<usize> = near
                .into_iter()
                .filter(|&k| boxes[k].overlap_area(&q) > 0.0)
                .collect();
            assert_eq!(found, scan);
        }
    }

    #[test]
    fn removing_the_last_boxes_undoes_their_insertion() {
        let room = Room::rect(1000.0, 700.0);
        let kept = [b(0.0, 0.0, 150.0, 90.0), b(400.0, 300.0, 700.0, 650.0)];
        let mut grid = BoxBuckets::with_boxes(&room, kept);
        let added = [b(100.0, 50.0, 450.0, 350.0), b(-50.0, 600.0, 20.0, 800.0)];
        for a in &added {
            grid.insert(a);
        }
        for a in added.iter().rev() {
            grid.remove_last(a);
        }
        assert_eq!(grid.len(), 2);
        let everything = b(-1e9, -1e9, 1e9, 1e9);
        assert_eq!(grid.near(&everything), vec![0, 1]);
        assert_eq!(
            grid.insert(&added[0]),
            2,
            "the next box takes the freed index"
        );
        assert_eq!(grid.near(&added[0]), vec![0, 1, 2]);
    }

    #[test]
    fn boxes_outside_the_room_are_still_found() {
        let room = Room::rect(300.0, 300.0);
        let grid = BoxBuckets::with_boxes(&room, [b(-500.0, -500.0, -400.0, -400.0)]);
        assert_eq!(grid.near(&b(-450.0, -450.0, -440.0, -440.0)), vec![0]);
        assert!(grid.any(&b(-1e9, -1e9, 1e9, 1e9), |k| k == 0));
    }
}
