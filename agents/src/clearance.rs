//! An example of a role the paper lacks: the clearance keeper, a `patch` stage that opens walkways.
//!
//! A slit of 1 to `max_slit_cm` cm between two pieces of furniture is neither touching nor
//! walkable. For each object of the current group in such a slit with an object it has no
//! constraint with, the keeper moves it (along the axis of the gap) either to touch or to leave a
//! `walkway_cm` walkway, whichever is the smaller move. The PRT then settles anything it disturbed.
//!
//! Enable it with a TOML entry (see `config/experiments/clearance.toml`):
//!
//! ```toml
//! [agents.clearance]
//! role = "patch"
//! impl = "clearance"
//! [pipeline]
//! round = ["evaluate", "srt", "clearance", "prt"]
//! ```

use async_trait::async_trait;
use glam::DVec2;

use disco_core::layout::PlacedObject;
use disco_core::roles::{Output, PatchRequest, Patcher, RoleResult};

/// Opens or closes slits between furniture.
pub struct ClearanceKeeper {
    max_slit_cm: f64,
    walkway_cm: f64,
}

impl ClearanceKeeper {
    /// The keys its `options` table may hold.
    pub const OPTIONS: &'static [&'static str] = &["max_slit_cm", "walkway_cm"];

    /// A keeper with `max_slit_cm` (default 40) and `walkway_cm` (default 60) from `options`.
    pub fn from_options(options: &toml::Table) -> Result<Self, String> {
        use super::options::{number, only_known};
        only_known(options, Self::OPTIONS)?;
        let get = |k: &str, d: f64| number(options, k, d, f64::MIN_POSITIVE);
        let keeper = ClearanceKeeper {
            max_slit_cm: get("max_slit_cm", 40.0)?,
            walkway_cm: get("walkway_cm", 60.0)?,
        };
        if keeper.walkway_cm <= keeper.max_slit_cm {
            return Err("options.walkway_cm must exceed options.max_slit_cm".into());
        }
        Ok(keeper)
    }

    /// The objects of `group` it moves, with their new poses.
    pub fn patch_layout(&self, req: &PatchRequest) -> Vec<PlacedObject> {
        let layout = &req.layout;
        let plan = &req.ctx.plan;
        let related = |a: &str, b: &str| {
            let mentions = |x: &str, y: &str| {
                plan.constraints.get(x).is_some_and(|c| {
                    c.relations.iter().any(|r| r.target == y) || c.facing.as_deref() == Some(y)
                })
            };
            mentions(a, b) || mentions(b, a)
        };
        let mut moved = Vec::new();
        for name in &req.group {
            let Some(obj) = layout.object(name).filter(|o| !o.is_flat()) else {
                continue;
            };
            let a = obj.footprint().aabb();
            let mut shift = DVec2::ZERO;
            for other in layout
                .objects
                .iter()
                .filter(|o| o.name != *name && !o.is_flat())
            {
                if related(name, &other.name) {
                    continue;
                }
                let b = other.footprint().aabb();
                let gap = a.gap(&b);
                if gap < 1.0 || gap > self.max_slit_cm {
                    continue;
                }
                // The axis of the gap, pointing from the other object towards this one.
                let dx = (a.min.x - b.max.x).max(b.min.x - a.max.x);
                let dy = (a.min.y - b.max.y).max(b.min.y - a.max.y);
                let away = if dx >= dy {
                    DVec2::new(if a.min.x >= b.max.x { 1.0 } else { -1.0 }, 0.0)
                } else {
                    DVec2::new(0.0, if a.min.y >= b.max.y { 1.0 } else { -1.0 })
                };
                let widen = self.walkway_cm - gap;
                shift = if widen < gap {
                    away * widen
                } else {
                    -away * gap
                };
                break;
            }
            if shift != DVec2::ZERO {
                let mut o = obj.clone();
                o.position = [o.position[0] + shift.x, o.position[1] + shift.y];
                moved.push(o);
            }
        }
        moved
    }
}

#[async_trait]
impl Patcher for ClearanceKeeper {
    async fn patch(&self, req: &PatchRequest) -> RoleResult<Vec<PlacedObject>> {
        Ok(Output::free(self.patch_layout(req)))
    }
}
