//! The prompt's placement wishes (which pieces go in a corner, which in the middle), read once
//! per scene. Reading them scans the prompt against every asset, so reading them again for each
//! group would cost the designer time in the square of the scene's size.

use std::sync::{Arc, Mutex};

use std::collections::HashMap;

use crate::hints::{Hint, read_hints};
use crate::knowledge::Knowledge;
use disco_core::room::analysis::WallRole;
use disco_core::scene::SceneSpec;

/// How many scenes' wishes are kept: a batch designs a few scenes at once.
const SCENES_KEPT: usize = 8;

/// What the prompt wishes for the placement of named assets.
#[derive(Debug, Default, PartialEq)]
pub(super) struct Wishes {
    /// Names of the assets the prompt wants in a corner.
    pub(super) in_corner: Vec<String>,
    /// Names of the assets the prompt wants in the middle of the room.
    pub(super) centre: Vec<String>,
    /// Names of the assets the prompt wants by a window.
    pub(super) by_window: Vec<String>,
    /// Names of the assets the prompt wants in the middle of their wall.
    pub(super) centred_on_wall: Vec<String>,
    /// Names of the assets the prompt wants at the window nearest the main door.
    pub(super) window_by_door: Vec<String>,
    /// Members of rows the prompt turns to a wall with nothing on it to face, and that wall.
    pub(super) rows_wall: HashMap<String, WallRole>,
}

impl Wishes {
    /// The wishes of `scene`'s prompt, read afresh.
    pub(super) fn read(scene: &SceneSpec, knowledge: &Knowledge) -> Self {
        let hints = read_hints(scene, knowledge);
        let spot = |want: &Hint| -> Vec<String> {
            hints
                .iter()
                .filter(|h| h.hint == *want)
                .flat_map(|h| h.subjects.iter().map(|&i| scene.assets[i].name.clone()))
                .collect()
        };
        let rows_wall = hints
            .iter()
            .filter_map(|h| match &h.hint {
                Hint::Formation(f) => f.wall.map(|w| (h, w)),
                _ => None,
            })
            .flat_map(|(h, w)| {
                h.subjects
                    .iter()
                    .map(move |&i| (scene.assets[i].name.clone(), w))
            })
            .collect();
        Wishes {
            in_corner: spot(&Hint::Corner),
            centre: spot(&Hint::Centre),
            by_window: spot(&Hint::ByWindow),
            centred_on_wall: spot(&Hint::CentredOnWall),
            window_by_door: spot(&Hint::WindowByDoor),
            rows_wall,
        }
    }
}

/// The wishes of the last few scenes designed, each with the scene it was read from.
#[derive(Default)]
pub(super) struct WishCache {
    recent: Mutex<Vec<(Arc<SceneSpec>, Arc<Wishes>)>>,
}

impl WishCache {
    /// The wishes of `scene`: kept ones when the very same scene was read before, else read now
    /// (and kept, in place of the oldest when full).
    pub(super) fn get(&self, scene: &SceneSpec, knowledge: &Knowledge) -> Arc<Wishes> {
        let kept = |recent: &[(Arc<SceneSpec>, Arc<Wishes>)]| {
            recent
                .iter()
                .find(|(s, _)| **s == *scene)
                .map(|(_, w)| Arc::clone(w))
        };
        if let Some(w) = kept(&self.lock()) {
            return w;
        }
        let wishes = Arc::new(Wishes::read(scene, knowledge));
        let mut recent = self.lock();
        if kept(&recent).is_none() {
            if recent.len() >= SCENES_KEPT {
                recent.remove(0);
            }
            recent.push((Arc::new(scene.clone()), Arc::clone(&wishes)));
        }
        wishes
    }

    /// The kept scenes; a poisoned lock (a panic elsewhere) still holds valid entries.
    fn lock(&self) -> std::sync::MutexGuard<'_, Vec<(Arc<SceneSpec>, Arc<Wishes>)>> {
        self.recent.lock().unwrap_or_else(|e| e.into_inner())
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use disco_core::scene::{Asset, Room};

    fn scene(prompt: &str) -> SceneSpec {
        SceneSpec {
            id: "w".into(),
            prompt: prompt.into(),
            room_type: "room".into(),
            room: Room::rect(500.0, 400.0),
            assets: vec![
                Asset::new("table-0", "dining table", [160.0, 90.0, 75.0]),
                Asset::new("bookshelf-0", "bookshelf", [90.0, 35.0, 180.0]),
            ],
        }
    }

    #[test]
    fn kept_wishes_are_the_ones_read_afresh_and_scenes_do_not_mix() {
        let knowledge = Knowledge::builtin();
        let cache = WishCache::default();
        let a = scene("a bookshelf in the corner and a central dining table");
        let b = scene("a bookshelf and a dining table");
        let first = cache.get(&a, &knowledge);
        assert_eq!(first.in_corner, ["bookshelf-0"]);
        assert_eq!(first.centre, ["table-0"]);
        assert!(Arc::ptr_eq(&first, &cache.get(&a, &knowledge)));
        let other = cache.get(&b, &knowledge);
        assert_eq!(*other, Wishes::read(&b, &knowledge));
        assert!(other.in_corner.is_empty() && other.centre.is_empty());
    }
}
