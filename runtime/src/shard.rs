//! Splitting a scene set across processes: `--shard I/N` keeps the scenes whose id hashes to
//! shard `I` of `N`, so N processes (Slurm array tasks, Kubernetes indexed pods) together cover
//! every scene exactly once.
//!
//! The split is a pure function of the scene id: `fnv1a_64(id as UTF-8) % N == I`, with the
//! 64-bit FNV-1a hash (offset basis `0xcbf29ce484222325`, prime `0x100000001b3`). It does not
//! depend on the machine, the process, the file's path or the order the files are listed in,
//! so a retried task picks exactly the scenes it had before. Shards are numbered from 0, like
//! Kubernetes' `JOB_COMPLETION_INDEX` and a Slurm array `--array=0-(N-1)`.
//!
//! A scene file that cannot be read is assigned by the id it is reported under: its file stem.

use std::fmt;
use std::path::{Path, PathBuf};
use std::str::FromStr;

use disco_core::scene::SceneSpec;

/// One shard of a split: shard `index` of `count`, numbered from 0.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Shard {
    index: u32,
    count: u32,
}

/// Why a `--shard` value was refused.
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
pub enum ShardError {
    /// Not of the form `I/N`.
    #[error("{0:?} is not I/N (shard I of N, numbered from 0, e.g. 0/3, 1/3, 2/3)")]
    Form(String),
    /// `N` is zero.
    #[error("the shard count must be at least 1")]
    NoShards,
    /// `I` is not below `N`.
    #[error("shard {index} does not exist: shards of {count} are numbered 0 to {last}")]
    OutOfRange {
        /// The index given.
        index: u32,
        /// The count given.
        count: u32,
        /// The highest valid index.
        last: u32,
    },
}

impl Shard {
    /// Shard `index` of `count`; `index` must be below `count`.
    pub fn new(index: u32, count: u32) -> Result<Shard, ShardError> {
        if count == 0 {
            return Err(ShardError::NoShards);
        }
        if index >= count {
            return Err(ShardError::OutOfRange {
                index,
                count,
                last: count - 1,
            });
        }
        Ok(Shard { index, count })
    }

    /// This shard's number, from 0.
    pub fn index(&self) -> u32 {
        self.index
    }

    /// How many shards the scene set is split into.
    pub fn count(&self) -> u32 {
        self.count
    }

    /// The shard (of `count`) that scene `id` belongs to.
    pub fn of(id: &str, count: u32) -> u32 {
        (fnv1a_64(id.as_bytes()) % u64::from(count.max(1))) as u32
    }

    /// Whether scene `id` belongs to this shard.
    pub fn owns(&self, id: &str) -> bool {
        Shard::of(id, self.count) == self.index
    }

    /// The scene files of `inputs` that belong to this shard, in their given order.
    pub fn select(&self, inputs: &[PathBuf]) -> Vec<PathBuf> {
        inputs
            .iter()
            .filter(|p| self.owns(&scene_id(p)))
            .cloned()
            .collect()
    }
}

impl FromStr for Shard {
    type Err = ShardError;

    fn from_str(text: &str) -> Result<Shard, ShardError> {
        let form = || ShardError::Form(text.to_string());
        let (i, n) = text.trim().split_once('/').ok_or_else(form)?;
        let index: u32 = i.trim().parse().map_err(|_| form())?;
        let count: u32 = n.trim().parse().map_err(|_| form())?;
        Shard::new(index, count)
    }
}

impl fmt::Display for Shard {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{}/{}", self.index, self.count)
    }
}

/// The 64-bit FNV-1a hash of `bytes`: fixed constants, the same on every platform and run
/// (unlike the standard library's randomly seeded hasher).
pub fn fnv1a_64(bytes: &[u8]) -> u64 {
    const OFFSET_BASIS: u64 = 0xcbf2_9ce4_8422_2325;
    const PRIME: u64 = 0x0000_0100_0000_01b3;
    bytes.iter().fold(OFFSET_BASIS, |hash, &b| {
        (hash ^ u64::from(b)).wrapping_mul(PRIME)
    })
}

/// The id scene file `path` is sharded (and reported) under: its `id`, or its file stem when it
/// cannot be read.
pub fn scene_id(path: &Path) -> String {
    match SceneSpec::load(path) {
        Ok(spec) => spec.id,
        Err(_) => file_stem(path),
    }
}

/// The ids a run over `inputs` reports its scenes under, in the order of its results (sorted by
/// file path). Files that share an id are all refused by a batch and reported under their file
/// stems, so they are listed that way here too.
pub fn reported_ids(inputs: &[PathBuf]) -> Vec<String> {
    let mut sorted: Vec<&PathBuf> = inputs.iter().collect();
    sorted.sort();
    let ids: Vec<String> = sorted.iter().map(|p| scene_id(p)).collect();
    let mut seen = std::collections::HashMap::<String, usize>::new();
    for id in &ids {
        *seen.entry(crate::batch::file_safe(id)).or_default() += 1;
    }
    ids.into_iter()
        .zip(sorted)
        .map(|(id, path)| {
            if seen[&crate::batch::file_safe(&id)] > 1 {
                file_stem(path)
            } else {
                id
            }
        })
        .collect()
}

fn file_stem(path: &Path) -> String {
    path.file_stem()
        .map(|s| s.to_string_lossy().into_owned())
        .unwrap_or_default()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn fnv1a_matches_the_published_test_vectors() {
        assert_eq!(fnv1a_64(b""), 0xcbf29ce484222325);
        assert_eq!(fnv1a_64(b"a"), 0xaf63dc4c8601ec8c);
        assert_eq!(fnv1a_64(b"foobar"), 0x85944171f73967e8);
    }

    #[test]
    fn shard_values_are_parsed_and_bad_ones_refused() {
        assert_eq!("0/3".parse::<Shard>(), Shard::new(0, 3));
        assert_eq!(" 2 / 3 ".parse::<Shard>().unwrap().to_string(), "2/3");
        assert_eq!("0/1".parse::<Shard>().unwrap().count(), 1);
        assert_eq!(
            "3/3".parse::<Shard>().unwrap_err().to_string(),
            "shard 3 does not exist: shards of 3 are numbered 0 to 2"
        );
        assert_eq!("0/0".parse::<Shard>(), Err(ShardError::NoShards));
        for bad in ["", "1", "1/", "/3", "-1/3", "a/3", "1/3/4", "1.5/3"] {
            assert!(
                matches!(bad.parse::<Shard>(), Err(ShardError::Form(_))),
                "{bad:?}"
            );
        }
    }

    #[test]
    fn every_scene_is_in_exactly_one_shard() {
        let ids: Vec<String> = (0..2000).map(|i| format!("room-{i:05}")).collect();
        for count in [1, 2, 3, 7, 64] {
            let shards: Vec<Shard> = (0..count).map(|i| Shard::new(i, count).unwrap()).collect();
            let mut sizes = vec![0usize; count as usize];
            for id in &ids {
                let owners: Vec<&Shard> = shards.iter().filter(|s| s.owns(id)).collect();
                assert_eq!(owners.len(), 1, "{id} in {owners:?}");
                sizes[owners[0].index() as usize] += 1;
            }
            // Roughly even: no shard under half its fair share when shares are large enough.
            let fair = ids.len() / count as usize;
            if fair >= 30 {
                assert!(sizes.iter().all(|&n| n * 2 > fair), "{count}: {sizes:?}");
            }
        }
    }

    #[test]
    fn the_split_is_the_same_on_every_run_and_machine() {
        // Fixed expectations: a change of hash would move scenes between shards and break
        // the retries and merges of runs already under way.
        let ids = ["bedroom-01", "kitchen-03", "office-05", "a", ""];
        let of_3: Vec<u32> = ids.iter().map(|id| Shard::of(id, 3)).collect();
        let of_7: Vec<u32> = ids.iter().map(|id| Shard::of(id, 7)).collect();
        assert_eq!(of_3, [0, 2, 2, 1, 2]);
        assert_eq!(of_7, [3, 4, 0, 5, 2]);
    }

    #[test]
    fn files_are_selected_by_id_not_by_name_and_unreadable_ones_by_stem() {
        let dir = tempfile::tempdir().unwrap();
        let scene = dir.path().join("file-name.json");
        std::fs::write(
            &scene,
            r#"{"id": "the-id", "prompt": "p", "room_type": "bedroom",
               "room": {"width": 400, "depth": 350},
               "assets": [{"name": "bed-0", "category": "bed", "size": [160, 210, 100]}]}"#,
        )
        .unwrap();
        let broken = dir.path().join("broken.json");
        std::fs::write(&broken, "{").unwrap();
        assert_eq!(scene_id(&scene), "the-id");
        assert_eq!(scene_id(&broken), "broken");
        let inputs = vec![scene.clone(), broken.clone()];
        let owner = Shard::new(Shard::of("the-id", 5), 5).unwrap();
        assert!(owner.select(&inputs).contains(&scene));
        let stem_owner = Shard::new(Shard::of("broken", 5), 5).unwrap();
        assert!(stem_owner.select(&inputs).contains(&broken));
        assert_eq!(reported_ids(&[scene, broken]), ["broken", "the-id"]);
    }
}
