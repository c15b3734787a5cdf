//! The scene spec: a prompt, a room and the assets to place (docs/formats.md, "The scene").

use std::collections::HashMap;
use std::path::Path;

use serde::{Deserialize, Serialize};

use crate::error::{Error, Result};
use crate::io;

/// Largest room side accepted, in cm (100 m). Anything larger is almost certainly a unit mistake.
pub const MAX_ROOM_SIDE_CM: f64 = 10_000.0;

/// Objects this tall or lower (cm) are floor coverings (rugs, mats): they may lie under furniture.
pub const FLAT_HEIGHT_CM: f64 = 3.0;

/// The room's floor: a `width` x `depth` rectangle with its bottom-left corner at the origin.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Room {
    /// Extent along x, in cm.
    pub width: f64,
    /// Extent along y, in cm.
    pub depth: f64,
}

impl Room {
    /// Floor area in cm².
    pub fn area(&self) -> f64 {
        self.width * self.depth
    }
}

/// One asset to place: its unique name, category and size `[width, depth, height]` in cm.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Asset {
    /// Unique name within the scene, e.g. `chair-0`.
    pub name: String,
    /// Furniture category, e.g. `chair`.
    pub category: String,
    /// `[width, depth, height]` in cm: width along the object's left-right axis, depth back to front.
    pub size: [f64; 3],
    /// Optional path to a `.glb` mesh used by 3D export.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub mesh: Option<String>,
    /// Optional free-text description.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub description: Option<String>,
}

impl Asset {
    /// An asset with no mesh and no description: `Asset::new("bed-0", "bed", [160.0, 210.0, 100.0])`.
    pub fn new(name: &str, category: &str, size: [f64; 3]) -> Self {
        Asset {
            name: name.to_string(),
            category: category.to_string(),
            size,
            mesh: None,
            description: None,
        }
    }

    /// True for floor coverings (height at most [`FLAT_HEIGHT_CM`]).
    pub fn is_flat(&self) -> bool {
        self.size[2] <= FLAT_HEIGHT_CM
    }

    /// Why this asset cannot stand in `room` in any rotation, if it cannot.
    pub fn misfit(&self, room: &Room) -> Option<String> {
        misfit(self.size, room)
    }
}

/// Why an object of `size` cannot stand in `room` in any rotation, if it cannot.
pub fn misfit(size: [f64; 3], room: &Room) -> Option<String> {
    let [w, d, _] = size;
    let fits = |a: f64, b: f64| a <= room.width + 1e-9 && b <= room.depth + 1e-9;
    if fits(w, d) || fits(d, w) {
        None
    } else {
        Some(format!(
            "its footprint {w} x {d} cm does not fit the {} x {} cm room in any rotation",
            room.width, room.depth
        ))
    }
}

/// A scene to furnish (the input of every command).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SceneSpec {
    /// Identifier; defaults to the file stem when read from a file.
    #[serde(default)]
    pub id: String,
    /// What the user asked for, in words.
    #[serde(default)]
    pub prompt: String,
    /// Room type, e.g. `bedroom`.
    pub room_type: String,
    /// The floor.
    pub room: Room,
    /// What to place.
    pub assets: Vec<Asset>,
}

/// A problem that does not stop a scene but that the user should hear about.
#[derive(Debug, Clone, PartialEq)]
pub struct Warning {
    /// Where, as a JSON path (e.g. `assets[3]`).
    pub field: String,
    /// What, in words.
    pub message: String,
}

impl SceneSpec {
    /// Reads, parses and validates a scene file. `id` defaults to the file stem.
    pub fn load(path: &Path) -> Result<Self> {
        let text = io::read_text(path)?;
        Self::from_json(path, &text)
    }

    /// Parses and validates scene JSON; `path` labels errors and supplies the default `id`.
    pub fn from_json(path: &Path, text: &str) -> Result<Self> {
        let mut spec: SceneSpec = io::parse_json(path, text)?;
        if spec.id.trim().is_empty() {
            spec.id = path
                .file_stem()
                .map(|s| s.to_string_lossy().into_owned())
                .unwrap_or_else(|| "scene".to_string());
        }
        spec.validate(path)?;
        Ok(spec)
    }

    /// Checks the scene against docs/formats.md; the error names `path`, the field and the reason.
    pub fn validate(&self, path: &Path) -> Result<()> {
        validate_room(path, "room", &self.room)?;
        if self.room_type.trim().is_empty() {
            return Err(Error::invalid(path, "room_type", "must not be empty"));
        }
        if self.assets.is_empty() {
            return Err(Error::invalid(
                path,
                "assets",
                "the scene has no assets to place",
            ));
        }
        let mut seen: HashMap<&str, usize> = HashMap::new();
        for (i, asset) in self.assets.iter().enumerate() {
            if asset.name.trim().is_empty() {
                return Err(Error::invalid(
                    path,
                    format!("assets[{i}].name"),
                    "must not be empty",
                ));
            }
            if let Some(first) = seen.insert(asset.name.as_str(), i) {
                return Err(Error::invalid(
                    path,
                    format!("assets[{i}].name"),
                    format!("duplicate name {:?} (also assets[{first}])", asset.name),
                ));
            }
            if asset.category.trim().is_empty() {
                return Err(Error::invalid(
                    path,
                    format!("assets[{i}].category"),
                    "must not be empty",
                ));
            }
            validate_size(path, &format!("assets[{i}].size"), &asset.size)?;
        }
        Ok(())
    }

    /// Non-fatal problems: assets that cannot fit the room in any rotation (they end in `dropped`).
    pub fn warnings(&self) -> Vec<Warning> {
        self.assets
            .iter()
            .enumerate()
            .filter_map(|(i, a)| {
                a.misfit(&self.room).map(|why| Warning {
                    field: format!("assets[{i}]"),
                    message: format!("{:?} will be dropped: {why}", a.name),
                })
            })
            .collect()
    }

    /// The asset called `name`, if any.
    pub fn asset(&self, name: &str) -> Option<&Asset> {
        self.assets.iter().find(|a| a.name == name)
    }
}

/// Checks a room's sides: finite, positive and at most [`MAX_ROOM_SIDE_CM`].
pub fn validate_room(path: &Path, field: &str, room: &Room) -> Result<()> {
    for (name, v) in [("width", room.width), ("depth", room.depth)] {
        let field = format!("{field}.{name}");
        if !v.is_finite() {
            return Err(Error::invalid(
                path,
                field,
                format!("must be a finite number, got {v}"),
            ));
        }
        if v <= 0.0 {
            return Err(Error::invalid(
                path,
                field,
                format!("must be positive, got {v} cm"),
            ));
        }
        if v > MAX_ROOM_SIDE_CM {
            return Err(Error::invalid(
                path,
                field,
                format!(
                    "{v} cm is over the {MAX_ROOM_SIDE_CM} cm (100 m) limit; sizes are in centimetres"
                ),
            ));
        }
    }
    Ok(())
}

/// Checks an object size: three finite, positive numbers.
pub fn validate_size(path: &Path, field: &str, size: &[f64; 3]) -> Result<()> {
    for (axis, v) in ["width", "depth", "height"].iter().zip(size) {
        if !v.is_finite() || *v <= 0.0 {
            return Err(Error::invalid(
                path,
                field,
                format!("{axis} must be a finite positive number of cm, got {v}"),
            ));
        }
    }
    Ok(())
}
