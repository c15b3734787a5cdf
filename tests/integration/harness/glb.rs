//! The glTF checker: the Khronos validator and three.js, run by node (`scripts/glb-check`).

use std::path::Path;
use std::process::Command;

use serde_json::Value;

use super::{stderr, stdout};

/// Checks a .glb with the Khronos validator and three.js (`scripts/glb-check`, from npm).
pub fn check_glb(path: &Path) -> Value {
    let script = Path::new(env!("CARGO_MANIFEST_DIR")).join("scripts/glb-check/check");
    let o = Command::new(script).arg(path).output().expect("node runs");
    assert!(o.status.success(), "glb check: {}", stderr(&o));
    serde_json::from_str(stdout(&o).trim()).unwrap()
}
