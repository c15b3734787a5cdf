//! The VLM evaluator: yes/no questions answered by the model looking at the layout (one call per
//! question, or one batched call), and the physical yes/no.
//!
//! Every question about a constraint is measurable: the metric grades it with a predicate of
//! `disco_core::relations`. By default (`ask = "unsettled"`) such a question is not sent: the
//! geometry answers it, with the predicate and the measured values as its reason, and only
//! questions the geometry cannot settle (an open question) reach the model. With
//! `ask = "all"` every question is sent, stating the predicate and the measured values; an
//! answer that contradicts the geometry is noted, and the geometry's answer is the one that
//! counts (it drives refinement), as `physical = "either"` does for physics. A question the
//! model leaves unanswered gets the geometric answer, and the notes say so.

use async_trait::async_trait;
use serde_json::{Value, json};

use std::collections::HashMap;

use super::measure::{self, Measured};
use super::schema::{self, list};
use super::{VlmBase, moved_vars, object_vars, scene_vars, yes_no};
use crate::rules::RuleEvaluator;
use disco_core::roles::{Answer, EvalRequest, Evaluator, Infeasible, Output, Question, RoleResult};

/// Whose physical verdict counts.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum PhysicalVerdict {
    /// The model's alone (the paper's setting).
    Model,
    /// Exact geometry alone.
    Geometry,
    /// Refine when either says so.
    Either,
}

/// Which questions go to the model.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Ask {
    /// Only what the geometry cannot settle (open questions; the physical verdict only with
    /// `physical = "model"`).
    Unsettled,
    /// Every question, with its predicate and measured values; the geometry still decides.
    All,
}

/// Evaluates with a model.
pub struct VlmEvaluator {
    base: VlmBase,
    physical: PhysicalVerdict,
    ask: Ask,
}

impl VlmEvaluator {
    /// An evaluator over `base`; `options.physical` is `model`, `geometry` or `either`;
    /// `options.ask` is `unsettled` (the default) or `all`.
    pub fn new(base: VlmBase, options: &toml::Table) -> Result<Self, String> {
        let ask = match options.get("ask").and_then(|v| v.as_str()) {
            None | Some("unsettled") => Ask::Unsettled,
            Some("all") => Ask::All,
            Some(other) => {
                return Err(format!(
                    "options.ask = {other:?}; expected unsettled or all"
                ));
            }
        };
        let physical = match options.get("physical").and_then(|v| v.as_str()) {
            None | Some("either") => PhysicalVerdict::Either,
            Some("model") => PhysicalVerdict::Model,
            Some("geometry") => PhysicalVerdict::Geometry,
            Some(other) => {
                return Err(format!(
                    "options.physical = {other:?}; expected model, geometry or either"
                ));
            }
        };
        Ok(VlmEvaluator {
            base,
            physical,
            ask,
        })
    }

    fn vars(&self, req: &EvalRequest) -> Value {
        let mut vars = scene_vars(&req.ctx.scene);
        vars["objects"] = json!(object_vars(&req.layout.objects));
        super::off_floor_vars(
            &mut vars,
            &req.ctx.scene,
            &req.ctx.plan,
            &req.layout.objects,
        );
        vars["has_image"] = json!(self.base.client.vision && req.render.is_some());
        vars["moved"] = json!(moved_vars(&req.ctx));
        vars["against_wall"] = json!(
            req.layout
                .objects
                .iter()
                .filter(|o| req.ctx.plan.wants_wall(&o.name))
                .map(|o| o.name.clone())
                .collect::<Vec<_>>()
        );
        vars
    }
}

/// A model's answer: yes or no with its reason; `"infeasible"` is a no the model says cannot be
/// helped (read by [`read_verdict`]).
fn read_answer(v: &Value) -> Result<(bool, String), String> {
    read_verdict(v).map(|(yes, reason, _)| (yes, reason))
}

/// As [`read_answer`], and whether the model called the constraint infeasible.
fn read_verdict(v: &Value) -> Result<(bool, String, bool), String> {
    let word = v.get("answer").unwrap_or(v);
    let infeasible = word
        .as_str()
        .is_some_and(|s| s.trim().to_lowercase().starts_with("infeasible"));
    let yes = match infeasible {
        true => false,
        false => yes_no(word)
            .or_else(|| yes_no(v))
            .ok_or("expected {\"answer\": \"yes\", \"no\" or \"infeasible\", \"reason\": ...}")?,
    };
    let reason = v
        .get("reason")
        .and_then(Value::as_str)
        .unwrap_or("")
        .to_string();
    Ok((yes, reason, infeasible))
}

/// The geometry's answer to `q`, with the measured values and the predicate as its reason.
fn geometric_answer(q: &Question, m: &Measured) -> Answer {
    Answer {
        id: q.id,
        yes: m.holds,
        reason: format!(
            "{}measured: {}",
            if m.holds { "" } else { "no: " },
            m.values
        ),
    }
}

/// A question as the prompts show it: its text, the predicate and the measured values.
fn question_vars(q: &Question, m: Option<&Measured>) -> Value {
    let means = q.constraint.as_ref().map(measure::meaning);
    json!({
        "id": q.id,
        "text": q.text,
        "means": means,
        "measured": m.map(|m| m.values.clone()),
    })
}

/// Records that the model called `q` infeasible, unless the geometry finds it met.
fn report_infeasible(
    q: &Question,
    m: Option<&Measured>,
    reason: &str,
    out: &mut Output<Vec<Answer>>,
) {
    if m.is_some_and(|m| m.holds) {
        return;
    }
    if let (Some(subject), Some(constraint)) = (&q.subject, &q.constraint) {
        out.infeasible.push(Infeasible {
            subject: subject.clone(),
            constraint: constraint.clone(),
            reason: reason.to_string(),
        });
    }
}

impl VlmEvaluator {
    /// Asks the model `questions` (one call, or one batched call); the answers it gives go to
    /// `out.value`.
    async fn ask_model(
        &self,
        req: &EvalRequest,
        questions: &[(Question, Option<Measured>)],
        out: &mut Output<Vec<Answer>>,
    ) -> Result<(), disco_core::roles::RoleError> {
        let mut vars = self.vars(req);
        if let [(q, m)] = questions {
            let qv = question_vars(q, m.as_ref());
            vars["question"] = json!(q.text);
            vars["means"] = qv["means"].clone();
            vars["measured"] = qv["measured"].clone();
            let asked = self
                .base
                .ask(
                    &format!("evaluator: {}", q.text),
                    "evaluator",
                    &vars,
                    req.render.clone(),
                    &schema::answer(),
                    read_verdict,
                )
                .await?;
            if let Ok((yes, reason, infeasible)) = out.absorb(asked) {
                if infeasible {
                    report_infeasible(q, m.as_ref(), &reason, out);
                }
                out.value.push(Answer {
                    id: q.id,
                    yes,
                    reason,
                });
            }
            return Ok(());
        }
        vars["questions"] = json!(
            questions
                .iter()
                .map(|(q, m)| question_vars(q, m.as_ref()))
                .collect::<Vec<_>>()
        );
        let ids: Vec<usize> = questions.iter().map(|(q, _)| q.id).collect();
        let asked = self
            .base
            .ask(
                "evaluator: batch",
                "evaluator_batch",
                &vars,
                req.render.clone(),
                &schema::answers(),
                |v| {
                    let answers: Vec<(Answer, bool)> = list(v, "answers")?
                        .iter()
                        .filter_map(|a| {
                            let id = a.get("id").and_then(Value::as_u64)? as usize;
                            let (yes, reason, infeasible) = read_verdict(a).ok()?;
                            ids.contains(&id)
                                .then_some((Answer { id, yes, reason }, infeasible))
                        })
                        .collect();
                    if answers.is_empty() {
                        Err("no answer carries a known question id".into())
                    } else {
                        Ok(answers)
                    }
                },
            )
            .await?;
        if let Ok(mut answers) = out.absorb(asked) {
            answers.sort_by_key(|(a, _)| a.id);
            answers.dedup_by_key(|(a, _)| a.id);
            for (a, infeasible) in answers {
                if infeasible && let Some((q, m)) = questions.iter().find(|(q, _)| q.id == a.id) {
                    report_infeasible(q, m.as_ref(), &a.reason, out);
                }
                out.value.push(a);
            }
        }
        Ok(())
    }
}

#[async_trait]
impl Evaluator for VlmEvaluator {
    async fn answer(&self, req: &EvalRequest, questions: &[Question]) -> RoleResult<Vec<Answer>> {
        let mut out: Output<Vec<Answer>> = Output::free(Vec::new());
        // What the metric's predicate measures for each question (none for an open one).
        let measured: HashMap<usize, Measured> = questions
            .iter()
            .filter_map(|q| {
                let m =
                    measure::measure(&req.layout, q.subject.as_deref()?, q.constraint.as_ref()?)?;
                Some((q.id, m))
            })
            .collect();
        let mut to_ask = Vec::new();
        for q in questions {
            match (self.ask, measured.get(&q.id)) {
                // Settled by the geometry: not sent.
                (Ask::Unsettled, Some(m)) => out.value.push(geometric_answer(q, m)),
                (_, m) => to_ask.push((q.clone(), m.cloned())),
            }
        }
        if !to_ask.is_empty() {
            self.ask_model(req, &to_ask, &mut out).await?;
        }
        // A model's answer that contradicts the geometry on a measurable question: noted, and
        // the geometry's answer counts.
        for a in &mut out.value {
            let Some(m) = measured.get(&a.id) else {
                continue;
            };
            if a.yes != m.holds && to_ask.iter().any(|(q, _)| q.id == a.id) {
                let text = questions
                    .iter()
                    .find(|q| q.id == a.id)
                    .map_or("", |q| q.text.as_str());
                let said = if a.yes { "yes" } else { "no" };
                let truth = if m.holds { "yes" } else { "no" };
                out.notes.push(format!(
                    "the model answered {said} to {text:?} but the metric's predicate says {truth} (measured: {}); the geometry's answer counts",
                    m.values
                ));
                a.reason = format!(
                    "the model said {said} ({}); the geometry says {truth}, measured: {}",
                    a.reason, m.values
                );
                a.yes = m.holds;
            }
        }
        // Whatever the model left unanswered: geometry.
        let missing: Vec<Question> = questions
            .iter()
            .filter(|q| !out.value.iter().any(|a| a.id == q.id))
            .cloned()
            .collect();
        if !missing.is_empty() {
            out.notes.push(format!(
                "the model left {} question(s) unanswered; geometry answered",
                missing.len()
            ));
            let exact = RuleEvaluator.answer(req, &missing).await?;
            out.value.extend(exact.value);
        }
        out.value.sort_by_key(|a| {
            questions
                .iter()
                .position(|q| q.id == a.id)
                .unwrap_or(usize::MAX)
        });
        Ok(out)
    }

    async fn needs_physical(&self, req: &EvalRequest) -> RoleResult<bool> {
        let geometry = RuleEvaluator.needs_physical(req).await?.value;
        // Settled without the model: geometry alone; or "either" while the geometry already
        // asks for repair (the model's answer could not change the verdict); or "either" when
        // only unsettled questions are sent (a model's "yes" the geometry does not share could
        // only run a PRT that keeps every valid pose).
        let settled = match self.physical {
            PhysicalVerdict::Geometry => true,
            PhysicalVerdict::Either => geometry || self.ask == Ask::Unsettled,
            PhysicalVerdict::Model => false,
        };
        if settled {
            return Ok(Output::free(geometry));
        }
        let mut asked = self
            .base
            .ask(
                "evaluator: physical",
                "physical",
                &self.vars(req),
                req.render.clone(),
                &schema::answer(),
                read_answer,
            )
            .await?;
        let model = match std::mem::replace(&mut asked.value, Err(String::new())) {
            Ok((yes, _)) => Some(yes),
            Err(reason) => {
                asked.notes.push(format!(
                    "no usable physical verdict ({reason}); geometry used"
                ));
                None
            }
        };
        let verdict = match (self.physical, model) {
            (PhysicalVerdict::Model, Some(m)) => m,
            (PhysicalVerdict::Either, Some(m)) => m || geometry,
            _ => geometry,
        };
        Ok(asked.map(|_| verdict))
    }

    fn wants_render(&self) -> bool {
        self.base.client.vision
    }
}
