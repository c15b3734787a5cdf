//! One scene under supervision: the role actors, the scene supervisor that owns them, the typed
//! messages between them, and the scene loop (plan, then design, evaluate and refine group by group).

mod actors;
pub mod caller;
pub mod messages;
pub mod scene_loop;

pub use actors::{RoleActor, RoleMsg, SceneRun, SceneSupervisor, SupervisorArgs, SupervisorMsg};
