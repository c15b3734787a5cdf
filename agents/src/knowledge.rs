//! Furniture knowledge, read from `config/furniture.toml`: what stands against a wall, what relates
//! to what and how, the clearance people need, and the order anchors are placed in.

use std::sync::{Arc, OnceLock};

use serde::Deserialize;

use disco_core::plan::{FormationShape, Place, Relation};
use disco_core::scene::{Asset, Support};

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
    /// How people sit at it, when they do (a table all round, a desk or a station at its
    /// front, a bar along its front): seats of the room are shared out among such pieces by
    /// [`SeatsAt::capacity`].
    #[serde(default)]
    pub seats: Option<SeatsAt>,
    /// Free depth (cm) kept on its staff side for the people who work there: it stands off a
    /// wall by that much, the staff side towards the wall (see [`Kind::staff_behind`]).
    #[serde(default)]
    pub staff: f64,
    /// Where in the room a piece of this kind stands when the prompt says nothing else (a
    /// checkout by the entrance; an altar in the apse, else on the wall across from the door):
    /// the first of these the room has.
    #[serde(default)]
    pub places: Vec<Place>,
    /// The formation the pieces of this kind stand in together when a room has two or more:
    /// `aisles` (a shop's gondolas), `rows` (pews facing one of the kind's `faces`).
    #[serde(default)]
    pub formation: Option<FormationShape>,
    /// Space (cm) between the pieces of its `aisles` formation, along a line and across an
    /// aisle (an exhibition's plinths); `None`: shelving's own (end to end, 120 cm aisles).
    #[serde(default)]
    pub spacing: Option<f64>,
    /// What a `rows` formation of this kind faces, by name in order of preference (none in
    /// the room: no rows).
    #[serde(default)]
    pub faces: Vec<String>,
    /// The fewest pieces of this kind that make its formation (0 or 1 read as 2).
    #[serde(default)]
    pub at_least: usize,
    /// Where it goes when it does not stand on the floor (a lamp on a nightstand, a painting
    /// on a wall); `None`: on the floor.
    #[serde(default)]
    pub mount: Option<Mount>,
    /// A thin piece placed against a wall like a floor piece (a whiteboard, the rows' focus) is
    /// then hung on that wall, its centre at this height (cm); see [`Kind::lifts`].
    #[serde(default)]
    pub lift: Option<f64>,
    /// The fewest people it seats, whatever its width: set from the asset's words by the
    /// file's `[[seats_named]]` ("a double desk" seats two); 0 when no word says.
    #[serde(default)]
    pub seats_least: usize,
}

/// Where a kind goes off the floor: on another piece's top or on a wall.
#[derive(Debug, Clone, PartialEq, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Mount {
    /// `surface` or `wall` (`floor` reads as no mount).
    pub support: Support,
    /// For `surface`: what it stands on, by name in order of preference.
    #[serde(default)]
    pub on: Vec<String>,
    /// For `wall`: the floor pieces it hangs above, centred, by name in order of preference
    /// (a painting above the bed or the sofa); none free: anywhere on a free stretch of wall.
    #[serde(default)]
    pub above: Vec<String>,
    /// Only pieces at most this tall (cm) leave the floor: a 40 cm lamp goes on a nightstand, a
    /// 160 cm one stands on the floor as the kind's floor fields say.
    #[serde(default)]
    pub up_to: Option<f64>,
    /// A `surface` piece with nothing to stand on hangs on a wall instead (a TV without a stand).
    #[serde(default)]
    pub or_wall: bool,
    /// Pieces of the kind take the best named top before spreading over several (a pair of
    /// speakers on the TV's stand; one monitor to each of four desks).
    #[serde(default)]
    pub together: bool,
    /// For a wall piece hung on a free stretch of wall: the height (cm) of its centre.
    #[serde(default = "default_hang_cm")]
    pub height: f64,
    /// For a wall piece hung above another: the gap (cm) between that piece's top and its bottom.
    #[serde(default = "default_above_gap_cm")]
    pub gap: f64,
}

fn default_hang_cm() -> f64 {
    150.0
}

fn default_above_gap_cm() -> f64 {
    20.0
}

impl Mount {
    /// A mount of `support` with nothing else known: a wall piece hung at eye height, a
    /// surface piece on whatever holds things (see the planner).
    pub fn plain(support: Support) -> Self {
        Mount {
            support,
            on: Vec::new(),
            above: Vec::new(),
            up_to: None,
            or_wall: false,
            together: false,
            height: default_hang_cm(),
            gap: default_above_gap_cm(),
        }
    }
}

impl Kind {
    /// Whether its staff work at its back: a bar, whose front is the customers' (its stools
    /// stand along it). At any other counter the staff side is the front, where the person
    /// who works at it stands or sits (a receptionist's chair at the reception desk's front).
    pub fn staff_behind(&self) -> bool {
        self.seats == Some(SeatsAt::AlongFront)
    }

    /// The height (cm) of the centre of `asset` (of this kind) hung on the wall it was placed
    /// against, when the kind lifts it and it is thin: at most [`LIFT_DEPTH_CM`] deep and
    /// [`LIFT_HEIGHT_CM`] tall (a whiteboard on legs stays on the floor).
    pub fn lifts(&self, asset: &Asset) -> Option<f64> {
        self.lift
            .filter(|_| asset.size[1] <= LIFT_DEPTH_CM && asset.size[2] <= LIFT_HEIGHT_CM)
    }

    /// Where `asset` (of this kind) goes when it leaves the floor, if it does: its own
    /// `support` first (a user who says `"wall"` is obeyed, and `"floor"` keeps it down), then
    /// the kind's mount when the asset is no taller than the mount allows.
    pub fn mount_for(&self, asset: &Asset) -> Option<Mount> {
        let own = |s: Support| match &self.mount {
            Some(m) if m.support == s => m.clone(),
            Some(m) if m.or_wall && s == Support::Wall => Mount {
                support: Support::Wall,
                ..m.clone()
            },
            _ => Mount::plain(s),
        };
        match asset.support {
            Some(Support::Floor) => None,
            Some(s) => Some(own(s)),
            None => self
                .mount
                .clone()
                .filter(|m| m.support != Support::Floor)
                .filter(|m| m.up_to.is_none_or(|h| asset.size[2] <= h)),
        }
    }
}

/// How people sit at a piece, and so how many seats it takes.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum SeatsAt {
    /// All round (a table): a seat per [`SEAT_PITCH_CM`] of each side long enough for one.
    Around,
    /// At its front, one person per [`FRONT_PLACE_CM`] of its width (a desk, a styling
    /// station, a potter's wheel: one; a long workbench: two).
    Front,
    /// In a line along its front, one per [`STOOL_PITCH_CM`] (a bar, an island).
    AlongFront,
}

/// The deepest piece (cm) a kind's `lift` hangs on its wall.
pub const LIFT_DEPTH_CM: f64 = 10.0;

/// The tallest piece (cm) a kind's `lift` hangs on its wall.
pub const LIFT_HEIGHT_CM: f64 = 150.0;

/// Seats at least this wide (cm) are long benches (pews): two to a row, about a centre aisle.
pub const LONG_BENCH_CM: f64 = 150.0;

/// Width (cm) one person's place takes at a desk, a station or a workbench: a 2 m workbench
/// seats two, a desk or a styling station one.
pub const FRONT_PLACE_CM: f64 = 100.0;

/// Width (cm) one stool takes along a bar's or an island's front: stools stand closer than
/// chairs (a 180 cm island seats four).
pub const STOOL_PITCH_CM: f64 = 45.0;

/// Width (cm) one seat takes along a table's side.
pub const SEAT_PITCH_CM: f64 = 60.0;

impl SeatsAt {
    /// How many seats a piece of `width` x `depth` cm takes: at least one.
    pub fn capacity(self, width: f64, depth: f64) -> usize {
        // `as` saturates a huge float; the sums saturate too.
        let per = |side: f64| (side / SEAT_PITCH_CM).floor() as usize;
        let n = match self {
            SeatsAt::Front => (width / FRONT_PLACE_CM).floor() as usize,
            SeatsAt::AlongFront => (width / STOOL_PITCH_CM).floor() as usize,
            SeatsAt::Around => per(width).saturating_add(per(depth)).saturating_mul(2),
        };
        n.max(1)
    }
}

/// How the kind of an asset was found, for the notes of a run.
#[derive(Debug, Clone, PartialEq)]
pub enum Reading {
    /// Its category or name is a synonym of a kind, or contains one.
    Known,
    /// Its head noun (the category's last word, or the word before "of") names a kind, and
    /// the modifiers before it were not known (`"gaming chair"`: a chair).
    ByHead(String),
    /// No word was known: the kind was guessed from the size and shape, for this reason.
    Guessed(String),
}

/// A word before the head noun that changes where a piece stands, whatever the head noun
/// ("gondola shelving" and "double-sided bookcase" stand free; "wall cabinet" on a wall).
#[derive(Debug, Clone, PartialEq, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Modifier {
    /// The words (lower case; several words match as a phrase).
    pub words: Vec<String>,
    /// Stands against a wall (true) or free of the walls (false).
    pub wall: bool,
}

/// Words that say how many people a piece seats, whatever its width ("double desk", "twin
/// workstation", "two-person table").
#[derive(Debug, Clone, PartialEq, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SeatsNamed {
    /// The words (lower case; several words match as a phrase), in the asset's category, name
    /// or description.
    pub words: Vec<String>,
    /// The people it seats.
    pub seats: usize,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct KnowledgeFile {
    kind: Vec<Kind>,
    #[serde(default)]
    modifier: Vec<Modifier>,
    #[serde(default)]
    seats_named: Vec<SeatsNamed>,
}

/// All kinds, with lookup by category or name.
#[derive(Debug, Clone)]
pub struct Knowledge {
    kinds: Vec<Kind>,
    modifiers: Vec<Modifier>,
    seats_named: Vec<SeatsNamed>,
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

/// Whether `text` ends with the words of `tail` ("gaming chair" ends with "chair").
pub(crate) fn ends_with_words(text: &str, tail: &str) -> bool {
    text == tail || text.ends_with(&format!(" {tail}"))
}

impl Knowledge {
    /// Parses a knowledge file.
    pub fn parse(text: &str) -> Result<Self, String> {
        let file: KnowledgeFile = toml::from_str(text).map_err(|e| e.to_string())?;
        Ok(Knowledge {
            kinds: file.kind,
            modifiers: file.modifier,
            seats_named: file.seats_named,
        })
    }

    /// The built-in knowledge, parsed once.
    pub fn builtin() -> Arc<Knowledge> {
        static CELL: OnceLock<Arc<Knowledge>> = OnceLock::new();
        CELL.get_or_init(|| {
            Arc::new(Knowledge::parse(FURNITURE_TOML).expect("config/furniture.toml is valid"))
        })
        .clone()
    }

    /// The kind of a category or name: an exact synonym first, then the longest synonym the
    /// words end with (the head noun and its modifiers: "gaming chair" is a chair), then the
    /// longest synonym found among its words.
    pub fn lookup_text(&self, text: &str) -> Option<&Kind> {
        self.read_text(text).map(|(k, _)| k)
    }

    /// [`lookup_text`](Self::lookup_text), and whether the kind came from the whole text
    /// ([`Reading::Known`]) or from its head noun alone ([`Reading::ByHead`]).
    pub fn read_text(&self, text: &str) -> Option<(&Kind, Reading)> {
        let w = words(text);
        if w.is_empty() {
            return None;
        }
        if let Some(k) = self.kinds.iter().find(|k| k.names.contains(&w)) {
            return Some((k, Reading::Known));
        }
        let synonyms = || {
            self.kinds
                .iter()
                .flat_map(|k| k.names.iter().map(move |n| (k, n)))
        };
        // "X of Y" is an X: a "rack of shelves" is a rack.
        let head_phrase = w.split(" of ").next().unwrap_or(&w);
        let ending = synonyms()
            .filter(|(_, n)| ends_with_words(head_phrase, n))
            .max_by_key(|(_, n)| n.len());
        if let Some((k, n)) = ending {
            let reading = if n.contains(' ') || head_phrase == n.as_str() {
                Reading::Known
            } else {
                Reading::ByHead(n.clone())
            };
            return Some((k, reading));
        }
        synonyms()
            .filter(|(_, n)| contains_words(&w, n))
            .max_by_key(|(_, n)| n.len())
            .map(|(k, _)| (k, Reading::Known))
    }

    /// Whether `text` is, word for word, a name the knowledge lists.
    pub fn knows_exactly(&self, text: &str) -> bool {
        let w = words(text);
        self.kinds.iter().any(|k| k.names.contains(&w))
    }

    /// The kind of an asset: by category, then by name, then a guess from its size and shape;
    /// a modifier of the category ("gondola", "wall") may move it to or off the walls.
    pub fn kind_of(&self, asset: &Asset) -> Kind {
        self.read(asset).0
    }

    /// [`kind_of`](Self::kind_of), and how the kind was found.
    pub fn read(&self, asset: &Asset) -> (Kind, Reading) {
        let found = self
            .read_text(&asset.category)
            .or_else(|| self.read_text(&asset.name));
        let (mut kind, reading) = match found {
            Some((k, r)) => (k.clone(), r),
            None => {
                let (k, why) = guess(asset);
                (k, Reading::Guessed(why))
            }
        };
        // A modifier moves a piece the knowledge does not name word for word ("gondola
        // shelving" is shelving that stands free); a name it lists ("entertainment center",
        // "partition wall") keeps its own kind's place.
        // Whether it is so listed is asked only when a modifier is there at all: `kind_of` runs
        // for every piece the designer looks at, and few categories hold a modifier.
        let category = words(&asset.category);
        if let Some(m) = self
            .modifiers
            .iter()
            .find(|m| m.words.iter().any(|w| contains_words(&category, w)))
            && !self.knows_exactly(&category)
            && !self.knows_exactly(&asset.name)
        {
            kind.wall = m.wall;
        }
        // A piece its description puts on a wall ("wall units of spectacle frames", "fixed to
        // the wall", "for spectators along the wall") stands on one, whatever its kind.
        if !kind.wall
            && !kind.seat
            && !asset.is_flat()
            && !self.knows_exactly(&asset.category)
            && asset
                .description
                .as_deref()
                .is_some_and(|d| words(d).split(' ').any(|w| w == "wall" || w == "walls"))
        {
            kind.wall = true;
        }
        // A piece its description says people work behind ("boarding desk, agents work behind
        // it") is a counter that serves: it stands free, its staff side kept clear.
        if kind.staff == 0.0
            && !kind.seat
            && asset.size[2] >= STAFFED_MIN_CM
            && asset.description.as_deref().is_some_and(worked_from_behind)
            && let Some(counter) = self.lookup_text(SERVING_COUNTER)
        {
            kind = counter.clone();
        }
        if kind.seats.is_some() {
            kind.seats_least = self.seats_named_in(asset);
        }
        (kind, reading)
    }

    /// The people `asset`'s own words say it seats (its category, name or description: "a
    /// double desk"), 0 when none do.
    pub fn seats_named_in(&self, asset: &Asset) -> usize {
        let text = format!(
            "{} {} {}",
            words(&asset.category),
            words(&asset.name),
            asset.description.as_deref().map(words).unwrap_or_default()
        );
        self.seats_named
            .iter()
            .filter(|s| s.words.iter().any(|w| contains_words(&text, w)))
            .map(|s| s.seats)
            .max()
            .unwrap_or(0)
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

    /// [`target_rank`](Self::target_rank), stricter: a name the asset's kind lists counts only
    /// when the asset's category holds the name's last word ("double vanity" is a vanity; the
    /// toilet, of the same family of bathroom fixtures, is not). For what goes on or above a
    /// piece, where the family is too wide a net.
    pub fn named_rank(asset: &Asset, kind: &Kind, to: &[String]) -> Option<usize> {
        let cat = words(&asset.category);
        to.iter()
            .enumerate()
            .filter_map(|(i, name)| {
                let head = name.rsplit(' ').next().unwrap_or(name);
                if cat == *name {
                    Some(2 * i)
                } else if kind.names.contains(name) && contains_words(&cat, head) {
                    Some(2 * i + 1)
                } else {
                    None
                }
            })
            .min()
    }
}

/// A piece at least this tall (cm) and at most [`THIN_DEPTH_CM`] deep is a wall piece (a rack,
/// a machine, a tall cabinet).
const TALL_CM: f64 = 140.0;
/// See [`TALL_CM`].
const THIN_DEPTH_CM: f64 = 90.0;
/// A footprint of at least this area (cm²) no taller than [`LOW_CM`] is a centre piece people
/// walk round (a game table, a display, an instrument).
const CENTRE_AREA_CM2: f64 = 15_000.0;
/// See [`CENTRE_AREA_CM2`]; it must also be at least [`THIN_DEPTH_CM`] on its short side.
const LOW_CM: f64 = 120.0;

/// The kind a piece takes when its description says people work behind it.
const SERVING_COUNTER: &str = "serving counter";

/// The lowest piece (cm) people work behind standing or seated at a counter.
const STAFFED_MIN_CM: f64 = 70.0;

/// Whether a description says people work behind the piece ("staff work behind it", "officers
/// behind it", "the chef works behind the counter").
fn worked_from_behind(description: &str) -> bool {
    let d = words(description);
    contains_words(&d, "behind it") || contains_words(&d, "behind the counter")
}

/// A footprint of at least this area (cm²) and [`VAST_SHORT_CM`] on its short side stands free
/// whatever its height: a car in a showroom, a boat, a large machine people walk round.
const VAST_AREA_CM2: f64 = 30_000.0;
/// See [`VAST_AREA_CM2`].
const VAST_SHORT_CM: f64 = 120.0;

/// A kind for a category no word of which is known, from its size and shape, and the reason in
/// words: flat things cover the floor; tall, thin things stand on a wall; large, low things
/// stand free in the room with room all round; the rest stand by a wall. (A seat-sized thing
/// is not taken for a seat: seats have names people know, and a cart, an amplifier or a globe
/// is seat-sized too.)
fn guess(asset: &Asset) -> (Kind, String) {
    let [w, d, h] = asset.size;
    let short = w.min(d);
    let mut kind = Kind {
        names: vec![words(&asset.category)],
        wall: true,
        centred: false,
        rows: Vec::new(),
        seat: false,
        priority: 40,
        clearance: 50.0,
        relate: None,
        run: None,
        seats: None,
        staff: 0.0,
        places: Vec::new(),
        formation: None,
        spacing: None,
        faces: Vec::new(),
        at_least: 0,
        mount: None,
        lift: None,
        seats_least: 0,
    };
    let why = if asset.is_flat() {
        kind.wall = false;
        kind.priority = 1;
        kind.clearance = 0.0;
        "flat: a floor covering"
    } else if w * d >= VAST_AREA_CM2 && short >= VAST_SHORT_CM {
        kind.wall = false;
        kind.priority = 70;
        kind.clearance = 100.0;
        "vast: a free-standing piece people walk round"
    } else if h >= TALL_CM && short <= THIN_DEPTH_CM {
        kind.priority = 45;
        kind.clearance = 70.0;
        "tall and thin: a wall piece"
    } else if w * d >= CENTRE_AREA_CM2 && short >= THIN_DEPTH_CM && h <= LOW_CM {
        kind.wall = false;
        kind.priority = 60;
        kind.clearance = 90.0;
        "large and low: a free-standing centre piece"
    } else if w * d < 2_500.0 {
        kind.priority = 10;
        kind.clearance = 0.0;
        "small: by a wall"
    } else {
        "a piece by a wall"
    };
    (kind, why.to_string())
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
        let (big, how) = k.read(&Asset::new("x-0", "zorbotron", [300.0, 80.0, 110.0]));
        assert!(big.wall, "long and deep but narrow: a wall piece");
        assert!(matches!(how, Reading::Guessed(_)));
        let (tall, how) = k.read(&Asset::new("s-0", "zorbotron", [60.0, 60.0, 180.0]));
        assert!(tall.wall && !tall.seat);
        assert_eq!(how, Reading::Guessed("tall and thin: a wall piece".into()));
        let (centre, _) = k.read(&Asset::new("t-0", "zorbotron", [150.0, 250.0, 90.0]));
        assert!(!centre.wall, "large and low: free-standing");
        let (car, how) = k.read(&Asset::new("car-0", "car", [185.0, 460.0, 145.0]));
        assert!(!car.wall, "vast, however tall: free-standing");
        assert!(matches!(how, Reading::Guessed(w) if w.starts_with("vast")));
        let mut gate = Asset::new("gate-counter-0", "gate counter", [250.0, 70.0, 105.0]);
        gate.description = Some("boarding desk, agents work behind it".into());
        let served = k.kind_of(&gate);
        assert!(
            served.staff > 0.0 && !served.wall,
            "worked from behind: a serving counter"
        );
        let (small, _) = k.read(&Asset::new("c-0", "zorbotron", [45.0, 45.0, 80.0]));
        assert!(!small.seat && small.wall, "seat-sized is not a seat");
        let rug = k.kind_of(&Asset::new("y-0", "tatami", [200.0, 100.0, 2.0]));
        assert!(!rug.wall && rug.priority == 1);
    }
}
