//! A design of a group in progress: the floor so far, where everything stands, the seats still
//! to hand out and the formations laid out.

use std::collections::{HashMap, HashSet};

use disco_core::geometry::Footprint;
use disco_core::layout::PlacedObject;
use disco_core::placement::Pose;

use super::floor::Floor;

/// Seats around each table, by the table's name, still to hand out (the next one last).
pub(super) type Seats = HashMap<String, Vec<Pose>>;

/// A design in progress: the floor so far, and where everything stands.
pub(super) struct Draft<'a, 'd> {
    /// What stands on the floor, earlier groups and this one: the start's floor, in a trial
    /// that is rolled back when the attempt is done.
    pub(super) floor: &'d mut Floor<'a>,
    /// Footprint of every object placed, by name.
    pub(super) where_is: HashMap<&'a str, Footprint>,
    /// The row pose of each desk of the group that stands in rows, by name.
    pub(super) rows: HashMap<String, Pose>,
    /// Seats around each table, handed out in order.
    pub(super) seats: Seats,
    /// The pose each member of a formation laid out so far takes in it, by name.
    pub(super) formation: HashMap<String, Pose>,
    /// How many formations the room made bend from their own shape.
    pub(super) formations_bent: usize,
    /// Formations (by their first member) the room could not hold in this attempt.
    pub(super) formations_failed: HashSet<String>,
    /// The group's objects placed so far.
    pub(super) out: Vec<PlacedObject>,
}
