//! The arrangement test set (`bench/patterns/`): each scene's prompt names an arrangement (rows
//! facing a board, a U, an island with stools, a tub in the middle...), and `expect.toml` beside
//! the scenes says which pattern and which objects. [`check`] decides, from the layout alone,
//! whether the arrangement was built: one geometric predicate per [`Pattern`] (in
//! [`predicates`]), plus the wall fixtures the scene lists under `on_wall`.
//!
//! The expectations never live in the scene files, so the scenes stay plain `disco validate`
//! input that any method can be run on.

pub mod predicates;
#[cfg(test)]
mod tests;

use std::collections::BTreeMap;
use std::path::Path;

use serde::Deserialize;

use crate::error::{Error, Result};
use crate::layout::{Layout, PlacedObject};

/// The arrangements a prompt of the set can name.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Pattern {
    /// Rows facing a focal wall piece (classroom, lecture hall, cinema).
    Rows,
    /// Three runs around a space open to the focal piece (U, horseshoe).
    UShape,
    /// One run over two adjacent walls, meeting at their corner.
    LShape,
    /// A free-standing island with seats at it.
    Island,
    /// Two runs on opposite walls.
    Galley,
    /// One run on a single wall.
    OneWall,
    /// A kitchen work zone: the `pair` side by side on one wall, and an optional triangle.
    WorkZone,
    /// Members around a centre piece, on more than one side, turned to it.
    Around,
    /// The focal piece in a corner.
    Corner,
    /// The focal piece free in the middle of the room.
    Centred,
    /// The `pair` mirrored about the focal piece's axis.
    SymmetricPair,
    /// Seats turned to a shared focus (a coffee table, a TV), the screen seen unblocked.
    Conversation,
    /// Every member against a wall.
    AlongWall,
}

/// What one scene asks for: its pattern and the objects it applies to (by name).
#[derive(Debug, Clone, PartialEq, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Expectation {
    /// The arrangement the prompt names.
    pub pattern: Pattern,
    /// The piece the arrangement is about (the board, the island, the bed, the tub).
    #[serde(default)]
    pub focal: Option<String>,
    /// The pieces that make up the arrangement (desks, counters, chairs around a table).
    #[serde(default)]
    pub members: Vec<String>,
    /// The seats that must face what they are for.
    #[serde(default)]
    pub seats: Vec<String>,
    /// Two pieces that belong together (nightstands, sink and dishwasher).
    #[serde(default)]
    pub pair: Vec<String>,
    /// Fridge, stove and sink of a work triangle.
    #[serde(default)]
    pub triangle: Vec<String>,
    /// A screen the seats must see without anything tall in between.
    #[serde(default)]
    pub screen: Option<String>,
    /// How far (cm) from each of its two walls a piece in a corner may stand.
    #[serde(default)]
    pub within: Option<f64>,
    /// Wall fixtures that must stay against a wall whatever else moves.
    #[serde(default)]
    pub on_wall: Vec<String>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct ExpectFile {
    scene: BTreeMap<String, Expectation>,
}

/// Reads `expect.toml`: scene id -> what it asks for.
pub fn load_expectations(path: &Path) -> Result<BTreeMap<String, Expectation>> {
    let text = std::fs::read_to_string(path).map_err(|source| Error::Read {
        path: path.to_path_buf(),
        source,
    })?;
    let file: ExpectFile = toml::from_str(&text).map_err(|e| Error::Invalid {
        path: path.to_path_buf(),
        field: "scene".into(),
        reason: e.to_string(),
    })?;
    Ok(file.scene)
}

/// Whether a layout builds the arrangement, and if not, the first reason why not.
#[derive(Debug, Clone, PartialEq)]
pub struct Verdict {
    /// The predicate holds.
    pub met: bool,
    /// What failed, empty when met.
    pub why: String,
}

impl Verdict {
    fn from(result: std::result::Result<(), String>) -> Self {
        match result {
            Ok(()) => Verdict {
                met: true,
                why: String::new(),
            },
            Err(why) => Verdict { met: false, why },
        }
    }
}

/// The objects of a layout by name; a name the layout lacks (dropped) fails the predicate.
pub(crate) struct Named<'a> {
    layout: &'a Layout,
}

impl<'a> Named<'a> {
    /// The placed object called `name`.
    pub(crate) fn get(&self, name: &str) -> std::result::Result<&'a PlacedObject, String> {
        self.layout
            .object(name)
            .ok_or_else(|| format!("{name} is not placed"))
    }

    /// The placed objects called `names`, in that order.
    pub(crate) fn all(
        &self,
        names: &[String],
    ) -> std::result::Result<Vec<&'a PlacedObject>, String> {
        names.iter().map(|n| self.get(n)).collect()
    }

    /// The focal object, which the pattern needs.
    pub(crate) fn focal(&self, e: &Expectation) -> std::result::Result<&'a PlacedObject, String> {
        let name = e
            .focal
            .as_deref()
            .ok_or("the expectation names no focal piece")?;
        self.get(name)
    }
}

/// Checks `layout` against what its scene asks for.
pub fn check(layout: &Layout, e: &Expectation) -> Verdict {
    use predicates as p;
    let named = Named { layout };
    let room = &layout.room;
    let result = (|| {
        let on_wall = named.all(&e.on_wall)?;
        p::all_on_walls(room, &on_wall)?;
        match e.pattern {
            Pattern::Rows => p::rows(
                named.focal(e)?,
                &named.all(&e.members)?,
                &named.all(&e.seats)?,
            ),
            Pattern::UShape => p::u_shape(
                named.focal(e)?,
                &named.all(&e.members)?,
                &named.all(&e.seats)?,
            ),
            Pattern::LShape => p::l_shape(room, &named.all(&e.members)?),
            Pattern::Island => p::island(room, named.focal(e)?, &named.all(&e.seats)?),
            Pattern::Galley => p::galley(room, &named.all(&e.members)?),
            Pattern::OneWall => p::one_wall(room, &named.all(&e.members)?),
            Pattern::WorkZone => p::work_zone(room, &named.all(&e.pair)?, &named.all(&e.triangle)?),
            Pattern::Around => p::around(named.focal(e)?, &named.all(&e.members)?),
            Pattern::Corner => p::corner(room, named.focal(e)?, e.within.unwrap_or(30.0)),
            Pattern::Centred => p::centred(room, named.focal(e)?),
            Pattern::SymmetricPair => p::symmetric_pair(named.focal(e)?, &named.all(&e.pair)?),
            Pattern::Conversation => {
                let screen = e.screen.as_deref().map(|s| named.get(s)).transpose()?;
                p::conversation(layout, named.focal(e)?, &named.all(&e.seats)?, screen)
            }
            Pattern::AlongWall => p::all_on_walls(room, &named.all(&e.members)?),
        }
    })();
    Verdict::from(result)
}

/// One scene's outcome on the set.
#[derive(Debug, Clone)]
pub struct PatternResult {
    /// The scene id.
    pub id: String,
    /// The pattern it asks for.
    pub pattern: Pattern,
    /// Whether the layout builds it.
    pub verdict: Verdict,
}

/// The set's table: per pattern, scenes and how many met their predicate, then the total.
pub fn to_markdown(results: &[PatternResult]) -> String {
    let mut by: BTreeMap<String, (usize, usize)> = BTreeMap::new();
    for r in results {
        let e = by.entry(format!("{:?}", r.pattern)).or_default();
        e.0 += 1;
        e.1 += usize::from(r.verdict.met);
    }
    let mut out = String::from("| pattern | scenes | met |\n|---|---|---|\n");
    for (p, (n, met)) in &by {
        out.push_str(&format!("| {p} | {n} | {met} |\n"));
    }
    let met = results.iter().filter(|r| r.verdict.met).count();
    out.push_str(&format!(
        "| all | {} | {met} ({:.0}%) |\n",
        results.len(),
        100.0 * met as f64 / results.len().max(1) as f64
    ));
    out
}
