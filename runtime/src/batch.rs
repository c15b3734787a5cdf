//! Many scenes at once: a bounded number in flight, a progress bar, outputs written atomically
//! as `OUT/<id>.json`, finished scenes skipped on a rerun, one failing scene reported while the
//! rest finish.

use std::collections::HashMap;
use std::path::{Path, PathBuf};
use std::sync::Arc;
use std::time::Instant;

use futures::StreamExt;
use indicatif::{ProgressBar, ProgressDrawTarget, ProgressStyle};
use serde::Serialize;

use super::Runtime;
use crate::trace::Trace;
use disco_core::error::{Error, Result};
use disco_core::layout::Layout;
use disco_core::metrics::{Metrics, measure};
use disco_core::scene::SceneSpec;

/// How a batch runs.
#[derive(Debug, Clone)]
pub struct BatchOptions {
    /// Scenes in flight at once.
    pub jobs: usize,
    /// Where `<id>.json` outputs go.
    pub out_dir: PathBuf,
    /// Draw a progress bar (only shown on a terminal).
    pub progress: bool,
}

/// What happened to one scene.
#[derive(Debug, Clone, PartialEq, Serialize)]
#[serde(tag = "status", rename_all = "snake_case")]
pub enum Outcome {
    /// Generated and written.
    Done,
    /// Its output already existed and was valid.
    Skipped,
    /// It could not be generated; the reason.
    Failed {
        /// Why.
        reason: String,
    },
}

/// One scene of a batch.
#[derive(Debug, Clone, Serialize)]
pub struct SceneReport {
    /// The scene file.
    pub input: PathBuf,
    /// The scene's id (the file stem when the file could not be read).
    pub id: String,
    /// The scene's room type (`None` when the file could not be read).
    pub room_type: Option<String>,
    /// What happened.
    #[serde(flatten)]
    pub outcome: Outcome,
    /// Metrics of the written (or existing) layout.
    pub metrics: Option<Metrics>,
    /// Time spent on it, in milliseconds.
    pub wall_ms: u64,
}

/// The scene files named by `inputs`: files as given, folders expanded to their `*.json` files
/// (sorted, layouts `*.layout.json` left out).
pub fn collect_scenes(inputs: &[PathBuf]) -> Result<Vec<PathBuf>> {
    let mut out = Vec::new();
    for input in inputs {
        if input.is_dir() {
            let entries = std::fs::read_dir(input).map_err(|source| Error::Read {
                path: input.clone(),
                source,
            })?;
            let mut files: Vec<PathBuf> = entries
                .filter_map(|e| e.ok().map(|e| e.path()))
                // Only regular files: a FIFO or socket in the folder would block the batch.
                .filter(|p| p.metadata().is_ok_and(|m| m.is_file()))
                .filter(|p| {
                    let name = p
                        .file_name()
                        .map(|n| n.to_string_lossy().into_owned())
                        .unwrap_or_default();
                    name.ends_with(".json") && !name.ends_with(".layout.json")
                })
                .collect();
            files.sort();
            out.extend(files);
        } else {
            out.push(input.clone());
        }
    }
    Ok(out)
}

/// Runs every scene of `inputs` with at most `options.jobs` in flight.
pub async fn run_batch(
    runtime: &Runtime,
    inputs: &[PathBuf],
    options: &BatchOptions,
    trace: Arc<Trace>,
) -> Vec<SceneReport> {
    run_batch_reporting(runtime, inputs, options, trace, &|_| {}).await
}

/// [`run_batch`], telling `on_report` of each scene's report as soon as that scene is done
/// (skipped and failed scenes too), e.g. to drive a progress display of the caller's own.
pub async fn run_batch_reporting(
    runtime: &Runtime,
    inputs: &[PathBuf],
    options: &BatchOptions,
    trace: Arc<Trace>,
    on_report: &(dyn Fn(&SceneReport) + Sync),
) -> Vec<SceneReport> {
    let bar = if options.progress {
        ProgressBar::with_draw_target(Some(inputs.len() as u64), ProgressDrawTarget::stderr())
    } else {
        ProgressBar::hidden()
    };
    bar.set_style(
        ProgressStyle::with_template(
            "{spinner} [{elapsed_precise}] {bar:30} {pos}/{len} scenes {msg}",
        )
        .unwrap_or_else(|_| ProgressStyle::default_bar()),
    );
    disco_core::io::clean_stale_temp_files(&options.out_dir);
    let scenes = load_scenes(inputs, &options.out_dir);
    let mut reports: Vec<SceneReport> = futures::stream::iter(scenes)
        .map(|(path, scene)| {
            let trace = Arc::clone(&trace);
            let bar = bar.clone();
            async move {
                let report = run_one(runtime, &path, scene, &options.out_dir, trace).await;
                if let Outcome::Failed { reason } = &report.outcome {
                    let line = format!("failed: {}: {reason}", path.display());
                    // A hidden bar swallows println; failures must still be heard.
                    if bar.is_hidden() {
                        disco_core::io::to_stderr(&format!("{line}\n"));
                    } else {
                        bar.println(line);
                    }
                }
                bar.inc(1);
                on_report(&report);
                report
            }
        })
        .buffer_unordered(options.jobs.max(1))
        .collect()
        .await;
    bar.finish_and_clear();
    reports.sort_by(|a, b| a.input.cmp(&b.input));
    reports
}

/// Reads every scene up front, so that two scenes that would write the same output file are
/// both refused (naming each other) instead of one silently taking the other's place, and a
/// scene whose output would replace an input file is refused.
fn load_scenes(inputs: &[PathBuf], out_dir: &Path) -> Vec<(PathBuf, Result<SceneSpec>)> {
    let mut loaded: Vec<(PathBuf, Result<SceneSpec>)> = inputs
        .iter()
        .map(|p| (p.clone(), SceneSpec::load(p)))
        .collect();
    let mut by_output: HashMap<PathBuf, Vec<usize>> = HashMap::new();
    for (i, (_, scene)) in loaded.iter().enumerate() {
        if let Ok(scene) = scene {
            by_output
                .entry(output_path(out_dir, &scene.id))
                .or_default()
                .push(i);
        }
    }
    let inputs_canonical: HashMap<PathBuf, usize> = inputs
        .iter()
        .enumerate()
        .filter_map(|(i, p)| p.canonicalize().ok().map(|c| (c, i)))
        .collect();
    for (out, users) in by_output {
        let clash = |i: usize| -> Option<String> {
            let others: Vec<String> = users
                .iter()
                .filter(|&&j| j != i)
                .map(|&j| inputs[j].display().to_string())
                .collect();
            if !others.is_empty() {
                return Some(format!(
                    "its id would write {} like {}: give each scene its own id",
                    out.display(),
                    others.join(", ")
                ));
            }
            let canonical = out.canonicalize().ok()?;
            inputs_canonical.get(&canonical).map(|&j| {
                format!(
                    "its output {} would replace the input {}: choose another --out folder",
                    out.display(),
                    inputs[j].display()
                )
            })
        };
        for &i in &users {
            if let Some(why) = clash(i) {
                loaded[i].1 = Err(Error::invalid(&inputs[i], "id", why));
            }
        }
    }
    loaded
}

/// Where scene `id`'s layout goes.
fn output_path(out_dir: &Path, id: &str) -> PathBuf {
    out_dir.join(format!("{}.json", file_safe(id)))
}

async fn run_one(
    runtime: &Runtime,
    path: &Path,
    scene: Result<SceneSpec>,
    out_dir: &Path,
    trace: Arc<Trace>,
) -> SceneReport {
    let t0 = Instant::now();
    let stem = path
        .file_stem()
        .map(|s| s.to_string_lossy().into_owned())
        .unwrap_or_default();
    let report = |id: String, outcome: Outcome, metrics: Option<Metrics>| SceneReport {
        input: path.to_path_buf(),
        room_type: None,
        id,
        outcome,
        metrics,
        wall_ms: t0.elapsed().as_millis() as u64,
    };
    let failed = |e: Error| Outcome::Failed {
        reason: e.to_string(),
    };
    let scene = match scene {
        Ok(s) => s,
        Err(e) => return report(stem, failed(e), None),
    };
    let id = scene.id.clone();
    let room_type = Some(scene.room_type.clone());
    let report = |id: String, outcome: Outcome, metrics: Option<Metrics>| SceneReport {
        room_type: room_type.clone(),
        ..report(id, outcome, metrics)
    };
    let out = output_path(out_dir, &id);
    match previous_layout(&out, &scene) {
        Ok(Some(existing)) => return report(id, Outcome::Skipped, Some(measure(&existing))),
        Ok(None) => {}
        Err(e) => return report(id, failed(e), None),
    }
    match runtime.generate(scene, trace).await {
        Ok(layout) => match disco_core::io::write_json(&out, &layout) {
            Ok(()) => report(id, Outcome::Done, Some(measure(&layout))),
            Err(e) => report(id, failed(e), None),
        },
        Err(e) => report(id, failed(e), None),
    }
}

/// The layout an earlier run wrote at `out` for exactly this scene, if any. A layout made from
/// another version of the scene (or carrying no fingerprint) is `None`: the scene runs again and
/// replaces it. A file there that is not a layout is an error: it is never overwritten.
fn previous_layout(out: &Path, scene: &SceneSpec) -> Result<Option<Layout>> {
    if !out.exists() {
        return Ok(None);
    }
    match Layout::load(out) {
        Ok(layout) if layout.stats.scene_sha256.as_deref() == Some(scene.digest().as_str()) => {
            Ok(Some(layout))
        }
        Ok(_) => Ok(None),
        Err(e) => Err(Error::invalid(
            out,
            "(file)",
            format!("exists and is not a layout, so it is not overwritten ({e})"),
        )),
    }
}

/// The file name stem of scene `id`'s outputs (see [`disco_core::io::safe_file_stem`]).
pub fn file_safe(id: &str) -> String {
    disco_core::io::safe_file_stem(id)
}

/// A plain-text table of the reports: one row per scene, the mean of the measured ones, and a
/// total.
pub fn summary_table(reports: &[SceneReport]) -> String {
    let mut s = format!(
        "{:<28} {:<8} {:>7} {:>6} {:>6} {:>7} {:>6} {:>8}\n",
        "scene", "status", "placed", "Col%", "OOB%", "constr%", "reach%", "ms"
    );
    for r in reports {
        let status = match &r.outcome {
            Outcome::Done => "done",
            Outcome::Skipped => "skipped",
            Outcome::Failed { .. } => "FAILED",
        };
        match &r.metrics {
            Some(m) => s.push_str(&format!(
                "{:<28} {:<8} {:>7} {:>6.1} {:>6.2} {:>7.1} {:>6.1} {:>8}\n",
                truncate(&r.id, 28),
                status,
                format!("{}/{}", m.placed, m.assets),
                m.collision_pct,
                m.oob_pct,
                m.constraint_pct,
                m.reach_pct,
                r.wall_ms
            )),
            None => s.push_str(&format!("{:<28} {:<8}\n", truncate(&r.id, 28), status)),
        }
    }
    let done = reports
        .iter()
        .filter(|r| r.outcome == Outcome::Done)
        .count();
    let skipped = reports
        .iter()
        .filter(|r| r.outcome == Outcome::Skipped)
        .count();
    let failed = reports.len() - done - skipped;
    let measured: Vec<_> = reports.iter().filter_map(|r| r.metrics.as_ref()).collect();
    if !measured.is_empty() {
        let n = measured.len() as f64;
        let mean = |f: fn(&disco_core::metrics::Metrics) -> f64| {
            measured.iter().map(|m| f(m)).sum::<f64>() / n
        };
        s.push_str(&format!(
            "{:<28} {:<8} {:>7} {:>6.1} {:>6.2} {:>7.1} {:>6.1}\n",
            "mean",
            "",
            "",
            mean(|m| m.collision_pct),
            mean(|m| m.oob_pct),
            mean(|m| m.constraint_pct),
            mean(|m| m.reach_pct),
        ));
    }
    s.push_str(&format!(
        "{} {}: {done} done, {skipped} skipped, {failed} failed\n",
        reports.len(),
        if reports.len() == 1 {
            "scene"
        } else {
            "scenes"
        }
    ));
    s
}

fn truncate(s: &str, n: usize) -> String {
    if s.chars().count() <= n {
        s.to_string()
    } else {
        s.chars().take(n - 1).collect::<String>() + "…"
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::config::GraphConfig;
    use crate::registry::Registry;

    fn scene_json(id: &str, assets: &str) -> String {
        format!(
            r#"{{"id": {id:?}, "prompt": "a bedroom", "room_type": "bedroom",
                "room": {{"width": 400, "depth": 350}}, "assets": [{assets}]}}"#
        )
    }
    const BED: &str = r#"{"name": "bed-0", "category": "bed", "size": [160, 210, 100]}"#;
    const LAMP: &str = r#"{"name": "lamp-0", "category": "floor lamp", "size": [40, 40, 160]}"#;

    async fn batch(inputs: &[PathBuf], out: &Path) -> Vec<SceneReport> {
        let runtime =
            Runtime::new(GraphConfig::load(None, &[]).unwrap(), Registry::builtin()).unwrap();
        let options = BatchOptions {
            jobs: 2,
            out_dir: out.to_path_buf(),
            progress: false,
        };
        run_batch(&runtime, inputs, &options, Arc::new(Trace::default())).await
    }

    fn failure(r: &SceneReport) -> &str {
        match &r.outcome {
            Outcome::Failed { reason } => reason,
            other => panic!("expected a failure, got {other:?}"),
        }
    }

    #[tokio::test]
    async fn two_scenes_with_one_id_are_both_refused_and_name_each_other() {
        let dir = tempfile::tempdir().unwrap();
        let (a, b) = (dir.path().join("a.json"), dir.path().join("b.json"));
        std::fs::write(&a, scene_json("same", BED)).unwrap();
        std::fs::write(&b, scene_json("same", LAMP)).unwrap();
        let out = dir.path().join("out");
        std::fs::create_dir(&out).unwrap();
        let reports = batch(&[a, b], &out).await;
        assert!(failure(&reports[0]).contains("b.json"), "{reports:?}");
        assert!(failure(&reports[1]).contains("a.json"), "{reports:?}");
        assert!(!out.join("same.json").exists());
    }

    #[tokio::test]
    async fn ids_that_differ_only_in_odd_characters_get_their_own_files() {
        let dir = tempfile::tempdir().unwrap();
        let mut inputs = Vec::new();
        for (i, id) in ["a/b", "a_b", "a?b", ".."].iter().enumerate() {
            let p = dir.path().join(format!("s{i}.json"));
            std::fs::write(&p, scene_json(id, BED)).unwrap();
            inputs.push(p);
        }
        let out = dir.path().join("out");
        std::fs::create_dir(&out).unwrap();
        let reports = batch(&inputs, &out).await;
        assert!(
            reports.iter().all(|r| r.outcome == Outcome::Done),
            "{reports:?}"
        );
        let written = std::fs::read_dir(&out).unwrap().count();
        assert_eq!(written, 4, "one file per scene, all inside the folder");
    }

    #[tokio::test]
    async fn an_edited_scene_runs_again_and_an_unchanged_one_is_skipped() {
        let dir = tempfile::tempdir().unwrap();
        let scene = dir.path().join("bedroom.json");
        std::fs::write(&scene, scene_json("bedroom", BED)).unwrap();
        let out = dir.path().join("out");
        std::fs::create_dir(&out).unwrap();
        let first = batch(std::slice::from_ref(&scene), &out).await;
        assert_eq!(first[0].outcome, Outcome::Done);
        let again = batch(std::slice::from_ref(&scene), &out).await;
        assert_eq!(again[0].outcome, Outcome::Skipped);
        std::fs::write(&scene, scene_json("bedroom", &format!("{BED}, {LAMP}"))).unwrap();
        let edited = batch(std::slice::from_ref(&scene), &out).await;
        assert_eq!(edited[0].outcome, Outcome::Done);
        let layout = Layout::load(&out.join("bedroom.json")).unwrap();
        let names: Vec<&str> = layout
            .objects
            .iter()
            .map(|o| o.name.as_str())
            .chain(layout.dropped.iter().map(|d| d.name.as_str()))
            .collect();
        assert!(names.contains(&"lamp-0"), "{names:?}");
    }

    #[tokio::test]
    async fn outputs_never_replace_inputs() {
        let dir = tempfile::tempdir().unwrap();
        let scene = dir.path().join("bedroom.json");
        let text = scene_json("bedroom", BED);
        std::fs::write(&scene, &text).unwrap();
        let reports = batch(
            &collect_scenes(&[dir.path().to_path_buf()]).unwrap(),
            dir.path(),
        )
        .await;
        assert!(
            failure(&reports[0]).contains("would replace the input"),
            "{reports:?}"
        );
        assert_eq!(std::fs::read_to_string(&scene).unwrap(), text);
        // Nor is any other file that is not a layout.
        let out = dir.path().join("out");
        std::fs::create_dir(&out).unwrap();
        std::fs::write(out.join("bedroom.json"), "my notes").unwrap();
        let reports = batch(std::slice::from_ref(&scene), &out).await;
        assert!(failure(&reports[0]).contains("not a layout"), "{reports:?}");
        assert_eq!(
            std::fs::read_to_string(out.join("bedroom.json")).unwrap(),
            "my notes"
        );
    }

    #[cfg(unix)]
    #[tokio::test]
    async fn a_fifo_in_a_scene_folder_is_passed_over() {
        let dir = tempfile::tempdir().unwrap();
        std::fs::write(dir.path().join("bedroom.json"), scene_json("bedroom", BED)).unwrap();
        let fifo = dir.path().join("stuck.json");
        let made = std::process::Command::new("mkfifo").arg(&fifo).status();
        if !made.is_ok_and(|s| s.success()) {
            return;
        }
        let scenes = collect_scenes(&[dir.path().to_path_buf()]).unwrap();
        assert_eq!(scenes, vec![dir.path().join("bedroom.json")]);
        // Named on its own, it is refused, not read.
        let out = dir.path().join("out");
        std::fs::create_dir(&out).unwrap();
        let reports = batch(&[fifo], &out).await;
        assert!(
            failure(&reports[0]).contains("not a regular file"),
            "{reports:?}"
        );
    }
}
