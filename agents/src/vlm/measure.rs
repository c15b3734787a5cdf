//! What a constraint's words mean, in words and numbers, and what the layout measures for it.
//!
//! The final metric grades every constraint with the predicates of `disco_core::relations`; a
//! model asked "is the sideboard near the table?" answers from its own sense unless it is told
//! the predicate ("near: the shortest gap between the two footprints is at most 50 cm") and the
//! measured values ("gap now 130 cm"). [`meaning`] gives the first, [`measure`] the second and
//! the predicate's own verdict, so the prompts state both and a model's answer can be checked.

use glam::DVec2;

use disco_core::geometry::{Footprint, Wall};
use disco_core::layout::{Layout, PlacedObject};
use disco_core::plan::{Place, Relation};
use disco_core::relations::{
    ALIGN_TOL_CM, BACK_GAP_CM, BACK_TURN_DEG, CENTRED_TOL_CM, ConstraintKind, FRONT_GAP_CM,
    NEAR_GAP_CM, ON_WALL_CM, check_one,
};
use disco_core::targets::RoomPart;

/// What one constraint measures on a layout.
#[derive(Debug, Clone, PartialEq)]
pub struct Measured {
    /// Whether the metric's predicate holds.
    pub holds: bool,
    /// The measured values in words: `gap 130 cm`, `its front is turned 29° away from table-0`.
    pub values: String,
}

/// The predicate the metric uses for `kind` (with `target` its other object), in words and
/// numbers, e.g. `near means the shortest gap between the two footprints is at most 50 cm`.
pub fn meaning(kind: &ConstraintKind) -> String {
    match kind {
        ConstraintKind::AgainstWall => {
            "against a wall means its back edge lies on a wall (within 1 cm), clear of doors and of windows whose sill is lower than it is tall, its front into the room".into()
        }
        ConstraintKind::Facing { target } => format!(
            "faces means the line straight out of the middle of its front meets {target}'s footprint"
        ),
        ConstraintKind::Relation { relation, target } => match relation {
            Relation::Near => format!(
                "near means the shortest gap between its footprint and {target}'s is at most {} cm",
                NEAR_GAP_CM
            ),
            Relation::SideOf if RoomPart::parse(target).is_some() => format!(
                "beside {target} means it stands along {target}'s wall, its centre past one end of {target}'s span and no farther from that wall than half its own size and {} cm, the gap between them at most {} cm",
                ALIGN_TOL_CM, NEAR_GAP_CM
            ),
            Relation::SideOf => format!(
                "beside means its centre lies past {target}'s left or right edge, within {target}'s front-to-back span, and the gap between them is at most {} cm",
                NEAR_GAP_CM
            ),
            Relation::InFrontOf => format!(
                "in front of means its centre lies past {target}'s front edge, within {target}'s width, and the gap between them is at most {} cm",
                FRONT_GAP_CM
            ),
            Relation::AlignedWith => format!(
                "aligned with means its centre lies within {} cm of one of {target}'s two centre lines, or both face the same way with their back edges on one line (within {} cm)",
                ALIGN_TOL_CM, ALIGN_TOL_CM
            ),
            Relation::Opposite => "opposite means the two face each other: the line straight out of each one's front meets the other's footprint".to_string(),
            Relation::Around => format!(
                "around means the gap to {target} is at most {} cm and the line straight out of its front meets {target}'s footprint",
                NEAR_GAP_CM
            ),
            Relation::On => format!(
                "on means, seen from above, its footprint lies within {target}'s top (1 cm margin), standing at the height of that top"
            ),
            Relation::Above => format!(
                "above means it hangs on the wall {target} stands against, over {target} (within its width, reaching past it by at most a tenth of it, or centred on it within {} cm), turned the same way",
                CENTRED_TOL_CM
            ),
            Relation::BackToBack => format!(
                "back to back means the two are turned opposite ways (within {} degrees), each stands behind the other's back edge, and the gap between them is at most {} cm",
                BACK_TURN_DEG, BACK_GAP_CM
            ),
        },
        ConstraintKind::Place(place) => format!(
            "{place} means: {}",
            place_meaning(place)
        ),
    }
}

/// The parts of a place request, each as the metric checks it.
fn place_meaning(place: &Place) -> String {
    let mut parts = Vec::new();
    if place.zone.is_some() {
        parts.push("its centre lies in that zone".to_string());
    }
    if place.wall.is_some() {
        parts.push(format!(
            "its back is on a wall of that role (a free-standing piece: within {ON_WALL_CM} cm of one)"
        ));
    }
    if place.far_corner {
        parts.push(
            "it comes within 40 cm of the corner farthest from the main door (of the zone named, when one is)"
                .into(),
        );
    }
    if place.under_window {
        parts.push(
            "the middle of its back edge lies on a window's span, within 20 cm of the window"
                .into(),
        );
    }
    if place.by_entrance {
        parts.push("some corner of it is within 180 cm of the main door's centre".into());
    }
    parts.join("; ")
}

/// What the layout measures for `subject`'s constraint `kind`, with the predicate's verdict;
/// `None` when the subject or the target is not placed.
pub fn measure(layout: &Layout, subject: &str, kind: &ConstraintKind) -> Option<Measured> {
    let a = layout.object(subject)?.footprint();
    let holds = check_one(layout, subject, kind);
    let values = match kind {
        ConstraintKind::AgainstWall => wall_values(&a, layout),
        ConstraintKind::Place(place) => place_values(&a, layout, place),
        ConstraintKind::Facing { target } => {
            let b = layout.target_footprint(target)?;
            turn_words(&a, &b, target)
        }
        ConstraintKind::Relation { relation, target } => {
            let b = layout.target_footprint(target)?;
            let values = match relation {
                Relation::SideOf if layout.object(target).is_none() => {
                    part_side_values(&a, &b, target)
                }
                _ => relation_values(*relation, &a, &b, subject, target),
            };
            match layout
                .object(subject)
                .zip(layout.object(target))
                .and_then(|(s, t)| height_values(*relation, s, t))
            {
                Some(heights) => format!("{values}; {heights}"),
                None => values,
            }
        }
    };
    Some(Measured { holds, values })
}

/// What "beside" a door, a window or a wall measures: how far past the end of its span along
/// the wall, how far from the wall, and the gap.
fn part_side_values(a: &Footprint, part: &Footprint, target: &str) -> String {
    let l = part.to_local(a.center);
    let past = l.x.abs() - part.half.x;
    format!(
        "its centre is {} cm {} the end of {target}'s span along the wall and {} cm from the wall; gap {} cm",
        cm(past.abs()),
        if past >= 0.0 { "past" } else { "short of" },
        cm((l.y + part.half.y).max(0.0)),
        cm(a.gap(part))
    )
}

fn relation_values(
    relation: Relation,
    a: &Footprint,
    b: &Footprint,
    subject: &str,
    target: &str,
) -> String {
    let gap = format!("gap {} cm", cm(a.gap(b)));
    let l = b.to_local(a.center);
    match relation {
        Relation::Near => gap,
        Relation::SideOf => {
            let side = if l.x >= 0.0 { "right" } else { "left" };
            let past = l.x.abs() - b.half.x;
            let span = l.y.abs() - b.half.y;
            format!(
                "its centre is {} cm {} {target}'s {side} edge and {}; {gap}",
                cm(past.abs()),
                if past >= 0.0 { "past" } else { "short of" },
                if span <= 0.0 {
                    "within its front-to-back span".to_string()
                } else {
                    format!("{} cm outside its front-to-back span", cm(span))
                }
            )
        }
        Relation::InFrontOf => {
            let ahead = l.y - b.half.y;
            let wide = l.x.abs() - b.half.x;
            format!(
                "its centre is {} cm {} {target}'s front edge and {}; {gap}",
                cm(ahead.abs()),
                if ahead > 0.0 { "past" } else { "behind" },
                if wide <= 0.0 {
                    "within its width".to_string()
                } else {
                    format!("{} cm to the side of its width", cm(wide))
                }
            )
        }
        Relation::AlignedWith => format!(
            "its centre is {} cm from {target}'s nearest centre line",
            cm(l.x.abs().min(l.y.abs()))
        ),
        Relation::Opposite => format!(
            "{}; {}",
            turn_words(a, b, target),
            turn_words(b, a, subject).replacen("its front", &format!("{target}'s front"), 1)
        ),
        Relation::Around => format!("{gap}; {}", turn_words(a, b, target)),
        Relation::On => {
            let past = a
                .corners()
                .iter()
                .map(|&c| {
                    let l = b.to_local(c);
                    (l.x.abs() - b.half.x).max(l.y.abs() - b.half.y)
                })
                .fold(f64::NEG_INFINITY, f64::max);
            if past <= 0.0 {
                format!("its footprint lies within {target}'s top")
            } else {
                format!("it reaches {} cm past the edge of {target}'s top", cm(past))
            }
        }
        Relation::Above => format!(
            "its centre is {} cm off {target}'s centre line; its back is {} cm from {target}'s back",
            cm(l.x.abs()),
            cm((b.to_local(a.back_center()).y + b.half.y).abs())
        ),
        Relation::BackToBack => {
            let turn = a.front.dot(b.front).clamp(-1.0, 1.0).acos().to_degrees();
            format!(
                "the two are turned {} degrees apart (opposite is 180); its centre is {} cm {} {target}'s back edge; {gap}",
                cm(turn),
                cm((l.y + b.half.y).abs()),
                if l.y < -b.half.y {
                    "behind"
                } else {
                    "in front of"
                }
            )
        }
    }
}

/// The heights that go with `on` and `above`: where the subject's bottom is against the
/// target's top, and for `above` the wall it hangs on; `None` for the other relations.
fn height_values(relation: Relation, s: &PlacedObject, t: &PlacedObject) -> Option<String> {
    match relation {
        Relation::On => Some(format!(
            "its bottom is {} cm above the floor, {}'s top {} cm{}",
            cm(s.elevation),
            t.name,
            cm(t.top()),
            match &s.on {
                Some(on) if *on == t.name => String::new(),
                Some(on) => format!("; it stands on {on}"),
                None => "; it stands on nothing".to_string(),
            }
        )),
        Relation::Above => {
            let gap = s.elevation - t.top();
            Some(format!(
                "its bottom is {} cm {} {}'s top{}",
                cm(gap.abs()),
                if gap >= 0.0 { "above" } else { "below" },
                t.name,
                match s.wall {
                    Some(w) => format!("; it hangs on wall {w}"),
                    None => "; it hangs on no wall".to_string(),
                }
            ))
        }
        _ => None,
    }
}

/// Whether `a`'s front line meets `b`, and if not how far it is turned from `b`'s centre.
fn turn_words(a: &Footprint, b: &Footprint, target: &str) -> String {
    if a.front_ray_hit(b).is_some() {
        return format!("the line out of its front meets {target}");
    }
    let to = b.center - a.center;
    let angle = if to.length() < 1e-9 {
        0.0
    } else {
        a.front.angle_to(to).to_degrees().abs()
    };
    format!(
        "its front is turned {}° away from {target}'s centre (the line out of its front misses {target})",
        angle.round()
    )
}

fn wall_values(a: &Footprint, layout: &Layout) -> String {
    let back = a.back_center();
    let nearest = Wall::all(&layout.room)
        .into_iter()
        .map(|w| (w.segment_distance(back), w.index()))
        .min_by(|x, y| x.0.total_cmp(&y.0));
    match nearest {
        Some((d, i)) => format!("the middle of its back edge is {} cm from wall {i}", cm(d)),
        None => "the room has no walls".into(),
    }
}

fn place_values(a: &Footprint, layout: &Layout, place: &Place) -> String {
    let room = &layout.room;
    let analysis = room.analysis();
    let mut parts = Vec::new();
    if place.zone.is_some() {
        let zone = analysis
            .zones
            .iter()
            .find(|z| z.contains(a.center, 1.0))
            .map_or("no zone".to_string(), |z| format!("zone {}", z.name));
        parts.push(format!("its centre is in {zone}"));
    }
    if let Some(role) = place.wall {
        let asked = analysis.walls_with(role);
        let asked = match asked.as_slice() {
            [] => "no wall has that role".to_string(),
            [one] => format!("the wall of that role is wall {one}"),
            many => format!(
                "the walls of that role are {}",
                many.iter()
                    .map(|i| format!("wall {i}"))
                    .collect::<Vec<_>>()
                    .join(", ")
            ),
        };
        let on = match a.against_wall(room) {
            Some(w) => format!("its back is on wall {}", w.index()),
            None => format!("it stands free ({})", wall_values(a, layout)),
        };
        parts.push(format!("{on}; {asked}"));
    }
    if place.under_window {
        let back = {
            let (l, r) = a.back_edge();
            (l + r) / 2.0
        };
        let nearest = room
            .windows
            .iter()
            .enumerate()
            .filter_map(|(i, w)| {
                let (s, e) = room.opening_ends(w.wall, w.at, w.width)?;
                Some((disco_core::room::distance_to_segment(back, s, e), i))
            })
            .min_by(|x, y| x.0.total_cmp(&y.0));
        parts.push(match nearest {
            Some((d, i)) => format!(
                "the middle of its back edge is {} cm from window {i}'s span",
                cm(d)
            ),
            None => "the room has no window".into(),
        });
    }
    if place.far_corner
        && let Some(c) = analysis.far_corner(place.zone.as_deref())
    {
        let p = DVec2::new(c.at[0], c.at[1]);
        let d = a
            .corners()
            .iter()
            .map(|k| k.distance(p))
            .fold(f64::INFINITY, f64::min);
        parts.push(format!(
            "its nearest corner is {} cm from the far corner",
            cm(d)
        ));
    }
    if place.by_entrance
        && let Some(d) = analysis.main_door.and_then(|i| room.doors.get(i))
        && let Some((s, e)) = room.opening_ends(d.wall, d.at, d.width)
    {
        let door = (s + e) / 2.0;
        let dist = a
            .corners()
            .iter()
            .map(|k| k.distance(door))
            .fold(f64::INFINITY, f64::min);
        parts.push(format!(
            "its nearest corner is {} cm from the main door",
            cm(dist)
        ));
    }
    parts.join("; ")
}

/// A length in whole centimetres.
fn cm(v: f64) -> String {
    format!("{}", v.round() as i64)
}

#[cfg(test)]
mod tests {
    use super::*;
    use disco_core::layout::PlacedObject;
    use std::sync::Arc;

    fn object(name: &str, at: [f64; 2], size: [f64; 2], rotation: f64) -> PlacedObject {
        PlacedObject {
            name: name.into(),
            category: name.trim_end_matches("-0").into(),
            size: [size[0], size[1], 80.0],
            position: at,
            rotation,
            ..Default::default()
        }
    }

    fn layout(objects: Vec<PlacedObject>) -> Layout {
        Layout {
            id: "t".into(),
            room: disco_core::scene::Room::rect(600.0, 500.0),
            objects,
            dropped: Vec::new(),
            plan: Arc::default(),
            stats: Default::default(),
        }
    }

    fn near(target: &str) -> ConstraintKind {
        ConstraintKind::Relation {
            relation: Relation::Near,
            target: target.into(),
        }
    }

    #[test]
    fn near_states_the_fifty_centimetres_and_the_measured_gap() {
        assert!(meaning(&near("table-0")).contains("at most 50 cm"));
        // A 200 x 100 table at (300, 250); a sideboard whose near edge is 130 cm right of it.
        let l = layout(vec![
            object("table-0", [300.0, 250.0], [200.0, 100.0], 0.0),
            object("sideboard-0", [550.0, 250.0], [100.0, 40.0], 270.0),
        ]);
        let m = measure(&l, "sideboard-0", &near("table-0")).unwrap();
        assert!(!m.holds);
        assert_eq!(m.values, "gap 130 cm");
    }

    #[test]
    fn on_and_above_give_the_heights_and_what_holds_the_piece() {
        let on = |t: &str| ConstraintKind::Relation {
            relation: Relation::On,
            target: t.into(),
        };
        let above = |t: &str| ConstraintKind::Relation {
            relation: Relation::Above,
            target: t.into(),
        };
        let stand = object("nightstand-0", [100.0, 480.0], [50.0, 40.0], 180.0);
        let lamp = PlacedObject {
            size: [30.0, 30.0, 50.0],
            elevation: 80.0,
            on: Some("nightstand-0".into()),
            ..object("lamp-0", [100.0, 480.0], [30.0, 30.0], 180.0)
        };
        let bed = object("bed-0", [300.0, 400.0], [160.0, 200.0], 180.0);
        let painting = PlacedObject {
            size: [100.0, 4.0, 70.0],
            elevation: 95.0,
            wall: Some(2),
            ..object("painting-0", [300.0, 498.0], [100.0, 4.0], 180.0)
        };
        let l = layout(vec![stand, lamp, bed, painting]);
        let m = measure(&l, "lamp-0", &on("nightstand-0")).unwrap();
        assert_eq!(
            m.values,
            "its footprint lies within nightstand-0's top; its bottom is 80 cm above the floor, nightstand-0's top 80 cm"
        );
        let m = measure(&l, "painting-0", &above("bed-0")).unwrap();
        assert!(
            m.values
                .ends_with("its bottom is 15 cm above bed-0's top; it hangs on wall 2"),
            "{}",
            m.values
        );
        // A lamp that stands on nothing says so.
        let mut l = l;
        l.objects[1].on = None;
        let m = measure(&l, "lamp-0", &on("nightstand-0")).unwrap();
        assert!(m.values.ends_with("; it stands on nothing"), "{}", m.values);
    }

    #[test]
    fn facing_gives_the_angle_turned_away() {
        let l = layout(vec![
            object("tv-0", [300.0, 450.0], [150.0, 40.0], 180.0),
            // At (300, 100), turned 45° clockwise: its front points up-right; the TV is straight up.
            object("sofa-0", [300.0, 100.0], [200.0, 90.0], 45.0),
        ]);
        let kind = ConstraintKind::Facing {
            target: "tv-0".into(),
        };
        let m = measure(&l, "sofa-0", &kind).unwrap();
        assert!(!m.holds);
        assert!(
            m.values.contains("turned 45° away from tv-0"),
            "{}",
            m.values
        );
        assert!(meaning(&kind).contains("line straight out of the middle of its front"));
    }

    #[test]
    fn opposite_measures_both_ways() {
        let l = layout(vec![
            object("tv-0", [300.0, 450.0], [150.0, 40.0], 180.0),
            object("sofa-0", [300.0, 100.0], [200.0, 90.0], 0.0),
        ]);
        let kind = ConstraintKind::Relation {
            relation: Relation::Opposite,
            target: "tv-0".into(),
        };
        let m = measure(&l, "sofa-0", &kind).unwrap();
        assert!(m.holds);
        assert!(
            m.values.contains("the line out of its front meets tv-0")
                && m.values.contains("meets sofa-0"),
            "{}",
            m.values
        );
        assert!(meaning(&kind).contains("face each other"));
    }

    #[test]
    fn in_front_and_beside_say_where_the_centre_lies() {
        let l = layout(vec![
            object("desk-0", [300.0, 30.0], [120.0, 60.0], 0.0),
            object("chair-0", [300.0, 110.0], [50.0, 50.0], 180.0),
            object("cabinet-0", [420.0, 30.0], [40.0, 60.0], 0.0),
        ]);
        let front = ConstraintKind::Relation {
            relation: Relation::InFrontOf,
            target: "desk-0".into(),
        };
        let m = measure(&l, "chair-0", &front).unwrap();
        assert!(m.holds);
        assert!(
            m.values
                .contains("50 cm past desk-0's front edge and within its width"),
            "{}",
            m.values
        );
        let beside = ConstraintKind::Relation {
            relation: Relation::SideOf,
            target: "desk-0".into(),
        };
        let m = measure(&l, "cabinet-0", &beside).unwrap();
        assert!(m.holds, "{}", m.values);
        assert!(
            m.values.contains("past desk-0's right edge"),
            "{}",
            m.values
        );
        assert!(measure(&l, "chair-0", &near("ghost-0")).is_none());
    }

    #[test]
    fn a_place_says_which_zone_and_wall_the_piece_is_in_now() {
        let mut room = disco_core::scene::Room::from_polygon(vec![
            [0.0, 0.0],
            [500.0, 0.0],
            [500.0, 250.0],
            [280.0, 250.0],
            [280.0, 420.0],
            [0.0, 420.0],
        ]);
        room.doors.push(disco_core::room::Door::new(1, 125.0, 85.0));
        let mut l = layout(vec![
            object("armchair-0", [400.0, 100.0], [80.0, 80.0], 0.0),
            object("shelf-0", [300.0, 17.5], [80.0, 35.0], 0.0),
        ]);
        l.room = room;
        let zone = ConstraintKind::Place(Place {
            zone: Some("recess".into()),
            ..Default::default()
        });
        let m = measure(&l, "armchair-0", &zone).unwrap();
        assert!(!m.holds);
        assert_eq!(m.values, "its centre is in zone main");
        let wall = ConstraintKind::Place(Place {
            wall: Some(disco_core::room::analysis::WallRole::OppositeDoor),
            ..Default::default()
        });
        let m = measure(&l, "shelf-0", &wall).unwrap();
        assert!(!m.holds);
        assert_eq!(
            m.values,
            "its back is on wall 0; the wall of that role is wall 5"
        );
        assert!(meaning(&wall).contains("its back is on a wall of that role"));
    }
}
