//! The `noisy` designer: the rule-based designer's poses, perturbed (seeded) the way a vision
//! model's raw answer is off. It gives the refinement tools something to do offline, so ablations
//! without a model still mean something.

use std::hash::{DefaultHasher, Hash, Hasher};

use async_trait::async_trait;

use super::rules::RuleDesigner;
use disco_core::layout::PlacedObject;
use disco_core::roles::{DesignRequest, Designer, RoleResult};

/// Rule-based poses plus seeded noise.
pub struct NoisyDesigner {
    inner: RuleDesigner,
    seed: u64,
    shift_cm: f64,
    turn_deg: f64,
}

impl NoisyDesigner {
    /// The keys its `options` table may hold.
    pub const OPTIONS: &'static [&'static str] = &["seed", "shift_cm", "turn_deg"];

    /// A noisy designer; `seed`, `shift_cm` (default 40) and `turn_deg` (default 20) come from the
    /// agent's `options` table.
    pub fn from_options(options: &toml::Table) -> Result<Self, String> {
        use super::options::{number, only_known};
        only_known(options, Self::OPTIONS)?;
        Ok(NoisyDesigner {
            inner: RuleDesigner::new(),
            seed: number(options, "seed", 0.0, 0.0)? as u64,
            shift_cm: number(options, "shift_cm", 40.0, 0.0)?,
            turn_deg: number(options, "turn_deg", 20.0, 0.0)?,
        })
    }
}

#[async_trait]
impl Designer for NoisyDesigner {
    async fn design(&self, req: &DesignRequest) -> RoleResult<Vec<PlacedObject>> {
        let mut out = self.inner.design(req).await?;
        let mut h = DefaultHasher::new();
        (self.seed, &req.ctx.scene.id, &req.group).hash(&mut h);
        let mut rng = fastrand::Rng::with_seed(h.finish());
        for o in &mut out.value {
            let mut r = || rng.f64() * 2.0 - 1.0;
            o.position[0] = (o.position[0] + r() * self.shift_cm).round();
            o.position[1] = (o.position[1] + r() * self.shift_cm).round();
            o.rotation = (o.rotation + r() * self.turn_deg).round();
        }
        Ok(out)
    }
}
