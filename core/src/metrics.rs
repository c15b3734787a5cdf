//! Layout quality, measured one way everywhere (docs/formats.md, "Metrics").
//!
//! - **Col**: % of pairs of solid objects (floor coverings aside) that collide, i.e. share more
//!   than [`COLLISION_AREA_CM2`](crate::geometry::COLLISION_AREA_CM2) and overlap in height
//!   ([`geometry3d::collide`]).
//! - **OOB**: mean over objects of the % of footprint area outside the room.
//! - **Constraint satisfaction**: % of the plan's constraints met, using [`crate::relations`].
//! - **Reach**: % of solid objects whose front (any side, for tables and seats) a 40 cm wide agent
//!   walking in through a door can reach (from the largest free region of the floor when the room
//!   has no door).
//! - **Dropped**: % of assets not placed. **Displacement**: mean cm the PRT moved an object.
//! - **Blocked openings** (rooms with doors or windows only): doors whose keep-clear zone a
//!   solid object enters, and windows whose zone an object whose top is above the sill enters.
//! - **Objects off the floor** (when there are any): objects not held where they are
//!   (`unsupported`) and wall objects over openings (`over_openings`), by [`geometry3d`].

use std::collections::BTreeMap;

use serde::{Deserialize, Serialize};

use crate::geometry::Footprint;
use crate::geometry3d;
use crate::layout::{Layout, PlacedObject};
use crate::relations::{ConstraintKind, check_plan};
use crate::room::ZoneKind;

/// Width of the agent that must reach objects (cm).
pub const AGENT_WIDTH_CM: f64 = 40.0;
/// How far beyond its own radius the agent can reach an edge (cm).
pub const REACH_MARGIN_CM: f64 = 10.0;
/// Cell size of the floor raster used for reach (cm).
pub const REACH_CELL_CM: f64 = 5.0;

pub mod reach;
pub use reach::{ReachMap, unreachable_objects};

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
    /// Doors whose keep-clear zone some object other than a floor covering enters; `None` when
    /// the room has no doors or windows (so rectangular rooms report as before).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub doors_blocked: Option<usize>,
    /// Windows whose keep-clear zone some object taller than the sill enters; `None` when the
    /// room has no doors or windows.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub windows_blocked: Option<usize>,
    /// Objects not held where they are (floating above the floor, off or beside their support,
    /// not on their wall), as `name: why`; left out when none.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub unsupported: Vec<String>,
    /// Wall objects that cover a door (below its top) or a window's opening, as `name: why`;
    /// left out when none.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub over_openings: Vec<String>,
}

/// Measures `layout`. Assets are the placed objects plus the dropped ones.
pub fn measure(layout: &Layout) -> Metrics {
    let solid: Vec<&PlacedObject> = layout.objects.iter().filter(|o| !o.is_flat()).collect();

    let mut colliding_pairs = Vec::new();
    for (i, a) in solid.iter().enumerate() {
        for b in &solid[i + 1..] {
            if geometry3d::collide(a, b) {
                colliding_pairs.push((a.name.clone(), b.name.clone()));
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
            ConstraintKind::Relation { .. } | ConstraintKind::Place(_) => positional.add(c.met),
            ConstraintKind::Facing { .. } => facing.add(c.met),
        }
        if !c.met {
            unmet.push(c.to_string());
        }
    }

    let unreachable = unreachable_objects(&layout.room, &layout.objects, REACH_CELL_CM);
    let on_floor = solid
        .iter()
        .filter(|o| geometry3d::reaches_floor(o))
        .count();
    let blocked = layout.room.has_openings().then(|| blocked_openings(layout));
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
        reach_pct: 100.0 - pct(unreachable.len(), on_floor),
        unreachable,
        dropped_pct: pct(layout.dropped.len(), assets),
        mean_displacement_cm: layout.stats.prt.as_ref().map(|p| p.mean_displacement_cm),
        doors_blocked: blocked.map(|(doors, _)| doors),
        windows_blocked: blocked.map(|(_, windows)| windows),
        unsupported: geometry3d::unsupported(&layout.objects, &layout.room),
        over_openings: geometry3d::over_openings(&layout.objects, &layout.room),
    }
}

/// How many doors and how many windows have their keep-clear zone entered by an object the
/// zone binds (by its height: any solid object for a door, taller than the sill for a window).
fn blocked_openings(layout: &Layout) -> (usize, usize) {
    // Wall objects are judged by the openings of their own wall (`over_openings`).
    let footprints: Vec<(Footprint, f64)> = layout
        .objects
        .iter()
        .filter(|o| o.wall.is_none())
        .map(|o| (o.footprint(), o.top()))
        .collect();
    let (mut doors, mut windows) = (0, 0);
    for zone in layout.room.keep_clear() {
        if !footprints.iter().any(|(f, h)| f.intrudes(&zone, *h)) {
            continue;
        }
        match zone.kind {
            ZoneKind::Door(_) => doors += 1,
            ZoneKind::Window(_) => windows += 1,
        }
    }
    (doors, windows)
}

fn pct(part: usize, whole: usize) -> f64 {
    if whole == 0 {
        0.0
    } else {
        100.0 * part as f64 / whole as f64
    }
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
        if let Some(n) = self.doors_blocked {
            writeln!(f, "doors blocked       {n}")?;
        }
        if let Some(n) = self.windows_blocked {
            writeln!(f, "windows blocked     {n}")?;
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
        for u in &self.unsupported {
            writeln!(f, "unsupported: {u}")?;
        }
        for u in &self.over_openings {
            writeln!(f, "over an opening: {u}")?;
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
            ..Default::default()
        }
    }

    fn layout(objects: Vec<PlacedObject>) -> Layout {
        Layout {
            id: "t".into(),
            room: Room::rect(400.0, 300.0),
            objects,
            dropped: vec![],
            plan: Plan::default().into(),
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
    fn objects_off_the_floor_collide_in_3d_and_are_reported_when_unheld() {
        let stand = obj(
            "nightstand-0",
            "nightstand",
            [45.0, 40.0, 55.0],
            [30.0, 20.0],
            0.0,
        );
        let lamp = PlacedObject {
            elevation: 55.0,
            on: Some("nightstand-0".into()),
            ..obj(
                "lamp-0",
                "table lamp",
                [25.0, 25.0, 45.0],
                [30.0, 20.0],
                0.0,
            )
        };
        // A clock over the door of the bottom wall, 100 cm up.
        let clock = PlacedObject {
            elevation: 100.0,
            wall: Some(0),
            ..obj("clock-0", "clock", [30.0, 4.0, 30.0], [200.0, 2.0], 0.0)
        };
        let mut l = layout(vec![stand.clone(), lamp.clone(), clock.clone()]);
        l.room.doors.push(crate::room::Door::new(0, 200.0, 90.0));
        let m = measure(&l);
        assert!(m.colliding_pairs.is_empty(), "{:?}", m.colliding_pairs);
        assert!(m.unsupported.is_empty(), "{:?}", m.unsupported);
        assert_eq!(m.over_openings.len(), 1, "{:?}", m.over_openings);
        assert!(m.over_openings[0].starts_with("clock-0: hangs over door 0"));
        // Reach counts what stands on the floor: the nightstand.
        assert_eq!(m.reach_pct, 100.0);
        let text = serde_json::to_string(&m).unwrap();
        assert!(
            text.contains("over_openings") && !text.contains("unsupported"),
            "{text}"
        );

        let sunk = PlacedObject {
            elevation: 40.0,
            ..lamp
        };
        let floating = PlacedObject {
            elevation: 30.0,
            ..obj("shelf-0", "shelf", [60.0, 30.0, 20.0], [300.0, 200.0], 0.0)
        };
        let m = measure(&layout(vec![stand, sunk, floating, clock]));
        assert_eq!(m.unsupported.len(), 2, "{:?}", m.unsupported);
        assert!(m.unsupported[0].contains("not on the top of nightstand-0"));
        assert!(m.unsupported[1].contains("floats 30.0 cm"));
        assert_eq!(
            m.colliding_pairs,
            vec![("nightstand-0".into(), "lamp-0".into())]
        );
        let text = serde_json::to_string(&m).unwrap();
        assert!(
            text.contains("unsupported") && !text.contains("over_openings"),
            "{text}"
        );
    }

    #[test]
    fn a_floor_only_layout_reports_no_new_fields() {
        let m = measure(&layout(vec![obj(
            "a",
            "cabinet",
            [100.0, 50.0, 90.0],
            [100.0, 100.0],
            0.0,
        )]));
        let text = serde_json::to_string(&m).unwrap();
        assert!(
            !text.contains("unsupported") && !text.contains("over_openings"),
            "{text}"
        );
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
        l.plan_mut().constraints.insert(
            "chair".into(),
            ObjectConstraints {
                against_wall: false,
                relations: vec![RelationSpec {
                    relation: Relation::Around,
                    target: "table".into(),
                }],
                facing: Some("table".into()),
                place: None,
                support: None,
            },
        );
        l.plan_mut().constraints.insert(
            "cab".into(),
            ObjectConstraints {
                against_wall: true,
                relations: vec![RelationSpec {
                    relation: Relation::Near,
                    target: "table".into(),
                }],
                facing: None,
                place: None,
                support: None,
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
    fn blocked_doors_and_windows_are_counted_by_what_their_zones_bind() {
        use crate::room::{Door, Hinge, Swing, Window};
        let door = |at: f64, swing: Swing| Door {
            wall: 0,
            at,
            width: 90.0,
            swing,
            hinge: Hinge::Left,
        };
        // Wall 2 runs along the top (y = 300) from x = 400 to x = 0.
        let window = |at: f64| Window {
            wall: 2,
            at,
            width: 120.0,
            sill: 90.0,
            height: 120.0,
        };
        let objects = vec![
            // In door 0's zone (x 55..145, y 0..90): blocks it.
            obj("cab", "cabinet", [60.0, 40.0, 90.0], [100.0, 45.0], 0.0),
            // A rug in door 1's zone: floor coverings may lie there.
            obj("rug", "rug", [80.0, 60.0, 1.0], [300.0, 40.0], 0.0),
            // Under window 0's sill (x 240..360, y 260..300): allowed.
            obj("bench", "bench", [80.0, 40.0, 45.0], [300.0, 280.0], 0.0),
            // In front of window 1 (x 40..160) and taller than its sill: blocks it.
            obj(
                "wardrobe",
                "wardrobe",
                [100.0, 60.0, 200.0],
                [100.0, 270.0],
                0.0,
            ),
        ];
        let mut l = layout(objects);
        let plain = measure(&l);
        assert_eq!((plain.doors_blocked, plain.windows_blocked), (None, None));
        assert!(!plain.to_string().contains("blocked"));

        l.room.doors = vec![door(100.0, Swing::In), door(300.0, Swing::Out)];
        l.room.windows = vec![window(100.0), window(300.0)];
        let m = measure(&l);
        assert_eq!((m.doors_blocked, m.windows_blocked), (Some(1), Some(1)));
        let text = m.to_string();
        assert!(text.contains("doors blocked       1"), "{text}");
        assert!(text.contains("windows blocked     1"), "{text}");

        // Moved clear of the window, the wardrobe blocks nothing.
        l.objects[3].position = [200.0, 150.0];
        let m = measure(&l);
        assert_eq!((m.doors_blocked, m.windows_blocked), (Some(1), Some(0)));
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
