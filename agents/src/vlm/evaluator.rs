//! The VLM evaluator: yes/no questions answered by the model looking at the layout (one call per
//! question, or one batched call), and the physical yes/no. A question the model leaves
//! unanswered gets the geometric answer, and the notes say so; the physical verdict is the
//! model's or the geometry's (`physical = "either"`, the default), so a model that misses a
//! collision cannot leave one in place.

use async_trait::async_trait;
use serde_json::{Value, json};

use super::schema::{self, list};
use super::{VlmBase, object_vars, scene_vars, yes_no};
use crate::rules::RuleEvaluator;
use disco_core::roles::{Answer, EvalRequest, Evaluator, Output, Question, RoleResult};

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

/// Evaluates with a model.
pub struct VlmEvaluator {
    base: VlmBase,
    physical: PhysicalVerdict,
}

impl VlmEvaluator {
    /// An evaluator over `base`; `options.physical` is `model`, `geometry` or `either`.
    pub fn new(base: VlmBase, options: &toml::Table) -> Result<Self, String> {
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
        Ok(VlmEvaluator { base, physical })
    }

    fn vars(&self, req: &EvalRequest) -> Value {
        let mut vars = scene_vars(&req.ctx.scene);
        vars["objects"] = json!(object_vars(&req.layout.objects));
        vars["has_image"] = json!(self.base.client.vision && req.render.is_some());
        vars
    }
}

fn read_answer(v: &Value) -> Result<(bool, String), String> {
    let yes = v
        .get("answer")
        .and_then(yes_no)
        .or_else(|| yes_no(v))
        .ok_or("expected {\"answer\": \"yes\" or \"no\", \"reason\": ...}")?;
    let reason = v
        .get("reason")
        .and_then(Value::as_str)
        .unwrap_or("")
        .to_string();
    Ok((yes, reason))
}

#[async_trait]
impl Evaluator for VlmEvaluator {
    async fn answer(&self, req: &EvalRequest, questions: &[Question]) -> RoleResult<Vec<Answer>> {
        let mut vars = self.vars(req);
        let mut out: Output<Vec<Answer>> = Output::free(Vec::new());
        if let [q] = questions {
            vars["question"] = json!(q.text);
            let asked = self
                .base
                .ask(
                    &format!("evaluator: {}", q.text),
                    "evaluator",
                    &vars,
                    req.render.clone(),
                    &schema::answer(),
                    read_answer,
                )
                .await?;
            if let Ok((yes, reason)) = out.absorb(asked) {
                out.value.push(Answer {
                    id: q.id,
                    yes,
                    reason,
                });
            }
        } else {
            vars["questions"] = json!(
                questions
                    .iter()
                    .map(|q| json!({"id": q.id, "text": q.text}))
                    .collect::<Vec<_>>()
            );
            let ids: Vec<usize> = questions.iter().map(|q| q.id).collect();
            let asked = self
                .base
                .ask(
                    "evaluator: batch",
                    "evaluator_batch",
                    &vars,
                    req.render.clone(),
                    &schema::answers(),
                    |v| {
                        let answers: Vec<Answer> = list(v, "answers")?
                            .iter()
                            .filter_map(|a| {
                                let id = a.get("id").and_then(Value::as_u64)? as usize;
                                let (yes, reason) = read_answer(a).ok()?;
                                ids.contains(&id).then_some(Answer { id, yes, reason })
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
                answers.dedup_by_key(|a| a.id);
                out.value = answers;
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
        Ok(out)
    }

    async fn needs_physical(&self, req: &EvalRequest) -> RoleResult<bool> {
        let geometry = RuleEvaluator.needs_physical(req).await?.value;
        if self.physical == PhysicalVerdict::Geometry {
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
