//! The scene spec: a prompt, a room and the assets to place (docs/formats.md, "The scene").

use std::collections::HashMap;
use std::path::Path;

use serde::{Deserialize, Serialize};

use crate::error::{Error, Result};
use crate::io;

pub use crate::room::{Room, validate_room};
pub use crate::units::{FLAT_HEIGHT_CM, MAX_ROOM_SIDE_CM, MIN_ROOM_SIDE_CM, show_number};

/// One asset to place: its unique name, category and size `[width, depth, height]` in cm.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, schemars::JsonSchema)]
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
    /// Where it goes (optional): on the floor, on a wall, or on another object's top. When
    /// absent, the furniture knowledge (or a model) decides.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub support: Option<Support>,
}

/// What an object stands on or hangs from (docs/formats.md, "The scene").
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Serialize, Deserialize, schemars::JsonSchema)]
#[serde(rename_all = "lowercase")]
pub enum Support {
    /// It stands on the floor (every object did before supports existed).
    Floor,
    /// It hangs on a wall, its back on the wall, at some height.
    Wall,
    /// It stands on top of another object (a lamp on a nightstand).
    Surface,
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
            support: None,
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
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, schemars::JsonSchema)]
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
        check_objects(path, text)?;
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
            if let Some(mesh) = &asset.mesh {
                validate_mesh_path(path, &format!("assets[{i}].mesh"), mesh)?;
            }
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

    /// A fingerprint of the whole spec (SHA-256 of its JSON, hex): a layout made from it carries
    /// it, so a rerun can tell a finished scene from one edited since.
    pub fn digest(&self) -> String {
        use sha2::{Digest, Sha256};
        let json = serde_json::to_vec(self).unwrap_or_default();
        Sha256::digest(&json)
            .iter()
            .map(|b| format!("{b:02x}"))
            .collect()
    }

    /// The asset called `name`, if any.
    pub fn asset(&self, name: &str) -> Option<&Asset> {
        self.assets.iter().find(|a| a.name == name)
    }
}

/// The smallest footprint taken, as its longer side: anything smaller was surely written in metres
/// (a bed of 1.6 x 2.1 "cm").
pub const MIN_OBJECT_SIDE_CM: f64 = 5.0;

/// Checks an object size: three finite, positive numbers.
pub fn validate_size(path: &Path, field: &str, size: &[f64; 3]) -> Result<()> {
    for (axis, v) in ["width", "depth", "height"].iter().zip(size) {
        if !v.is_finite() || *v <= 0.0 {
            return Err(Error::invalid(
                path,
                field,
                format!(
                    "{axis} must be a finite positive number of cm, got {}",
                    show_number(*v)
                ),
            ));
        }
    }
    if size[0].max(size[1]) < MIN_OBJECT_SIDE_CM {
        return Err(Error::invalid(
            path,
            field,
            format!(
                "a {} x {} cm footprint is too small to be real: sizes are in centimetres (did you mean [{}, {}, {}]?)",
                show_number(size[0]),
                show_number(size[1]),
                show_number(size[0] * 100.0),
                show_number(size[1] * 100.0),
                show_number(size[2] * 100.0)
            ),
        ));
    }
    Ok(())
}

/// Checks a mesh path: relative to the scene file's folder and staying inside it (no absolute
/// path, no `..`), so a scene cannot make the exporter read files elsewhere.
pub fn validate_mesh_path(path: &Path, field: &str, mesh: &str) -> Result<()> {
    use std::path::Component;
    let p = Path::new(mesh);
    let inside = !mesh.trim().is_empty()
        && p.components()
            .all(|c| matches!(c, Component::Normal(_) | Component::CurDir));
    if !inside {
        return Err(Error::invalid(
            path,
            field,
            format!("{mesh:?} must be a path relative to the scene's folder, without `..`"),
        ));
    }
    Ok(())
}

/// Refuses what serde would take but no person means: a document, room or asset written as a
/// list instead of an object (`"room": [400, 300]`). Text that is not JSON is left to the parser,
/// which says where it breaks.
fn check_objects(path: &Path, text: &str) -> Result<()> {
    let Ok(value) = serde_json::from_str::<serde_json::Value>(text.trim_start_matches('\u{feff}'))
    else {
        return Ok(());
    };
    let expect_object = |v: &serde_json::Value, field: &str, example: &str| {
        if v.is_object() || v.is_null() {
            Ok(())
        } else {
            Err(Error::invalid(
                path,
                field,
                format!("expected an object such as {example}, got {}", kind_of(v)),
            ))
        }
    };
    expect_object(
        &value,
        "(document)",
        r#"{"prompt": ..., "room": {...}, "assets": [...]}"#,
    )?;
    expect_object(&value["room"], "room", r#"{"width": 400, "depth": 350}"#)?;
    if let Some(assets) = value["assets"].as_array() {
        for (i, a) in assets.iter().enumerate() {
            expect_object(
                a,
                &format!("assets[{i}]"),
                r#"{"name": "bed-0", "category": "bed", "size": [160, 210, 100]}"#,
            )?;
        }
    }
    Ok(())
}

fn kind_of(v: &serde_json::Value) -> &'static str {
    match v {
        serde_json::Value::Array(_) => "a list",
        serde_json::Value::String(_) => "a string",
        serde_json::Value::Number(_) => "a number",
        serde_json::Value::Bool(_) => "true or false",
        serde_json::Value::Null => "null",
        serde_json::Value::Object(_) => "an object",
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn refused(text: &str) -> String {
        SceneSpec::from_json(Path::new("s.json"), text)
            .unwrap_err()
            .to_string()
    }

    const ASSET: &str = r#"{"name": "bed-0", "category": "bed", "size": [160, 210, 100]}"#;

    #[test]
    fn lists_where_objects_belong_are_refused() {
        let e = refused(&format!(
            r#"{{"prompt": "p", "room_type": "bedroom", "room": [400, 300], "assets": [{ASSET}]}}"#
        ));
        assert!(
            e.contains("room") && e.contains("expected an object"),
            "{e}"
        );
        let e = refused(&format!(
            r#"["p", "bedroom", {{"width": 400, "depth": 300}}, [{ASSET}]]"#
        ));
        assert!(
            e.contains("expected an object") && e.contains("a list"),
            "{e}"
        );
    }

    #[test]
    fn sizes_in_metres_are_caught_with_a_suggestion() {
        let e = refused(&format!(
            r#"{{"prompt": "p", "room_type": "bedroom", "room": {{"width": 4, "depth": 5}}, "assets": [{ASSET}]}}"#
        ));
        assert!(
            e.contains("centimetres") && e.contains("did you mean 400 x 500?"),
            "{e}"
        );
        let e = refused(
            r#"{"prompt": "p", "room_type": "bedroom", "room": {"width": 400, "depth": 500},
                "assets": [{"name": "bed-0", "category": "bed", "size": [1.6, 2.1, 1]}]}"#,
        );
        assert!(
            e.contains("assets[0].size") && e.contains("[160, 210, 100]"),
            "{e}"
        );
    }

    #[test]
    fn huge_numbers_are_shown_short() {
        let e = refused(&format!(
            r#"{{"prompt": "p", "room_type": "bedroom", "room": {{"width": 1e308, "depth": 500}}, "assets": [{ASSET}]}}"#
        ));
        assert!(e.contains("1e308") && e.len() < 200, "{e}");
    }

    #[test]
    fn a_size_with_four_numbers_says_what_was_expected() {
        let e = refused(
            r#"{"prompt": "p", "room_type": "bedroom", "room": {"width": 400, "depth": 500},
                "assets": [{"name": "bed-0", "category": "bed", "size": [160, 210, 100, 5]}]}"#,
        );
        assert!(e.contains("assets[0].size"), "{e}");
        assert!(e.contains("3"), "{e}");
    }

    #[test]
    fn mesh_paths_stay_beside_the_scene() {
        for bad in ["/etc/passwd", "../secret.glb", "meshes/../../x.glb", ""] {
            let text = format!(
                r#"{{"prompt": "p", "room_type": "bedroom", "room": {{"width": 400, "depth": 500}},
                    "assets": [{{"name": "bed-0", "category": "bed", "size": [160, 210, 100], "mesh": {bad:?}}}]}}"#
            );
            let e = refused(&text);
            assert!(
                e.contains("assets[0].mesh") && e.contains("relative"),
                "{bad}: {e}"
            );
        }
        let ok = r#"{"prompt": "p", "room_type": "bedroom", "room": {"width": 400, "depth": 500},
            "assets": [{"name": "bed-0", "category": "bed", "size": [160, 210, 100], "mesh": "meshes/bed.glb"}]}"#;
        assert!(SceneSpec::from_json(Path::new("s.json"), ok).is_ok());
    }

    #[test]
    fn an_asset_may_say_where_it_goes() {
        let text = r#"{"prompt": "p", "room_type": "bedroom", "room": {"width": 400, "depth": 500},
            "assets": [{"name": "clock-0", "category": "clock", "size": [30, 5, 30], "support": "wall"},
                       {"name": "bed-0", "category": "bed", "size": [160, 210, 100]}]}"#;
        let s = SceneSpec::from_json(Path::new("s.json"), text).unwrap();
        assert_eq!(s.assets[0].support, Some(Support::Wall));
        assert_eq!(s.assets[1].support, None);
        let back = serde_json::to_string(&s).unwrap();
        assert!(back.contains(r#""support":"wall""#), "{back}");
        assert_eq!(back.matches("support").count(), 1, "{back}");
        let e = refused(&text.replace(r#""wall""#, r#""ceiling""#));
        assert!(
            e.contains("assets[0].support") || e.contains("ceiling"),
            "{e}"
        );
    }

    #[test]
    fn floats_come_back_exactly() {
        let text = r#"{"prompt": "p", "room_type": "bedroom", "room": {"width": 400, "depth": 500},
            "assets": [{"name": "bed-0", "category": "bed", "size": [15.333940689182553, 210, 100]}]}"#;
        let s = SceneSpec::from_json(Path::new("s.json"), text).unwrap();
        assert_eq!(s.assets[0].size[0].to_string(), "15.333940689182553");
        let back = serde_json::to_string(&s).unwrap();
        assert!(back.contains("15.333940689182553"), "{back}");
    }
}
