//! Each acceptance against the replies a misbehaving role gives.

use std::collections::HashSet;

use super::*;
use disco_core::roles::Answer;
use disco_core::synth;
use disco_tools::prt::{PhysicalRefiner, PrtConfig};

fn bedroom() -> (SceneSpec, Vec<PlacedObject>) {
    let (scene, layout) = synth::bedroom();
    (scene, layout.objects)
}

/// What the built-in PRT makes of the bedroom: a valid reply.
fn valid_refined(scene: &SceneSpec, given: &[PlacedObject]) -> Refined {
    PhysicalRefiner::new(PrtConfig::default()).refine_settled(
        &scene.room,
        given,
        &disco_core::plan::Plan::default(),
        &HashSet::new(),
    )
}

fn refusal(r: Result<impl std::fmt::Debug, RoleError>) -> String {
    match r {
        Err(RoleError::Refused(why)) => why,
        other => panic!("expected a refusal, got {other:?}"),
    }
}

#[test]
fn poses_name_known_objects_once_with_bounded_numbers_and_the_scenes_sizes() {
    let (scene, current) = bedroom();
    let group = vec!["bed-0".to_string(), "desk-0".to_string()];
    let bed = current[0].clone();
    let accept = |reply: Vec<PlacedObject>| poses(&scene, &group, &current, reply);

    // A good reply: taken, rotation normalised, the scene's category.
    let mut turned = bed.clone();
    turned.rotation = -90.0;
    let ok = accept(vec![turned]).unwrap();
    assert_eq!(ok.len(), 1);
    assert_eq!(ok[0].rotation, 270.0);
    // Nothing to move is an answer too.
    assert!(accept(Vec::new()).unwrap().is_empty());

    let mut ghost = bed.clone();
    ghost.name = "ghost".into();
    assert!(refusal(accept(vec![ghost])).contains("\"ghost\" is not an object of the scene"));
    assert!(refusal(accept(vec![bed.clone(), bed.clone()])).contains("posed twice"));
    for (position, written) in [
        ([-500.0, -500.0], "[-500, -500]"),
        ([1e308, 10.0], "[1e308, 10]"),
        ([f64::NAN, 10.0], "[NaN, 10]"),
    ] {
        let mut far = bed.clone();
        far.position = position;
        let why = refusal(accept(vec![far]));
        assert!(
            why.contains(&format!("\"bed-0\" at {written} is far outside the")),
            "{why}"
        );
    }
    let mut spun = bed.clone();
    spun.rotation = 1e308;
    assert!(refusal(accept(vec![spun])).contains("rotation"));
    let mut grown = bed.clone();
    grown.size[0] *= 2.0;
    assert!(refusal(accept(vec![grown])).contains("the scene has a \"bed\""));
    let mut renamed = bed.clone();
    renamed.category = "sofa".into();
    assert!(refusal(accept(vec![renamed])).contains("came back as a \"sofa\""));

    // An object outside the group: an echo of where it stands is left out, a move refused.
    let lamp = current[8].clone();
    assert!(accept(vec![lamp.clone()]).unwrap().is_empty());
    let mut moved = lamp;
    moved.position[0] += 10.0;
    assert!(refusal(accept(vec![moved])).contains("not among the objects this call may move"));
}

#[test]
fn a_long_ghost_name_is_quoted_short() {
    let (scene, current) = bedroom();
    let mut ghost = current[0].clone();
    ghost.name = "x".repeat(1_000_000);
    let why = refusal(poses(&scene, &[], &current, vec![ghost]));
    assert!(why.len() < 200, "{} characters", why.len());
}

#[test]
fn answers_are_to_questions_asked_once_each() {
    let questions: Vec<Question> = (0..2)
        .map(|id| Question {
            id,
            text: format!("q{id}"),
            subject: None,
            constraint: None,
        })
        .collect();
    let answer = |id: usize, reason: &str| Answer {
        id,
        yes: true,
        reason: reason.into(),
    };
    let eval = |answers: Vec<Answer>| Evaluation {
        answers,
        needs_physical: false,
    };
    let long = "y".repeat(10 * MAX_TEXT_CHARS);
    let ok = answers(&questions, eval(vec![answer(1, &long)])).unwrap();
    assert_eq!(ok.answers[0].reason.chars().count(), MAX_TEXT_CHARS + 1);
    assert!(refusal(answers(&questions, eval(vec![answer(7, "")]))).contains("question 7"));
    assert!(
        refusal(answers(
            &questions,
            eval(vec![answer(0, ""), answer(0, "")])
        ))
        .contains("twice")
    );
}

#[test]
fn a_prt_reply_has_every_object_once_placed_validly_or_dropped_with_a_reason() {
    let (scene, given) = bedroom();
    let good = valid_refined(&scene, &given);
    let accept = |r: Refined| refined(&scene, &given, r);
    let ok = accept(good.clone()).unwrap();
    assert_eq!(ok.objects.len() + ok.dropped.len(), given.len());
    assert_eq!(ok.moves.len(), ok.objects.len());

    // Every object at (-500, -500), or at 1e308.
    for position in [[-500.0, -500.0], [1e308, 1e308]] {
        let mut far = good.clone();
        for o in &mut far.objects {
            o.position = position;
        }
        assert!(refusal(accept(far)).contains("far outside"), "{position:?}");
    }
    // Everything piled in the middle: inside the bounds, but colliding.
    let mut piled = good.clone();
    for o in &mut piled.objects {
        o.position = [scene.room.width / 2.0, scene.room.depth / 2.0];
    }
    assert!(refusal(accept(piled)).contains("collide"));
    // Each object placed and dropped, and a ghost dropped.
    let mut both = good.clone();
    both.dropped = given
        .iter()
        .map(|o| Dropped {
            name: o.name.clone(),
            reason: "too big".into(),
        })
        .collect();
    assert!(refusal(accept(both.clone())).contains("both placed and dropped"));
    both.objects.clear();
    both.dropped.push(Dropped {
        name: "ghost".into(),
        reason: "it is not there".into(),
    });
    assert!(refusal(accept(both)).contains("\"ghost\" is not an object of the scene"));
    // Everything dropped without a reason.
    let mut silent = good.clone();
    silent.objects.clear();
    silent.dropped = given
        .iter()
        .map(|o| Dropped {
            name: o.name.clone(),
            reason: " ".into(),
        })
        .collect();
    assert!(refusal(accept(silent)).contains("dropped without a reason"));
    // A placed ghost, a twice-placed object, an object left out.
    let mut ghost = good.clone();
    let mut g = ghost.objects[0].clone();
    g.name = "ghost".into();
    ghost.objects.push(g);
    assert!(refusal(accept(ghost)).contains("not an object of the scene"));
    let mut twice = good.clone();
    twice.objects.push(twice.objects[0].clone());
    assert!(refusal(accept(twice)).contains("placed twice"));
    let mut lost = good.clone();
    lost.objects.pop();
    assert!(refusal(accept(lost)).contains("1 of the 10 objects it was given came back neither"));
    // An object not in the layout it was given (the scene has it, the layout did not).
    let fewer = &given[1..];
    let r = refined(&scene, fewer, valid_refined(&scene, &given));
    assert!(refusal(r).contains("was not in the layout it was given"));
}

#[test]
fn a_prt_reply_with_lying_moves_and_endless_notes_is_taken_with_its_own_moves_and_capped_notes() {
    let (scene, given) = bedroom();
    let mut r = valid_refined(&scene, &given);
    for m in &mut r.moves {
        m.displacement_cm = f64::NAN;
    }
    r.notes = vec!["the same note".to_string(); 200_000];
    let ok = refined(&scene, &given, r).unwrap();
    assert!(ok.moves.iter().all(|m| m.displacement_cm.is_finite()));
    assert_eq!(ok.notes.len(), MAX_REPLY_NOTES + 1);
    assert!(
        ok.notes
            .last()
            .unwrap()
            .starts_with(&format!("{} more notes", 200_000 - MAX_REPLY_NOTES)),
        "{:?}",
        ok.notes.last()
    );
}

#[test]
fn notes_are_capped_in_count_and_length() {
    let kept = cap_notes(vec!["z".repeat(100_000)]);
    assert_eq!(kept[0].chars().count(), MAX_TEXT_CHARS + 1);
    assert!(kept[0].ends_with('…'));
    let mut scene_notes = vec![String::from("n"); MAX_SCENE_NOTES + 5];
    cap_scene_notes(&mut scene_notes);
    assert_eq!(scene_notes.len(), MAX_SCENE_NOTES + 1);
    assert!(scene_notes.last().unwrap().starts_with("5 more notes"));
}

#[test]
fn the_final_layout_has_every_asset_exactly_once() {
    let (scene, given) = bedroom();
    let mut placed = given.clone();
    placed.push(given[0].clone());
    let mut ghost = given[1].clone();
    ghost.name = "ghost".into();
    placed.push(ghost);
    placed.retain(|o| o.name != "rug-0" && o.name != "desk-0");
    let dropped = vec![
        Dropped {
            name: "bed-0".into(),
            reason: "both".into(),
        },
        Dropped {
            name: "rug-0".into(),
            reason: "".into(),
        },
        Dropped {
            name: "rug-0".into(),
            reason: "again".into(),
        },
        Dropped {
            name: "phantom".into(),
            reason: "never was".into(),
        },
    ];
    let mut notes = Vec::new();
    let (objects, dropped) = complete(&scene, placed, dropped, &mut notes);
    let mut names: Vec<&str> = objects
        .iter()
        .map(|o| o.name.as_str())
        .chain(dropped.iter().map(|d| d.name.as_str()))
        .collect();
    names.sort_unstable();
    let mut expected: Vec<&str> = scene.assets.iter().map(|a| a.name.as_str()).collect();
    expected.sort_unstable();
    assert_eq!(names, expected);
    assert!(objects.iter().any(|o| o.name == "bed-0"), "placed wins");
    let reason = |n: &str| dropped.iter().find(|d| d.name == n).unwrap().reason.clone();
    assert_eq!(reason("rug-0"), "dropped without a reason given");
    assert_eq!(reason("desk-0"), "no stage produced a pose for it");
    assert_eq!(notes.len(), 5, "{notes:?}");
}

#[test]
fn a_prt_reply_that_blocks_a_door_is_refused() {
    let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../examples/scenes/l-shaped-studio.json");
    let scene = SceneSpec::load(&path).unwrap();
    let zone = scene
        .room
        .keep_clear()
        .into_iter()
        .find(|z| matches!(z.kind, ZoneKind::Door(_)))
        .expect("the studio has a door");
    let centre = zone.corners.iter().copied().sum::<glam::DVec2>() / 4.0;
    // The smallest solid asset, alone in the room, in the middle of the door's zone.
    let asset = scene
        .assets
        .iter()
        .filter(|a| !a.is_flat())
        .min_by(|a, b| (a.size[0] * a.size[1]).total_cmp(&(b.size[0] * b.size[1])))
        .unwrap();
    let blocking = PlacedObject {
        name: asset.name.clone(),
        category: asset.category.clone(),
        size: asset.size,
        position: [centre.x, centre.y],
        rotation: 0.0,
        ..Default::default()
    };
    let given = vec![blocking.clone()];
    let reply = Refined {
        objects: given.clone(),
        dropped: Vec::new(),
        moves: Vec::new(),
        notes: Vec::new(),
    };
    let why = refusal(refined(&scene, &given, reply));
    assert!(
        why.contains("stands in the keep-clear zone of door"),
        "{why}"
    );
}
