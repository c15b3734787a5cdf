//! Where the plan puts an anchor in the room (a zone, a wall's role, the far corner, under a
//! window, by the entrance): the anchor's candidate poses re-ranked so the ones that honour it
//! come first, the designer's own order kept among equals.

use glam::DVec2;

use disco_core::geometry::{Footprint, Wall};
use disco_core::placement::Pose;
use disco_core::plan::Place;
use disco_core::relations::placed_as_asked_in;
use disco_core::room::analysis::RoomAnalysis;
use disco_core::scene::{Asset, Room};

/// Candidates whose distances from the asked place differ by less than this (cm) count as
/// equally good: the designer's own order decides between them.
const BUCKET_CM: f64 = 10.0;

/// What a distance counts for when nothing of the place can be measured (cm).
const MISSED_CM: f64 = 10_000.0;

/// `cands` for `asset`, those that honour `place` first, then those where `fits` holds (the
/// anchor's seats have their floor), then the nearer ones; stable otherwise. A table asked into
/// a corner whose chairs go all round stands as near the corner as its chairs allow rather
/// than in it.
pub(super) fn prefer_place(
    room: &Room,
    analysis: &RoomAnalysis,
    asset: &Asset,
    place: &Place,
    cands: Vec<Pose>,
    fits: &dyn Fn(&Pose) -> bool,
) -> Vec<Pose> {
    let [w, d, h] = asset.size;
    let mut keyed: Vec<((bool, bool, i64), usize, Pose)> = cands
        .into_iter()
        .enumerate()
        .map(|(i, p)| {
            let fp = Footprint::new(p.center, w, d, p.rotation).with_height(h);
            let missed = !placed_as_asked_in(&fp, room, analysis, place);
            let miss = distance_from_place(&fp, room, analysis, place);
            ((missed, !fits(&p), (miss / BUCKET_CM).floor() as i64), i, p)
        })
        .collect();
    keyed.sort_by_key(|(k, i, _)| (*k, *i));
    keyed.into_iter().map(|(_, _, p)| p).collect()
}

/// How far (cm) a footprint stands from what `place` asks, summed over its parts.
fn distance_from_place(fp: &Footprint, room: &Room, analysis: &RoomAnalysis, place: &Place) -> f64 {
    let mut total = 0.0;
    if let Some(zone) = &place.zone {
        // How far its farthest corner lies outside: a piece wholly in the zone is best.
        total += analysis
            .zones_named(zone)
            .iter()
            .map(|z| {
                fp.corners()
                    .iter()
                    .map(|&c| z.distance(c))
                    .fold(0.0, f64::max)
            })
            .fold(f64::INFINITY, f64::min)
            .min(MISSED_CM);
    }
    let walls = Wall::all(room);
    let to_walls = |ids: &[usize]| {
        ids.iter()
            .filter_map(|&i| walls.get(i))
            .map(|w| w.segment_distance(fp.back_center()))
            .fold(MISSED_CM, f64::min)
    };
    if let Some(role) = place.wall {
        total += to_walls(&analysis.walls_with(role));
    }
    if place.far_corner
        && let Some(c) = analysis.far_corner(place.zone.as_deref())
    {
        let p = DVec2::new(c.at[0], c.at[1]);
        total += fp
            .corners()
            .iter()
            .map(|k| k.distance(p))
            .fold(f64::INFINITY, f64::min);
    }
    if place.under_window {
        // The window the piece fits under, else any: its middle.
        let low = room.windows.iter().filter(|win| win.sill >= fp.height);
        let any = room.windows.iter();
        let mids: Vec<DVec2> = low
            .chain(any)
            .filter_map(|win| room.opening_ends(win.wall, win.at, win.width))
            .map(|(a, b)| (a + b) / 2.0)
            .collect();
        total += mids
            .iter()
            .map(|m| m.distance(fp.back_center()))
            .fold(MISSED_CM, f64::min);
    }
    if place.by_entrance
        && let Some(mid) = analysis.main_door.and_then(|i| room.door_middle(i))
    {
        total += fp
            .corners()
            .iter()
            .map(|k| k.distance(mid))
            .fold(f64::INFINITY, f64::min);
    }
    total
}
