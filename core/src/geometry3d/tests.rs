//! The 3D predicates on a bedroom with a door, a window, a nightstand and things on it or on walls.

use super::*;
use crate::room::{Door, Window};

fn room() -> Room {
    let mut room = Room::rect(400.0, 300.0);
    room.doors.push(Door::new(0, 100.0, 90.0));
    room.windows.push(Window {
        wall: 2,
        at: 200.0,
        width: 100.0,
        sill: 90.0,
        height: 120.0,
    });
    room
}

fn object(name: &str, category: &str, size: [f64; 3], at: [f64; 2], rotation: f64) -> PlacedObject {
    PlacedObject {
        name: name.into(),
        category: category.into(),
        size,
        position: at,
        rotation,
        ..Default::default()
    }
}

fn nightstand() -> PlacedObject {
    object(
        "nightstand-0",
        "nightstand",
        [45.0, 40.0, 55.0],
        [30.0, 20.0],
        0.0,
    )
}

fn lamp(at: [f64; 2], elevation: f64, on: &str) -> PlacedObject {
    PlacedObject {
        elevation,
        on: Some(on.into()),
        ..object("lamp-0", "table lamp", [25.0, 25.0, 45.0], at, 0.0)
    }
}

/// A painting 80 cm wide and 4 deep on wall `wall` of the 400 x 300 room, centred `along` it.
fn painting(wall: usize, along: f64, elevation: f64) -> PlacedObject {
    let w = Wall::get(&room(), wall).unwrap();
    let back = w.edge.start + w.direction() * along;
    let centre = back + w.inward_normal() * 2.0;
    PlacedObject {
        elevation,
        wall: Some(wall),
        ..object(
            "painting-0",
            "painting",
            [80.0, 4.0, 60.0],
            [centre.x, centre.y],
            w.inward_rotation(),
        )
    }
}

#[test]
fn a_lamp_on_its_nightstand_stands_and_does_not_collide_with_it() {
    let (n, l) = (nightstand(), lamp([30.0, 20.0], 55.0, "nightstand-0"));
    assert!(!collide(&n, &l));
    assert_eq!(surface_problem(&l, &n), None);
    assert!(unsupported(&[n.clone(), l.clone()], &room()).is_empty());
    // The same lamp on the floor at the nightstand's place collides with it.
    let on_floor = object(
        "lamp-0",
        "table lamp",
        [25.0, 25.0, 45.0],
        [30.0, 20.0],
        0.0,
    );
    assert!(collide(&n, &on_floor));
}

#[test]
fn a_lamp_below_beside_or_past_the_top_is_not_supported() {
    let n = nightstand();
    let low = surface_problem(&lamp([30.0, 20.0], 50.0, "nightstand-0"), &n).unwrap();
    assert!(low.contains("not on the top"), "{low}");
    let past = surface_problem(&lamp([50.0, 20.0], 55.0, "nightstand-0"), &n).unwrap();
    assert!(past.contains("reaches past"), "{past}");
    // Within the margin: the lamp sticks out 0.5 cm.
    assert_eq!(
        surface_problem(&lamp([40.0, 20.0], 55.2, "nightstand-0"), &n),
        None
    );
    let all = unsupported(&[lamp([30.0, 20.0], 55.0, "nightstand-9")], &room());
    assert_eq!(
        all,
        vec!["lamp-0: stands on nightstand-9, which is not placed"]
    );
}

#[test]
fn nothing_stands_on_a_rug_or_a_chair() {
    let rug = object("rug-0", "rug", [200.0, 140.0, 1.0], [200.0, 150.0], 0.0);
    let why = surface_problem(&lamp([200.0, 150.0], 1.0, "rug-0"), &rug).unwrap();
    assert!(why.contains("floor covering"), "{why}");
    let chair = object(
        "chair-0",
        "armchair",
        [80.0, 80.0, 45.0],
        [200.0, 150.0],
        0.0,
    );
    let why = surface_problem(&lamp([200.0, 150.0], 45.0, "chair-0"), &chair).unwrap();
    assert!(why.contains("a seat"), "{why}");
}

#[test]
fn two_lamps_on_one_top_collide_when_they_overlap() {
    let a = lamp([30.0, 20.0], 55.0, "nightstand-0");
    let b = PlacedObject {
        name: "lamp-1".into(),
        position: [40.0, 20.0],
        ..a.clone()
    };
    assert!(collide(&a, &b));
    let apart = PlacedObject {
        position: [80.0, 20.0],
        ..b
    };
    assert!(!collide(&a, &apart));
}

#[test]
fn an_object_held_by_nothing_above_the_floor_floats() {
    let floating = PlacedObject {
        elevation: 10.0,
        ..nightstand()
    };
    let all = unsupported(&[floating], &room());
    assert_eq!(all.len(), 1);
    assert!(all[0].contains("floats 10.0 cm"), "{all:?}");
    assert!(!reaches_floor(&lamp([0.0, 0.0], 55.0, "x")));
}

#[test]
fn a_painting_hangs_on_its_wall_facing_the_room() {
    let room = room();
    let p = painting(3, 150.0, 140.0);
    assert_eq!(wall_problem(&p, &room, 3), None);
    assert_eq!(opening_problem(&p, &room, 3), None);
    assert!(unsupported(std::slice::from_ref(&p), &room).is_empty());
    let off = PlacedObject {
        position: [10.0, 150.0],
        ..p.clone()
    };
    assert!(
        wall_problem(&off, &room, 3)
            .unwrap()
            .contains("not on the left wall")
    );
    let turned = PlacedObject {
        rotation: 0.0,
        ..p.clone()
    };
    assert!(
        wall_problem(&turned, &room, 3)
            .unwrap()
            .contains("face into")
    );
    assert!(wall_problem(&p, &room, 1).is_some());
    let past_end = painting(3, 10.0, 140.0);
    assert!(
        wall_problem(&past_end, &room, 3)
            .unwrap()
            .contains("past the end")
    );
}

#[test]
fn a_wall_object_may_not_cover_a_door_below_its_top_nor_a_window() {
    let room = room();
    let over_door = painting(0, 100.0, 100.0);
    let why = opening_problem(&over_door, &room, 0).unwrap();
    assert!(why.contains("door 0"), "{why}");
    assert_eq!(opening_problem(&painting(0, 100.0, 215.0), &room, 0), None);
    assert_eq!(opening_problem(&painting(0, 250.0, 100.0), &room, 0), None);
    // Wall 2 runs from (400, 300) to (0, 300): the window at 200 is centred at x = 200.
    let over_window = painting(2, 200.0, 100.0);
    assert!(
        opening_problem(&over_window, &room, 2)
            .unwrap()
            .contains("window 0")
    );
    assert_eq!(opening_problem(&painting(2, 200.0, 211.0), &room, 2), None);
    assert_eq!(opening_problem(&painting(2, 200.0, 20.0), &room, 2), None);
    assert_eq!(over_openings(&[over_door, over_window], &room).len(), 2);
}

#[test]
fn a_painting_above_a_sofa_is_clear_and_one_behind_a_wardrobe_collides() {
    let p = painting(3, 150.0, 140.0);
    let sofa = object("sofa-0", "sofa", [200.0, 90.0, 90.0], [45.0, 150.0], 90.0);
    assert!(!collide(&p, &sofa));
    let wardrobe = object(
        "wardrobe-0",
        "wardrobe",
        [120.0, 60.0, 200.0],
        [30.0, 150.0],
        90.0,
    );
    assert!(collide(&p, &wardrobe));
    let other = PlacedObject {
        name: "mirror-0".into(),
        ..painting(3, 190.0, 150.0)
    };
    assert!(collide(&p, &other));
    assert!(!collide(&p, &painting(3, 250.0, 140.0)));
}
