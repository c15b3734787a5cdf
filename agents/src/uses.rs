//! What pieces are for, checked on a finished layout: every seat at something people sit at,
//! every counter open on its staff side and its customers' side, every run of aisle shelving
//! standing free. The furniture knowledge says which piece is which (`config/furniture.toml`:
//! `seat`, `seats`, `staff`, `formation = "aisles"`); the geometry says whether the layout
//! serves those uses.
//!
//! These are the checks the open-universe benchmark (`bench/open`) holds the default to, and a
//! report or a test can run them on any layout.

use std::fmt;

use disco_core::geometry::Footprint;
use disco_core::layout::Layout;
use disco_core::plan::FormationShape;
use disco_core::relations;
use disco_core::scene::SceneSpec;

use crate::knowledge::{Kind, Knowledge, SeatsAt, ends_with_words, words};

/// Largest gap (cm) between a seat and what it serves.
pub const SEAT_REACH_CM: f64 = 60.0;

/// Depth (cm) of the strip on a counter's staff side that must be open floor.
pub const STAFF_STRIP_CM: f64 = 60.0;

/// What a check is about.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum UseKind {
    /// A seat stands within [`SEAT_REACH_CM`] of a table, desk, station or bar and faces it.
    SeatServes,
    /// The [`STAFF_STRIP_CM`] deep strips along a counter's staff side and along its customers'
    /// side lie in the room and hold nothing but seats.
    StaffSideOpen,
    /// A piece of aisle shelving stands free of the walls, parallel to the others of its run.
    AisleFree,
}

impl fmt::Display for UseKind {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(match self {
            UseKind::SeatServes => "seat serves something",
            UseKind::StaffSideOpen => "both sides of the counter open",
            UseKind::AisleFree => "aisle shelving free",
        })
    }
}

/// One check of one piece.
#[derive(Debug, Clone, PartialEq)]
pub struct UseCheck {
    /// The piece checked.
    pub subject: String,
    /// What was checked.
    pub kind: UseKind,
    /// Whether the layout serves that use.
    pub met: bool,
    /// For an unmet seat: the run's notes say nothing had room for it (reported, not silent).
    pub reported: bool,
}

/// What a piece of `asset`'s kind is for, in words a model reads with each piece it places:
/// who works at it and on which side, who sits at it and how many, whether it is a seat, how
/// shop shelving stands. Empty for a piece the knowledge gives no use.
pub fn use_words(knowledge: &Knowledge, asset: &disco_core::scene::Asset) -> Vec<String> {
    let kind = knowledge.kind_of(asset);
    let [w, d, _] = asset.size;
    let mut out = Vec::new();
    if kind.staff > 0.0 && kind.staff_behind() {
        out.push(format!(
            "a bar: its seats stand along its front; the staff work behind it, so keep {:.0} cm free behind it",
            kind.staff
        ));
    } else if kind.staff > 0.0 {
        out.push(format!(
            "a counter: its staff work at its front, so keep {:.0} cm free in front of it (not against a wall); customers come to its back",
            kind.staff
        ));
    }
    match kind.seats {
        Some(how @ SeatsAt::Around) => out.push(format!(
            "people sit all round it: seats for up to {}",
            how.capacity(w, d)
        )),
        Some(how @ SeatsAt::Front) => out.push(format!(
            "people work at its front: {} seat(s), facing it",
            how.capacity(w, d)
        )),
        Some(how @ SeatsAt::AlongFront) if kind.staff == 0.0 => out.push(format!(
            "stools stand along its front: up to {}",
            how.capacity(w, d)
        )),
        _ => {}
    }
    if kind.seat {
        out.push("a seat: it belongs at a table, desk, station or bar, facing it".into());
    }
    if kind.formation == Some(FormationShape::Aisles) {
        out.push(
            format!(
                "shop shelving: free-standing in parallel lines with aisles of about {:.0} cm, fronts to the aisles",
                disco_tools::formation::AISLE_CM
            ),
        );
    }
    out
}

/// The note a run carries for `n` seats of `category` nothing had room for; [`check_uses`]
/// reads it back to tell a reported seat from a silent one.
pub fn left_over_note(category: &str, n: usize) -> String {
    format!("{n} x {category}{LEFT_OVER}; stood along the walls")
}

/// What [`left_over_note`] says after the count and the category.
const LEFT_OVER: &str = ": nothing in the room has room for this seat";

/// One placed piece as the checks see it.
struct Piece<'a> {
    name: &'a str,
    fp: Footprint,
    kind: Kind,
    /// Its category's words.
    category: String,
    /// A seat, or a chair of another kind: what may stand on a counter's staff side.
    seat_like: bool,
}

/// The use checks of every placed piece of `layout` the knowledge gives a use. Each piece's
/// kind and words are read once; the checks pair pieces, so the work grows with the square of
/// the pieces that have a use and the pieces near them.
pub fn check_uses(scene: &SceneSpec, layout: &Layout, knowledge: &Knowledge) -> Vec<UseCheck> {
    let assets: std::collections::HashMap<&str, &disco_core::scene::Asset> =
        scene.assets.iter().map(|a| (a.name.as_str(), a)).collect();
    let pieces: Vec<Piece<'_>> = layout
        .objects
        .iter()
        .filter_map(|o| {
            let a = assets.get(o.name.as_str())?;
            let kind = knowledge.kind_of(a);
            let category = words(&a.category);
            let seat_like = kind.seat || ends_with_words(&category, "chair");
            Some(Piece {
                name: &o.name,
                fp: o.footprint(),
                kind,
                category,
                seat_like,
            })
        })
        .collect();
    let served: Vec<&Piece<'_>> = pieces.iter().filter(|p| p.kind.seats.is_some()).collect();
    let mut out = Vec::new();
    for p in &pieces {
        if p.kind.seat && p.kind.rows.is_empty() {
            let met = served.iter().any(|t| {
                t.name != p.name
                    && p.fp.gap(&t.fp) <= SEAT_REACH_CM
                    && relations::facing(&p.fp, &t.fp)
            });
            let said = format!(" x {}{LEFT_OVER}", p.category);
            let reported = !met && layout.stats.notes.iter().any(|n| n.contains(&said));
            out.push(UseCheck {
                subject: p.name.to_string(),
                kind: UseKind::SeatServes,
                met,
                reported,
            });
        }
        if p.kind.staff > 0.0 {
            out.push(UseCheck {
                subject: p.name.to_string(),
                kind: UseKind::StaffSideOpen,
                met: sides_open(p, &pieces, &layout.room),
                reported: false,
            });
        }
    }
    // Aisle shelving: each run of one kind, when there are two or more of it.
    let mut runs: Vec<Vec<&Piece<'_>>> = Vec::new();
    for p in pieces
        .iter()
        .filter(|p| p.kind.formation == Some(FormationShape::Aisles))
    {
        match runs.iter_mut().find(|r| r[0].kind.names == p.kind.names) {
            Some(r) => r.push(p),
            None => runs.push(vec![p]),
        }
    }
    for run in runs.iter().filter(|r| r.len() >= 2) {
        let fps: Vec<Footprint> = run.iter().map(|p| p.fp).collect();
        let free = crate::requests::aisles_met(&fps, &layout.room);
        for p in run {
            out.push(UseCheck {
                subject: p.name.to_string(),
                kind: UseKind::AisleFree,
                met: free,
                reported: false,
            });
        }
    }
    out
}

/// Whether the strips [`STAFF_STRIP_CM`] deep along a counter's front and back lie in the room
/// and hold nothing but seats: the staff's side and the customers' side both.
fn sides_open(counter: &Piece<'_>, pieces: &[Piece<'_>], room: &disco_core::scene::Room) -> bool {
    let fp = &counter.fp;
    [fp.front, -fp.front].into_iter().all(|side| {
        let edge = fp.center + side * fp.half.y;
        let strip = Footprint::new(
            edge + side * (STAFF_STRIP_CM / 2.0),
            2.0 * fp.half.x - 2.0,
            STAFF_STRIP_CM - 2.0,
            fp.rotation,
        );
        strip.inside(room)
            && pieces
                .iter()
                .all(|o| o.name == counter.name || o.seat_like || !strip.collides(&o.fp))
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use disco_core::layout::{PlacedObject, Stats};
    use disco_core::plan::Plan;
    use disco_core::scene::{Asset, Room};

    fn scene(items: &[(&str, &str, [f64; 3])]) -> SceneSpec {
        SceneSpec {
            id: "s".into(),
            prompt: String::new(),
            room_type: "shop".into(),
            room: Room::rect(800.0, 600.0),
            assets: items.iter().map(|(n, c, s)| Asset::new(n, c, *s)).collect(),
        }
    }

    fn at(s: &SceneSpec, name: &str, x: f64, y: f64, rotation: f64) -> PlacedObject {
        let a = s.asset(name).unwrap();
        PlacedObject {
            name: a.name.clone(),
            category: a.category.clone(),
            size: a.size,
            position: [x, y],
            rotation,
            ..Default::default()
        }
    }

    fn checks(s: &SceneSpec, objects: Vec<PlacedObject>) -> Vec<UseCheck> {
        let layout = Layout {
            id: s.id.clone(),
            room: s.room.clone(),
            objects,
            dropped: vec![],
            plan: Plan::default().into(),
            stats: Stats::default(),
        };
        check_uses(s, &layout, &Knowledge::builtin())
    }

    #[test]
    fn a_stool_at_its_bar_serves_it_and_one_across_the_room_does_not() {
        let s = scene(&[
            ("bar-0", "bar counter", [300.0, 70.0, 110.0]),
            ("stool-0", "bar stool", [45.0, 45.0, 75.0]),
            ("stool-1", "bar stool", [45.0, 45.0, 75.0]),
        ]);
        // The bar's front faces up; stool-0 just above it facing down at it.
        let c = checks(
            &s,
            vec![
                at(&s, "bar-0", 400.0, 200.0, 0.0),
                at(&s, "stool-0", 400.0, 260.0, 180.0),
                at(&s, "stool-1", 100.0, 550.0, 180.0),
            ],
        );
        let seat = |n: &str| {
            c.iter()
                .find(|k| k.subject == n && k.kind == UseKind::SeatServes)
        };
        assert!(seat("stool-0").unwrap().met);
        assert!(!seat("stool-1").unwrap().met);
        // The bar's staff work behind it: 165 cm of open floor below it.
        let staff = c.iter().find(|k| k.kind == UseKind::StaffSideOpen).unwrap();
        assert!(staff.met);
    }

    #[test]
    fn a_counter_with_its_staff_side_on_the_wall_is_caught() {
        let s = scene(&[("till-0", "checkout counter", [160.0, 70.0, 100.0])]);
        // Front (the staff side) towards the bottom wall, flush against it.
        let flush = checks(&s, vec![at(&s, "till-0", 400.0, 35.0, 180.0)]);
        assert!(!flush[0].met);
        let off = checks(&s, vec![at(&s, "till-0", 400.0, 135.0, 180.0)]);
        assert!(off[0].met);
    }

    #[test]
    fn a_model_is_told_what_counters_tables_and_seats_are_for() {
        let k = Knowledge::builtin();
        let till = use_words(
            &k,
            &Asset::new("t", "checkout counter", [160.0, 70.0, 100.0]),
        );
        assert!(till[0].contains("staff work at its front"), "{till:?}");
        let bar = use_words(&k, &Asset::new("b", "bar counter", [400.0, 70.0, 110.0]));
        assert!(bar[0].contains("behind it"), "{bar:?}");
        let table = use_words(&k, &Asset::new("g", "card table", [90.0, 90.0, 75.0]));
        assert_eq!(
            table,
            vec!["people sit all round it: seats for up to 4".to_string()]
        );
        let stool = use_words(&k, &Asset::new("s", "pottery stool", [40.0, 40.0, 50.0]));
        assert!(stool[0].starts_with("a seat"));
        assert!(use_words(&k, &Asset::new("w", "wardrobe", [100.0, 60.0, 200.0])).is_empty());
    }

    #[test]
    fn gondolas_against_a_wall_are_not_aisles() {
        let s = scene(&[
            ("g-0", "gondola shelving", [240.0, 90.0, 160.0]),
            ("g-1", "gondola shelving", [240.0, 90.0, 160.0]),
        ]);
        let free = checks(
            &s,
            vec![
                at(&s, "g-0", 400.0, 200.0, 0.0),
                at(&s, "g-1", 400.0, 410.0, 180.0),
            ],
        );
        assert!(free.iter().all(|c| c.met), "{free:?}");
        let walled = checks(
            &s,
            vec![
                at(&s, "g-0", 400.0, 45.0, 0.0),
                at(&s, "g-1", 400.0, 410.0, 180.0),
            ],
        );
        assert!(!walled.iter().find(|c| c.subject == "g-0").unwrap().met);
    }
}
