//! One scene under supervision: the role actors, the scene supervisor that owns them, the typed
//! calls between them and the acceptance of every reply, and the scene loop (plan, then design,
//! evaluate and refine group by group).

pub mod accept;
mod actors;
pub mod caller;
pub mod messages;
pub mod scene_loop;

pub use actors::{RoleActor, RoleMsg, SceneRun, SceneSupervisor, SupervisorArgs, SupervisorMsg};
pub use caller::SceneFailure;
