//! Inputs from Python (a path, or a dict holding the same JSON as the file) and outputs to it
//! (dicts made from the JSON the CLI writes). Dicts go through JSON text and the library's own
//! readers, so a dict is refused exactly where the file would be, naming the field.

use std::path::{Path, PathBuf};

use pyo3::prelude::*;
use serde::Serialize;

use disco_layout::config::GraphConfig;
use disco_layout::layout::DraftLayout;
use disco_layout::{Layout, SceneSpec, commands, io};

use crate::errors::IntoPy;

/// The label errors give a scene passed as a dict (in place of a file name).
pub const SCENE_LABEL: &str = "<scene>";
/// The label of a layout passed as a dict.
pub const LAYOUT_LABEL: &str = "<layout>";
/// The id of a scene given as a dict without one (a file's scene takes its file's stem).
pub const DEFAULT_SCENE_ID: &str = "scene";

/// Where an input comes from.
pub enum Source {
    /// A file, as the CLI reads it.
    File(PathBuf),
    /// JSON text made from a Python object.
    Json(String),
}

impl Source {
    /// A path (`str` or `os.PathLike`) or a mapping (dumped as JSON by `disco_layout._json`).
    pub fn of(obj: &Bound<'_, PyAny>) -> PyResult<Source> {
        let helper = obj.py().import("disco_layout._json")?;
        if helper.getattr("is_path")?.call1((obj,))?.is_truthy()? {
            let path: PathBuf = obj
                .py()
                .import("os")?
                .getattr("fspath")?
                .call1((obj,))?
                .extract()?;
            return Ok(Source::File(path));
        }
        Ok(Source::Json(
            helper.getattr("dumps")?.call1((obj,))?.extract()?,
        ))
    }

    /// The file, if the input is one.
    pub fn path(&self) -> Option<&Path> {
        match self {
            Source::File(p) => Some(p),
            Source::Json(_) => None,
        }
    }

    /// The label of errors and the text: the file's, read as the CLI reads it, or the JSON.
    fn text(&self, py: Python<'_>, label: &str) -> PyResult<(PathBuf, String)> {
        match self {
            Source::File(p) => Ok((p.clone(), io::read_text(p).py_err(py)?)),
            Source::Json(t) => Ok((PathBuf::from(label), t.clone())),
        }
    }
}

/// A scene and the file it came from (meshes are relative to its folder).
pub struct Scene {
    /// The scene.
    pub spec: SceneSpec,
    /// Its file, when it was given as one.
    pub path: Option<PathBuf>,
}

impl Scene {
    /// Reads and checks a scene: a file as `SceneSpec::load` does, a dict the same way under
    /// the label [`SCENE_LABEL`] (its id defaulting to [`DEFAULT_SCENE_ID`]).
    pub fn of(obj: &Bound<'_, PyAny>) -> PyResult<Scene> {
        let py = obj.py();
        match Source::of(obj)? {
            Source::File(path) => Ok(Scene {
                spec: SceneSpec::load(&path).py_err(py)?,
                path: Some(path),
            }),
            Source::Json(text) => {
                let mut spec = SceneSpec::from_json(Path::new(SCENE_LABEL), &text).py_err(py)?;
                if spec.id == SCENE_LABEL {
                    spec.id = DEFAULT_SCENE_ID.to_string();
                }
                Ok(Scene { spec, path: None })
            }
        }
    }
}

/// A complete layout, as `Layout::load` reads a file.
pub fn layout(obj: &Bound<'_, PyAny>) -> PyResult<(Layout, PathBuf)> {
    let py = obj.py();
    match Source::of(obj)? {
        Source::File(path) => Ok((Layout::load(&path).py_err(py)?, path)),
        Source::Json(text) => {
            let label = PathBuf::from(LAYOUT_LABEL);
            Ok((commands::parse_layout(&label, &text).py_err(py)?, label))
        }
    }
}

/// A draft layout (names and poses are enough), completed from `scene` as `disco refine` does;
/// also the assets the draft does not place.
pub fn draft(obj: &Bound<'_, PyAny>, scene: &SceneSpec) -> PyResult<(Layout, Vec<String>)> {
    let py = obj.py();
    let (label, text) = Source::of(obj)?.text(py, LAYOUT_LABEL)?;
    let draft: DraftLayout = io::parse_json(&label, &text).py_err(py)?;
    draft.resolve(&label, scene).py_err(py)
}

/// The layout `disco render` draws: completed from `scene` when given, else complete (missing
/// categories taken from the names).
pub fn drawable(obj: &Bound<'_, PyAny>, scene: Option<&SceneSpec>) -> PyResult<Layout> {
    let py = obj.py();
    let (label, text) = Source::of(obj)?.text(py, LAYOUT_LABEL)?;
    commands::drawable_layout(&label, &text, scene).py_err(py)
}

/// The agent graph: `None` for the built-in default, a path or a preset's name as `--config`
/// takes it, or a dict of the TOML's tables; `sets` are `--set` overrides, `cache` is `--cache`.
pub fn graph(
    config: Option<&Bound<'_, PyAny>>,
    sets: &[String],
    cache: Option<&Path>,
) -> PyResult<GraphConfig> {
    let Some(config) = config else {
        return Python::attach(|py| commands::load_graph(None, sets, cache).py_err(py));
    };
    let py = config.py();
    match Source::of(config)? {
        Source::File(path) => commands::load_graph(Some(&path), sets, cache).py_err(py),
        Source::Json(text) => {
            let label = Path::new(crate::errors::CONFIG_LABEL);
            let invalid = |reason: String| {
                crate::errors::to_py(
                    py,
                    &disco_layout::Error::invalid(label, "(document)", reason),
                )
            };
            let value: serde_json::Value =
                serde_json::from_str(&text).map_err(|e| invalid(e.to_string()))?;
            let toml_text = toml::to_string(&value)
                .map_err(|e| invalid(format!("cannot be written as TOML: {e}")))?;
            let mut graph = GraphConfig::from_toml(label, &toml_text, sets).py_err(py)?;
            if let Some(dir) = cache {
                graph.run.cache = Some(dir.to_string_lossy().into_owned());
            }
            Ok(graph)
        }
    }
}

/// A value as the Python object of its JSON (`json.loads` of what the CLI writes).
pub fn to_python<T: Serialize + ?Sized>(py: Python<'_>, value: &T) -> PyResult<Py<PyAny>> {
    let text = serde_json::to_string(value)
        .map_err(|e| pyo3::exceptions::PyValueError::new_err(format!("as JSON: {e}")))?;
    json_to_python(py, &text)
}

/// JSON text as a Python object.
pub fn json_to_python(py: Python<'_>, text: &str) -> PyResult<Py<PyAny>> {
    Ok(py
        .import("json")?
        .getattr("loads")?
        .call1((text,))?
        .unbind())
}
