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

#[test]
fn render_walls_draws_the_elevation_sheet() {
    let dir = tempfile::tempdir().unwrap();
    let layout = write(
        dir.path(),
        "layout.json",
        r#"{"id": "x", "room": {"width": 400, "depth": 300}, "objects": [
            {"name": "dresser-0", "category": "dresser", "size": [100, 45, 80], "position": [200, 277.5], "rotation": 180},
            {"name": "lamp-0", "category": "table lamp", "size": [30, 30, 45], "position": [230, 277.5], "rotation": 180, "elevation": 80, "on": "dresser-0"},
            {"name": "painting-0", "category": "painting", "size": [80, 4, 60], "position": [398, 150], "rotation": 270, "elevation": 150, "wall": 1}]}"#,
    );
    // The PNG's width, from its header.
    let width = |png: &std::path::Path| {
        let bytes = std::fs::read(png).unwrap();
        assert_eq!(&bytes[..4], b"\x89PNG");
        u32::from_be_bytes(bytes[16..20].try_into().unwrap())
    };
    let png = dir.path().join("walls.png");
    let o = disco(&["render", &layout, "-o", png.to_str().unwrap(), "--walls"]);
    assert!(o.status.success(), "{}", stderr(&o));
    let said = crate::harness::stdout(&o);
    assert!(
        said.contains("4 walls of 3 objects drawn, 1280 x "),
        "{said}"
    );
    assert_eq!(width(&png), 1280);
    let o = disco(&[
        "render",
        &layout,
        "-o",
        png.to_str().unwrap(),
        "--walls",
        "--size",
        "900",
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    assert_eq!(width(&png), 900);
    // Without --walls the same file is the view from above, 1024 px on its long side.
    let o = disco(&["render", &layout, "-o", png.to_str().unwrap()]);
    assert!(o.status.success(), "{}", stderr(&o));
    assert_eq!(width(&png), 1024);
}
