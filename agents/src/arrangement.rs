//! Arrangements of several pieces named in a prompt, for the rule agents. Each is triggered by
//! words of the prompt (matched on its lower-case words, hyphens split) and applies to the
//! pieces the plan stands against a wall as anchors (no relation of their own):
//!
//! | arrangement | trigger | what the designer does |
//! |---|---|---|
//! | [`RunShape::Galley`] | "galley", "parallel" | the wall pieces split over the two long walls, by width, each run packed from the same end |
//! | [`RunShape::OneWall`] | "on one wall", "single wall", "one line", "one-wall kitchen" (not "along one wall", which is said of a single piece) | every wall piece on the longest wall, packed from one end |
//! | [`RunShape::LShape`] | "l shape", "l shaped", "an l" | the wall pieces on the longest wall and the wall left of it, packed into their shared corner |
//! | U before a board ([`names_u_shape`]) | "u shape", "u shaped", "horseshoe" | desks that would stand in rows before a board form a U open to it instead |
//!
//! In a room whose outline has more than four corners, "L-shaped" and "U-shaped" usually say
//! what the room looks like ("an L-shaped studio"): there they name an arrangement only when one
//! of the next two words is a piece that can form one ("an L-shaped counter", "a U-shaped
//! sectional"), see [`ARRANGED_PIECES`]. In a rectangle every such phrase names an arrangement.
//!
//! The patterns of one or two pieces (in a corner, in the middle, around a table, a pair on both
//! sides) are read by [`crate::hints`]; rows and U shapes before a board by the row designer.

use std::collections::HashMap;

use glam::DVec2;

use disco_core::geometry::Wall;
use disco_core::plan::Plan;
use disco_core::scene::{Room, SceneSpec};

/// How wall pieces form runs along the walls.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum RunShape {
    /// Two runs on opposite (long) walls facing across an aisle.
    Galley,
    /// One run on a single wall.
    OneWall,
    /// One run over two adjacent walls, turning at their corner.
    LShape,
}

/// Where one wall piece of a run goes: the walls it may stand on, and the point its run is packed
/// towards (a corner of the room).
#[derive(Debug, Clone, PartialEq)]
pub struct RunSlot {
    /// The walls it may stand against.
    pub walls: Vec<Wall>,
    /// The run is packed towards this point.
    pub towards: DVec2,
    /// The furniture forms this run by itself (a kitchen's work pieces), the prompt names none:
    /// it holds its pieces together less hard, and never in a cramped spot.
    pub joined: bool,
}

impl RunSlot {
    /// Score a spot loses per cm it stands from `towards`. A run the prompt names holds hard (a
    /// gap in a counter run the prompt asked for is worse than a cramped spot); a joined run
    /// lets a piece go a metre further for room for its dependents (a dishwasher by the sink).
    pub fn pull(&self) -> f64 {
        if self.joined { 1.0 } else { 3.0 }
    }
}

/// The lower-case words of a prompt, hyphens and punctuation split.
fn prompt_words(prompt: &str) -> Vec<String> {
    prompt
        .to_lowercase()
        .split(|c: char| !c.is_alphanumeric())
        .filter(|w| !w.is_empty())
        .map(str::to_string)
        .collect()
}

/// Words that, right after "L-shaped" or "U-shaped", name pieces forming the shape rather than
/// the room: in a room of that outline only these make the phrase an arrangement.
pub const ARRANGED_PIECES: [&str; 22] = [
    "counter",
    "counters",
    "run",
    "runs",
    "worktop",
    "worktops",
    "cabinets",
    "cabinetry",
    "units",
    "desk",
    "desks",
    "table",
    "tables",
    "bench",
    "benches",
    "sofa",
    "sectional",
    "seating",
    "couch",
    "bar",
    "layout",
    "arrangement",
];

/// The letter shapes a prompt may give an arrangement.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Letter {
    L,
    U,
}

/// Whether `w` (a prompt's words) names the `letter` shape for an arrangement in `room`: a
/// phrase for it ("l shaped", "u shape", "an l", "horseshoe") that, when the room's outline has
/// more than four corners and the phrase is an adjective ("an L-shaped ...", not "in an L" or
/// "a horseshoe"), is followed within two words by one of [`ARRANGED_PIECES`].
fn names_letter(w: &[String], letter: Letter, room: &Room) -> bool {
    let phrases: &[&[&str]] = match letter {
        Letter::L => &[&["l", "shape"], &["l", "shaped"], &["an", "l"]],
        Letter::U => &[&["u", "shape"], &["u", "shaped"], &["horseshoe"]],
    };
    let shaped_room = room.polygon.as_ref().is_some_and(|p| p.len() > 4);
    let is_shape = |x: &String| x == "shape" || x == "shaped";
    phrases.iter().any(|p| {
        w.windows(p.len()).enumerate().any(|(i, x)| {
            let after = i + p.len();
            // "an l shaped" is read as "l shaped".
            if x != *p || (p[0] == "an" && w.get(after).is_some_and(is_shape)) {
                return false;
            }
            // "in an L", "a horseshoe": nouns, never the room's outline.
            let adjective = p.last().is_some_and(|l| *l == "shape" || *l == "shaped");
            !shaped_room
                || !adjective
                || w[after..]
                    .iter()
                    .take(2)
                    .any(|x| ARRANGED_PIECES.contains(&x.as_str()))
        })
    })
}

/// The run shape the prompt names for `room`, if any (see the table in the module's
/// documentation).
pub fn read_run_shape(prompt: &str, room: &Room) -> Option<RunShape> {
    let w = prompt_words(prompt);
    let has = |p: &[&str]| w.windows(p.len()).any(|x| x == p);
    if has(&["galley"]) || has(&["parallel"]) {
        Some(RunShape::Galley)
    } else if names_letter(&w, Letter::L, room) {
        Some(RunShape::LShape)
    } else if has(&["on", "one", "wall"])
        || has(&["single", "wall"])
        || has(&["one", "line"])
        || has(&["one", "wall", "kitchen"])
    {
        Some(RunShape::OneWall)
    } else {
        None
    }
}

/// Whether the prompt asks for a U (or horseshoe) of desks rather than rows in `room`.
pub fn names_u_shape(prompt: &str, room: &Room) -> bool {
    names_letter(&prompt_words(prompt), Letter::U, room)
}

/// How `n` desks split over a U: the number down each arm and across its far end; `None` when
/// there are too few for both arms and the far end. Laid out as a snake (down the left arm,
/// across, up the right arm), the first desk across and the first up the right arm turn a corner.
pub fn u_runs(n: usize) -> Option<(usize, usize)> {
    let side = n.div_ceil(3).max(2);
    let across = n.checked_sub(2 * side).filter(|&k| k >= 1)?;
    Some((side, across))
}

/// Which of `n` desks laid out as a U snake (see [`u_runs`]) turn a corner of the U: they meet
/// the desk before them end to side, not in line. Empty when `n` desks make no U.
pub fn u_corners(n: usize) -> Vec<usize> {
    u_runs(n).map_or_else(Vec::new, |(side, across)| vec![side, side + across])
}

/// The room's longest wall: for a rectangle bottom when it is at least as wide as deep, else
/// left; for an outline its longest edge.
fn longest_wall(room: &Room) -> Wall {
    let walls = Wall::all(room);
    if room.is_rectangle() {
        return walls[if room.width >= room.depth { 0 } else { 3 }];
    }
    walls.iter().copied().fold(walls[0], |best, w| {
        if w.length() > best.length() + 1e-9 {
            w
        } else {
            best
        }
    })
}

/// The wall that turns the corner from `long`: on a rectangle the one meeting it at the origin
/// (left for the bottom wall, else bottom), on an outline the longer of its two neighbours.
fn corner_wall(room: &Room, long: Wall) -> Wall {
    let walls = Wall::all(room);
    let n = walls.len();
    if room.is_rectangle() {
        return walls[if long.index() == 0 { 3 } else { 0 }];
    }
    let (before, after) = (
        walls[(long.index() + n - 1) % n],
        walls[(long.index() + 1) % n],
    );
    if before.length() > after.length() {
        before
    } else {
        after
    }
}

/// The wall across from `long`: on a rectangle the opposite side, on an outline the longest
/// wall running the other way.
fn opposite_wall(room: &Room, long: Wall) -> Wall {
    let walls = Wall::all(room);
    if room.is_rectangle() {
        return walls[(long.index() + 2) % 4];
    }
    walls
        .iter()
        .copied()
        .filter(|w| w.direction().dot(long.direction()) < -0.9)
        .fold(None, |best: Option<Wall>, w| match best {
            Some(b) if b.length() >= w.length() => Some(b),
            _ => Some(w),
        })
        .unwrap_or(long)
}

/// The run slot of every wall anchor of the plan, by name, for the run shape the prompt names;
/// empty when it names none.
pub fn run_slots(scene: &SceneSpec, plan: &Plan) -> HashMap<String, RunSlot> {
    let Some(shape) = read_run_shape(&scene.prompt, &scene.room) else {
        return HashMap::new();
    };
    let room = &scene.room;
    let members: Vec<(&str, f64)> = scene
        .assets
        .iter()
        .filter(|a| !a.is_flat())
        .filter(|a| {
            plan.constraints
                .get(&a.name)
                .is_some_and(|c| c.against_wall && c.relations.is_empty())
        })
        .map(|a| (a.name.as_str(), a.size[0]))
        .collect();
    let long = longest_wall(room);
    let origin = DVec2::ZERO;
    let slot = |walls: Vec<Wall>| RunSlot {
        walls,
        towards: origin,
        joined: false,
    };
    match shape {
        RunShape::OneWall => members
            .iter()
            .map(|(n, _)| (n.to_string(), slot(vec![long])))
            .collect(),
        RunShape::LShape => {
            let other = corner_wall(room, long);
            members
                .iter()
                .map(|(n, _)| (n.to_string(), slot(vec![long, other])))
                .collect()
        }
        RunShape::Galley => {
            let opposite = opposite_wall(room, long);
            let mut used = [0.0, 0.0];
            let mut widest: Vec<&(&str, f64)> = members.iter().collect();
            widest.sort_by(|a, b| b.1.total_cmp(&a.1));
            widest
                .into_iter()
                .map(|(n, w)| {
                    let side = usize::from(used[1] < used[0]);
                    used[side] += w;
                    (n.to_string(), slot(vec![[long, opposite][side]]))
                })
                .collect()
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A 600 x 400 rectangle.
    fn rect() -> Room {
        Room::rect(600.0, 400.0)
    }

    /// An L-shaped outline (six corners).
    fn l_room() -> Room {
        Room::from_polygon(vec![
            [0.0, 0.0],
            [600.0, 0.0],
            [600.0, 300.0],
            [350.0, 300.0],
            [350.0, 500.0],
            [0.0, 500.0],
        ])
    }

    #[test]
    fn triggers() {
        let r = rect();
        let shape = |p: &str| read_run_shape(p, &r);
        assert_eq!(shape("a galley kitchen"), Some(RunShape::Galley));
        assert_eq!(shape("two parallel counter runs"), Some(RunShape::Galley));
        assert_eq!(shape("an L-shaped kitchen"), Some(RunShape::LShape));
        assert_eq!(shape("desks joined in an L"), Some(RunShape::LShape));
        assert_eq!(
            shape("washer and dryer side by side on one wall"),
            Some(RunShape::OneWall)
        );
        assert_eq!(shape("a living room"), None);
        assert_eq!(shape("a double vanity along one wall"), None);
        assert!(names_u_shape("desks form a U-shape facing the screen", &r));
        assert!(names_u_shape("tables set out as a horseshoe", &r));
        assert!(!names_u_shape("a seminar room", &r));
        assert_eq!(shape("a hall with tall walls"), None);
    }

    #[test]
    fn in_a_shaped_room_the_letter_describes_the_room_unless_pieces_follow() {
        let l = l_room();
        let shape = |p: &str| read_run_shape(p, &l);
        // The room's own shape: no run of every wall piece into one corner.
        assert_eq!(
            shape("an L-shaped living room with a sofa facing the TV"),
            None
        );
        assert_eq!(shape("an L-shaped kitchen with a small table"), None);
        assert_eq!(shape("an L-shaped open office with a meeting table"), None);
        assert!(!names_u_shape("a U-shaped library with reading tables", &l));
        // Pieces named right after the letter still form it.
        assert_eq!(
            shape("an L-shaped studio with an L-shaped counter run"),
            Some(RunShape::LShape)
        );
        assert_eq!(shape("desks joined in an L"), Some(RunShape::LShape));
        assert!(names_u_shape("a U-shaped sectional before the TV", &l));
        // Other arrangements are read as in any room.
        assert_eq!(shape("an L-shaped galley"), Some(RunShape::Galley));
    }

    #[test]
    fn u_runs_and_their_corners() {
        // 8 desks: 3 down each arm, 2 across; the 4th and the 6th turn a corner.
        assert_eq!(u_runs(8), Some((3, 2)));
        assert_eq!(u_corners(8), vec![3, 5]);
        assert_eq!(u_runs(7), Some((3, 1)));
        assert_eq!(u_corners(7), vec![3, 4]);
        // Too few for two arms and a far end.
        assert_eq!(u_runs(4), None);
        assert!(u_corners(4).is_empty());
    }
}
