//! What the scene loop takes from the roles, and how: plans made usable, poses checked and
//! completed, questions asked and answers read, refined layouts taken over, the final layout
//! assembled so that every asset ends in `objects` or `dropped`.

use std::collections::HashSet;

use glam::DVec2;

use serde_json::json;

use super::super::accept::complete;
use super::moved::tool_moves;
use super::{Loop, Progress};
use crate::config::{QuestionStyle, Stage};
use crate::trace::TraceKind;
use disco_agents::vlm::formation::formation_settles;
use disco_core::layout::{Dropped, Layout, PlacedObject, Stats};
use disco_core::plan::Plan;
use disco_core::relations::{ConstraintCheck, ConstraintKind, constraints_of};
use disco_core::roles::{Answer, Evaluation, Question, Refined};
use disco_core::scene::SceneSpec;
use disco_core::targets::{is_room_part, takes_room_part};

impl Loop<'_> {
    /// One question per constraint of the group's objects, or one open question (`style`: the
    /// evaluator's).
    pub(super) fn questions(
        &self,
        plan: &Plan,
        group: &[String],
        p: &Progress,
        style: QuestionStyle,
    ) -> Vec<Question> {
        if style == QuestionStyle::Open {
            return vec![Question {
                id: 0,
                text: format!(
                    "Does the layout of {} look right for a {}?",
                    group.join(", "),
                    self.scene.room_type
                ),
                subject: None,
                constraint: None,
            }];
        }
        let placed: HashSet<&str> = p.placed.iter().map(|o| o.name.as_str()).collect();
        let in_group: HashSet<&str> = group.iter().map(String::as_str).collect();
        // The group's own constraints whose other object is placed, then the deferred ones:
        // earlier objects' constraints on an object of this group, askable only now. A
        // constraint on an object not placed yet waits for its group (nobody could fix it now).
        let deferred = p
            .placed
            .iter()
            .map(|o| o.name.as_str())
            .filter(|n| !in_group.contains(n) && names_any_of(plan, n, &in_group));
        let mut out = Vec::new();
        for (subject, own) in group
            .iter()
            .map(|n| (n.as_str(), true))
            .chain(deferred.map(|n| (n, false)))
        {
            for kind in constraints_of(plan, subject) {
                let askable = match (&kind, kind.target()) {
                    // Where in the room it stands (a zone, a wall's role, under a window): a
                    // question about the group's own object, whose answer the SRT can act on.
                    (ConstraintKind::Place(_), _) => own,
                    // Against-wall is a physical matter (the PRT's); the questions are semantic.
                    (_, None) => false,
                    // A relation the subject's formation settles (a chair of an arc about its
                    // piano) is the formation's: it is posed as a whole, not asked piece by piece.
                    (_, Some(t)) if formation_settles(plan, subject, t) => false,
                    (_, Some(t)) if placed.contains(t) => own || in_group.contains(t),
                    // A door, a window or a wall is always there: asked with its subject.
                    (_, Some(t)) => own && is_room_part(&self.scene.room, t),
                };
                if !askable {
                    continue;
                }
                // Reported infeasible: not asked about again (the notes say so).
                if self
                    .infeasible
                    .iter()
                    .any(|i| i.subject == subject && i.constraint == kind)
                {
                    continue;
                }
                let statement = ConstraintCheck {
                    subject: subject.to_string(),
                    kind: kind.clone(),
                    met: false,
                };
                out.push(Question {
                    id: out.len(),
                    text: format!("Is it true that {statement}?"),
                    subject: Some(subject.to_string()),
                    constraint: Some(kind),
                });
            }
        }
        out
    }

    /// The designer's accepted poses, and the objects of `group` it left out at the room centre
    /// (the PRT finds them a place); the notes say which.
    pub(super) fn park_missing(
        &mut self,
        group: &[String],
        mut poses: Vec<PlacedObject>,
    ) -> Vec<PlacedObject> {
        let posed: HashSet<String> = poses.iter().map(|o| o.name.clone()).collect();
        let centre = DVec2::new(self.scene.room.width / 2.0, self.scene.room.depth / 2.0);
        for name in group.iter().filter(|n| !posed.contains(*n)) {
            if let Some(a) = self.scene.asset(name) {
                self.notes.push(format!("designer did not place {name:?}"));
                self.unplaced.insert(name.clone());
                poses.push(PlacedObject {
                    name: a.name.clone(),
                    category: a.category.clone(),
                    size: a.size,
                    position: [centre.x, centre.y],
                    rotation: 0.0,
                    ..Default::default()
                });
            }
        }
        poses
    }

    /// Objects the designer left out start at the room centre when a PRT stage will find them a
    /// place; in a graph without one they are dropped, as a method without physical refinement
    /// would have to.
    pub(super) fn park_or_drop(
        &self,
        poses: Vec<PlacedObject>,
    ) -> (Vec<PlacedObject>, Vec<Dropped>) {
        let graph = self.graph;
        let has_prt =
            graph.run.final_prt || graph.round().iter().any(|s| matches!(s, Stage::Prt(_)));
        if has_prt {
            return (poses, Vec::new());
        }
        let mut dropped = Vec::new();
        let kept = poses
            .into_iter()
            .filter(|p| {
                let unplaced = self.unplaced.contains(&p.name);
                if unplaced {
                    dropped.push(Dropped {
                        name: p.name.clone(),
                        reason: "the designer found no place for it and no PRT stage runs".into(),
                    });
                }
                !unplaced
            })
            .collect();
        (kept, dropped)
    }

    /// Takes the PRT's accepted poses and drops; its notes go to the scene's, each once (the PRT
    /// runs over the whole layout every round, and says the same of an object each time). What
    /// it moved (`by`: the stage) is found and explained, the objects the plan ties to a moved
    /// one move with it where they can, and each move goes to the notes, the trace and the next
    /// request of every agent.
    pub(super) fn take_refined(&mut self, p: &mut Progress, refined: Refined, by: &str) {
        let known: HashSet<&String> = self.notes.iter().collect();
        let fresh: Vec<String> = refined
            .notes
            .into_iter()
            .filter(|n| !known.contains(n))
            .collect();
        self.notes.extend(fresh);
        let before = self.layout_of(p);
        let mut after = before.clone();
        after.objects = refined.objects;
        let moves = tool_moves(&before, &mut after, by);
        for m in moves {
            self.event(None, TraceKind::Moved, None, None, json!(m));
            self.notes.push(format!("unasked move: {m}"));
            self.tool_moves.push(m);
        }
        p.dropped.extend(refined.dropped);
        p.placed = after.objects;
    }

    /// The final layout: every asset of the scene exactly once, in `objects` (scene order) or in
    /// `dropped` with a reason; whatever had to be mended on the way is noted.
    pub(super) fn finish(&mut self, p: Progress) -> Layout {
        let Progress {
            plan,
            placed,
            dropped,
            ..
        } = p;
        let (objects, dropped) = complete(&self.scene, placed, dropped, &mut self.notes);
        Layout {
            id: self.scene.id.clone(),
            room: self.scene.room.clone(),
            objects,
            dropped,
            plan,
            stats: Stats::default(),
        }
    }
}

/// A fingerprint of an SRT request: the poses (to 0.1 cm and degree) and the failed checks.
pub(super) fn srt_key(placed: &[PlacedObject], failed: &[(Question, Answer)]) -> u64 {
    use std::hash::{Hash, Hasher};
    let mut h = std::collections::hash_map::DefaultHasher::new();
    for o in placed {
        o.name.hash(&mut h);
        for v in [o.position[0], o.position[1], o.rotation] {
            ((v * 10.0).round() as i64).hash(&mut h);
        }
    }
    for (q, _) in failed {
        q.text.hash(&mut h);
    }
    h.finish()
}

/// Applies an SRT's or a custom stage's moves to `placed`: each object takes its new pose, and
/// what holds it (`elevation`, `on`, `wall`) when the move says; a move that says nothing of it
/// (a refiner that only knows the floor) leaves an object off the floor where it hangs or
/// stands, for the PRT to settle.
pub(super) fn apply(placed: &mut [PlacedObject], moves: Vec<PlacedObject>) {
    for m in moves {
        if let Some(o) = placed.iter_mut().find(|o| o.name == m.name) {
            o.position = m.position;
            o.rotation = m.rotation;
            if !m.on_floor() || m.elevation != 0.0 {
                o.elevation = m.elevation;
                o.on = m.on;
                o.wall = m.wall;
            }
        }
    }
}

pub(super) fn failed_questions(
    questions: &[Question],
    eval: &Evaluation,
) -> Vec<(Question, Answer)> {
    questions
        .iter()
        .filter_map(|q| {
            // A question the evaluator did not answer counts as failed: nothing is silently passed.
            let a = eval
                .answers
                .iter()
                .find(|a| a.id == q.id)
                .cloned()
                .unwrap_or(Answer {
                    id: q.id,
                    yes: false,
                    reason: "no answer".into(),
                });
            (!a.yes).then(|| (q.clone(), a))
        })
        .collect()
}

/// Makes any plan usable: unknown names are dropped from constraints and groups, repeated
/// relations too (so the plan stays bounded by the scene), each asset is in exactly one group (the missing ones in a last group), and assets that fit the room in no
/// rotation are dropped up front with the reason.
pub fn sanitize_plan(
    scene: &SceneSpec,
    mut plan: Plan,
    notes: &mut Vec<String>,
) -> (Plan, Vec<Dropped>) {
    let known: HashSet<&str> = scene.assets.iter().map(|a| a.name.as_str()).collect();
    let before = plan.constraints.len();
    plan.constraints.retain(|k, _| known.contains(k.as_str()));
    let mut repeated = 0;
    // A target is an asset, or a part of the room (a door, a window, a wall) for the relations
    // that can take one.
    let part = |t: &str| !known.contains(t) && is_room_part(&scene.room, t);
    for c in plan.constraints.values_mut() {
        c.relations.retain(|r| {
            known.contains(r.target.as_str()) || (takes_room_part(r.relation) && part(&r.target))
        });
        // Each relation once: a plan cannot grow without bound with repeats.
        let before = c.relations.len();
        let mut seen_relations = HashSet::new();
        c.relations
            .retain(|r| seen_relations.insert((r.relation, r.target.clone())));
        repeated += before - c.relations.len();
        if c.facing
            .as_deref()
            .is_some_and(|t| !known.contains(t) && !part(t))
        {
            c.facing = None;
        }
    }
    if repeated > 0 {
        notes.push(format!("plan: ignored {repeated} repeated relations"));
    }
    if plan.constraints.len() < before {
        notes.push(format!(
            "plan: ignored constraints for {} unknown objects",
            before - plan.constraints.len()
        ));
    }
    let mut dropped = Vec::new();
    let mut misfits = HashSet::new();
    for a in &scene.assets {
        if let Some(why) = a.misfit(&scene.room) {
            dropped.push(Dropped {
                name: a.name.clone(),
                reason: why,
            });
            misfits.insert(a.name.clone());
        }
    }
    let mut seen: HashSet<String> = HashSet::new();
    let mut groups: Vec<Vec<String>> = Vec::new();
    for g in plan.groups {
        let g: Vec<String> = g
            .into_iter()
            .filter(|n| {
                known.contains(n.as_str()) && !misfits.contains(n) && seen.insert(n.clone())
            })
            .collect();
        if !g.is_empty() {
            groups.push(g);
        }
    }
    let rest: Vec<String> = scene
        .assets
        .iter()
        .filter(|a| !seen.contains(&a.name) && !misfits.contains(&a.name))
        .map(|a| a.name.clone())
        .collect();
    if !rest.is_empty() {
        notes.push(format!(
            "plan: {} objects were in no group; placed last",
            rest.len()
        ));
        groups.push(rest);
    }
    plan.groups = groups;
    (plan, dropped)
}

/// Whether a constraint of `subject` in `plan` targets one of `names`: a cheap test that skips the
/// many earlier objects with nothing to ask about the group at hand.
fn names_any_of(plan: &Plan, subject: &str, names: &HashSet<&str>) -> bool {
    plan.constraints.get(subject).is_some_and(|c| {
        c.relations
            .iter()
            .any(|r| names.contains(r.target.as_str()))
            || c.facing.as_deref().is_some_and(|t| names.contains(t))
    })
}
