//! Synthetic scenes and noisy layouts, seeded and reproducible: the fixtures of the benchmarks and
//! property tests, and a quick way to get a messy layout to refine.

use crate::layout::{Layout, PlacedObject, Stats};
use crate::plan::{ObjectConstraints, Plan, Relation, RelationSpec};
use crate::scene::{Asset, Room, SceneSpec};

fn placed(a: &Asset, x: f64, y: f64, rotation: f64) -> PlacedObject {
    PlacedObject {
        name: a.name.clone(),
        category: a.category.clone(),
        size: a.size,
        position: [x, y],
        rotation,
        ..Default::default()
    }
}

fn wall(plan: &mut Plan, name: &str) {
    plan.constraints
        .entry(name.to_string())
        .or_default()
        .against_wall = true;
}

fn relate(plan: &mut Plan, name: &str, relation: Relation, target: &str, face: bool) {
    let c: &mut ObjectConstraints = plan.constraints.entry(name.to_string()).or_default();
    c.relations.push(RelationSpec {
        relation,
        target: target.to_string(),
    });
    if face {
        c.facing = Some(target.to_string());
    }
}

/// A 10-object bedroom (400 x 350 cm) and a sensible layout of it, with its plan.
pub fn bedroom() -> (SceneSpec, Layout) {
    let assets = vec![
        Asset::new("bed-0", "bed", [160.0, 210.0, 100.0]),
        Asset::new("nightstand-0", "nightstand", [50.0, 40.0, 55.0]),
        Asset::new("nightstand-1", "nightstand", [50.0, 40.0, 55.0]),
        Asset::new("wardrobe-0", "wardrobe", [120.0, 60.0, 200.0]),
        Asset::new("desk-0", "desk", [120.0, 60.0, 75.0]),
        Asset::new("chair-0", "chair", [45.0, 50.0, 90.0]),
        Asset::new("dresser-0", "dresser", [100.0, 45.0, 80.0]),
        Asset::new("armchair-0", "armchair", [80.0, 80.0, 95.0]),
        Asset::new("floor lamp-0", "floor lamp", [35.0, 35.0, 160.0]),
        Asset::new("rug-0", "rug", [200.0, 140.0, 1.0]),
    ];
    let a = |i: usize| &assets[i];
    let objects = vec![
        placed(a(0), 200.0, 245.0, 180.0),
        placed(a(1), 95.0, 330.0, 180.0),
        placed(a(2), 305.0, 330.0, 180.0),
        placed(a(3), 30.0, 120.0, 90.0),
        placed(a(4), 320.0, 30.0, 0.0),
        placed(a(5), 320.0, 90.0, 180.0),
        placed(a(6), 377.5, 200.0, 270.0),
        placed(a(7), 160.0, 50.0, 0.0),
        placed(a(8), 217.5, 17.5, 0.0),
        placed(a(9), 200.0, 150.0, 0.0),
    ];
    let mut plan = Plan::default();
    for n in [
        "bed-0",
        "nightstand-0",
        "nightstand-1",
        "wardrobe-0",
        "desk-0",
        "dresser-0",
        "floor lamp-0",
    ] {
        wall(&mut plan, n);
    }
    relate(&mut plan, "nightstand-0", Relation::SideOf, "bed-0", false);
    relate(&mut plan, "nightstand-1", Relation::SideOf, "bed-0", false);
    relate(&mut plan, "chair-0", Relation::InFrontOf, "desk-0", true);
    relate(
        &mut plan,
        "armchair-0",
        Relation::Near,
        "floor lamp-0",
        false,
    );
    plan.groups = vec![
        vec!["bed-0".into(), "nightstand-0".into(), "nightstand-1".into()],
        vec!["wardrobe-0".into(), "dresser-0".into()],
        vec!["desk-0".into(), "chair-0".into()],
        vec!["armchair-0".into(), "floor lamp-0".into(), "rug-0".into()],
    ];
    finish(
        "bedroom-synth",
        "bedroom",
        "a bedroom with a desk and a reading corner",
        Room::rect(400.0, 350.0),
        assets,
        objects,
        plan,
    )
}

/// A 24 x 18 m banquet hall: 12 round tables (180 cm) with 8 chairs each, plus 4 buffet counters
/// and 8 plants against the walls: 120 objects.
pub fn banquet_hall() -> (SceneSpec, Layout) {
    let mut assets = Vec::new();
    let mut objects = Vec::new();
    let mut plan = Plan::default();
    let mut groups = Vec::new();
    for t in 0..12 {
        let (cx, cy) = (
            300.0 + 600.0 * (t % 4) as f64,
            350.0 + 550.0 * (t / 4) as f64,
        );
        let table = Asset::new(
            &format!("table-{t}"),
            "round dining table",
            [180.0, 180.0, 75.0],
        );
        objects.push(placed(&table, cx, cy, 0.0));
        let mut group = vec![table.name.clone()];
        for c in 0..8 {
            let angle = c as f64 * 45.0;
            let (s, co) = angle.to_radians().sin_cos();
            let chair = Asset::new(&format!("chair-{}", t * 8 + c), "chair", [45.0, 50.0, 90.0]);
            let r = 90.0 + 30.0;
            // The chair sits at `angle` around the table and faces its centre.
            objects.push(placed(&chair, cx + r * s, cy + r * co, angle + 180.0));
            relate(&mut plan, &chair.name, Relation::Around, &table.name, true);
            group.push(chair.name.clone());
            assets.push(chair);
        }
        assets.push(table);
        groups.push(group);
    }
    let mut side = Vec::new();
    for b in 0..4 {
        let counter = Asset::new(
            &format!("buffet counter-{b}"),
            "buffet counter",
            [240.0, 80.0, 90.0],
        );
        objects.push(placed(&counter, 400.0 + 520.0 * b as f64, 1760.0, 180.0));
        wall(&mut plan, &counter.name);
        side.push(counter.name.clone());
        assets.push(counter);
    }
    for p in 0..8 {
        let plant = Asset::new(&format!("plant-{p}"), "potted plant", [50.0, 50.0, 120.0]);
        let x = if p % 2 == 0 { 25.0 } else { 2375.0 };
        objects.push(placed(
            &plant,
            x,
            200.0 + 380.0 * (p / 2) as f64,
            if p % 2 == 0 { 90.0 } else { 270.0 },
        ));
        wall(&mut plan, &plant.name);
        side.push(plant.name.clone());
        assets.push(plant);
    }
    groups.push(side);
    plan.groups = groups;
    finish(
        "banquet-hall-synth",
        "banquet hall",
        "a banquet hall with round tables and a buffet",
        Room::rect(2400.0, 1800.0),
        assets,
        objects,
        plan,
    )
}

fn finish(
    id: &str,
    room_type: &str,
    prompt: &str,
    room: Room,
    assets: Vec<Asset>,
    objects: Vec<PlacedObject>,
    plan: Plan,
) -> (SceneSpec, Layout) {
    let scene = SceneSpec {
        id: id.to_string(),
        prompt: prompt.to_string(),
        room_type: room_type.to_string(),
        room: room.clone(),
        assets,
    };
    let layout = Layout {
        id: id.to_string(),
        room,
        objects,
        dropped: Vec::new(),
        plan: plan.into(),
        stats: Stats::default(),
    };
    (scene, layout)
}

/// A copy of `layout` with every pose perturbed, the way a model's raw answer is off: centres moved
/// by up to `shift_cm` on each axis and rotations by up to `turn_deg` (seeded, reproducible).
pub fn jitter(layout: &Layout, seed: u64, shift_cm: f64, turn_deg: f64) -> Layout {
    let mut rng = fastrand::Rng::with_seed(seed);
    let mut noisy = layout.clone();
    for o in &mut noisy.objects {
        let mut r = || rng.f64() * 2.0 - 1.0;
        o.position[0] += r() * shift_cm;
        o.position[1] += r() * shift_cm;
        o.rotation += r() * turn_deg;
    }
    noisy
}

/// The kinds of furniture [`crowded_room`] repeats, in order, as (category, width, depth):
/// each line is one unit placed together (an anchor and what goes with it).
const CROWD_UNITS: &[&[(&str, f64, f64)]] = &[
    &[
        ("dining table", 160.0, 90.0),
        ("dining chair", 45.0, 50.0),
        ("dining chair", 45.0, 50.0),
        ("dining chair", 45.0, 50.0),
        ("dining chair", 45.0, 50.0),
    ],
    &[("desk", 120.0, 60.0), ("office chair", 50.0, 50.0)],
    &[("bookshelf", 90.0, 35.0)],
    &[("sofa", 200.0, 90.0), ("coffee table", 100.0, 50.0)],
    &[("potted plant", 45.0, 45.0)],
    &[("armchair", 80.0, 80.0)],
    &[("cabinet", 100.0, 45.0)],
];

/// A scene of `objects` pieces of everyday furniture (dining sets, desks with chairs, sofas with
/// coffee tables, shelves, plants, armchairs, cabinets, repeated in that order) in a 4:3 room
/// sized so that they cover `cover` (0..1) of its floor: the big scenes the growth curve of
/// `disco perf` is measured on. Deterministic.
pub fn crowded_room(objects: usize, cover: f64) -> SceneSpec {
    let mut assets: Vec<Asset> = Vec::with_capacity(objects);
    let mut units = CROWD_UNITS.iter().cycle();
    while assets.len() < objects {
        let Some(unit) = units.next() else { break };
        for &(category, w, d) in unit.iter() {
            if assets.len() == objects {
                break;
            }
            let height = if category.contains("table") || category == "desk" {
                75.0
            } else {
                90.0
            };
            let name = format!("{category}-{}", assets.len());
            assets.push(Asset::new(&name, category, [w, d, height]));
        }
    }
    let covered: f64 = assets.iter().map(|a| a.size[0] * a.size[1]).sum();
    let area = covered / cover.clamp(0.01, 0.9);
    // width : depth = 4 : 3, and never narrower than the largest unit needs.
    let depth = ((area * 3.0 / 4.0).sqrt()).max(400.0).round();
    let width = (area / depth).max(400.0).round();
    SceneSpec {
        id: format!("crowded-{objects}"),
        prompt: format!("a large room with {objects} pieces of furniture"),
        room_type: "hall".to_string(),
        room: Room::rect(width, depth),
        assets,
    }
}

/// An L-shaped room for tests and examples: 600 x 450 cm without its top-right 250 x 150 cm, six
/// walls, the inner corner at (350, 300).
pub fn l_shaped_room() -> Room {
    Room::from_polygon(vec![
        [0.0, 0.0],
        [600.0, 0.0],
        [600.0, 300.0],
        [350.0, 300.0],
        [350.0, 450.0],
        [0.0, 450.0],
    ])
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_crowded_room_has_its_objects_at_the_asked_cover() {
        for n in [1, 10, 137, 1000] {
            let scene = crowded_room(n, 0.3);
            assert_eq!(scene.assets.len(), n);
            let covered: f64 = scene.assets.iter().map(|a| a.size[0] * a.size[1]).sum();
            let cover = covered / scene.room.area();
            assert!(cover <= 0.31, "{n}: {cover}");
            if n >= 100 {
                assert!(cover >= 0.29, "{n}: {cover}");
            }
        }
        let names: std::collections::HashSet<_> = crowded_room(500, 0.3)
            .assets
            .into_iter()
            .map(|a| a.name)
            .collect();
        assert_eq!(names.len(), 500);
    }
}
