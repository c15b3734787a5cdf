//! The layout: where every asset ended up (docs/formats.md, "The layout").

use std::collections::{HashMap, HashSet};
use std::path::Path;
use std::sync::Arc;

use serde::{Deserialize, Serialize};

use crate::error::{Error, Result};
use crate::geometry::Footprint;
use crate::io;
use crate::plan::Plan;
use crate::scene::{self, FLAT_HEIGHT_CM, Room, SceneSpec};

/// The highest an object's bottom may be above the floor, in cm (10 m): anything higher is a
/// unit mistake.
pub const MAX_ELEVATION_CM: f64 = 1000.0;

/// One placed object: an asset plus its pose on the floor, and, for an object that does not stand
/// on the floor, its height and what holds it (docs/formats.md, "The layout").
#[derive(Debug, Clone, Default, PartialEq, Serialize, Deserialize, schemars::JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct PlacedObject {
    /// The asset's name.
    pub name: String,
    /// The asset's category.
    pub category: String,
    /// `[width, depth, height]` in cm, never changed by any stage.
    pub size: [f64; 3],
    /// Footprint centre `[x, y]` in cm.
    pub position: [f64; 2],
    /// Degrees clockwise seen from above; 0 faces +y, 90 faces +x.
    pub rotation: f64,
    /// Height of the object's bottom above the floor, in cm (0, and left out, on the floor).
    #[serde(default, skip_serializing_if = "is_zero_cm")]
    pub elevation: f64,
    /// The name of the object it stands on, when it stands on another object's top.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub on: Option<String>,
    /// The index of the wall it hangs on, its back on the wall.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub wall: Option<usize>,
}

fn is_zero_cm(v: &f64) -> bool {
    *v == 0.0
}

impl PlacedObject {
    /// Height of the object's top above the floor, in cm.
    pub fn top(&self) -> f64 {
        self.elevation + self.size[2]
    }

    /// True when nothing holds it but the floor: it stands on no object and hangs on no wall.
    pub fn on_floor(&self) -> bool {
        self.on.is_none() && self.wall.is_none()
    }

    /// The object's oriented footprint on the floor.
    pub fn footprint(&self) -> Footprint {
        Footprint::new(
            glam::DVec2::new(self.position[0], self.position[1]),
            self.size[0],
            self.size[1],
            self.rotation,
        )
        .with_height(self.size[2])
    }

    /// True for floor coverings (height at most 3 cm).
    pub fn is_flat(&self) -> bool {
        self.size[2] <= FLAT_HEIGHT_CM
    }
}

/// An asset that could not be placed, and why.
#[derive(Debug, Clone, PartialEq, Eq, Serialize, Deserialize, schemars::JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct Dropped {
    /// The asset's name.
    pub name: String,
    /// Why it has no place.
    pub reason: String,
}

/// Counters a run fills in: model usage and time, plus what the refinement tools did.
#[derive(Debug, Clone, Default, PartialEq, Serialize, Deserialize, schemars::JsonSchema)]
#[serde(default)]
pub struct Stats {
    /// Model calls made.
    pub llm_calls: u64,
    /// Prompt tokens reported by the model servers.
    pub prompt_tokens: u64,
    /// Completion tokens reported by the model servers.
    pub completion_tokens: u64,
    /// Wall-clock time of the run in milliseconds.
    pub wall_ms: u64,
    /// What the Physical Refinement Tool moved, when it ran.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub prt: Option<PrtStats>,
    /// Evaluate-and-refine rounds run, over all groups.
    #[serde(skip_serializing_if = "is_zero")]
    pub rounds: u32,
    /// Role actors the supervisor restarted.
    #[serde(skip_serializing_if = "is_zero")]
    pub restarts: u32,
    /// Fallback implementations swapped in, e.g. `designer: vlm -> rules after 3 tries (...)`.
    #[serde(skip_serializing_if = "Vec::is_empty")]
    pub fallbacks: Vec<String>,
    /// The scene ran past `run.scene_deadline_s`; what was left was finished by fallback
    /// implementations and the final PRT (`disco generate` then exits 5).
    #[serde(default, skip_serializing_if = "std::ops::Not::not")]
    pub deadline_missed: bool,
    /// Model-server failures that forced a fallback: the layout is complete, but part of it was
    /// made without the model the graph asked for (`disco generate` then exits 3).
    #[serde(skip_serializing_if = "Vec::is_empty")]
    pub model_failures: Vec<String>,
    /// The [`SceneSpec::digest`](crate::scene::SceneSpec::digest) of the scene this layout was
    /// made from (a batch rerun skips a scene only when it matches).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub scene_sha256: Option<String>,
    /// Things the user should know: ignored answers, unmet wall requirements, ...
    #[serde(skip_serializing_if = "Vec::is_empty")]
    pub notes: Vec<String>,
}

fn is_zero(v: &u32) -> bool {
    *v == 0
}

/// A summary of the Physical Refinement Tool's work.
#[derive(Debug, Clone, Default, PartialEq, Serialize, Deserialize, schemars::JsonSchema)]
#[serde(default)]
pub struct PrtStats {
    /// Objects whose pose changed.
    pub moved: usize,
    /// Mean displacement over placed objects, in cm.
    pub mean_displacement_cm: f64,
    /// Largest displacement, in cm.
    pub max_displacement_cm: f64,
    /// Requirements it could not meet (e.g. an against-wall object placed away from walls).
    #[serde(skip_serializing_if = "Vec::is_empty")]
    pub notes: Vec<String>,
}

/// A furnished room: every asset of the scene is in `objects` or in `dropped`, exactly once.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, schemars::JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct Layout {
    /// The scene's id.
    pub id: String,
    /// The floor.
    pub room: Room,
    /// Placed objects.
    pub objects: Vec<PlacedObject>,
    /// Assets that found no place, with reasons.
    #[serde(default)]
    pub dropped: Vec<Dropped>,
    // Shared, so that the copies of a growing layout (one per role call) do not copy the plan;
    // written as a plain plan.
    /// The plan the layout was made under.
    #[serde(default, with = "shared_plan")]
    #[schemars(with = "Plan")]
    pub plan: Arc<Plan>,
    /// Counters of the run.
    #[serde(default)]
    pub stats: Stats,
}

/// (De)serializes a shared plan as the plan itself.
mod shared_plan {
    use std::sync::Arc;

    use serde::{Deserialize, Deserializer, Serialize, Serializer};

    use crate::plan::Plan;

    pub(super) fn serialize<S: Serializer>(plan: &Arc<Plan>, s: S) -> Result<S::Ok, S::Error> {
        plan.as_ref().serialize(s)
    }

    pub(super) fn deserialize<'de, D: Deserializer<'de>>(d: D) -> Result<Arc<Plan>, D::Error> {
        Plan::deserialize(d).map(Arc::new)
    }
}

impl Layout {
    /// Reads and validates a complete layout file (every object has a category and size).
    pub fn load(path: &Path) -> Result<Self> {
        let text = io::read_text(path)?;
        let layout: Layout = io::parse_json(path, &text)?;
        layout.validate(path)?;
        Ok(layout)
    }

    /// Checks the room, sizes, poses and name uniqueness; errors name `path` and the field.
    pub fn validate(&self, path: &Path) -> Result<()> {
        scene::validate_room(path, "room", &self.room)?;
        let mut seen = HashSet::new();
        for (i, o) in self.objects.iter().enumerate() {
            if !seen.insert(o.name.as_str()) {
                return Err(Error::invalid(
                    path,
                    format!("objects[{i}].name"),
                    format!("duplicate name {:?}", o.name),
                ));
            }
            scene::validate_size(path, &format!("objects[{i}].size"), &o.size)?;
            validate_pose(path, i, o.position, o.rotation)?;
        }
        let placed: HashSet<&str> = self.objects.iter().map(|o| o.name.as_str()).collect();
        let mounts: Vec<Mount<'_>> = self.objects.iter().map(Mount::of).collect();
        validate_mounts(
            path,
            &self.room,
            &mounts,
            |n| placed.contains(n),
            "a placed object",
        )
    }

    /// The plan, to change: copied first when another layout shares it.
    pub fn plan_mut(&mut self) -> &mut Plan {
        Arc::make_mut(&mut self.plan)
    }

    /// The placed object called `name`, if any.
    pub fn object(&self, name: &str) -> Option<&PlacedObject> {
        self.objects.iter().find(|o| o.name == name)
    }

    /// The footprint a relation's target names: a placed object's, else a part of the room
    /// (`door-0`, `window-1`, `wall-2`: [`crate::targets`]).
    pub fn target_footprint(&self, name: &str) -> Option<Footprint> {
        self.object(name)
            .map(PlacedObject::footprint)
            .or_else(|| crate::targets::room_part_footprint(&self.room, name))
    }

    /// Placed objects by name.
    pub fn by_name(&self) -> HashMap<&str, &PlacedObject> {
        self.objects.iter().map(|o| (o.name.as_str(), o)).collect()
    }
}

/// What holds one object, as a file gives it (for validation).
struct Mount<'a> {
    name: &'a str,
    elevation: f64,
    on: Option<&'a str>,
    wall: Option<usize>,
}

impl<'a> Mount<'a> {
    fn of(o: &'a PlacedObject) -> Self {
        Mount {
            name: &o.name,
            elevation: o.elevation,
            on: o.on.as_deref(),
            wall: o.wall,
        }
    }
}

/// Checks each object's `elevation`, `on` and `wall`: a finite height in [0,
/// [`MAX_ELEVATION_CM`]], `on` naming another object that `known` accepts (`what` says what it
/// must be), `wall` a wall of `room`, never both, and no object standing (through others) on itself.
fn validate_mounts(
    path: &Path,
    room: &Room,
    mounts: &[Mount<'_>],
    known: impl Fn(&str) -> bool,
    what: &str,
) -> Result<()> {
    let walls = room.walls().len();
    for (i, m) in mounts.iter().enumerate() {
        if !m.elevation.is_finite() || !(0.0..=MAX_ELEVATION_CM).contains(&m.elevation) {
            return Err(Error::invalid(
                path,
                format!("objects[{i}].elevation"),
                format!(
                    "must be a finite number of cm from 0 to {MAX_ELEVATION_CM}, got {}",
                    scene::show_number(m.elevation)
                ),
            ));
        }
        if m.on.is_some() && m.wall.is_some() {
            return Err(Error::invalid(
                path,
                format!("objects[{i}]"),
                "an object stands `on` another or hangs on a `wall`, not both",
            ));
        }
        if let Some(on) = m.on {
            if on == m.name {
                return Err(Error::invalid(
                    path,
                    format!("objects[{i}].on"),
                    format!("{on:?} cannot stand on itself"),
                ));
            }
            if !known(on) {
                return Err(Error::invalid(
                    path,
                    format!("objects[{i}].on"),
                    format!("{on:?} is not {what}"),
                ));
            }
        }
        if let Some(w) = m.wall
            && w >= walls
        {
            return Err(Error::invalid(
                path,
                format!("objects[{i}].wall"),
                format!(
                    "the room has walls 0 to {}, not {w}",
                    walls.saturating_sub(1)
                ),
            ));
        }
    }
    // Following `on` from any object must end on the floor or a wall, never come back round.
    let on: HashMap<&str, &str> = mounts
        .iter()
        .filter_map(|m| m.on.map(|t| (m.name, t)))
        .collect();
    for (i, m) in mounts.iter().enumerate() {
        let mut at = m.name;
        for _ in 0..=mounts.len() {
            match on.get(at) {
                Some(next) if *next == m.name => {
                    return Err(Error::invalid(
                        path,
                        format!("objects[{i}].on"),
                        format!("{:?} stands, through others, on itself", m.name),
                    ));
                }
                Some(next) => at = next,
                None => break,
            }
        }
    }
    Ok(())
}

fn validate_pose(path: &Path, i: usize, position: [f64; 2], rotation: f64) -> Result<()> {
    if position.iter().any(|v| !v.is_finite() || v.abs() > 1e6) {
        return Err(Error::invalid(
            path,
            format!("objects[{i}].position"),
            format!("must be two finite numbers of cm, got {position:?}"),
        ));
    }
    if !rotation.is_finite() {
        return Err(Error::invalid(
            path,
            format!("objects[{i}].rotation"),
            format!("must be a finite number of degrees, got {rotation}"),
        ));
    }
    Ok(())
}

/// One object of a hand-made or foreign layout: only the name and pose are required.
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct DraftObject {
    /// The asset's name (must exist in the scene).
    pub name: String,
    /// Optional; must match the scene when given.
    #[serde(default)]
    pub category: Option<String>,
    /// Optional; must match the scene when given (sizes are never changed).
    #[serde(default)]
    pub size: Option<[f64; 3]>,
    /// Footprint centre in cm.
    pub position: [f64; 2],
    /// Degrees clockwise; defaults to 0.
    #[serde(default)]
    pub rotation: f64,
    /// Height of its bottom above the floor, in cm; defaults to 0.
    #[serde(default)]
    pub elevation: f64,
    /// The scene asset it stands on, if any.
    #[serde(default)]
    pub on: Option<String>,
    /// The wall it hangs on, if any.
    #[serde(default)]
    pub wall: Option<usize>,
}

/// A layout as another tool or a person may write it, to be completed from its scene.
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct DraftLayout {
    /// Ignored in favour of the scene's id when absent.
    #[serde(default)]
    pub id: Option<String>,
    /// Must match the scene's room when given.
    #[serde(default)]
    pub room: Option<Room>,
    /// Posed objects (a subset of the scene's assets).
    #[serde(default)]
    pub objects: Vec<DraftObject>,
    /// Assets the other tool gave up on; they get another chance.
    #[serde(default)]
    pub dropped: Vec<Dropped>,
    /// Carried over; its `against_wall` flags steer the PRT.
    #[serde(default)]
    pub plan: Plan,
    /// Carried over.
    #[serde(default)]
    pub stats: Stats,
}

impl DraftLayout {
    /// Reads a draft layout file.
    pub fn load(path: &Path) -> Result<Self> {
        let text = io::read_text(path)?;
        io::parse_json(path, &text)
    }

    /// Completes the draft from `scene`: fills categories and sizes, checks they agree, and returns
    /// the layout plus the names of scene assets the draft did not place.
    pub fn resolve(self, path: &Path, scene: &SceneSpec) -> Result<(Layout, Vec<String>)> {
        if let Some(room) = self.room
            && room != scene.room
        {
            return Err(Error::invalid(
                path,
                "room",
                format!(
                    "{} x {} cm differs from the scene's room {} x {} cm",
                    room.width, room.depth, scene.room.width, scene.room.depth
                ),
            ));
        }
        let mounts: Vec<Mount<'_>> = self
            .objects
            .iter()
            .map(|d| Mount {
                name: &d.name,
                elevation: d.elevation,
                on: d.on.as_deref(),
                wall: d.wall,
            })
            .collect();
        validate_mounts(
            path,
            &scene.room,
            &mounts,
            |n| scene.asset(n).is_some(),
            "an asset of the scene",
        )?;
        let mut seen = HashSet::new();
        let mut objects = Vec::with_capacity(self.objects.len());
        for (i, d) in self.objects.into_iter().enumerate() {
            let Some(asset) = scene.asset(&d.name) else {
                return Err(Error::invalid(
                    path,
                    format!("objects[{i}].name"),
                    format!("{:?} is not an asset of scene {:?}", d.name, scene.id),
                ));
            };
            if !seen.insert(d.name.clone()) {
                return Err(Error::invalid(
                    path,
                    format!("objects[{i}].name"),
                    format!("duplicate name {:?}", d.name),
                ));
            }
            if let Some(size) = d.size
                && size != asset.size
            {
                return Err(Error::invalid(
                    path,
                    format!("objects[{i}].size"),
                    format!(
                        "{size:?} differs from the scene's size {:?}; sizes are never changed",
                        asset.size
                    ),
                ));
            }
            if let Some(cat) = &d.category
                && cat != &asset.category
            {
                return Err(Error::invalid(
                    path,
                    format!("objects[{i}].category"),
                    format!(
                        "{cat:?} differs from the scene's category {:?}",
                        asset.category
                    ),
                ));
            }
            validate_pose(path, i, d.position, d.rotation)?;
            objects.push(PlacedObject {
                name: d.name,
                category: asset.category.clone(),
                size: asset.size,
                position: d.position,
                rotation: d.rotation,
                elevation: d.elevation,
                on: d.on,
                wall: d.wall,
            });
        }
        // Assets the draft did not pose (including ones it had dropped) get another chance.
        let missing = scene
            .assets
            .iter()
            .filter(|a| !seen.contains(&a.name))
            .map(|a| a.name.clone())
            .collect();
        let layout = Layout {
            id: self.id.unwrap_or_else(|| scene.id.clone()),
            room: scene.room.clone(),
            objects,
            dropped: Vec::new(),
            plan: Arc::new(self.plan),
            stats: self.stats,
        };
        Ok((layout, missing))
    }
}

#[cfg(test)]
mod tests;
