//! Self-contained HTML reports (every image inline as a data URL, no outside files): one per run
//! of `disco generate` ([`scene_report`]) and one over all scenes of `disco bench`
//! ([`bench_report`]). A reader sees the final render, the metrics, the plan, each group's steps
//! with the evaluator's questions and answers, every model call, and what was dropped and why.
//! A layout with objects off the floor also shows its walls unrolled, with everything at its
//! height ([`crate::render::render_walls`]), beside the final render and beside each step's.

use base64::Engine as _;
use serde_json::{Value, json};

use super::room::{opening_words, outline_words, room_size};
use super::steps::{Step, render_step_walls, render_steps, steps};
use crate::bench::{SceneResult, Table};
use crate::error::{Error, Result};
use crate::layout::Layout;
use crate::metrics::{Metrics, measure};
use crate::relations::check_plan;
use crate::render::{
    ElevationOptions, RenderOptions, contact_sheet, encode_png, has_objects_off_the_floor,
    render_png, render_walls_png,
};
use crate::scene::SceneSpec;
use crate::trace::{TraceEvent, TraceKind};

const TEMPLATE: &str = include_str!("report.html.j2");

/// Width of the per-step pictures in a report, in pixels.
const STEP_PX: u32 = 360;

/// Width of a step's sheet of walls in a report, in pixels: the page shows it at a step
/// picture's width, and a reader who opens it reads the names.
const STEP_WALLS_PX: u32 = 960;

/// The report of one run: `events` is its trace (made with
/// [`crate::trace::Trace::with_snapshots`] for step pictures; any trace works).
pub fn scene_report(scene: &SceneSpec, layout: &Layout, events: &[TraceEvent]) -> Result<String> {
    let section = scene_section(scene, Some(layout), None, Some(events), 1024)?;
    page(json!({
        "title": format!("{}: {}", layout.id, scene.room_type),
        "lede": format!(
            "{} objects placed, {} dropped, in {} ms; {} model calls, {} tokens.",
            layout.objects.len(),
            layout.dropped.len(),
            layout.stats.wall_ms,
            layout.stats.llm_calls,
            layout.stats.prompt_tokens + layout.stats.completion_tokens
        ),
        "scenes": [section],
    }))
}

/// One report over a benchmark run: the table, then every scene's render, metrics and drops.
/// `scenes` pairs each result with its spec and layout when they could be read.
pub fn bench_report(
    title: &str,
    table: &Table,
    scenes: &[(SceneResult, Option<SceneSpec>, Option<Layout>)],
) -> Result<String> {
    let mut sections = Vec::new();
    for (result, spec, layout) in scenes {
        let section = match spec {
            Some(spec) => {
                scene_section(spec, layout.as_ref(), result.failure.as_deref(), None, 640)?
            }
            None => json!({"id": result.id, "failure": result.failure}),
        };
        sections.push(section);
    }
    let openings = table.rows.iter().any(|r| r.openings.is_some());
    let mut header = vec![
        table.first_column.as_str(),
        "scenes",
        "Col %",
        "OOB %",
        "positional %",
        "facing %",
        "all constraints %",
        "reach %",
        "dropped %",
        "calls",
        "tokens",
        "s / scene",
    ];
    if openings {
        header.extend(["doors blocked", "windows blocked"]);
    }
    let rows: Vec<Vec<String>> = table
        .rows
        .iter()
        .map(|r| {
            let mut row = vec![
                r.label.clone(),
                if r.failed > 0 {
                    format!("{} (+{} failed)", r.scenes, r.failed)
                } else {
                    r.scenes.to_string()
                },
                format!("{:.2}", r.col),
                format!("{:.2}", r.oob),
                format!("{:.1}", r.positional),
                format!("{:.1}", r.facing),
                format!("{:.1}", r.constraints),
                format!("{:.1}", r.reach),
                format!("{:.1}", r.dropped),
                format!("{:.1}", r.calls),
                format!("{:.0}", r.tokens),
                format!("{:.2}", r.seconds),
            ];
            if openings {
                row.extend(crate::bench::OpeningsBlocked::cells(r.openings));
            }
            row
        })
        .collect();
    page(json!({
        "title": title,
        "lede": format!("{} {}; per room category and on average, then scene by scene.", scenes.len(), if scenes.len() == 1 { "scene" } else { "scenes" }),
        "table": {"header": header, "rows": rows},
        "scenes": sections,
    }))
}

/// The steps (minijinja's fuel) the report template may take before anything it shows: the
/// page itself, the table header, the empty sections.
const REPORT_FUEL_BASE: u64 = 1_000_000;

/// The steps the report template may take per value it is given (each scene, metric, step,
/// question, answer, cell...): the template visits each a few times, far fewer than this.
const REPORT_FUEL_PER_VALUE: u64 = 200;

/// The report's fuel for `ctx`: proportional to what it shows, so a report of 2,000 scenes
/// renders and a template that loops without end stops with an error instead of hanging.
fn report_fuel(ctx: &Value) -> u64 {
    REPORT_FUEL_BASE.saturating_add(REPORT_FUEL_PER_VALUE.saturating_mul(values_in(ctx)))
}

/// How many JSON values `v` holds, itself included.
fn values_in(v: &Value) -> u64 {
    1 + match v {
        Value::Array(items) => items.iter().map(values_in).sum(),
        Value::Object(fields) => fields.values().map(values_in).sum(),
        _ => 0,
    }
}

fn page(ctx: Value) -> Result<String> {
    render_page(TEMPLATE, ctx)
}

/// Renders `template` over `ctx` with the fuel [`report_fuel`] gives it.
fn render_page(template: &str, mut ctx: Value) -> Result<String> {
    ctx["version"] = json!(env!("CARGO_PKG_VERSION"));
    let fuel = report_fuel(&ctx);
    let mut env = minijinja::Environment::new();
    env.set_fuel(Some(fuel));
    env.add_template("report.html", template)
        .map_err(|e| Error::Render(format!("report template: {e}")))?;
    env.get_template("report.html")
        .and_then(|t| t.render(minijinja::value::Serde(&ctx)))
        .map_err(|e| match e.kind() {
            minijinja::ErrorKind::OutOfFuel => Error::Render(format!(
                "report template: ran out of fuel (more than {fuel} steps for what it shows); \
                 it loops too long"
            )),
            _ => Error::Render(format!("report template: {e}")),
        })
}

fn base64_png(png: &[u8]) -> String {
    base64::engine::general_purpose::STANDARD.encode(png)
}

fn scene_section(
    scene: &SceneSpec,
    layout: Option<&Layout>,
    failure: Option<&str>,
    events: Option<&[TraceEvent]>,
    render_px: u32,
) -> Result<Value> {
    let mut s = json!({
        "id": scene.id,
        "prompt": scene.prompt,
        "room_type": scene.room_type,
        "room": room_size(&scene.room),
        "outline": outline_words(&scene.room),
        "openings": opening_words(&scene.room),
        "failure": failure,
        "trace": events.is_some(),
    });
    let Some(layout) = layout else {
        return Ok(s);
    };
    let png = render_png(
        layout,
        &RenderOptions {
            long_side_px: render_px,
            ..RenderOptions::default()
        },
    )?;
    s["render"] = json!(base64_png(&png));
    s["render_px"] = json!(render_px);
    // The walls, only when something is off the floor: a floor-only report stays as it was.
    if has_objects_off_the_floor(layout) {
        let options = ElevationOptions {
            width_px: render_px,
            ..ElevationOptions::default()
        };
        s["walls"] = json!(base64_png(&render_walls_png(layout, &options)?));
    }
    s["metrics"] = metric_rows(scene, layout, &measure(layout));
    s["dropped"] = json!(layout.dropped);
    let notes: Vec<&String> = layout
        .stats
        .fallbacks
        .iter()
        .chain(&layout.stats.notes)
        .collect();
    s["notes"] = json!(notes);
    let Some(events) = events else {
        return Ok(s);
    };
    s["plan"] = plan_rows(layout);
    let all_steps = steps(events, layout);
    if !all_steps.is_empty() {
        let tiles: Vec<(String, tiny_skia::Pixmap)> = all_steps
            .iter()
            .map(Step::caption)
            .zip(render_steps(&all_steps, 300)?)
            .collect();
        s["sheet"] = json!(base64_png(&encode_png(&contact_sheet(&tiles, 4)?)?));
    }
    s["groups"] = group_sections(layout, events, &all_steps)?;
    s["calls"] = json!(
        events
            .iter()
            .filter(|e| e.scene == layout.id && e.kind == TraceKind::ModelCall)
            .map(|e| {
                let d = &e.detail;
                json!({
                    "role": e.role,
                    "purpose": d["purpose"],
                    "latency": format!("{:.0}", d["latency_ms"].as_f64().unwrap_or(0.0)),
                    "prompt_tokens": d["prompt_tokens"],
                    "completion_tokens": d["completion_tokens"],
                    "attempts": d["attempts"],
                    "cached": d["cached"],
                    "error": d["error"],
                })
            })
            .collect::<Vec<_>>()
    );
    Ok(s)
}

/// The metrics as rows, then the prompt's requests checked on the layout, as `disco generate`
/// prints them (`prompt requests  N of M met`, each missed one named).
fn metric_rows(scene: &SceneSpec, layout: &Layout, m: &Metrics) -> Value {
    let list = |v: &[String]| v.join(", ");
    let pairs: Vec<String> = m
        .colliding_pairs
        .iter()
        .map(|(a, b)| format!("{a} / {b}"))
        .collect();
    let kinds: Vec<String> = m
        .by_kind
        .iter()
        .map(|(k, t)| format!("{k} {}/{}", t.met, t.total))
        .collect();
    let mut rows = vec![
        json!({"name": "objects placed", "value": format!("{} of {}", m.placed, m.assets), "detail": "", "bad": m.placed < m.assets}),
        json!({"name": "Col (collisions)", "value": format!("{:.1}%", m.collision_pct), "detail": list(&pairs), "bad": m.collision_pct > 0.0}),
        json!({"name": "OOB (out of room)", "value": format!("{:.2}%", m.oob_pct), "detail": "", "bad": m.oob_pct > 0.0}),
        json!({"name": "constraints met", "value": format!("{:.1}%", m.constraint_pct), "detail": kinds.join(", "), "bad": m.constraint_pct < 100.0}),
        json!({"name": "positional relations", "value": format!("{:.1}%", m.positional_pct), "detail": list(&m.unmet), "bad": m.positional_pct < 100.0}),
        json!({"name": "facing", "value": format!("{:.1}%", m.facing_pct), "detail": "", "bad": m.facing_pct < 100.0}),
        json!({"name": "reach", "value": format!("{:.1}%", m.reach_pct), "detail": list(&m.unreachable), "bad": m.reach_pct < 100.0}),
        json!({"name": "dropped", "value": format!("{:.1}%", m.dropped_pct), "detail": "", "bad": m.dropped_pct > 0.0}),
    ];
    if let (Some(doors), Some(windows)) = (m.doors_blocked, m.windows_blocked) {
        let doors_total = layout.room.doors.len();
        let windows_total = layout.room.windows.len();
        rows.push(json!({"name": "doors blocked", "value": format!("{doors} of {doors_total}"), "detail": "keep-clear zone entered by something other than a floor covering", "bad": doors > 0}));
        rows.push(json!({"name": "windows blocked", "value": format!("{windows} of {windows_total}"), "detail": "zone entered by a piece taller than the sill", "bad": windows > 0}));
    }
    if let Some(d) = m.mean_displacement_cm {
        rows.push(json!({"name": "PRT displacement", "value": format!("{d:.1} cm"), "detail": "mean over moved objects", "bad": false}));
    }
    let requests = crate::agents::requests::check_requests(scene, layout);
    if !requests.is_empty() {
        let met = requests.iter().filter(|r| r.met).count();
        let missed: Vec<&str> = requests
            .iter()
            .filter(|r| !r.met)
            .map(|r| r.request.as_str())
            .collect();
        let detail = match missed.is_empty() {
            true => String::new(),
            false => format!("missed: {}", missed.join("; ")),
        };
        rows.push(json!({"name": "prompt requests", "value": format!("{met} of {} met", requests.len()), "detail": detail, "bad": met < requests.len()}));
    }
    rows.push(json!({"name": "time", "value": format!("{} ms", layout.stats.wall_ms), "detail": format!("{} rounds", layout.stats.rounds), "bad": false}));
    json!(rows)
}

fn plan_rows(layout: &Layout) -> Value {
    let checks = check_plan(layout);
    let mut rows = Vec::new();
    for (gi, group) in layout.plan.groups.iter().enumerate() {
        for name in group {
            let mine: Vec<Value> = checks
                .iter()
                .filter(|c| &c.subject == name)
                .map(|c| json!({"text": c.to_string(), "met": c.met}))
                .collect();
            rows.push(json!({
                "group": gi + 1,
                "name": name,
                "checks": mine,
            }));
        }
    }
    json!(rows)
}

/// The scene's events split at each group's design stage (planning first, the final PRT last),
/// each with its evaluations and step pictures.
fn group_sections(layout: &Layout, events: &[TraceEvent], all_steps: &[Step]) -> Result<Value> {
    let mut sections = Sections::default();
    for e in events.iter().filter(|e| e.scene == layout.id) {
        sections.add(e);
    }
    sections.add_pictures(all_steps)?;
    Ok(json!(sections.list))
}

/// The sections of a run being read event by event, with what the reading needs to remember.
struct Sections {
    /// Planning, then one per group, then the final PRT, as the template wants them.
    list: Vec<Value>,
    /// Groups designed so far.
    groups: usize,
    /// The current evaluate-and-refine round.
    round: u64,
    /// The evaluator's last questions, to put next to its answers.
    pending_questions: Option<Value>,
}

impl Default for Sections {
    fn default() -> Self {
        Sections {
            list: vec![section("Planning")],
            groups: 0,
            round: 0,
            pending_questions: None,
        }
    }
}

/// An empty section.
fn section(title: &str) -> Value {
    json!({"title": title, "events": [], "evaluations": [], "images": []})
}

/// Appends `item` to the array `section[key]`.
fn push_to(section: &mut Value, key: &str, item: Value) {
    section[key].as_array_mut().expect("an array").push(item);
}

impl Sections {
    /// Takes one event of the scene: a stage may open a section; an evaluator's reply adds an
    /// evaluation; every event but snapshots and model calls is listed.
    fn add(&mut self, e: &TraceEvent) {
        if e.kind == TraceKind::Stage {
            self.stage(e);
        }
        if matches!(e.kind, TraceKind::Snapshot | TraceKind::ModelCall) {
            return;
        }
        if e.role == "evaluator" && e.kind == TraceKind::Request {
            self.pending_questions = Some(e.detail["questions"].clone());
        }
        if e.role == "evaluator" && e.kind == TraceKind::Reply {
            let evaluation = self.evaluation(e);
            // A round with no questions (nothing to ask of this group) says nothing.
            if evaluation["answers"]
                .as_array()
                .is_some_and(|a| !a.is_empty())
            {
                push_to(self.current(), "evaluations", evaluation);
            }
        }
        let row = json!({
            "t": e.t_ms,
            "role": e.role,
            "kind": kind_word(e.kind),
            "text": describe(e),
        });
        push_to(self.current(), "events", row);
    }

    fn current(&mut self) -> &mut Value {
        self.list.last_mut().expect("never empty")
    }

    /// A design stage opens a group's section, the final PRT its own; an evaluation sets the round.
    fn stage(&mut self, e: &TraceEvent) {
        match e.detail["stage"].as_str().unwrap_or("") {
            "design" => {
                self.groups += 1;
                self.round = 0;
                let members: Vec<&str> = e.detail["group"]
                    .as_array()
                    .map(|a| a.iter().filter_map(Value::as_str).collect())
                    .unwrap_or_default();
                let mut group = section(&format!("Group {}", self.groups));
                group["members"] = json!(members.join(", "));
                self.list.push(group);
            }
            "final prt" => self.list.push(section("Final PRT")),
            "evaluate" => self.round = e.detail["round"].as_u64().unwrap_or(0),
            _ => {}
        }
    }

    /// The evaluator's reply `e` as questions with their answers, against the pending questions.
    fn evaluation(&mut self, e: &TraceEvent) -> Value {
        let questions = self.pending_questions.take().unwrap_or(Value::Null);
        let text_of = |id: &Value| {
            questions
                .as_array()
                .and_then(|qs| qs.iter().find(|q| &q["id"] == id))
                .and_then(|q| q["text"].as_str())
                .unwrap_or("?")
                .to_string()
        };
        let answers: Vec<Value> = e.detail["answers"]
            .as_array()
            .map(|a| {
                a.iter()
                    .map(|a| json!({"question": text_of(&a["id"]), "yes": a["yes"], "reason": a["reason"]}))
                    .collect()
            })
            .unwrap_or_default();
        let failed = answers.iter().filter(|a| a["yes"] != json!(true)).count();
        json!({"round": self.round, "answers": answers, "failed": failed, "physical": e.detail["needs_physical"]})
    }

    /// Each step's picture, in its group's section (the final pass in the final PRT's).
    fn add_pictures(&mut self, all_steps: &[Step]) -> Result<()> {
        let pictures = render_steps(all_steps, STEP_PX)?;
        for (step, pixmap) in all_steps.iter().zip(pictures) {
            let title = if step.group == 0 {
                "Final PRT".to_string()
            } else {
                format!("Group {}", step.group)
            };
            if let Some(section) = self.list.iter_mut().find(|s| s["title"] == json!(title)) {
                let image = json!({
                    "caption": step.caption(),
                    "png": base64_png(&encode_png(&pixmap)?),
                });
                push_to(section, "images", image);
                if let Some(walls) = render_step_walls(step, STEP_WALLS_PX)? {
                    let image = json!({
                        "caption": format!("{} · walls", step.caption()),
                        "png": base64_png(&encode_png(&walls)?),
                    });
                    push_to(section, "images", image);
                }
            }
        }
        Ok(())
    }
}

fn kind_word(kind: TraceKind) -> &'static str {
    match kind {
        TraceKind::Request => "asked",
        TraceKind::Reply => "answered",
        TraceKind::Error => "failed",
        TraceKind::Timeout => "timed out",
        TraceKind::Restart => "restarted",
        TraceKind::Fallback => "fallback",
        TraceKind::Stage => "stage",
        TraceKind::ModelCall => "model call",
        TraceKind::Snapshot => "snapshot",
        TraceKind::Moved => "moved unasked",
        TraceKind::Done => "done",
    }
}

/// One line about an event: what was asked or answered, in words where we know the shape.
fn describe(e: &TraceEvent) -> String {
    let d = &e.detail;
    let poses = |v: &Value| -> String {
        v.as_array()
            .map(|ps| {
                ps.iter()
                    .map(|p| {
                        format!(
                            "{} at ({:.0}, {:.0}) turned {:.0}°",
                            p["name"].as_str().unwrap_or("?"),
                            p["position"][0].as_f64().unwrap_or(0.0),
                            p["position"][1].as_f64().unwrap_or(0.0),
                            p["rotation"].as_f64().unwrap_or(0.0)
                        )
                    })
                    .collect::<Vec<_>>()
                    .join("; ")
            })
            .unwrap_or_default()
    };
    let text = match e.kind {
        TraceKind::Stage => d["stage"].as_str().unwrap_or("").to_string(),
        TraceKind::Reply if d.get("poses").is_some() => {
            let mut t = poses(&d["poses"]);
            if let Some(dropped) = d["dropped"].as_array().filter(|a| !a.is_empty()) {
                t.push_str(&format!("; dropped {}", dropped.len()));
            }
            t
        }
        TraceKind::Reply if d.get("answers").is_some() => {
            let answers = d["answers"].as_array().map_or(0, Vec::len);
            let yes = d["answers"]
                .as_array()
                .map_or(0, |a| a.iter().filter(|a| a["yes"] == json!(true)).count());
            format!(
                "{yes} of {answers} yes; physical problems: {}",
                if d["needs_physical"] == json!(true) {
                    "yes"
                } else {
                    "no"
                }
            )
        }
        TraceKind::Reply if d.get("groups").is_some() => format!(
            "{} groups, constraints for {} objects",
            d["groups"].as_array().map_or(0, Vec::len),
            d["constraints"].as_object().map_or(0, |c| c.len())
        ),
        TraceKind::Request if d.get("questions").is_some() => {
            format!(
                "{} questions",
                d["questions"].as_array().map_or(0, Vec::len)
            )
        }
        _ => match d {
            Value::String(s) => s.clone(),
            other => other.to_string(),
        },
    };
    let mut out: String = text.chars().take(400).collect();
    if let Some(ms) = e.ms {
        out.push_str(&format!(" ({ms:.1} ms)"));
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::report::steps::tests::{noisy_bedroom_run, raised_bedroom};
    use crate::scene::Room;

    #[test]
    fn a_report_template_that_loops_runs_out_of_fuel_with_a_clear_error() {
        let looping =
            "{% for i in range(100000) %}{% for j in range(100000) %}{% endfor %}{% endfor %}";
        let t0 = std::time::Instant::now();
        let e = render_page(looping, json!({"scenes": []}))
            .unwrap_err()
            .to_string();
        assert!(
            e.starts_with("render: report template: ran out of fuel (more than"),
            "{e}"
        );
        assert!(
            t0.elapsed() < std::time::Duration::from_secs(30),
            "{:?}",
            t0.elapsed()
        );
        // The fuel grows with what the report shows.
        let many = json!({"scenes": vec![json!({"a": 1, "b": [1, 2]}); 1000]});
        assert_eq!(values_in(&many), 1 + 1 + 1000 * 5);
        assert!(report_fuel(&many) > report_fuel(&json!({})) + 1000 * 5 * 100);
    }

    #[tokio::test]
    async fn a_run_report_holds_pictures_metrics_plan_steps_and_answers() {
        let (scene, _) = crate::synth::bedroom();
        let (_, layout, events) = noisy_bedroom_run().await;
        let html = scene_report(&scene, &layout, &events).unwrap();
        assert!(html.starts_with("<!doctype html>"));
        let images = html.matches("src=\"data:image/png;base64,").count();
        let all = steps(&events, &layout);
        let snapshots = all.len();
        // The final render, the contact sheet, one picture per step; and the walls of the final
        // layout and of each step when something in them is off the floor.
        let walls = std::iter::once(&layout)
            .chain(all.iter().map(|s| &s.layout))
            .filter(|l| has_objects_off_the_floor(l))
            .count();
        assert_eq!(images, 2 + snapshots + walls, "{snapshots} steps");
        for part in [
            "Metrics",
            "Plan",
            "Group 1",
            "Final PRT",
            "Is it true that",
            "No model calls",
        ] {
            assert!(html.contains(part), "{part}");
        }
        for o in &layout.objects {
            assert!(html.contains(&o.name), "{}", o.name);
        }
        assert!(!html.contains("src=\"http"), "self-contained");
    }

    #[test]
    fn a_polygon_room_is_described_and_drawn() {
        use disco_core::room::{Door, Window};
        let (mut scene, mut layout) = crate::synth::bedroom();
        let (w, d) = (scene.room.width, scene.room.depth);
        let mut room = Room::from_polygon(vec![
            [0.0, 0.0],
            [w, 0.0],
            [w, d / 2.0],
            [w / 2.0, d],
            [0.0, d],
        ]);
        room.doors.push(Door::new(0, 60.0, 90.0));
        room.windows.push(Window {
            wall: 4,
            at: 100.0,
            width: 80.0,
            sill: 90.0,
            height: 110.0,
        });
        scene.room = room.clone();
        layout.room = room;
        let html = scene_report(&scene, &layout, &[]).unwrap();
        for part in [
            "5 walls in",
            &format!("({w}, {})", d / 2.0),
            "door on wall 0 at 60 cm, 90 cm wide, swings in, hinge on the left",
            "window on wall 4 at 100 cm, 80 cm wide, sill at 90 cm, 110 cm high",
            "doors blocked",
            "windows blocked",
        ] {
            assert!(html.contains(part), "{part}");
        }
        // A benchmark table shows door and window columns only when some room has openings.
        let result = |layout: &Layout| crate::bench::SceneResult {
            id: layout.id.clone(),
            category: "bedroom".into(),
            metrics: Some(measure(layout)),
            failure: None,
            llm_calls: 0,
            tokens: 0,
            wall_ms: 1,
            judge: None,
        };
        let (_, plain) = crate::synth::bedroom();
        for (l, shown) in [(&plain, false), (&layout, true)] {
            let table = Table::by_category("t", &[result(l)]);
            let html = bench_report("t", &table, &[]).unwrap();
            assert_eq!(html.contains("<th>doors blocked</th>"), shown);
        }
        // The render embedded is the polygon's, openings drawn: the same bytes as render_png's.
        let png = render_png(&layout, &RenderOptions::default()).unwrap();
        assert!(html.contains(&base64_png(&png).replace('/', "&#x2f;")));
    }

    #[tokio::test]
    async fn prompt_requests_are_listed_and_empty_evaluations_left_out() {
        let (_, layout, events) = noisy_bedroom_run().await;
        let (mut scene, _) = crate::synth::bedroom();
        scene.prompt = "a bedroom with a floor lamp next to the armchair".into();
        let requests = crate::agents::requests::check_requests(&scene, &layout);
        assert!(!requests.is_empty(), "the prompt holds a request");
        let html = scene_report(&scene, &layout, &events).unwrap();
        let met = requests.iter().filter(|r| r.met).count();
        assert!(html.contains("<th>prompt requests</th>"), "{html}");
        assert!(html.contains(&format!("{met} of {} met", requests.len())));
        // An evaluator's reply with no answers makes no "0 of 0 questions" table.
        let mut quiet = events.clone();
        for e in &mut quiet {
            if e.role == "evaluator" && e.kind == TraceKind::Reply {
                e.detail["answers"] = json!([]);
            }
        }
        let html = scene_report(&scene, &layout, &quiet).unwrap();
        assert!(!html.contains("of 0 questions failed"), "empty table shown");
        let html = scene_report(&scene, &layout, &events).unwrap();
        assert!(html.contains("questions failed"), "non-empty tables stay");
    }

    #[test]
    fn walls_are_drawn_beside_the_render_only_when_something_is_off_the_floor() {
        let wall_sheet = "each wall unrolled";
        let (scene, layout) = crate::synth::bedroom();
        let html = scene_report(&scene, &layout, &[]).unwrap();
        assert!(!html.contains(wall_sheet));
        assert_eq!(html.matches("src=\"data:image/png;base64,").count(), 1);
        let (scene, layout) = raised_bedroom();
        let html = scene_report(&scene, &layout, &[]).unwrap();
        assert!(html.contains(wall_sheet));
        assert_eq!(html.matches("src=\"data:image/png;base64,").count(), 2);
        let options = ElevationOptions {
            width_px: 1024,
            ..ElevationOptions::default()
        };
        let png = render_walls_png(&layout, &options).unwrap();
        assert!(html.contains(&base64_png(&png).replace('/', "&#x2f;")));
        // In a benchmark report too, at the report's size.
        let result = crate::bench::SceneResult {
            id: layout.id.clone(),
            category: "bedroom".into(),
            metrics: Some(measure(&layout)),
            failure: None,
            llm_calls: 0,
            tokens: 0,
            wall_ms: 1,
            judge: None,
        };
        let table = Table::by_category("t", std::slice::from_ref(&result));
        let html = bench_report("t", &table, &[(result, Some(scene), Some(layout))]).unwrap();
        assert!(html.contains(wall_sheet));
    }

    #[test]
    fn a_step_with_objects_off_the_floor_shows_its_walls_too() {
        use crate::trace::TraceEvent;
        let (scene, layout) = raised_bedroom();
        let event = |kind: TraceKind, detail: Value| TraceEvent {
            t_ms: 0,
            scene: layout.id.clone(),
            role: "supervisor".into(),
            implementation: String::new(),
            kind,
            ms: None,
            usage: None,
            detail,
        };
        let floor_only: Vec<&crate::layout::PlacedObject> =
            layout.objects.iter().filter(|o| o.on_floor()).collect();
        let events = vec![
            event(
                TraceKind::Stage,
                json!({"stage": "design", "group": ["bed-0"]}),
            ),
            event(
                TraceKind::Snapshot,
                json!({"step": "design", "group": 1, "round": 0, "objects": floor_only, "dropped": []}),
            ),
            event(TraceKind::Stage, json!({"stage": "final prt"})),
            event(
                TraceKind::Snapshot,
                json!({"step": "final prt", "group": 0, "round": 0, "objects": layout.objects, "dropped": []}),
            ),
        ];
        let html = scene_report(&scene, &layout, &events).unwrap();
        // The final render and its walls, the contact sheet, two steps and the final one's walls.
        assert_eq!(html.matches("src=\"data:image/png;base64,").count(), 6);
        assert!(html.contains("final prt · walls"));
        assert!(!html.contains("group 1 · design · walls"));
    }

    #[test]
    fn text_from_the_scene_is_escaped() {
        let (mut scene, mut layout) = crate::synth::bedroom();
        scene.prompt = "<script>alert(1)</script> & more".into();
        layout.dropped.push(crate::layout::Dropped {
            name: "<b>x</b>".into(),
            reason: "a \"quoted\" <reason>".into(),
        });
        let html = scene_report(&scene, &layout, &[]).unwrap();
        assert!(!html.contains("<script>alert"));
        assert!(html.contains("&lt;script&gt;alert(1)&lt;&#x2f;script&gt; &amp; more"));
        assert!(html.contains("&lt;b&gt;x&lt;&#x2f;b&gt;"));
    }
}
