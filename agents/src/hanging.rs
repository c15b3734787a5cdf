//! Where a piece hangs on a wall, for every designer that hangs one (the rules' and the model
//! path's): the test of one spot, sliding along the wall from a wanted spot, and the spot in the
//! middle of a wall's widest free stretch.
//!
//! A spot holds a piece when its back is on the wall's segment, it covers no opening of the wall
//! (`disco_core::geometry3d`), it lies in the room, and nothing reaches its height within
//! [`IN_FRONT_CM`] before it (a painting is not hung behind a TV on its stand, nor a clock
//! behind a tall plant).

use glam::DVec2;

use disco_core::geometry::Wall;
use disco_core::geometry3d::{collide, opening_problem, wall_problem};
use disco_core::layout::PlacedObject;
use disco_core::scene::{Asset, Room};

/// Step (cm) of the searches along a wall (and over a top).
pub const STEP_CM: f64 = 5.0;

/// How high (cm) a wall piece's top may reach: a room is about 260 cm high.
pub const CEILING_CM: f64 = 250.0;

/// How far before a wall piece (cm) nothing may reach its height.
pub const IN_FRONT_CM: f64 = 30.0;

/// Space (cm) a wall piece hung on a free stretch keeps beside other wall pieces of its wall, at
/// any height (a clock does not hang right over a painting).
pub const WALL_SPACING_CM: f64 = 20.0;

/// The bottom (cm) of a piece `height` tall whose centre is at `centre`, kept under the ceiling.
pub fn bottom_for_centre(centre: f64, height: f64) -> f64 {
    (centre - height / 2.0).clamp(0.0, (CEILING_CM - height).max(0.0))
}

/// Whether `cand` may be where it is among `now`: it collides (in 3D) with nothing solid.
pub fn clear(cand: &PlacedObject, now: &[PlacedObject]) -> bool {
    now.iter()
        .filter(|o| o.name != cand.name && !o.is_flat())
        .all(|o| !collide(cand, o))
}

/// `asset` hung on wall `w`, its centre `along` cm from the wall's start and its bottom at
/// `elevation`; `None` when it would not hang there (see the module's docs).
pub fn on_wall(
    room: &Room,
    asset: &Asset,
    w: &Wall,
    along: f64,
    elevation: f64,
    now: &[PlacedObject],
) -> Option<PlacedObject> {
    let point = w.edge.start + w.direction() * along;
    // The back a hair off the wall, well within the wall gap.
    let centre = point + w.inward_normal() * (asset.size[1] / 2.0 + 0.1);
    let cand = PlacedObject {
        name: asset.name.clone(),
        category: asset.category.clone(),
        size: asset.size,
        position: [centre.x, centre.y],
        rotation: w.inward_rotation(),
        elevation,
        on: None,
        wall: Some(w.index()),
    };
    let depth = asset.size[1] + IN_FRONT_CM;
    let reach = point + w.inward_normal() * (depth / 2.0 + 0.1);
    let before_it = PlacedObject {
        size: [asset.size[0], depth, asset.size[2]],
        position: [reach.x, reach.y],
        ..cand.clone()
    };
    let ok = wall_problem(&cand, room, w.index()).is_none()
        && opening_problem(&cand, room, w.index()).is_none()
        && cand.footprint().inside(room)
        && clear(&before_it, now);
    ok.then_some(cand)
}

/// The first spot from `along` (cm from the wall's start), tried outwards up to `reach` cm
/// either way, where `asset` hangs on `w` at `elevation`.
pub fn slide(
    room: &Room,
    asset: &Asset,
    w: &Wall,
    along: f64,
    elevation: f64,
    reach: f64,
    now: &[PlacedObject],
) -> Option<PlacedObject> {
    let steps = (reach / STEP_CM) as i64;
    (0..=steps)
        .flat_map(|k| [k, -k])
        .map(|k| along + k as f64 * STEP_CM)
        .find_map(|a| on_wall(room, asset, w, a, elevation, now))
}

/// `asset` at every [`STEP_CM`] of wall `w` at `elevation`, where it hangs there and keeps
/// [`WALL_SPACING_CM`] from the other pieces on the wall (`None` where it does not).
pub fn spots_on_wall(
    room: &Room,
    asset: &Asset,
    w: &Wall,
    elevation: f64,
    now: &[PlacedObject],
) -> Vec<Option<PlacedObject>> {
    let n = (w.length() / STEP_CM).floor() as usize;
    // The stretches other wall pieces of this wall take, widened by the spacing.
    let taken: Vec<(f64, f64)> = now
        .iter()
        .filter(|o| o.wall == Some(w.index()) && o.name != asset.name)
        .map(|o| {
            let at = w.along(DVec2::from(o.position));
            let half = o.size[0] / 2.0 + asset.size[0] / 2.0 + WALL_SPACING_CM;
            (at - half, at + half)
        })
        .collect();
    (0..=n)
        .map(|k| {
            let along = k as f64 * STEP_CM;
            if taken.iter().any(|&(a, b)| along > a && along < b) {
                return None;
            }
            on_wall(room, asset, w, along, elevation, now)
        })
        .collect()
}

/// Of `spots` (from [`spots_on_wall`]), the one farthest from any spot that does not hold the
/// piece (the middle of the widest free stretch), with that distance in cm.
pub fn widest(spots: &[Option<PlacedObject>]) -> Option<(f64, PlacedObject)> {
    let mut best: Option<(f64, PlacedObject)> = None;
    for (k, cand) in spots.iter().enumerate() {
        let Some(cand) = cand else { continue };
        let left = (0..k).rev().take_while(|&j| spots[j].is_some()).count();
        let right = (k + 1..spots.len())
            .take_while(|&j| spots[j].is_some())
            .count();
        let margin = left.min(right) as f64 * STEP_CM;
        if best.as_ref().is_none_or(|(m, _)| margin > *m) {
            best = Some((margin, cand.clone()));
        }
    }
    best
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_widest_free_stretch_is_the_middle_of_the_longest_run_of_spots() {
        let room = Room::rect(400.0, 300.0);
        let w = Wall::get(&room, 0).unwrap();
        let clock = Asset::new("clock-0", "clock", [30.0, 5.0, 30.0]);
        // A 200 cm cabinet reaching 210 cm against the left half of the bottom wall.
        let cabinet = PlacedObject {
            name: "cab-0".into(),
            category: "cabinet".into(),
            size: [200.0, 50.0, 210.0],
            position: [100.0, 25.0],
            ..Default::default()
        };
        let spots = spots_on_wall(&room, &clock, &w, 175.0, std::slice::from_ref(&cabinet));
        let (margin, best) = widest(&spots).unwrap();
        assert!((best.position[0] - 300.0).abs() <= STEP_CM, "{best:?}");
        assert!(margin >= 60.0);
        assert!(on_wall(&room, &clock, &w, 100.0, 175.0, &[cabinet]).is_none());
    }
}
