//! Roles written in Python, in the same process: a callable (or a class, made once per scene)
//! registered by name for a role, and used from an agent graph like any implementation
//! (`impl = "NAME"`), under the same supervision (deadline, retries, fallback, restarts).
//!
//! Such a role is an [`ExternalAgent`] whose transport is a Python call instead of a pipe or
//! a socket: the callable gets the request of the JSON protocol of `docs/protocol/` as a dict
//! and returns the reply (see `disco_layout/_roles.py`, which wraps the call). The call runs on
//! a blocking thread of the runtime, holding the GIL only while Python runs. When the
//! supervisor gives up on it (deadline), `RoleTimeout` (a `TimeoutError`) is raised inside the
//! callable, so a role stuck in Python code stops; one blocked in C (a `time.sleep`) stops
//! when that returns, and its reply is thrown away.

use std::sync::{Arc, Mutex};

use async_trait::async_trait;
use pyo3::prelude::*;

use disco_layout::registry::{BuildContext, Registry};
use disco_layout::roles::{RoleError, RoleKind};
use disco_layout::runtime::external::{ExternalAgent, Transport};

/// The Python roles registered so far, by role and name, in registration order.
static ROLES: Mutex<Vec<PyRole>> = Mutex::new(Vec::new());

/// One registered Python role.
struct PyRole {
    role: RoleKind,
    name: String,
    /// A callable, or a class to instantiate per scene.
    implementation: Py<PyAny>,
}

/// Registers `implementation` as implementation `name` of `role` (replacing an earlier one of
/// that name). Every graph run afterwards may name it.
pub fn register(role: RoleKind, name: String, implementation: Py<PyAny>) {
    let mut roles = ROLES.lock().unwrap_or_else(|e| e.into_inner());
    roles.retain(|r| !(r.role == role && r.name == name));
    roles.push(PyRole {
        role,
        name,
        implementation,
    });
}

/// Removes Python implementation `name` of `role`; whether there was one.
pub fn unregister(role: RoleKind, name: &str) -> bool {
    let mut roles = ROLES.lock().unwrap_or_else(|e| e.into_inner());
    let before = roles.len();
    roles.retain(|r| !(r.role == role && r.name == name));
    roles.len() != before
}

/// The registered Python roles as `(role, name)`.
pub fn registered() -> Vec<(RoleKind, String)> {
    let roles = ROLES.lock().unwrap_or_else(|e| e.into_inner());
    roles.iter().map(|r| (r.role, r.name.clone())).collect()
}

/// The built-in implementations and every Python role registered so far.
pub fn registry(py: Python<'_>) -> Registry {
    let mut registry = Registry::builtin();
    let roles = ROLES.lock().unwrap_or_else(|e| e.into_inner());
    for r in roles.iter() {
        let implementation = r.implementation.clone_ref(py);
        let role = r.role;
        registry.register(role, &r.name, move |ctx| {
            Python::attach(|py| build(py, role, &implementation, ctx)).map_err(|e| e.to_string())
        });
    }
    registry
}

/// One agent's implementation: the callable itself, or a new instance of the class made with
/// the agent's `options` (but `render`) as keyword arguments.
fn build(
    py: Python<'_>,
    role: RoleKind,
    implementation: &Py<PyAny>,
    ctx: &BuildContext<'_>,
) -> PyResult<disco_layout::roles::RoleImpl> {
    let render = match ctx.agent.options.get("render") {
        None => false,
        Some(v) => v.as_bool().ok_or_else(|| {
            pyo3::exceptions::PyValueError::new_err(format!(
                "options.render must be true or false, got {v}"
            ))
        })?,
    };
    let mut options = ctx.agent.options.clone();
    options.remove("render");
    let options = crate::convert::to_python(py, &options)?;
    let callable = py
        .import("disco_layout._roles")?
        .getattr("instantiate")?
        .call1((implementation.bind(py), options))?
        .unbind();
    let transport = PyTransport {
        callable: Arc::new(callable),
        one_at_a_time: tokio::sync::Mutex::new(()),
    };
    let agent = ExternalAgent::new(ctx.agent_name, role, Box::new(transport), render);
    Ok(agent.into_role_impl())
}

/// Carries a request to a Python callable and its reply back.
struct PyTransport {
    callable: Arc<Py<PyAny>>,
    /// The protocol's promise: an agent's requests come one at a time.
    one_at_a_time: tokio::sync::Mutex<()>,
}

/// Abandons the call (`disco_layout._roles.Call`) when the supervisor drops it before it
/// finished: `RoleTimeout` is raised inside the Python code still running it.
struct AbandonGuard {
    call: Py<PyAny>,
    armed: bool,
}

impl Drop for AbandonGuard {
    fn drop(&mut self) {
        if !self.armed {
            return;
        }
        Python::attach(|py| {
            let abandoned = py
                .import("disco_layout._roles")
                .and_then(|m| m.getattr("abandon")?.call1((self.call.bind(py),)).map(drop));
            if let Err(e) = abandoned {
                e.print(py);
            }
        });
    }
}

#[async_trait]
impl Transport for PyTransport {
    async fn exchange(&self, line: String) -> Result<String, RoleError> {
        let _turn = self.one_at_a_time.lock().await;
        let failed = |e: PyErr| RoleError::Failed(format!("the Python role failed: {e}"));
        let call = Python::attach(|py| -> PyResult<Py<PyAny>> {
            Ok(py
                .import("disco_layout._roles")?
                .getattr("Call")?
                .call0()?
                .unbind())
        })
        .map_err(failed)?;
        let mut guard = AbandonGuard {
            call: Python::attach(|py| call.clone_ref(py)),
            armed: true,
        };
        let callable = Arc::clone(&self.callable);
        let running = tokio::task::spawn_blocking(move || {
            Python::attach(|py| -> PyResult<Option<String>> {
                py.import("disco_layout._roles")?
                    .getattr("run")?
                    .call1((call.bind(py), callable.bind(py), line))?
                    .extract()
            })
        });
        let outcome = running.await;
        guard.armed = false;
        match outcome {
            Ok(Ok(Some(reply))) => Ok(reply),
            Ok(Ok(None)) => Err(RoleError::Failed("the call was abandoned".into())),
            Ok(Err(e)) => Err(failed(e)),
            Err(e) => Err(RoleError::Panicked(e.to_string())),
        }
    }

    async fn discard(&self) {}
}
