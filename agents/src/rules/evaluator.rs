//! The rule-based evaluator: answers each question with the shared geometric predicates; the
//! physical verdict is exact geometry.

use async_trait::async_trait;

use disco_core::geometry::BoxBuckets;
use disco_core::relations::{ConstraintCheck, check_one, check_plan};
use disco_core::roles::{Answer, EvalRequest, Evaluator, Output, Question, RoleResult};

/// Exact answers from geometry.
pub struct RuleEvaluator;

#[async_trait]
impl Evaluator for RuleEvaluator {
    async fn answer(&self, req: &EvalRequest, questions: &[Question]) -> RoleResult<Vec<Answer>> {
        let answers = questions
            .iter()
            .map(|q| match (&q.subject, &q.constraint) {
                (Some(subject), Some(kind)) => {
                    let check = ConstraintCheck {
                        subject: subject.clone(),
                        kind: kind.clone(),
                        met: check_one(&req.layout, subject, kind),
                    };
                    Answer {
                        id: q.id,
                        yes: check.met,
                        reason: if check.met {
                            format!("{check}: holds")
                        } else {
                            format!("not so: {check} fails")
                        },
                    }
                }
                _ => {
                    // An open question: the whole plan, in one verdict.
                    let unmet: Vec<String> = check_plan(&req.layout)
                        .into_iter()
                        .filter(|c| !c.met)
                        .map(|c| c.to_string())
                        .collect();
                    Answer {
                        id: q.id,
                        yes: unmet.is_empty(),
                        reason: if unmet.is_empty() {
                            "the layout looks right".into()
                        } else {
                            "something looks off".into()
                        },
                    }
                }
            })
            .collect();
        Ok(Output::free(answers))
    }

    async fn needs_physical(&self, req: &EvalRequest) -> RoleResult<bool> {
        let l = &req.layout;
        let fps: Vec<_> = l
            .objects
            .iter()
            .map(|o| (o.is_flat(), o.footprint()))
            .collect();
        // Furniture may not overlap furniture, nor rugs other rugs; rugs may lie under furniture.
        // Each object is tested against the earlier ones filed near it.
        let mut near = BoxBuckets::new(&l.room);
        let overlap = fps.iter().any(|(fa, a)| {
            let b = a.aabb();
            let hit = near.any(&b, |j| {
                let (fb, other) = &fps[j];
                fa == fb && other.collides(a)
            });
            near.insert(&b);
            hit
        });
        let outside = fps.iter().any(|(_, f)| !f.inside(&l.room));
        // Only the group's own wall pieces: an earlier group's piece left off its wall had the
        // PRT's search then, and found no stretch free; walls only fill up since, so asking
        // again for every later group would re-run the PRT for nothing.
        let off_wall = l.objects.iter().any(|o| {
            req.group.contains(&o.name)
                && l.plan.wants_wall(&o.name)
                && o.footprint().against_wall(&l.room).is_none()
        });
        Ok(Output::free(overlap || outside || off_wall))
    }
}
