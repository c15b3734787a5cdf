//! The reach of what earlier groups placed, kept from one group to the next. Building it
//! afresh rasters the whole floor and every object for each group, which costs a big scene
//! time in the square of its size; the next group usually finds the same objects plus its
//! predecessor's, which are added to the kept map one by one (a [`ReachMap`] grows so, and
//! counts as a fresh one would). The zones kept clear in front of those objects are kept with
//! it the same way, so each group looks up the furniture knowledge only for what is new.

use std::sync::Mutex;

use disco_core::geometry::Aabb;
use disco_core::layout::PlacedObject;
use disco_core::metrics::ReachMap;
use disco_core::scene::Room;

/// How many maps are kept: a batch designs a few scenes at once.
const MAPS_KEPT: usize = 8;

/// What a reach map was made of: the room and its solid objects, in order; with the zone kept
/// clear in front of each of them.
pub(super) struct ReachKey {
    room: Room,
    solid: Vec<PlacedObject>,
    /// The access zone of each object of `solid`, in the same order.
    pub(super) access: Vec<Aabb>,
}

/// A kept reach map and what it was made of.
struct KeptReach {
    key: ReachKey,
    map: ReachMap,
}

/// The reach maps of the last few designs.
#[derive(Default)]
pub(super) struct ReachCache {
    kept: Mutex<Vec<KeptReach>>,
}

impl ReachCache {
    /// The reach of the solid objects of `placed` in `room` on a raster of `cell` cm: a kept
    /// map made of the first of them, grown by the rest, when there is one; else a new map.
    /// The map is taken out of the cache, with what it is made of and each solid object's
    /// `access_zone`: [`put_back`](Self::put_back) returns both.
    pub(super) fn take(
        &self,
        room: &Room,
        placed: &[PlacedObject],
        cell: f64,
        access_zone: impl Fn(&PlacedObject) -> Aabb,
    ) -> (ReachMap, ReachKey) {
        let solid: Vec<&PlacedObject> = placed.iter().filter(|o| !o.is_flat()).collect();
        let grows = |k: &KeptReach| {
            k.key.room == *room
                && k.key.solid.len() <= solid.len()
                && k.key.solid.iter().zip(&solid).all(|(a, b)| a == *b)
        };
        let found = {
            let mut kept = self.lock();
            let best = (0..kept.len())
                .filter(|&i| grows(&kept[i]))
                .max_by_key(|&i| kept[i].key.solid.len());
            best.map(|i| kept.swap_remove(i))
        };
        match found {
            Some(KeptReach { mut key, mut map }) => {
                for o in &solid[key.solid.len()..] {
                    map.add(o);
                    key.access.push(access_zone(o));
                    key.solid.push((*o).clone());
                }
                (map, key)
            }
            None => (
                ReachMap::new(room, placed, cell),
                ReachKey {
                    room: room.clone(),
                    access: solid.iter().map(|o| access_zone(o)).collect(),
                    solid: solid.into_iter().cloned().collect(),
                },
            ),
        }
    }

    /// Keeps `map`, made of `key`, for the next design, in place of the oldest when full.
    pub(super) fn put_back(&self, map: ReachMap, key: ReachKey) {
        let mut kept = self.lock();
        if kept.len() >= MAPS_KEPT {
            kept.remove(0);
        }
        kept.push(KeptReach { key, map });
    }

    /// The kept maps; a poisoned lock (a panic elsewhere) still holds valid maps.
    fn lock(&self) -> std::sync::MutexGuard<'_, Vec<KeptReach>> {
        self.kept.lock().unwrap_or_else(|e| e.into_inner())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn zone(o: &PlacedObject) -> Aabb {
        o.footprint().aabb()
    }

    fn obj(name: &str, x: f64, y: f64) -> PlacedObject {
        PlacedObject {
            name: name.into(),
            category: "cabinet".into(),
            size: [100.0, 45.0, 90.0],
            position: [x, y],
            rotation: 0.0,
            ..Default::default()
        }
    }

    #[test]
    fn a_grown_map_counts_as_a_fresh_one_and_a_moved_object_starts_afresh() {
        let room = Room::rect(400.0, 300.0);
        let cache = ReachCache::default();
        // A row of cabinets that closes off the bottom strip, one group at a time.
        let all: Vec<PlacedObject> = (0..4)
            .map(|i| obj(&format!("c{i}"), 50.0 + 100.0 * i as f64, 100.0))
            .chain([obj("low", 200.0, 22.5)])
            .collect();
        for n in 1..=all.len() {
            let (map, key) = cache.take(&room, &all[..n], 10.0, zone);
            let fresh = ReachMap::new(&room, &all[..n], 10.0);
            assert_eq!(map.unreachable(), fresh.unreachable(), "{n} objects");
            assert_eq!(key.solid.len(), n);
            assert_eq!(key.access.len(), n, "a zone per solid object");
            cache.put_back(map, key);
        }
        assert_eq!(
            ReachMap::new(&room, &all, 10.0).unreachable(),
            1,
            "the row walls the low cabinet in"
        );
        assert_eq!(
            cache.lock().len(),
            1,
            "each grown map replaces the one it grew from"
        );
        let mut moved = all.clone();
        moved[0].position = [50.0, 200.0];
        let (map, key) = cache.take(&room, &moved, 10.0, zone);
        let fresh = ReachMap::new(&room, &moved, 10.0);
        assert_eq!(map.unreachable(), fresh.unreachable());
        assert_eq!(key.solid[0].position, [50.0, 200.0]);
    }
}
