//! What the floor holds while a group is designed, and the tests a candidate pose must pass
//! against it: fitting, keeping others' access clear, walling nothing in.

use std::collections::HashMap;

use glam::DVec2;

use super::brief::GroupBrief;
use crate::arrangement::RunSlot;
use crate::knowledge::Knowledge;
use disco_core::geometry::{Aabb, BoxBuckets, Footprint};
use disco_core::layout::PlacedObject;
use disco_core::metrics::ReachMap;
use disco_core::placement::Pose;
use disco_core::room::{KeepClear, distance_to_segment};
use disco_core::scene::{Asset, FLAT_HEIGHT_CM, Room};

/// Depth (cm) kept free in front of every object of an earlier group, so people can reach it.
const MIN_ACCESS_CM: f64 = 45.0;

/// Raster (cm) of the reach test run on candidate poses in a room of up to
/// [`FINE_REACH_MAX_AREA_CM2`]: the metric's own. A coarser one sees passages the metric does
/// not (with 10 cm cells a centre falls exactly in the middle of a 40 cm gap between pieces on
/// round coordinates, which a 5 cm raster never does), so pieces passed the test and were walled
/// in all the same.
const FINE_REACH_CELL_CM: f64 = 5.0;

/// Raster (cm) of the reach test in bigger halls, where a 5 cm raster costs four times the cells
/// for every test and most of a thousand-object scene's time.
const COARSE_REACH_CELL_CM: f64 = 10.0;

/// The floor area (cm², bounding box) up to which the designer tests reach on the metric's raster:
/// 200 m², more than any room of the benchmark sets (the largest is 140 m²).
const FINE_REACH_MAX_AREA_CM2: f64 = 200.0 * 10_000.0;

/// Whether the designer tests reach finely in `room`: on the metric's raster, over
/// [`FINE_REACH_TESTS`] candidates. Halls over [`FINE_REACH_MAX_AREA_CM2`] are tested coarsely.
fn fine_reach(room: &Room) -> bool {
    room.width * room.depth <= FINE_REACH_MAX_AREA_CM2
}

/// How many fitting candidates a placement tests for reach before settling for less, in a room
/// tested finely (12 left a floor lamp and a nightstand walling others in where a later candidate
/// kept them free).
const FINE_REACH_TESTS: usize = 48;

/// The same in a big hall, where every test costs more and a thousand objects each test.
const COARSE_REACH_TESTS: usize = 12;

/// The raster (cm) of the designer's reach test in `room`.
pub(super) fn reach_test_cell(room: &Room) -> f64 {
    if fine_reach(room) {
        FINE_REACH_CELL_CM
    } else {
        COARSE_REACH_CELL_CM
    }
}

/// How many fitting candidates a placement in `room` tests for reach.
pub(super) fn reach_tests(room: &Room) -> usize {
    if fine_reach(room) {
        FINE_REACH_TESTS
    } else {
        COARSE_REACH_TESTS
    }
}

/// What is on the floor so far. Footprints and zones are filed in buckets over the room, so a
/// test looks only at what stands near the pose it tests.
#[derive(Clone)]
pub(super) struct Floor<'a> {
    /// The room.
    pub(super) room: &'a Room,
    /// The zones the room's doors and windows keep clear (none in a room without openings).
    zones: Vec<KeepClear>,
    /// Footprints of the solid objects placed so far.
    pub(super) solid: Vec<Footprint>,
    /// The boxes of `solid`, by index.
    solid_near: BoxBuckets,
    /// Footprints of the floor coverings placed so far.
    flat: Vec<Footprint>,
    /// The boxes of `flat`, by index.
    flat_near: BoxBuckets,
    /// Zones people need in front of objects, which new objects should keep clear of.
    keep_clear: Vec<Aabb>,
    /// `keep_clear` by index.
    keep_clear_near: BoxBuckets,
    /// For each zone of `keep_clear`, whether its object belongs to a run the prompt names (an
    /// L, a galley, a one-wall run): pieces of a run may stand in each other's zones.
    keep_clear_of_run: Vec<bool>,
    /// The reach of every solid object placed so far.
    reach: ReachMap,
    /// How many solid objects an agent cannot reach now.
    pub(super) unreachable: usize,
    /// What the floor held when the trial under way began (see [`Floor::begin_trial`]).
    trial: TrialMark,
    /// Where a free-standing anchor of this group should go: its share of the room when several
    /// (tables in a hall) spread over the floor.
    pub(super) aim: DVec2,
    /// Objects the prompt wants in a corner.
    pub(super) in_corner: &'a [String],
    /// Objects the prompt wants by a window.
    pub(super) by_window: &'a [String],
    /// Objects the prompt wants in the middle of their wall.
    pub(super) centred_on_wall: &'a [String],
    /// The run each wall piece belongs to, when the prompt names one.
    runs: &'a HashMap<String, RunSlot>,
}

impl<'a> Floor<'a> {
    /// The floor a design of the brief's group starts from: what earlier groups placed, with the
    /// floor in front of each of their solid objects kept clear (their kind's clearance, and at
    /// least room for a person to reach them). `reach` is the reach of what they placed, on a
    /// raster of [`reach_test_cell`]; `keep_clear` the [`access_zone`] of each of their solid
    /// objects, in order.
    pub(super) fn for_group(
        brief: &GroupBrief<'a>,
        reach: ReachMap,
        keep_clear: Vec<Aabb>,
    ) -> Self {
        let (room, placed) = (brief.room, brief.placed);
        let solid: Vec<Footprint> = placed
            .iter()
            .filter(|o| !o.is_flat())
            .map(|o| o.footprint())
            .collect();
        let flat: Vec<Footprint> = placed
            .iter()
            .filter(|o| o.is_flat())
            .map(|o| o.footprint())
            .collect();
        let keep_clear_of_run: Vec<bool> = placed
            .iter()
            .filter(|o| !o.is_flat())
            .map(|o| brief.runs.contains_key(&o.name))
            .collect();
        Floor {
            room,
            zones: room.keep_clear(),
            solid_near: BoxBuckets::with_boxes(room, solid.iter().map(Footprint::aabb)),
            solid,
            flat_near: BoxBuckets::with_boxes(room, flat.iter().map(Footprint::aabb)),
            flat,
            keep_clear_near: BoxBuckets::with_boxes(room, keep_clear.iter().copied()),
            keep_clear,
            keep_clear_of_run,
            unreachable: reach.unreachable(),
            trial: TrialMark::default(),
            reach,
            aim: brief.aim,
            in_corner: brief.in_corner,
            by_window: brief.by_window,
            centred_on_wall: brief.centred_on_wall,
            runs: brief.runs,
        }
    }

    /// Whether an object `height` cm tall fits at `fp`: inside the room, out of every zone an
    /// opening keeps clear of objects that tall (a door's for anything but a floor covering, a
    /// window's for anything above its sill), and without colliding with what is there (other
    /// coverings for a floor covering, else solid objects).
    pub(super) fn fits(&self, fp: &Footprint, height: f64) -> bool {
        let (others, near) = match height <= FLAT_HEIGHT_CM {
            true => (&self.flat, &self.flat_near),
            false => (&self.solid, &self.solid_near),
        };
        fp.inside(self.room)
            && !self.zones.iter().any(|z| fp.intrudes(z, height))
            && !near.any(&fp.aabb(), |i| others[i].collides(fp))
    }

    /// Whether an object of `size` (width, depth, height) fits at `pose` (see [`Floor::fits`]).
    pub(super) fn fits_pose(&self, pose: &Pose, size: [f64; 3]) -> bool {
        let fp = Footprint::new(pose.center, size[0], size[1], pose.rotation);
        self.fits(&fp, size[2])
    }

    /// Whether the box `b` lies on the floor (within a square centimetre, for a rectangle).
    pub(super) fn holds_box(&self, b: &Aabb) -> bool {
        if self.room.is_rectangle() {
            return b.overlap_area(&self.room_box()) >= b.area() - 1.0;
        }
        let size = b.max - b.min;
        Footprint::new((b.min + b.max) / 2.0, size.x, size.y, 0.0).inside(self.room)
    }

    /// Whether some solid object's box overlaps `b` by more than `min_area` cm².
    pub(super) fn solid_overlaps(&self, b: &Aabb, min_area: f64) -> bool {
        self.solid_near
            .any(b, |i| self.solid[i].aabb().overlap_area(b) > min_area)
    }

    /// The least gap between `b` and the box of a solid object, when some object stands nearer
    /// than `within` cm; else `within` or more (infinity when nothing is that near).
    pub(super) fn nearest_solid_gap(&self, b: &Aabb, within: f64) -> f64 {
        let mut least = f64::INFINITY;
        let reach = DVec2::splat(within.max(0.0));
        let area = Aabb {
            min: b.min - reach,
            max: b.max + reach,
        };
        self.solid_near.for_each_near(&area, |i| {
            least = least.min(self.solid[i].aabb().gap(b));
        });
        least
    }

    /// Whether `fp`, the footprint of the object named `who`, stands in the zone kept clear in
    /// front of an earlier group's object; a piece of a run may stand in the zones of the run's
    /// other pieces, as the two legs of an L meet in their corner.
    pub(super) fn blocks_clearance(&self, fp: &Footprint, who: &str) -> bool {
        let in_run = self.runs.contains_key(who);
        let b = fp.aabb();
        self.keep_clear_near.any(&b, |i| {
            !(in_run && self.keep_clear_of_run[i]) && self.keep_clear[i].overlap_area(&b) > 1.0
        })
    }

    /// Adds an object of the group being placed. Its clearance zone is not added: the group's
    /// own dependents stand in it by design (chairs at a desk, a coffee table before a sofa).
    pub(super) fn add(&mut self, obj: PlacedObject) {
        let fp = obj.footprint();
        if obj.is_flat() {
            self.flat_near.insert(&fp.aabb());
            self.flat.push(fp);
        } else {
            self.solid_near.insert(&fp.aabb());
            self.solid.push(fp);
            self.reach.add(&obj);
            self.unreachable = self.reach.unreachable();
        }
    }

    /// Begins a trial: what is added from now on is taken back by [`Floor::roll_back`].
    pub(super) fn begin_trial(&mut self) {
        self.trial = TrialMark {
            solid: self.solid.len(),
            flat: self.flat.len(),
            unreachable: self.unreachable,
        };
        self.reach.begin_trial();
    }

    /// Takes back every object added since [`Floor::begin_trial`]: the floor is as it was then.
    pub(super) fn roll_back(&mut self) {
        while self.solid.len() > self.trial.solid {
            if let Some(fp) = self.solid.pop() {
                self.solid_near.remove_last(&fp.aabb());
            }
        }
        while self.flat.len() > self.trial.flat {
            if let Some(fp) = self.flat.pop() {
                self.flat_near.remove_last(&fp.aabb());
            }
        }
        self.unreachable = self.trial.unreachable;
        self.reach.roll_back();
    }

    /// The reach of what stands on the floor.
    pub(super) fn into_reach(self) -> ReachMap {
        self.reach
    }

    /// Whether `obj` can stand there without walling anything in, itself included.
    pub(super) fn keeps_reach(&self, obj: PlacedObject) -> bool {
        obj.is_flat() || self.reach.unreachable_with(&obj) <= self.unreachable
    }

    /// Free distance around `b`, to the walls and to every solid object, up to `cap`.
    pub(super) fn clearance_of(&self, b: &Aabb, cap: f64) -> f64 {
        let walls = if self.room.is_rectangle() {
            b.min
                .x
                .min(b.min.y)
                .min(self.room.width - b.max.x)
                .min(self.room.depth - b.max.y)
        } else {
            self.room
                .walls()
                .iter()
                .map(|e| box_to_segment(b, e.start, e.end))
                .fold(f64::INFINITY, f64::min)
        };
        walls.min(self.nearest_solid_gap(b, cap)).min(cap)
    }

    /// The room's floor as a box.
    pub(super) fn room_box(&self) -> Aabb {
        Aabb {
            min: DVec2::ZERO,
            max: DVec2::new(self.room.width, self.room.depth),
        }
    }
}

/// How much the floor held when a trial began.
#[derive(Clone, Copy, Default)]
struct TrialMark {
    /// Solid footprints.
    solid: usize,
    /// Floor coverings.
    flat: usize,
    /// Objects an agent could not reach.
    unreachable: usize,
}

/// The distance from the box `b` to the segment `a`-`b2` (0 when it crosses the box).
fn box_to_segment(b: &Aabb, a: DVec2, b2: DVec2) -> f64 {
    let corners = [
        b.min,
        DVec2::new(b.max.x, b.min.y),
        b.max,
        DVec2::new(b.min.x, b.max.y),
    ];
    let inside = |p: DVec2| p.cmpge(b.min).all() && p.cmple(b.max).all();
    if inside(a) || inside(b2) {
        return 0.0;
    }
    let to_box = |p: DVec2| p.clamp(b.min, b.max).distance(p);
    let from_corners = (0..4)
        .map(|i| {
            // A box side meeting the segment means they cross.
            let (c, d) = (corners[i], corners[(i + 1) % 4]);
            if segments_cross(a, b2, c, d) {
                0.0
            } else {
                distance_to_segment(c, a, b2)
            }
        })
        .fold(f64::INFINITY, f64::min);
    from_corners.min(to_box(a)).min(to_box(b2))
}

/// Whether the segments `a`-`b` and `c`-`d` cross.
fn segments_cross(a: DVec2, b: DVec2, c: DVec2, d: DVec2) -> bool {
    let side = |p: DVec2, q: DVec2, r: DVec2| (q - p).perp_dot(r - p);
    let (d1, d2) = (side(c, d, a), side(c, d, b));
    let (d3, d4) = (side(a, b, c), side(a, b, d));
    (d1 * d2 <= 0.0) && (d3 * d4 <= 0.0)
}

/// The zone in front of an earlier group's solid object that people need to reach it: as wide
/// as the object, as deep as its kind's clearance but at least [`MIN_ACCESS_CM`].
///
/// A piece with a staff side (a counter) keeps both sides clear: the staff's and the
/// customers'.
pub(super) fn access_zone(knowledge: &Knowledge, o: &PlacedObject) -> Aabb {
    let kind = knowledge.kind_of(&Asset::new(&o.name, &o.category, o.size));
    let clearance = kind.clearance.max(MIN_ACCESS_CM);
    let fp = o.footprint();
    if kind.staff > 0.0 {
        // The staff side and the other side both: the larger of the two depths each way.
        let side = clearance.max(kind.staff);
        let depth = 2.0 * side + 2.0 * fp.half.y;
        return Footprint::new(fp.center, fp.half.x * 2.0, depth, fp.rotation).aabb();
    }
    Footprint::new(
        fp.front_center() + fp.front * (clearance / 2.0),
        fp.half.x * 2.0,
        clearance,
        fp.rotation,
    )
    .aabb()
}
