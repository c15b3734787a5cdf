//! The VLM judge of the paper's evaluation protocol: positional and rotational coherency, 0-100,
//! scored by a model looking at the render.

use std::sync::Arc;

use serde::Serialize;
use serde_json::{Value, json};

use super::{VlmBase, object_vars, scene_vars};
use disco_core::layout::Layout;
use disco_core::roles::{RoleError, Usage};
use disco_core::scene::SceneSpec;
use disco_llm::CallRecord;

/// The judge's verdict on one layout.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Scores {
    /// Are objects where they belong (0-100).
    pub positional: f64,
    /// Do objects face the right way (0-100).
    pub rotational: f64,
    /// One sentence.
    pub comment: String,
    /// What judging cost.
    pub usage: Usage,
    /// The calls made.
    pub calls: Vec<CallRecord>,
}

fn read_scores(v: &Value) -> Result<(f64, f64, String), String> {
    let score = |k: &str| {
        v.get(k)
            .and_then(disco_llm::extract::number)
            .filter(|s| (0.0..=100.0).contains(s))
            .ok_or_else(|| format!("`{k}` must be a number from 0 to 100"))
    };
    let comment = v
        .get("comment")
        .and_then(Value::as_str)
        .unwrap_or("")
        .to_string();
    Ok((score("positional")?, score("rotational")?, comment))
}

/// Scores `layout` of `scene`, looking at `png` when the model sees images.
pub async fn judge(
    base: &VlmBase,
    scene: &SceneSpec,
    layout: &Layout,
    png: Option<Arc<Vec<u8>>>,
) -> Result<Scores, RoleError> {
    let mut vars = scene_vars(scene);
    vars["objects"] = json!(object_vars(&layout.objects));
    super::off_floor_vars(&mut vars, scene, &layout.plan, &layout.objects);
    vars["has_image"] = json!(base.client.vision && png.is_some());
    let asked = base
        .ask(
            "judge",
            "judge",
            &vars,
            png,
            &super::schema::scores(),
            read_scores,
        )
        .await?;
    let (positional, rotational, comment) = asked.value.map_err(|reason| {
        RoleError::Failed(format!("the judge gave no usable scores: {reason}"))
    })?;
    Ok(Scores {
        positional,
        rotational,
        comment,
        usage: asked.usage,
        calls: asked.calls,
    })
}
