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
/// someone who had not seen the code): requests met when it was frozen, of the 64 the check reads
/// there (42 of 62 on the layouts made before the session's changes for it).
const THIRD_BATCH_MET_AT_LEAST: usize = 49;

/// Pieces walled in when the third batch was frozen, a known fault counted rather than hidden:
/// in the open-plan living-dining room the sofa, the island, its stools and the armchair seal
/// the door on the left wall, and the repair does not free it.
const THIRD_BATCH_WALLED_IN: [(&str, usize); 1] = [("n10-living-dining", 11)];

/// Runs the default graph over `set` and checks its `rooms` layouts: no physical fault, nothing
/// walled in, and at least `floor` of the prompts' requests met. Returns (met, asked).
fn requests_hold(set: &str, rooms: usize, floor: usize) -> (usize, usize) {
    requests_hold_but(set, rooms, floor, &[])
}

/// [`requests_hold`], but the rooms of `walled_in` may keep at most that many pieces walled in.
fn requests_hold_but(
    set: &str,
    rooms: usize,
    floor: usize,
    walled_in: &[(&str, usize)],
) -> (usize, usize) {
    let (mut met, mut asked, mut layouts) = (0, 0, 0);
    let mut broken = Vec::new();
    for (scene, layout) in bench_layouts(set) {
        layouts += 1;
        broken.extend(
            faults(&layout)
                .into_iter()
                .map(|f| format!("{}: {f}", scene.id)),
        );
        let unreachable = unreachable_objects(&layout.room, &layout.objects, REACH_CELL_CM);
        let allowed = walled_in
            .iter()
            .find(|(id, _)| *id == scene.id)
            .map_or(0, |(_, n)| *n);
        if unreachable.len() > allowed {
            broken.extend(
                unreachable
                    .into_iter()
                    .map(|n| format!("{}: {n} is walled in", scene.id)),
            );
        }
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
    requests_hold_but(
        "requests-3",
        10,
        THIRD_BATCH_MET_AT_LEAST,
        &THIRD_BATCH_WALLED_IN,
    );
}
