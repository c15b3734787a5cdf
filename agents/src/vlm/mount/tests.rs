use serde_json::json;

use super::*;
use crate::fixtures::plan_holding;
use disco_core::geometry3d::{opening_problem, surface_problem, wall_problem};
use disco_core::room::Window;

/// The synthetic bedroom (bed's head on the top wall, wall 2; a nightstand each side) with a
/// table lamp, a painting and a wall clock added.
fn bedroom_with_decor() -> (SceneSpec, Vec<PlacedObject>) {
    let (mut scene, layout) = disco_core::synth::bedroom();
    scene.assets.extend([
        Asset::new("lamp-0", "table lamp", [30.0, 30.0, 50.0]),
        Asset::new("painting-0", "framed painting", [100.0, 4.0, 70.0]),
        Asset::new("clock-0", "wall clock", [35.0, 5.0, 35.0]),
    ]);
    (scene, layout.objects)
}

#[test]
fn only_scenes_and_plans_with_pieces_off_the_floor_count() {
    let (synth, layout) = disco_core::synth::bedroom();
    // Its floor lamp is 160 cm tall: a floor lamp, so the synthetic bedroom keeps its prompts.
    assert!(!leaves_floor(&synth));
    assert!(!plan_leaves_floor(&layout.plan, &layout.objects));
    let (scene, _) = bedroom_with_decor();
    assert!(leaves_floor(&scene));
    let lamp = scene.asset("lamp-0").unwrap();
    assert_eq!(
        leaving_words(&scene, lamp).as_deref(),
        Some(
            "usually stands on another piece's top (here: nightstand-0, nightstand-1, desk-0, dresser-0)"
        )
    );
    let painting = scene.asset("painting-0").unwrap();
    assert_eq!(
        leaving_words(&scene, painting).as_deref(),
        Some("usually hangs on a wall (above one of: bed-0, desk-0, dresser-0)")
    );
    assert_eq!(leaving_words(&scene, scene.asset("bed-0").unwrap()), None);
    let plan = plan_holding(&[("lamp-0", Support::Surface, None)]);
    assert!(plan_leaves_floor(&plan, &[]));
}

#[test]
fn what_holds_an_object_is_said_in_words() {
    let lamp = PlacedObject {
        name: "lamp-0".into(),
        elevation: 55.0,
        on: Some("nightstand-0".into()),
        ..Default::default()
    };
    assert_eq!(
        held_words(&lamp).as_deref(),
        Some("on top of nightstand-0, its bottom 55 cm above the floor")
    );
    let painting = PlacedObject {
        elevation: 120.5,
        wall: Some(2),
        ..Default::default()
    };
    assert_eq!(
        held_words(&painting).as_deref(),
        Some("hung on wall 2, its bottom 120.5 cm above the floor")
    );
    assert_eq!(held_words(&PlacedObject::default()), None);
}

#[test]
fn the_designer_is_told_what_the_plan_says_holds_a_piece() {
    let (scene, placed) = bedroom_with_decor();
    let plan = plan_holding(&[
        (
            "lamp-0",
            Support::Surface,
            Some((Relation::On, "nightstand-0")),
        ),
        (
            "painting-0",
            Support::Wall,
            Some((Relation::Above, "bed-0")),
        ),
        ("clock-0", Support::Wall, None),
    ]);
    let lamp = held_request(&scene, &plan, "lamp-0", &placed).unwrap();
    assert_eq!(
        lamp,
        "it leaves the floor: answer \"on\": \"nightstand-0\" (its top: 50 x 40 cm, 55 cm high), or the name of another piece whose top suits it better"
    );
    let painting = held_request(&scene, &plan, "painting-0", &placed).unwrap();
    assert!(
        painting.ends_with(
            "answer \"above\": \"bed-0\" and \"wall\": 2, the wall bed-0 stands against"
        ),
        "{painting}"
    );
    let clock = held_request(&scene, &plan, "clock-0", &[]).unwrap();
    assert!(clock.contains("with a free stretch for it"), "{clock}");
    assert_eq!(held_request(&scene, &plan, "bed-0", &placed), None);
}

#[test]
fn mounts_are_read_leniently_and_floor_poses_pass_through() {
    let (scene, _) = bedroom_with_decor();
    let all = NameMap::new(scene.assets.iter().map(|a| a.name.clone()));
    let held: HashSet<String> = ["lamp-0", "painting-0", "clock-0"].map(String::from).into();
    let mut names = NameMap::new(["desk-0", "lamp-0", "painting-0", "clock-0"].map(String::from));
    let v = json!({"objects": [
        {"name": "desk-0", "position": [320, 30], "rotation": 0},
        {"name": "Lamp 0", "on": "nightstand 0"},
        {"name": "painting-0", "wall": "wall 2", "above": "bed-0"},
        {"name": "clock-0", "wall": 9, "on": "unicorn"},
    ]});
    let (rest, mounts, notes) = read_mounts(&v, &mut names, &held, &all, 4).unwrap();
    assert_eq!(rest["objects"].as_array().unwrap().len(), 1);
    assert_eq!(rest["objects"][0]["name"], "desk-0");
    assert_eq!(
        mounts[0],
        ReadMount {
            name: "lamp-0".into(),
            on: Some("nightstand-0".into()),
            ..Default::default()
        }
    );
    assert_eq!(mounts[1].wall, Some(2));
    assert_eq!(mounts[1].above.as_deref(), Some("bed-0"));
    assert_eq!(mounts[2].wall, None, "the room has no wall 9");
    assert_eq!(mounts[2].on, None, "the scene has no unicorn");
    assert_eq!(notes.len(), 2, "{notes:?}");
    assert_eq!(
        names.missing(),
        ["desk-0"],
        "the pose reader takes the desk"
    );
}

#[test]
fn named_supports_and_walls_become_exact_poses() {
    let (mut scene, placed) = bedroom_with_decor();
    let plan = plan_holding(&[
        (
            "lamp-0",
            Support::Surface,
            Some((Relation::On, "nightstand-0")),
        ),
        (
            "painting-0",
            Support::Wall,
            Some((Relation::Above, "bed-0")),
        ),
        ("clock-0", Support::Wall, None),
    ]);
    let assets = scene.assets.clone();
    let asset = |n: &str| assets.iter().find(|a| a.name == n).unwrap().clone();
    // On the other nightstand, as the model said: at its top's height, within it.
    let said = ReadMount {
        name: "lamp-0".into(),
        on: Some("nightstand-1".into()),
        ..Default::default()
    };
    let (lamp, note) = pose_held(&scene, &plan, &asset("lamp-0"), &said, &placed);
    let stand = placed.iter().find(|o| o.name == "nightstand-1").unwrap();
    assert_eq!(note, None);
    assert_eq!(lamp.on.as_deref(), Some("nightstand-1"));
    assert_eq!(lamp.elevation, 55.0);
    assert!(surface_problem(&lamp, stand).is_none(), "{lamp:?}");
    // Above the bed: on the bed's wall, centred, 20 cm over its top.
    let said = ReadMount {
        name: "painting-0".into(),
        wall: Some(2),
        above: Some("bed-0".into()),
        ..Default::default()
    };
    let (painting, _) = pose_held(&scene, &plan, &asset("painting-0"), &said, &placed);
    assert_eq!(painting.wall, Some(2));
    assert!((painting.position[0] - 200.0).abs() < 1e-6, "{painting:?}");
    assert_eq!(painting.elevation, 120.0);
    // On wall 1 (the right one, x = 400) near where the model pointed, its centre at 190 cm,
    // slid off a window there.
    scene.room.windows.push(Window {
        wall: 1,
        at: 100.0,
        width: 80.0,
        sill: 90.0,
        height: 140.0,
    });
    let said = ReadMount {
        name: "clock-0".into(),
        wall: Some(1),
        position: Some([400.0, 100.0]),
        ..Default::default()
    };
    let mut with_painting = placed.clone();
    with_painting.push(painting);
    let (clock, note) = pose_held(&scene, &plan, &asset("clock-0"), &said, &with_painting);
    assert_eq!(note, None);
    assert_eq!(clock.wall, Some(1));
    assert_eq!(clock.elevation, 190.0 - 17.5);
    assert!(wall_problem(&clock, &scene.room, 1).is_none());
    assert!(opening_problem(&clock, &scene.room, 1).is_none());
    assert!(
        (clock.position[1] - 100.0).abs() >= 40.0 + 17.5 - 1e-6,
        "slid off the window: {clock:?}"
    );
    assert!(
        (clock.position[1] - 100.0).abs() <= 40.0 + 17.5 + STEP_CM,
        "{clock:?}"
    );
}

#[test]
fn a_support_that_does_not_stand_or_no_answer_falls_back_to_the_plan() {
    let (scene, placed) = bedroom_with_decor();
    let plan = plan_holding(&[(
        "lamp-0",
        Support::Surface,
        Some((Relation::On, "nightstand-0")),
    )]);
    let lamp = scene.asset("lamp-0").unwrap();
    let said = ReadMount {
        name: "lamp-0".into(),
        on: Some("painting-0".into()),
        ..Default::default()
    };
    let (o, note) = pose_held(&scene, &plan, lamp, &said, &placed);
    assert!(note.unwrap().contains("painting-0 does not stand yet"));
    assert_eq!(o.on.as_deref(), Some("nightstand-0"), "the plan's support");
    assert_eq!(o.elevation, 55.0);
    let (o, note) = pose_held(
        &scene,
        &plan,
        lamp,
        &ReadMount {
            name: "lamp-0".into(),
            ..Default::default()
        },
        &placed,
    );
    assert!(note.unwrap().contains("named no top or wall"));
    assert_eq!(o.on.as_deref(), Some("nightstand-0"));

    // Only a point, as for a floor piece: the top under it, or the wall nearest it.
    let nightstand_1 = placed.iter().find(|o| o.name == "nightstand-1").unwrap();
    let said = ReadMount {
        name: "lamp-0".into(),
        position: Some(nightstand_1.position),
        ..Default::default()
    };
    let (o, note) = pose_held(&scene, &plan, lamp, &said, &placed);
    assert_eq!(note, None);
    assert_eq!(o.on.as_deref(), Some("nightstand-1"));
    let plan = plan_holding(&[("clock-0", Support::Wall, None)]);
    let said = ReadMount {
        name: "clock-0".into(),
        position: Some([390.0, 180.0]),
        ..Default::default()
    };
    let clock = scene.asset("clock-0").unwrap();
    let (o, note) = pose_held(&scene, &plan, clock, &said, &placed);
    assert_eq!(note, None);
    assert_eq!(o.wall, Some(1), "the right wall, nearest the point: {o:?}");
}
