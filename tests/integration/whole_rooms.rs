//! Whole rooms: the default graph on `bench/whole`, thirty rooms whose asset lists hang pieces on
//! the walls and stand them on other pieces (TVs and stands, lamps and nightstands, paintings,
//! mirrors, clocks, monitors, kitchen appliances), written by a helper who had not seen the
//! code, before the rule agents put anything off the floor; frozen here as a regression set
//! (bench/whole/README.md has what a judge checks).
//!
//! Every layout keeps the physical rules in 3D (nothing colliding, floating, off its support or
//! over a door or window, nothing outside the room or in a keep-clear zone, nothing dropped,
//! everything reachable); the kinds that belong off the floor are off it, wall pieces at heights
//! plausible for their kind; and as many pieces stand off the floor as when the set was frozen. Plus the issue's own bedroom, end to end.

use disco_layout::Layout;
use disco_layout::layout::PlacedObject;
use disco_layout::metrics::{REACH_CELL_CM, unreachable_objects};
use disco_layout::plan::Relation;

use crate::harness::{disco, stderr};
use crate::rooms::faults;

/// Pieces off the floor over the set when it was frozen (of 586; the writer meant 272 to be,
/// none was before the agents knew what goes on walls and tops).
const OFF_THE_FLOOR_AT_LEAST: usize = 260;

/// Why a piece hung on a wall hangs at an implausible height for its kind, if it does: a
/// picture's centre at 130-175 cm or its bottom 10-100 cm above the piece it hangs over (over
/// that piece and what stands on it), a mirror's likewise or centred at 120-180 cm, a clock's
/// centre at 150 cm or more, a TV's at 90-160 cm; nothing reaching past 250 cm.
fn height_fault(o: &PlacedObject, layout: &Layout) -> Option<String> {
    let words: Vec<String> = o
        .category
        .to_lowercase()
        .split([' ', '-'])
        .map(String::from)
        .collect();
    let has = |w: &str| words.iter().any(|x| x == w);
    let centre = o.elevation + o.size[2] / 2.0;
    let over = layout
        .plan
        .constraints
        .get(&o.name)
        .and_then(|c| c.relations.iter().find(|r| r.relation == Relation::Above))
        .and_then(|r| layout.object(&r.target));
    let above_ok = over.is_some_and(|u| (10.0..=100.0).contains(&(o.elevation - u.top())));
    let picture = [
        "painting", "print", "poster", "photo", "diploma", "canvas", "map",
    ]
    .iter()
    .any(|w| has(w));
    let ok = if o.top() > 250.0 + 1e-6 {
        false
    } else if picture {
        above_ok || (130.0..=175.0).contains(&centre)
    } else if has("mirror") {
        above_ok || (120.0..=180.0).contains(&centre)
    } else if has("clock") {
        centre >= 150.0
    } else if has("tv") {
        (90.0..=160.0).contains(&centre)
    } else {
        true
    };
    (!ok).then(|| {
        format!(
            "{} ({}) hangs with its bottom at {:.0} cm, centre {centre:.0} cm",
            o.name, o.category, o.elevation
        )
    })
}

/// Whether a category names a piece that belongs on a wall or a top whatever the room: a table
/// or desk lamp, a TV, a clock, a picture, a mirror no taller than a person.
fn belongs_off_the_floor(category: &str, size: [f64; 3]) -> bool {
    let c = category.to_lowercase();
    let words: Vec<&str> = c.split([' ', '-']).collect();
    let has = |w: &str| words.contains(&w);
    let lamp = has("lamp") && !has("floor") && !has("standing");
    let picture = [
        "painting", "print", "poster", "photo", "diploma", "canvas", "map",
    ]
    .iter()
    .any(|w| has(w));
    let tv = has("tv") && !has("stand");
    let mirror = has("mirror") && size[2] <= 180.0;
    lamp || picture || tv || has("clock") || mirror
}

#[test]
fn whole_rooms_hang_and_stand_what_belongs_off_the_floor_and_stay_sound() {
    let (mut layouts, mut off) = (0, 0);
    let mut broken = Vec::new();
    for (scene, layout) in crate::harness::bench_layouts("whole") {
        layouts += 1;
        let id = &scene.id;
        broken.extend(faults(&layout).into_iter().map(|f| format!("{id}: {f}")));
        broken.extend(
            unreachable_objects(&layout.room, &layout.objects, REACH_CELL_CM)
                .into_iter()
                .map(|n| format!("{id}: {n} is walled in")),
        );
        for o in &layout.objects {
            if o.wall.is_some() {
                broken.extend(height_fault(o, &layout).map(|f| format!("{id}: {f}")));
            }
            if !o.on_floor() {
                off += 1;
            } else if belongs_off_the_floor(&o.category, o.size) {
                broken.push(format!(
                    "{id}: {} ({}) stands on the floor",
                    o.name, o.category
                ));
            }
        }
    }
    assert_eq!(layouts, 30);
    assert!(broken.is_empty(), "{broken:#?}");
    assert!(
        off >= OFF_THE_FLOOR_AT_LEAST,
        "{off} pieces off the floor, fewer than the {OFF_THE_FLOOR_AT_LEAST} when frozen"
    );
}

/// The issue's bedroom: a TV and its stand, two lamps and two nightstands, a painting and a
/// clock come out with the TV on its stand, a lamp on each nightstand, the painting above the
/// bed and the clock on a wall, all held where they are.
#[test]
fn the_issues_bedroom_comes_out_whole() {
    let dir = tempfile::tempdir().unwrap();
    let scene = dir.path().join("bedroom.json");
    std::fs::write(
        &scene,
        r#"{"room_type": "bedroom", "prompt": "a bedroom",
  "room": {"width": 450, "depth": 400,
           "doors": [{"wall": 0, "at": 380, "width": 90}],
           "windows": [{"wall": 2, "at": 225, "width": 120, "sill": 90, "height": 120}]},
  "assets": [{"name": "bed-0", "category": "double bed", "size": [160, 210, 100]},
             {"name": "nightstand-0", "category": "nightstand", "size": [50, 40, 55]},
             {"name": "nightstand-1", "category": "nightstand", "size": [50, 40, 55]},
             {"name": "lamp-0", "category": "table lamp", "size": [30, 30, 50]},
             {"name": "lamp-1", "category": "table lamp", "size": [30, 30, 50]},
             {"name": "tv-stand-0", "category": "tv stand", "size": [120, 40, 50]},
             {"name": "tv-0", "category": "tv", "size": [100, 8, 60]},
             {"name": "painting-0", "category": "painting", "size": [90, 4, 60]},
             {"name": "clock-0", "category": "clock", "size": [30, 5, 30]}]}"#,
    )
    .unwrap();
    let out = dir.path().join("layout.json");
    let o = disco(&[
        "generate",
        scene.to_str().unwrap(),
        "-o",
        out.to_str().unwrap(),
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    let layout: Layout = serde_json::from_str(&std::fs::read_to_string(&out).unwrap()).unwrap();
    assert!(faults(&layout).is_empty(), "{:#?}", faults(&layout));
    let get = |n: &str| layout.object(n).unwrap();
    assert_eq!(get("tv-0").on.as_deref(), Some("tv-stand-0"));
    let mut lamps_on: Vec<_> = ["lamp-0", "lamp-1"]
        .iter()
        .map(|n| get(n).on.clone().unwrap_or_default())
        .collect();
    lamps_on.sort();
    assert_eq!(lamps_on, vec!["nightstand-0", "nightstand-1"]);
    let painting = get("painting-0");
    assert!(painting.wall.is_some());
    assert!(
        disco_layout::relations::hung_above(&painting.footprint(), &get("bed-0").footprint()),
        "the painting hangs above the bed: {painting:?}"
    );
    assert!(painting.elevation >= get("bed-0").top());
    let clock = get("clock-0");
    assert!(
        clock.wall.is_some() && clock.elevation >= 150.0,
        "{clock:?}"
    );
}
