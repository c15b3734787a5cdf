//! A prompt-only custom stage (`role = "patch"`, `impl = "vlm"`): the graph's `prompt` file is the
//! whole stage. The template sees the scene, the plan, the layout so far and the group; the model
//! answers in the SRT's moves schema (new poses for the objects it moves, of the group only).

use std::sync::Arc;

use async_trait::async_trait;
use serde_json::json;

use super::schema;
use super::{VlmBase, object_vars, scene_vars};
use disco_core::layout::PlacedObject;
use disco_core::render::{RenderOptions, render_png};
use disco_core::roles::{Output, PatchRequest, Patcher, RoleResult};
use disco_llm::extract::NameMap;

/// The template name the stage's prompt file is loaded under.
pub const TEMPLATE: &str = "patch";

/// A custom stage written as a prompt.
pub struct VlmPatch {
    base: VlmBase,
    name: String,
}

impl VlmPatch {
    /// The stage `name` over `base`, whose prompts hold the stage's template as [`TEMPLATE`].
    pub fn new(base: VlmBase, name: &str) -> Self {
        VlmPatch {
            base,
            name: name.to_string(),
        }
    }
}

#[async_trait]
impl Patcher for VlmPatch {
    async fn patch(&self, req: &PatchRequest) -> RoleResult<Vec<PlacedObject>> {
        if req.group.is_empty() {
            return Ok(Output::free(Vec::new()));
        }
        let scene = &req.ctx.scene;
        let mut vars = scene_vars(scene);
        vars["objects"] = json!(object_vars(&req.layout.objects));
        super::off_floor_vars(&mut vars, scene, &req.ctx.plan, &req.layout.objects);
        vars["plan"] = serde_json::to_value(&*req.ctx.plan).unwrap_or_default();
        vars["group"] = json!(req.group);
        vars["movable"] = json!(req.group);
        vars["moved"] = json!(super::moved_vars(&req.ctx));
        let render = match self.base.client.vision {
            true => render_png(&req.layout, &RenderOptions::default())
                .ok()
                .map(Arc::new),
            false => None,
        };
        vars["has_image"] = json!(render.is_some());
        let names = NameMap::new(req.group.iter().cloned());
        let out = self
            .base
            .ask(
                &self.name,
                TEMPLATE,
                &vars,
                render,
                &schema::with_turns(schema::poses(&req.group), &scene.room),
                |v| super::srt::read_moves(v, &mut names.clone(), &scene.room),
            )
            .await?;
        Ok(super::srt::into_moves(out, &req.layout))
    }
}
