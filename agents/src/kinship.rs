//! What an asset's own words say it belongs with: the words of its category, its name and its
//! description that tell whose or what it is ("gate agent's chair" and a gate counter where
//! "agents work behind it", a "steriliser" and the "sterilisation counter", a "payment terminal on
//! the front desk" and the reception counter described as the "front desk").
//!
//! Object lists that a language model writes name their pieces generically ("office chair",
//! "stool", "computer monitor") and say what each is for in the name or the description. The
//! rule agents read categories for what a piece *is* ([`crate::knowledge`]); this module reads
//! all three for what it *belongs to*, so seats go to the piece they serve, small pieces onto the
//! top they were written for, and companions gather.
//!
//! Each word is weighed: a word that tells (a modifier such as "gate", "boarding", "reception")
//! counts [`TELLING`], a furniture noun ("desk", "counter") or a word of position ("front")
//! counts [`WEAK`], and filler, materials, colours and sizes count nothing. Two words match when
//! they are the same after plurals and possessives are taken off, or share a stem of
//! seven letters ("reception" and "receptionist"). Two assets are kin when what one tells is
//! found among the other's words for at least [`KIN`].

use crate::knowledge::words;
use disco_core::scene::Asset;

/// Weight of a word that says whose or what a piece is.
pub const TELLING: u32 = 2;

/// Weight of a furniture noun or a word of position: it tells only with another.
pub const WEAK: u32 = 1;

/// The weight two assets must share to be kin.
pub const KIN: u32 = 2;

/// Letters two words must share at the start to count as one stem ("dispensary" and
/// "dispensing", "steriliser" and "sterilisation").
const STEM: usize = 7;

/// Words that say nothing of what a piece belongs to: grammar, counts, sizes, shapes, colours,
/// materials and finishes.
#[rustfmt::skip]
const FILLER: &[&str] = &[
    "a", "an", "the", "of", "for", "with", "and", "or", "on", "in", "at", "to", "by", "it", "its",
    "is", "are", "be", "from", "into", "onto", "under", "over", "near", "next", "beside", "behind",
    "this", "that", "these", "those", "their", "them", "they", "who", "which", "where", "when",
    "while", "each", "every", "all", "some", "any", "one", "two", "three", "four", "five", "six",
    "seven", "eight", "nine", "ten", "twelve", "single", "double", "pair", "set", "small", "large",
    "big", "little", "mini", "round", "square", "rectangular", "oval", "curved", "long", "short",
    "wide", "narrow", "tall", "low", "high", "deep", "shallow", "heavy", "light", "wooden", "wood",
    "metal", "steel", "stainless", "glass", "plastic", "leather", "vinyl", "fabric", "marble",
    "stone", "oak", "pine", "walnut", "chrome", "brass", "black", "white", "grey", "gray", "red",
    "blue", "green", "yellow", "pink", "orange", "brown", "beige", "pastel", "dark", "bright",
    "new", "old", "modern", "classic", "vintage", "padded", "upholstered", "adjustable", "wheeled",
    "rolling", "mobile", "folding", "stacking", "swivel", "portable", "lockable", "clean", "wipe",
    "style", "type", "unit", "piece", "item", "use", "used", "work", "works", "working", "sit",
    "sits", "sitting", "stand", "stands", "standing", "keep", "kept", "hold", "holds", "holding",
    "put", "place", "placed", "room", "area", "space", "wall", "floor", "cm", "m", "up", "down",
    "out", "off", "also", "as", "so", "not", "no", "very", "extra",
];

/// Nouns every kind of room has, and words of position: they tell only together with another
/// word ("front desk").
#[rustfmt::skip]
const WEAK_WORDS: &[&str] = &[
    "table", "desk", "counter", "chair", "stool", "seat", "bench", "sofa", "shelf", "shelving",
    "rack", "cabinet", "cupboard", "stand", "station", "machine", "screen", "display", "case",
    "box", "bin", "cart", "trolley", "lamp", "light", "front", "back", "side", "top", "corner",
    "centre", "center", "middle", "end", "customer", "customers", "guest", "guests", "visitor",
    "visitors", "people", "person",
];

/// The words of one asset, each with its weight as a telling word (0 for a word that is only
/// there to be found, such as its head noun).
#[derive(Debug, Clone, Default, PartialEq, Eq)]
pub struct OwnWords {
    /// Every word of its category, name and description, normalised, with the weight it tells
    /// with (the category's head noun and filler tell nothing).
    words: Vec<(String, u32)>,
}

impl OwnWords {
    /// The words of `asset`: its category, its name (instance numbers dropped) and its
    /// description.
    pub fn of(asset: &Asset) -> Self {
        Self::from_texts(
            &asset.category,
            &asset.name,
            asset.description.as_deref().unwrap_or(""),
        )
    }

    /// The words of a piece with this category, name and description.
    pub fn from_texts(category: &str, name: &str, description: &str) -> Self {
        let mut out: Vec<(String, u32)> = Vec::new();
        let mut add = |w: String, weight: u32| match out.iter_mut().find(|(x, _)| *x == w) {
            Some((_, k)) => *k = (*k).max(weight),
            None => out.push((w, weight)),
        };
        for text in [category, name] {
            let ws = normalised(text);
            // The head noun says what it is, not whose: it is only there to be found.
            for (k, w) in ws.iter().enumerate() {
                let weight = if k + 1 == ws.len() { 0 } else { weight_of(w) };
                add(w.clone(), weight);
            }
        }
        for w in normalised(description) {
            let weight = weight_of(&w);
            add(w, weight);
        }
        OwnWords { words: out }
    }

    /// How much of what `self` tells is found among `other`'s words: the sum of the weights of
    /// its telling words that match one of `other`'s.
    fn found_in(&self, other: &OwnWords) -> u32 {
        self.words
            .iter()
            .filter(|(_, weight)| *weight > 0)
            .filter(|(w, _)| other.words.iter().any(|(x, _)| same_word(w, x)))
            .map(|(_, weight)| *weight)
            .sum()
    }

    /// How strongly the two pieces' words tie them together: what either tells that the other
    /// holds, the larger of the two.
    pub fn kinship(&self, other: &OwnWords) -> u32 {
        self.found_in(other).max(other.found_in(self))
    }

    /// Whether the two are kin: [`kinship`](Self::kinship) of at least [`KIN`].
    pub fn kin(&self, other: &OwnWords) -> bool {
        self.kinship(other) >= KIN
    }
}

/// The weight a word tells with.
fn weight_of(w: &str) -> u32 {
    if FILLER.contains(&w) || w.len() < 3 || w.chars().all(|c| c.is_ascii_digit()) {
        0
    } else if WEAK_WORDS.contains(&w) {
        WEAK
    } else {
        TELLING
    }
}

/// The lower-case words of a text, possessives and plurals taken off ("agent's", "agents":
/// "agent"), punctuation dropped.
fn normalised(text: &str) -> Vec<String> {
    let cleaned: String = text
        .chars()
        .map(|c| {
            if c.is_alphanumeric() || c == '\'' || c == '’' {
                c
            } else {
                ' '
            }
        })
        .collect();
    words(&cleaned)
        .split(' ')
        .map(|w| {
            let w = w
                .trim_end_matches("'s")
                .trim_end_matches("’s")
                .trim_matches(|c| c == '\'' || c == '’');
            singular(w)
        })
        .filter(|w| !w.is_empty())
        .collect()
}

/// A plural's singular, by its ending ("agents", "benches", "shelves", "bodies"); other words
/// as they are.
fn singular(w: &str) -> String {
    let n = w.chars().count();
    if n <= 3 || w.ends_with("ss") || w.ends_with("us") || w.ends_with("is") {
        return w.to_string();
    }
    if let Some(stem) = w.strip_suffix("ies") {
        return format!("{stem}y");
    }
    if let Some(stem) = w.strip_suffix("ves") {
        return format!("{stem}f");
    }
    for tail in ["ches", "shes", "xes"] {
        if w.ends_with(tail) {
            return w[..w.len() - 2].to_string();
        }
    }
    w.strip_suffix('s').unwrap_or(w).to_string()
}

/// Whether two normalised words are one: equal, or of one stem of [`STEM`] letters.
fn same_word(a: &str, b: &str) -> bool {
    if a == b {
        return true;
    }
    let stem = |w: &str| w.chars().take(STEM).collect::<String>();
    a.chars().count() >= STEM && b.chars().count() >= STEM && stem(a) == stem(b)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn of(category: &str, name: &str, description: &str) -> OwnWords {
        OwnWords::from_texts(category, name, description)
    }

    #[test]
    fn a_seat_named_or_described_for_a_piece_is_its_kin() {
        let counter = of(
            "gate counter",
            "gate-counter-0",
            "boarding desk, agents work behind it",
        );
        let chair = of("office chair", "agent-chair-0", "gate agent's chair");
        let charger = of(
            "charging station",
            "charging-station-0",
            "phone charging pillar",
        );
        assert!(chair.kin(&counter));
        assert!(!chair.kin(&charger));
        let reception = of("reception counter", "reception-counter-0", "front desk");
        let receptionist = of("office chair", "office-chair-0", "receptionist chair");
        assert!(receptionist.kin(&reception));
        let vet_desk = of("desk", "desk-0", "vet's consulting desk");
        assert!(!receptionist.kin(&vet_desk));
    }

    #[test]
    fn two_weak_words_tell_together_one_does_not() {
        let reception = of("reception counter", "reception-counter-0", "front desk");
        let terminal = of(
            "card terminal",
            "card-terminal-0",
            "payment terminal on the front desk",
        );
        let vet_desk = of("desk", "desk-0", "vet's consulting desk");
        assert!(terminal.kin(&reception), "front + desk");
        assert!(!terminal.kin(&vet_desk), "desk alone");
    }

    #[test]
    fn stems_plurals_and_possessives_match_filler_does_not() {
        let steriliser = of("autoclave", "autoclave-0", "steriliser");
        let counter = of("sterilisation counter", "sterilisation-counter-0", "");
        assert!(steriliser.kin(&counter));
        let officers = of("reception counter", "front-counter-0", "officers behind it");
        let officer_chair = of("office chair", "officer-chair-0", "");
        assert!(officer_chair.kin(&officers));
        // Materials, colours and sizes tie nothing together.
        let kennel = of("kennel", "kennel-0", "stainless recovery kennel");
        let table = of("examination table", "exam-table-0", "stainless steel table");
        assert!(!kennel.kin(&table));
        assert_eq!(singular("benches"), "bench");
        assert_eq!(singular("shelves"), "shelf");
        assert_eq!(singular("glass"), "glass");
    }
}
