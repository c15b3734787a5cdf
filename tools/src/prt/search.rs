//! Pieces of the PRT's searches: the shortcut for an object valid where it stands, the
//! re-check of a wall stretch found full, and the candidate orders (nearest first, rings).

use glam::DVec2;

use super::coords::{self, Line, Settled, WallShape};
use disco_core::geometry::{Footprint, WallSlot};

/// `fp` where it stands, when that is valid among the `settled` footprints for an object
/// `height` cm tall and lies on the candidates' rounding (see [`coords::tidy`]); the caller
/// knows it lies in the room's bounding box. The search outward from a position finds that
/// position itself first when it is a valid candidate, so this is its answer without building
/// the candidate lines: most objects of a big layout stand where an earlier pass left them.
pub(super) fn kept_in_place(fp: &Footprint, height: f64, settled: &Settled) -> Option<Footprint> {
    let o = fp.center;
    let on_grid = coords::tidy(o.x) == o.x && coords::tidy(o.y) == o.y;
    let cand = fp.with_pose(o, fp.rotation);
    (on_grid && !settled.collides(&cand) && settled.fits_room(&cand, height)).then_some(cand)
}

/// Searches a stretch (`lo..hi`, of `shape`) found full when `since` footprints were settled:
/// only the object's own position and the flush positions against the footprints settled
/// since (of half extent `h_along` along the wall) can be free now. Marks it full again when
/// none is; else offers the nearest free one to `best`.
pub(super) fn recheck_full_stretch(
    s: &WallSearch<'_>,
    shape: WallShape,
    since: usize,
    (lo, hi): (f64, f64),
    h_along: f64,
    best: &mut Option<(f64, Footprint)>,
) {
    let (slot, fp, o, settled) = (s.slot, s.fp, s.o, s.settled);
    let o_along = slot.along(o);
    let fresh: Vec<f64> = settled
        .contacts_since(since, slot.along_x(), h_along)
        .filter(|c| *c >= lo && *c <= hi)
        .chain([o_along.clamp(lo, hi)])
        .collect();
    let found = nearest_free_of(&fresh, (lo, hi), o_along, |v| {
        let cand = fp.with_pose(slot.point(v), fp.rotation);
        (!settled.collides(&cand) && settled.fits_room(&cand, s.height)).then_some(cand)
    });
    match found {
        None => settled.mark_full(shape),
        Some(cand) => {
            let d = cand.center.distance(o);
            if best.is_none_or(|(bd, _)| d < bd) {
                *best = Some((d, cand));
            }
        }
    }
}

/// One wall search: the slot, the object turned to the wall, where it stood, how tall it is,
/// and what is settled.
pub(super) struct WallSearch<'a> {
    /// The wall's slot for the object's shape.
    pub(super) slot: &'a WallSlot,
    /// The object turned to the wall.
    pub(super) fp: Footprint,
    /// Where it stood.
    pub(super) o: DVec2,
    /// Its height (cm).
    pub(super) height: f64,
    /// What is settled.
    pub(super) settled: &'a Settled,
}

/// The first of the raw coordinates `raw` (rounded as candidates are, clamped to `range`,
/// each once) by distance from `o`, the lower of two as near first, where `free` finds a pose.
pub(super) fn nearest_free_of(
    raw: &[f64],
    range: (f64, f64),
    o: f64,
    free: impl Fn(f64) -> Option<Footprint>,
) -> Option<Footprint> {
    let mut vs: Vec<f64> = raw
        .iter()
        .map(|v| coords::tidy(*v).clamp(range.0, range.1))
        .collect();
    vs.sort_by(f64::total_cmp);
    vs.dedup();
    vs.sort_by(|a, b| (a - o).abs().total_cmp(&(b - o).abs()));
    vs.into_iter().find_map(free)
}

/// Smallest axis distance from `c` of the coordinates `k` steps from `i0` (infinite if none exist).
pub(super) fn ring_axis_bound(coords: &mut Line<'_>, i0: i64, k: i64, c: f64) -> f64 {
    let below = coords.get(i0 - k).map(|v| (c - v).abs());
    let above = coords.get(i0 + k).map(|v| (v - c).abs());
    match (below, above) {
        (Some(a), Some(b)) => a.min(b),
        (Some(a), None) | (None, Some(a)) => a,
        (None, None) => f64::INFINITY,
    }
}

/// Index pairs on the square ring at Chebyshev distance `k` around `(i0, j0)`, in the order the
/// search visits them (those beyond a list's ends are skipped by the caller). Visits only the
/// ring's perimeter (at most 8k points).
pub(super) fn ring(i0: i64, j0: i64, k: i64) -> Vec<(i64, i64)> {
    if k == 0 {
        return vec![(i0, j0)];
    }
    let mut pts = Vec::with_capacity(8 * k as usize);
    for i in i0 - k..=i0 + k {
        pts.push((i, j0 - k));
        pts.push((i, j0 + k));
    }
    for j in j0 - k + 1..=j0 + k - 1 {
        pts.push((i0 - k, j));
        pts.push((i0 + k, j));
    }
    pts
}
