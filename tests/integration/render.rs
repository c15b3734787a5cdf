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

#[test]
fn render_creates_its_folder_and_says_what_it_wrote() {
    let dir = tempfile::tempdir().unwrap();
    let layout = write(
        dir.path(),
        "layout.json",
        r#"{"id": "x", "room": {"width": 400, "depth": 350}, "objects": [{"name": "a", "category": "box", "size": [50, 40, 30], "position": [100, 100], "rotation": 0}]}"#,
    );
    let png = dir.path().join("new/folder/x.png");
    let o = disco(&["render", &layout, "-o", png.to_str().unwrap()]);
    assert!(o.status.success(), "{}", stderr(&o));
    assert!(png.is_file());
    let said = crate::harness::stdout(&o);
    assert!(said.starts_with(&format!("{}: ", png.display())), "{said}");
    assert!(
        said.contains("1 object drawn, 1024 px on the long side"),
        "{said}"
    );
    let o = disco(&["-q", "render", &layout, "-o", png.to_str().unwrap()]);
    assert!(o.status.success() && o.stdout.is_empty(), "{}", stderr(&o));
}
