//! The geometric meaning of every word in the plan's vocabulary.
//!
//! One written predicate per relation, shared by the evaluator, the metrics and the tests, so that
//! "the chair is around the table" means the same thing everywhere. `a` is the subject, `b` the
//! target ("a is near b"); positions are read in `b`'s own frame (x to its right, y to its front).
//!
//! | relation | holds when |
//! |---|---|
//! | near | the gap between the footprints is at most [`NEAR_GAP_CM`] |
//! | side of | `a`'s centre lies beyond `b`'s left or right edge, within `b`'s depth span, and `a` is near `b` |
//! | in front of | `a`'s centre lies beyond `b`'s front edge, within `b`'s width span, at most [`FRONT_GAP_CM`] away |
//! | aligned with | `a`'s centre lies within [`ALIGN_TOL_CM`] of one of `b`'s centre lines, or both face the same way with their back edges on one line |
//! | opposite | each faces the other |
//! | around | `a` is near `b` and faces it |
//! | facing | the ray from `a`'s centre along its front meets `b`'s footprint |
//! | against wall | `a`'s back edge is within 1 cm of a wall and its front points into the room |
//! | on | `a`'s footprint lies within `b`'s, seen from above (the heights are the 3D predicates' business: `disco_core::geometry3d`) |
//! | above | `a` hangs over `b`: within `b`'s width (reaching past it by at most a tenth of it, as a row of pictures over a sofa may), or centred on it within [`CENTRED_TOL_CM`]; its back within [`ABOVE_WALL_CM`] of `b`'s back (on the wall `b` backs onto), turned the same way |
//! | back to back | the two are turned opposite ways (within [`BACK_TURN_DEG`]), each stands behind the other (its centre past the other's back edge, within the wider one's width) and the gap between them is at most [`BACK_GAP_CM`] |
//!
//! A target may also be a part of the room, `door-N`, `window-N` or `wall-N`
//! ([`crate::targets`]): a thin footprint on its wall, front into the room, read by the same
//! predicates, but for *beside*, which means along its wall past an end of its span
//! ([`beside_part`]).

use std::fmt;

use glam::DVec2;

use crate::geometry::{Footprint, Wall};
use crate::layout::Layout;
use crate::plan::{Place, Relation};
use crate::scene::Room;
use crate::targets::room_part_footprint;

/// Largest gap (cm) between two footprints that still counts as "near".
pub const NEAR_GAP_CM: f64 = 50.0;
/// Largest gap (cm) for "in front of": further away is across the room, not in front.
pub const FRONT_GAP_CM: f64 = 150.0;
/// Tolerance (cm) for "aligned with".
pub const ALIGN_TOL_CM: f64 = 10.0;
/// How far (cm) the centre of an object hung "above" another may be off the other's centre line
/// when it is wider than the other.
pub const CENTRED_TOL_CM: f64 = 15.0;
/// How far (cm) the back of an object hung "above" a piece may be from that piece's back: both
/// are on one wall, the piece standing a little off it.
pub const ABOVE_WALL_CM: f64 = 25.0;
/// Largest gap (cm) between two pieces standing "back to back".
pub const BACK_GAP_CM: f64 = 30.0;
/// How far (degrees) from exactly opposite two pieces "back to back" may be turned.
pub const BACK_TURN_DEG: f64 = 10.0;
/// How far (cm) a footprint may reach past the top it stands "on", seen from above.
const ON_MARGIN_CM: f64 = 1.0;

/// `a` is near `b`.
pub fn near(a: &Footprint, b: &Footprint) -> bool {
    a.gap(b) <= NEAR_GAP_CM
}

/// `a` stands beside `b` (to its left or right).
pub fn side_of(a: &Footprint, b: &Footprint) -> bool {
    let l = b.to_local(a.center);
    l.x.abs() >= b.half.x && l.y.abs() <= b.half.y && near(a, b)
}

/// `a` stands in `b`'s front zone.
pub fn in_front_of(a: &Footprint, b: &Footprint) -> bool {
    let l = b.to_local(a.center);
    l.y > b.half.y && l.x.abs() <= b.half.x && a.gap(b) <= FRONT_GAP_CM
}

/// `a` is lined up with `b`.
pub fn aligned_with(a: &Footprint, b: &Footprint) -> bool {
    let l = b.to_local(a.center);
    if l.x.abs() <= ALIGN_TOL_CM || l.y.abs() <= ALIGN_TOL_CM {
        return true;
    }
    let same_way = a.front.dot(b.front) >= 0.999;
    same_way && (b.to_local(a.back_center()).y + b.half.y).abs() <= ALIGN_TOL_CM
}

/// `a`'s front points at `b`.
pub fn facing(a: &Footprint, b: &Footprint) -> bool {
    a.front_ray_hit(b).is_some()
}

/// `a` and `b` face each other.
pub fn opposite(a: &Footprint, b: &Footprint) -> bool {
    facing(a, b) && facing(b, a)
}

/// `a` is close to `b` and turned towards it.
pub fn around(a: &Footprint, b: &Footprint) -> bool {
    near(a, b) && facing(a, b)
}

/// `a` stands on `b`'s top, seen from above: its footprint within `b`'s.
pub fn on_top_of(a: &Footprint, b: &Footprint) -> bool {
    let limit = b.half + DVec2::splat(ON_MARGIN_CM);
    a.corners().iter().all(|&c| {
        let l = b.to_local(c);
        l.x.abs() <= limit.x && l.y.abs() <= limit.y
    })
}

/// `a` hangs above `b`: over it (within its width, reaching past it by at most a tenth of it, or
/// centred on it), its back on the wall behind `b`, turned as `b` is.
pub fn hung_above(a: &Footprint, b: &Footprint) -> bool {
    let same_way = a.front.dot(b.front) >= 0.99;
    let l = b.to_local(a.center);
    let centred = l.x.abs() <= CENTRED_TOL_CM || l.x.abs() + a.half.x <= 1.1 * b.half.x;
    let back_a = b.to_local(a.back_center()).y;
    let on_b_wall = (back_a + b.half.y).abs() <= ABOVE_WALL_CM;
    same_way && centred && on_b_wall
}

/// `a` and `b` stand back to back: turned opposite ways, each behind the other, close.
pub fn back_to_back(a: &Footprint, b: &Footprint) -> bool {
    let turned_away = a.front.dot(b.front) <= -BACK_TURN_DEG.to_radians().cos();
    let wide = a.half.x.max(b.half.x);
    let behind = |p: &Footprint, q: &Footprint| {
        let l = q.to_local(p.center);
        l.y < -q.half.y && l.x.abs() <= wide
    };
    turned_away && behind(a, b) && behind(b, a) && a.gap(b) <= BACK_GAP_CM
}

/// `a` stands beside the room part `part` (its thin footprint): along the same wall, its centre
/// past one end of the part's span and no farther from the wall than its own half size and
/// [`ALIGN_TOL_CM`] (so it stands on or by that wall), the gap at most
/// [`NEAR_GAP_CM`]. The piece
/// predicate ("within the target's front-to-back span") would ask a cabinet beside a door to
/// stand within the door's 2 cm.
pub fn beside_part(a: &Footprint, part: &Footprint) -> bool {
    let l = part.to_local(a.center);
    l.x.abs() >= part.half.x
        && l.y <= part.half.y + a.half.max_element() + ALIGN_TOL_CM
        && near(a, part)
}

/// `a` stands with its back on a wall of `room`, front into the room.
pub fn against_wall(a: &Footprint, room: &Room) -> bool {
    a.against_wall(room).is_some()
}

impl Relation {
    /// Whether `a` stands in this relation to `b`.
    pub fn holds(self, a: &Footprint, b: &Footprint) -> bool {
        match self {
            Relation::Near => near(a, b),
            Relation::SideOf => side_of(a, b),
            Relation::InFrontOf => in_front_of(a, b),
            Relation::AlignedWith => aligned_with(a, b),
            Relation::Opposite => opposite(a, b),
            Relation::Around => around(a, b),
            Relation::On => on_top_of(a, b),
            Relation::Above => hung_above(a, b),
            Relation::BackToBack => back_to_back(a, b),
        }
    }
}

/// What one constraint of the plan asks.
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum ConstraintKind {
    /// The subject's back is on a wall.
    AgainstWall,
    /// The subject stands in this relation to `target`.
    Relation {
        /// The relation.
        relation: Relation,
        /// The other object.
        target: String,
    },
    /// The subject faces `target`.
    Facing {
        /// The other object.
        target: String,
    },
    /// The subject stands where the plan puts it in the room (a zone, a wall's role, ...).
    Place(Place),
}

impl ConstraintKind {
    /// The other object the constraint is about (`None` for against-wall).
    pub fn target(&self) -> Option<&str> {
        match self {
            ConstraintKind::AgainstWall | ConstraintKind::Place(_) => None,
            ConstraintKind::Relation { target, .. } | ConstraintKind::Facing { target } => {
                Some(target)
            }
        }
    }

    /// The bucket this constraint is reported in: `against_wall`, a relation's name, or `facing`.
    pub fn label(&self) -> &'static str {
        match self {
            ConstraintKind::AgainstWall => "against_wall",
            ConstraintKind::Relation { relation, .. } => relation.as_str(),
            ConstraintKind::Facing { .. } => "facing",
            ConstraintKind::Place(_) => "place",
        }
    }
}

/// One constraint of a plan, checked against a layout.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct ConstraintCheck {
    /// The object the constraint is about.
    pub subject: String,
    /// What it asks.
    pub kind: ConstraintKind,
    /// Whether the layout meets it.
    pub met: bool,
}

impl fmt::Display for ConstraintCheck {
    /// The constraint as a plain statement, e.g. `chair-0 is around table-0`.
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match &self.kind {
            ConstraintKind::AgainstWall => write!(f, "{} stands against a wall", self.subject),
            ConstraintKind::Relation { relation, target } => {
                write!(f, "{} is {} {}", self.subject, relation.words(), target)
            }
            ConstraintKind::Facing { target } => write!(f, "{} faces {}", self.subject, target),
            ConstraintKind::Place(place) => write!(f, "{} stands {place}", self.subject),
        }
    }
}

/// How far (cm) from a wall a piece that does not stand against one still counts as on it.
pub const ON_WALL_CM: f64 = 60.0;

/// How far (cm) from the main door's centre a piece "by the entrance" may stand (its nearest
/// point).
pub const BY_ENTRANCE_CM: f64 = 180.0;

/// How far (cm) from the far corner a piece "in the corner farthest from the door" may stand
/// (its nearest point).
pub const IN_CORNER_CM: f64 = 40.0;

/// `a` stands where `place` puts it in `room`: in the zone (its centre in the zone's box), on a
/// wall of the role (its back on one, or within [`ON_WALL_CM`] of one for a free-standing
/// piece), in the far corner, under a window (back on the window's wall, centre within the
/// window's span), by the entrance.
pub fn placed_as_asked(a: &Footprint, room: &Room, place: &Place) -> bool {
    placed_as_asked_in(a, room, &room.analysis(), place)
}

/// [`placed_as_asked`] with the room's analysis already made (a caller that checks many
/// poses in one room makes it once).
pub fn placed_as_asked_in(
    a: &Footprint,
    room: &Room,
    analysis: &crate::room::analysis::RoomAnalysis,
    place: &Place,
) -> bool {
    let zone_ok = place.zone.as_deref().is_none_or(|z| {
        analysis
            .zones_named(z)
            .iter()
            .any(|zone| zone.contains(a.center, 1.0))
    });
    let walls = Wall::all(room);
    let on_wall = |ids: &[usize]| match a.against_wall(room) {
        Some(w) => ids.contains(&w.index()),
        None => ids.iter().any(|&i| {
            walls.get(i).is_some_and(|w| {
                a.corners()
                    .iter()
                    .any(|&c| w.segment_distance(c) <= ON_WALL_CM)
            })
        }),
    };
    let wall_ok = place
        .wall
        .is_none_or(|role| on_wall(&analysis.walls_with(role)));
    let corner_ok = !place.far_corner
        || analysis.far_corner(place.zone.as_deref()).is_some_and(|c| {
            let p = DVec2::new(c.at[0], c.at[1]);
            a.corners()
                .iter()
                .any(|&k| k.distance(p) <= IN_CORNER_CM + a.half.min_element())
        });
    let window_ok = !place.under_window
        || room.windows.iter().any(|w| {
            room.opening_ends(w.wall, w.at, w.width)
                .is_some_and(|(s, e)| {
                    let (bl, br) = a.back_edge();
                    let back = (bl + br) / 2.0;
                    let along = (back - s).dot((e - s).normalize());
                    let span = s.distance(e);
                    crate::room::distance_to_segment(back, s, e) <= 20.0
                        && along >= -5.0
                        && along <= span + 5.0
                })
        });
    let entrance_ok = !place.by_entrance
        || analysis.main_door.is_some_and(|i| {
            let d = &room.doors[i];
            room.opening_ends(d.wall, d.at, d.width)
                .is_some_and(|(s, e)| {
                    let door = (s + e) / 2.0;
                    a.corners()
                        .iter()
                        .map(|c| c.distance(door))
                        .fold(f64::INFINITY, f64::min)
                        <= BY_ENTRANCE_CM
                })
        });
    zone_ok && wall_ok && corner_ok && window_ok && entrance_ok
}

/// Whether `layout` meets one constraint of `subject` (unmet when an object is missing).
pub fn check_one(layout: &Layout, subject: &str, kind: &ConstraintKind) -> bool {
    let fp = |n: &str| layout.object(n).map(|o| o.footprint());
    fp(subject).is_some_and(|a| kind.holds(&a, &layout.room, fp))
}

impl ConstraintKind {
    /// Whether the subject at `a` meets this constraint, with `find` giving other objects'
    /// footprints by name (unmet when the target is not there); a target no object is named
    /// after may be a part of the room (`door-0`, `window-1`, `wall-2`).
    pub fn holds(
        &self,
        a: &Footprint,
        room: &Room,
        find: impl Fn(&str) -> Option<Footprint>,
    ) -> bool {
        let target = |t: &str| find(t).or_else(|| room_part_footprint(room, t));
        match self {
            ConstraintKind::AgainstWall => against_wall(a, room),
            ConstraintKind::Relation {
                relation: Relation::SideOf,
                target: t,
            } if find(t).is_none() => {
                room_part_footprint(room, t).is_some_and(|b| beside_part(a, &b))
            }
            ConstraintKind::Relation {
                relation,
                target: t,
            } => target(t).is_some_and(|b| relation.holds(a, &b)),
            ConstraintKind::Facing { target: t } => target(t).is_some_and(|b| facing(a, &b)),
            ConstraintKind::Place(place) => placed_as_asked(a, room, place),
        }
    }
}

/// The constraints the plan sets for `subject`, in order: wall, relations, facing.
pub fn constraints_of(plan: &crate::plan::Plan, subject: &str) -> Vec<ConstraintKind> {
    let Some(c) = plan.constraints.get(subject) else {
        return Vec::new();
    };
    let mut out = Vec::new();
    if c.against_wall {
        out.push(ConstraintKind::AgainstWall);
    }
    for r in &c.relations {
        out.push(ConstraintKind::Relation {
            relation: r.relation,
            target: r.target.clone(),
        });
    }
    if let Some(t) = &c.facing {
        out.push(ConstraintKind::Facing { target: t.clone() });
    }
    if let Some(p) = c.place.as_ref().filter(|p| !p.is_empty()) {
        out.push(ConstraintKind::Place(p.clone()));
    }
    out
}

/// Checks every constraint of `layout.plan` against `layout`. A constraint whose subject or target
/// was not placed is unmet. Order: subjects by name, then wall, relations, facing.
pub fn check_plan(layout: &Layout) -> Vec<ConstraintCheck> {
    layout
        .plan
        .constraints
        .keys()
        .flat_map(|subject| {
            constraints_of(&layout.plan, subject)
                .into_iter()
                .map(move |kind| ConstraintCheck {
                    subject: subject.clone(),
                    met: check_one(layout, subject, &kind),
                    kind,
                })
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use glam::DVec2;

    use super::*;

    fn fp(x: f64, y: f64, w: f64, d: f64, r: f64) -> Footprint {
        Footprint::new(DVec2::new(x, y), w, d, r)
    }

    // A 160 x 210 bed with its head on the top wall of a 400 x 350 room, facing down.
    fn bed() -> Footprint {
        fp(200.0, 245.0, 160.0, 210.0, 180.0)
    }

    #[test]
    fn near_uses_the_gap_not_the_centres() {
        let table = fp(200.0, 200.0, 200.0, 100.0, 0.0);
        assert!(near(&fp(200.0, 120.0, 40.0, 40.0, 0.0), &table)); // gap 10
        assert!(near(&fp(200.0, 80.0, 40.0, 40.0, 0.0), &table)); // gap 50
        assert!(!near(&fp(200.0, 79.0, 40.0, 40.0, 0.0), &table)); // gap 51
    }

    #[test]
    fn nightstand_is_beside_the_bed() {
        let stand = fp(305.0, 330.0, 50.0, 40.0, 180.0);
        assert!(side_of(&stand, &bed()));
        assert!(side_of(&fp(95.0, 330.0, 50.0, 40.0, 180.0), &bed()));
        // At the foot of the bed, beyond its front edge: in front, not beside.
        let foot = fp(200.0, 110.0, 100.0, 40.0, 180.0);
        assert!(!side_of(&foot, &bed()));
        assert!(in_front_of(&foot, &bed()));
        // Beside but two metres away: not beside.
        assert!(!side_of(
            &fp(395.0, 330.0, 10.0, 40.0, 180.0),
            &fp(100.0, 245.0, 160.0, 210.0, 180.0)
        ));
    }

    #[test]
    fn in_front_follows_the_targets_rotation() {
        let sofa = fp(50.0, 200.0, 200.0, 90.0, 90.0); // against the left wall, facing +x
        assert!(in_front_of(&fp(160.0, 200.0, 100.0, 60.0, 0.0), &sofa));
        assert!(!in_front_of(&fp(200.0, 50.0, 100.0, 60.0, 0.0), &sofa));
        assert!(
            !in_front_of(&fp(400.0, 200.0, 100.0, 60.0, 0.0), &sofa),
            "too far"
        );
    }

    #[test]
    fn aligned_with_centre_lines_or_rows() {
        let table = fp(200.0, 200.0, 120.0, 80.0, 0.0);
        assert!(aligned_with(&fp(205.0, 120.0, 40.0, 40.0, 0.0), &table));
        assert!(aligned_with(&fp(300.0, 195.0, 40.0, 40.0, 270.0), &table));
        assert!(!aligned_with(&fp(240.0, 120.0, 40.0, 40.0, 0.0), &table));
        // Two cabinets in a row along the bottom wall, back edges on y = 0.
        let c1 = fp(50.0, 30.0, 60.0, 60.0, 0.0);
        let c2 = fp(300.0, 20.0, 60.0, 40.0, 0.0);
        assert!(aligned_with(&c2, &c1));
    }

    #[test]
    fn facing_opposite_and_around() {
        let table = fp(200.0, 200.0, 120.0, 80.0, 0.0);
        let chair_south = fp(200.0, 135.0, 45.0, 45.0, 0.0);
        let chair_turned = fp(200.0, 135.0, 45.0, 45.0, 90.0);
        assert!(facing(&chair_south, &table));
        assert!(!facing(&chair_turned, &table));
        assert!(around(&chair_south, &table));
        assert!(
            !around(&fp(200.0, 50.0, 45.0, 45.0, 0.0), &table),
            "facing but far"
        );
        let sofa = fp(200.0, 50.0, 200.0, 90.0, 0.0);
        let tv = fp(200.0, 330.0, 150.0, 40.0, 180.0);
        assert!(opposite(&tv, &sofa) && opposite(&sofa, &tv));
        assert!(!opposite(&fp(200.0, 330.0, 150.0, 40.0, 0.0), &sofa));
    }

    #[test]
    fn back_to_back_needs_both_turned_away_behind_each_other_and_close() {
        // Two desks of a pod: one facing +y, one facing -y, backs 5 cm apart.
        let a = fp(200.0, 170.0, 120.0, 60.0, 180.0);
        let b = fp(200.0, 235.0, 120.0, 60.0, 0.0);
        assert!(back_to_back(&a, &b) && back_to_back(&b, &a));
        assert!(
            !back_to_back(&fp(200.0, 170.0, 120.0, 60.0, 0.0), &b),
            "same way"
        );
        assert!(
            !back_to_back(&fp(200.0, 100.0, 120.0, 60.0, 180.0), &b),
            "75 cm apart"
        );
        assert!(
            !back_to_back(&fp(340.0, 170.0, 120.0, 60.0, 180.0), &b),
            "beside, not behind"
        );
        // Face to face is opposite, not back to back.
        let c = fp(200.0, 170.0, 120.0, 60.0, 0.0);
        let d = fp(200.0, 235.0, 120.0, 60.0, 180.0);
        assert!(!back_to_back(&c, &d));
        // A sofa backing onto a narrower console behind it.
        let sofa = fp(200.0, 200.0, 220.0, 90.0, 0.0);
        let console = fp(210.0, 135.0, 140.0, 35.0, 180.0);
        assert!(back_to_back(&console, &sofa));
    }

    #[test]
    fn relations_read_a_part_as_a_piece_flat_on_its_wall() {
        let fp0 = Footprint::new;
        let mut r = Room::rect(500.0, 400.0);
        r.doors.push(crate::room::Door::new(0, 100.0, 90.0));
        r.windows.push(crate::room::Window {
            wall: 2,
            at: 150.0,
            width: 120.0,
            sill: 90.0,
            height: 120.0,
        });
        let window = crate::targets::room_part_footprint(&r, "window-0").unwrap();
        // An armchair in the middle of the room, turned to the window (front +y).
        let chair = fp0(DVec2::new(350.0, 200.0), 80.0, 80.0, 0.0);
        assert!(facing(&chair, &window));
        assert!(
            opposite(&chair, &window),
            "the window looks into the room at it"
        );
        assert!(!near(&chair, &window), "160 cm away");
        let turned = fp0(DVec2::new(350.0, 200.0), 80.0, 80.0, 90.0);
        assert!(!facing(&turned, &window));
        // A desk against the top wall under the window is near it.
        let desk = fp0(DVec2::new(350.0, 370.0), 120.0, 60.0, 180.0);
        assert!(near(&desk, &window));
        let door = crate::targets::room_part_footprint(&r, "door-0").unwrap();
        let printer = fp0(DVec2::new(200.0, 30.0), 50.0, 50.0, 0.0);
        assert!(near(&printer, &door), "gap 30 cm along the wall");
        // Beside the door: on its wall, past the end of its span.
        assert!(beside_part(&printer, &door));
        let out_in_the_room = fp0(DVec2::new(200.0, 90.0), 50.0, 50.0, 0.0);
        assert!(
            !beside_part(&out_in_the_room, &door),
            "60 cm out from the wall"
        );
        let in_front = fp0(DVec2::new(100.0, 40.0), 50.0, 50.0, 0.0);
        assert!(
            !beside_part(&in_front, &door),
            "in front of the span, not beside it"
        );
    }

    #[test]
    fn a_target_may_be_a_part_of_the_room() {
        use crate::layout::PlacedObject;
        let mut room = Room::rect(400.0, 300.0);
        room.windows.push(crate::room::Window {
            wall: 1,
            at: 150.0,
            width: 100.0,
            sill: 80.0,
            height: 120.0,
        });
        let chair = fp(200.0, 150.0, 60.0, 60.0, 90.0); // facing +x, at the right wall's window
        let none = |_: &str| None::<Footprint>;
        let faces = ConstraintKind::Facing {
            target: "window-0".into(),
        };
        assert!(faces.holds(&chair, &room, none));
        assert!(!faces.holds(&fp(200.0, 150.0, 60.0, 60.0, 0.0), &room, none));
        let near_it = ConstraintKind::Relation {
            relation: Relation::Near,
            target: "window-0".into(),
        };
        assert!(!near_it.holds(&chair, &room, none), "170 cm away");
        assert!(near_it.holds(&fp(360.0, 150.0, 60.0, 60.0, 270.0), &room, none));
        // An object named like a part wins over the part.
        let lamp = PlacedObject {
            name: "window-0".into(),
            category: "lamp".into(),
            size: [30.0, 30.0, 150.0],
            position: [40.0, 40.0],
            rotation: 0.0,
            elevation: 0.0,
            on: None,
            wall: None,
        };
        let find = |n: &str| (n == "window-0").then(|| lamp.footprint());
        assert!(!faces.holds(&chair, &room, find));
        assert!(
            !ConstraintKind::Facing {
                target: "door-3".into()
            }
            .holds(&chair, &room, none),
            "no such door"
        );
    }

    #[test]
    fn the_far_corner_of_a_zone_is_the_zones_own() {
        // An L: the long arm along the bottom (650 x 300), the short arm up the left (x 0-300,
        // y 300-550); the door on the right wall. The room's farthest corner, (0, 550), ends the
        // short arm; the main area's farthest is (0, 0).
        let mut room = Room::from_polygon(vec![
            [0.0, 0.0],
            [650.0, 0.0],
            [650.0, 300.0],
            [300.0, 300.0],
            [300.0, 550.0],
            [0.0, 550.0],
        ]);
        room.doors.push(crate::room::Door::new(1, 150.0, 90.0));
        let plant_low = fp(22.0, 22.0, 40.0, 40.0, 0.0);
        let plant_high = fp(22.0, 528.0, 40.0, 40.0, 180.0);
        let far = Place {
            far_corner: true,
            ..Default::default()
        };
        let far_in_main = Place {
            zone: Some("main".into()),
            far_corner: true,
            ..Default::default()
        };
        assert!(placed_as_asked(&plant_high, &room, &far));
        assert!(!placed_as_asked(&plant_low, &room, &far));
        assert!(placed_as_asked(&plant_low, &room, &far_in_main));
        assert!(
            !placed_as_asked(&plant_high, &room, &far_in_main),
            "not in main"
        );
    }

    #[test]
    fn against_wall_predicate() {
        let room = Room::rect(400.0, 350.0);
        assert!(against_wall(&bed(), &room));
        assert!(!against_wall(&fp(200.0, 240.0, 160.0, 210.0, 180.0), &room));
    }

    #[test]
    fn relation_dispatch_matches_predicates() {
        let table = fp(200.0, 200.0, 120.0, 80.0, 0.0);
        let chair = fp(200.0, 135.0, 45.0, 45.0, 0.0);
        for r in Relation::ALL {
            let direct = match r {
                Relation::Near => near(&chair, &table),
                Relation::SideOf => side_of(&chair, &table),
                Relation::InFrontOf => in_front_of(&chair, &table),
                Relation::AlignedWith => aligned_with(&chair, &table),
                Relation::Opposite => opposite(&chair, &table),
                Relation::Around => around(&chair, &table),
                Relation::On => on_top_of(&chair, &table),
                Relation::Above => hung_above(&chair, &table),
                Relation::BackToBack => back_to_back(&chair, &table),
            };
            assert_eq!(r.holds(&chair, &table), direct, "{r}");
        }
    }

    #[test]
    fn a_lamp_is_on_its_nightstand_only_within_its_top() {
        let stand = fp(100.0, 30.0, 50.0, 40.0, 0.0);
        assert!(on_top_of(&fp(100.0, 30.0, 30.0, 30.0, 0.0), &stand));
        assert!(on_top_of(&fp(110.0, 25.0, 30.0, 30.0, 0.0), &stand));
        assert!(!on_top_of(&fp(120.0, 30.0, 30.0, 30.0, 0.0), &stand));
        assert!(!on_top_of(&fp(100.0, 30.0, 60.0, 30.0, 0.0), &stand));
    }

    #[test]
    fn a_painting_is_above_the_bed_when_centred_on_the_wall_behind_it() {
        // The bed's back on the bottom wall (y = 0), facing +y.
        let bed = fp(200.0, 105.0, 160.0, 210.0, 0.0);
        let painting = |x: f64, y: f64, r: f64| fp(x, y, 100.0, 4.0, r);
        assert!(hung_above(&painting(200.0, 2.0, 0.0), &bed));
        assert!(
            hung_above(&painting(225.0, 2.0, 0.0), &bed),
            "a fifth of 160 is 32"
        );
        assert!(!hung_above(&painting(250.0, 2.0, 0.0), &bed), "off centre");
        assert!(
            !hung_above(&painting(200.0, 60.0, 0.0), &bed),
            "not on the wall"
        );
        assert!(
            !hung_above(&painting(200.0, 2.0, 180.0), &bed),
            "turned to the wall"
        );
    }
}
