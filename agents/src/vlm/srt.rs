//! The VLM Semantic Refinement Tool: the model proposes small moves for the objects whose
//! questions failed; only objects of the current group move.

use async_trait::async_trait;
use serde_json::json;

use super::schema::{self, ReadPose, read_poses};
use super::{VlmBase, object_vars, scene_vars};
use disco_core::layout::{Layout, PlacedObject};
use disco_core::roles::{Output, RoleResult, SemanticRefiner, SrtRequest};
use disco_llm::extract::NameMap;

/// Refines with a model.
pub struct VlmSrt {
    base: VlmBase,
}

impl VlmSrt {
    /// An SRT over `base`.
    pub fn new(base: VlmBase) -> Self {
        VlmSrt { base }
    }
}

#[async_trait]
impl SemanticRefiner for VlmSrt {
    async fn refine(&self, req: &SrtRequest) -> RoleResult<Vec<PlacedObject>> {
        if req.failed.is_empty() || req.movable.is_empty() {
            return Ok(Output::free(Vec::new()));
        }
        let scene = &req.ctx.scene;
        let mut vars = scene_vars(scene);
        vars["objects"] = json!(object_vars(&req.layout.objects));
        vars["failed"] = json!(
            req.failed
                .iter()
                .map(|(q, a)| json!({"question": q.text, "reason": a.reason}))
                .collect::<Vec<_>>()
        );
        vars["movable"] = json!(req.movable);
        vars["has_image"] = json!(self.base.client.vision && req.render.is_some());
        let names = NameMap::new(req.movable.iter().cloned());
        let out = self
            .base
            .ask(
                "srt",
                "srt",
                &vars,
                req.render.clone(),
                &schema::poses(&req.movable),
                |v| read_poses(v, &mut names.clone(), &scene.room),
            )
            .await?;
        Ok(into_moves(out, &req.layout))
    }

    fn wants_render(&self) -> bool {
        self.base.client.vision
    }
}

/// What reading a model's poses gives: the poses and notes, or why none was usable.
pub(super) type PosesRead = Result<(Vec<ReadPose>, Vec<String>), String>;

/// The model's poses as moves of objects already in `layout` (names it does not hold are
/// skipped); an unusable answer moves nothing and says so in the notes.
pub(super) fn into_moves(mut out: Output<PosesRead>, layout: &Layout) -> Output<Vec<PlacedObject>> {
    let moves = match std::mem::replace(&mut out.value, Err(String::new())) {
        Ok((poses, notes)) => {
            out.notes.extend(notes);
            poses
                .into_iter()
                .filter_map(|p| {
                    let o = layout.object(&p.name)?;
                    Some(PlacedObject {
                        position: p.position,
                        rotation: p.rotation,
                        ..o.clone()
                    })
                })
                .collect()
        }
        Err(reason) => {
            out.notes.push(format!(
                "no usable moves from the model ({reason}); nothing moved"
            ));
            Vec::new()
        }
    };
    out.map(|_| moves)
}
