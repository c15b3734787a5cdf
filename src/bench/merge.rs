//! A benchmark run split into shards (`disco bench --shard I/N`, one process per shard, each
//! into its own folder) and merged back (`disco bench merge OUT SHARD_DIR...`) into the
//! `results.json`, `table.json`, `table.md` and `layouts/` a single process would have written.
//!
//! Each shard's folder holds a manifest, `shard.json`: which shard it is, and every scene id of
//! the whole run in the order a single run lists its results. The merge checks that the shards
//! agree on that list, refuses a scene that two shards both report (naming it and both
//! folders), and refuses to write anything while a scene of the list has no result (naming the
//! scenes and the shards not given), so a merged table never silently loses or counts a scene
//! twice. Wall times are the shards' own: a merged table equals a single run's except for the
//! time column (`s / scene`, `wall_ms`), which measures the processes that made the layouts.

use std::collections::HashMap;
use std::path::{Path, PathBuf};

use serde::{Deserialize, Serialize};

use super::{MethodRun, SceneResult, write_tables};
use crate::error::Error;
use crate::runtime::batch::file_safe;
use crate::runtime::shard::{Shard, reported_ids};

/// The manifest file in each shard's output folder.
pub const MANIFEST: &str = "shard.json";

/// How many scene names an error lists before saying how many more there are.
const NAMES_SHOWN: usize = 20;

/// What `shard.json` records about one shard of a split run.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct ShardManifest {
    /// This shard's number, from 0.
    pub index: u32,
    /// How many shards the run is split into.
    pub count: u32,
    /// Every scene of the whole run (all shards), by the id its result carries, in the order a
    /// single run lists its results.
    pub scenes: Vec<String>,
}

/// Why shard outputs could not be merged.
#[derive(Debug, thiserror::Error)]
pub enum MergeError {
    /// A file could not be read or written, or was not what it should be.
    #[error(transparent)]
    Io(#[from] Error),
    /// Two shard folders do not belong to the same split run.
    #[error("{a} and {b} are not shards of the same run: {why}")]
    Mismatch {
        /// One folder.
        a: PathBuf,
        /// The other.
        b: PathBuf,
        /// What differs.
        why: String,
    },
    /// Scenes reported by more than one shard folder.
    #[error("{} in more than one shard: {}", count(.0.len()), overlap_list(.0))]
    Overlap(Vec<(String, PathBuf, PathBuf)>),
    /// Scenes of the run that no shard reported; nothing was written.
    #[error("{} of {total} missing, nothing written: {}{}", count(.missing.len()), name_list(.missing), absent_list(.absent))]
    Missing {
        /// The scenes without a result.
        missing: Vec<String>,
        /// Scenes in the run.
        total: usize,
        /// Shards (`I/N`) no folder was given for, or whose folder has no `results.json` yet.
        absent: Vec<String>,
    },
}

fn count(n: usize) -> String {
    if n == 1 {
        "1 scene".into()
    } else {
        format!("{n} scenes")
    }
}

fn name_list(names: &[String]) -> String {
    let mut s = names
        .iter()
        .take(NAMES_SHOWN)
        .cloned()
        .collect::<Vec<_>>()
        .join(", ");
    if names.len() > NAMES_SHOWN {
        s.push_str(&format!(" and {} more", names.len() - NAMES_SHOWN));
    }
    s
}

fn overlap_list(overlaps: &[(String, PathBuf, PathBuf)]) -> String {
    let named: Vec<String> = overlaps
        .iter()
        .map(|(id, a, b)| format!("{id} ({} and {})", a.display(), b.display()))
        .collect();
    name_list(&named)
}

fn absent_list(absent: &[String]) -> String {
    if absent.is_empty() {
        String::new()
    } else {
        format!(" (no results from shard {})", absent.join(", "))
    }
}

/// Prepares `out_dir` for shard `shard` of a run over `inputs`: writes its manifest (refusing a
/// folder that already holds another shard's outputs) and returns this shard's scene files.
pub fn prepare_shard(
    out_dir: &Path,
    shard: Shard,
    inputs: &[PathBuf],
) -> crate::error::Result<Vec<PathBuf>> {
    let path = out_dir.join(MANIFEST);
    let manifest = ShardManifest {
        index: shard.index(),
        count: shard.count(),
        scenes: reported_ids(inputs),
    };
    if path.exists() {
        let old: ShardManifest = crate::io::parse_json(&path, &crate::io::read_text(&path)?)?;
        if (old.index, old.count) != (manifest.index, manifest.count) {
            return Err(Error::invalid(
                &path,
                "index",
                format!(
                    "this folder holds shard {}/{}'s outputs, not {shard}'s: give each shard its own --out folder",
                    old.index, old.count
                ),
            ));
        }
    }
    std::fs::create_dir_all(out_dir).map_err(|source| Error::Write {
        path: out_dir.to_path_buf(),
        source,
    })?;
    crate::io::write_json(&path, &manifest)?;
    Ok(shard.select(inputs))
}

/// One shard folder as read for a merge.
struct ShardOutput {
    dir: PathBuf,
    manifest: ShardManifest,
    /// `None` when the shard has not finished (no `results.json` yet).
    results: Option<Vec<SceneResult>>,
}

fn read_shard(dir: &Path) -> Result<ShardOutput, MergeError> {
    let path = dir.join(MANIFEST);
    if !path.exists() {
        return Err(Error::invalid(
            &path,
            "(file)",
            "missing: not the output folder of `disco bench --shard I/N`",
        )
        .into());
    }
    let manifest: ShardManifest = crate::io::parse_json(&path, &crate::io::read_text(&path)?)?;
    let results_path = dir.join("results.json");
    let results = if results_path.exists() {
        Some(crate::io::parse_json(
            &results_path,
            &crate::io::read_text(&results_path)?,
        )?)
    } else {
        None
    };
    Ok(ShardOutput {
        dir: dir.to_path_buf(),
        manifest,
        results,
    })
}

/// Merges the shard folders `shard_dirs` into `out_dir`: every scene's result once, in a single
/// run's order, the tables over all of them, and the layouts copied to `out_dir/layouts/`.
pub fn merge_shards(out_dir: &Path, shard_dirs: &[PathBuf]) -> Result<MethodRun, MergeError> {
    for dir in shard_dirs {
        if crate::io::lies_within(out_dir, dir) {
            return Err(Error::invalid(
                out_dir,
                "OUT_DIR",
                format!(
                    "is the shard folder {} or lies inside it: the merged tables would mix with a shard's own; choose another folder",
                    dir.display()
                ),
            )
            .into());
        }
    }
    let shards = shard_dirs
        .iter()
        .map(|d| read_shard(d))
        .collect::<Result<Vec<_>, _>>()?;
    let Some(first) = shards.first() else {
        return Err(Error::invalid(out_dir, "SHARD_DIR", "no shard folder given").into());
    };
    for other in &shards[1..] {
        check_same_run(first, other)?;
    }
    let results = collect_results(&shards)?;
    // Every layout is read and checked before anything is written.
    let copies = results
        .iter()
        .filter(|(result, _)| result.metrics.is_some())
        .map(|(result, dir)| checked_layout(&result.id, dir))
        .collect::<Result<Vec<_>, _>>()?;
    let layouts = out_dir.join("layouts");
    let existed = layouts.is_dir();
    let copied = write_layouts(&layouts, &copies);
    if copied.is_err() && !existed {
        // Leave no empty folder behind (`remove_dir` removes only an empty one).
        let _ = std::fs::remove_dir(&layouts);
    }
    copied?;
    let results: Vec<SceneResult> = results.into_iter().map(|(r, _)| r).collect();
    let table = write_tables(out_dir, &results)?;
    Ok(MethodRun { results, table })
}

/// Scene `id`'s layout in shard folder `dir`, read and checked: a layout file (every object
/// complete, the room valid) of that very scene. Returns its file name and text.
fn checked_layout(id: &str, dir: &Path) -> Result<(String, String), MergeError> {
    let name = format!("{}.json", file_safe(id));
    let from = dir.join("layouts").join(&name);
    let text = crate::io::read_text(&from)?;
    let layout: crate::Layout = crate::io::parse_json(&from, &text)?;
    layout.validate(&from)?;
    if layout.id != id {
        return Err(Error::invalid(
            &from,
            "id",
            format!(
                "is {:?}, but the shard's results.json lists this file for scene {id:?}",
                layout.id
            ),
        )
        .into());
    }
    Ok((name, text))
}

/// Writes the checked layouts into `dir`, creating it.
fn write_layouts(dir: &Path, copies: &[(String, String)]) -> crate::error::Result<()> {
    std::fs::create_dir_all(dir).map_err(|source| Error::Write {
        path: dir.to_path_buf(),
        source,
    })?;
    for (name, text) in copies {
        crate::io::write_atomic(&dir.join(name), text.as_bytes())?;
    }
    Ok(())
}

fn check_same_run(a: &ShardOutput, b: &ShardOutput) -> Result<(), MergeError> {
    let mismatch = |why: String| MergeError::Mismatch {
        a: a.dir.clone(),
        b: b.dir.clone(),
        why,
    };
    if a.manifest.count != b.manifest.count {
        return Err(mismatch(format!(
            "split into {} and into {} shards",
            a.manifest.count, b.manifest.count
        )));
    }
    if a.manifest.scenes != b.manifest.scenes {
        return Err(mismatch("run over different scene sets".into()));
    }
    Ok(())
}

/// Every scene's result with the folder it came from, in the manifest's order; refuses
/// overlaps, results for scenes outside the run, and missing scenes.
fn collect_results(shards: &[ShardOutput]) -> Result<Vec<(SceneResult, PathBuf)>, MergeError> {
    let order = &shards[0].manifest.scenes;
    let position: HashMap<&str, usize> = order
        .iter()
        .enumerate()
        .map(|(i, id)| (id.as_str(), i))
        .collect();
    let mut slots: Vec<Option<(SceneResult, PathBuf)>> = vec![None; order.len()];
    let mut overlaps = Vec::new();
    for shard in shards {
        for result in shard.results.iter().flatten() {
            let Some(&i) = position.get(result.id.as_str()) else {
                return Err(Error::invalid(
                    &shard.dir.join("results.json"),
                    "id",
                    format!(
                        "{} is not a scene of the run its shard.json lists",
                        result.id
                    ),
                )
                .into());
            };
            if let Some((_, first)) = &slots[i] {
                overlaps.push((result.id.clone(), first.clone(), shard.dir.clone()));
                continue;
            }
            slots[i] = Some((result.clone(), shard.dir.clone()));
        }
    }
    if !overlaps.is_empty() {
        return Err(MergeError::Overlap(overlaps));
    }
    let missing: Vec<String> = order
        .iter()
        .zip(&slots)
        .filter(|(_, s)| s.is_none())
        .map(|(id, _)| id.clone())
        .collect();
    if !missing.is_empty() {
        let count = shards[0].manifest.count;
        let absent = (0..count)
            .filter(|i| {
                !shards
                    .iter()
                    .any(|s| s.manifest.index == *i && s.results.is_some())
            })
            .map(|i| format!("{i}/{count}"))
            .collect();
        return Err(MergeError::Missing {
            missing,
            total: order.len(),
            absent,
        });
    }
    Ok(slots.into_iter().flatten().collect())
}

#[cfg(test)]
mod tests {
    use super::*;

    fn result(id: &str, category: &str) -> SceneResult {
        SceneResult {
            id: id.into(),
            category: category.into(),
            metrics: None,
            failure: Some("broken".into()),
            llm_calls: 0,
            tokens: 0,
            wall_ms: 5,
            judge: None,
        }
    }

    /// A shard folder of a 3-shard run over `all`, reporting `ids` (or unfinished with `None`).
    fn shard_dir(root: &Path, index: u32, all: &[&str], ids: Option<&[&str]>) -> PathBuf {
        let dir = root.join(format!("shard-{index}"));
        std::fs::create_dir_all(&dir).unwrap();
        let manifest = ShardManifest {
            index,
            count: 3,
            scenes: all.iter().map(|s| s.to_string()).collect(),
        };
        crate::io::write_json(&dir.join(MANIFEST), &manifest).unwrap();
        if let Some(ids) = ids {
            let results: Vec<SceneResult> = ids.iter().map(|id| result(id, "bedroom")).collect();
            crate::io::write_json(&dir.join("results.json"), &results).unwrap();
        }
        dir
    }

    const ALL: &[&str] = &["a", "b", "c", "d"];

    #[test]
    fn shards_merge_into_the_single_run_order() {
        let root = tempfile::tempdir().unwrap();
        let dirs = [
            shard_dir(root.path(), 0, ALL, Some(&["d", "a"][..])),
            shard_dir(root.path(), 1, ALL, Some(&[][..])),
            shard_dir(root.path(), 2, ALL, Some(&["c", "b"][..])),
        ];
        let out = root.path().join("merged");
        let run = merge_shards(&out, &dirs).unwrap();
        let ids: Vec<&str> = run.results.iter().map(|r| r.id.as_str()).collect();
        assert_eq!(ids, ALL);
        assert_eq!(run.table.title, "4 scenes");
        assert_eq!(run.table.rows.last().unwrap().failed, 4);
        assert!(out.join("table.md").exists() && out.join("results.json").exists());
    }

    #[test]
    fn a_scene_in_two_shards_is_refused_by_name() {
        let root = tempfile::tempdir().unwrap();
        let dirs = [
            shard_dir(root.path(), 0, ALL, Some(&["a", "b"][..])),
            shard_dir(root.path(), 1, ALL, Some(&["b", "c", "d"][..])),
        ];
        let out = root.path().join("merged");
        let e = merge_shards(&out, &dirs).unwrap_err().to_string();
        assert!(e.starts_with("1 scene in more than one shard: b ("), "{e}");
        assert!(e.contains("shard-0") && e.contains("shard-1"), "{e}");
        assert!(!out.join("table.md").exists());
    }

    #[test]
    fn missing_scenes_and_shards_are_named_and_nothing_is_written() {
        let root = tempfile::tempdir().unwrap();
        let dirs = [
            shard_dir(root.path(), 0, ALL, Some(&["a"][..])),
            shard_dir(root.path(), 1, ALL, None),
        ];
        let out = root.path().join("merged");
        let e = merge_shards(&out, &dirs).unwrap_err();
        assert!(matches!(e, MergeError::Missing { .. }));
        assert_eq!(
            e.to_string(),
            "3 scenes of 4 missing, nothing written: b, c, d (no results from shard 1/3, 2/3)"
        );
        assert!(!out.join("results.json").exists());
    }

    #[test]
    fn shards_of_different_runs_are_refused() {
        let root = tempfile::tempdir().unwrap();
        let a = shard_dir(root.path(), 0, ALL, Some(&[][..]));
        let b = shard_dir(root.path(), 1, &["a", "b"], Some(&[][..]));
        let e = merge_shards(&root.path().join("m"), &[a, b]).unwrap_err();
        assert!(e.to_string().contains("different scene sets"), "{e}");
        let plain = root.path().join("plain");
        std::fs::create_dir_all(&plain).unwrap();
        let e = merge_shards(&root.path().join("m"), &[plain]).unwrap_err();
        assert!(e.to_string().contains("--shard"), "{e}");
    }

    /// Shard `index` of a 1-shard run over scene "a" that finished it, with `layout` as its
    /// layout file's text.
    fn finished_shard(root: &Path, layout: &str) -> PathBuf {
        let dir = root.join("shard-0");
        std::fs::create_dir_all(dir.join("layouts")).unwrap();
        let manifest = ShardManifest {
            index: 0,
            count: 1,
            scenes: vec!["a".into()],
        };
        crate::io::write_json(&dir.join(MANIFEST), &manifest).unwrap();
        let mut done = result("a", "bedroom");
        let (_, good) = crate::synth::bedroom();
        done.metrics = Some(crate::metrics::measure(&good));
        done.failure = None;
        crate::io::write_json(&dir.join("results.json"), &[done]).unwrap();
        std::fs::write(dir.join("layouts/a.json"), layout).unwrap();
        dir
    }

    fn layout_of(id: &str) -> String {
        let (_, mut layout) = crate::synth::bedroom();
        layout.id = id.into();
        serde_json::to_string(&layout).unwrap()
    }

    #[test]
    fn a_shard_folder_or_one_inside_it_is_refused_as_the_output() {
        let root = tempfile::tempdir().unwrap();
        let shard = finished_shard(root.path(), &layout_of("a"));
        for out in [shard.clone(), shard.join("merged"), shard.join("x/../")] {
            let e = merge_shards(&out, std::slice::from_ref(&shard))
                .unwrap_err()
                .to_string();
            assert!(e.contains("OUT_DIR: is the shard folder"), "{e}");
        }
        assert!(!shard.join("table.md").exists());
        let out = root.path().join("merged");
        merge_shards(&out, &[shard]).unwrap();
        assert!(out.join("layouts/a.json").is_file());
    }

    #[test]
    fn a_broken_or_foreign_layout_is_refused_and_no_empty_folder_is_left() {
        let root = tempfile::tempdir().unwrap();
        let out = root.path().join("merged");
        let broken = finished_shard(root.path(), "{\"id\": \"a\", \"objects\": [");
        let e = merge_shards(&out, &[broken]).unwrap_err().to_string();
        assert!(e.contains("layouts/a.json"), "{e}");
        assert!(!out.join("layouts").exists(), "an empty layouts/ is left");
        assert!(!out.join("results.json").exists());
        let root = tempfile::tempdir().unwrap();
        let foreign = finished_shard(root.path(), &layout_of("b"));
        let e = merge_shards(&out, &[foreign]).unwrap_err().to_string();
        assert!(e.contains("lists this file for scene \"a\""), "{e}");
        assert!(!out.join("layouts").exists());
    }

    #[test]
    fn a_folder_keeps_to_one_shard() {
        let root = tempfile::tempdir().unwrap();
        let out = root.path().join("out");
        prepare_shard(&out, Shard::new(0, 3).unwrap(), &[]).unwrap();
        prepare_shard(&out, Shard::new(0, 3).unwrap(), &[]).unwrap();
        let e = prepare_shard(&out, Shard::new(1, 3).unwrap(), &[]).unwrap_err();
        assert!(e.to_string().contains("its own --out"), "{e}");
    }
}
