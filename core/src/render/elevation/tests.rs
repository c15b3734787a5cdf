use super::*;
use crate::layout::Stats;
use crate::plan::Plan;
use crate::render::GROUP_COLOURS;
use crate::room::{Door, Window};
use crate::scene::Room;

/// A 400 x 300 bedroom: the bed and a nightstand against the top wall (wall 2), a lamp on the
/// nightstand, a painting at 150 cm on the right wall (wall 1), which also has a window (sill
/// 90 cm, from y = 200 to 280); a door in the left wall. Each of bed, lamp and painting has a
/// group (so a colour) of its own.
fn bedroom() -> Layout {
    let mut room = Room::rect(400.0, 300.0);
    room.windows.push(Window {
        wall: 1,
        at: 240.0,
        width: 80.0,
        sill: 90.0,
        height: 120.0,
    });
    room.doors.push(Door::new(3, 80.0, 90.0));
    let plan = Plan {
        groups: vec![
            vec!["bed-0".into(), "nightstand-0".into()],
            vec!["painting-0".into()],
            vec!["lamp-0".into()],
        ],
        ..Plan::default()
    };
    let object = |name: &str, size: [f64; 3], position: [f64; 2], rotation: f64| PlacedObject {
        name: name.into(),
        category: name.trim_end_matches("-0").into(),
        size,
        position,
        rotation,
        ..Default::default()
    };
    Layout {
        id: "walls-test".into(),
        room,
        objects: vec![
            object("bed-0", [160.0, 200.0, 50.0], [200.0, 200.0], 180.0),
            object("nightstand-0", [50.0, 40.0, 55.0], [90.0, 280.0], 180.0),
            PlacedObject {
                elevation: 55.0,
                on: Some("nightstand-0".into()),
                ..object("lamp-0", [30.0, 30.0, 45.0], [90.0, 280.0], 180.0)
            },
            PlacedObject {
                elevation: 150.0,
                wall: Some(1),
                ..object("painting-0", [80.0, 4.0, 60.0], [398.0, 150.0], 270.0)
            },
            object("rug-0", [200.0, 140.0, 1.0], [200.0, 120.0], 0.0),
        ],
        dropped: vec![],
        plan: plan.into(),
        stats: Stats::default(),
    }
}

fn pixel(p: &Pixmap, at: DVec2) -> [u8; 3] {
    let c = p
        .pixel(at.x as u32, at.y as u32)
        .expect("inside the sheet")
        .demultiply();
    [c.red(), c.green(), c.blue()]
}

/// Writes `p` to `$DISCO_RENDER_DUMP/name` when that variable is set (to look at it).
fn dump(p: &Pixmap, name: &str) {
    if let Ok(dir) = std::env::var("DISCO_RENDER_DUMP") {
        std::fs::write(
            format!("{dir}/{name}"),
            super::super::encode_png(p).unwrap(),
        )
        .unwrap();
    }
}

/// How many pixels of `rgb` lie on `strip` (the wall, from the floor to `height` cm).
fn count_on_strip(p: &Pixmap, strip: &Strip, height: f64, rgb: [u8; 3]) -> usize {
    let (tl, br) = (strip.to_px(strip.length, height), strip.to_px(0.0, 0.0));
    let mut n = 0;
    for y in tl.y.ceil() as u32..br.y.floor() as u32 {
        for x in tl.x.ceil() as u32..br.x.floor() as u32 {
            if pixel(p, DVec2::new(f64::from(x), f64::from(y))) == rgb {
                n += 1;
            }
        }
    }
    n
}

#[test]
fn a_painting_hangs_at_its_height_on_its_own_wall_only() {
    let l = bedroom();
    let p = render_walls(&l, &ElevationOptions::default()).unwrap();
    dump(&p, "walls-bedroom.png");
    let g = sheet_geometry(&l, &ElevationOptions::default());
    assert_eq!((p.width(), p.height()), (g.width, g.height));
    assert_eq!(g.strips.len(), 4);
    assert_eq!(g.room_height, ROOM_HEIGHT_CM);
    let painting = GROUP_COLOURS[1];
    let wall1 = &g.strips[1];
    // The painting spans y = 110..190 on wall 1 (along = y there), from 150 to 210 cm. Off its
    // centre (where its name is written): its colour inside, the wall's face just outside.
    assert_eq!(pixel(&p, wall1.to_px(125.0, 160.0)), painting);
    assert_eq!(pixel(&p, wall1.to_px(175.0, 203.0)), painting);
    assert_eq!(pixel(&p, wall1.to_px(125.0, 144.0)), WALL_FACE);
    assert_eq!(pixel(&p, wall1.to_px(125.0, 216.0)), WALL_FACE);
    assert_eq!(pixel(&p, wall1.to_px(100.0, 160.0)), WALL_FACE);
    // Drawn on wall 1 and nowhere else.
    let on_each: Vec<usize> = g
        .strips
        .iter()
        .map(|s| count_on_strip(&p, s, g.room_height, painting))
        .collect();
    assert!(on_each[1] > 500, "{on_each:?}");
    assert_eq!(on_each[0] + on_each[2] + on_each[3], 0, "{on_each:?}");
    let names = |i: usize| -> Vec<&str> {
        seen_on_wall(&l, i)
            .iter()
            .map(|s| s.object.name.as_str())
            .collect()
    };
    assert_eq!(names(1), ["painting-0"]);
    assert!(names(0).is_empty() && names(3).is_empty());
}

#[test]
fn a_window_is_glass_from_sill_to_top_and_a_door_an_opening() {
    let l = bedroom();
    let p = render_walls(&l, &ElevationOptions::default()).unwrap();
    let g = sheet_geometry(&l, &ElevationOptions::default());
    let wall1 = &g.strips[1];
    // The window: y = 200..280 (along wall 1), sill 90, top 210; its mullion at 240.
    assert_eq!(pixel(&p, wall1.to_px(220.0, 120.0)), WINDOW_GLASS);
    assert_eq!(pixel(&p, wall1.to_px(260.0, 180.0)), WINDOW_GLASS);
    assert_eq!(pixel(&p, wall1.to_px(220.0, 80.0)), WALL_FACE);
    assert_eq!(pixel(&p, wall1.to_px(220.0, 220.0)), WALL_FACE);
    // The door on wall 3 (from (0, 300) down to the origin): along 35..125, up to 210 cm.
    let wall3 = &g.strips[3];
    assert_eq!(pixel(&p, wall3.to_px(50.0, 100.0)), DOOR_OPENING);
    assert_eq!(pixel(&p, wall3.to_px(50.0, 225.0)), WALL_FACE);
    assert_eq!(pixel(&p, wall3.to_px(200.0, 120.0)), WALL_FACE);
}

#[test]
fn pieces_against_a_wall_stand_on_the_floor_and_a_lamp_on_its_nightstand() {
    let l = bedroom();
    let p = render_walls(
        &l,
        &ElevationOptions {
            labels: false,
            ..ElevationOptions::default()
        },
    )
    .unwrap();
    let g = sheet_geometry(&l, &ElevationOptions::default());
    let wall2 = &g.strips[2];
    // Wall 2 runs from (400, 300) to (0, 300): x = 400 - along. Seen from inside, its start is
    // on the right: the nightstand (x = 65..115) is near the left end of the strip.
    let nightstand = wall2.to_px(400.0 - 90.0, 30.0);
    assert!(nightstand.x < wall2.to_px(200.0, 0.0).x);
    let bed = GROUP_COLOURS[0];
    assert_eq!(
        pixel(&p, nightstand),
        bed,
        "the nightstand shares the bed's group"
    );
    assert_eq!(pixel(&p, wall2.to_px(200.0, 25.0)), bed);
    assert_eq!(
        pixel(&p, wall2.to_px(200.0, 60.0)),
        WALL_FACE,
        "above the bed"
    );
    // The lamp (x = 75..105) on the nightstand's top, from 55 to 100 cm.
    assert_eq!(pixel(&p, wall2.to_px(400.0 - 90.0, 75.0)), GROUP_COLOURS[2]);
    assert_eq!(pixel(&p, wall2.to_px(400.0 - 90.0, 106.0)), WALL_FACE);
    let names: Vec<&str> = seen_on_wall(&l, 2)
        .iter()
        .map(|s| s.object.name.as_str())
        .collect();
    // Nearest the wall first; the rug (a floor covering) is not drawn.
    assert_eq!(names, ["nightstand-0", "lamp-0", "bed-0"]);
    let lamp = seen_on_wall(&l, 2)[1];
    assert_eq!(lamp.z, (55.0, 100.0));
    assert_eq!(lamp.along, (295.0, 325.0));
}

#[test]
fn a_floor_only_layout_and_a_polygon_room_still_render() {
    let mut l = bedroom();
    l.objects.clear();
    assert!(!has_objects_off_the_floor(&l));
    let p = render_walls(&l, &ElevationOptions::default()).unwrap();
    let g = sheet_geometry(&l, &ElevationOptions::default());
    for s in &g.strips {
        assert!(seen_on_wall(&l, s.wall).is_empty());
        assert_eq!(pixel(&p, s.to_px(s.length * 0.8, 40.0)), WALL_FACE);
    }
    // An L-shaped room: six walls in three rows of two, every strip at one scale.
    l.room = Room::from_polygon(vec![
        [0.0, 0.0],
        [400.0, 0.0],
        [400.0, 200.0],
        [250.0, 200.0],
        [250.0, 300.0],
        [0.0, 300.0],
    ]);
    let g = sheet_geometry(&l, &ElevationOptions::default());
    assert_eq!(g.strips.len(), 6);
    assert!(g.strips.windows(2).all(|w| w[0].scale == w[1].scale));
    assert_eq!(g.strips[0].start_px.y, g.strips[1].start_px.y);
    assert!(g.strips[2].start_px.y > g.strips[0].start_px.y);
    let p = render_walls(&l, &ElevationOptions::default()).unwrap();
    dump(&p, "walls-l-shaped-empty.png");
    assert_eq!(pixel(&p, g.strips[5].to_px(100.0, 40.0)), WALL_FACE);
}

#[test]
fn a_tall_piece_raises_the_room_and_a_chain_that_loops_does_not_hang() {
    let mut l = bedroom();
    assert!(has_objects_off_the_floor(&l));
    l.objects[1].size[2] = 290.0;
    let g = sheet_geometry(&l, &ElevationOptions::default());
    assert_eq!(g.room_height, 290.0 + HEADROOM_CM);
    // A lamp and a nightstand each on the other (a file refuses it; a picture must not loop).
    l.objects[1].on = Some("lamp-0".into());
    let seen = seen_on_wall(&l, 2);
    assert!(seen.iter().any(|s| s.object.name == "bed-0"));
    render_walls(&l, &ElevationOptions::default()).unwrap();
}

#[test]
fn a_room_of_many_short_walls_gets_a_sheet_of_bounded_size() {
    // A round room: 256 walls about 5 cm long, in four columns of 64 rows.
    let mut l = bedroom();
    l.objects.clear();
    let n = 256;
    let points: Vec<[f64; 2]> = (0..n)
        .map(|i| {
            let a = std::f64::consts::TAU * f64::from(i) / f64::from(n);
            [200.0 + 200.0 * a.cos(), 200.0 + 200.0 * a.sin()]
        })
        .collect();
    l.room = Room::from_polygon(points);
    l.room.doors.clear();
    l.room.windows.clear();
    let g = sheet_geometry(&l, &ElevationOptions::default());
    assert_eq!(g.strips.len(), 256);
    assert!(
        g.height <= 16384 && g.width <= 1280,
        "{} x {}",
        g.width,
        g.height
    );
    assert_eq!(
        g.strips[3].start_px.y, g.strips[0].start_px.y,
        "four to a row"
    );
    assert!(g.strips[4].start_px.y > g.strips[0].start_px.y);
    let p = render_walls(&l, &ElevationOptions::default()).unwrap();
    assert_eq!((p.width(), p.height()), (g.width, g.height));
}
