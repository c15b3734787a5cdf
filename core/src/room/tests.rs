use std::path::Path;

use glam::DVec2;

use super::*;

fn room(json: &str) -> Room {
    serde_json::from_str(json).expect("room parses")
}

fn refusal(json: &str) -> String {
    let r: Room = match serde_json::from_str(json) {
        Ok(r) => r,
        Err(e) => return e.to_string(),
    };
    validate_room(Path::new("s.json"), "room", &r)
        .expect_err("room must be refused")
        .to_string()
}

const L_SHAPE: &str = "[[0,0],[600,0],[600,300],[350,300],[350,450],[0,450]]";

#[test]
fn a_rectangle_reads_and_writes_exactly_as_before() {
    let r = room(r#"{"width": 400, "depth": 350}"#);
    assert_eq!(r, Room::rect(400.0, 350.0));
    assert_eq!(
        serde_json::to_string(&r).unwrap(),
        r#"{"width":400.0,"depth":350.0}"#
    );
    assert_eq!(r.walls().len(), 4);
    assert_eq!(r.area(), 400.0 * 350.0);
}

#[test]
fn rectangle_walls_are_bottom_right_top_left_facing_in() {
    let r = Room::rect(400.0, 300.0);
    let rotations: Vec<f64> = r.walls().iter().map(|w| w.inward_rotation()).collect();
    // Bottom wall: front faces +y (0); right wall: faces -x (270); top: -y (180); left: +x (90).
    assert_eq!(rotations, vec![0.0, 270.0, 180.0, 90.0]);
    let bottom = r.walls()[0];
    assert_eq!(bottom.offset(DVec2::new(10.0, 25.0)), 25.0);
}

#[test]
fn an_l_shaped_polygon_has_its_bounding_box_area_and_walls() {
    let r = room(&format!(
        r#"{{"polygon": {L_SHAPE}, "doors": [{{"wall": 0, "at": 120, "width": 90}}]}}"#
    ));
    validate_room(Path::new("s.json"), "room", &r).unwrap();
    assert_eq!((r.width, r.depth), (600.0, 450.0));
    assert_eq!(r.area(), 600.0 * 300.0 + 350.0 * 150.0);
    assert_eq!(r.walls().len(), 6);
    assert!(r.contains_point(DVec2::new(100.0, 400.0), 0.0));
    assert!(!r.contains_point(DVec2::new(500.0, 400.0), 0.0));
    assert!(r.contains_point(DVec2::new(350.0, 400.0), 0.5), "on a wall");
    let text = serde_json::to_string(&r).unwrap();
    assert!(text.starts_with(r#"{"polygon":"#) && !text.contains("width\":600"));
    assert_eq!(room(&text), r, "writes what it reads");
}

#[test]
fn door_zones_reach_into_the_room_and_cover_the_sweep() {
    let mut r = Room::rect(400.0, 300.0);
    r.doors.push(Door::new(0, 100.0, 90.0));
    let zone = &r.keep_clear()[0];
    assert_eq!(zone.kind, ZoneKind::Door(0));
    let ys: Vec<f64> = zone.corners.iter().map(|c| c.y).collect();
    assert_eq!(ys, vec![0.0, 0.0, 90.0, 90.0], "a 90 cm leaf sweeps 90 cm");
    assert!(zone.applies_to(40.0) && !zone.applies_to(1.0));
    // Seen from inside, the bottom wall runs right to left: the left hinge is at the far end.
    let (hinge, _, radius) = r.door_sweep(&r.doors[0]).unwrap();
    assert_eq!((hinge, radius), (DVec2::new(145.0, 0.0), 90.0));
}

#[test]
fn windows_bind_only_objects_taller_than_the_sill() {
    let r = room(
        r#"{"width": 400, "depth": 300,
            "windows": [{"wall": 3, "at": 150, "width": 100, "sill": 90, "height": 120}]}"#,
    );
    validate_room(Path::new("s.json"), "room", &r).unwrap();
    let zone = &r.keep_clear()[0];
    assert!(zone.applies_to(180.0) && !zone.applies_to(80.0));
    let xs: Vec<f64> = zone.corners.iter().map(|c| c.x).collect();
    assert_eq!(xs, vec![0.0, 0.0, 40.0, 40.0]);
}

#[test]
fn bad_rooms_are_refused_with_field_and_reason() {
    let cases = [
        (
            r#"{"polygon": [[0,0],[400,0],[0,300],[400,300]]}"#,
            "crosses itself",
        ),
        (r#"{"polygon": [[0,0],[400,0],[800,0]]}"#, "crosses itself"),
        (
            r#"{"polygon": [[0,0],[0,300],[400,300],[400,0]]}"#,
            "clockwise",
        ),
        (
            r#"{"polygon": [[0,0],[400,0],[400,300],[0,300],[0,0]]}"#,
            "repeated",
        ),
        (
            r#"{"polygon": [[10,0],[400,0],[400,300],[10,300]]}"#,
            "lowest x and y must be 0",
        ),
        (
            r#"{"width": 400, "depth": 300, "polygon": [[0,0],[400,0],[0,300]]}"#,
            "not both",
        ),
        (
            r#"{"width": 400, "depth": 300, "doors": [{"wall": 4, "at": 100, "width": 90}]}"#,
            "no wall 4",
        ),
        (
            r#"{"width": 400, "depth": 300, "doors": [{"wall": 0, "at": 380, "width": 90}]}"#,
            "wholly on its wall",
        ),
        (
            r#"{"width": 400, "depth": 300, "doors": [{"wall": 0, "at": 100, "width": 90}],
                "windows": [{"wall": 0, "at": 160, "width": 80, "sill": 90, "height": 100}]}"#,
            "overlaps room.doors[0]",
        ),
        (
            r#"{"width": 400, "depth": 300, "doors": [{"wall": 0, "at": 100, "width": 90, "swing": "ajar"}]}"#,
            "unknown variant",
        ),
        (
            r#"{"width": 400, "depth": 70, "doors": [{"wall": 0, "at": 100, "width": 60, "swing": "out"}]}"#,
            "leaves the room",
        ),
        (
            r#"{"polygon": [[0,0],[500,0],[500,400],[440,400],[440,150],[150,150],[150,400],[0,400]],
                "doors": [{"wall": 3, "at": 100, "width": 70, "swing": "sliding"}]}"#,
            "leaves the room",
        ),
    ];
    for (json, why) in cases {
        let e = refusal(json);
        assert!(e.contains(why), "{json}: {e}");
    }
}

#[test]
fn a_door_beside_an_inner_corner_is_allowed_while_its_zone_stays_inside() {
    // Wall 3 of the L runs from the inner corner (350,300) to (350,450); a door on it opens
    // into the arm at x < 350, which is deep enough.
    let ok = room(&format!(
        r#"{{"polygon": {L_SHAPE}, "doors": [{{"wall": 3, "at": 75, "width": 80}}]}}"#
    ));
    validate_room(Path::new("s.json"), "room", &ok).unwrap();
}
