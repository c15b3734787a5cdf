//! Open-universe rooms: the default graph on `bench/open`, twenty-six rooms of kinds nobody here
//! listed (a pharmacy, a pottery studio, a chapel, a casino, a laundromat, an art gallery...)
//! with the object lists a language model would write, in two batches (o01-o14, p01-p12), each
//! written by a helper who had not seen the code; frozen here as a regression set
//! (bench/open/README.md has what a judge checks).
//!
//! Every layout keeps the physical rules of the real rooms, and the uses the furniture
//! knowledge gives its pieces hold ([`check_uses`]): no seat serves nothing unless the run's
//! notes say nothing had room for it, aisle shelving stands free, and as many seats serve
//! something and as many counters are open on both sides as when the set was frozen.

use disco_layout::agents::knowledge::Knowledge;
use disco_layout::agents::uses::{UseKind, check_uses};
use disco_layout::metrics::{REACH_CELL_CM, unreachable_objects};

use crate::harness::bench_layouts;
use crate::rooms::faults;

/// Seats at what they serve over the set when it was frozen, of the 180 the knowledge counts as
/// seats in its 26 rooms (the first 14 rooms: 56 of 96 before the agents knew what the pieces
/// are for, the other 40 at nothing and not reported); a change below this has lost seats the
/// rooms need.
const SEATS_SERVING_AT_LEAST: usize = 180;

/// Counters open on their staff side and their customers' side over the set when it was frozen,
/// of the 25 the knowledge gives a staff side (in the first 14 rooms, 2 of 12 before: every
/// counter but the two bars stood against a wall).
const COUNTERS_OPEN_AT_LEAST: usize = 23;

#[test]
fn open_universe_rooms_serve_their_uses_and_stay_sound() {
    let knowledge = Knowledge::builtin();
    let (mut layouts, mut seats, mut serving, mut counters, mut open) = (0, 0, 0, 0, 0);
    let mut broken = Vec::new();
    for (scene, layout) in bench_layouts("open") {
        layouts += 1;
        let id = &scene.id;
        broken.extend(faults(&layout).into_iter().map(|f| format!("{id}: {f}")));
        broken.extend(
            unreachable_objects(&layout.room, &layout.objects, REACH_CELL_CM)
                .into_iter()
                .map(|n| format!("{id}: {n} is walled in")),
        );
        for c in check_uses(&scene, &layout, &knowledge) {
            match c.kind {
                UseKind::SeatServes => {
                    seats += 1;
                    serving += usize::from(c.met);
                    if !c.met && !c.reported {
                        broken.push(format!("{id}: {} serves nothing, silently", c.subject));
                    }
                }
                UseKind::StaffSideOpen => {
                    counters += 1;
                    open += usize::from(c.met);
                }
                _ if !c.met => broken.push(format!("{id}: {} fails {}", c.subject, c.kind)),
                _ => {}
            }
        }
    }
    assert_eq!(layouts, 26);
    assert!(broken.is_empty(), "{broken:#?}");
    assert!(
        open >= COUNTERS_OPEN_AT_LEAST,
        "{open} of {counters} counters open on both sides, fewer than the {COUNTERS_OPEN_AT_LEAST} when frozen"
    );
    assert!(
        serving >= SEATS_SERVING_AT_LEAST,
        "{serving} of {seats} seats serve something, fewer than the {SEATS_SERVING_AT_LEAST} when frozen"
    );
}
