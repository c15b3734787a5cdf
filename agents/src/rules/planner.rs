//! The rule-based planner: constraints from the furniture knowledge, groups around anchors.

use std::collections::{BTreeMap, HashMap};
use std::sync::Arc;

use async_trait::async_trait;

use super::mounting::{Mounted, Wish, mount_all};
use super::seating::{share_seats, share_words};
use crate::arrangement::{names_u_shape, u_corners};
use crate::hints::{FormationHint, Hint, PromptHint, read_hints_apart, unread_phrases};
use crate::kinship::OwnWords;
use crate::knowledge::{Kind, Knowledge, Reading, SeatsAt, words};
use disco_core::plan::{
    Formation, FormationShape, ObjectConstraints, Place, Plan, Relation, RelationSpec,
};
use disco_core::roles::{Output, Planner, RoleResult};
use disco_core::scene::{SceneSpec, Support};

/// Plans from `config/furniture.toml`: every asset gets its kind's wall flag and relation to the
/// best-matching target present (spreading dependents over several targets), and each anchor forms
/// a group with everything that depends on it, anchors by priority.
pub struct RulePlanner {
    knowledge: Arc<Knowledge>,
}

impl RulePlanner {
    /// A planner over the built-in knowledge.
    pub fn new() -> Self {
        RulePlanner {
            knowledge: Knowledge::builtin(),
        }
    }
}

impl Default for RulePlanner {
    fn default() -> Self {
        Self::new()
    }
}

/// Whether the room has the parts `place` names: the zone, a wall of the role, a main door, a
/// corner, a window.
fn room_has(
    room: &disco_core::scene::Room,
    analysis: &disco_core::room::analysis::RoomAnalysis,
    place: &Place,
) -> bool {
    place
        .zone
        .as_deref()
        .is_none_or(|z| !analysis.zones_named(z).is_empty())
        && place
            .wall
            .is_none_or(|w| !analysis.walls_with(w).is_empty())
        && (!place.by_entrance || analysis.main_door.is_some())
        && (!place.far_corner || !analysis.corners.is_empty())
        && (!place.under_window || !room.windows.is_empty())
}

/// Whether the zone a kind's `place` names (if any) has a part away from the main door: the
/// stem of a T that people enter by is no stage's or altar's recess, whatever its shape.
fn quiet_zone(
    room: &disco_core::scene::Room,
    analysis: &disco_core::room::analysis::RoomAnalysis,
    place: &Place,
) -> bool {
    let Some(zone) = place.zone.as_deref() else {
        return true;
    };
    let door = analysis.main_door.and_then(|i| room.door_middle(i));
    analysis
        .zones_named(zone)
        .iter()
        .any(|z| door.is_none_or(|d| !z.contains(d, DOOR_SLACK_CM)))
}

/// How far (cm) outside a zone's box the main door's middle may lie and still count as the
/// zone's door.
const DOOR_SLACK_CM: f64 = 30.0;

/// Words of a seat's category that say what kind of seat it is, not whose ("counter height
/// stool" is a tall stool, not the kitchen counter's).
const SEAT_QUALIFIERS: [&str; 8] = [
    "counter", "bar", "height", "high", "low", "swivel", "folding", "stacking",
];

/// Members from which rows or an arc are laid out before the other groups of the floor.
const ARRANGED_MEMBERS: usize = 4;

/// Kinds of at most this placement priority are small pieces (carts, stands, lamps) that may
/// gather by name at the piece they serve.
const SMALL_PRIORITY: i32 = 45;

/// How much wider (cm) than its counter the stock behind it may run.
const STOCK_OVERHANG_CM: f64 = 100.0;

/// How many dependents of one relation a target takes before the next target is preferred.
fn capacity(relation: Relation) -> usize {
    match relation {
        Relation::SideOf => 2,
        Relation::InFrontOf | Relation::Opposite => 1,
        _ => usize::MAX,
    }
}

impl RulePlanner {
    /// The plan, synchronously: each asset's target by the knowledge, desks lined up in rows,
    /// the prompt's hints on top, then constraints and groups.
    pub fn make_plan(&self, scene: &SceneSpec) -> Plan {
        self.plan_with_notes(scene).0
    }

    /// [`make_plan`](Self::make_plan), and the notes a run should carry about it: the
    /// categories whose kind was read from the head noun alone or guessed from the shape, and
    /// the seats nothing had room for.
    pub fn plan_with_notes(&self, scene: &SceneSpec) -> (Plan, Vec<String>) {
        let readings: Vec<(Kind, Reading)> = scene
            .assets
            .iter()
            .map(|a| self.knowledge.read(a))
            .collect();
        let kinds: Vec<Kind> = readings.iter().map(|(k, _)| k.clone()).collect();
        let mut notes = reading_notes(scene, &readings);
        let mut draft = Draft::by_knowledge(scene, &kinds);
        draft.orphans_to_walls(&kinds);
        let analysis = scene.room.analysis();
        for (i, k) in kinds.iter().enumerate() {
            let fits = |p: &&Place| {
                room_has(&scene.room, &analysis, p) && quiet_zone(&scene.room, &analysis, p)
            };
            if let Some(place) = k
                .places
                .iter()
                .find(fits)
                .filter(|_| draft.target[i].is_none())
            {
                draft.put(i, place);
            }
        }
        draft.form_by_kind(scene, &self.knowledge, &kinds);
        draft.stock_behind_counters(scene, &kinds);
        draft.gather_by_name(scene, &kinds);
        let mut placed = draft.seat_companions(scene, &self.knowledge);
        let (described, asked) = read_hints_apart(scene, &self.knowledge);
        // Seats the prompt arranges in a formation of their own (a ring, an arc, rows) are no
        // table's seats: they are neither shared out nor left over.
        for i in formation_members(described.iter().chain(&asked)) {
            placed[i] = true;
        }
        notes.extend(draft.seat_everyone(scene, &kinds, &placed));
        draft.apply_hints(scene, &self.knowledge, &kinds, &described, &asked);
        notes.extend(
            unread_phrases(scene, &self.knowledge)
                .into_iter()
                .map(|p| format!("not understood in the prompt: \"{p}\"")),
        );
        notes.extend(draft.mount(scene, &kinds));
        draft.hold_letters();
        let plan = Plan {
            constraints: draft.constraints(scene),
            groups: draft.groups(scene, &kinds),
            formations: draft.formations(scene),
        };
        (plan, notes)
    }
}

/// Words of a seat for the people a desk's worker receives.
const VISITOR_WORDS: [&str; 5] = ["visitor", "customer", "client", "guest", "patient"];

/// Width (cm) of a desk each visitor across it takes.
const VISITOR_PITCH_CM: f64 = 60.0;

/// The assets the prompt puts in a formation of their own, about no table they sit at: rings,
/// arcs, rows, blocks and pieces one per (or behind each) member. Seats down the sides or along
/// the front of a table are that table's seats, and not among them.
fn formation_members<'h>(hints: impl Iterator<Item = &'h PromptHint>) -> Vec<usize> {
    hints
        .filter(|h| {
            matches!(&h.hint, Hint::Formation(f)
                if !matches!(f.shape, FormationShape::PerSide | FormationShape::AlongFront))
        })
        .flat_map(|h| h.subjects.iter().copied())
        .collect()
}

/// A formation by asset index: shape, focus, count, members and (one per member) their objects.
type DraftFormation = (
    FormationShape,
    Option<usize>,
    Option<usize>,
    Vec<usize>,
    Vec<usize>,
);

/// How many dependents of each relation every target has taken, by (target, relation).
type Load = HashMap<(usize, Relation), usize>;

/// The plan in the making, one entry per scene asset (by index).
struct Draft {
    /// The asset each one depends on, if any.
    target: Vec<Option<usize>>,
    /// Its relation to that target.
    relation: Vec<Option<Relation>>,
    /// The asset it faces, if any.
    facing: Vec<Option<usize>>,
    /// Whether it stands against a wall.
    wall: Vec<bool>,
    /// Where in the room the prompt puts it, if anywhere.
    place: Vec<Option<Place>>,
    /// Formations the prompt asks for, by asset index.
    formations: Vec<DraftFormation>,
    /// How many dependents of each relation every target has taken.
    load: Load,
    /// Stock on a counter's staff side: before the counter, and against the wall all the same.
    stock: Vec<bool>,
    /// Where it goes off the floor, if it does.
    support: Vec<Option<Support>>,
    /// The prompt put it on a wall ("the TV on the wall").
    asked_wall: Vec<bool>,
}

impl Draft {
    /// The draft the knowledge alone gives: targets by kind, rows of desks, each kind's wall
    /// flag and facing.
    fn by_knowledge(scene: &SceneSpec, kinds: &[Kind]) -> Self {
        let (target, load) = choose_targets(scene, kinds);
        let mut draft = Draft {
            target,
            relation: Vec::new(),
            facing: Vec::new(),
            wall: kinds.iter().map(|k| k.wall).collect(),
            place: vec![None; kinds.len()],
            formations: Vec::new(),
            load,
            stock: vec![false; kinds.len()],
            support: vec![None; kinds.len()],
            asked_wall: vec![false; kinds.len()],
        };
        let (in_rows, at_u_corner) = draft.line_up_rows(scene, kinds);
        let n = kinds.len();
        draft.relation = (0..n)
            .map(|i| {
                // A desk turning a corner of a U meets the one before it end to side.
                if at_u_corner[i] {
                    return Some(Relation::Near);
                }
                if in_rows[i] {
                    return Some(Relation::AlignedWith);
                }
                let rel = kinds[i].relate.as_ref().map(|r| r.relation);
                // A chair at a desk of the rows sits at its front, not around it.
                let at_row_desk = draft.target[i].is_some_and(|t| !kinds[t].rows.is_empty());
                match rel {
                    Some(Relation::Around) if at_row_desk => Some(Relation::InFrontOf),
                    other => other,
                }
            })
            .collect();
        draft.facing = (0..n)
            .map(|i| {
                draft.target[i]
                    .filter(|_| !in_rows[i] && kinds[i].relate.as_ref().is_some_and(|r| r.face))
            })
            .collect();
        draft
    }

    /// Rows (student desks before a board): each desk lines up with the one of its kind before
    /// it, when there is something for the rows to face. Which assets stand in rows, and which
    /// of them turn a corner of a U the prompt asks for (see [`u_corners`]).
    fn line_up_rows(&mut self, scene: &SceneSpec, kinds: &[Kind]) -> (Vec<bool>, Vec<bool>) {
        let n = kinds.len();
        let mut in_rows = vec![false; n];
        let mut at_u_corner = vec![false; n];
        let u_shape = names_u_shape(&scene.prompt, &scene.room);
        for i in 0..n {
            let rows = &kinds[i].rows;
            if rows.is_empty() || in_rows[i] {
                continue;
            }
            let faced =
                (0..n).any(|j| Knowledge::target_rank(&scene.assets[j], &kinds[j], rows).is_some());
            if !faced {
                continue;
            }
            let members: Vec<usize> = (i..n)
                .filter(|&m| kinds[m].names == kinds[i].names)
                .collect();
            for pair in members.windows(2) {
                self.target[pair[1]] = Some(pair[0]);
                in_rows[pair[1]] = true;
            }
            if u_shape {
                for k in u_corners(members.len()) {
                    at_u_corner[members[k]] = true;
                }
            }
            in_rows[i] = true;
        }
        (in_rows, at_u_corner)
    }

    /// Hints in the prompt override the knowledge: centre, corner and wall placement, facing,
    /// and relations to named targets.
    ///
    /// What an asset's description says of a seat's neighbours ("opposite the banquette at a
    /// bistro table") does not take a seat from what the seating gave it: only the prompt does.
    fn apply_hints(
        &mut self,
        scene: &SceneSpec,
        knowledge: &Knowledge,
        kinds: &[Kind],
        described: &[PromptHint],
        asked: &[PromptHint],
    ) {
        let in_order = described
            .iter()
            .map(|h| (h, true))
            .chain(asked.iter().map(|h| (h, false)));
        for (h, from_description) in in_order {
            if let Hint::Formation(f) = &h.hint {
                self.arrange(scene, knowledge, &h.subjects, f);
                continue;
            }
            let about_neighbours = !matches!(
                h.hint,
                Hint::Centre
                    | Hint::Corner
                    | Hint::AlongWall
                    | Hint::ByWindow
                    | Hint::CentredOnWall
                    | Hint::WindowByDoor
                    | Hint::Place(_)
            );
            let from_description = about_neighbours && from_description;
            for &s in &h.subjects {
                if from_description && kinds[s].seat && self.target[s].is_some() {
                    continue;
                }
                match &h.hint {
                    Hint::Centre => self.free_from_walls(s),
                    Hint::Corner | Hint::ByWindow => {
                        // A piece asked for in a corner or by a window stands there on its
                        // own, back to a wall, not by its usual target; a free-standing one (a
                        // table) keeps its chairs' ring between it and the walls.
                        if self.target[s].is_some() {
                            self.detach(s);
                            self.wall[s] = true;
                        }
                    }
                    Hint::AlongWall => {
                        self.wall[s] = true;
                        self.asked_wall[s] = true;
                    }
                    // The designer takes the middle of the wall, the window by the door (its
                    // wishes).
                    Hint::CentredOnWall | Hint::WindowByDoor => self.wall[s] = true,
                    Hint::Facing(targets) => {
                        self.facing[s] =
                            targets.iter().copied().find(|&t| t != s).or(self.facing[s]);
                    }
                    // "A coffee table on a rug": the rug lies under it, the table stays
                    // on the floor.
                    Hint::Relation(Relation::On, targets)
                        if targets.iter().all(|&t| scene.assets[t].is_flat()) =>
                    {
                        if let Some(&rug) = targets.first() {
                            self.relate(rug, Relation::Near, &[s]);
                        }
                    }
                    // "A chair at each end of the table": beside its end, facing it.
                    Hint::Relation(Relation::SideOf, targets)
                        if kinds[s].seat && targets.iter().any(|t| kinds[*t].seats.is_some()) =>
                    {
                        self.relate(s, Relation::SideOf, targets);
                        self.facing[s] = self.target[s];
                        // It sits at the table, off the wall the table may be put on.
                        self.wall[s] = false;
                        self.place[s] = None;
                    }
                    Hint::Relation(rel, targets) => self.relate(s, *rel, targets),
                    // Pieces facing each other: only those with no place of their own by the
                    // knowledge (a second sofa, not armchairs at a coffee table).
                    Hint::FacingEachOther(first) if self.target[s].is_none() => {
                        self.relate(s, Relation::Opposite, &[*first]);
                        self.facing[s] = Some(*first);
                    }
                    Hint::FacingEachOther(_) => {}
                    Hint::Place(place) => self.put(s, place),
                    Hint::Behind(targets) => {
                        // A seat behind what it serves (a desk, a counter, an easel) sits at
                        // its working side, which the formats call its front.
                        let serves = |t: &usize| kinds[*t].seats.is_some() || kinds[*t].staff > 0.0;
                        if kinds[s].seat && targets.iter().any(serves) {
                            let at: Vec<usize> = targets.iter().copied().filter(serves).collect();
                            self.relate(s, Relation::InFrontOf, &at);
                            self.facing[s] = self.target[s];
                        } else if self.target[s].is_none_or(|t| !targets.contains(&t)) {
                            self.relate(s, Relation::Near, targets);
                        }
                    }
                    Hint::Under(targets) => {
                        let hung = |t: &usize| {
                            kinds[*t]
                                .mount
                                .as_ref()
                                .is_some_and(|m| m.support == Support::Wall || m.or_wall)
                        };
                        if !targets.iter().any(hung)
                            && self.target[s].is_none_or(|t| !targets.contains(&t))
                        {
                            self.relate(s, Relation::Near, targets);
                        }
                    }
                    Hint::Between(targets) => {
                        if self.target[s].is_none_or(|t| !targets.contains(&t)) {
                            self.relate(s, Relation::Near, targets);
                        }
                    }
                    Hint::Formation(_) => {}
                }
            }
        }
    }

    /// `s` stands where `place` says. A piece put on a wall by its role or under a window
    /// stands against it; a piece put anywhere in particular stands there on its own, not by
    /// the target the knowledge gave it (its own dependents come along).
    fn put(&mut self, s: usize, place: &Place) {
        let slot = self.place[s].get_or_insert_with(Place::default);
        slot.zone = place.zone.clone().or(slot.zone.take());
        slot.wall = place.wall.or(slot.wall);
        slot.far_corner |= place.far_corner;
        slot.under_window |= place.under_window;
        slot.by_entrance |= place.by_entrance;
        if place.wall.is_some() || place.under_window || place.far_corner {
            self.wall[s] = true;
        }
        // A piece put somewhere across from an anchor that is put nowhere (the TV asked on the
        // left wall, across from the sofa): the anchor turns round to it, so the piece is placed
        // first and the anchor across from it, facing it.
        if let (Some(t), Some(Relation::Opposite)) = (self.target[s], self.relation[s])
            && self.target[t].is_none()
            && self.place[t].is_none()
        {
            self.detach(s);
            self.target[t] = Some(s);
            self.relation[t] = Some(Relation::Opposite);
            self.facing[t] = Some(s);
            self.wall[t] = false;
            return;
        }
        // A dependent stays by its target when the target is asked to the same place (the
        // lamp of an armchair both put in the reading nook).
        let with_target = self.target[s].is_some_and(|t| self.place[t].as_ref() == Some(place));
        if self.target[s].is_some() && !with_target {
            self.detach(s);
        }
    }

    /// The members stand in formation `f`: each tied to the focus (or, for pods, to the first
    /// desk; for one per member, to its own object) so they are designed as one group, and the
    /// formation kept for the designer. Seats per side of a piece that is no table (a nightstand
    /// "on each side" of a bed) keep the knowledge's own relation.
    fn arrange(
        &mut self,
        scene: &SceneSpec,
        knowledge: &Knowledge,
        members: &[usize],
        f: &FormationHint,
    ) {
        let Some(&first) = members.first() else {
            return;
        };
        // Seats go round a piece; what stands beside one (a nightstand) does not.
        let seats = |i: usize| {
            knowledge
                .kind_of(&scene.assets[i])
                .relate
                .is_none_or(|r| r.relation != Relation::SideOf)
        };
        let focus = f
            .focus
            .iter()
            .copied()
            .find(|t| !members.contains(t))
            .or(self.target[first].filter(|t| !members.contains(t)));
        match f.shape {
            FormationShape::PerSide | FormationShape::Ring
                if !members.iter().all(|&i| seats(i)) =>
            {
                return;
            }
            // Blocks that stand on their own: tied to their first member, free of the walls.
            FormationShape::Pods | FormationShape::Aisles => {
                self.stand_as_block(members);
            }
            FormationShape::UTables | FormationShape::LDesks => {
                self.arrange_letter(scene, knowledge, members, f);
                return;
            }
            FormationShape::OnePerMember | FormationShape::BehindEach => {
                if f.of.is_empty() {
                    return;
                }
                let members = self.one_each(members, f);
                let behind = f.shape == FormationShape::BehindEach;
                for (&s, &t) in members.iter().zip(&f.of) {
                    self.detach(s);
                    self.target[s] = Some(t);
                    // Behind a piece, no word of the plan's says where: near it, facing it.
                    self.relation[s] = Some(if behind {
                        Relation::Near
                    } else {
                        Relation::InFrontOf
                    });
                    self.facing[s] = Some(t);
                    self.wall[s] = false;
                }
                self.keep_formation(f, members, None);
                return;
            }
            // A ring about nothing stands on its own, free of the walls, in the room's middle.
            FormationShape::Ring if focus.is_none() => {
                self.stand_as_block(members);
            }
            // Rows facing a wall with nothing on it to face: one block tied to its first
            // member, free of the walls; the designer turns it to the wall the prompt names.
            FormationShape::Rows if focus.is_none() && f.wall.is_some() => {
                self.stand_as_block(members);
            }
            _ => {
                let Some(t) = focus else {
                    return;
                };
                let desks = members.iter().all(|&i| {
                    !knowledge.kind_of(&scene.assets[i]).rows.is_empty()
                        || scene.assets[i].category.contains("desk")
                });
                // Rows: the first row before the focus, each seat behind in line with the one
                // in front of it (the rows' own order: first row first, as many in each).
                let rows = f.count.unwrap_or(members.len().div_ceil(4)).max(1);
                let per_row = members.len().div_ceil(rows);
                for (k, &s) in members.iter().enumerate() {
                    self.detach(s);
                    let (target, rel) = match f.shape {
                        FormationShape::Rows if k >= per_row => {
                            (members[k - per_row], Relation::AlignedWith)
                        }
                        FormationShape::Rows | FormationShape::AlongFront => {
                            (t, Relation::InFrontOf)
                        }
                        _ => (t, Relation::Around),
                    };
                    self.target[s] = Some(target);
                    self.relation[s] = Some(rel);
                    self.facing[s] = (!desks).then_some(t);
                    self.wall[s] = false;
                }
            }
        }
        let desks = members
            .iter()
            .all(|&i| scene.assets[i].category.contains("desk"));
        if desks && matches!(f.shape, FormationShape::Rows | FormationShape::Pods) {
            self.seat_each_desk(scene, members);
        }
        let focus = match f.shape {
            FormationShape::Pods | FormationShape::OnePerMember | FormationShape::Aisles => None,
            _ => focus,
        };
        self.keep_formation(f, members, focus);
    }

    /// `members` stand as one block of their own, free of the walls: each tied to the first,
    /// the first to nothing (pods, aisles, a ring about nothing, rows facing a bare wall).
    fn stand_as_block(&mut self, members: &[usize]) {
        let Some((&first, rest)) = members.split_first() else {
            return;
        };
        for &s in rest {
            self.detach(s);
            self.target[s] = Some(first);
            self.relation[s] = Some(Relation::Near);
        }
        for &s in members {
            self.wall[s] = false;
            self.facing[s] = None;
        }
        self.detach(first);
    }

    /// Formation `f` of `members` about `focus`, kept for the designer. A member of an earlier
    /// formation (stools the knowledge set along a bar) leaves it.
    fn keep_formation(&mut self, f: &FormationHint, members: &[usize], focus: Option<usize>) {
        for earlier in &mut self.formations {
            earlier.3.retain(|m| !members.contains(m));
        }
        self.formations.retain(|earlier| !earlier.3.is_empty());
        let of = if matches!(
            f.shape,
            FormationShape::OnePerMember | FormationShape::BehindEach
        ) {
            f.of.clone()
        } else {
            Vec::new()
        };
        self.formations
            .push((f.shape, focus, f.count, members.to_vec(), of));
    }

    /// A U of tables or an L of desks (see [`FormationShape::UTables`] and
    /// [`FormationShape::LDesks`]) from the pieces people sit at among `members`, with the
    /// seats the tables were given (a U's, at most `count` per table) or the first seat at the
    /// desks (an L's). A U needs three tables or more, an L two desks; else nothing changes.
    /// A U's tables go with its focus (no relation: the shape places them), its seats round
    /// their tables; an L's main desk (named "main", else the widest) anchors it against a
    /// wall, the return desk against a wall near it, the chair before the main desk.
    fn arrange_letter(
        &mut self,
        scene: &SceneSpec,
        knowledge: &Knowledge,
        members: &[usize],
        f: &FormationHint,
    ) {
        let assets = &scene.assets;
        let is_seat = |i: usize| knowledge.kind_of(&assets[i]).seat;
        let mut tables: Vec<usize> = members
            .iter()
            .copied()
            .filter(|&i| {
                !is_seat(i)
                    && !assets[i].is_flat()
                    && (knowledge.kind_of(&assets[i]).seats.is_some()
                        || ["table", "desk"]
                            .iter()
                            .any(|w| assets[i].category.contains(w)))
            })
            .collect();
        let seats_at = |this: &Self, at: &[usize]| -> Vec<usize> {
            (0..assets.len())
                .filter(|&i| is_seat(i) && this.target[i].is_some_and(|t| at.contains(&t)))
                .collect()
        };
        let (all, focus) = match f.shape {
            FormationShape::UTables => {
                // Desks in a U (seats at their fronts) are the knowledge's U of desks along the
                // walls (`names_u_shape`); this shape is for tables seated all round.
                let seated_round =
                    |i: &usize| knowledge.kind_of(&assets[*i]).seats == Some(SeatsAt::Around);
                if tables.len() < 3 || !tables.iter().all(seated_round) {
                    return;
                }
                let mut seats = seats_at(self, &tables);
                if let Some(c) = f.count {
                    seats.truncate(c.saturating_mul(tables.len()));
                }
                let focus = f
                    .focus
                    .iter()
                    .copied()
                    .find(|t| !tables.contains(t) && !seats.contains(t));
                // The focus must not hang on a table in turn (a screen set before one).
                if let Some(fc) = focus
                    && tables.iter().any(|&t| depends_on(&self.target, fc, t))
                {
                    self.detach(fc);
                }
                for (k, &t) in tables.iter().enumerate() {
                    self.detach(t);
                    // With the focus, or else with the first table: one group, posed as one.
                    self.target[t] = focus.or((k > 0).then_some(tables[0]));
                    self.facing[t] = None;
                    self.wall[t] = false;
                }
                for (k, &s) in seats.iter().enumerate() {
                    let t = tables[k % tables.len()];
                    self.detach(s);
                    self.target[s] = Some(t);
                    self.relation[s] = Some(Relation::Around);
                    *self.load.entry((t, Relation::Around)).or_default() += 1;
                    self.facing[s] = Some(t);
                    self.wall[s] = false;
                }
                (
                    tables.iter().chain(&seats).copied().collect::<Vec<_>>(),
                    focus,
                )
            }
            _ => {
                if tables.len() < 2 {
                    return;
                }
                let said = |i: usize| {
                    let a = &assets[i];
                    words(&format!(
                        "{} {}",
                        a.name,
                        a.description.as_deref().unwrap_or("")
                    ))
                    .split(' ')
                    .any(|w| w == "main" || w == "primary")
                };
                // The main desk first (named so, else the widest), then the return.
                tables.sort_by(|&a, &b| {
                    said(b)
                        .cmp(&said(a))
                        .then(assets[b].size[0].total_cmp(&assets[a].size[0]))
                        .then(a.cmp(&b))
                });
                tables.truncate(2);
                let (main, side) = (tables[0], tables[1]);
                let chair = seats_at(self, &tables).into_iter().next();
                self.detach(main);
                self.wall[main] = true;
                self.facing[main] = None;
                self.detach(side);
                self.target[side] = Some(main);
                self.relation[side] = Some(Relation::Near);
                self.wall[side] = true;
                self.facing[side] = None;
                if let Some(c) = chair {
                    self.detach(c);
                    self.target[c] = Some(main);
                    self.relation[c] = Some(Relation::InFrontOf);
                    self.facing[c] = Some(main);
                    self.wall[c] = false;
                }
                (tables.iter().copied().chain(chair).collect(), None)
            }
        };
        for earlier in &mut self.formations {
            earlier.3.retain(|m| !all.contains(m));
        }
        self.formations.retain(|earlier| !earlier.3.is_empty());
        self.formations
            .push((f.shape, focus, f.count, all, Vec::new()));
    }

    /// The members of a U of tables or an L of desks that a later hint or the mounting freed
    /// (a place asked of the desks, a focus hung on a wall) are tied back to their formation,
    /// so the designer poses it as one group: a U's tables to its focus (else, or when the
    /// focus leaves the floor, its first table), an L's return desk and chair to its main desk.
    fn hold_letters(&mut self) {
        let letters: Vec<(FormationShape, Option<usize>, Vec<usize>)> = self
            .formations
            .iter()
            .filter(|f| matches!(f.0, FormationShape::UTables | FormationShape::LDesks))
            .map(|f| (f.0, f.1, f.3.clone()))
            .collect();
        for (shape, focus, members) in letters {
            let Some(&first) = members.first() else {
                continue;
            };
            // A focus off the floor (a TV on the wall) is posed with the wall pieces, last:
            // the U stands on its own then.
            let anchor = match shape {
                FormationShape::UTables => focus
                    .filter(|&t| self.support[t].is_none())
                    .unwrap_or(first),
                _ => first,
            };
            for &m in &members {
                if m == anchor || self.target[m].is_some() {
                    continue;
                }
                if depends_on(&self.target, anchor, m) {
                    continue;
                }
                self.target[m] = Some(anchor);
                if shape == FormationShape::LDesks {
                    self.relation[m] = Some(if self.wall[m] {
                        Relation::Near
                    } else {
                        Relation::InFrontOf
                    });
                }
            }
        }
    }

    /// The members of a formation one per object of `f.of` (a music stand before each chair):
    /// the first as many as there are objects. Any more (the conductor's stand) stand before
    /// the focus of the formation those objects are in (the podium the chairs face), facing it,
    /// and are not in this one.
    fn one_each<'m>(&mut self, members: &'m [usize], f: &FormationHint) -> &'m [usize] {
        let (each, extra) = members.split_at(members.len().min(f.of.len()));
        let focus = self
            .formations
            .iter()
            .find(|o| o.3.iter().any(|m| f.of.contains(m)))
            .and_then(|o| o.1);
        if let Some(t) = focus {
            for &s in extra {
                self.detach(s);
                self.target[s] = Some(t);
                self.relation[s] = Some(Relation::InFrontOf);
                self.facing[s] = Some(t);
                self.wall[s] = false;
            }
        }
        each
    }

    /// The formations the knowledge gives kinds of pieces when a room has two or more of one
    /// (a shop's gondolas in aisles, pews in rows facing the altar), as if the prompt had asked.
    /// Rows of pieces wider than [`LONG_BENCH_CM`](crate::knowledge::LONG_BENCH_CM) (pews) take two to a row, about a centre
    /// aisle; narrower ones four. Rows face the piece the kind `faces` (no rows without one); a
    /// kind forms only when the room has `at_least` of it.
    fn form_by_kind(&mut self, scene: &SceneSpec, knowledge: &Knowledge, kinds: &[Kind]) {
        let mut done = vec![false; kinds.len()];
        for i in 0..kinds.len() {
            let Some(shape) = kinds[i].formation else {
                continue;
            };
            if done[i] || scene.assets[i].is_flat() {
                continue;
            }
            let members: Vec<usize> = (i..kinds.len())
                .filter(|&m| kinds[m].names == kinds[i].names && !scene.assets[m].is_flat())
                .collect();
            for &m in &members {
                done[m] = true;
            }
            if members.len() < kinds[i].at_least.max(2) {
                continue;
            }
            // Rows face the best-ranked piece the kind faces; none in the room, no rows.
            let focus: Vec<usize> = (0..kinds.len())
                .filter(|j| !members.contains(j))
                .filter_map(|j| {
                    Knowledge::target_rank(&scene.assets[j], &kinds[j], &kinds[i].faces)
                        .map(|r| (r, j))
                })
                .min()
                .map(|(_, j)| j)
                .into_iter()
                .collect();
            if shape == FormationShape::Rows && focus.is_empty() {
                continue;
            }
            let count = match shape {
                FormationShape::Rows => {
                    let per_row = if scene.assets[i].size[0] >= crate::knowledge::LONG_BENCH_CM {
                        2
                    } else {
                        4
                    };
                    Some(members.len().div_ceil(per_row))
                }
                _ => None,
            };
            let hint = FormationHint {
                shape,
                count,
                focus,
                of: Vec::new(),
                wall: None,
            };
            self.arrange(scene, knowledge, &members, &hint);
        }
    }

    /// A wall piece named after a counter ("prize display shelf" and "prize counter", "back bar
    /// shelving" and "bar counter"), or a work counter of the room's run ("prep counter" behind
    /// a sushi bar, "back counter" behind a gelato counter), stands on the staff side, across
    /// the staff's aisle from the counter (its front, or a bar's back), facing it: what the
    /// staff hand out is behind them. One per counter, no wider than the counter and
    /// [`STOCK_OVERHANG_CM`]; the others of its kind stand on the walls as usual.
    fn stock_behind_counters(&mut self, scene: &SceneSpec, kinds: &[Kind]) {
        let mut counters: Vec<usize> = (0..kinds.len()).filter(|&j| kinds[j].staff > 0.0).collect();
        for (i, k) in kinds.iter().enumerate() {
            if !k.wall || k.seat || k.staff > 0.0 || k.seats.is_some() || self.target[i].is_some() {
                continue;
            }
            let width = scene.assets[i].size[0];
            // A work counter of the room's run ("prep counter", "back counter") is what the
            // staff of a serving counter turn round to: it stands behind them too.
            // A home's "kitchen counter" keeps to its kitchen run.
            let category = words(&scene.assets[i].category);
            let work_counter = k.run.as_deref() == Some("kitchen")
                && !category.split(' ').any(|w| w == "kitchen")
                && category
                    .rsplit(' ')
                    .next()
                    .is_some_and(|h| h == "counter" || h == "worktop");
            // What customers use themselves ("self service copier") is on their side.
            let self_served = category.split(' ').any(|w| w == "self");
            let counter = counters.iter().position(|&j| {
                !self_served
                    && scene.assets[j].size[0] + STOCK_OVERHANG_CM >= width
                    && (work_counter
                        || share_words(&scene.assets[i].category, &scene.assets[j].category))
            });
            if let Some(p) = counter {
                let j = counters.remove(p);
                self.target[i] = Some(j);
                self.stock[i] = true;
                // Before a counter's front; behind a bar, where no relation of the plan's
                // words applies: it faces the bar's back all the same.
                if !kinds[j].staff_behind() {
                    self.relation[i] = Some(Relation::InFrontOf);
                    *self.load.entry((j, Relation::InFrontOf)).or_default() += 1;
                }
                self.facing[i] = Some(j);
                self.wall[i] = true;
            }
        }
    }

    /// A free-standing piece whose kind depends on another that the room lacks (armchairs
    /// with no coffee table or sofa, a coffee table with no sofa) stands against a wall rather
    /// than alone in the open facing nothing, unless something depends on it in turn.
    fn orphans_to_walls(&mut self, kinds: &[Kind]) {
        for (i, k) in kinds.iter().enumerate() {
            let orphan = k.relate.is_some()
                && self.target[i].is_none()
                && !self.wall[i]
                && !k.seat
                && k.seats.is_none()
                && k.formation.is_none()
                && k.rows.is_empty()
                && k.staff == 0.0;
            if orphan && !self.target.contains(&Some(i)) {
                self.wall[i] = true;
            }
        }
    }

    /// Small pieces named after a free-standing piece or a station ("dental delivery cart" and
    /// "dental chair"), or whose names and descriptions make them its kin ("stage monitor
    /// speaker" and "stage platform"), stand near it, not wherever a wall has room.
    fn gather_by_name(&mut self, scene: &SceneSpec, kinds: &[Kind]) {
        let own: Vec<OwnWords> = scene.assets.iter().map(OwnWords::of).collect();
        for (i, k) in kinds.iter().enumerate() {
            // What a seat's description tells ("leather reading armchair") is the seating's to
            // read: the seat does not gather by it at a piece ("reading table").
            let seat_itself = disco_core::geometry3d::is_seat(&scene.assets[i].category);
            let loose = self.target[i].is_none()
                && k.priority <= SMALL_PRIORITY
                && !k.seat
                && k.seats.is_none()
                && k.staff == 0.0
                && k.formation.is_none()
                && !scene.assets[i].is_flat();
            if !loose {
                continue;
            }
            // A seat named after a piece is that piece's ("piano bench"), never the other way.
            let a_seat = |j: usize| {
                let category = words(&scene.assets[j].category);
                matches!(
                    category.rsplit(' ').next(),
                    Some("bench" | "stool" | "chair" | "seat")
                )
            };
            let piece = (0..kinds.len()).find(|&j| {
                j != i
                    && kinds[j].names != k.names
                    && !kinds[j].seat
                    && !a_seat(j)
                    && (!kinds[j].wall || kinds[j].seats.is_some())
                    && !scene.assets[j].is_flat()
                    && !depends_on(&self.target, j, i)
                    && (share_words(&scene.assets[i].category, &scene.assets[j].category)
                        || (!seat_itself && own[i].kin(&own[j])))
            });
            if let Some(j) = piece {
                self.relate(i, Relation::Near, &[j]);
                self.wall[i] = false;
            }
        }
    }

    /// One chair at each desk of a formation, in order: the chairs the knowledge gave these
    /// desks (or others), and the others of their categories.
    fn seat_each_desk(&mut self, scene: &SceneSpec, desks: &[usize]) {
        let n = self.target.len();
        let at_desks: Vec<usize> = (0..n)
            .filter(|&i| self.target[i].is_some_and(|t| desks.contains(&t)) && !desks.contains(&i))
            .collect();
        let categories: Vec<&str> = at_desks
            .iter()
            .map(|&i| scene.assets[i].category.as_str())
            .collect();
        let mut chairs = at_desks.clone();
        chairs.extend((0..n).filter(|i| {
            !at_desks.contains(i)
                && !desks.contains(i)
                && categories.contains(&scene.assets[*i].category.as_str())
        }));
        for (&c, &d) in chairs.iter().zip(desks) {
            self.detach(c);
            self.target[c] = Some(d);
            self.relation[c] = Some(Relation::InFrontOf);
            self.facing[c] = Some(d);
            self.wall[c] = false;
        }
    }

    /// A seat named after another piece of the room ("piano-bench", "vanity stool", "desk
    /// chair") sits at that piece: before it, facing it.
    /// Returns which assets it seated.
    fn seat_companions(&mut self, scene: &SceneSpec, knowledge: &Knowledge) -> Vec<bool> {
        const SEATS: [&str; 4] = ["bench", "stool", "chair", "seat"];
        let mut seated: Vec<usize> = Vec::new();
        let head = |text: &str| words(text).rsplit(' ').next().map(str::to_string);
        // Seats each piece has taken: two desk chairs go to two desks, not both to the first.
        let mut taken: HashMap<usize, usize> = HashMap::new();
        for i in 0..scene.assets.len() {
            let name = words(&scene.assets[i].name);
            let tokens: Vec<&str> = name
                .split(' ')
                .filter(|w| !w.chars().all(|c| c.is_ascii_digit()))
                .collect();
            let Some((seat, modifiers)) = tokens.split_last() else {
                continue;
            };
            // Only words of the name beyond a category the knowledge lists name a piece: a
            // "counter stool" is a kind of stool, not the kitchen counter's; an "organ bench"
            // is the organ's.
            let category = words(&scene.assets[i].category);
            let listed = knowledge.knows_exactly(&category);
            let modifiers: Vec<&str> = modifiers
                .iter()
                .copied()
                .filter(|w| !listed || !category.split(' ').any(|c| c == *w))
                .filter(|w| !SEAT_QUALIFIERS.contains(w) || !category.split(' ').any(|c| c == *w))
                .collect();
            if !SEATS.contains(seat) || modifiers.is_empty() {
                continue;
            }
            let piece = (0..scene.assets.len())
                .filter(|&j| {
                    j != i
                        && !scene.assets[j].is_flat()
                        && !depends_on(&self.target, j, i)
                        && head(&scene.assets[j].category).is_some_and(|h| {
                            !SEATS.contains(&h.as_str()) && modifiers.contains(&h.as_str())
                        })
                })
                // The piece whose category holds the most of the name's words ("round table
                // chair": the round dining table before the square ones), then the least taken.
                .min_by_key(|&j| {
                    let category = words(&scene.assets[j].category);
                    let shared = category
                        .split(' ')
                        .filter(|w| modifiers.contains(w))
                        .count();
                    (usize::MAX - shared, taken.get(&j).copied().unwrap_or(0), j)
                });
            if let Some(j) = piece {
                *taken.entry(j).or_default() += 1;
                self.detach(i);
                self.target[i] = Some(j);
                // Round a table, before anything else (a piano, an organ, a desk).
                let around = knowledge.kind_of(&scene.assets[j]).seats == Some(SeatsAt::Around);
                self.relation[i] = Some(if around {
                    Relation::Around
                } else {
                    Relation::InFrontOf
                });
                self.facing[i] = Some(j);
                self.wall[i] = false;
                seated.push(i);
            }
        }
        let mut marks = vec![false; scene.assets.len()];
        for i in seated {
            marks[i] = true;
        }
        marks
    }

    /// Every seat of the room not seated already (`seated`, or in rows) goes to a piece people
    /// sit at, by [`share_seats`]: around a table, at a desk's or a station's front, along a
    /// bar's front (as a formation, so the stools keep to the customer side). Seats nothing
    /// has room for stand along the walls, and the notes say so.
    fn seat_everyone(&mut self, scene: &SceneSpec, kinds: &[Kind], seated: &[bool]) -> Vec<String> {
        // A seat the knowledge gave to a piece that declares no seats of its own (a student
        // chair at its desk in the rows) keeps it.
        let keep: Vec<bool> = (0..kinds.len())
            .map(|i| seated[i] || self.target[i].is_some_and(|t| kinds[t].seats.is_none()))
            .collect();
        let seating = share_seats(scene, kinds, &keep);
        let mut along: BTreeMap<usize, Vec<usize>> = BTreeMap::new();
        for at in &seating.placed {
            let (s, t) = (at.seat, at.piece);
            self.detach(s);
            let rel = match at.how {
                SeatsAt::Around => Relation::Around,
                SeatsAt::Front | SeatsAt::AlongFront => Relation::InFrontOf,
            };
            *self.load.entry((t, rel)).or_default() += 1;
            self.target[s] = Some(t);
            self.relation[s] = Some(rel);
            self.facing[s] = Some(t);
            self.wall[s] = false;
            if at.how != SeatsAt::Around {
                along.entry(t).or_default().push(s);
            }
        }
        let left_over = self.seat_visitors_across(scene, kinds, &seating.left_over, &along);
        // Seats along a front stand in a line along it, as a formation, when there are two or
        // more (a bar's stools, two at a long workbench); one is simply before it.
        for (t, members) in along.into_iter().filter(|(_, m)| m.len() > 1) {
            self.formations.push((
                FormationShape::AlongFront,
                Some(t),
                None,
                members,
                Vec::new(),
            ));
        }
        for &s in &left_over {
            self.detach(s);
            self.facing[s] = None;
            self.wall[s] = true;
        }
        left_over_notes(scene, &left_over)
    }

    /// Seats left over whose own words say they are for the people a desk's worker receives (a
    /// "customer chair", a "client chair", one "across from the optician") sit across that
    /// desk, facing its worker: the desk, seated at its front by one person, takes up to one
    /// visitor per [`VISITOR_PITCH_CM`] of its width, those whose words name it first, and
    /// stands free with its worker alone at its front and its visitors down its other side
    /// (a `per_side` formation). Returns the seats still left over.
    fn seat_visitors_across(
        &mut self,
        scene: &SceneSpec,
        kinds: &[Kind],
        left_over: &[usize],
        along: &BTreeMap<usize, Vec<usize>>,
    ) -> Vec<usize> {
        let text = |i: usize| {
            let a = &scene.assets[i];
            format!(
                "{} {} {}",
                words(&a.category),
                words(&a.name),
                a.description.as_deref().map(words).unwrap_or_default()
            )
        };
        let visitor = |i: usize| {
            text(i)
                .split(' ')
                .any(|w| VISITOR_WORDS.contains(&w) || w == "across")
        };
        // Desks with one worker seated at their front.
        let desks: Vec<(usize, usize)> = along
            .iter()
            .filter(|(t, m)| kinds[**t].seats == Some(SeatsAt::Front) && m.len() == 1)
            .map(|(t, m)| (*t, m[0]))
            .collect();
        let mut across: BTreeMap<usize, Vec<usize>> = BTreeMap::new();
        let mut still = Vec::new();
        for &s in left_over {
            let room_at = |t: usize, across: &BTreeMap<usize, Vec<usize>>| {
                let cap = (scene.assets[t].size[0] / VISITOR_PITCH_CM)
                    .floor()
                    .max(1.0) as usize;
                across.get(&t).map_or(0, Vec::len) < cap
            };
            let named = |t: usize| text(s).contains(&words(&scene.assets[t].category));
            let pick = if visitor(s) {
                desks
                    .iter()
                    .map(|(t, _)| *t)
                    .filter(|&t| room_at(t, &across))
                    .min_by_key(|&t| (!named(t), across.get(&t).map_or(0, Vec::len), t))
            } else {
                None
            };
            match pick {
                Some(t) => across.entry(t).or_default().push(s),
                None => still.push(s),
            }
        }
        for (t, visitors) in across {
            let Some(&(_, worker)) = desks.iter().find(|(d, _)| *d == t) else {
                continue;
            };
            for &v in &visitors {
                self.detach(v);
                self.target[v] = Some(t);
                self.relation[v] = Some(Relation::Around);
                self.facing[v] = Some(t);
                self.wall[v] = false;
                *self.load.entry((t, Relation::Around)).or_default() += 1;
            }
            let count = visitors.len();
            let members = std::iter::once(worker).chain(visitors).collect();
            self.formations.push((
                FormationShape::PerSide,
                Some(t),
                Some(count),
                members,
                Vec::new(),
            ));
        }
        still
    }

    /// The formations by name.
    fn formations(&self, scene: &SceneSpec) -> Vec<Formation> {
        let name = |i: &usize| scene.assets[*i].name.clone();
        self.formations
            .iter()
            .map(|(shape, focus, count, members, of)| Formation {
                shape: *shape,
                focus: focus.as_ref().map(name),
                members: members.iter().map(name).collect(),
                count: *count,
                of: of.iter().map(name).collect(),
            })
            .collect()
    }

    /// `s` stands free of the walls (the prompt wants it in the middle). The wall pieces that
    /// would stand by it (a vanity or a toilet by a tub) are not freed with it: they keep to the
    /// walls as anchors of their own.
    fn free_from_walls(&mut self, s: usize) {
        self.wall[s] = false;
        for j in 0..self.target.len() {
            if j != s && self.target[j] == Some(s) && self.wall[j] {
                self.detach(j);
            }
        }
    }

    /// Frees `s` from the target the knowledge gave it, so it anchors a group of its own.
    fn detach(&mut self, s: usize) {
        if let (Some(t), Some(rel)) = (self.target[s], self.relation[s])
            && let Some(n) = self.load.get_mut(&(t, rel))
        {
            *n = n.saturating_sub(1);
        }
        // Stock behind a bar has a target and no relation: it is freed all the same.
        self.target[s] = None;
        self.relation[s] = None;
        self.stock[s] = false;
    }

    /// The pieces that leave the floor ([`mount_all`]): each stands on its support's top, or
    /// hangs on a wall (above a piece, across from one, or anywhere free), instead of whatever
    /// the floor passes gave it; returns the notes on those that stay on the floor.
    fn mount(&mut self, scene: &SceneSpec, kinds: &[Kind]) -> Vec<String> {
        // What the prompt asked ("a lamp on each nightstand", "the TV on the wall").
        let wishes: Vec<Wish> = (0..kinds.len())
            .map(|s| match (self.relation[s], self.target[s]) {
                (Some(Relation::On), Some(t)) => Wish::On(t),
                (Some(Relation::Above), Some(t)) => Wish::Above(t),
                _ if self.asked_wall[s] => Wish::Wall,
                _ => Wish::None,
            })
            .collect();
        let (mounted, mut notes) = mount_all(scene, kinds, &self.wall, &wishes);
        // A piece asked on or above another that cannot leave the floor keeps to the floor.
        for (s, w) in wishes.iter().enumerate() {
            if mounted[s].is_none() && matches!(w, Wish::On(_) | Wish::Above(_)) {
                let t = self.target[s].map(|t| scene.assets[t].name.clone());
                self.detach(s);
                notes.push(format!(
                    "{} stands on the floor: the prompt put it {} {}, which cannot hold it",
                    scene.assets[s].name,
                    if matches!(w, Wish::On(_)) {
                        "on"
                    } else {
                        "above"
                    },
                    t.unwrap_or_default()
                ));
            }
        }
        for (s, m) in mounted.into_iter().enumerate() {
            let Some(m) = m else { continue };
            // A support that depends on this piece would make a loop: it keeps its floor plan.
            let target = match m {
                Mounted::On(j) => Some(j),
                Mounted::Wall { above, across } => above.or(across),
            };
            if target.is_some_and(|t| depends_on(&self.target, t, s)) {
                continue;
            }
            let place = self.place[s].take();
            self.detach(s);
            self.support[s] = Some(m.support());
            self.facing[s] = None;
            match m {
                Mounted::On(j) => {
                    self.wall[s] = false;
                    self.target[s] = Some(j);
                    self.relation[s] = Some(Relation::On);
                }
                Mounted::Wall { above, across } => {
                    self.wall[s] = true;
                    if let Some(j) = above {
                        self.target[s] = Some(j);
                        self.relation[s] = Some(Relation::Above);
                    } else if let Some(j) = across {
                        self.target[s] = Some(j);
                        self.relation[s] = Some(Relation::Opposite);
                        self.facing[s] = Some(j);
                    } else {
                        // Hung on a free stretch of wall: where the prompt put it, if anywhere.
                        self.place[s] = place;
                    }
                }
            }
        }
        // A floor piece that depended on a piece now off the floor (a recliner near the TV)
        // depends on what holds it instead (the TV's stand), which stands on the floor.
        for i in 0..self.target.len() {
            if self.support[i].is_some() {
                continue;
            }
            let mut steps = 0;
            while let Some(t) = self.target[i] {
                if self.support[t].is_none() || steps > self.target.len() {
                    break;
                }
                self.target[i] = self.target[t].filter(|&u| u != i);
                if self.target[i].is_none() {
                    self.relation[i] = None;
                    self.facing[i] = self.facing[i].filter(|&f| self.support[f].is_none());
                }
                steps += 1;
            }
        }
        notes
    }

    /// Puts `s` in `rel` to the least loaded of `targets` it may depend on, unless it already
    /// stands in that relation to one of them; around a target, it faces it too.
    fn relate(&mut self, s: usize, rel: Relation, targets: &[usize]) {
        let keep =
            self.target[s].is_some_and(|t| targets.contains(&t)) && self.relation[s] == Some(rel);
        if keep {
            return;
        }
        let best = targets
            .iter()
            .copied()
            .filter(|&t| t != s && !depends_on(&self.target, t, s))
            .min_by_key(|&t| (load_of(&self.load, t, rel), t));
        if let Some(t) = best {
            *self.load.entry((t, rel)).or_default() += 1;
            self.target[s] = Some(t);
            self.relation[s] = Some(rel);
            if rel == Relation::Around {
                self.facing[s] = Some(t);
            }
        }
    }

    /// The constraints of every asset that has any. Dependents that stand around, before or in
    /// line with their target leave the wall.
    fn constraints(&self, scene: &SceneSpec) -> BTreeMap<String, ObjectConstraints> {
        // What seats stand down both sides of, or all round, stands free of the walls ("two
        // rows of chairs facing each other across the magazine table").
        let seated_round: Vec<usize> = self
            .formations
            .iter()
            .filter(|(shape, ..)| matches!(shape, FormationShape::PerSide | FormationShape::Ring))
            .filter_map(|(_, focus, ..)| *focus)
            .collect();
        let mut constraints = BTreeMap::new();
        for (i, a) in scene.assets.iter().enumerate() {
            let mut c = ObjectConstraints {
                against_wall: self.wall[i] && !seated_round.contains(&i),
                ..Default::default()
            };
            if let (Some(j), Some(rel)) = (self.target[i], self.relation[i]) {
                if matches!(
                    rel,
                    Relation::Around | Relation::InFrontOf | Relation::AlignedWith
                ) && !self.stock[i]
                {
                    c.against_wall = false;
                }
                c.relations.push(RelationSpec {
                    relation: rel,
                    target: scene.assets[j].name.clone(),
                });
            }
            c.facing = self.facing[i].map(|j| scene.assets[j].name.clone());
            c.place = self.place[i].clone();
            c.support = self.support[i];
            if c.against_wall
                || !c.relations.is_empty()
                || c.facing.is_some()
                || c.place.is_some()
                || c.support.is_some()
            {
                constraints.insert(a.name.clone(), c);
            }
        }
        constraints
    }

    /// Groups: each anchor (no target) with everything that depends on it, transitively, what
    /// stands on a top with its support (the round's PRT then knows the stand carries a TV).
    /// Anchors by priority, then area, then scene order; in a group the anchor first, then its
    /// dependents by depth and scene order. Last, one group of everything on the walls (see
    /// [`Draft::wall_group`]).
    fn groups(&self, scene: &SceneSpec, kinds: &[Kind]) -> Vec<Vec<String>> {
        let mut members: BTreeMap<usize, Vec<usize>> = BTreeMap::new();
        for i in (0..self.target.len()).filter(|&i| self.support[i] != Some(Support::Wall)) {
            members
                .entry(chain_end(&self.target, i).0)
                .or_default()
                .push(i);
        }
        let mut anchors: Vec<usize> = members.keys().copied().collect();
        let area = |i: usize| scene.assets[i].size[0] * scene.assets[i].size[1];
        // A group holding rows or an arc of several (the pews before the altar, the wheels
        // about the teacher's) takes the floor before pieces that would stand in its way.
        let arranged = |a: usize| {
            self.formations.iter().any(|(shape, _, _, members, _)| {
                matches!(shape, FormationShape::Rows | FormationShape::Arc)
                    && members.len() >= ARRANGED_MEMBERS
                    && members.iter().any(|&m| chain_end(&self.target, m).0 == a)
            })
        };
        anchors.sort_by(|&a, &b| {
            arranged(b)
                .cmp(&arranged(a))
                .then(kinds[b].priority.cmp(&kinds[a].priority))
                .then(area(b).total_cmp(&area(a)))
                .then(a.cmp(&b))
        });
        let mut groups: Vec<Vec<usize>> = anchors
            .into_iter()
            .map(|a| {
                let mut m = members.remove(&a).unwrap_or_default();
                m.sort_by_key(|&i| (i != a, chain_end(&self.target, i).1, i));
                m
            })
            .collect();
        let on_walls = self.wall_group(&groups);
        if !on_walls.is_empty() {
            groups.push(on_walls);
        }
        groups
            .into_iter()
            .map(|g| {
                g.into_iter()
                    .map(|i| scene.assets[i].name.clone())
                    .collect()
            })
            .collect()
    }

    /// Everything on the walls, posed after every piece on the floor and on the tops (a
    /// painting then knows what stands against its wall and how high): what hangs above a
    /// piece, across from one, and anywhere free; each by its target's group and scene order.
    /// `floor_groups` are the other groups, by asset index.
    fn wall_group(&self, floor_groups: &[Vec<usize>]) -> Vec<usize> {
        let group_of = |i: usize| {
            floor_groups
                .iter()
                .position(|g| g.contains(&i))
                .unwrap_or(usize::MAX)
        };
        let mut on_walls: Vec<usize> = (0..self.target.len())
            .filter(|&i| self.support[i] == Some(Support::Wall))
            .collect();
        on_walls.sort_by_key(|&i| {
            let order = match self.relation[i] {
                Some(Relation::Above) => 0,
                Some(Relation::Opposite) => 1,
                _ => 2,
            };
            (order, self.target[i].map_or(usize::MAX, group_of), i)
        });
        on_walls
    }
}

/// The notes on how categories were read: the categories whose kind came from their head noun
/// alone share one note; each one guessed from its size and shape has its own.
fn reading_notes(scene: &SceneSpec, readings: &[(Kind, Reading)]) -> Vec<String> {
    let mut seen = std::collections::BTreeSet::new();
    let mut by_head = Vec::new();
    let mut notes = Vec::new();
    for (a, (_, how)) in scene.assets.iter().zip(readings) {
        let category = words(&a.category);
        if !seen.insert(category.clone()) {
            continue;
        }
        match how {
            Reading::Known => {}
            Reading::ByHead(head) => by_head.push(format!("{category} as a {head}")),
            Reading::Guessed(why) => notes.push(format!(
                "{category}: not a known kind; placed by its shape ({} x {} x {} cm): {why}",
                a.size[0], a.size[1], a.size[2]
            )),
        }
    }
    if !by_head.is_empty() {
        notes.insert(0, format!("read by the last word: {}", by_head.join(", ")));
    }
    notes
}

/// The note on seats nothing had room for, by category.
fn left_over_notes(scene: &SceneSpec, left: &[usize]) -> Vec<String> {
    let mut by_category: BTreeMap<String, usize> = BTreeMap::new();
    for &s in left {
        *by_category
            .entry(words(&scene.assets[s].category))
            .or_default() += 1;
    }
    by_category
        .into_iter()
        .map(|(c, n)| crate::uses::left_over_note(&c, n))
        .collect()
}

/// Each asset's target by the knowledge: the best-ranked asset its kind relates to, preferring
/// targets not yet full (see [`capacity`]) and then the least loaded, never one that depends on
/// it. Returns the targets and the load they leave.
fn choose_targets(scene: &SceneSpec, kinds: &[Kind]) -> (Vec<Option<usize>>, Load) {
    let n = kinds.len();
    let mut target: Vec<Option<usize>> = vec![None; n];
    let mut load = Load::new();
    // The assets each target list matches, with their rank, in scene order: worked out once
    // per list (a scene has a few kinds, but may have thousands of assets).
    let mut matches: HashMap<&[String], Vec<(usize, usize)>> = HashMap::new();
    for i in 0..n {
        let Some(rel) = &kinds[i].relate else {
            continue;
        };
        let ranked = matches.entry(rel.to.as_slice()).or_insert_with(|| {
            (0..n)
                .filter_map(|j| {
                    Knowledge::target_rank(&scene.assets[j], &kinds[j], &rel.to).map(|r| (j, r))
                })
                .collect()
        });
        let best = ranked
            .iter()
            .copied()
            .filter(|&(j, _)| j != i)
            .filter(|(j, _)| !depends_on(&target, *j, i))
            .min_by_key(|&(j, rank)| {
                let used = load_of(&load, j, rel.relation);
                let full = usize::from(used >= capacity(rel.relation));
                (full, rank, used, j)
            });
        if let Some((j, _)) = best {
            *load.entry((j, rel.relation)).or_default() += 1;
            target[i] = Some(j);
        }
    }
    (target, load)
}

/// How many dependents in `relation` target `t` has taken.
fn load_of(load: &Load, t: usize, relation: Relation) -> usize {
    load.get(&(t, relation)).copied().unwrap_or(0)
}

/// Where the chain of targets from `i` ends, and how many steps it takes; a cycle is cut after
/// as many steps as there are assets.
fn chain_end(target: &[Option<usize>], mut i: usize) -> (usize, usize) {
    let mut steps = 0;
    while let Some(j) = target[i] {
        i = j;
        steps += 1;
        if steps > target.len() {
            break;
        }
    }
    (i, steps)
}

/// Whether `j` (transitively) depends on `i`.
fn depends_on(target: &[Option<usize>], mut j: usize, i: usize) -> bool {
    for _ in 0..target.len() {
        match target[j] {
            Some(t) if t == i => return true,
            Some(t) => j = t,
            None => return false,
        }
    }
    false
}

#[async_trait]
impl Planner for RulePlanner {
    async fn plan(&self, scene: &SceneSpec) -> RoleResult<Plan> {
        let (plan, notes) = self.plan_with_notes(scene);
        let mut out = Output::free(plan);
        out.notes = notes;
        Ok(out)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::fixtures::scene;

    #[test]
    fn a_bedroom_plan() {
        let s = scene(&[
            ("nightstand-0", "nightstand", [50.0, 40.0, 55.0]),
            ("bed-0", "bed", [160.0, 210.0, 100.0]),
            ("nightstand-1", "nightstand", [50.0, 40.0, 55.0]),
            ("wardrobe-0", "wardrobe", [120.0, 60.0, 200.0]),
        ]);
        let p = RulePlanner::new().make_plan(&s);
        assert_eq!(p.groups[0], ["bed-0", "nightstand-0", "nightstand-1"]);
        assert_eq!(p.groups[1], ["wardrobe-0"]);
        let ns = &p.constraints["nightstand-1"];
        assert!(ns.against_wall);
        assert_eq!(
            ns.relations,
            vec![RelationSpec {
                relation: Relation::SideOf,
                target: "bed-0".into()
            }]
        );
        assert!(p.constraints["bed-0"].against_wall);
    }

    #[test]
    fn a_table_on_a_rug_stays_on_the_floor_with_the_rug_under_it() {
        let mut s = scene(&[
            ("counter-0", "reception counter", [240.0, 80.0, 110.0]),
            ("sofa-0", "sofa", [180.0, 85.0, 80.0]),
            ("coffee-table-0", "coffee table", [100.0, 50.0, 42.0]),
            ("rug-0", "rug", [200.0, 160.0, 1.0]),
            ("chair-0", "office chair", [60.0, 60.0, 100.0]),
        ]);
        s.prompt =
            "a sofa facing a coffee table on a rug; the counter with a chair behind it".into();
        let (p, notes) = RulePlanner::new().plan_with_notes(&s);
        let table = &p.constraints["coffee-table-0"];
        assert_eq!(table.support, None, "{notes:?}");
        assert_eq!(
            p.constraints["rug-0"].relations,
            vec![RelationSpec {
                relation: Relation::Near,
                target: "coffee-table-0".into()
            }]
        );
        // The chair behind the counter sits at its working side, turned to it.
        let chair = &p.constraints["chair-0"];
        assert_eq!(chair.relations[0].relation, Relation::InFrontOf);
        assert_eq!(chair.facing.as_deref(), Some("counter-0"));
    }

    #[test]
    fn a_table_seated_down_both_sides_stands_free() {
        let mut pieces: Vec<(String, &str, [f64; 3])> = (0..8)
            .map(|i| (format!("chair-{i}"), "chair", [50.0, 55.0, 82.0]))
            .collect();
        pieces.push(("coffee-table-0".into(), "coffee table", [100.0, 50.0, 45.0]));
        let named: Vec<(&str, &str, [f64; 3])> = pieces
            .iter()
            .map(|(n, c, s)| (n.as_str(), *c, *s))
            .collect();
        let mut s = scene(&named);
        s.assets[8].description = Some("magazine table".into());
        s.prompt =
            "two rows of four waiting chairs facing each other across the magazine table".into();
        let (p, notes) = RulePlanner::new().plan_with_notes(&s);
        let f = p.formations.first().expect("a formation");
        assert_eq!(
            (f.shape, f.count, f.focus.as_deref()),
            (FormationShape::PerSide, Some(4), Some("coffee-table-0")),
            "{notes:?}"
        );
        assert!(
            !p.constraints
                .get("coffee-table-0")
                .is_some_and(|c| c.against_wall),
            "{:?}",
            p.constraints.get("coffee-table-0")
        );
    }

    #[test]
    fn a_bench_named_after_the_piano_is_the_piano_s() {
        let s = scene(&[
            ("piano-0", "upright piano", [150.0, 60.0, 125.0]),
            ("piano-bench-0", "piano bench", [80.0, 40.0, 50.0]),
        ]);
        let p = RulePlanner::new().make_plan(&s);
        assert!(
            p.constraints
                .get("piano-0")
                .is_none_or(|c| c.relations.is_empty())
        );
        assert_eq!(
            p.constraints["piano-bench-0"].relations[0].target, "piano-0",
            "{:?}",
            p.constraints
        );
    }

    #[test]
    fn chairs_spread_over_tables_and_face_them() {
        let mut items = vec![
            ("table-0", "dining table", [160.0, 90.0, 75.0]),
            ("table-1", "dining table", [160.0, 90.0, 75.0]),
        ];
        let names: Vec<String> = (0..8).map(|i| format!("chair-{i}")).collect();
        for n in &names {
            items.push((n.as_str(), "dining chair", [45.0, 50.0, 90.0]));
        }
        let p = RulePlanner::new().make_plan(&scene(&items));
        assert_eq!(p.groups.len(), 2);
        assert_eq!(p.groups[0].len(), 5);
        assert_eq!(p.groups[1].len(), 5);
        let c = &p.constraints["chair-3"];
        assert!(!c.against_wall);
        assert_eq!(c.facing.as_deref(), Some(c.relations[0].target.as_str()));
        assert_eq!(c.relations[0].relation, Relation::Around);
    }

    #[test]
    fn a_dishwasher_stands_by_the_sink_not_the_fridge() {
        // The fridge is listed first: one list of kitchen kinds once made it "a sink" too.
        let s = scene(&[
            ("refrigerator-0", "refrigerator", [70.0, 70.0, 180.0]),
            ("kitchen sink-0", "kitchen sink", [80.0, 60.0, 90.0]),
            ("dishwasher-0", "dishwasher", [60.0, 60.0, 85.0]),
        ]);
        let plan = RulePlanner::new().make_plan(&s);
        let rel = &plan.constraints["dishwasher-0"].relations[0];
        assert_eq!(rel.relation, Relation::SideOf);
        assert_eq!(rel.target, "kitchen sink-0");
    }

    #[test]
    fn stools_sit_at_the_island_and_chairs_at_the_table() {
        let s = scene(&[
            ("kitchen table-0", "kitchen table", [160.0, 90.0, 75.0]),
            ("kitchen island-0", "kitchen island", [200.0, 100.0, 90.0]),
            ("dining chair-0", "dining chair", [45.0, 50.0, 90.0]),
            ("bar stool-0", "bar stool", [40.0, 40.0, 75.0]),
            ("bar stool-1", "bar stool", [40.0, 40.0, 75.0]),
        ]);
        let plan = RulePlanner::new().make_plan(&s);
        let target = |n: &str| plan.constraints[n].relations[0].target.clone();
        assert_eq!(target("bar stool-0"), "kitchen island-0");
        assert_eq!(target("bar stool-1"), "kitchen island-0");
        assert_eq!(target("dining chair-0"), "kitchen table-0");
    }

    #[test]
    fn names_and_descriptions_say_whose_seat_and_top_a_piece_is() {
        let mut s = scene(&[
            ("gate-counter-0", "gate counter", [250.0, 70.0, 105.0]),
            (
                "charging-station-0",
                "charging station",
                [60.0, 60.0, 110.0],
            ),
            ("agent-chair-0", "office chair", [60.0, 60.0, 100.0]),
            ("agent-chair-1", "office chair", [60.0, 60.0, 100.0]),
            ("scanner-0", "boarding pass scanner", [25.0, 25.0, 30.0]),
            ("side-table-0", "side table", [60.0, 60.0, 60.0]),
        ]);
        let describe = |s: &mut SceneSpec, name: &str, text: &str| {
            if let Some(a) = s.assets.iter_mut().find(|a| a.name == name) {
                a.description = Some(text.into());
            }
        };
        describe(
            &mut s,
            "gate-counter-0",
            "boarding desk, agents work behind it",
        );
        describe(&mut s, "agent-chair-0", "gate agent's chair");
        describe(&mut s, "agent-chair-1", "gate agent's chair");
        describe(&mut s, "scanner-0", "reads boarding passes");
        s.assets[4].support = Some(disco_core::scene::Support::Surface);
        let plan = RulePlanner::new().make_plan(&s);
        // Worked from behind: a serving counter, standing free.
        let counter = plan.constraints.get("gate-counter-0");
        assert!(counter.is_none_or(|c| !c.against_wall), "{counter:?}");
        for chair in ["agent-chair-0", "agent-chair-1"] {
            let at = &plan.constraints[chair].relations[0];
            assert_eq!(
                at.target, "gate-counter-0",
                "{chair} is the gate agents' seat"
            );
        }
        // The scanner's words name the boarding desk, not the lower side table.
        let on = plan.constraints["scanner-0"]
            .relations
            .iter()
            .find(|r| r.relation == Relation::On)
            .map(|r| r.target.as_str());
        assert_eq!(on, Some("gate-counter-0"));
    }

    #[test]
    fn waiting_chairs_line_the_walls_not_the_reception_desk() {
        let s = scene(&[
            ("reception desk-0", "reception desk", [180.0, 70.0, 105.0]),
            ("office chair-0", "office chair", [60.0, 60.0, 100.0]),
            ("waiting chair-0", "waiting chair", [55.0, 60.0, 85.0]),
            ("waiting chair-1", "waiting chair", [55.0, 60.0, 85.0]),
            ("chair-0", "chair", [55.0, 55.0, 85.0]),
        ]);
        let plan = RulePlanner::new().make_plan(&s);
        for n in ["waiting chair-0", "waiting chair-1"] {
            let c = &plan.constraints[n];
            assert!(c.against_wall, "{n} stands against a wall");
            assert!(c.relations.is_empty(), "{n} is nobody's desk chair");
        }
        // A plain chair is nobody's seat at the reception desk either: the desk is the staff's.
        let chair = plan.constraints.get("chair-0");
        assert!(chair.is_none_or(|c| c.relations.is_empty()), "{chair:?}");
        let desk_chair = &plan.constraints["office chair-0"].relations[0];
        assert_eq!(desk_chair.target, "reception desk-0");
    }

    #[test]
    fn a_living_room_chain_stays_in_one_group() {
        let s = scene(&[
            ("sofa-0", "sofa", [220.0, 95.0, 85.0]),
            ("coffee table-0", "coffee table", [110.0, 60.0, 45.0]),
            ("tv stand-0", "tv stand", [180.0, 45.0, 55.0]),
            ("armchair-0", "armchair", [85.0, 85.0, 95.0]),
        ]);
        let p = RulePlanner::new().make_plan(&s);
        assert_eq!(p.groups.len(), 1, "{:?}", p.groups);
        assert_eq!(p.groups[0][0], "sofa-0");
        assert_eq!(
            p.constraints["tv stand-0"].relations[0].relation,
            Relation::Opposite
        );
        assert_eq!(
            p.constraints["armchair-0"].relations[0].target,
            "coffee table-0"
        );
    }

    #[test]
    fn every_asset_is_in_exactly_one_group() {
        let s = scene(&[
            ("x-0", "mystery machine", [100.0, 100.0, 100.0]),
            ("rug-0", "rug", [200.0, 100.0, 1.0]),
            ("chair-0", "chair", [45.0, 45.0, 90.0]),
        ]);
        let p = RulePlanner::new().make_plan(&s);
        let mut all: Vec<&String> = p.groups.iter().flatten().collect();
        all.sort();
        assert_eq!(all, ["chair-0", "rug-0", "x-0"]);
    }

    #[test]
    fn the_prompt_says_what_goes_on_and_above_what() {
        let mut s = scene(&[
            ("bed-0", "double bed", [160.0, 210.0, 100.0]),
            ("dresser-0", "dresser", [120.0, 50.0, 80.0]),
            ("painting-0", "painting", [80.0, 4.0, 60.0]),
            ("vase-0", "vase", [15.0, 15.0, 30.0]),
            ("sofa-0", "sofa", [200.0, 90.0, 85.0]),
            ("tv-stand-0", "tv stand", [150.0, 40.0, 50.0]),
            ("tv-0", "tv", [120.0, 8.0, 70.0]),
            ("box-0", "storage box", [40.0, 30.0, 25.0]),
        ]);
        let rel = |p: &Plan, n: &str| {
            p.constraints
                .get(n)
                .and_then(|c| c.relations.first())
                .map(|r| (r.relation, r.target.clone()))
        };
        // The knowledge alone: the painting above the bed, the TV on its stand, the box on
        // the floor.
        let plain = RulePlanner::new().make_plan(&s);
        assert_eq!(
            rel(&plain, "painting-0"),
            Some((Relation::Above, "bed-0".into()))
        );
        assert_eq!(
            rel(&plain, "tv-0"),
            Some((Relation::On, "tv-stand-0".into()))
        );
        assert_eq!(plain.support_of("box-0"), None);
        s.prompt = "the painting above the dresser, the TV on the wall facing the sofa and a \
                    storage box on the dresser"
            .into();
        let asked = RulePlanner::new().make_plan(&s);
        assert_eq!(
            rel(&asked, "painting-0"),
            Some((Relation::Above, "dresser-0".into()))
        );
        assert_eq!(asked.support_of("tv-0"), Some(Support::Wall));
        assert_eq!(
            rel(&asked, "tv-0"),
            Some((Relation::Opposite, "sofa-0".into()))
        );
        assert_eq!(asked.support_of("box-0"), Some(Support::Surface));
        assert_eq!(
            rel(&asked, "box-0"),
            Some((Relation::On, "dresser-0".into()))
        );
    }

    #[test]
    fn a_u_of_tables_takes_its_seats_and_an_l_its_desks_and_chair() {
        let mut items = vec![("screen-0", "presentation screen", [200.0, 50.0, 200.0])];
        let tables: Vec<String> = (0..6).map(|i| format!("table-{i}")).collect();
        let chairs: Vec<String> = (0..12).map(|i| format!("chair-{i}")).collect();
        for t in &tables {
            items.push((t.as_str(), "meeting table", [140.0, 70.0, 75.0]));
        }
        for c in &chairs {
            items.push((c.as_str(), "office chair", [55.0, 55.0, 88.0]));
        }
        let mut s = scene(&items);
        s.prompt = "Six tables in a U whose open end faces the presentation screen, with \
                    chairs round the outside, two per table."
            .into();
        let p = RulePlanner::new().make_plan(&s);
        let u = p
            .formations
            .iter()
            .find(|f| f.shape == FormationShape::UTables)
            .expect("a U");
        assert_eq!(u.focus.as_deref(), Some("screen-0"));
        assert_eq!(u.count, Some(2));
        assert_eq!(u.members[..6], tables[..]);
        assert_eq!(u.members.len(), 18);
        for t in &tables {
            let at = chairs
                .iter()
                .filter(|c| p.constraints[c.as_str()].relations[0].target == *t)
                .count();
            assert_eq!(at, 2, "{t}");
        }
        // One group with the screen, posed as one.
        let g = p.group_of("table-3").unwrap();
        assert_eq!(p.group_of("screen-0"), Some(g));
        assert_eq!(p.group_of("chair-7"), Some(g));

        let mut s = scene(&[
            ("desk-0", "desk", [120.0, 60.0, 75.0]),
            ("desk-1", "desk", [160.0, 70.0, 75.0]),
            ("office-chair-0", "office chair", [65.0, 65.0, 110.0]),
        ]);
        s.prompt = "An L-shaped desk in the corner, the office chair in the crook.".into();
        let p = RulePlanner::new().make_plan(&s);
        let l = p
            .formations
            .iter()
            .find(|f| f.shape == FormationShape::LDesks)
            .expect("an L");
        // The wider desk is the main one.
        assert_eq!(l.members, ["desk-1", "desk-0", "office-chair-0"]);
        assert!(p.constraints["desk-1"].against_wall);
        assert!(p.constraints["desk-0"].against_wall);
        assert_eq!(p.group_of("desk-0"), p.group_of("desk-1"));
        assert_eq!(p.group_of("office-chair-0"), p.group_of("desk-1"));
    }

    #[test]
    fn seats_in_a_ring_are_no_tables_seats_and_not_left_over() {
        let mut scene = SceneSpec {
            id: "ring".into(),
            prompt:
                "Six chairs in a closed circle around the rug, the table against the left wall."
                    .into(),
            room_type: "seminar room".into(),
            room: disco_core::scene::Room::rect(700.0, 600.0),
            assets: Vec::new(),
        };
        for i in 0..6 {
            scene.assets.push(disco_core::scene::Asset::new(
                &format!("chair-{i}"),
                "chair",
                [50.0, 50.0, 85.0],
            ));
        }
        scene.assets.push(disco_core::scene::Asset::new(
            "rug-0",
            "rug",
            [300.0, 300.0, 1.0],
        ));
        scene.assets.push(disco_core::scene::Asset::new(
            "table-0",
            "table",
            [160.0, 60.0, 75.0],
        ));
        let (plan, notes) = RulePlanner::new().plan_with_notes(&scene);
        let ring = plan.formation_of("chair-0").expect("a ring");
        assert_eq!(ring.shape, FormationShape::Ring);
        assert_eq!(ring.focus.as_deref(), Some("rug-0"));
        assert_eq!(ring.members.len(), 6);
        assert!(
            !notes.iter().any(|n| n.contains("has room for this seat")),
            "{notes:?}"
        );
        for i in 0..6 {
            let c = &plan.constraints[&format!("chair-{i}")];
            assert!(c.relations.iter().all(|r| r.target != "table-0"), "{c:?}");
        }
    }

    #[test]
    fn what_a_description_says_of_a_seats_neighbours_leaves_it_at_its_table() {
        let mut s = scene(&[
            ("banquette-bench-0", "banquette bench", [240.0, 55.0, 45.0]),
            ("bistro-table-0", "bistro table", [70.0, 70.0, 75.0]),
            ("cafe-chair-0", "cafe chair", [45.0, 50.0, 85.0]),
        ]);
        s.assets[2].description = Some("opposite the banquette at a bistro table".into());
        let plan = RulePlanner::new().make_plan(&s);
        let at = &plan.constraints["cafe-chair-0"].relations;
        assert_eq!(at.len(), 1, "{at:?}");
        assert_eq!(at[0].target, "bistro-table-0", "{at:?}");
        // The same words in the prompt are the user's: they win.
        s.prompt = "the cafe chair opposite the banquette bench".into();
        s.assets[2].description = None;
        let plan = RulePlanner::new().make_plan(&s);
        let at = &plan.constraints["cafe-chair-0"].relations;
        assert!(at.iter().any(|r| r.target == "banquette-bench-0"), "{at:?}");
    }
}
