//! Open-universe rooms: the default graph on `bench/open`, thirty-eight rooms of kinds nobody
//! here listed (a pharmacy, a pottery studio, a chapel, a casino, a laundromat, a car showroom,
//! an airport gate...) with the object lists a language model would write, in three batches
//! (o01-o14, p01-p12, q01-q12), each written by a helper who had not seen the code; frozen here
//! as a regression set (bench/open/README.md has what a judge checks). The third batch's known
//! faults are counted, not yet zero: see the `Q_` floors.
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

/// Seats at what they serve over the set when it was frozen, of the 268 the knowledge counts as
/// seats in its 38 rooms (180 of 180 in the first two batches; the first 14 rooms: 56 of 96
/// before the agents knew what the pieces are for); a change below this has lost seats the rooms
/// need.
const SEATS_SERVING_AT_LEAST: usize = 267;

/// Seats of the third batch (q01-q12) that serve nothing and whose run does not say so, when it
/// was frozen: a chair planned at the police front counter that the physical repair moved away.
/// More is a loss.
const Q_SEATS_ASTRAY_AT_MOST: usize = 1;

/// Pieces of the third batch walled in when it was frozen: the second gate agent's chair, behind
/// the gate counter in a corner. More is a loss.
const Q_WALLED_IN_AT_MOST: usize = 1;

/// Counters open on their staff side and their customers' side over the set when it was frozen,
/// of the 37 the knowledge gives a staff side (23 of 25 in the first two batches, 10 of 12 in
/// the third; in the first 14 rooms, 2 of 12 before: every counter but the two bars stood
/// against a wall).
const COUNTERS_OPEN_AT_LEAST: usize = 33;

#[test]
fn open_universe_rooms_serve_their_uses_and_stay_sound() {
    let knowledge = Knowledge::builtin();
    let (mut layouts, mut seats, mut serving, mut counters, mut open) = (0, 0, 0, 0, 0);
    let mut broken = Vec::new();
    let (mut astray, mut walled_in) = (0, 0);
    for (scene, layout) in bench_layouts("open") {
        layouts += 1;
        let id = &scene.id;
        broken.extend(faults(&layout).into_iter().map(|f| format!("{id}: {f}")));
        let walled = unreachable_objects(&layout.room, &layout.objects, REACH_CELL_CM);
        if id.starts_with('q') {
            walled_in += walled.len();
        } else {
            broken.extend(
                walled
                    .into_iter()
                    .map(|n| format!("{id}: {n} is walled in")),
            );
        }
        for c in check_uses(&scene, &layout, &knowledge) {
            match c.kind {
                UseKind::SeatServes => {
                    seats += 1;
                    serving += usize::from(c.met);
                    if !c.met && !c.reported {
                        if id.starts_with('q') {
                            astray += 1;
                        } else {
                            broken.push(format!("{id}: {} serves nothing, silently", c.subject));
                        }
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
    assert_eq!(layouts, 38);
    assert!(broken.is_empty(), "{broken:#?}");
    assert!(
        walled_in <= Q_WALLED_IN_AT_MOST,
        "{walled_in} pieces of the third batch walled in, more than the {Q_WALLED_IN_AT_MOST} when frozen"
    );
    assert!(
        astray <= Q_SEATS_ASTRAY_AT_MOST,
        "{astray} seats of the third batch serve nothing silently, more than the {Q_SEATS_ASTRAY_AT_MOST} when frozen"
    );
    assert!(
        open >= COUNTERS_OPEN_AT_LEAST,
        "{open} of {counters} counters open on both sides, fewer than the {COUNTERS_OPEN_AT_LEAST} when frozen"
    );
    assert!(
        serving >= SEATS_SERVING_AT_LEAST,
        "{serving} of {seats} seats serve something, fewer than the {SEATS_SERVING_AT_LEAST} when frozen"
    );
}
