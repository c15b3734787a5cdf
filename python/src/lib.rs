//! `disco_layout` for Python: the native module `disco_layout._disco`, which the package's
//! `__init__.py` re-exports. Every function here calls the same library functions as the
//! `disco` command of the same name, so its results are the CLI's (the tests compare them byte
//! for byte). Long calls run on the library's tokio runtime with the GIL released ([`runner`]);
//! errors become the exceptions of `disco_layout.errors` ([`errors`]); Python callables can
//! play roles of an agent graph ([`roles`]).
#![deny(missing_docs)]

pub mod convert;
pub mod errors;
pub mod roles;
pub mod runner;

use std::path::{Path, PathBuf};
use std::sync::Arc;

use pyo3::exceptions::PyValueError;
use pyo3::prelude::*;
use pyo3::types::PyBytes;

use disco_layout::export::{self, ExportOptions};
use disco_layout::outputs::{self, OutputOptions};
use disco_layout::render::RenderOptions;
use disco_layout::roles::RoleKind;
use disco_layout::runtime::batch::{self as batching, BatchOptions, Outcome, SceneReport};
use disco_layout::runtime::shard::Shard;
use disco_layout::{Layout, PrtConfig, Runtime, commands, io};

use convert::{Scene, to_python};
use errors::IntoPy;

/// The grid step `disco refine` uses unless told otherwise, in cm.
const DEFAULT_GRID_STEP_CM: f64 = 5.0;
/// The wall height of `disco export` and `disco generate --glb`, in cm.
const DEFAULT_WALL_HEIGHT_CM: f64 = 250.0;
/// The long side of `disco render`'s pictures, in pixels.
const DEFAULT_RENDER_PX: u32 = 1024;

/// A run's events (`--trace`): pass one to `generate(trace=...)` to record them, then read
/// them with `events()`, write them with `write_jsonl()`, or draw a report with
/// `report_html(scene, layout, trace)`.
#[pyclass(frozen, module = "disco_layout")]
pub struct Trace {
    inner: Arc<disco_layout::trace::Trace>,
}

#[pymethods]
impl Trace {
    /// A new, empty trace; with `snapshots` (the default) it keeps the layout after every step,
    /// which the report's step pictures need.
    #[new]
    #[pyo3(signature = (snapshots = true))]
    fn new(snapshots: bool) -> Self {
        let inner = if snapshots {
            disco_layout::trace::Trace::with_snapshots()
        } else {
            disco_layout::trace::Trace::default()
        };
        Trace {
            inner: Arc::new(inner),
        }
    }

    /// Every event so far, as the dicts of the JSON lines `--trace` writes.
    fn events(&self, py: Python<'_>) -> PyResult<Py<PyAny>> {
        to_python(py, &self.inner.events())
    }

    /// Writes the events as JSON lines, atomically, as `disco generate --trace` does.
    fn write_jsonl(&self, py: Python<'_>, path: PathBuf) -> PyResult<()> {
        self.inner.write_jsonl(&path).py_err(py)
    }

    fn __len__(&self) -> usize {
        self.inner.events().len()
    }
}

/// Where `generate` records its events: a `Trace` given by the caller, or a file.
enum TraceTarget {
    Object(Arc<disco_layout::trace::Trace>),
    File(PathBuf),
}

fn trace_target(obj: Option<&Bound<'_, PyAny>>) -> PyResult<Option<TraceTarget>> {
    let Some(obj) = obj.filter(|o| !o.is_none()) else {
        return Ok(None);
    };
    if let Ok(trace) = obj.cast::<Trace>() {
        return Ok(Some(TraceTarget::Object(Arc::clone(&trace.get().inner))));
    }
    Ok(Some(TraceTarget::File(obj.extract()?)))
}

/// Issues a Python warning of `disco_layout.errors.SceneWarning`.
fn warn(py: Python<'_>, message: &str) -> PyResult<()> {
    let category = py.import("disco_layout.errors")?.getattr("SceneWarning")?;
    py.import("warnings")?
        .getattr("warn")?
        .call1((message, category, 3))?;
    Ok(())
}

/// The scene's warnings (assets too big for the room), as `disco` prints them.
fn warn_about(py: Python<'_>, scene: &Scene) -> PyResult<()> {
    let label = scene
        .path
        .as_deref()
        .unwrap_or(Path::new(convert::SCENE_LABEL));
    for w in scene.spec.warnings() {
        warn(
            py,
            &format!("{}: {}: {}", label.display(), w.field, w.message),
        )?;
    }
    Ok(())
}

/// The checks `disco validate` makes: the scene's verdict (as `--json` prints it) when it is
/// valid; raises `ValidationError` (or `FileError`) naming the file, field and reason when not.
#[pyfunction]
fn validate(py: Python<'_>, scene: &Bound<'_, PyAny>) -> PyResult<Py<PyAny>> {
    let scene = Scene::of(scene)?;
    to_python(py, &commands::verdict(&scene.spec))
}

/// Furnishes one room, as `disco generate`; see `disco_layout.generate`.
#[pyfunction]
#[pyo3(signature = (scene, config = None, sets = Vec::new(), *, cache = None, output = None,
    renders = None, glb = None, report = None, trace = None,
    wall_height_cm = DEFAULT_WALL_HEIGHT_CM, strict = true))]
#[allow(clippy::too_many_arguments)]
fn generate(
    py: Python<'_>,
    scene: &Bound<'_, PyAny>,
    config: Option<&Bound<'_, PyAny>>,
    sets: Vec<String>,
    cache: Option<PathBuf>,
    output: Option<PathBuf>,
    renders: Option<PathBuf>,
    glb: Option<PathBuf>,
    report: Option<PathBuf>,
    trace: Option<&Bound<'_, PyAny>>,
    wall_height_cm: f64,
    strict: bool,
) -> PyResult<Py<PyAny>> {
    check_wall_height(wall_height_cm)?;
    let scene = Scene::of(scene)?;
    warn_about(py, &scene)?;
    let config = config.filter(|c| !c.is_none());
    let config_file = match config {
        Some(c) => convert::Source::of(c)?
            .path()
            .filter(|p| p.is_file())
            .map(Path::to_path_buf),
        None => None,
    };
    let graph = convert::graph(config, &sets, cache.as_deref())?;
    let trace = trace_target(trace)?;
    let options = OutputOptions {
        layout: output,
        trace: match &trace {
            Some(TraceTarget::File(p)) => Some(p.clone()),
            _ => None,
        },
        renders,
        report,
        glb,
        export: ExportOptions {
            wall_height_cm,
            ..ExportOptions::default()
        },
        meshes: export::meshes_of(&scene.spec, scene.path.as_deref()),
    };
    let mut inputs = Vec::new();
    if let Some(p) = &scene.path {
        inputs.push(io::NamedPath::new("scene", p));
    }
    if let Some(p) = &config_file {
        inputs.push(io::NamedPath::new("config", p));
    }
    options
        .refuse_clobbering(&scene.spec.id, &inputs)
        .py_err(py)?;
    create_parents(
        py,
        [
            &options.layout,
            &options.glb,
            &options.report,
            &options.trace,
        ]
        .into_iter()
        .flatten(),
    )?;
    let events = match trace {
        Some(TraceTarget::Object(t)) => t,
        _ => Arc::new(options.new_trace()),
    };
    let registry = roles::registry(py);
    let spec = scene.spec;
    let task = async move {
        let runtime = Runtime::new(graph, registry)?;
        runtime.preflight().await?;
        let layout = match runtime.generate(spec.clone(), Arc::clone(&events)).await {
            Ok(layout) => layout,
            Err(e) => {
                outputs::write_trace(&events, &options)?;
                return Err(e);
            }
        };
        outputs::write_outputs(&spec, &layout, &events, &options)?;
        Ok(layout)
    };
    let layout = runner::run(py, task)?.py_err(py)?;
    let value = to_python(py, &layout)?;
    if strict {
        degraded(py, &layout, &value)?;
    }
    Ok(value)
}

/// Raises what `disco generate` exits with for a layout it wrote but did not make as the graph
/// asked: `ModelError` (exit 3) when a model server failed and fallbacks made part of it,
/// `DeadlineError` (exit 5) when the scene missed its deadline; each carries the layout.
fn degraded(py: Python<'_>, layout: &Layout, value: &Py<PyAny>) -> PyResult<()> {
    if let Some(first) = layout.stats.model_failures.first() {
        let message = format!(
            "scene {}: a model server failed and fallbacks made part of the layout: {first}",
            layout.id
        );
        return Err(errors::raise(
            py,
            "ModelError",
            &message,
            &[
                ("reason", first.into_pyobject(py)?.into_any().unbind()),
                ("layout", value.clone_ref(py)),
            ],
        ));
    }
    if layout.stats.deadline_missed {
        let message = format!(
            "scene {}: missed its deadline and fallbacks finished it",
            layout.id
        );
        return Err(errors::raise(
            py,
            "DeadlineError",
            &message,
            &[("layout", value.clone_ref(py))],
        ));
    }
    Ok(())
}

/// Creates the folders the files of `paths` go into, as the CLI does.
fn create_parents<'a>(
    py: Python<'_>,
    paths: impl IntoIterator<Item = &'a PathBuf>,
) -> PyResult<()> {
    for path in paths {
        if let Some(dir) = path.parent().filter(|d| !d.as_os_str().is_empty()) {
            std::fs::create_dir_all(dir)
                .map_err(|source| disco_layout::Error::Write {
                    path: dir.to_path_buf(),
                    source,
                })
                .py_err(py)?;
        }
    }
    Ok(())
}

/// Many scenes at once, as `disco batch`; see `disco_layout.batch`.
#[pyfunction]
#[pyo3(signature = (scenes, out, *, jobs = 4, config = None, sets = Vec::new(), cache = None,
    shard = None, trace = None, on_progress = None, strict = true))]
#[allow(clippy::too_many_arguments)]
fn batch(
    py: Python<'_>,
    scenes: Vec<PathBuf>,
    out: PathBuf,
    jobs: usize,
    config: Option<&Bound<'_, PyAny>>,
    sets: Vec<String>,
    cache: Option<PathBuf>,
    shard: Option<&str>,
    trace: Option<PathBuf>,
    on_progress: Option<Py<PyAny>>,
    strict: bool,
) -> PyResult<Py<PyAny>> {
    if jobs == 0 {
        return Err(PyValueError::new_err("jobs must be at least 1"));
    }
    let graph = convert::graph(config.filter(|c| !c.is_none()), &sets, cache.as_deref())?;
    let mut inputs = batching::collect_scenes(&scenes).py_err(py)?;
    if let Some(shard) = shard {
        let shard: Shard = shard
            .parse()
            .map_err(|e| PyValueError::new_err(format!("shard {shard:?}: {e}")))?;
        inputs = shard.select(&inputs);
    }
    if let Some(trace) = &trace {
        let named: Vec<_> = inputs
            .iter()
            .map(|p| io::NamedPath::new("scenes", p))
            .collect();
        io::refuse_clobbering(&named, &[io::NamedPath::new("trace", trace)], &[]).py_err(py)?;
    }
    std::fs::create_dir_all(&out)
        .map_err(|source| disco_layout::Error::Write {
            path: out.clone(),
            source,
        })
        .py_err(py)?;
    let events = Arc::new(match trace {
        Some(_) => disco_layout::trace::Trace::default(),
        None => disco_layout::trace::Trace::discarding(),
    });
    let options = BatchOptions {
        jobs,
        out_dir: out,
        progress: false,
    };
    let total = inputs.len();
    let registry = roles::registry(py);
    let (tx, rx) = tokio::sync::mpsc::unbounded_channel::<SceneReport>();
    let task = async move {
        let runtime = Runtime::new(graph, registry)?;
        runtime.preflight().await?;
        let notify = move |r: &SceneReport| {
            // The receiver is gone only when the caller stopped waiting.
            let _ = tx.send(r.clone());
        };
        let reports = batching::run_batch_reporting(
            &runtime,
            &inputs,
            &options,
            Arc::clone(&events),
            &notify,
        )
        .await;
        if let Some(path) = &trace {
            events.write_jsonl(path)?;
        }
        Ok::<_, disco_layout::Error>(reports)
    };
    let mut done = 0;
    let reports = runner::run_with(py, task, rx, |py, report| {
        done += 1;
        match &on_progress {
            Some(f) => f
                .call1(py, (done, total, to_python(py, &report)?))
                .map(drop),
            None => Ok(()),
        }
    })?
    .py_err(py)?;
    let value = to_python(py, &reports)?;
    let failed = reports
        .iter()
        .filter(|r| matches!(r.outcome, Outcome::Failed { .. }))
        .count();
    if strict && failed > 0 {
        let scenes = if reports.len() == 1 {
            "scene"
        } else {
            "scenes"
        };
        let message = format!("{failed} of {} {scenes} failed", reports.len());
        return Err(errors::raise(
            py,
            "ScenesFailedError",
            &message,
            &[("reports", value)],
        ));
    }
    Ok(value)
}

/// Makes any layout physically valid, as `disco refine`; see `disco_layout.refine`.
#[pyfunction]
#[pyo3(signature = (scene, layout, *, grid_step_cm = DEFAULT_GRID_STEP_CM, output = None,
    render = None))]
fn refine(
    py: Python<'_>,
    scene: &Bound<'_, PyAny>,
    layout: &Bound<'_, PyAny>,
    grid_step_cm: f64,
    output: Option<PathBuf>,
    render: Option<PathBuf>,
) -> PyResult<Py<PyAny>> {
    if !(grid_step_cm.is_finite() && (0.5..=100.0).contains(&grid_step_cm)) {
        return Err(PyValueError::new_err(
            "grid_step_cm must be between 0.5 and 100 cm",
        ));
    }
    let scene = Scene::of(scene)?;
    let layout_source = convert::Source::of(layout)?;
    let mut inputs = Vec::new();
    inputs.extend(
        scene
            .path
            .as_deref()
            .map(|p| io::NamedPath::new("scene", p)),
    );
    inputs.extend(
        layout_source
            .path()
            .map(|p| io::NamedPath::new("layout", p)),
    );
    let mut outs = Vec::new();
    outs.extend(output.as_deref().map(|p| io::NamedPath::new("output", p)));
    outs.extend(render.as_deref().map(|p| io::NamedPath::new("render", p)));
    io::refuse_clobbering(&inputs, &outs, &[]).py_err(py)?;
    let (draft, missing) = convert::draft(layout, &scene.spec)?;
    let config = PrtConfig {
        grid_step_cm,
        ..PrtConfig::default()
    };
    let spec = scene.spec;
    let task = async move {
        let refined = disco_layout::refine::refine_layout(&spec, draft, &missing, config);
        if let Some(path) = &output {
            io::write_json(path, &refined)?;
        }
        if let Some(png) = &render {
            let bytes = disco_layout::render::render_png(&refined, &RenderOptions::default())?;
            io::write_atomic(png, &bytes)?;
        }
        Ok::<_, disco_layout::Error>(refined)
    };
    let refined = runner::run(py, task)?.py_err(py)?;
    to_python(py, &refined)
}

/// A layout's metrics against its scene, as `disco metrics --json`; see `disco_layout.metrics`.
#[pyfunction]
fn metrics(
    py: Python<'_>,
    scene: &Bound<'_, PyAny>,
    layout: &Bound<'_, PyAny>,
) -> PyResult<Py<PyAny>> {
    let scene = Scene::of(scene)?;
    let (layout, path) = convert::layout(layout)?;
    if let Some(warning) = commands::check_belongs(&scene.spec, &layout, &path).py_err(py)? {
        warn(py, &warning)?;
    }
    let spec = scene.spec;
    let value = runner::run(py, async move { commands::measured(&spec, &layout) })?.py_err(py)?;
    to_python(py, &value)
}

/// A layout drawn from above as PNG bytes, as `disco render`; see `disco_layout.render_png`.
#[pyfunction]
#[pyo3(signature = (layout, *, scene = None, size = DEFAULT_RENDER_PX))]
fn render_png(
    py: Python<'_>,
    layout: &Bound<'_, PyAny>,
    scene: Option<&Bound<'_, PyAny>>,
    size: u32,
) -> PyResult<Py<PyBytes>> {
    if !(16..=16384).contains(&size) {
        return Err(PyValueError::new_err(
            "size must be between 16 and 16384 px",
        ));
    }
    let scene = scene.filter(|s| !s.is_none()).map(Scene::of).transpose()?;
    let layout = convert::drawable(layout, scene.as_ref().map(|s| &s.spec))?;
    let options = RenderOptions {
        long_side_px: size,
        ..RenderOptions::default()
    };
    let png = runner::run(py, async move {
        disco_layout::render::render_png(&layout, &options)
    })?
    .py_err(py)?;
    Ok(PyBytes::new(py, &png).unbind())
}

/// A layout as binary glTF bytes, as `disco export`; see `disco_layout.export_glb`.
#[pyfunction]
#[pyo3(signature = (layout, scene = None, *, wall_height_cm = DEFAULT_WALL_HEIGHT_CM))]
fn export_glb(
    py: Python<'_>,
    layout: &Bound<'_, PyAny>,
    scene: Option<&Bound<'_, PyAny>>,
    wall_height_cm: f64,
) -> PyResult<Py<PyBytes>> {
    check_wall_height(wall_height_cm)?;
    let (layout, path) = convert::layout(layout)?;
    let meshes = match scene.filter(|s| !s.is_none()) {
        Some(scene) => {
            let scene = Scene::of(scene)?;
            if let Some(warning) =
                commands::check_belongs(&scene.spec, &layout, &path).py_err(py)?
            {
                warn(py, &warning)?;
            }
            export::meshes_of(&scene.spec, scene.path.as_deref())
        }
        None => Default::default(),
    };
    let options = ExportOptions {
        wall_height_cm,
        ..ExportOptions::default()
    };
    let glb = runner::run(
        py,
        async move { export::export_glb(&layout, &meshes, &options) },
    )?
    .py_err(py)?;
    Ok(PyBytes::new(py, &glb).unbind())
}

/// The self-contained HTML report of a run, as `disco generate --report` writes it; see
/// `disco_layout.report_html`.
#[pyfunction]
#[pyo3(signature = (scene, layout, trace = None))]
fn report_html(
    py: Python<'_>,
    scene: &Bound<'_, PyAny>,
    layout: &Bound<'_, PyAny>,
    trace: Option<&Bound<'_, Trace>>,
) -> PyResult<String> {
    let scene = Scene::of(scene)?;
    let (layout, _) = convert::layout(layout)?;
    let events = trace.map(|t| t.get().inner.events()).unwrap_or_default();
    let spec = scene.spec;
    runner::run(py, async move {
        disco_layout::report::html::scene_report(&spec, &layout, &events)
    })?
    .py_err(py)
}

/// Registers a Python role; see `disco_layout.register_role`.
#[pyfunction]
fn register_role(role: &str, name: &str, implementation: Py<PyAny>) -> PyResult<()> {
    let role = role_kind(role)?;
    if name.trim().is_empty() {
        return Err(PyValueError::new_err("a role's name must not be empty"));
    }
    roles::register(role, name.to_string(), implementation);
    Ok(())
}

/// Removes a Python role; whether there was one.
#[pyfunction]
fn unregister_role(role: &str, name: &str) -> PyResult<bool> {
    Ok(roles::unregister(role_kind(role)?, name))
}

/// The Python roles registered, as `(role, name)` pairs.
#[pyfunction]
fn registered_roles() -> Vec<(String, String)> {
    roles::registered()
        .into_iter()
        .map(|(role, name)| (role.to_string(), name))
        .collect()
}

/// A role by its protocol name (`planner`, `designer`, `evaluator`, `srt`, `prt`, `patch`).
fn role_kind(role: &str) -> PyResult<RoleKind> {
    serde_json::from_value(serde_json::Value::String(role.to_string())).map_err(|_| {
        PyValueError::new_err(format!(
            "unknown role {role:?}; roles are planner, designer, evaluator, srt, prt, patch"
        ))
    })
}

/// The built-in agent graphs (`disco config list`): name and purpose.
#[pyfunction]
fn presets() -> Vec<(&'static str, &'static str)> {
    disco_layout::config::PRESETS
        .iter()
        .map(|p| (p.name, p.description()))
        .collect()
}

/// `wall_height_cm` as the CLI bounds it: 0 (no walls) to 100 m.
fn check_wall_height(cm: f64) -> PyResult<()> {
    if cm.is_finite() && (0.0..=10_000.0).contains(&cm) {
        Ok(())
    } else {
        Err(PyValueError::new_err(
            "wall_height_cm must be between 0 and 10000 cm",
        ))
    }
}

/// The native module.
#[pymodule]
#[pyo3(name = "_disco")]
fn disco_module(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add("__version__", env!("CARGO_PKG_VERSION"))?;
    m.add("DEFAULT_SCENE_ID", convert::DEFAULT_SCENE_ID)?;
    m.add_class::<Trace>()?;
    m.add_function(wrap_pyfunction!(validate, m)?)?;
    m.add_function(wrap_pyfunction!(generate, m)?)?;
    m.add_function(wrap_pyfunction!(batch, m)?)?;
    m.add_function(wrap_pyfunction!(refine, m)?)?;
    m.add_function(wrap_pyfunction!(metrics, m)?)?;
    m.add_function(wrap_pyfunction!(render_png, m)?)?;
    m.add_function(wrap_pyfunction!(export_glb, m)?)?;
    m.add_function(wrap_pyfunction!(report_html, m)?)?;
    m.add_function(wrap_pyfunction!(register_role, m)?)?;
    m.add_function(wrap_pyfunction!(unregister_role, m)?)?;
    m.add_function(wrap_pyfunction!(registered_roles, m)?)?;
    m.add_function(wrap_pyfunction!(presets, m)?)?;
    Ok(())
}
