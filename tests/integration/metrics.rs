//! `disco metrics`: a layout is measured only against its own scene.

use crate::harness::{GOOD, disco, stderr, write};

#[test]
fn metrics_refuses_a_layout_from_another_scene() {
    let dir = tempfile::tempdir().unwrap();
    let scene = write(dir.path(), "scene.json", GOOD);
    let layout = write(
        dir.path(),
        "layout.json",
        r#"{"id": "x", "room": {"width": 400, "depth": 350}, "objects": [{"name": "sofa-0", "category": "sofa", "size": [200, 90, 80], "position": [200, 100], "rotation": 0}]}"#,
    );
    let o = disco(&["metrics", &scene, &layout]);
    assert_eq!(o.status.code(), Some(1));
    assert!(
        stderr(&o).contains("object \"sofa-0\" is not an asset of scene"),
        "{}",
        stderr(&o)
    );
}
