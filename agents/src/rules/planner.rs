//! The rule-based planner: constraints from the furniture knowledge, groups around anchors.

use std::collections::{BTreeMap, HashMap};
use std::sync::Arc;

use async_trait::async_trait;

use crate::hints::{Hint, read_hints};
use crate::knowledge::{Kind, Knowledge};
use disco_core::plan::{ObjectConstraints, Plan, Relation, RelationSpec};
use disco_core::roles::{Output, Planner, RoleResult};
use disco_core::scene::SceneSpec;

/// Plans from `config/furniture.toml`: every asset gets its kind's wall flag and relation to the
/// best-matching target present (spreading dependents over several targets), and each anchor forms
/// a group with everything that depends on it, anchors by priority.
pub struct RulePlanner {
    knowledge: Arc<Knowledge>,
}

impl RulePlanner {
    /// A planner over the built-in knowledge.
    pub fn new() -> Self {
        RulePlanner {
            knowledge: Knowledge::builtin(),
        }
    }
}

impl Default for RulePlanner {
    fn default() -> Self {
        Self::new()
    }
}

/// How many dependents of one relation a target takes before the next target is preferred.
fn capacity(relation: Relation) -> usize {
    match relation {
        Relation::SideOf => 2,
        Relation::InFrontOf | Relation::Opposite => 1,
        _ => usize::MAX,
    }
}

impl RulePlanner {
    /// The plan, synchronously.
    pub fn make_plan(&self, scene: &SceneSpec) -> Plan {
        let kinds: Vec<Kind> = scene
            .assets
            .iter()
            .map(|a| self.knowledge.kind_of(a))
            .collect();
        let n = scene.assets.len();
        // target[i] = Some((j, relation spec)) when asset i depends on asset j.
        let mut target: Vec<Option<usize>> = vec![None; n];
        let mut load: HashMap<(usize, Relation), usize> = HashMap::new();
        for i in 0..n {
            let Some(rel) = &kinds[i].relate else {
                continue;
            };
            let best = (0..n)
                .filter(|&j| j != i)
                .filter_map(|j| {
                    Knowledge::target_rank(&scene.assets[j], &kinds[j], &rel.to).map(|r| (j, r))
                })
                .filter(|(j, _)| !depends_on(&target, *j, i))
                .min_by_key(|&(j, rank)| {
                    let used = load.get(&(j, rel.relation)).copied().unwrap_or(0);
                    let full = usize::from(used >= capacity(rel.relation));
                    (full, rank, used, j)
                });
            if let Some((j, _)) = best {
                *load.entry((j, rel.relation)).or_default() += 1;
                target[i] = Some(j);
            }
        }

        // Rows (student desks before a board): each desk lines up with the one before it, when
        // there is something for the rows to face.
        let mut in_rows = vec![false; n];
        for i in 0..n {
            let rows = &kinds[i].rows;
            let faced =
                (0..n).any(|j| Knowledge::target_rank(&scene.assets[j], &kinds[j], rows).is_some());
            if rows.is_empty() || !faced || in_rows[i] {
                continue;
            }
            let members: Vec<usize> = (i..n)
                .filter(|&m| kinds[m].names == kinds[i].names)
                .collect();
            for pair in members.windows(2) {
                target[pair[1]] = Some(pair[0]);
                in_rows[pair[1]] = true;
            }
            in_rows[i] = true;
        }

        // Hints in the prompt override the knowledge.
        let mut relation: Vec<Option<Relation>> = (0..n)
            .map(|i| {
                if in_rows[i] {
                    Some(Relation::AlignedWith)
                } else {
                    kinds[i].relate.as_ref().map(|r| r.relation)
                }
            })
            .collect();
        let mut facing: Vec<Option<usize>> = (0..n)
            .map(|i| {
                target[i]
                    .filter(|_| !in_rows[i] && kinds[i].relate.as_ref().is_some_and(|r| r.face))
            })
            .collect();
        let mut wall: Vec<bool> = kinds.iter().map(|k| k.wall).collect();
        for h in read_hints(scene, &self.knowledge) {
            for &s in &h.subjects {
                match &h.hint {
                    Hint::Centre => wall[s] = false,
                    Hint::Corner | Hint::AlongWall => wall[s] = true,
                    Hint::Facing(targets) => {
                        facing[s] = targets.iter().copied().find(|&t| t != s).or(facing[s]);
                    }
                    Hint::Relation(rel, targets) => {
                        let keep = target[s].is_some_and(|t| targets.contains(&t))
                            && relation[s] == Some(*rel);
                        if keep {
                            continue;
                        }
                        let best = targets
                            .iter()
                            .copied()
                            .filter(|&t| t != s && !depends_on(&target, t, s))
                            .min_by_key(|&t| (load.get(&(t, *rel)).copied().unwrap_or(0), t));
                        if let Some(t) = best {
                            *load.entry((t, *rel)).or_default() += 1;
                            target[s] = Some(t);
                            relation[s] = Some(*rel);
                            if *rel == Relation::Around {
                                facing[s] = Some(t);
                            }
                        }
                    }
                }
            }
        }

        let mut constraints = BTreeMap::new();
        for (i, a) in scene.assets.iter().enumerate() {
            let mut c = ObjectConstraints {
                against_wall: wall[i],
                ..Default::default()
            };
            if let (Some(j), Some(rel)) = (target[i], relation[i]) {
                if matches!(
                    rel,
                    Relation::Around | Relation::InFrontOf | Relation::AlignedWith
                ) {
                    c.against_wall = false;
                }
                c.relations.push(RelationSpec {
                    relation: rel,
                    target: scene.assets[j].name.clone(),
                });
            }
            c.facing = facing[i].map(|j| scene.assets[j].name.clone());
            if c.against_wall || !c.relations.is_empty() || c.facing.is_some() {
                constraints.insert(a.name.clone(), c);
            }
        }

        // Groups: each anchor (no target) with everything that depends on it, transitively.
        let root = |mut i: usize| {
            let mut steps = 0;
            while let Some(j) = target[i] {
                i = j;
                steps += 1;
                if steps > n {
                    break;
                }
            }
            i
        };
        let mut members: BTreeMap<usize, Vec<usize>> = BTreeMap::new();
        for i in 0..n {
            members.entry(root(i)).or_default().push(i);
        }
        let mut anchors: Vec<usize> = members.keys().copied().collect();
        let area = |i: usize| scene.assets[i].size[0] * scene.assets[i].size[1];
        anchors.sort_by(|&a, &b| {
            kinds[b]
                .priority
                .cmp(&kinds[a].priority)
                .then(area(b).total_cmp(&area(a)))
                .then(a.cmp(&b))
        });
        let groups = anchors
            .into_iter()
            .map(|a| {
                let mut m = members.remove(&a).unwrap_or_default();
                // The anchor first, then its dependents by depth and scene order.
                m.sort_by_key(|&i| (i != a, depth(&target, i), i));
                m.into_iter()
                    .map(|i| scene.assets[i].name.clone())
                    .collect()
            })
            .collect();
        Plan {
            constraints,
            groups,
        }
    }
}

fn depth(target: &[Option<usize>], mut i: usize) -> usize {
    let mut d = 0;
    while let Some(j) = target[i] {
        i = j;
        d += 1;
        if d > target.len() {
            break;
        }
    }
    d
}

/// Whether `j` (transitively) depends on `i`.
fn depends_on(target: &[Option<usize>], mut j: usize, i: usize) -> bool {
    for _ in 0..target.len() {
        match target[j] {
            Some(t) if t == i => return true,
            Some(t) => j = t,
            None => return false,
        }
    }
    false
}

#[async_trait]
impl Planner for RulePlanner {
    async fn plan(&self, scene: &SceneSpec) -> RoleResult<Plan> {
        Ok(Output::free(self.make_plan(scene)))
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use disco_core::scene::{Asset, Room};

    fn scene(items: &[(&str, &str, [f64; 3])]) -> SceneSpec {
        SceneSpec {
            id: "t".into(),
            prompt: String::new(),
            room_type: "room".into(),
            room: Room {
                width: 500.0,
                depth: 400.0,
            },
            assets: items
                .iter()
                .map(|(n, c, s)| Asset {
                    name: n.to_string(),
                    category: c.to_string(),
                    size: *s,
                    mesh: None,
                    description: None,
                })
                .collect(),
        }
    }

    #[test]
    fn a_bedroom_plan() {
        let s = scene(&[
            ("nightstand-0", "nightstand", [50.0, 40.0, 55.0]),
            ("bed-0", "bed", [160.0, 210.0, 100.0]),
            ("nightstand-1", "nightstand", [50.0, 40.0, 55.0]),
            ("wardrobe-0", "wardrobe", [120.0, 60.0, 200.0]),
        ]);
        let p = RulePlanner::new().make_plan(&s);
        assert_eq!(p.groups[0], ["bed-0", "nightstand-0", "nightstand-1"]);
        assert_eq!(p.groups[1], ["wardrobe-0"]);
        let ns = &p.constraints["nightstand-1"];
        assert!(ns.against_wall);
        assert_eq!(
            ns.relations,
            vec![RelationSpec {
                relation: Relation::SideOf,
                target: "bed-0".into()
            }]
        );
        assert!(p.constraints["bed-0"].against_wall);
    }

    #[test]
    fn chairs_spread_over_tables_and_face_them() {
        let mut items = vec![
            ("table-0", "dining table", [160.0, 90.0, 75.0]),
            ("table-1", "dining table", [160.0, 90.0, 75.0]),
        ];
        let names: Vec<String> = (0..8).map(|i| format!("chair-{i}")).collect();
        for n in &names {
            items.push((n.as_str(), "dining chair", [45.0, 50.0, 90.0]));
        }
        let p = RulePlanner::new().make_plan(&scene(&items));
        assert_eq!(p.groups.len(), 2);
        assert_eq!(p.groups[0].len(), 5);
        assert_eq!(p.groups[1].len(), 5);
        let c = &p.constraints["chair-3"];
        assert!(!c.against_wall);
        assert_eq!(c.facing.as_deref(), Some(c.relations[0].target.as_str()));
        assert_eq!(c.relations[0].relation, Relation::Around);
    }

    #[test]
    fn a_living_room_chain_stays_in_one_group() {
        let s = scene(&[
            ("sofa-0", "sofa", [220.0, 95.0, 85.0]),
            ("coffee table-0", "coffee table", [110.0, 60.0, 45.0]),
            ("tv stand-0", "tv stand", [180.0, 45.0, 55.0]),
            ("armchair-0", "armchair", [85.0, 85.0, 95.0]),
        ]);
        let p = RulePlanner::new().make_plan(&s);
        assert_eq!(p.groups.len(), 1, "{:?}", p.groups);
        assert_eq!(p.groups[0][0], "sofa-0");
        assert_eq!(
            p.constraints["tv stand-0"].relations[0].relation,
            Relation::Opposite
        );
        assert_eq!(
            p.constraints["armchair-0"].relations[0].target,
            "coffee table-0"
        );
    }

    #[test]
    fn every_asset_is_in_exactly_one_group() {
        let s = scene(&[
            ("x-0", "mystery machine", [100.0, 100.0, 100.0]),
            ("rug-0", "rug", [200.0, 100.0, 1.0]),
            ("chair-0", "chair", [45.0, 45.0, 90.0]),
        ]);
        let p = RulePlanner::new().make_plan(&s);
        let mut all: Vec<&String> = p.groups.iter().flatten().collect();
        all.sort();
        assert_eq!(all, ["chair-0", "rug-0", "x-0"]);
    }
}
