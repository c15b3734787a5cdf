//! Choosing among an object's candidate poses: the first that fits, keeps earlier objects'
//! access clear and walls nothing in, as far as any does.

use super::brief::room_centre;
use super::floor::Floor;
use disco_core::geometry::Footprint;
use disco_core::layout::PlacedObject;
use disco_core::placement::Pose;
use disco_core::scene::Asset;

/// Poses by descending score.
pub(super) fn ranked(mut scored: Vec<(f64, Pose)>) -> Vec<Pose> {
    scored.sort_by(|a, b| b.0.total_cmp(&a.0));
    scored.into_iter().map(|(_, p)| p).collect()
}

/// Up to `limit` poses for `asset` from `cands` (best first), in order of preference: poses that
/// fit, leave earlier objects' clearance free and wall nothing in; then ones that fit and wall
/// nothing in; then ones that merely fit. When none fits, the first candidate pulled inside the
/// room, for the PRT to settle. Never empty.
pub(super) fn options(
    floor: &Floor<'_>,
    asset: &Asset,
    cands: &[Pose],
    limit: usize,
) -> Vec<PlacedObject> {
    let [w, d, h] = asset.size;
    // Each fitting candidate, and whether it leaves earlier objects' clearance free.
    let fitting: Vec<(&Pose, bool)> = cands
        .iter()
        .filter_map(|p| {
            let fp = Footprint::new(p.center, w, d, p.rotation);
            floor
                .fits(&fp, h)
                .then(|| (p, !floor.blocks_clearance(&fp, &asset.name)))
        })
        .collect();
    let mut picked: Vec<&Pose> = Vec::new();
    // First those that wall nothing in (the first few of each kind tested, clear ones first);
    // then any that fit, clear ones first. A candidate of both kinds is tested once.
    let mut keeps_reach: Vec<Option<bool>> = vec![None; fitting.len()];
    for want_clear in [true, false] {
        for (k, (p, _)) in fitting
            .iter()
            .enumerate()
            .filter(|(_, (_, clear))| *clear || !want_clear)
            .take(super::floor::reach_tests(floor.room))
        {
            if picked.len() < limit
                && *keeps_reach[k].get_or_insert_with(|| floor.keeps_reach(placed_at(asset, p)))
            {
                take(&mut picked, p, limit);
            }
        }
    }
    for want_clear in [true, false] {
        for (p, _) in fitting.iter().filter(|(_, clear)| *clear || !want_clear) {
            take(&mut picked, p, limit);
        }
    }
    if !picked.is_empty() {
        return picked.into_iter().map(|p| placed_at(asset, p)).collect();
    }
    vec![placed_at(asset, &pulled_inside(floor, asset, cands))]
}

/// Adds `p` to `picked` unless it is there already or `limit` is reached.
fn take<'c>(picked: &mut Vec<&'c Pose>, p: &'c Pose, limit: usize) {
    if picked.len() < limit && !picked.iter().any(|q| std::ptr::eq(*q, p)) {
        picked.push(p);
    }
}

/// The first candidate (the room's centre when there is none) moved just far enough to lie
/// inside the room.
fn pulled_inside(floor: &Floor<'_>, asset: &Asset, cands: &[Pose]) -> Pose {
    let [w, d, _] = asset.size;
    let p = cands.first().copied().unwrap_or(Pose {
        center: room_centre(floor.room),
        rotation: 0.0,
    });
    let h = Footprint::new(p.center, w, d, p.rotation).aabb_half();
    let max = (glam::DVec2::new(floor.room.width, floor.room.depth) - h).max(h);
    Pose {
        center: p.center.clamp(h, max),
        rotation: p.rotation,
    }
}

/// `asset` standing at `p`, position and rotation rounded to a millimetre.
fn placed_at(asset: &Asset, p: &Pose) -> PlacedObject {
    PlacedObject {
        name: asset.name.clone(),
        category: asset.category.clone(),
        size: asset.size,
        position: [round1(p.center.x), round1(p.center.y)],
        rotation: round1(p.rotation),
        ..Default::default()
    }
}

/// `v` rounded to one decimal.
fn round1(v: f64) -> f64 {
    (v * 10.0).round() / 10.0
}
