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
            },
            PlacedObject {
                name: "desk-0".into(),
                category: "desk".into(),
                size: [120.0, 60.0, 75.0],
                position: [340.0, 100.0],
                rotation: 270.0,
            },
        ],
        dropped: vec![],
        plan,
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
    let inside_front = view.to_px(DVec2::new(200.0, 100.0)) + DVec2::new(0.0, -4.0);
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
    // openings must keep every pixel.
    let p = render(&sample(), &RenderOptions::default()).unwrap();
    assert_eq!(fingerprint(&p), 0xa102_fe6e_5c59_8b8f, "{:#x}", fingerprint(&p));
}
