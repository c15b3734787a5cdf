//! Tests of reach: the incremental map against a fresh raster, and hand-made rooms.

use super::raster::Raster;
use super::*;
use crate::room::Door;
use crate::room::point_in_polygon;

/// The metric's raster.
const REACH_CELL: f64 = super::super::REACH_CELL_CM;

/// Random solid objects, some of them tilted, in a small room crowded enough to wall some in.
fn crowd(seed: u64, n: usize) -> (Room, Vec<PlacedObject>) {
    (Room::rect(500.0, 400.0), crowd_in(seed, n))
}

/// Random solid objects, some of them tilted, over a 500 x 400 floor.
fn crowd_in(seed: u64, n: usize) -> Vec<PlacedObject> {
    let mut rng = fastrand::Rng::with_seed(seed);
    let cats = ["table", "wardrobe", "chair", "shelf"];
    (0..n)
        .map(|i| PlacedObject {
            name: format!("o{i}"),
            category: cats[i % 4].to_string(),
            size: [30.0 + rng.f64() * 150.0, 30.0 + rng.f64() * 80.0, 80.0],
            position: [rng.f64() * 500.0, rng.f64() * 400.0],
            rotation: if i % 5 == 0 {
                rng.f64() * 360.0
            } else {
                90.0 * rng.usize(0..4) as f64
            },
            ..Default::default()
        })
        .collect()
}

fn door(wall: usize, at: f64, width: f64) -> Door {
    Door::new(wall, at, width)
}

/// Rooms with doors over the 500 x 400 floor the crowds use: a rectangle with one door, the
/// same with two doors on facing walls, and an L with a door on a wall of its notch.
fn rooms_with_doors() -> Vec<Room> {
    let mut one = Room::rect(500.0, 400.0);
    one.doors.push(door(0, 120.0, 90.0));
    let mut two = one.clone();
    two.doors.push(door(2, 250.0, 80.0));
    let mut l = Room::from_polygon(vec![
        [0.0, 0.0],
        [500.0, 0.0],
        [500.0, 220.0],
        [280.0, 220.0],
        [280.0, 400.0],
        [0.0, 400.0],
    ]);
    l.doors.push(door(3, 110.0, 90.0));
    l.doors.push(door(1, 110.0, 90.0));
    vec![one, two, l]
}

/// Adds `objects` one by one to a map of `room`, checking at every step that the map's counts,
/// before and after adding, are those of a fresh raster.
fn assert_map_matches_fresh(room: &Room, objects: &[PlacedObject], what: &str) {
    let mut map = ReachMap::new(room, &[], 10.0);
    for (i, o) in objects.iter().enumerate() {
        let fresh = unreachable_objects(room, &objects[..=i], 10.0).len();
        assert_eq!(map.unreachable_with(o), fresh, "{what}, object {i}");
        map.add(o);
        assert_eq!(map.unreachable(), fresh, "{what}, object {i}");
    }
}

#[test]
fn the_map_counts_as_a_fresh_raster_at_every_step() {
    for seed in 0..12 {
        let (room, objects) = crowd(seed, 24);
        let mut map = ReachMap::new(&room, &[], 10.0);
        for (i, o) in objects.iter().enumerate() {
            let with: Vec<PlacedObject> = objects[..=i].to_vec();
            let fresh = unreachable_objects(&room, &with, 10.0).len();
            assert_eq!(map.unreachable_with(o), fresh, "seed {seed}, object {i}");
            map.add(o);
            assert_eq!(map.unreachable(), fresh, "seed {seed}, object {i}");
        }
    }
}

#[test]
fn the_map_counts_as_a_fresh_raster_in_rooms_with_doors() {
    let mut walled_in = 0;
    for (r, room) in rooms_with_doors().iter().enumerate() {
        for seed in 0..10 {
            let objects = crowd_in(100 + seed, 24);
            assert_map_matches_fresh(room, &objects, &format!("room {r}, seed {seed}"));
            walled_in += unreachable_objects(room, &objects, 10.0).len();
        }
    }
    // The crowds are dense enough to cut pieces off the doors' regions, so the map's local
    // updates and its rebuilds are both exercised.
    assert!(walled_in > 0);
}

/// A 400 x 400 room cut in two by a row of counters at y = 150 facing down, with a shelf
/// against the top wall facing them: the top part is the larger.
fn split_room(with_door: bool) -> (Room, Vec<PlacedObject>) {
    let mut room = Room::rect(400.0, 400.0);
    if with_door {
        room.doors.push(door(0, 300.0, 90.0));
    }
    let at = |name: &str, cat: &str, w: f64, x: f64, y: f64, rotation: f64| PlacedObject {
        name: name.into(),
        category: cat.into(),
        size: [w, 40.0, 90.0],
        position: [x, y],
        rotation,
        ..Default::default()
    };
    let objects = vec![
        at("shelf", "shelf", 80.0, 200.0, 380.0, 180.0),
        at("a", "counter", 200.0, 100.0, 150.0, 180.0),
        at("b", "counter", 200.0, 300.0, 150.0, 180.0),
    ];
    (room, objects)
}

#[test]
fn a_piece_cut_off_from_the_door_is_out_of_reach_even_in_the_largest_region() {
    let (room, objects) = split_room(true);
    assert_eq!(
        unreachable_objects(&room, &objects, REACH_CELL),
        vec!["shelf"]
    );
    let mut map = ReachMap::new(&room, &objects[..2], 10.0);
    assert_eq!(map.unreachable(), 0, "the row is still open");
    assert_eq!(map.unreachable_with(&objects[2]), 1);
    map.add(&objects[2]);
    assert_eq!(map.unreachable(), 1);
    // Without the door the larger, top part is walkable: the counters face away from it.
    let (doorless, objects) = split_room(false);
    assert_eq!(
        unreachable_objects(&doorless, &objects, REACH_CELL),
        vec!["a", "b"]
    );
}

#[test]
fn a_front_against_a_wall_of_the_outline_is_out_of_reach() {
    // An L whose missing quarter is the top right: the bounding box is free there, the room not.
    let mut room = Room::from_polygon(vec![
        [0.0, 0.0],
        [600.0, 0.0],
        [600.0, 300.0],
        [300.0, 300.0],
        [300.0, 600.0],
        [0.0, 600.0],
    ]);
    let cabinet = PlacedObject {
        name: "cabinet".into(),
        category: "cabinet".into(),
        size: [80.0, 40.0, 90.0],
        // Facing +x, its front on the notch wall x = 300.
        position: [280.0, 450.0],
        rotation: 90.0,
        ..Default::default()
    };
    assert_eq!(
        unreachable_objects(&room, std::slice::from_ref(&cabinet), REACH_CELL),
        vec!["cabinet"]
    );
    room.doors.push(door(0, 150.0, 90.0));
    assert_eq!(
        unreachable_objects(&room, &[cabinet], REACH_CELL),
        vec!["cabinet"]
    );
}

#[test]
fn free_cells_of_a_polygon_stay_inside_its_outline() {
    let room = Room::from_polygon(vec![
        [0.0, 0.0],
        [400.0, 0.0],
        [400.0, 100.0],
        [100.0, 400.0],
        [0.0, 400.0],
    ]);
    let raster = Raster::new(&room, 10.0);
    let free = raster.free_cells(&room, std::iter::empty());
    let outline = room.outline();
    let mut count = 0;
    for (k, _) in free.iter().enumerate().filter(|(_, f)| **f) {
        let p = raster.centre(k % raster.nx, k / raster.nx);
        assert!(point_in_polygon(p, &outline), "{p}");
        count += 1;
    }
    // Most of the floor is free: the slanted wall cuts a corner, not the room.
    assert!(count as f64 * 100.0 > room.area() * 0.6, "{count} cells");
}

#[test]
fn entry_cells_lie_just_inside_each_door() {
    let mut room = Room::rect(400.0, 300.0);
    assert!(Raster::new(&room, 5.0).entry_cells(&room).is_empty());
    room.doors.push(door(1, 150.0, 90.0));
    let raster = Raster::new(&room, 5.0);
    let cells = raster.entry_cells(&room);
    assert!(!cells.is_empty());
    for k in cells {
        let p = raster.centre(k % raster.nx, k / raster.nx);
        // Wall 1 is the right wall, x = 400, running up from y = 0.
        assert!(p.x >= 400.0 - AGENT_RADIUS_CM - 10.0 && p.x < 400.0, "{p}");
        assert!((105.0..=195.0).contains(&p.y), "{p}");
    }
}

#[test]
fn a_wall_of_objects_that_seals_a_corner_counts_it() {
    let room = Room::rect(400.0, 400.0);
    let at = |name: &str, cat: &str, w: f64, x: f64, y: f64, rotation: f64| PlacedObject {
        name: name.into(),
        category: cat.into(),
        size: [w, 40.0, 80.0],
        position: [x, y],
        rotation,
        ..Default::default()
    };
    // A cabinet in the corner, then two long counters facing out that close it in.
    let objects = [
        at("cab", "cabinet", 60.0, 30.0, 20.0, 0.0),
        at("a", "counter", 200.0, 160.0, 100.0, 90.0),
        at("b", "counter", 200.0, 100.0, 220.0, 0.0),
    ];
    let mut map = ReachMap::new(&room, &objects[..2], 10.0);
    assert_eq!(map.unreachable(), 0);
    assert_eq!(map.unreachable_with(&objects[2]), 1);
    map.add(&objects[2]);
    assert_eq!(map.unreachable(), 1);
    assert_eq!(unreachable_objects(&room, &objects, 10.0), vec!["cab"]);
}

#[test]
fn a_rolled_back_trial_leaves_the_map_as_it_was() {
    let rooms = rooms_with_doors()
        .into_iter()
        .chain([Room::rect(500.0, 400.0)]);
    for (r, room) in rooms.enumerate() {
        for seed in 0..6 {
            let objects = crowd_in(seed + 100 * r as u64, 24);
            let (base, trial) = objects.split_at(10);
            let mut map = ReachMap::new(&room, base, REACH_CELL);
            let (free, label) = (map.free.clone(), map.label.clone());
            map.begin_trial();
            for o in trial {
                map.add(o);
            }
            map.roll_back();
            let what = format!("room {r}, seed {seed}");
            assert_eq!(map.objects.len(), base.len(), "{what}");
            assert!(map.free == free && map.label == label, "{what}: cells");
            assert_eq!(map.zones.len(), base.len(), "{what}: zones");
            // Growing the rolled-back map still counts as a fresh raster does.
            for (n, o) in trial.iter().enumerate() {
                map.add(o);
                let fresh = ReachMap::new(&room, &objects[..=10 + n], REACH_CELL);
                assert_eq!(map.unreachable(), fresh.unreachable(), "{what}, {n}");
            }
        }
    }
}
