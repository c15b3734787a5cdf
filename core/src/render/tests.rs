use super::*;
use crate::layout::Stats;
use crate::plan::Plan;
use crate::scene::Room;

fn sample() -> Layout {
    let plan = Plan {
        groups: vec![vec!["bed-0".into()], vec!["desk-0".into()]],
        ..Plan::default()
    };
    Layout {
        id: "test".into(),
        room: Room::rect(400.0, 300.0),
        objects: vec![
            PlacedObject {
                name: "bed-0".into(),
                category: "bed".into(),
                size: [160.0, 200.0, 50.0],
                position: [200.0, 200.0],
                rotation: 180.0,
                ..Default::default()
            },
            PlacedObject {
                name: "desk-0".into(),
                category: "desk".into(),
                size: [120.0, 60.0, 75.0],
                position: [340.0, 100.0],
                rotation: 270.0,
                ..Default::default()
            },
        ],
        dropped: vec![],
        plan: plan.into(),
        stats: Stats::default(),
    }
}

fn pixel(p: &Pixmap, at: DVec2) -> [u8; 3] {
    let c = p
        .pixel(at.x as u32, at.y as u32)
        .expect("inside the image")
        .demultiply();
    [c.red(), c.green(), c.blue()]
}

#[test]
fn long_side_is_1024_by_default() {
    let p = render(&sample(), &RenderOptions::default()).unwrap();
    assert_eq!(p.width(), 1024);
    assert!(p.height() < 1024 && p.height() > 600, "{}", p.height());
    let mut tall = sample();
    tall.room = Room::rect(300.0, 600.0);
    assert_eq!(
        render(&tall, &RenderOptions::default()).unwrap().height(),
        1024
    );
}

#[test]
fn floor_objects_and_walls_have_their_colours() {
    let l = sample();
    let p = render(&l, &RenderOptions::default()).unwrap();
    let (_, _, view) = view_for(&l, 1024);
    assert_eq!(pixel(&p, view.to_px(DVec2::new(60.0, 60.0))), FLOOR);
    // Off the label and the arrow: a quarter of the way from the bed's centre to its corner.
    assert_eq!(
        pixel(&p, view.to_px(DVec2::new(160.0, 150.0))),
        GROUP_COLOURS[0]
    );
    assert_eq!(
        pixel(&p, view.to_px(DVec2::new(355.0, 140.0))),
        GROUP_COLOURS[1]
    );
    assert_eq!(
        pixel(
            &p,
            view.to_px(DVec2::new(200.0, 0.0)) + DVec2::new(0.0, 2.0)
        ),
        WALL
    );
    assert_eq!(pixel(&p, DVec2::new(3.0, 3.0)), BACKGROUND);
}

#[test]
fn names_are_written_on_objects() {
    let l = sample();
    let with = render(&l, &RenderOptions::default()).unwrap();
    let without = render(
        &l,
        &RenderOptions {
            labels: false,
            ..RenderOptions::default()
        },
    )
    .unwrap();
    let (_, _, view) = view_for(&l, 1024);
    let c = view.to_px(DVec2::new(200.0, 200.0));
    let mut changed = 0;
    for dy in -10..=10 {
        for dx in -40..=40 {
            let at = c + DVec2::new(f64::from(dx), f64::from(dy));
            if pixel(&with, at) != pixel(&without, at) {
                changed += 1;
            }
        }
    }
    assert!(changed > 100, "only {changed} label pixels");
}

#[test]
fn front_marker_is_white_at_the_front_edge() {
    let l = sample();
    let p = render(&l, &RenderOptions::default()).unwrap();
    let (_, _, view) = view_for(&l, 1024);
    // The bed faces down (180°): its front edge is at y = 100; the arrow sits just inside it.
    let inside_front = view.to_px(DVec2::new(200.0, 100.0)) + DVec2::new(0.0, -8.0);
    assert_eq!(pixel(&p, inside_front), [255, 255, 255]);
    let inside_back = view.to_px(DVec2::new(200.0, 300.0)) + DVec2::new(0.0, 12.0);
    assert_eq!(pixel(&p, inside_back), GROUP_COLOURS[0]);
}

#[test]
fn png_round_trips() {
    let png = render_png(&sample(), &RenderOptions::default()).unwrap();
    let back = Pixmap::decode_png(&png).unwrap();
    assert_eq!(back.width(), 1024);
}

/// FNV-1a over the pixels: a fingerprint of a whole picture.
fn fingerprint(p: &Pixmap) -> u64 {
    p.data().iter().fold(0xcbf2_9ce4_8422_2325, |h, b| {
        (h ^ u64::from(*b)).wrapping_mul(0x0100_0000_01b3)
    })
}

#[test]
fn a_plain_rectangle_renders_exactly_as_before_rooms_had_outlines() {
    // Taken from the renderer before polygons, doors and windows existed: a rectangle without
    // openings must keep every pixel. (Retaken in session 12 when the front arrowheads were
    // made narrower, so they read as pointing out of the front edge at free angles.)
    let p = render(&sample(), &RenderOptions::default()).unwrap();
    assert_eq!(
        fingerprint(&p),
        0xfed0_1af9_e183_b1f4,
        "{:#x}",
        fingerprint(&p)
    );
}

/// An L-shaped room (the top-right corner cut away) with a door that swings in on wall 0, a
/// sliding door on wall 5 and a window on wall 1; the sample's desk in it.
fn l_shaped() -> Layout {
    use crate::room::{Door, Hinge, Swing, Window};
    let mut room = Room::from_polygon(vec![
        [0.0, 0.0],
        [400.0, 0.0],
        [400.0, 200.0],
        [250.0, 200.0],
        [250.0, 300.0],
        [0.0, 300.0],
    ]);
    room.doors.push(Door::new(0, 100.0, 90.0));
    room.doors.push(Door {
        wall: 5,
        at: 150.0,
        width: 80.0,
        swing: Swing::Sliding,
        hinge: Hinge::Left,
    });
    room.windows.push(Window {
        wall: 1,
        at: 100.0,
        width: 120.0,
        sill: 90.0,
        height: 120.0,
    });
    let mut l = sample();
    l.room = room;
    l.objects.retain(|o| o.name == "desk-0");
    l
}

#[test]
fn a_polygon_room_shows_its_outline_openings_and_wall_numbers() {
    let l = l_shaped();
    let p = render(&l, &RenderOptions::default()).unwrap();
    if let Ok(dir) = std::env::var("DISCO_RENDER_DUMP") {
        std::fs::write(format!("{dir}/l-shaped.png"), encode_png(&p).unwrap()).unwrap();
    }
    let (_, _, view) = view_for(&l, 1024);
    // Floor inside the outline; the cut-away corner is hatched "not floor".
    assert_eq!(pixel(&p, view.to_px(DVec2::new(60.0, 250.0))), FLOOR);
    let notch: Vec<[u8; 3]> = (0..12)
        .map(|i| pixel(&p, view.to_px(DVec2::new(330.0 + f64::from(i), 260.0))))
        .collect();
    assert!(notch.contains(&NOT_FLOOR), "{notch:?}");
    assert!(!notch.contains(&FLOOR), "{notch:?}");
    // Wall 0 is white beside the door and floor-coloured across the door's gap.
    let below = DVec2::new(0.0, 2.0);
    assert_eq!(pixel(&p, view.to_px(DVec2::new(250.0, 0.0)) + below), WALL);
    assert_eq!(pixel(&p, view.to_px(DVec2::new(80.0, 0.0)) + below), FLOOR);
    // The door (hinge left seen from inside: at x = 145) stands open into the room.
    assert_eq!(pixel(&p, view.to_px(DVec2::new(145.0, 45.0))), DOOR_LEAF);
    // The window is glass in wall 1 (x = 400, y from 40 to 160).
    let right = DVec2::new(3.0, 0.0);
    assert_eq!(
        pixel(&p, view.to_px(DVec2::new(400.0, 70.0)) + right),
        WINDOW_GLASS
    );
    assert_eq!(
        pixel(&p, view.to_px(DVec2::new(400.0, 180.0)) + right),
        WALL
    );
    // The wall badges: wall 2 (the top of the short arm) has one at its middle.
    let badge = view.to_px(DVec2::new(325.0, 200.0)) + DVec2::new(-4.0, 0.0);
    assert_eq!(pixel(&p, badge), BACKGROUND);
    // A rectangle with openings gets them too, but no badges.
    let mut rect = l.clone();
    rect.room.polygon = None;
    rect.room.doors.truncate(1);
    let p = render(&rect, &RenderOptions::default()).unwrap();
    assert_eq!(pixel(&p, view.to_px(DVec2::new(80.0, 0.0)) + below), FLOOR);
    assert_eq!(pixel(&p, view.to_px(DVec2::new(200.0, 0.0)) + below), WALL);
}

#[test]
fn an_object_on_another_is_drawn_above_it_with_a_white_dashed_edge() {
    let mut l = sample();
    // A 40 x 30 lamp on the desk, listed before it and in another group (colour).
    let lamp = PlacedObject {
        name: "lamp-0".into(),
        category: "lamp".into(),
        size: [40.0, 30.0, 45.0],
        position: [340.0, 100.0],
        rotation: 270.0,
        elevation: 75.0,
        on: Some("desk-0".into()),
        ..Default::default()
    };
    l.objects.insert(0, lamp);
    let plan = Plan {
        groups: vec![vec!["bed-0".into(), "lamp-0".into()], vec!["desk-0".into()]],
        ..Plan::default()
    };
    l.plan = plan.into();
    let p = render(
        &l,
        &RenderOptions {
            labels: false,
            ..RenderOptions::default()
        },
    )
    .unwrap();
    let (_, _, view) = view_for(&l, 1024);
    // Inside the lamp, off its arrow (it faces -x): its colour, not the desk's.
    assert_eq!(
        pixel(&p, view.to_px(DVec2::new(345.0, 108.0))),
        GROUP_COLOURS[0]
    );
    // The desk around it keeps the desk's colour.
    assert_eq!(
        pixel(&p, view.to_px(DVec2::new(355.0, 140.0))),
        GROUP_COLOURS[1]
    );
    // The lamp's back edge (at x = 355) is drawn white and dashed: some pixels along it are white.
    let white = (0..40)
        .filter(|k| {
            let at = view.to_px(DVec2::new(355.0, 85.0 + f64::from(*k) * 0.75));
            pixel(&p, at) == WHITE
        })
        .count();
    assert!(white > 5, "{white}");
}
