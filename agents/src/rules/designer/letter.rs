//! Formations shaped like a letter: a U of tables with their seats round the outside, open to
//! its focus (or to the wall opposite the door), and an L of two desks in a corner with the
//! chair in the crook. Each gives the variants [`formation`](super::formation) picks from (the
//! one where most members fit, the first among equals), every pose computed exactly by
//! `disco_tools::formation` ([`u_tables`](shape::u_tables), [`l_workstation`](shape::l_workstation)).

use std::collections::HashMap;

use glam::DVec2;

use super::brief::{GroupBrief, target_of};
use disco_core::geometry::{Footprint, normalize_degrees};
use disco_core::placement::{Pose, facing_rotation};
use disco_core::plan::{Formation, WallRole};
use disco_core::scene::Asset;
use disco_tools::formation::{self as shape, CHAIR_GAP_CM, LSpec, Size, TABLE_GAP_CM, UTablesSpec};

/// Distances (cm) from the focus's front to the U's open end tried, the first preferred.
const U_OPENINGS: [f64; 4] = [100.0, 140.0, 70.0, 180.0];

/// Clear floor (cm) the U keeps from the walls when it can: a walkway behind its seats.
const U_WALKWAY_CM: f64 = 45.0;

/// Sideways slides (cm) of the U tried, when the room cuts the centred one short.
const U_SHIFTS: [f64; 9] = [0.0, -40.0, 40.0, -80.0, 80.0, -120.0, 120.0, -160.0, 160.0];

/// The size of `a` seen from above.
fn size(a: &Asset) -> Size {
    Size::new(a.size[0], a.size[1])
}

/// Variants of a U of tables: `members` are the formation's assets present (tables, then
/// seats), `focus` where the focus stands. Each seat goes to the table the plan ties it to
/// (else to the table with fewest), at most as many per table as fit along it (`count`, when
/// the plan gives it, caps them too).
pub(super) fn u_variants(
    brief: &GroupBrief<'_>,
    f: &Formation,
    members: &[&Asset],
    focus: Option<Footprint>,
) -> Vec<HashMap<String, Pose>> {
    let Some(first) = members.first() else {
        return Vec::new();
    };
    let (tables, seats): (Vec<&Asset>, Vec<&Asset>) =
        members.iter().partition(|a| a.category == first.category);
    let table = size(first);
    let seat = seats.first().map_or(Size::new(50.0, 50.0), |s| size(s));
    let fit = ((table.width / seat.width).floor() as usize).min(f.count.unwrap_or(usize::MAX));
    let mut at: Vec<Vec<&Asset>> = vec![Vec::new(); tables.len()];
    let mut loose: Vec<&Asset> = Vec::new();
    for s in &seats {
        let own = target_of(brief.plan, &s.name)
            .and_then(|(_, t)| tables.iter().position(|a| a.name == t))
            .filter(|&k| at[k].len() < fit);
        match own {
            Some(k) => at[k].push(s),
            None => loose.push(s),
        }
    }
    for s in loose {
        if let Some(k) = (0..at.len())
            .filter(|&k| at[k].len() < fit)
            .min_by_key(|&k| (at[k].len(), k))
        {
            at[k].push(s);
        }
    }
    let spec = UTablesSpec {
        seat_gap: TABLE_GAP_CM,
        ..UTablesSpec::new(table, seat, at.iter().map(Vec::len).collect())
    };
    let named = |u: shape::UTables| -> HashMap<String, Pose> {
        let mut out: HashMap<String, Pose> = tables
            .iter()
            .zip(&u.tables)
            .map(|(a, p)| (a.name.clone(), *p))
            .collect();
        out.extend(
            at.iter()
                .flatten()
                .zip(&u.seats)
                .map(|(a, p)| (a.name.clone(), *p)),
        );
        out
    };
    let Ok(probe) = shape::u_tables(DVec2::ZERO, 0.0, &spec) else {
        return Vec::new();
    };
    // The open end's middle, and the way the opening faces.
    let mut starts: Vec<(DVec2, DVec2)> = Vec::new();
    match focus {
        Some(t) => {
            for d in U_OPENINGS {
                starts.push((t.center + t.front * (t.half.y + d), -t.front));
            }
        }
        None => {
            // Open towards the wall opposite the door, the U in the main area's middle.
            let walls = brief.room.walls();
            let towards = brief
                .analysis
                .walls_with(WallRole::OppositeDoor)
                .first()
                .and_then(|&i| walls.get(i))
                .map(|w| {
                    let d = (w.end - w.start).normalize_or_zero();
                    DVec2::new(d.y, -d.x)
                })
                .filter(|v| *v != DVec2::ZERO)
                .unwrap_or(DVec2::Y);
            let middle = brief
                .analysis
                .zones
                .first()
                .map_or(brief.aim, |z| z.centre());
            for back in [0.0, -60.0, 60.0, -120.0, 120.0] {
                starts.push((middle + towards * (probe.depth / 2.0 + back), towards));
            }
        }
    }
    let mut variants = starts
        .into_iter()
        .flat_map(|(at, open)| {
            let side = DVec2::new(open.y, -open.x);
            U_SHIFTS
                .iter()
                .map(move |&dx| (at + side * dx, facing_rotation(DVec2::ZERO, open)))
        })
        .filter_map(|(anchor, rotation)| shape::u_tables(anchor, rotation, &spec).ok())
        .map(named)
        .collect::<Vec<_>>();
    // Those that leave a walkway between every member and the walls first.
    let sizes: HashMap<&str, Size> = members.iter().map(|a| (a.name.as_str(), size(a))).collect();
    let walkable = |v: &HashMap<String, Pose>| {
        v.iter().all(|(n, p)| {
            sizes.get(n.as_str()).is_some_and(|s| {
                Footprint::new(
                    p.center,
                    s.width + 2.0 * U_WALKWAY_CM,
                    s.depth + 2.0 * U_WALKWAY_CM,
                    p.rotation,
                )
                .inside(brief.room)
            })
        })
    };
    variants.sort_by_key(|v| !walkable(v));
    variants
}

/// Variants of an L of desks: `members` are the main desk, the return desk and the chair (if
/// any). Each of the room's corners is tried, farthest from the door first, the main desk on
/// the wall with a window first (else the longer wall); the chair in the crook facing the main
/// desk.
pub(super) fn l_variants(
    brief: &GroupBrief<'_>,
    f: &Formation,
    members: &[&Asset],
) -> Vec<HashMap<String, Pose>> {
    let [main, ret, rest @ ..] = members else {
        return Vec::new();
    };
    // Both desks must be in the group (the plan ties them): never a chair as the return.
    if f.members.get(1) != Some(&ret.name) {
        return Vec::new();
    }
    let chair = rest.first();
    let spec = LSpec {
        desk_a: size(main),
        desk_b: size(ret),
        chair: chair.map_or(Size::new(50.0, 50.0), |c| size(c)),
        chair_gap: CHAIR_GAP_CM,
    };
    let outline = brief.room.outline();
    let n = outline.len();
    let windowed = |wall: usize| brief.room.windows.iter().any(|w| w.wall == wall);
    let mut out = Vec::new();
    for c in &brief.analysis.corners {
        let v = c.vertex % n;
        let p = outline[v];
        // Wall v runs on from the corner, wall v - 1 comes into it.
        let (next, prev) = ((v + 1) % n, (v + n - 1) % n);
        let along_next = (v, outline[next] - p);
        let along_prev = (prev, outline[prev] - p);
        let rank = |(w, d): (usize, DVec2)| (windowed(w), d.length());
        let mut orders = [(along_next, along_prev), (along_prev, along_next)];
        let (before, after) = (rank(along_prev), rank(along_next));
        if before > after {
            orders.swap(0, 1);
        }
        for ((_, a), (_, b)) in orders {
            let Ok(ws) = shape::l_workstation(p, a, b, &spec) else {
                continue;
            };
            let mut poses = HashMap::new();
            poses.insert(main.name.clone(), ws.desks[0]);
            poses.insert(ret.name.clone(), ws.desks[1]);
            if let (Some(ch), Some(at)) = (chair, ws.chairs.first()) {
                // Turned to the main desk, square to it.
                poses.insert(
                    ch.name.clone(),
                    Pose {
                        center: at.center,
                        rotation: normalize_degrees(ws.desks[0].rotation + 180.0),
                    },
                );
            }
            out.push(poses);
        }
    }
    out
}
