//! Reach: which solid objects an agent walking in can get to, on a raster of square cells.
//!
//! The agent walks in through the doors: the free regions it can stand in are those holding a
//! cell just inside some door (the entry cells). A room without doors is entered anywhere: there
//! the largest free region counts.
//!
//! [`unreachable_objects`] answers once for a whole layout. [`ReachMap`] keeps the answer while
//! objects are added one at a time, and says what adding one more would do, touching only the
//! cells near it: the free cells it covers, and any pocket of the walkable floor it cuts off. It
//! falls back to a fresh raster only when the walkable floor might change hands: without doors,
//! when the largest region shrank to no more than another region's size or split into pieces
//! that are all small; with doors, when the object covers an entry cell or cuts one off. Its
//! counts are always those [`unreachable_objects`] would give.

use std::collections::VecDeque;
use std::hash::{BuildHasherDefault, Hasher};

use glam::DVec2;

use super::{AGENT_WIDTH_CM, ANY_SIDE_WORDS, REACH_MARGIN_CM};
use crate::geometry::{Aabb, BoxBuckets, Footprint};
use crate::layout::PlacedObject;
use crate::scene::Room;

mod raster;
mod trial;
use raster::Raster;
use trial::Journal;

/// Sets and maps of cell numbers, hashed by one multiplication (the default hasher is built to
/// resist attacks, which cell numbers are not, and costs most of a reach test).
type HashSet<K> = std::collections::HashSet<K, BuildHasherDefault<CellHasher>>;
type HashMap<K, V> = std::collections::HashMap<K, V, BuildHasherDefault<CellHasher>>;

/// Fibonacci hashing of one `usize`.
#[derive(Default)]
struct CellHasher(u64);

impl Hasher for CellHasher {
    fn finish(&self) -> u64 {
        self.0
    }

    fn write(&mut self, bytes: &[u8]) {
        for &b in bytes {
            self.0 = (self.0.rotate_left(8) ^ u64::from(b)).wrapping_mul(0x9E37_79B9_7F4A_7C15);
        }
    }

    fn write_usize(&mut self, n: usize) {
        self.0 = (self.0 ^ n as u64).wrapping_mul(0x9E37_79B9_7F4A_7C15);
    }
}

/// Half the agent's width: how close its centre comes to walls and furniture.
pub(super) const AGENT_RADIUS_CM: f64 = AGENT_WIDTH_CM / 2.0;

/// How far from a side the agent reaches it: its radius and the margin.
pub(super) const REACH_CM: f64 = AGENT_RADIUS_CM + REACH_MARGIN_CM;

/// Solid objects among `objects` whose accessible sides no cell of the walkable floor can reach
/// (the regions entered through a door; the largest free region when the room has no door), on
/// a raster of `cell` cm (the metric uses [`REACH_CELL_CM`](super::REACH_CELL_CM); the rule
/// designer a coarser one to test candidate poses quickly).
pub fn unreachable_objects(room: &Room, objects: &[PlacedObject], cell: f64) -> Vec<String> {
    let raster = Raster::new(room, cell);
    let entries = raster.entry_cells(room);
    let solid: Vec<(&str, Footprint, bool)> = objects
        .iter()
        .filter(|o| blocks_floor(o))
        .map(|o| (o.name.as_str(), o.footprint(), any_side(o)))
        .collect();
    let free = raster.free_cells(room, solid.iter().map(|(_, fp, _)| fp));
    let region = raster.walkable_region(&free, &entries);
    solid
        .iter()
        .filter(|(_, fp, any_side)| !raster.reaches(|k| region.contains(k), fp, *any_side))
        .map(|(n, _, _)| n.to_string())
        .collect()
}

/// Whether `o` takes floor from the agent and is one of the objects it must reach: a solid object
/// standing on the floor (floor coverings lie underfoot; objects on others or high on walls
/// leave the floor free and are reached with their support).
fn blocks_floor(o: &PlacedObject) -> bool {
    !o.is_flat() && crate::geometry3d::reaches_floor(o)
}

/// Whether the object is reached from any side (tables, seats), not only its front.
fn any_side(o: &PlacedObject) -> bool {
    let cat = o.category.to_lowercase();
    ANY_SIDE_WORDS.iter().any(|w| cat.contains(w))
}

/// The reach of a layout that grows one solid object at a time (floor coverings are ignored).
#[derive(Debug, Clone)]
pub struct ReachMap {
    room: Room,
    raster: Raster,
    /// Where the agent's centre can stand.
    free: Vec<bool>,
    /// Each free cell's region, 0 for cells that are not free.
    label: Vec<u32>,
    /// Cells per region, by label (exact for the largest, at most that for the others).
    sizes: Vec<usize>,
    /// The largest region's label; 0 when no cell is free.
    largest: u32,
    /// By label, whether the region is walkable (never label 0).
    walkable: Vec<bool>,
    /// Where the agent enters: for each cell, whether it lies just inside a door (none in a
    /// room without doors, where the largest region is walkable).
    entry: Vec<bool>,
    /// Whether the room has a door, so `entry` decides what is walkable.
    has_entries: bool,
    /// The solid objects so far.
    objects: Vec<Reachee>,
    /// The box each object's reach is tested in, by object index.
    zones: BoxBuckets,
    /// How many objects the agent cannot reach.
    unreachable: usize,
    /// What the trial under way changed, to take it back (see [`ReachMap::begin_trial`]).
    journal: Option<Box<Journal>>,
}

/// One object of a [`ReachMap`].
#[derive(Debug, Clone)]
struct Reachee {
    object: PlacedObject,
    footprint: Footprint,
    any_side: bool,
    reached: bool,
}

/// What adding one object does to the walkable floor.
enum Change {
    /// Cells it covers, and the walkable cells it removes (covered or cut off), with the pockets
    /// cut off.
    Local {
        covered: Vec<usize>,
        removed: HashSet<usize>,
        pockets: Vec<Vec<usize>>,
    },
    /// The walkable floor may change hands: start again.
    Rebuild,
}

impl ReachMap {
    /// The reach of the solid `objects` in `room`, on a raster of `cell` cm.
    pub fn new(room: &Room, objects: &[PlacedObject], cell: f64) -> Self {
        let raster = Raster::new(room, cell);
        let entries = raster.entry_cells(room);
        let solid: Vec<&PlacedObject> = objects.iter().filter(|o| blocks_floor(o)).collect();
        let footprints: Vec<Footprint> = solid.iter().map(|o| o.footprint()).collect();
        let free = raster.free_cells(room, footprints.iter());
        let region = raster.walkable_region(&free, &entries);
        let mut entry = vec![false; free.len()];
        for &k in &entries {
            entry[k] = true;
        }
        let mut zones = BoxBuckets::new(room);
        let mut unreachable = 0;
        let objects = solid
            .iter()
            .zip(footprints)
            .map(|(o, footprint)| {
                let any_side = any_side(o);
                let reached = raster.reaches(|k| region.contains(k), &footprint, any_side);
                unreachable += usize::from(!reached);
                zones.insert(&reach_zone(&footprint));
                Reachee {
                    object: (*o).clone(),
                    footprint,
                    any_side,
                    reached,
                }
            })
            .collect();
        ReachMap {
            room: room.clone(),
            raster,
            free,
            label: region.label,
            sizes: region.sizes,
            largest: region.largest,
            walkable: region.walkable,
            entry,
            has_entries: !entries.is_empty(),
            objects,
            zones,
            unreachable,
            journal: None,
        }
    }

    /// How many of the objects the agent cannot reach.
    pub fn unreachable(&self) -> usize {
        self.unreachable
    }

    /// How many objects the agent could not reach if `obj` were added (itself included).
    pub fn unreachable_with(&self, obj: &PlacedObject) -> usize {
        if !blocks_floor(obj) {
            return self.unreachable;
        }
        let fp = obj.footprint();
        match self.change(&fp) {
            Change::Rebuild => {
                let mut all: Vec<PlacedObject> =
                    self.objects.iter().map(|r| r.object.clone()).collect();
                all.push(obj.clone());
                ReachMap::new(&self.room, &all, self.raster.cell).unreachable
            }
            Change::Local { removed, .. } => {
                let inside = |k: usize| self.in_walkable(k) && !removed.contains(&k);
                let lost = self
                    .affected(&removed)
                    .into_iter()
                    .filter(|&i| {
                        let r = &self.objects[i];
                        !self.raster.reaches(inside, &r.footprint, r.any_side)
                    })
                    .count();
                let own = !self.raster.reaches(inside, &fp, any_side(obj));
                self.unreachable + lost + usize::from(own)
            }
        }
    }

    /// Adds `obj` (a floor covering, or an object off the floor, changes nothing).
    pub fn add(&mut self, obj: &PlacedObject) {
        if !blocks_floor(obj) {
            return;
        }
        let fp = obj.footprint();
        let (covered, removed, pockets) = match self.change(&fp) {
            Change::Rebuild => {
                let mut all: Vec<PlacedObject> =
                    self.objects.iter().map(|r| r.object.clone()).collect();
                all.push(obj.clone());
                let fresh = ReachMap::new(&self.room, &all, self.raster.cell);
                self.replace_in_trial(fresh);
                return;
            }
            Change::Local {
                covered,
                removed,
                pockets,
            } => (covered, removed, pockets),
        };
        let affected = self.affected(&removed);
        for k in covered {
            let l = self.label[k] as usize;
            if let Some(j) = self.journal.as_mut() {
                j.cell(k, self.free[k], self.label[k]);
                j.size(l, self.sizes[l]);
            }
            self.free[k] = false;
            self.label[k] = 0;
            self.sizes[l] = self.sizes[l].saturating_sub(1);
        }
        for pocket in pockets {
            let l = self.sizes.len() as u32;
            let from = self.label[pocket[0]] as usize;
            if let Some(j) = self.journal.as_mut() {
                j.size(from, self.sizes[from]);
                for &k in &pocket {
                    j.cell(k, self.free[k], self.label[k]);
                }
            }
            self.sizes[from] -= pocket.len();
            self.sizes.push(pocket.len());
            self.walkable.push(false);
            for k in pocket {
                self.label[k] = l;
            }
        }
        for i in affected {
            let r = &self.objects[i];
            let reached = self
                .raster
                .reaches(|k| self.in_walkable(k), &r.footprint, r.any_side);
            if !reached {
                self.objects[i].reached = false;
                self.unreachable += 1;
                if let Some(j) = self.journal.as_mut() {
                    j.lost(i);
                }
            }
        }
        let any_side = any_side(obj);
        let reached = self.raster.reaches(|k| self.in_walkable(k), &fp, any_side);
        self.unreachable += usize::from(!reached);
        self.zones.insert(&reach_zone(&fp));
        self.objects.push(Reachee {
            object: obj.clone(),
            footprint: fp,
            any_side,
            reached,
        });
    }

    /// Whether cell `k` lies on the walkable floor.
    fn in_walkable(&self, k: usize) -> bool {
        self.walkable[self.label[k] as usize]
    }

    /// Objects reached now whose reach zone holds a `removed` cell: the only ones that may be
    /// reached no longer.
    fn affected(&self, removed: &HashSet<usize>) -> Vec<usize> {
        let mut out = Vec::new();
        for &k in removed {
            let c = self.raster.centre(k % self.raster.nx, k / self.raster.nx);
            let b = Aabb { min: c, max: c };
            self.zones.for_each_near(&b, |i| {
                if self.objects[i].reached && reach_zone(&self.objects[i].footprint).contains(c) {
                    out.push(i);
                }
            });
        }
        out.sort_unstable();
        out.dedup();
        out
    }

    /// What adding a solid object at `fp` does to the walkable floor.
    fn change(&self, fp: &Footprint) -> Change {
        let covered = self.raster.covered_cells(fp, &self.free);
        if covered.iter().any(|&k| self.entry[k]) {
            return Change::Rebuild;
        }
        let mut removed: HashSet<usize> = covered
            .iter()
            .copied()
            .filter(|&k| self.in_walkable(k))
            .collect();
        if removed.is_empty() {
            return Change::Local {
                covered,
                removed,
                pockets: Vec::new(),
            };
        }
        let open = |k: usize| self.in_walkable(k) && !removed.contains(&k);
        let seeds: Vec<usize> = removed
            .iter()
            .flat_map(|&k| self.raster.neighbours(k))
            .filter(|&k| open(k))
            .collect();
        let Some(pockets) = cut_off(&self.raster, &seeds, open) else {
            return Change::Rebuild;
        };
        if self.has_entries {
            // Walkable is what the doors open onto, whatever its size: only a pocket holding an
            // entry cell (one door's region cut off whole, or split from the rest) changes it.
            if pockets.iter().flatten().any(|&k| self.entry[k]) {
                return Change::Rebuild;
            }
            removed.extend(pockets.iter().flatten().copied());
            return Change::Local {
                covered,
                removed,
                pockets,
            };
        }
        let pocket_cells: usize = pockets.iter().map(Vec::len).sum();
        let main = self.sizes[self.largest as usize] - removed.len() - pocket_cells;
        let rival = self
            .sizes
            .iter()
            .enumerate()
            .filter(|&(l, _)| l != self.largest as usize && l != 0)
            .map(|(_, &s)| s)
            .chain(pockets.iter().map(Vec::len))
            .max()
            .unwrap_or(0);
        if main <= rival {
            return Change::Rebuild;
        }
        removed.extend(pockets.iter().flatten().copied());
        Change::Local {
            covered,
            removed,
            pockets,
        }
    }
}

/// The box an object's reach is tested in: the footprint's box widened by the reach, and a
/// centimetre more against round-off (a wider box only means a few more objects re-tested).
fn reach_zone(fp: &Footprint) -> Aabb {
    let b = fp.aabb();
    let margin = DVec2::splat(REACH_CM + 1.0);
    Aabb {
        min: b.min - margin,
        max: b.max + margin,
    }
}

trait Contains {
    fn contains(&self, p: DVec2) -> bool;
}

impl Contains for Aabb {
    fn contains(&self, p: DVec2) -> bool {
        p.x >= self.min.x && p.x <= self.max.x && p.y >= self.min.y && p.y <= self.max.y
    }
}

/// The pockets the `open` cells split into, seen from `seeds` (the open cells next to what was
/// removed): all but one piece, when exactly one piece could not be walked to its end. `None`
/// when every piece ended (the region may be small, or split in even parts): then only a fresh
/// count says which is largest. An empty list: the seeds all meet, nothing was cut off.
///
/// Each seed walks its piece breadth first, one cell per seed in turn, and walks that meet join;
/// so the work is about the size of the smaller pieces, not of the whole region.
fn cut_off(
    raster: &Raster,
    seeds: &[usize],
    open: impl Fn(usize) -> bool,
) -> Option<Vec<Vec<usize>>> {
    let n = seeds.len();
    let mut parent: Vec<usize> = (0..n).collect();
    let mut queues: Vec<VecDeque<usize>> = seeds.iter().map(|&s| VecDeque::from([s])).collect();
    let mut owner: HashMap<usize, usize> = HashMap::default();
    for (w, &s) in seeds.iter().enumerate() {
        if let Some(&other) = owner.get(&s) {
            union(&mut parent, w, other);
            queues[w].clear();
        } else {
            owner.insert(s, w);
        }
    }
    loop {
        // Pieces still walking, by root; a root counts once however many walks it joined.
        let mut walking: Vec<usize> = (0..n)
            .filter(|&w| !queues[w].is_empty())
            .map(|w| find(&mut parent, w))
            .collect();
        walking.sort_unstable();
        walking.dedup();
        let mut roots: Vec<usize> = (0..n).map(|w| find(&mut parent, w)).collect();
        roots.sort_unstable();
        roots.dedup();
        if roots.len() == 1 {
            return Some(Vec::new());
        }
        match walking.len() {
            0 => return None,
            1 => {
                let main = walking[0];
                let mut pockets: HashMap<usize, Vec<usize>> = HashMap::default();
                for (&cell, &w) in &owner {
                    let root = find(&mut parent, w);
                    if root != main {
                        pockets.entry(root).or_default().push(cell);
                    }
                }
                let mut pockets: Vec<Vec<usize>> = pockets.into_values().collect();
                for p in &mut pockets {
                    p.sort_unstable();
                }
                pockets.sort_unstable();
                return Some(pockets);
            }
            _ => {}
        }
        for (w, queue) in queues.iter_mut().enumerate() {
            let Some(c) = queue.pop_front() else {
                continue;
            };
            for k in raster.neighbours(c) {
                if !open(k) {
                    continue;
                }
                match owner.get(&k) {
                    Some(&other) => union(&mut parent, w, other),
                    None => {
                        owner.insert(k, w);
                        queue.push_back(k);
                    }
                }
            }
        }
    }
}

/// The root of `x`'s set.
fn find(parent: &mut [usize], mut x: usize) -> usize {
    while parent[x] != x {
        parent[x] = parent[parent[x]];
        x = parent[x];
    }
    x
}

/// Joins the sets of `a` and `b`.
fn union(parent: &mut [usize], a: usize, b: usize) {
    let (ra, rb) = (find(parent, a), find(parent, b));
    if ra != rb {
        parent[ra.max(rb)] = ra.min(rb);
    }
}

#[cfg(test)]
mod tests;
