//! The library half of the `disco` commands: what `validate`, `metrics`, `render` and `--config`
//! compute, apart from parsing arguments and printing. The command line (`src/cli/`) and the
//! Python package (`python/`) both call these, so the two give the same answers.

use std::path::Path;

use serde::Serialize;

use crate::config::{GraphConfig, PRESETS, Preset};
use crate::error::{Error, Result};
use crate::io;
use crate::layout::{DraftLayout, Layout, PlacedObject};
use crate::scene::{Room, SceneSpec};

/// The category given to an object a layout names without one, when its name says nothing
/// either.
const UNKNOWN_CATEGORY: &str = "unknown";

/// The agent graph of `--config` (a TOML file, or a built-in graph's name; the offline default
/// when `None`) with the `--set KEY=VALUE` overrides and the `--cache` folder applied. A name
/// that is neither a file nor a preset is refused with the nearest preset's name.
pub fn load_graph(
    config: Option<&Path>,
    sets: &[String],
    cache: Option<&Path>,
) -> Result<GraphConfig> {
    if let Some(path) = config {
        config_exists(path)?;
    }
    let mut graph = GraphConfig::load(config, sets)?;
    if let Some(dir) = cache {
        graph.run.cache = Some(dir.to_string_lossy().into_owned());
    }
    Ok(graph)
}

/// `--config NAME`: a file, or a built-in graph's name; neither is an error that suggests the
/// nearest preset and says where they are listed.
fn config_exists(path: &Path) -> Result<()> {
    let name = path.to_string_lossy();
    if path.exists() || Preset::named(&name).is_some() {
        return Ok(());
    }
    let names: Vec<&str> = PRESETS.iter().map(|p| p.name).collect();
    let stem = name.strip_suffix(".toml").unwrap_or(&name);
    let typo = crate::agents::options::closest(stem, &names)
        .map(|n| format!("; did you mean `{n}`?"))
        .unwrap_or_default();
    Err(Error::invalid(
        path,
        "--config",
        format!("no such file or preset{typo} (see `disco config list`)"),
    ))
}

/// What `disco validate --json` prints for a valid scene (an invalid one is an error instead).
#[derive(Debug, Serialize)]
pub struct Verdict<'a> {
    /// Always true: an invalid scene never gets this far.
    pub valid: bool,
    /// The scene's id.
    pub id: &'a str,
    /// The number of assets.
    pub assets: usize,
    /// The floor.
    pub room: &'a Room,
    /// The room type.
    pub room_type: &'a str,
    /// The non-fatal problems (assets too big for the room).
    pub warnings: Vec<WarningJson>,
}

/// One non-fatal problem of a scene.
#[derive(Debug, Serialize)]
pub struct WarningJson {
    /// Where, as a JSON path (e.g. `assets[3]`).
    pub field: String,
    /// What, in words.
    pub message: String,
}

/// The verdict on a scene that loaded (and so is valid), with its warnings.
pub fn verdict(spec: &SceneSpec) -> Verdict<'_> {
    let warnings = spec
        .warnings()
        .into_iter()
        .map(|w| WarningJson {
            field: w.field,
            message: w.message,
        })
        .collect();
    Verdict {
        valid: true,
        id: &spec.id,
        assets: spec.assets.len(),
        room: &spec.room,
        room_type: &spec.room_type,
        warnings,
    }
}

/// A layout's metrics and the prompt's requests checked on it (the plan's constraint score
/// cannot see a request the planner dropped), as the one JSON object `disco metrics --json` and
/// `disco generate --json` print: the metrics with a `prompt_requests` list beside them.
pub fn measured(spec: &SceneSpec, layout: &Layout) -> Result<serde_json::Value> {
    let m = crate::metrics::measure(layout);
    let requests = crate::agents::requests::check_requests(spec, layout);
    let as_json = |e: serde_json::Error| Error::Render(format!("metrics as JSON: {e}"));
    let mut value = serde_json::to_value(&m).map_err(as_json)?;
    value["prompt_requests"] = serde_json::to_value(&requests).map_err(as_json)?;
    Ok(value)
}

/// Refuses a layout (read from `path`) whose objects are not the scene's assets: metrics over
/// the wrong pair mislead. A layout that lists only some of the assets is allowed, with the
/// warning returned.
pub fn check_belongs(spec: &SceneSpec, layout: &Layout, path: &Path) -> Result<Option<String>> {
    let names = layout
        .objects
        .iter()
        .map(|o| &o.name)
        .chain(layout.dropped.iter().map(|d| &d.name));
    for (i, name) in names.enumerate() {
        if spec.asset(name).is_none() {
            let field = match layout.objects.len() {
                n if i < n => format!("objects[{i}].name"),
                n => format!("dropped[{}].name", i - n),
            };
            return Err(Error::invalid(
                path,
                field,
                format!("object {name:?} is not an asset of scene {:?}", spec.id),
            ));
        }
    }
    let listed = layout.objects.len() + layout.dropped.len();
    if listed == spec.assets.len() {
        return Ok(None);
    }
    let assets = match spec.assets.len() {
        1 => "1 asset".to_string(),
        n => format!("{n} assets"),
    };
    Ok(Some(format!(
        "{}: lists {listed} of the scene's {assets}; the missing ones count as neither placed nor dropped",
        path.display()
    )))
}

/// Parses and checks a complete layout (every object has a category and size): what
/// [`Layout::load`] does with a file's text. `path` labels errors.
pub fn parse_layout(path: &Path, text: &str) -> Result<Layout> {
    let layout: Layout = io::parse_json(path, text)?;
    layout.validate(path)?;
    Ok(layout)
}

/// The layout `disco render` draws from `text` (the content of `path`): completed from `scene`
/// when given (a draft of names and poses is enough, as for `disco refine`); else the text as a
/// complete layout, where an object without a `category` takes it from its name (`floor lamp-0`
/// is a `floor lamp`).
pub fn drawable_layout(path: &Path, text: &str, scene: Option<&SceneSpec>) -> Result<Layout> {
    if let Some(spec) = scene {
        let draft: DraftLayout = io::parse_json(path, text)?;
        let (layout, _) = draft.resolve(path, spec)?;
        return Ok(layout);
    }
    let complete = match parse_layout(path, text) {
        Ok(layout) => return Ok(layout),
        Err(e) => e,
    };
    let Ok(draft) = io::parse_json::<DraftLayout>(path, text) else {
        return Err(complete);
    };
    match without_categories(draft, path)? {
        Some(layout) => Ok(layout),
        None => Err(match complete {
            Error::Invalid {
                path,
                field,
                reason,
            } => Error::Invalid {
                path,
                field,
                reason: format!(
                    "{reason} (a draft layout of names and positions is drawn with its scene: add --scene SCENE.json)"
                ),
            },
            other => other,
        }),
    }
}

/// A draft with a room and every object's size, its missing categories taken from the objects'
/// names; `None` when the room or a size is missing.
fn without_categories(draft: DraftLayout, path: &Path) -> Result<Option<Layout>> {
    let Some(room) = draft.room else {
        return Ok(None);
    };
    let mut objects = Vec::with_capacity(draft.objects.len());
    for d in draft.objects {
        let Some(size) = d.size else {
            return Ok(None);
        };
        let category = d.category.unwrap_or_else(|| category_of(&d.name));
        objects.push(PlacedObject {
            name: d.name,
            category,
            size,
            position: d.position,
            rotation: d.rotation,
            ..Default::default()
        });
    }
    let layout = Layout {
        id: draft.id.unwrap_or_else(|| {
            path.file_stem()
                .map(|s| s.to_string_lossy().into_owned())
                .unwrap_or_default()
        }),
        room,
        objects,
        dropped: draft.dropped,
        plan: std::sync::Arc::new(draft.plan),
        stats: draft.stats,
    };
    layout.validate(path)?;
    Ok(Some(layout))
}

/// An asset's category from its name: the name without a trailing `-N` instance number, or
/// [`UNKNOWN_CATEGORY`] when nothing is left.
fn category_of(name: &str) -> String {
    let base = match name.rsplit_once('-') {
        Some((stem, n)) if !n.is_empty() && n.chars().all(|c| c.is_ascii_digit()) => stem,
        _ => name,
    };
    let base = base.trim();
    if base.is_empty() {
        UNKNOWN_CATEGORY.to_string()
    } else {
        base.to_string()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_category_comes_from_the_name() {
        assert_eq!(category_of("floor lamp-0"), "floor lamp");
        assert_eq!(category_of("bed"), "bed");
        assert_eq!(category_of("x-ray-12"), "x-ray");
        assert_eq!(category_of("-3"), UNKNOWN_CATEGORY);
    }

    #[test]
    fn a_misspelt_preset_gets_the_nearest_name() {
        let e = load_graph(Some(Path::new("defualt")), &[], None).unwrap_err();
        assert!(e.to_string().contains("did you mean `default`?"), "{e}");
        let graph = load_graph(None, &[], Some(Path::new("answers"))).unwrap();
        assert_eq!(graph.run.cache.as_deref(), Some("answers"));
    }

    #[test]
    fn a_layout_of_another_scene_is_refused_and_a_partial_one_warned_about() {
        let (scene, mut layout) = crate::synth::bedroom();
        assert_eq!(
            check_belongs(&scene, &layout, Path::new("l.json")).unwrap(),
            None
        );
        layout.objects.pop();
        let warning = check_belongs(&scene, &layout, Path::new("l.json")).unwrap();
        assert!(
            warning.unwrap().contains("lists"),
            "a partial layout is warned about"
        );
        layout.objects[0].name = "ghost-0".into();
        let e = check_belongs(&scene, &layout, Path::new("l.json")).unwrap_err();
        assert!(e.to_string().contains("\"ghost-0\" is not an asset"), "{e}");
    }
}
