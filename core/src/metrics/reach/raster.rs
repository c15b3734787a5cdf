//! The floor of a reach test as square cells: which cells are free for the agent's centre, their
//! 4-connected regions and the walkable ones among them, where the agent enters, and whether the
//! cells of a region reach an object's side.

use std::collections::VecDeque;

use glam::DVec2;

use super::{AGENT_RADIUS_CM, REACH_CM};
use crate::geometry::Footprint;
use crate::room::{distance_to_segment, point_in_polygon};
use crate::scene::Room;

/// Distance from `p` to the footprint (0 inside).
fn distance_to(fp: &Footprint, p: DVec2) -> f64 {
    let l = fp.to_local(p);
    (l.abs() - fp.half).max(DVec2::ZERO).length()
}

/// The floor as square cells of `cell` cm, `nx` by `ny`, numbered row by row from the origin.
#[derive(Debug, Clone, Copy)]
pub(super) struct Raster {
    pub(super) cell: f64,
    pub(super) nx: usize,
    pub(super) ny: usize,
}

/// The cells of a raster's 4-connected free regions.
pub(super) struct Region {
    /// Each cell's region number, 0 for cells that are not free.
    pub(super) label: Vec<u32>,
    /// Cells per region, by number (0: none).
    pub(super) sizes: Vec<usize>,
    /// The largest region's number (the first found among equals); 0 when no cell is free.
    pub(super) largest: u32,
    /// By number, whether the region is walkable (see [`Raster::walkable_region`]).
    pub(super) walkable: Vec<bool>,
}

impl Region {
    /// Whether cell `k` belongs to a walkable region.
    pub(super) fn contains(&self, k: usize) -> bool {
        self.walkable[self.label[k] as usize]
    }
}

impl Raster {
    /// The raster covering `room` with cells of `cell` cm (at least one each way).
    pub(super) fn new(room: &Room, cell: f64) -> Self {
        Raster {
            cell,
            nx: (room.width / cell).ceil().max(1.0) as usize,
            ny: (room.depth / cell).ceil().max(1.0) as usize,
        }
    }

    /// The centre of cell (`i`, `j`).
    pub(super) fn centre(&self, i: usize, j: usize) -> DVec2 {
        DVec2::new((i as f64 + 0.5) * self.cell, (j as f64 + 0.5) * self.cell)
    }

    /// The cells overlapping the box from `lo` to `hi`, clipped to the raster.
    pub(super) fn cells_near(&self, lo: DVec2, hi: DVec2) -> impl Iterator<Item = (usize, usize)> {
        let (cell, nx, ny) = (self.cell, self.nx, self.ny);
        let i0 = ((lo.x / cell).floor().max(0.0) as usize).min(nx);
        let i1 = ((hi.x / cell).ceil().max(0.0) as usize).min(nx);
        let j0 = ((lo.y / cell).floor().max(0.0) as usize).min(ny);
        let j1 = ((hi.y / cell).ceil().max(0.0) as usize).min(ny);
        (i0..i1).flat_map(move |i| (j0..j1).map(move |j| (i, j)))
    }

    /// The cells, free in `free`, where the agent's centre would touch `fp`.
    pub(super) fn covered_cells(&self, fp: &Footprint, free: &[bool]) -> Vec<usize> {
        let (r, b) = (AGENT_RADIUS_CM, fp.aabb());
        self.cells_near(b.min - DVec2::splat(r), b.max + DVec2::splat(r))
            .filter(|&(i, j)| distance_to(fp, self.centre(i, j)) < r)
            .map(|(i, j)| j * self.nx + i)
            .filter(|&k| free[k])
            .collect()
    }

    /// Free cells: where the agent's centre can stand, inside the outline, clear of the walls and
    /// of every footprint.
    pub(super) fn free_cells<'f>(
        &self,
        room: &Room,
        solid: impl Iterator<Item = &'f Footprint>,
    ) -> Vec<bool> {
        let (r, nx) = (AGENT_RADIUS_CM, self.nx);
        let mut free = vec![true; nx * self.ny];
        let walls = room.walls();
        let outline = room.outline();
        for j in 0..self.ny {
            for i in 0..nx {
                let p = self.centre(i, j);
                free[j * nx + i] = match room.polygon {
                    None => p.x >= r && p.y >= r && p.x <= room.width - r && p.y <= room.depth - r,
                    Some(_) => {
                        point_in_polygon(p, &outline)
                            && walls
                                .iter()
                                .all(|e| distance_to_segment(p, e.start, e.end) >= r)
                    }
                };
            }
        }
        for fp in solid {
            let b = fp.aabb();
            for (i, j) in self.cells_near(b.min - DVec2::splat(r), b.max + DVec2::splat(r)) {
                if distance_to(fp, self.centre(i, j)) < r {
                    free[j * nx + i] = false;
                }
            }
        }
        free
    }

    /// The 4-connected regions of `free` cells, and the largest (the first found among equals).
    pub(super) fn largest_region(&self, free: &[bool]) -> Region {
        let nx = self.nx;
        let mut label = vec![0u32; nx * self.ny];
        let mut sizes = vec![0usize];
        let (mut best_label, mut best_size, mut next) = (0u32, 0usize, 0u32);
        for start in 0..nx * self.ny {
            if !free[start] || label[start] != 0 {
                continue;
            }
            next += 1;
            label[start] = next;
            let mut size = 0;
            let mut queue = VecDeque::from([start]);
            while let Some(c) = queue.pop_front() {
                size += 1;
                for n in self.neighbours(c) {
                    if free[n] && label[n] == 0 {
                        label[n] = next;
                        queue.push_back(n);
                    }
                }
            }
            sizes.push(size);
            if size > best_size {
                (best_label, best_size) = (next, size);
            }
        }
        let mut walkable = vec![false; sizes.len()];
        walkable[best_label as usize] = best_label != 0;
        Region {
            label,
            sizes,
            largest: best_label,
            walkable,
        }
    }

    /// The free regions with the walkable ones marked: those holding a free `entries` cell, or
    /// the largest when there are no entry cells (a room without doors).
    pub(super) fn walkable_region(&self, free: &[bool], entries: &[usize]) -> Region {
        let mut region = self.largest_region(free);
        if entries.is_empty() {
            return region;
        }
        region.walkable.fill(false);
        for &k in entries {
            let l = region.label[k] as usize;
            region.walkable[l] = l != 0;
        }
        region
    }

    /// The cells where an agent walking in through a door first stands: within the door's span,
    /// their centres at most the agent's radius and two cells from the wall (the free ones
    /// among them are at least the radius away). None when the room has no door.
    pub(super) fn entry_cells(&self, room: &Room) -> Vec<usize> {
        let walls = room.walls();
        let depth = AGENT_RADIUS_CM + 2.0 * self.cell;
        let mut out = Vec::new();
        for door in &room.doors {
            let Some(edge) = walls.get(door.wall) else {
                continue;
            };
            let (lo, hi) = (door.at - door.width / 2.0, door.at + door.width / 2.0);
            let n = edge.inward_normal() * depth;
            let corners = [edge.point(lo), edge.point(hi)];
            let min = corners[0]
                .min(corners[1])
                .min(corners[0] + n)
                .min(corners[1] + n);
            let max = corners[0]
                .max(corners[1])
                .max(corners[0] + n)
                .max(corners[1] + n);
            for (i, j) in self.cells_near(min, max) {
                let p = self.centre(i, j);
                let (along, offset) = (edge.along(p), edge.offset(p));
                if along >= lo && along <= hi && offset > 0.0 && offset <= depth {
                    out.push(j * self.nx + i);
                }
            }
        }
        out.sort_unstable();
        out.dedup();
        out
    }

    /// The 4-connected neighbours of cell `c` inside the raster: left, right, below, above.
    pub(super) fn neighbours(&self, c: usize) -> impl Iterator<Item = usize> {
        let (nx, ny) = (self.nx, self.ny);
        let (i, j) = (c % nx, c / nx);
        [
            (i > 0).then(|| c - 1),
            (i + 1 < nx).then(|| c + 1),
            (j > 0).then(|| c - nx),
            (j + 1 < ny).then(|| c + nx),
        ]
        .into_iter()
        .flatten()
    }

    /// Whether an agent on the cells `in_region` says can reach `fp` from the front, or from
    /// any side when `any_side`: some such cell lies outside that side within reach of it.
    pub(super) fn reaches(
        &self,
        in_region: impl Fn(usize) -> bool,
        fp: &Footprint,
        any_side: bool,
    ) -> bool {
        let c = fp.corners();
        // Sides as (start, end, outward normal): front first.
        let sides = [
            (c[3], c[2], fp.front),
            (c[0], c[1], -fp.front),
            (c[1], c[2], fp.right),
            (c[0], c[3], -fp.right),
        ];
        let n_sides = if any_side { 4 } else { 1 };
        sides[..n_sides].iter().any(|&(a, b, normal)| {
            let lo = a.min(b) - DVec2::splat(REACH_CM);
            let hi = a.max(b) + DVec2::splat(REACH_CM);
            self.cells_near(lo, hi).any(|(i, j)| {
                if !in_region(j * self.nx + i) {
                    return false;
                }
                let p = self.centre(i, j);
                (p - a).dot(normal) > 0.0 && point_segment_distance(p, a, b) <= REACH_CM
            })
        })
    }
}

/// Distance from `p` to the segment `a`-`b`.
fn point_segment_distance(p: DVec2, a: DVec2, b: DVec2) -> f64 {
    let ab = b - a;
    let t = ((p - a).dot(ab) / ab.length_squared().max(1e-12)).clamp(0.0, 1.0);
    p.distance(a + ab * t)
}
