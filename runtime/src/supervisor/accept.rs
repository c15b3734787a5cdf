//! What a reply must be before the scene loop takes it: the checks each [`RoleCall`] applies in
//! its `accept` (names known and once, numbers finite and bounded, sizes unchanged, drops with a
//! reason, every object of a PRT's layout back exactly once and the result physically valid),
//! the caps on notes, and the last check of the final layout (every asset exactly once).
//!
//! A check that fails is a [`RoleError::Refused`] with the reason: the loop retries the call,
//! then hands it to the fallback (and, for a PRT, to the built-in grid PRT last).
//!
//! [`RoleCall`]: super::messages::RoleCall

use std::collections::{HashMap, HashSet};

use disco_core::geometry3d;
use disco_core::layout::{Dropped, MAX_ELEVATION_CM, PlacedObject};
use disco_core::roles::{Evaluation, Move, Question, Refined, RoleError};
use disco_core::room::ZoneKind;
use disco_core::scene::{Asset, Room, SceneSpec};

/// How far outside the room's bounding box a position may lie, as a fraction of the box's side:
/// a designer's first guess may stand a little outside (the PRT brings it in); beyond half a
/// room it is noise, not a pose (the model readers use the same bound).
pub const POSITION_MARGIN: f64 = 0.5;

/// The largest rotation taken, in degrees either way (ten turns): beyond that it is noise.
pub const MAX_ROTATION_DEG: f64 = 3600.0;

/// The most notes one reply adds to the layout; the rest are cut, and a note says how many.
pub const MAX_REPLY_NOTES: usize = 32;

/// The most notes a layout keeps in all; the rest are cut, and a note says how many.
pub const MAX_SCENE_NOTES: usize = 400;

/// The longest note, reason or answer kept, in characters; longer ones are cut with `…`.
pub const MAX_TEXT_CHARS: usize = 400;

/// The longest name quoted in a refusal, in characters.
const QUOTED_NAME_CHARS: usize = 60;

/// How far two poses may differ and still be the same pose (an echo of where an object stands).
const SAME_POSE_EPS: f64 = 1e-6;

fn refused(reason: String) -> RoleError {
    RoleError::Refused(reason)
}

/// `text` cut to `max` characters, with `…` when it was longer.
pub fn clip(text: &str, max: usize) -> String {
    match text.char_indices().nth(max) {
        None => text.to_string(),
        Some((at, _)) => format!("{}…", &text[..at]),
    }
}

/// A number as written in a refusal: short, 1e308 included.
fn num(v: f64) -> String {
    if v.is_finite() && v.abs() < 1e7 {
        format!("{v}")
    } else {
        format!("{v:e}")
    }
}

/// A name as quoted in a refusal: short, so that a reply cannot fill the notes.
fn quoted(name: &str) -> String {
    format!("{:?}", clip(name, QUOTED_NAME_CHARS))
}

/// Caps `incoming` at [`MAX_REPLY_NOTES`] notes of at most [`MAX_TEXT_CHARS`] characters;
/// returns the kept notes, ending with one that says how many were cut, if any were.
pub fn cap_notes(incoming: Vec<String>) -> Vec<String> {
    let total = incoming.len();
    let mut kept: Vec<String> = incoming
        .into_iter()
        .take(MAX_REPLY_NOTES)
        .map(|n| clip(&n, MAX_TEXT_CHARS))
        .collect();
    if total > MAX_REPLY_NOTES {
        kept.push(format!(
            "{} more notes of this reply were cut (at most {MAX_REPLY_NOTES} are kept)",
            total - MAX_REPLY_NOTES
        ));
    }
    kept
}

/// Caps a layout's notes at [`MAX_SCENE_NOTES`], saying how many were cut.
pub fn cap_scene_notes(notes: &mut Vec<String>) {
    if notes.len() > MAX_SCENE_NOTES {
        let cut = notes.len() - MAX_SCENE_NOTES;
        notes.truncate(MAX_SCENE_NOTES);
        notes.push(format!(
            "{cut} more notes were cut (a layout keeps at most {MAX_SCENE_NOTES})"
        ));
    }
}

/// The scene's assets by name.
fn assets(scene: &SceneSpec) -> HashMap<&str, &Asset> {
    scene.assets.iter().map(|a| (a.name.as_str(), a)).collect()
}

/// A position finite and within the room's bounding box enlarged by [`POSITION_MARGIN`]; a
/// rotation finite and within [`MAX_ROTATION_DEG`].
fn check_pose(room: &Room, o: &PlacedObject) -> Result<(), RoleError> {
    let [x, y] = o.position;
    let within = |v: f64, side: f64| {
        v.is_finite() && v >= -POSITION_MARGIN * side && v <= (1.0 + POSITION_MARGIN) * side
    };
    if !within(x, room.width) || !within(y, room.depth) {
        return Err(refused(format!(
            "{} at [{}, {}] is far outside the {} x {} cm room",
            quoted(&o.name),
            num(x),
            num(y),
            room.width,
            room.depth
        )));
    }
    if !(o.rotation.is_finite() && o.rotation.abs() <= MAX_ROTATION_DEG) {
        return Err(refused(format!(
            "{} has rotation {} (at most {MAX_ROTATION_DEG} degrees either way)",
            quoted(&o.name),
            num(o.rotation)
        )));
    }
    Ok(())
}

/// What holds `o`, when it is off the floor: an `elevation` finite and within
/// [`MAX_ELEVATION_CM`], `on` naming another object of the scene, `wall` a wall of the room,
/// never both.
fn check_mount(scene: &SceneSpec, o: &PlacedObject) -> Result<(), RoleError> {
    if !(o.elevation.is_finite() && (0.0..=MAX_ELEVATION_CM).contains(&o.elevation)) {
        return Err(refused(format!(
            "{} has elevation {} (0 to {MAX_ELEVATION_CM} cm)",
            quoted(&o.name),
            num(o.elevation)
        )));
    }
    if o.on.is_some() && o.wall.is_some() {
        return Err(refused(format!(
            "{} both stands on an object and hangs on a wall",
            quoted(&o.name)
        )));
    }
    if let Some(on) = &o.on
        && (on == &o.name || scene.asset(on).is_none())
    {
        return Err(refused(format!(
            "{} stands on {}, which is not another object of the scene",
            quoted(&o.name),
            quoted(on)
        )));
    }
    let walls = scene.room.walls().len();
    if let Some(w) = o.wall
        && w >= walls
    {
        return Err(refused(format!(
            "{} hangs on wall {w}; the room has {walls}",
            quoted(&o.name)
        )));
    }
    Ok(())
}

/// The object as the scene has it: a changed size or category is refused (the scene's win).
fn canonical(asset: &Asset, o: &PlacedObject) -> Result<PlacedObject, RoleError> {
    if o.size != asset.size || o.category != asset.category {
        return Err(refused(format!(
            "{} came back as a {:?} of {:?} cm; the scene has a {:?} of {:?} cm",
            quoted(&o.name),
            clip(&o.category, QUOTED_NAME_CHARS),
            o.size,
            asset.category,
            asset.size
        )));
    }
    Ok(PlacedObject {
        name: asset.name.clone(),
        category: asset.category.clone(),
        size: asset.size,
        position: o.position,
        rotation: disco_core::geometry::normalize_degrees(o.rotation),
        elevation: o.elevation,
        on: o.on.clone(),
        wall: o.wall,
    })
}

/// Whether two rotations differ (modulo whole turns).
fn turned(a: f64, b: f64) -> bool {
    let turn = disco_core::geometry::normalize_degrees(a - b);
    turn.min(360.0 - turn) > SAME_POSE_EPS
}

fn same_pose(a: &PlacedObject, b: &PlacedObject) -> bool {
    (a.position[0] - b.position[0]).abs() <= SAME_POSE_EPS
        && (a.position[1] - b.position[1]).abs() <= SAME_POSE_EPS
        && !turned(a.rotation, b.rotation)
        && (a.elevation - b.elevation).abs() <= SAME_POSE_EPS
        && a.on == b.on
        && a.wall == b.wall
}

/// Accepts the poses of a designer, SRT or custom stage: each names an object of the scene, once,
/// with a finite, bounded pose and the scene's size and category. Only objects of `movable` may
/// get a new pose; an entry for another object that leaves it where it stands in `current` is an
/// echo, left out. An empty list is a valid reply (nothing to move).
pub fn poses(
    scene: &SceneSpec,
    movable: &[String],
    current: &[PlacedObject],
    reply: Vec<PlacedObject>,
) -> Result<Vec<PlacedObject>, RoleError> {
    let assets = assets(scene);
    let movable: HashSet<&str> = movable.iter().map(String::as_str).collect();
    let current: HashMap<&str, &PlacedObject> =
        current.iter().map(|o| (o.name.as_str(), o)).collect();
    let mut seen: HashSet<String> = HashSet::new();
    let mut out = Vec::with_capacity(reply.len());
    for o in reply {
        let Some(asset) = assets.get(o.name.as_str()) else {
            return Err(refused(format!(
                "{} is not an object of the scene",
                quoted(&o.name)
            )));
        };
        if !seen.insert(o.name.clone()) {
            return Err(refused(format!("{} is posed twice", quoted(&o.name))));
        }
        check_pose(&scene.room, &o)?;
        check_mount(scene, &o)?;
        let o = canonical(asset, &o)?;
        if !movable.contains(o.name.as_str()) {
            match current.get(o.name.as_str()) {
                Some(now) if same_pose(now, &o) => continue,
                _ => {
                    return Err(refused(format!(
                        "{} is not among the objects this call may move",
                        quoted(&o.name)
                    )));
                }
            }
        }
        out.push(o);
    }
    Ok(out)
}

/// Accepts an evaluator's answers: each to a question asked, at most once; reasons are cut to
/// [`MAX_TEXT_CHARS`]. A question left unanswered counts as failed (the loop's rule).
pub fn answers(questions: &[Question], mut reply: Evaluation) -> Result<Evaluation, RoleError> {
    let asked: HashSet<usize> = questions.iter().map(|q| q.id).collect();
    let mut seen = HashSet::new();
    for a in &mut reply.answers {
        if !asked.contains(&a.id) {
            return Err(refused(format!(
                "it answers question {}, which was not asked",
                a.id
            )));
        }
        if !seen.insert(a.id) {
            return Err(refused(format!("it answers question {} twice", a.id)));
        }
        a.reason = clip(&a.reason, MAX_TEXT_CHARS);
    }
    Ok(reply)
}

/// Accepts a PRT's answer to `given`: every object of the layout it was given comes back exactly
/// once, placed or dropped; nothing else comes back; each placed one has a finite pose and the
/// scene's size and category; each dropped one has a reason; the placed ones are physically valid
/// (no two collide, floor coverings included among themselves, each stands inside the room and out
/// of the doors' and windows' keep-clear zones).
/// The moves are recomputed from `given` and the notes capped.
pub fn refined(
    scene: &SceneSpec,
    given: &[PlacedObject],
    reply: Refined,
) -> Result<Refined, RoleError> {
    let assets = assets(scene);
    let given_names: HashSet<&str> = given.iter().map(|o| o.name.as_str()).collect();
    let known = |name: &str| -> Result<(), RoleError> {
        if !assets.contains_key(name) {
            return Err(refused(format!(
                "{} is not an object of the scene",
                quoted(name)
            )));
        }
        if !given_names.contains(name) {
            return Err(refused(format!(
                "{} was not in the layout it was given",
                quoted(name)
            )));
        }
        Ok(())
    };
    let mut placed_names: HashSet<String> = HashSet::new();
    let mut objects = Vec::with_capacity(reply.objects.len());
    for o in reply.objects {
        known(&o.name)?;
        if !placed_names.insert(o.name.clone()) {
            return Err(refused(format!("{} is placed twice", quoted(&o.name))));
        }
        check_pose(&scene.room, &o)?;
        check_mount(scene, &o)?;
        objects.push(canonical(assets[o.name.as_str()], &o)?);
    }
    let mut dropped_names: HashSet<String> = HashSet::new();
    let mut dropped = Vec::with_capacity(reply.dropped.len());
    for d in reply.dropped {
        known(&d.name)?;
        if placed_names.contains(&d.name) {
            return Err(refused(format!(
                "{} is both placed and dropped",
                quoted(&d.name)
            )));
        }
        if !dropped_names.insert(d.name.clone()) {
            return Err(refused(format!("{} is dropped twice", quoted(&d.name))));
        }
        if d.reason.trim().is_empty() {
            return Err(refused(format!(
                "{} is dropped without a reason",
                quoted(&d.name)
            )));
        }
        dropped.push(Dropped {
            reason: clip(&d.reason, MAX_TEXT_CHARS),
            name: d.name,
        });
    }
    let missing: Vec<&str> = given
        .iter()
        .map(|o| o.name.as_str())
        .filter(|n| !placed_names.contains(*n) && !dropped_names.contains(*n))
        .collect();
    if let Some(first) = missing.first() {
        return Err(refused(format!(
            "{} of the {} objects it was given came back neither placed nor dropped (first: {})",
            missing.len(),
            given.len(),
            quoted(first)
        )));
    }
    physically_valid(&scene.room, &objects)?;
    let moves = objects.iter().map(|o| Move::between(given, o)).collect();
    Ok(Refined {
        objects,
        dropped,
        moves,
        notes: cap_notes(reply.notes),
    })
}

/// No two solid objects collide (in 3D: a lamp on a nightstand does not collide with it), no two
/// floor coverings overlap, every object on the floor stands inside the room and none taller than
/// a zone allows stands in a door's or window's keep-clear zone, and every object off the floor
/// is held where it is (on its support's top, or on its wall clear of the openings): the PRT's
/// promise (Col 0, OOB 0, doors and windows free, nothing floating), as the built-in grid PRT
/// keeps it.
fn physically_valid(room: &Room, objects: &[PlacedObject]) -> Result<(), RoleError> {
    let footprints: Vec<_> = objects.iter().map(PlacedObject::footprint).collect();
    let zones = room.keep_clear();
    let by_name: HashMap<&str, &PlacedObject> =
        objects.iter().map(|o| (o.name.as_str(), o)).collect();
    for (o, f) in objects.iter().zip(&footprints) {
        if let Some(why) = geometry3d::support_problem(o, &by_name, room)
            .or_else(|| o.wall.and_then(|w| geometry3d::opening_problem(o, room, w)))
        {
            return Err(refused(format!("{} {why}", quoted(&o.name))));
        }
        if !o.on_floor() {
            continue;
        }
        if let Some(z) = zones.iter().find(|z| f.intrudes(z, o.size[2])) {
            let whose = match z.kind {
                ZoneKind::Door(i) => format!("door {i}"),
                ZoneKind::Window(i) => format!("window {i}"),
            };
            return Err(refused(format!(
                "{} stands in the keep-clear zone of {whose}",
                quoted(&o.name)
            )));
        }
        if !f.inside(room) {
            return Err(refused(format!(
                "{} at [{}, {}] does not stand inside the room",
                quoted(&o.name),
                num(o.position[0]),
                num(o.position[1])
            )));
        }
    }
    for (i, (a, fa)) in objects.iter().zip(&footprints).enumerate() {
        for (b, fb) in objects[i + 1..].iter().zip(&footprints[i + 1..]) {
            // A floor covering may lie under furniture, not under another covering.
            if a.is_flat() == b.is_flat() && geometry3d::heights_overlap(a, b) && fa.collides(fb) {
                return Err(refused(format!(
                    "{} and {} collide",
                    quoted(&a.name),
                    quoted(&b.name)
                )));
            }
        }
    }
    Ok(())
}

/// The final layout's objects and drops, every asset of `scene` exactly once, in scene order:
/// poses of unknown or repeated names are removed, drops of unknown, repeated or placed names too,
/// an empty reason gets one, and an asset found in neither is dropped with a reason. `notes` says
/// what was changed. (The replies were accepted already, so this is the last guard, not the rule.)
pub fn complete(
    scene: &SceneSpec,
    placed: Vec<PlacedObject>,
    dropped: Vec<Dropped>,
    notes: &mut Vec<String>,
) -> (Vec<PlacedObject>, Vec<Dropped>) {
    let known: HashSet<&str> = scene.assets.iter().map(|a| a.name.as_str()).collect();
    let mut by_name: HashMap<String, PlacedObject> = HashMap::new();
    for o in placed {
        if !known.contains(o.name.as_str()) {
            notes.push(format!(
                "removed a pose of unknown object {}",
                quoted(&o.name)
            ));
        } else if by_name.contains_key(&o.name) {
            notes.push(format!("removed a second pose of {}", quoted(&o.name)));
        } else {
            by_name.insert(o.name.clone(), o);
        }
    }
    let mut drops: HashMap<String, Dropped> = HashMap::new();
    for mut d in dropped {
        if !known.contains(d.name.as_str()) {
            notes.push(format!(
                "removed a drop of unknown object {}",
                quoted(&d.name)
            ));
        } else if by_name.contains_key(&d.name) {
            notes.push(format!(
                "{} was both placed and dropped; it stays placed",
                quoted(&d.name)
            ));
        } else if drops.contains_key(&d.name) {
            notes.push(format!("removed a second drop of {}", quoted(&d.name)));
        } else {
            if d.reason.trim().is_empty() {
                d.reason = "dropped without a reason given".into();
            }
            drops.insert(d.name.clone(), d);
        }
    }
    let mut objects = Vec::with_capacity(by_name.len());
    let mut out_dropped = Vec::with_capacity(drops.len());
    for a in &scene.assets {
        if let Some(o) = by_name.remove(&a.name) {
            objects.push(o);
        } else if let Some(d) = drops.remove(&a.name) {
            out_dropped.push(d);
        } else {
            out_dropped.push(Dropped {
                name: a.name.clone(),
                reason: "no stage produced a pose for it".into(),
            });
        }
    }
    (objects, out_dropped)
}

#[cfg(test)]
mod tests;
