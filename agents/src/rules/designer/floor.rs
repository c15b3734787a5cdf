//! What the floor holds while a group is designed, and the tests a candidate pose must pass
//! against it: fitting, keeping others' access clear, walling nothing in.

use glam::DVec2;

use super::group::GroupBrief;
use crate::knowledge::Knowledge;
use disco_core::geometry::{Aabb, Footprint};
use disco_core::layout::PlacedObject;
use disco_core::metrics::unreachable_objects;
use disco_core::scene::{Asset, Room};

/// Depth (cm) kept free in front of every object of an earlier group, so people can reach it.
const MIN_ACCESS_CM: f64 = 45.0;

/// Raster (cm) of the reach test run on candidate poses: coarser than the metric's, for speed.
const REACH_TEST_CELL_CM: f64 = 10.0;

/// What is on the floor so far.
pub(super) struct Floor<'a> {
    /// The room.
    pub(super) room: &'a Room,
    /// Footprints of the solid objects placed so far.
    pub(super) solid: Vec<Footprint>,
    /// Footprints of the floor coverings placed so far.
    flat: Vec<Footprint>,
    /// Zones people need in front of objects, which new objects should keep clear of.
    keep_clear: Vec<Aabb>,
    /// Every solid object placed so far, for the reach test.
    objects: Vec<PlacedObject>,
    /// How many of `objects` an agent cannot reach now.
    pub(super) unreachable: usize,
    /// Where a free-standing anchor of this group should go: its share of the room when several
    /// (tables in a hall) spread over the floor.
    pub(super) aim: DVec2,
    /// Objects the prompt wants in a corner.
    pub(super) in_corner: &'a [String],
}

impl<'a> Floor<'a> {
    /// The floor a design of the brief's group starts from: what earlier groups placed, with the
    /// floor in front of each of their solid objects kept clear (their kind's clearance, and at
    /// least room for a person to reach them).
    pub(super) fn for_group(knowledge: &Knowledge, brief: &GroupBrief<'a>) -> Self {
        let (room, placed) = (brief.room, brief.placed);
        let solid: Vec<PlacedObject> = placed.iter().filter(|o| !o.is_flat()).cloned().collect();
        let keep_clear = solid.iter().map(|o| access_zone(knowledge, o)).collect();
        Floor {
            room,
            solid: solid.iter().map(|o| o.footprint()).collect(),
            flat: placed
                .iter()
                .filter(|o| o.is_flat())
                .map(|o| o.footprint())
                .collect(),
            keep_clear,
            unreachable: unreachable_objects(room, &solid, REACH_TEST_CELL_CM).len(),
            objects: solid,
            aim: brief.aim,
            in_corner: brief.in_corner,
        }
    }

    /// Whether `fp` stands inside the room without colliding with what is there: with other
    /// coverings when `flat`, else with solid objects.
    pub(super) fn fits(&self, fp: &Footprint, flat: bool) -> bool {
        let others = if flat { &self.flat } else { &self.solid };
        fp.inside(self.room) && !others.iter().any(|o| o.collides(fp))
    }

    /// Whether `fp` stands in the zone kept clear in front of an earlier group's object.
    pub(super) fn blocks_clearance(&self, fp: &Footprint) -> bool {
        let b = fp.aabb();
        self.keep_clear.iter().any(|z| z.overlap_area(&b) > 1.0)
    }

    /// Adds an object of the group being placed. Its clearance zone is not added: the group's
    /// own dependents stand in it by design (chairs at a desk, a coffee table before a sofa).
    pub(super) fn add(&mut self, obj: PlacedObject) {
        if obj.is_flat() {
            self.flat.push(obj.footprint());
        } else {
            self.solid.push(obj.footprint());
            self.objects.push(obj);
            self.unreachable =
                unreachable_objects(self.room, &self.objects, REACH_TEST_CELL_CM).len();
        }
    }

    /// Whether `obj` can stand there without walling anything in, itself included.
    pub(super) fn keeps_reach(&self, obj: PlacedObject) -> bool {
        if obj.is_flat() {
            return true;
        }
        let mut all = self.objects.clone();
        all.push(obj);
        unreachable_objects(self.room, &all, REACH_TEST_CELL_CM).len() <= self.unreachable
    }

    /// Free distance around `b`: to the walls and to every solid object.
    pub(super) fn clearance_of(&self, b: &Aabb) -> f64 {
        let walls = b
            .min
            .x
            .min(b.min.y)
            .min(self.room.width - b.max.x)
            .min(self.room.depth - b.max.y);
        self.solid
            .iter()
            .map(|o| o.aabb().gap(b))
            .fold(walls, f64::min)
    }

    /// The room's floor as a box.
    pub(super) fn room_box(&self) -> Aabb {
        Aabb {
            min: DVec2::ZERO,
            max: DVec2::new(self.room.width, self.room.depth),
        }
    }
}

/// The zone in front of an earlier group's solid object that people need to reach it: as wide
/// as the object, as deep as its kind's clearance but at least [`MIN_ACCESS_CM`].
fn access_zone(knowledge: &Knowledge, o: &PlacedObject) -> Aabb {
    let clearance = knowledge
        .kind_of(&Asset::new(&o.name, &o.category, o.size))
        .clearance
        .max(MIN_ACCESS_CM);
    let fp = o.footprint();
    Footprint::new(
        fp.front_center() + fp.front * (clearance / 2.0),
        fp.half.x * 2.0,
        clearance,
        fp.rotation,
    )
    .aabb()
}
