//! Layout quality, measured one way everywhere (docs/formats.md, "Metrics").
//!
//! - **Col**: % of pairs of solid objects (floor coverings aside) that collide, i.e. share more
//!   than [`COLLISION_AREA_CM2`](crate::geometry::COLLISION_AREA_CM2).
//! - **OOB**: mean over objects of the % of footprint area outside the room.
//! - **Constraint satisfaction**: % of the plan's constraints met, using [`crate::relations`].
//! - **Reach**: % of solid objects whose front (any side, for tables and seats) a 40 cm wide agent
//!   can reach from the largest free region of the floor.
//! - **Dropped**: % of assets not placed. **Displacement**: mean cm the PRT moved an object.

use std::collections::{BTreeMap, VecDeque};

use glam::DVec2;
use serde::{Deserialize, Serialize};

use crate::geometry::Footprint;
use crate::layout::{Layout, PlacedObject};
use crate::relations::{ConstraintKind, check_plan};
use crate::scene::Room;

/// Width of the agent that must reach objects (cm).
pub const AGENT_WIDTH_CM: f64 = 40.0;
/// How far beyond its own radius the agent can reach an edge (cm).
pub const REACH_MARGIN_CM: f64 = 10.0;
/// Cell size of the floor raster used for reach (cm).
pub const REACH_CELL_CM: f64 = 5.0;

/// Categories reachable from any side (words matched inside the category name).
const ANY_SIDE_WORDS: [&str; 9] = [
    "table", "chair", "stool", "sofa", "couch", "bench", "seat", "ottoman", "pouf",
];

/// Met and total counts of one kind of constraint.
#[derive(Debug, Clone, Copy, Default, PartialEq, Serialize, Deserialize)]
pub struct Tally {
    /// Constraints met.
    pub met: usize,
    /// Constraints checked.
    pub total: usize,
}

impl Tally {
    /// Percentage met (100 when there is nothing to meet).
    pub fn pct(&self) -> f64 {
        if self.total == 0 {
            100.0
        } else {
            100.0 * self.met as f64 / self.total as f64
        }
    }

    fn add(&mut self, met: bool) {
        self.total += 1;
        self.met += usize::from(met);
    }
}

/// Every metric of one layout.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Metrics {
    /// Assets in the scene (placed + dropped).
    pub assets: usize,
    /// Placed objects.
    pub placed: usize,
    /// Col: % of solid-object pairs that collide.
    pub collision_pct: f64,
    /// The colliding pairs, by name.
    pub colliding_pairs: Vec<(String, String)>,
    /// OOB: mean % of footprint area outside the room.
    pub oob_pct: f64,
    /// Constraint satisfaction over all constraints, %.
    pub constraint_pct: f64,
    /// Satisfaction of positional relations (near, side of, ...), %.
    pub positional_pct: f64,
    /// Satisfaction of facing constraints, %.
    pub facing_pct: f64,
    /// Satisfaction of against-wall constraints, %.
    pub wall_pct: f64,
    /// Met/total per constraint kind (`against_wall`, `facing`, each relation).
    pub by_kind: BTreeMap<String, Tally>,
    /// Constraints that are not met, as statements.
    pub unmet: Vec<String>,
    /// Reach: % of solid objects an agent can reach.
    pub reach_pct: f64,
    /// Objects the agent cannot reach.
    pub unreachable: Vec<String>,
    /// Dropped: % of assets not placed.
    pub dropped_pct: f64,
    /// Mean PRT displacement (cm), when the layout records a PRT run.
    pub mean_displacement_cm: Option<f64>,
}

/// Measures `layout`. Assets are the placed objects plus the dropped ones.
pub fn measure(layout: &Layout) -> Metrics {
    let solid: Vec<(&str, Footprint)> = layout
        .objects
        .iter()
        .filter(|o| !o.is_flat())
        .map(|o| (o.name.as_str(), o.footprint()))
        .collect();

    let mut colliding_pairs = Vec::new();
    for (i, (na, a)) in solid.iter().enumerate() {
        for (nb, b) in &solid[i + 1..] {
            if a.collides(b) {
                colliding_pairs.push((na.to_string(), nb.to_string()));
            }
        }
    }
    let pairs = solid.len() * solid.len().saturating_sub(1) / 2;
    let collision_pct = pct(colliding_pairs.len(), pairs);

    let oob_pct = if layout.objects.is_empty() {
        0.0
    } else {
        layout
            .objects
            .iter()
            .map(|o| {
                let f = o.footprint();
                100.0 * f.area_outside(&layout.room) / f.area()
            })
            .sum::<f64>()
            / layout.objects.len() as f64
    };

    let mut all = Tally::default();
    let (mut positional, mut facing, mut wall) =
        (Tally::default(), Tally::default(), Tally::default());
    let mut by_kind: BTreeMap<String, Tally> = BTreeMap::new();
    let mut unmet = Vec::new();
    for c in check_plan(layout) {
        all.add(c.met);
        by_kind
            .entry(c.kind.label().to_string())
            .or_default()
            .add(c.met);
        match c.kind {
            ConstraintKind::AgainstWall => wall.add(c.met),
            ConstraintKind::Relation { .. } => positional.add(c.met),
            ConstraintKind::Facing { .. } => facing.add(c.met),
        }
        if !c.met {
            unmet.push(c.to_string());
        }
    }

    let unreachable = unreachable_objects(&layout.room, &layout.objects, REACH_CELL_CM);
    let assets = layout.objects.len() + layout.dropped.len();
    Metrics {
        assets,
        placed: layout.objects.len(),
        collision_pct,
        colliding_pairs,
        oob_pct,
        constraint_pct: all.pct(),
        positional_pct: positional.pct(),
        facing_pct: facing.pct(),
        wall_pct: wall.pct(),
        by_kind,
        unmet,
        reach_pct: 100.0 - pct(unreachable.len(), solid.len()),
        unreachable,
        dropped_pct: pct(layout.dropped.len(), assets),
        mean_displacement_cm: layout.stats.prt.as_ref().map(|p| p.mean_displacement_cm),
    }
}

fn pct(part: usize, whole: usize) -> f64 {
    if whole == 0 {
        0.0
    } else {
        100.0 * part as f64 / whole as f64
    }
}

/// Distance from `p` to the footprint (0 inside).
fn distance_to(fp: &Footprint, p: DVec2) -> f64 {
    let l = fp.to_local(p);
    (l.abs() - fp.half).max(DVec2::ZERO).length()
}

/// Solid objects among `objects` whose accessible sides no cell of the largest free floor region
/// can reach, on a raster of `cell` cm (the metric uses [`REACH_CELL_CM`]; the rule designer a
/// coarser one to test candidate poses quickly).
pub fn unreachable_objects(room: &Room, objects: &[PlacedObject], cell: f64) -> Vec<String> {
    let raster = Raster::new(room, cell);
    let solid: Vec<(&str, Footprint, bool)> = objects
        .iter()
        .filter(|o| !o.is_flat())
        .map(|o| {
            let cat = o.category.to_lowercase();
            let any_side = ANY_SIDE_WORDS.iter().any(|w| cat.contains(w));
            (o.name.as_str(), o.footprint(), any_side)
        })
        .collect();
    let free = raster.free_cells(room, solid.iter().map(|(_, fp, _)| fp));
    let region = raster.largest_region(&free);
    solid
        .iter()
        .filter(|(_, fp, any_side)| !raster.reaches(&region, fp, *any_side))
        .map(|(n, _, _)| n.to_string())
        .collect()
}

/// Half the agent's width: how close its centre comes to walls and furniture.
const AGENT_RADIUS_CM: f64 = AGENT_WIDTH_CM / 2.0;

/// The floor as square cells of `cell` cm, `nx` by `ny`, numbered row by row from the origin.
struct Raster {
    cell: f64,
    nx: usize,
    ny: usize,
}

/// The cells of a raster's largest 4-connected free region.
struct Region {
    /// Each cell's region number, 0 for cells that are not free.
    label: Vec<u32>,
    /// The largest region's number; 0 when no cell is free.
    largest: u32,
}

impl Region {
    /// Whether cell `k` belongs to the largest region.
    fn contains(&self, k: usize) -> bool {
        self.largest != 0 && self.label[k] == self.largest
    }
}

impl Raster {
    /// The raster covering `room` with cells of `cell` cm (at least one each way).
    fn new(room: &Room, cell: f64) -> Self {
        Raster {
            cell,
            nx: (room.width / cell).ceil().max(1.0) as usize,
            ny: (room.depth / cell).ceil().max(1.0) as usize,
        }
    }

    /// The centre of cell (`i`, `j`).
    fn centre(&self, i: usize, j: usize) -> DVec2 {
        DVec2::new((i as f64 + 0.5) * self.cell, (j as f64 + 0.5) * self.cell)
    }

    /// The cells overlapping the box from `lo` to `hi`, clipped to the raster.
    fn cells_near(&self, lo: DVec2, hi: DVec2) -> impl Iterator<Item = (usize, usize)> {
        let (cell, nx, ny) = (self.cell, self.nx, self.ny);
        let i0 = ((lo.x / cell).floor().max(0.0) as usize).min(nx);
        let i1 = ((hi.x / cell).ceil().max(0.0) as usize).min(nx);
        let j0 = ((lo.y / cell).floor().max(0.0) as usize).min(ny);
        let j1 = ((hi.y / cell).ceil().max(0.0) as usize).min(ny);
        (i0..i1).flat_map(move |i| (j0..j1).map(move |j| (i, j)))
    }

    /// Free cells: where the agent's centre can stand, clear of the walls and of every footprint.
    fn free_cells<'f>(&self, room: &Room, solid: impl Iterator<Item = &'f Footprint>) -> Vec<bool> {
        let (r, nx) = (AGENT_RADIUS_CM, self.nx);
        let mut free = vec![true; nx * self.ny];
        for j in 0..self.ny {
            for i in 0..nx {
                let p = self.centre(i, j);
                free[j * nx + i] =
                    p.x >= r && p.y >= r && p.x <= room.width - r && p.y <= room.depth - r;
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

    /// The largest 4-connected region of `free` cells (the first found among equals).
    fn largest_region(&self, free: &[bool]) -> Region {
        let nx = self.nx;
        let mut label = vec![0u32; nx * self.ny];
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
            if size > best_size {
                (best_label, best_size) = (next, size);
            }
        }
        Region {
            label,
            largest: best_label,
        }
    }

    /// The 4-connected neighbours of cell `c` inside the raster: left, right, below, above.
    fn neighbours(&self, c: usize) -> impl Iterator<Item = usize> {
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

    /// Whether an agent in `region` can reach `fp` from the front, or from any side when
    /// `any_side`: some cell of the region lies outside that side within reach of it.
    fn reaches(&self, region: &Region, fp: &Footprint, any_side: bool) -> bool {
        let reach = AGENT_RADIUS_CM + REACH_MARGIN_CM;
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
            let lo = a.min(b) - DVec2::splat(reach);
            let hi = a.max(b) + DVec2::splat(reach);
            self.cells_near(lo, hi).any(|(i, j)| {
                if !region.contains(j * self.nx + i) {
                    return false;
                }
                let p = self.centre(i, j);
                (p - a).dot(normal) > 0.0 && point_segment_distance(p, a, b) <= reach
            })
        })
    }
}

fn point_segment_distance(p: DVec2, a: DVec2, b: DVec2) -> f64 {
    let ab = b - a;
    let t = ((p - a).dot(ab) / ab.length_squared().max(1e-12)).clamp(0.0, 1.0);
    p.distance(a + ab * t)
}

impl std::fmt::Display for Metrics {
    /// A short human-readable report, one metric per line.
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        writeln!(f, "objects placed      {} of {}", self.placed, self.assets)?;
        writeln!(
            f,
            "Col (collisions)    {:.1}%  ({} pairs)",
            self.collision_pct,
            self.colliding_pairs.len()
        )?;
        writeln!(f, "OOB (out of room)   {:.2}%", self.oob_pct)?;
        let total: usize = self.by_kind.values().map(|t| t.total).sum();
        writeln!(
            f,
            "constraints met     {:.1}%  ({total} checked)",
            self.constraint_pct
        )?;
        for (kind, t) in &self.by_kind {
            writeln!(f, "  {kind:<16}  {}/{}", t.met, t.total)?;
        }
        writeln!(f, "reach               {:.1}%", self.reach_pct)?;
        writeln!(f, "dropped             {:.1}%", self.dropped_pct)?;
        if let Some(d) = self.mean_displacement_cm {
            writeln!(f, "PRT displacement    {d:.1} cm mean")?;
        }
        for (a, b) in &self.colliding_pairs {
            writeln!(f, "collides: {a} / {b}")?;
        }
        for u in &self.unmet {
            writeln!(f, "unmet: {u}")?;
        }
        for u in &self.unreachable {
            writeln!(f, "unreachable: {u}")?;
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::layout::{Dropped, PlacedObject, Stats};
    use crate::plan::{ObjectConstraints, Plan, Relation, RelationSpec};
    use crate::scene::Room;

    fn obj(name: &str, cat: &str, size: [f64; 3], pos: [f64; 2], rot: f64) -> PlacedObject {
        PlacedObject {
            name: name.into(),
            category: cat.into(),
            size,
            position: pos,
            rotation: rot,
        }
    }

    fn layout(objects: Vec<PlacedObject>) -> Layout {
        Layout {
            id: "t".into(),
            room: Room {
                width: 400.0,
                depth: 300.0,
            },
            objects,
            dropped: vec![],
            plan: Plan::default(),
            stats: Stats::default(),
        }
    }

    #[test]
    fn collision_counts_pairs_and_ignores_rugs() {
        let l = layout(vec![
            obj("a", "cabinet", [100.0, 50.0, 90.0], [100.0, 100.0], 0.0),
            obj("b", "cabinet", [100.0, 50.0, 90.0], [150.0, 100.0], 0.0),
            obj("c", "cabinet", [100.0, 50.0, 90.0], [300.0, 250.0], 0.0),
            obj("rug", "rug", [200.0, 150.0, 1.0], [120.0, 100.0], 0.0),
        ]);
        let m = measure(&l);
        assert_eq!(m.colliding_pairs, vec![("a".to_string(), "b".to_string())]);
        assert!((m.collision_pct - 100.0 / 3.0).abs() < 1e-9);
    }

    #[test]
    fn oob_is_mean_percentage_outside() {
        let l = layout(vec![
            obj("in", "box", [100.0, 100.0, 50.0], [100.0, 100.0], 0.0),
            obj("half", "box", [100.0, 100.0, 50.0], [0.0, 100.0], 0.0),
        ]);
        assert!((measure(&l).oob_pct - 25.0).abs() < 1e-9);
    }

    #[test]
    fn constraints_are_tallied_by_kind() {
        let mut l = layout(vec![
            obj(
                "table",
                "dining table",
                [120.0, 80.0, 75.0],
                [200.0, 150.0],
                0.0,
            ),
            obj("chair", "chair", [45.0, 45.0, 90.0], [200.0, 85.0], 0.0),
            obj("cab", "cabinet", [100.0, 50.0, 90.0], [100.0, 270.0], 180.0),
        ]);
        l.plan.constraints.insert(
            "chair".into(),
            ObjectConstraints {
                against_wall: false,
                relations: vec![RelationSpec {
                    relation: Relation::Around,
                    target: "table".into(),
                }],
                facing: Some("table".into()),
            },
        );
        l.plan.constraints.insert(
            "cab".into(),
            ObjectConstraints {
                against_wall: true,
                relations: vec![RelationSpec {
                    relation: Relation::Near,
                    target: "table".into(),
                }],
                facing: None,
            },
        );
        let m = measure(&l);
        // cab's back is 5 cm off the top wall (y = 295 < 300) and it is far from the table.
        assert_eq!(m.by_kind["around"], Tally { met: 1, total: 1 });
        assert_eq!(m.by_kind["facing"], Tally { met: 1, total: 1 });
        assert_eq!(m.by_kind["against_wall"], Tally { met: 0, total: 1 });
        assert_eq!(m.by_kind["near"], Tally { met: 0, total: 1 });
        assert_eq!(m.constraint_pct, 50.0);
        assert_eq!(m.facing_pct, 100.0);
        assert_eq!(m.positional_pct, 50.0);
        assert_eq!(
            m.unmet,
            vec!["cab stands against a wall", "cab is near table"]
        );
    }

    #[test]
    fn reach_sees_a_walled_in_object() {
        // A wardrobe in the bottom-left corner facing up, boxed in by two cabinets that leave
        // only a 30 cm slot (narrower than the 40 cm agent) in front of it.
        let l = layout(vec![
            obj(
                "wardrobe",
                "wardrobe",
                [100.0, 60.0, 200.0],
                [50.0, 30.0],
                0.0,
            ),
            obj("wall-a", "cabinet", [150.0, 40.0, 90.0], [75.0, 150.0], 0.0),
            obj("wall-b", "cabinet", [40.0, 130.0, 90.0], [150.0, 65.0], 0.0),
            obj("desk", "desk", [120.0, 60.0, 75.0], [300.0, 30.0], 0.0),
        ]);
        let m = measure(&l);
        assert_eq!(m.unreachable, vec!["wardrobe"]);
        assert_eq!(m.reach_pct, 75.0);
    }

    #[test]
    fn reach_front_only_unless_table_or_seat() {
        // A desk facing the wall it stands against cannot be used; a table there can (other sides).
        let desk = layout(vec![obj(
            "desk",
            "desk",
            [120.0, 60.0, 75.0],
            [200.0, 30.0],
            180.0,
        )]);
        assert_eq!(measure(&desk).unreachable, vec!["desk"]);
        let table = layout(vec![obj(
            "t",
            "side table",
            [120.0, 60.0, 75.0],
            [200.0, 30.0],
            180.0,
        )]);
        assert!(measure(&table).unreachable.is_empty());
    }

    #[test]
    fn dropped_share() {
        let mut l = layout(vec![obj("a", "box", [10.0, 10.0, 10.0], [50.0, 50.0], 0.0)]);
        l.dropped.push(Dropped {
            name: "b".into(),
            reason: "too big".into(),
        });
        assert_eq!(measure(&l).dropped_pct, 50.0);
    }
}
