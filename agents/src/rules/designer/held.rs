//! Poses for the pieces the plan takes off the floor (its `support`): on the top of the piece
//! they stand `on`, or on a wall (centred `above` a piece, across from one, or on the widest
//! free stretch of wall). They are posed after the floor pieces of their group, so their
//! supports stand already; the PRT checks them in 3D afterwards and moves what does not hold.
//!
//! - **On a top**: turned as the support is (a TV on its stand faces where the stand faces, a
//!   monitor towards the desk's seat). A piece about as wide as the top, or the only one on a
//!   small top (a lamp on a nightstand), stands in the middle of its width at the back; on a
//!   big top the first small piece takes a back corner. Failing that, the nearest free point
//!   of the top.
//! - **On a wall**: its back on the wall, its front into the room. Above a piece: centred on it,
//!   the mount's `gap` above its top. Across from a piece: where the piece's front looks at the
//!   wall, its centre at the mount's `height`. Else the middle of the widest free stretch at
//!   that height (openings, and floor pieces reaching that high, cut the stretches).

use std::collections::HashMap;

use glam::DVec2;

use crate::hanging::{
    CEILING_CM, STEP_CM, bottom_for_centre, clear, on_wall, slide, spots_on_wall, widest,
};
use crate::knowledge::{Knowledge, Mount};
use crate::rules::mounting::ROW_GAP_CM;
use disco_core::geometry::{Footprint, Wall, normalize_degrees};
use disco_core::geometry3d::surface_problem;
use disco_core::layout::PlacedObject;
use disco_core::plan::{Plan, Relation};
use disco_core::scene::{Asset, Room, SceneSpec, Support};

/// How much higher (cm) than its kind's height a piece hung above another may have its centre.
const ABOVE_HANG_CM: f64 = 40.0;

/// How far (cm) a wall piece may slide along its wall from where it was meant to hang (across
/// from a piece; above one, no further than keeps it over the piece) before the free-stretch
/// search takes over.
const SLIDE_CM: f64 = 120.0;

/// Poses for the `held` pieces of a group, posed after `placed` (earlier groups and this
/// group's floor pieces), in order.
pub(super) fn place_held(
    knowledge: &Knowledge,
    room: &Room,
    plan: &Plan,
    held: &[&Asset],
    placed: &[PlacedObject],
) -> Vec<PlacedObject> {
    let mut now: Vec<PlacedObject> = placed.to_vec();
    let mut out = Vec::with_capacity(held.len());
    for asset in held {
        let mount = knowledge
            .kind_of(asset)
            .mount_for(asset)
            .unwrap_or_else(|| Mount::plain(plan.support_of(&asset.name).unwrap_or(Support::Wall)));
        let relation = plan
            .constraints
            .get(&asset.name)
            .and_then(|c| c.relations.first())
            .map(|r| (r.relation, r.target.clone()));
        let find = |n: &str| now.iter().find(|o| o.name == n).cloned();
        let posed = match plan.support_of(&asset.name) {
            Some(Support::Surface) => {
                let support = relation
                    .filter(|(r, _)| *r == Relation::On)
                    .and_then(|(_, t)| find(&t));
                match support {
                    Some(s) => on_top(room, plan, held, asset, &s, &now),
                    // Its support was not placed: the PRT stands it on the floor, with a note.
                    None => None,
                }
            }
            Some(Support::Wall) => {
                let wanted = match relation {
                    Some((Relation::Above, t)) => {
                        find(&t).and_then(|s| above(room, plan, held, asset, &mount, &s, &now))
                    }
                    Some((Relation::Opposite, t)) => {
                        find(&t).and_then(|s| across(room, asset, &mount, &s, &now))
                    }
                    _ => None,
                };
                // A wall asked by its role ("on the wall opposite the entrance") comes first.
                let role = plan
                    .constraints
                    .get(&asset.name)
                    .and_then(|c| c.place.as_ref())
                    .and_then(|p| p.wall);
                let on_role = role.and_then(|r| {
                    let walls = room.analysis().walls_with(r);
                    free_wall(room, asset, &mount, &now, |i| walls.contains(&i))
                });
                on_role
                    .or(wanted)
                    .or_else(|| free_wall(room, asset, &mount, &now, |_| true))
            }
            _ => None,
        };
        let obj = posed.unwrap_or_else(|| parked(room, asset, plan, &now));
        now.push(obj.clone());
        out.push(obj);
    }
    out
}

/// Where a piece that found no place off the floor is left: the room's middle (turned as its
/// support, if it has one and it is placed), still meant to stand on that support, for the PRT
/// to settle (on the support, else on the floor).
fn parked(room: &Room, asset: &Asset, plan: &Plan, now: &[PlacedObject]) -> PlacedObject {
    let on = plan
        .constraints
        .get(&asset.name)
        .and_then(|c| c.relations.first())
        .filter(|r| r.relation == Relation::On)
        .map(|r| r.target.clone());
    let rotation = on
        .as_deref()
        .and_then(|s| now.iter().find(|o| o.name == s))
        .map_or(0.0, |s| s.rotation);
    PlacedObject {
        name: asset.name.clone(),
        category: asset.category.clone(),
        size: asset.size,
        position: [room.width / 2.0, room.depth / 2.0],
        rotation,
        elevation: 0.0,
        on,
        wall: None,
    }
}

/// How much higher (cm) than itself each piece of `group` stands with what the plan puts on its
/// top (the tallest of those), by the piece's name; pieces that hold nothing are left out. One
/// pass over the plan, and a scene lookup only for what stands on a piece of the group.
pub(super) fn load_heights<'g>(
    plan: &Plan,
    scene: &SceneSpec,
    group: &[&'g Asset],
) -> HashMap<&'g str, f64> {
    let members: HashMap<&str, &'g str> = group
        .iter()
        .map(|a| (a.name.as_str(), a.name.as_str()))
        .collect();
    let mut out: HashMap<&'g str, f64> = HashMap::new();
    for (name, c) in &plan.constraints {
        for r in c.relations.iter().filter(|r| r.relation == Relation::On) {
            let (Some(&target), Some(piece)) = (members.get(r.target.as_str()), scene.asset(name))
            else {
                continue;
            };
            let e = out.entry(target).or_insert(0.0);
            *e = e.max(piece.size[2]);
        }
    }
    out
}

/// Whether `o`, on a top, keeps out of the doors' and windows' keep-clear zones that bind
/// something reaching as high as its top (a TV on a stand under a window would block it).
fn clear_of_zones(room: &Room, o: &PlacedObject) -> bool {
    let fp = o.footprint();
    room.keep_clear().iter().all(|z| !fp.intrudes(z, o.top()))
}

/// `asset` on the top of `support`, at the first free spot of [`top_spots`] clear of the
/// keep-clear zones.
fn on_top(
    room: &Room,
    plan: &Plan,
    held: &[&Asset],
    asset: &Asset,
    support: &PlacedObject,
    now: &[PlacedObject],
) -> Option<PlacedObject> {
    let top = support.footprint();
    // The other pieces the plan puts on this top: the widest of them needs room beside a
    // piece in the middle (a speaker beside the TV), else this one takes a back corner.
    let others: Vec<f64> = plan
        .constraints
        .iter()
        .filter(|(n, c)| {
            *n != &asset.name
                && c.relations
                    .iter()
                    .any(|r| r.relation == Relation::On && r.target == support.name)
        })
        .map(|(n, _)| {
            held.iter()
                .find(|a| &a.name == n)
                .map_or(0.0, |a| a.size[0].min(a.size[1]))
        })
        .collect();
    let beside = others.iter().copied().fold(0.0, f64::max);
    for (local, turn) in top_spots(asset.size, support.size, others.len(), beside) {
        let centre = top.center + top.right * local.x + top.front * local.y;
        let cand = PlacedObject {
            name: asset.name.clone(),
            category: asset.category.clone(),
            size: asset.size,
            position: [centre.x, centre.y],
            rotation: normalize_degrees(support.rotation + turn),
            elevation: support.top(),
            on: Some(support.name.clone()),
            wall: None,
        };
        if surface_problem(&cand, support).is_none()
            && clear(&cand, now)
            && clear_of_zones(room, &cand)
        {
            return Some(cand);
        }
    }
    None
}

/// The spots of a `top`-sized top (x across, y towards its front, from its centre) a piece of
/// `size` may take, best first, with the turn relative to the top: the middle of a small top
/// for the only piece on it, the back of the middle for a wide piece that leaves `beside` cm on
/// each side for the `others` pieces meant for the top, else a back corner; then every grid
/// point nearest the back first; turned as the top first, then a quarter.
fn top_spots(size: [f64; 3], top: [f64; 3], others: usize, beside: f64) -> Vec<(DVec2, f64)> {
    let mut out = Vec::new();
    for turn in [0.0, 90.0] {
        let (w, d) = if turn == 0.0 {
            (size[0], size[1])
        } else {
            (size[1], size[0])
        };
        let room = DVec2::new(top[0] - w, top[1] - d) / 2.0;
        if room.x < -1e-9 || room.y < -1e-9 {
            continue;
        }
        let back = -room.y;
        let wide = w >= 0.5 * top[0] && room.x >= beside - 1e-9;
        let small_top = top[0] * top[1] < 4_000.0;
        if (small_top && others == 0) || wide {
            out.push((DVec2::new(0.0, if small_top { 0.0 } else { back }), turn));
        } else {
            // Right-hand back corner first (a desk lamp beside the monitor), then the left.
            out.push((DVec2::new(room.x, back), turn));
            out.push((DVec2::new(-room.x, back), turn));
        }
        let nx = (room.x / STEP_CM).floor() as i64;
        let ny = (room.y / STEP_CM).floor() as i64;
        let mut grid: Vec<DVec2> = (-nx..=nx)
            .flat_map(|i| (-ny..=ny).map(move |j| DVec2::new(i as f64, j as f64) * STEP_CM))
            .collect();
        grid.sort_by(|a, b| {
            let key = |p: &DVec2| (p.y - back).abs() * 2.0 + p.x.abs();
            key(a).total_cmp(&key(b))
        });
        out.extend(grid.into_iter().map(|p| (p, turn)));
    }
    out
}

/// `asset` above `under`, which stands against a wall: the mount's gap above the top of `under`
/// (or of what stands on it, when that is in the way); centred on it, or in its place in the row of the pieces the plan
/// hangs above it (`held`, in name order, [`ROW_GAP_CM`] apart, the row centred on it).
fn above(
    room: &Room,
    plan: &Plan,
    held: &[&Asset],
    asset: &Asset,
    mount: &Mount,
    under: &PlacedObject,
    now: &[PlacedObject],
) -> Option<PlacedObject> {
    let fp = under.footprint();
    let w = fp
        .against_wall(room)
        .or_else(|| nearest_wall_behind(room, &fp))?;
    // The row: every piece the plan hangs above `under`, in name order.
    let mut row: Vec<(&str, f64)> = plan
        .constraints
        .iter()
        .filter(|(_, c)| {
            c.relations
                .iter()
                .any(|r| r.relation == Relation::Above && r.target == under.name)
        })
        .map(|(n, _)| {
            let width = held
                .iter()
                .find(|a| a.name == *n)
                .map_or(asset.size[0], |a| a.size[0]);
            (n.as_str(), width)
        })
        .collect();
    row.sort_by(|a, b| a.0.cmp(b.0));
    let total: f64 =
        row.iter().map(|(_, w)| w).sum::<f64>() + ROW_GAP_CM * row.len().saturating_sub(1) as f64;
    let mut offset = -total / 2.0;
    for (name, width) in &row {
        if *name == asset.name {
            offset += width / 2.0;
            break;
        }
        offset += width + ROW_GAP_CM;
    }
    let centre = if row.len() > 1 { offset } else { 0.0 };
    // Still over the piece: its centre within the piece's width.
    let reach = (under.size[0] / 2.0 - asset.size[0] / 4.0).clamp(0.0, SLIDE_CM);
    let along = w.along(fp.center) + centre;
    // The mount's gap above the piece's top, or above what stands on it when that is in the
    // way (a mirror over the dresser, raised over a plant at its end only when it must be).
    // No higher than its centre [`ABOVE_HANG_CM`] over the kind's own height (a print is not
    // hung up by the ceiling over a TV on a credenza: it goes to a free wall instead).
    let highest = (mount.height + ABOVE_HANG_CM - asset.size[2] / 2.0)
        .min(CEILING_CM - asset.size[2])
        .max(0.0);
    let mut heights: Vec<f64> = std::iter::once(under.top())
        .chain(
            now.iter()
                .filter(|o| o.on.as_deref() == Some(under.name.as_str()))
                .map(PlacedObject::top),
        )
        .map(|t| t + mount.gap)
        .filter(|&e| e <= highest)
        .collect();
    heights.sort_by(f64::total_cmp);
    heights.dedup();
    let steps = (reach / STEP_CM) as i64;
    (0..=steps)
        .flat_map(|k| [k, -k])
        .map(|k| along + k as f64 * STEP_CM)
        .find_map(|a| {
            heights
                .iter()
                .find_map(|&e| on_wall(room, asset, &w, a, e, now))
        })
}

/// The wall just behind `fp` (its back within 30 cm of it, facing the same way), if any: a piece
/// a little off its wall still has a wall above it.
fn nearest_wall_behind(room: &Room, fp: &Footprint) -> Option<Wall> {
    let (bl, br) = fp.back_edge();
    Wall::all(room).into_iter().find(|w| {
        fp.front.dot(w.inward_normal()) >= 0.99 && w.distance(bl) < 30.0 && w.distance(br) < 30.0
    })
}

/// `asset` on the wall `facing` looks at (a TV across from the sofa), its centre at the mount's
/// height.
fn across(
    room: &Room,
    asset: &Asset,
    mount: &Mount,
    facing: &PlacedObject,
    now: &[PlacedObject],
) -> Option<PlacedObject> {
    let fp = facing.footprint();
    let elevation = bottom_for_centre(mount.height, asset.size[2]);
    // The wall the front's ray meets first, facing back at it.
    let hit = Wall::all(room)
        .into_iter()
        .filter(|w| fp.front.dot(w.inward_normal()) < -0.7)
        .filter_map(|w| {
            let n = w.inward_normal();
            let dist = (fp.center - w.edge.start).dot(n);
            let speed = -fp.front.dot(n);
            if dist <= 0.0 || speed <= 0.0 {
                return None;
            }
            let at = fp.center + fp.front * (dist / speed);
            let along = w.along(at);
            (-1.0..=w.length() + 1.0)
                .contains(&along)
                .then_some((dist / speed, w, along))
        })
        .min_by(|a, b| a.0.total_cmp(&b.0));
    let (_, w, along) = hit?;
    slide(room, asset, &w, along, elevation, SLIDE_CM, now)
}

/// `asset` in the middle of the widest free stretch of any `allowed` wall (by index) at the mount's height (its
/// centre there): the stretches between the openings, the floor pieces reaching that high and
/// the other wall pieces (`hanging::spots_on_wall`).
fn free_wall(
    room: &Room,
    asset: &Asset,
    mount: &Mount,
    now: &[PlacedObject],
    allowed: impl Fn(usize) -> bool,
) -> Option<PlacedObject> {
    let elevation = bottom_for_centre(mount.height, asset.size[2]);
    Wall::all(room)
        .iter()
        .filter(|w| allowed(w.index()))
        .filter_map(|w| widest(&spots_on_wall(room, asset, w, elevation, now)))
        .fold(
            None,
            |best: Option<(f64, PlacedObject)>, (m, o)| match best {
                Some((b, _)) if b >= m => best,
                _ => Some((m, o)),
            },
        )
        .map(|(_, o)| o)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::fixtures::plan_holding;
    use disco_core::geometry3d::{opening_problem, wall_problem};
    use disco_core::room::Window;

    fn obj(name: &str, cat: &str, at: [f64; 2], size: [f64; 3], rotation: f64) -> PlacedObject {
        PlacedObject {
            name: name.into(),
            category: cat.into(),
            size,
            position: at,
            rotation,
            ..Default::default()
        }
    }

    #[test]
    fn a_lamp_stands_on_its_nightstand_and_a_painting_hangs_centred_above_the_bed() {
        let room = Room::rect(400.0, 350.0);
        // The bed's head on the bottom wall, facing up; a nightstand to its left.
        let bed = obj("bed-0", "bed", [200.0, 105.5], [160.0, 210.0, 100.0], 0.0);
        let stand = obj("ns-0", "nightstand", [90.0, 20.5], [50.0, 40.0, 55.0], 0.0);
        let lamp = Asset::new("lamp-0", "table lamp", [30.0, 30.0, 50.0]);
        let painting = Asset::new("art-0", "framed painting", [100.0, 4.0, 70.0]);
        let plan = plan_holding(&[
            ("lamp-0", Support::Surface, Some((Relation::On, "ns-0"))),
            ("art-0", Support::Wall, Some((Relation::Above, "bed-0"))),
        ]);
        let k = Knowledge::builtin();
        let out = place_held(&k, &room, &plan, &[&lamp, &painting], &[bed, stand.clone()]);
        let l = &out[0];
        assert_eq!(l.on.as_deref(), Some("ns-0"));
        assert_eq!(l.elevation, 55.0);
        assert!(surface_problem(l, &stand).is_none());
        let p = &out[1];
        assert_eq!(p.wall, Some(0));
        assert!((p.position[0] - 200.0).abs() < 1e-6, "centred over the bed");
        assert_eq!(p.elevation, 120.0, "20 cm above the 100 cm bed");
        assert!(wall_problem(p, &room, 0).is_none());
    }

    #[test]
    fn a_tv_without_a_stand_hangs_across_from_the_sofa_clear_of_the_window() {
        let mut room = Room::rect(500.0, 400.0);
        // A window on the top wall right across from the sofa's middle.
        room.windows.push(Window {
            wall: 2,
            at: 250.0,
            width: 100.0,
            sill: 90.0,
            height: 120.0,
        });
        let sofa = obj("sofa-0", "sofa", [250.0, 45.5], [200.0, 90.0, 85.0], 0.0);
        let tv = Asset::new("tv-0", "tv", [120.0, 8.0, 70.0]);
        let plan = plan_holding(&[("tv-0", Support::Wall, Some((Relation::Opposite, "sofa-0")))]);
        let out = place_held(&Knowledge::builtin(), &room, &plan, &[&tv], &[sofa]);
        let t = &out[0];
        assert_eq!(t.wall, Some(2), "the wall the sofa looks at");
        assert!(opening_problem(t, &room, 2).is_none());
        assert!(
            (t.position[0] - 250.0).abs() >= 110.0 - 1e-6,
            "slid off the window"
        );
        assert_eq!(t.elevation, 75.0, "centre at 110 cm");
    }

    #[test]
    fn a_clock_takes_the_middle_of_the_widest_free_wall() {
        let room = Room::rect(600.0, 300.0);
        let wardrobe = obj("w-0", "wardrobe", [100.0, 30.5], [200.0, 60.0, 210.0], 0.0);
        let clock = Asset::new("clock-0", "wall clock", [35.0, 5.0, 35.0]);
        let plan = plan_holding(&[("clock-0", Support::Wall, None)]);
        let out = place_held(&Knowledge::builtin(), &room, &plan, &[&clock], &[wardrobe]);
        let c = &out[0];
        assert!(c.wall.is_some());
        assert_eq!(c.elevation, 190.0 - 17.5);
        // The top wall (600 cm, nothing against it) is the widest free stretch.
        assert_eq!(c.wall, Some(2));
        assert!((c.position[0] - 300.0).abs() <= 5.0);
    }
}
