//! The attack kept as a test: mutated scene and layout files never panic the readers, and every
//! scene the reader accepts is one the PRT turns into a complete, valid layout.

use std::path::Path;

use disco_core::layout::{DraftLayout, Layout};
use disco_core::metrics::measure;
use disco_core::scene::SceneSpec;
use proptest::prelude::*;

use crate::PrtConfig;
use crate::refine::refine_layout;

const SCENE: &str = include_str!("../../examples/scenes/bedroom.json");
const LAYOUT: &str = include_str!("../../examples/scenes/bedroom-broken.layout.json");

/// Characters that make JSON interesting when dropped in: structure, signs, exponents, escapes.
const NOISE: &[&str] = &[
    "{",
    "}",
    "[",
    "]",
    ",",
    ":",
    "\"",
    "-",
    "e308",
    "1e-9",
    "0",
    "NaN",
    "null",
    "\\u0000",
    "\u{feff}",
    "..",
    "/",
    "9999999",
    "[1,2,3,4]",
    "true",
];

/// `text` with up to a few edits: a character removed, a noise token inserted, a span cut.
fn mutate(text: &str, edits: &[(usize, usize, usize)]) -> String {
    let mut chars: Vec<char> = text.chars().collect();
    for &(kind, at, which) in edits {
        if chars.is_empty() {
            break;
        }
        let at = at % chars.len();
        match kind % 3 {
            0 => {
                chars.remove(at);
            }
            1 => {
                let noise: Vec<char> = NOISE[which % NOISE.len()].chars().collect();
                chars.splice(at..at, noise);
            }
            _ => {
                let end = (at + which % 16).min(chars.len());
                chars.drain(at..end);
            }
        }
    }
    chars.into_iter().collect()
}

fn edits() -> impl Strategy<Value = Vec<(usize, usize, usize)>> {
    prop::collection::vec((0usize..3, 0usize..4000, 0usize..64), 1..4)
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(300))]

    #[test]
    fn mutated_scenes_are_refused_with_a_reason_or_furnished_validly(e in edits()) {
        let text = mutate(SCENE, &e);
        match SceneSpec::from_json(Path::new("s.json"), &text) {
            Err(err) => prop_assert!(err.to_string().starts_with("s.json: "), "{err}"),
            Ok(scene) => {
                let empty = Layout {
                    id: scene.id.clone(),
                    room: scene.room.clone(),
                    objects: Vec::new(),
                    dropped: Vec::new(),
                    plan: Default::default(),
                    stats: Default::default(),
                };
                let names: Vec<String> = scene.assets.iter().map(|a| a.name.clone()).collect();
                let layout = refine_layout(&scene, empty, &names, PrtConfig::default());
                let m = measure(&layout);
                prop_assert_eq!(m.collision_pct, 0.0);
                prop_assert_eq!(m.oob_pct, 0.0);
                prop_assert_eq!(layout.objects.len() + layout.dropped.len(), scene.assets.len());
            }
        }
    }

    #[test]
    fn mutated_layouts_never_panic_the_readers(e in edits()) {
        let text = mutate(LAYOUT, &e);
        let path = Path::new("l.json");
        match disco_core::io::parse_json::<Layout>(path, &text) {
            Err(err) => prop_assert!(err.to_string().starts_with("l.json: "), "{err}"),
            Ok(layout) => {
                let _ = layout.validate(path);
            }
        }
        let scene = SceneSpec::from_json(Path::new("s.json"), SCENE).unwrap();
        if let Ok(draft) = disco_core::io::parse_json::<DraftLayout>(path, &text) {
            let _ = draft.resolve(path, &scene);
        }
    }
}
