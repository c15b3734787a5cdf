//! `disco render`: a layout to draw must have complete objects.

use crate::harness::{disco, stderr, write};

#[test]
fn render_needs_complete_objects() {
    let dir = tempfile::tempdir().unwrap();
    let layout = write(
        dir.path(),
        "layout.json",
        r#"{"id": "x", "room": {"width": 400, "depth": 350}, "objects": [{"name": "a", "category": "box", "position": [1, 2], "rotation": 0}]}"#,
    );
    let o = disco(&[
        "render",
        &layout,
        "-o",
        dir.path().join("x.png").to_str().unwrap(),
    ]);
    assert_eq!(o.status.code(), Some(1));
    assert!(
        stderr(&o).contains("layout.json: objects[0]: missing field `size`"),
        "{}",
        stderr(&o)
    );
}
