//! Furniture knowledge, read from `config/furniture.toml`: what stands against a wall, what relates
//! to what and how, the clearance people need, and the order anchors are placed in.

use std::sync::{Arc, OnceLock};

use serde::Deserialize;

use disco_core::plan::Relation;
use disco_core::scene::Asset;

/// The built-in knowledge file.
pub const FURNITURE_TOML: &str = include_str!("../../config/furniture.toml");

/// How a kind of furniture stands to another.
#[derive(Debug, Clone, PartialEq, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Relate {
    /// Target names, in order of preference.
    pub to: Vec<String>,
    /// The relation.
    pub relation: Relation,
    /// Whether it also faces the target.
    #[serde(default)]
    pub face: bool,
    /// Distance in cm from the target the designer aims for.
    #[serde(default = "default_gap")]
    pub gap: f64,
}

fn default_gap() -> f64 {
    10.0
}

/// One family of categories.
#[derive(Debug, Clone, PartialEq, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Kind {
    /// Category names and synonyms, lower case.
    pub names: Vec<String>,
    /// Stands with its back against a wall.
    #[serde(default)]
    pub wall: bool,
    /// An anchor that takes the middle of its wall rather than a corner.
    #[serde(default)]
    pub centred: bool,
    /// Anchors with higher priority are placed first.
    #[serde(default)]
    pub priority: i32,
    /// Free depth (cm) people need in front of it.
    #[serde(default)]
    pub clearance: f64,
    /// Names of what this kind stands in rows facing (student desks and a board); empty when it
    /// does not stand in rows.
    #[serde(default)]
    pub rows: Vec<String>,
    /// People sit on it: in rows it faces what the rows face (cinema seats), where a desk in
    /// rows turns its back to it.
    #[serde(default)]
    pub seat: bool,
    /// Its relation to another kind, if it depends on one.
    #[serde(default)]
    pub relate: Option<Relate>,
    /// The run it joins along the walls (a kitchen's work pieces share "kitchen"): each
    /// piece of a run placed after the first stands as near to the first as it can.
    #[serde(default)]
    pub run: Option<String>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct KnowledgeFile {
    kind: Vec<Kind>,
}

/// All kinds, with lookup by category or name.
#[derive(Debug, Clone)]
pub struct Knowledge {
    kinds: Vec<Kind>,
}

/// Lower-case words of a name, with trailing instance numbers (`-0`, `_12`) removed.
pub fn words(s: &str) -> String {
    let lower = s.to_lowercase().replace(['_', '-'], " ");
    lower
        .split_whitespace()
        .filter(|w| !w.chars().all(|c| c.is_ascii_digit()))
        .collect::<Vec<_>>()
        .join(" ")
}

fn contains_words(haystack: &str, needle: &str) -> bool {
    let h = format!(" {haystack} ");
    h.contains(&format!(" {needle} "))
}

impl Knowledge {
    /// Parses a knowledge file.
    pub fn parse(text: &str) -> Result<Self, String> {
        let file: KnowledgeFile = toml::from_str(text).map_err(|e| e.to_string())?;
        Ok(Knowledge { kinds: file.kind })
    }

    /// The built-in knowledge, parsed once.
    pub fn builtin() -> Arc<Knowledge> {
        static CELL: OnceLock<Arc<Knowledge>> = OnceLock::new();
        CELL.get_or_init(|| {
            Arc::new(Knowledge::parse(FURNITURE_TOML).expect("config/furniture.toml is valid"))
        })
        .clone()
    }

    /// The kind of a category or name: an exact synonym first, then the longest synonym found
    /// among its words.
    pub fn lookup_text(&self, text: &str) -> Option<&Kind> {
        let w = words(text);
        if w.is_empty() {
            return None;
        }
        if let Some(k) = self.kinds.iter().find(|k| k.names.contains(&w)) {
            return Some(k);
        }
        self.kinds
            .iter()
            .flat_map(|k| k.names.iter().map(move |n| (k, n)))
            .filter(|(_, n)| contains_words(&w, n))
            .max_by_key(|(_, n)| n.len())
            .map(|(k, _)| k)
    }

    /// The kind of an asset: by category, then by name, then a guess from its size and shape.
    pub fn kind_of(&self, asset: &Asset) -> Kind {
        if let Some(k) = self
            .lookup_text(&asset.category)
            .or_else(|| self.lookup_text(&asset.name))
        {
            return k.clone();
        }
        guess(asset)
    }

    /// How well `asset` (of `kind`, from [`kind_of`](Self::kind_of)) matches a target list
    /// (lower is better): its category named exactly beats its kind listing the name; earlier
    /// names beat later ones. `None`: no match.
    pub fn target_rank(asset: &Asset, kind: &Kind, to: &[String]) -> Option<usize> {
        let cat = words(&asset.category);
        to.iter()
            .enumerate()
            .filter_map(|(i, name)| {
                if cat == *name {
                    Some(2 * i)
                } else if kind.names.contains(name) {
                    Some(2 * i + 1)
                } else {
                    None
                }
            })
            .min()
    }
}

/// A kind for an unknown category, from its size and shape: flat things cover the floor, large
/// things anchor a wall, small things stand by a wall.
fn guess(asset: &Asset) -> Kind {
    let [w, d, _] = asset.size;
    let area = w * d;
    let (wall, priority, clearance) = if asset.is_flat() {
        (false, 1, 0.0)
    } else if area >= 12_000.0 || w.max(d) >= 150.0 {
        (true, 50, 70.0)
    } else if area < 2_500.0 {
        (true, 10, 0.0)
    } else {
        (true, 40, 50.0)
    };
    Kind {
        names: vec![words(&asset.category)],
        wall,
        centred: false,
        rows: Vec::new(),
        seat: false,
        priority,
        clearance,
        relate: None,
        run: None,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn synonyms_and_words_find_the_kind() {
        let k = Knowledge::builtin();
        assert!(
            k.lookup_text("Queen Bed")
                .unwrap()
                .names
                .contains(&"bed".to_string())
        );
        assert!(k.lookup_text("bedside table").unwrap().relate.is_some());
        // "side table" must not be taken for a dining "table".
        let side = k.lookup_text("side table").unwrap();
        assert_eq!(side.relate.as_ref().unwrap().relation, Relation::SideOf);
        // Words inside a longer category.
        assert!(
            k.lookup_text("modern leather office chair")
                .unwrap()
                .names
                .contains(&"office chair".to_string())
        );
        assert_eq!(words("dining chair-12"), "dining chair");
    }

    #[test]
    fn unknown_categories_are_guessed_from_size() {
        let k = Knowledge::builtin();
        let big = k.kind_of(&Asset::new("x-0", "arcade machine", [300.0, 80.0, 110.0]));
        assert!(big.wall && big.priority == 50);
        let rug = k.kind_of(&Asset::new("y-0", "tatami", [200.0, 100.0, 2.0]));
        assert!(!rug.wall && rug.priority == 1);
    }
}
