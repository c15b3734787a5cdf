//! The benchmark's tables: per-scene results averaged into rows (per room category, or per
//! method), written as Markdown and JSON in the shape of the paper's Tables 1 and 2.

use std::collections::BTreeMap;
use std::fmt::Write as _;

use serde::{Deserialize, Serialize};

use crate::metrics::Metrics;

/// What one scene of a benchmark run came to.
#[derive(Debug, Clone, Serialize, Deserialize)]
pub struct SceneResult {
    /// The scene's id.
    pub id: String,
    /// Its room type: the category it is averaged under.
    pub category: String,
    /// Metrics of its layout; `None` when the scene failed.
    pub metrics: Option<Metrics>,
    /// Why it failed, if it did.
    pub failure: Option<String>,
    /// Model calls made for it.
    pub llm_calls: u64,
    /// Prompt plus completion tokens.
    pub tokens: u64,
    /// Wall time of its generation, in milliseconds.
    pub wall_ms: u64,
    /// The VLM judge's scores, with `--judge`.
    pub judge: Option<JudgeResult>,
}

/// The VLM judge's verdict on one layout.
#[derive(Debug, Clone, Serialize, Deserialize)]
pub struct JudgeResult {
    /// Positional coherency, 0-100.
    pub positional: f64,
    /// Rotational coherency, 0-100.
    pub rotational: f64,
}

/// One row: the mean over some scenes.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Row {
    /// The category or method name.
    pub label: String,
    /// Scenes averaged (failed ones excluded from the means, counted in `failed`).
    pub scenes: usize,
    /// Scenes that failed.
    pub failed: usize,
    /// Mean % of object pairs that collide.
    pub col: f64,
    /// Mean % of footprint area out of the room.
    pub oob: f64,
    /// Mean % of positional relations met.
    pub positional: f64,
    /// Mean % of facing constraints met.
    pub facing: f64,
    /// Mean % of all constraints met (wall included).
    pub constraints: f64,
    /// Mean % of objects reachable.
    pub reach: f64,
    /// Mean % of assets dropped.
    pub dropped: f64,
    /// Mean model calls per scene.
    pub calls: f64,
    /// Mean tokens per scene.
    pub tokens: f64,
    /// Mean wall time per scene, in seconds.
    pub seconds: f64,
    /// Mean judge positional score, when judged.
    pub judge_positional: Option<f64>,
    /// Mean judge rotational score, when judged.
    pub judge_rotational: Option<f64>,
    /// Doors and windows blocked, summed over the row's scenes whose room has openings; `None`
    /// when none has (so tables of rectangular rooms read as before).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub openings: Option<OpeningsBlocked>,
}

/// How many openings a row's layouts block, over its scenes with doors or windows.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize)]
pub struct OpeningsBlocked {
    /// Scenes whose room has openings.
    pub scenes: usize,
    /// Doors whose keep-clear zone something other than a floor covering enters.
    pub doors: usize,
    /// Windows whose zone an object taller than the sill enters.
    pub windows: usize,
}

impl OpeningsBlocked {
    /// The sums over `metrics` of rooms with openings; `None` when none has any.
    fn sum<'m>(metrics: impl Iterator<Item = &'m Metrics>) -> Option<OpeningsBlocked> {
        let mut total: Option<OpeningsBlocked> = None;
        for m in metrics {
            if m.doors_blocked.is_none() && m.windows_blocked.is_none() {
                continue;
            }
            let t = total.get_or_insert_with(OpeningsBlocked::default);
            t.scenes += 1;
            t.doors += m.doors_blocked.unwrap_or(0);
            t.windows += m.windows_blocked.unwrap_or(0);
        }
        total
    }

    /// A row's door and window cells: blocked counts out of its scenes with openings ("1 in 3
    /// rooms"), or dashes when it has none.
    pub fn cells(openings: Option<OpeningsBlocked>) -> [String; 2] {
        match openings {
            Some(o) => [
                format!("{} in {} rooms", o.doors, o.scenes),
                format!("{} in {} rooms", o.windows, o.scenes),
            ],
            None => ["-".into(), "-".into()],
        }
    }
}

impl Row {
    /// The mean of `results` under `label`.
    pub fn mean(label: &str, results: &[&SceneResult]) -> Row {
        let ok: Vec<(&SceneResult, &Metrics)> = results
            .iter()
            .filter_map(|r| r.metrics.as_ref().map(|m| (*r, m)))
            .collect();
        let n = ok.len().max(1) as f64;
        let avg = |f: &dyn Fn(&SceneResult, &Metrics) -> f64| {
            ok.iter().map(|(r, m)| f(r, m)).sum::<f64>() / n
        };
        let judged: Vec<&JudgeResult> = results.iter().filter_map(|r| r.judge.as_ref()).collect();
        let judge_mean = |f: fn(&JudgeResult) -> f64| {
            (!judged.is_empty())
                .then(|| judged.iter().map(|j| f(j)).sum::<f64>() / judged.len() as f64)
        };
        Row {
            label: label.to_string(),
            scenes: ok.len(),
            failed: results.len() - ok.len(),
            col: avg(&|_, m| m.collision_pct),
            oob: avg(&|_, m| m.oob_pct),
            positional: avg(&|_, m| m.positional_pct),
            facing: avg(&|_, m| m.facing_pct),
            constraints: avg(&|_, m| m.constraint_pct),
            reach: avg(&|_, m| m.reach_pct),
            dropped: avg(&|_, m| m.dropped_pct),
            calls: avg(&|r, _| r.llm_calls as f64),
            tokens: avg(&|r, _| r.tokens as f64),
            seconds: avg(&|r, _| r.wall_ms as f64 / 1000.0),
            judge_positional: judge_mean(|j| j.positional),
            judge_rotational: judge_mean(|j| j.rotational),
            openings: OpeningsBlocked::sum(ok.iter().map(|(_, m)| *m)),
        }
    }
}

/// A titled table of rows.
#[derive(Debug, Clone, Serialize, Deserialize)]
pub struct Table {
    /// Heading.
    pub title: String,
    /// What the first column holds (`category` or `method`).
    pub first_column: String,
    /// The rows, the average last for category tables.
    pub rows: Vec<Row>,
}

impl Table {
    /// One row per room category (sorted) and an `average` row over every scene.
    pub fn by_category(title: &str, results: &[SceneResult]) -> Table {
        let mut by: BTreeMap<&str, Vec<&SceneResult>> = BTreeMap::new();
        for r in results {
            by.entry(r.category.as_str()).or_default().push(r);
        }
        let mut rows: Vec<Row> = by.iter().map(|(c, rs)| Row::mean(c, rs)).collect();
        rows.push(Row::mean("average", &results.iter().collect::<Vec<_>>()));
        Table {
            title: title.to_string(),
            first_column: "category".into(),
            rows,
        }
    }

    /// One row per method: the mean over all of its scenes.
    pub fn by_method(title: &str, methods: &[(String, Vec<SceneResult>)]) -> Table {
        Table {
            title: title.to_string(),
            first_column: "method".into(),
            rows: methods
                .iter()
                .map(|(name, rs)| Row::mean(name, &rs.iter().collect::<Vec<_>>()))
                .collect(),
        }
    }

    /// The table as GitHub Markdown (judge columns only when some row was judged; door and
    /// window columns only when some row has scenes with openings).
    pub fn to_markdown(&self) -> String {
        let judged = self.rows.iter().any(|r| r.judge_positional.is_some());
        let openings = self.rows.iter().any(|r| r.openings.is_some());
        let mut s = format!(
            "| {} | scenes | Col % ↓ | OOB % ↓ | positional % ↑ | facing % ↑ | all constraints % ↑ | reach % ↑ | dropped % ↓ | calls | tokens | s / scene |",
            self.first_column
        );
        if judged {
            s.push_str(" judge pos. ↑ | judge rot. ↑ |");
        }
        if openings {
            s.push_str(" doors blocked ↓ | windows blocked ↓ |");
        }
        s.push('\n');
        let columns = 12 + if judged { 2 } else { 0 } + if openings { 2 } else { 0 };
        s.push_str(&"|---".repeat(columns));
        s.push_str("|\n");
        for r in &self.rows {
            let scenes = if r.failed > 0 {
                format!("{} (+{} failed)", r.scenes, r.failed)
            } else {
                r.scenes.to_string()
            };
            let _ = write!(
                s,
                "| {} | {} | {:.2} | {:.2} | {:.1} | {:.1} | {:.1} | {:.1} | {:.1} | {:.1} | {:.0} | {:.2} |",
                r.label,
                scenes,
                r.col,
                r.oob,
                r.positional,
                r.facing,
                r.constraints,
                r.reach,
                r.dropped,
                r.calls,
                r.tokens,
                r.seconds
            );
            if judged {
                let f = |v: Option<f64>| v.map_or("-".to_string(), |v| format!("{v:.1}"));
                let _ = write!(
                    s,
                    " {} | {} |",
                    f(r.judge_positional),
                    f(r.judge_rotational)
                );
            }
            if openings {
                let [doors, windows] = OpeningsBlocked::cells(r.openings);
                let _ = write!(s, " {doors} | {windows} |");
            }
            s.push('\n');
        }
        s
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::metrics::measure;

    fn result(category: &str, col: f64, judge: Option<f64>) -> SceneResult {
        let (_, layout) = crate::synth::bedroom();
        let mut m = measure(&layout);
        m.collision_pct = col;
        SceneResult {
            id: format!("{category}-{col}"),
            category: category.into(),
            metrics: Some(m),
            failure: None,
            llm_calls: 2,
            tokens: 100,
            wall_ms: 1500,
            judge: judge.map(|v| JudgeResult {
                positional: v,
                rotational: v / 2.0,
            }),
        }
    }

    #[test]
    fn categories_average_and_failures_are_counted_apart() {
        let mut failed = result("kitchen", 0.0, None);
        failed.metrics = None;
        failed.failure = Some("server down".into());
        let results = vec![
            result("kitchen", 10.0, Some(80.0)),
            result("kitchen", 20.0, None),
            result("bedroom", 0.0, Some(60.0)),
            failed,
        ];
        let t = Table::by_category("t", &results);
        let labels: Vec<&str> = t.rows.iter().map(|r| r.label.as_str()).collect();
        assert_eq!(labels, ["bedroom", "kitchen", "average"]);
        let kitchen = &t.rows[1];
        assert_eq!((kitchen.scenes, kitchen.failed), (2, 1));
        assert!((kitchen.col - 15.0).abs() < 1e-9);
        assert_eq!(kitchen.judge_positional, Some(80.0));
        let avg = &t.rows[2];
        assert!((avg.col - 10.0).abs() < 1e-9);
        assert_eq!(avg.judge_rotational, Some(35.0));
        assert!((avg.seconds - 1.5).abs() < 1e-9);
        let md = t.to_markdown();
        assert!(md.contains("| kitchen | 2 (+1 failed) | 15.00 |"), "{md}");
        assert!(md.contains("judge pos."), "{md}");
        let lines: Vec<&str> = md.lines().collect();
        let cells = |l: &str| l.matches('|').count();
        assert!(lines.iter().all(|l| cells(l) == cells(lines[0])), "{md}");
        assert!(!md.contains("doors blocked"), "{md}");
        assert!(t.rows.iter().all(|r| r.openings.is_none()));
        let json = serde_json::to_string(&t).unwrap();
        assert!(!json.contains("openings"), "{json}");
    }

    /// A result whose room has openings, with `doors` doors and `windows` windows blocked.
    fn with_openings(category: &str, doors: usize, windows: usize) -> SceneResult {
        let mut r = result(category, 0.0, None);
        let m = r.metrics.as_mut().unwrap();
        m.doors_blocked = Some(doors);
        m.windows_blocked = Some(windows);
        r
    }

    #[test]
    fn door_and_window_columns_appear_when_some_room_has_openings() {
        let results = vec![
            with_openings("kitchen", 1, 0),
            with_openings("kitchen", 0, 2),
            result("bedroom", 0.0, None),
        ];
        let t = Table::by_category("t", &results);
        let kitchen = t.rows[1].openings.unwrap();
        assert_eq!((kitchen.scenes, kitchen.doors, kitchen.windows), (2, 1, 2));
        assert_eq!(t.rows[0].openings, None, "the bedroom has no openings");
        assert_eq!(t.rows[2].openings.unwrap().scenes, 2);
        let md = t.to_markdown();
        assert!(md.contains("doors blocked ↓ | windows blocked ↓ |"), "{md}");
        assert!(md.contains("| 1 in 2 rooms | 2 in 2 rooms |"), "{md}");
        assert!(md.lines().nth(2).unwrap().ends_with("| - | - |"), "{md}");
        let lines: Vec<&str> = md.lines().collect();
        let cells = |l: &str| l.matches('|').count();
        assert!(lines.iter().all(|l| cells(l) == cells(lines[0])), "{md}");
        let back: Table = serde_json::from_str(&serde_json::to_string(&t).unwrap()).unwrap();
        assert_eq!(back.rows, t.rows);
    }
}
