//! The rule designer itself: the furniture knowledge it works by and what it keeps between
//! groups. Its work is written beside it, one decision per module, in `impl RuleDesigner` blocks.

use std::sync::Arc;

use super::reach_cache::ReachCache;
use super::wishes::WishCache;
use crate::knowledge::Knowledge;

/// Places a group by the furniture knowledge and the plan.
pub struct RuleDesigner {
    pub(super) knowledge: Arc<Knowledge>,
    /// The prompt's wishes of the scenes designed lately, read once per scene.
    pub(super) wishes: WishCache,
    /// The reach of what earlier groups placed, kept for the next group.
    pub(super) reach: ReachCache,
}

impl RuleDesigner {
    /// A designer over the built-in knowledge.
    pub fn new() -> Self {
        RuleDesigner {
            knowledge: Knowledge::builtin(),
            wishes: WishCache::default(),
            reach: ReachCache::default(),
        }
    }
}

impl Default for RuleDesigner {
    fn default() -> Self {
        Self::new()
    }
}
