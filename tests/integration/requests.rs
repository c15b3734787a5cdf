//! Specific requests in rooms nobody here wrote: the default graph on `bench/requests`, twelve
//! rooms (ten of them L-, T-, U-shaped, slanted or with an alcove or bay) whose prompts ask for
//! walls by their role ("opposite the door", "without windows"), zones ("in the alcove", "in the
//! short arm"), pieces under windows and formations ("two rows of four desks facing the
//! whiteboard", "six chairs in a semicircle", "two pods of four desks", "four chairs on each long
//! side"). Written by someone who had not seen the code, before the agents learnt these words;
//! frozen here as a regression set (bench/requests/README.md has the prompts and what a judge
//! checks).
//!
//! `bench/requests-2` is the second such batch (session 12: sixteen rooms; U and L formations,
//! rings about a rug, arcs with a stand each, a stool behind each easel, places said first,
//! wings by side, pronouns), frozen the same way; `bench/requests-3` the third (session 14: ten
//! rooms; rows facing each other across a table, pods with each desk's chair, mats in rows).
//! `bench/requests-4` the fourth (session 16: ten rooms; pews in columns either side of an
//! aisle, a front and a back row, a semicircle about a described teacher's wheel, a piece
//! centred on its wall, zones said before their pieces), and `bench/requests-5` the fifth (the
//! same session: eight rooms; rows behind a lectern, verbs and asides, a piece named by its
//! description, "either side of the window").
//! `bench/open-r` (session 15: twelve open-universe rooms) asks in its assets' descriptions
//! rather than its prompts ("beside a dialysis chair", "in the niche"); the check reads both.
//!
//! Every layout keeps the physical rules of the real rooms (nothing colliding, outside the
//! outline, in a door's or window's zone, dropped or walled in), and the prompts' requests, as the
//! prompt-requests check reads them, are met at least as often as when the set was frozen.

use disco_layout::agents::requests::check_requests;
use disco_layout::metrics::{REACH_CELL_CM, unreachable_objects};

use crate::harness::bench_layouts;
use crate::rooms::faults;

/// Requests met over the set when it was frozen, of the 50 the check reads (19 before the agents
/// read zones, wall roles and formations); a change that meets fewer has lost something a user
/// asked for.
const REQUESTS_MET_AT_LEAST: usize = 47;

/// The second batch (`bench/requests-2`, session 12: sixteen rooms, fifteen of them not
/// rectangles, written by someone who had not seen the code): requests met when it was frozen,
/// of the 108 the check reads there (62 of 107 on the layouts made before the session's
/// changes, which left the rows facing a bare wall unread).
const SECOND_BATCH_MET_AT_LEAST: usize = 91;

/// The third batch (`bench/requests-3`, session 14: ten rooms, eight not rectangles, written by
/// someone who had not seen the code): requests met, of the 65 the check reads there since it
/// reads the assets' descriptions too (42 of 62 on the layouts made before the session's changes
/// for it, 49 of 64 when it was frozen with the living-dining room's door sealed and 11 pieces
/// walled in; session 15 mended that room: the TV the sofa faces takes the middle of its wall,
/// and the dining table asked into the far corner keeps room for its chairs).
const THIRD_BATCH_MET_AT_LEAST: usize = 51;

/// The fourth batch (`bench/requests-4`, session 16: ten rooms, eight not rectangles, written
/// by someone who had not seen the code): requests met when it was frozen, of the 77 the check
/// reads there (55 on the layouts made before the session's changes, 61 on those two blind
/// judges scored after them, read by the same check).
const FOURTH_BATCH_MET_AT_LEAST: usize = 66;

/// The fifth batch (`bench/requests-5`, session 16: eight rooms, six not rectangles, written
/// by someone who had seen neither the code nor the earlier batches): requests met when it was
/// frozen, of the 59 the check reads there (33 on the layouts made before the changes for it,
/// 38 on those two blind judges scored after them, read by the same check).
const FIFTH_BATCH_MET_AT_LEAST: usize = 39;

/// Open-universe rooms whose object lists say in their descriptions where things go
/// (`bench/open-r`, session 15: twelve rooms, ten not rectangles, written by someone who had not
/// seen the code): requests met, of the 75 the check reads in the descriptions ("beside a
/// dialysis chair", "in the alcove", "across from the optician at a fitting desk"), when the
/// set was frozen (55 at first; 54 since a counter worked from behind stands by the staff door,
/// which two blind judges preferred in 6 of the 10 rooms it changed: the bakery's back counter
/// went to the staff door and its bread racks no longer stand behind it). Before the agents
/// read descriptions the check found one request there.
const DESCRIBED_ROOMS_MET_AT_LEAST: usize = 54;

/// Runs the default graph over `set` and checks its `rooms` layouts: no physical fault, nothing
/// walled in, and at least `floor` of the requests met. Returns (met, asked).
fn requests_hold(set: &str, rooms: usize, floor: usize) -> (usize, usize) {
    let (mut met, mut asked, mut layouts) = (0, 0, 0);
    let mut broken = Vec::new();
    for (scene, layout) in bench_layouts(set) {
        layouts += 1;
        broken.extend(
            faults(&layout)
                .into_iter()
                .map(|f| format!("{}: {f}", scene.id)),
        );
        broken.extend(
            unreachable_objects(&layout.room, &layout.objects, REACH_CELL_CM)
                .into_iter()
                .map(|n| format!("{}: {n} is walled in", scene.id)),
        );
        let checks = check_requests(&scene, &layout);
        for c in &checks {
            println!(
                "{}: {} {}",
                scene.id,
                if c.met { "met" } else { "NOT MET" },
                c.request
            );
        }
        asked += checks.len();
        met += checks.iter().filter(|c| c.met).count();
    }
    println!("{set}: {met} of {asked} requests met");
    assert_eq!(layouts, rooms);
    assert!(broken.is_empty(), "{broken:#?}");
    assert!(
        met >= floor,
        "{set}: {met} of {asked} requests met, fewer than the {floor} when frozen"
    );
    (met, asked)
}

#[test]
fn specific_requests_in_fresh_rooms_are_met_and_the_rooms_stay_sound() {
    requests_hold("requests", 12, REQUESTS_MET_AT_LEAST);
}

#[test]
fn the_second_batch_of_requests_is_met_and_its_rooms_stay_sound() {
    requests_hold("requests-2", 16, SECOND_BATCH_MET_AT_LEAST);
}

#[test]
fn the_third_batch_of_requests_is_met_and_its_rooms_stay_sound() {
    requests_hold("requests-3", 10, THIRD_BATCH_MET_AT_LEAST);
}

#[test]
fn the_fourth_batch_of_requests_is_met_and_its_rooms_stay_sound() {
    requests_hold("requests-4", 10, FOURTH_BATCH_MET_AT_LEAST);
}

#[test]
fn the_fifth_batch_of_requests_is_met_and_its_rooms_stay_sound() {
    requests_hold("requests-5", 8, FIFTH_BATCH_MET_AT_LEAST);
}

#[test]
fn what_the_descriptions_of_fresh_open_rooms_ask_is_met_and_the_rooms_stay_sound() {
    requests_hold("open-r", 12, DESCRIBED_ROOMS_MET_AT_LEAST);
}
