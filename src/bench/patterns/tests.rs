//! Each predicate on a hand-made layout that builds its pattern and on one that does not.

use super::predicates::*;
use super::*;
use crate::scene::Room;

fn o(name: &str, w: f64, d: f64, x: f64, y: f64, rotation: f64) -> PlacedObject {
    PlacedObject {
        name: name.into(),
        category: name.into(),
        size: [w, d, 80.0],
        position: [x, y],
        rotation,
        ..Default::default()
    }
}

fn room() -> Room {
    Room::rect(600.0, 500.0)
}

fn refs(v: &[PlacedObject]) -> Vec<&PlacedObject> {
    v.iter().collect()
}

/// A board on the top wall facing down.
fn board() -> PlacedObject {
    o("board", 240.0, 10.0, 300.0, 495.0, 180.0)
}

#[test]
fn rows_two_rows_of_desks_with_seats_facing_the_board() {
    let mut desks = Vec::new();
    let mut seats = Vec::new();
    for (i, (x, y)) in [
        (200.0, 380.0),
        (300.0, 380.0),
        (200.0, 260.0),
        (300.0, 260.0),
    ]
    .into_iter()
    .enumerate()
    {
        // Desk fronts (the sitter's side) point away from the board; seats face it.
        desks.push(o(&format!("d{i}"), 70.0, 50.0, x, y, 180.0));
        seats.push(o(&format!("s{i}"), 40.0, 40.0, x, y - 50.0, 0.0));
    }
    assert_eq!(rows(&board(), &refs(&desks), &refs(&seats)), Ok(()));
    // Seats turned away from the board.
    let away: Vec<PlacedObject> = seats
        .iter()
        .map(|s| PlacedObject {
            rotation: 180.0,
            ..s.clone()
        })
        .collect();
    assert!(rows(&board(), &refs(&desks), &refs(&away)).is_err());
    // All desks in one row.
    let one_row: Vec<PlacedObject> = desks
        .iter()
        .map(|d| PlacedObject {
            position: [
                d.position[0] + 200.0 * f64::from(d.position[1] < 300.0),
                380.0,
            ],
            ..d.clone()
        })
        .collect();
    assert!(rows(&board(), &refs(&one_row), &refs(&seats)).is_err());
}

#[test]
fn u_three_runs_open_to_the_board() {
    let desks = vec![
        o("l0", 120.0, 50.0, 150.0, 350.0, 90.0),
        o("l1", 120.0, 50.0, 150.0, 230.0, 90.0),
        o("r0", 120.0, 50.0, 450.0, 350.0, 270.0),
        o("r1", 120.0, 50.0, 450.0, 230.0, 270.0),
        o("b0", 120.0, 50.0, 300.0, 150.0, 0.0),
    ];
    // Seats outside the U, facing in.
    let seats = vec![
        o("sl", 45.0, 45.0, 100.0, 350.0, 90.0),
        o("sr", 45.0, 45.0, 500.0, 350.0, 270.0),
        o("sb", 45.0, 45.0, 300.0, 100.0, 0.0),
    ];
    assert_eq!(u_shape(&board(), &refs(&desks), &refs(&seats)), Ok(()));
    // A desk in the middle of the U.
    let mut inside = desks.clone();
    inside.push(o("mid", 120.0, 50.0, 300.0, 300.0, 0.0));
    assert!(u_shape(&board(), &refs(&inside), &refs(&seats)).is_err());
    // Seats with their backs to the U and the board.
    let backs = vec![o("sb", 45.0, 45.0, 300.0, 100.0, 180.0)];
    assert!(u_shape(&board(), &refs(&desks), &refs(&backs)).is_err());
}

#[test]
fn l_galley_and_one_wall_runs() {
    let r = room();
    // Bottom wall from the left corner, then the left wall from above the first piece.
    let l = vec![
        o("a", 100.0, 60.0, 50.0, 30.0, 0.0),
        o("b", 80.0, 60.0, 140.0, 30.0, 0.0),
        o("c", 80.0, 60.0, 30.0, 100.0, 90.0),
        o("d", 80.0, 60.0, 30.0, 180.0, 90.0),
    ];
    assert_eq!(l_shape(&r, &refs(&l)), Ok(()));
    assert!(galley(&r, &refs(&l)).is_err());
    assert!(one_wall(&r, &refs(&l)).is_err());
    // The same pieces with the left run pushed far from the corner.
    let far: Vec<PlacedObject> = l
        .iter()
        .map(|p| {
            if p.rotation == 90.0 {
                PlacedObject {
                    position: [30.0, p.position[1] + 250.0],
                    ..p.clone()
                }
            } else {
                p.clone()
            }
        })
        .collect();
    assert!(l_shape(&r, &refs(&far)).is_err());
    let g = vec![
        o("a", 100.0, 60.0, 100.0, 30.0, 0.0),
        o("b", 100.0, 60.0, 200.0, 30.0, 0.0),
        o("c", 100.0, 60.0, 120.0, 470.0, 180.0),
        o("d", 100.0, 60.0, 220.0, 470.0, 180.0),
    ];
    assert_eq!(galley(&r, &refs(&g)), Ok(()));
    assert!(l_shape(&r, &refs(&g)).is_err());
    let one = vec![
        o("a", 100.0, 60.0, 100.0, 30.0, 0.0),
        o("b", 100.0, 60.0, 200.0, 30.0, 0.0),
        o("c", 60.0, 60.0, 280.0, 30.0, 0.0),
    ];
    assert_eq!(one_wall(&r, &refs(&one)), Ok(()));
    let gappy = vec![one[0].clone(), o("c", 60.0, 60.0, 400.0, 30.0, 0.0)];
    assert!(one_wall(&r, &refs(&gappy)).is_err());
    // Off the wall by 5 cm: not a run on the wall at all.
    let off = vec![o("a", 100.0, 60.0, 100.0, 35.0, 0.0)];
    assert!(all_on_walls(&r, &refs(&off)).is_err());
}

#[test]
fn work_zone_pair_side_by_side_and_a_tight_triangle() {
    let r = room();
    let sink = o("sink", 80.0, 60.0, 200.0, 30.0, 0.0);
    let dw = o("dw", 60.0, 60.0, 270.0, 30.0, 0.0);
    let fridge = o("fridge", 80.0, 70.0, 40.0, 35.0, 0.0);
    let stove = o("stove", 60.0, 60.0, 30.0, 200.0, 90.0);
    assert_eq!(
        work_zone(&r, &[&sink, &dw], &[&fridge, &stove, &sink]),
        Ok(())
    );
    let far_dw = o("dw", 60.0, 60.0, 500.0, 30.0, 0.0);
    assert!(work_zone(&r, &[&sink, &far_dw], &[]).is_err());
    let far_stove = o("stove", 60.0, 60.0, 570.0, 400.0, 270.0);
    assert!(work_zone(&r, &[&sink, &dw], &[&fridge, &far_stove, &sink]).is_err());
}

#[test]
fn island_and_around_need_seats_at_and_facing_the_piece() {
    let r = room();
    let island_piece = o("island", 200.0, 100.0, 300.0, 250.0, 0.0);
    let stools = vec![
        o("s0", 40.0, 40.0, 250.0, 180.0, 0.0),
        o("s1", 40.0, 40.0, 350.0, 180.0, 0.0),
    ];
    assert_eq!(island(&r, &island_piece, &refs(&stools)), Ok(()));
    // Against the wall it is no island.
    let walled = o("island", 200.0, 100.0, 300.0, 50.0, 0.0);
    assert!(island(&r, &walled, &[]).is_err());
    // Stools on one side pass the island test but not "around".
    assert!(around(&island_piece, &refs(&stools)).is_err());
    let both = vec![stools[0].clone(), o("s2", 40.0, 40.0, 300.0, 320.0, 180.0)];
    assert_eq!(around(&island_piece, &refs(&both)), Ok(()));
    let turned = vec![o("s0", 40.0, 40.0, 250.0, 180.0, 90.0)];
    assert!(island(&r, &island_piece, &refs(&turned)).is_err());
}

#[test]
fn corner_and_centred() {
    let r = room();
    assert_eq!(
        corner(&r, &o("t", 160.0, 90.0, 90.0, 460.0, 0.0), 30.0),
        Ok(())
    );
    assert!(corner(&r, &o("t", 160.0, 90.0, 300.0, 460.0, 0.0), 30.0).is_err());
    assert_eq!(
        centred(&r, &o("tub", 170.0, 80.0, 310.0, 240.0, 0.0)),
        Ok(())
    );
    assert!(centred(&r, &o("tub", 170.0, 80.0, 310.0, 40.0, 0.0)).is_err());
    assert!(centred(&r, &o("tub", 170.0, 80.0, 120.0, 250.0, 0.0)).is_err());
}

#[test]
fn symmetric_pair_mirrored_about_the_bed() {
    let bed = o("bed", 160.0, 210.0, 300.0, 105.0, 0.0);
    let a = o("n0", 50.0, 40.0, 190.0, 20.0, 0.0);
    let b = o("n1", 50.0, 40.0, 410.0, 20.0, 0.0);
    assert_eq!(symmetric_pair(&bed, &[&a, &b]), Ok(()));
    let same_side = o("n1", 50.0, 40.0, 140.0, 20.0, 0.0);
    assert!(symmetric_pair(&bed, &[&a, &same_side]).is_err());
    let uneven = o("n1", 50.0, 40.0, 430.0, 20.0, 0.0);
    assert!(symmetric_pair(&bed, &[&a, &uneven]).is_err());
}

#[test]
fn conversation_seats_face_the_focus_and_the_screen_is_seen() {
    let sofa = o("sofa", 220.0, 95.0, 300.0, 48.0, 0.0);
    let table = PlacedObject {
        size: [110.0, 60.0, 45.0],
        ..o("table", 110.0, 60.0, 300.0, 180.0, 0.0)
    };
    let arm = o("arm", 85.0, 85.0, 300.0, 320.0, 180.0);
    let tv = o("tv", 180.0, 45.0, 300.0, 478.0, 180.0);
    let mut layout = Layout {
        id: "t".into(),
        room: room(),
        objects: vec![sofa.clone(), table.clone(), tv.clone()],
        dropped: Vec::new(),
        plan: Default::default(),
        stats: Default::default(),
    };
    assert_eq!(conversation(&layout, &tv, &[&sofa], Some(&tv)), Ok(()));
    assert_eq!(conversation(&layout, &table, &[&sofa, &arm], None), Ok(()));
    // The armchair between the sofa and the TV blocks the screen.
    layout.objects.push(arm.clone());
    assert!(conversation(&layout, &tv, &[&sofa], Some(&tv)).is_err());
    // Two seats side by side facing the same way do not converse.
    let beside = o("arm", 85.0, 85.0, 480.0, 48.0, 0.0);
    assert!(conversation(&layout, &table, &[&sofa, &beside], None).is_err());
}

#[test]
fn expectations_load_and_check_names_a_missing_object() {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("bench/patterns");
    let all = load_expectations(&dir.join("expect.toml")).unwrap();
    assert!(all.len() >= 30, "{} scenes", all.len());
    let e = &all["centred-spa"];
    assert_eq!(e.pattern, Pattern::Centred);
    assert_eq!(e.on_wall.len(), 3);
    let layout = Layout {
        id: "centred-spa".into(),
        room: room(),
        objects: vec![o("bathtub-0", 170.0, 80.0, 300.0, 250.0, 0.0)],
        dropped: Vec::new(),
        plan: Default::default(),
        stats: Default::default(),
    };
    let v = check(&layout, e);
    assert!(!v.met && v.why.contains("not placed"), "{v:?}");
}
