//! Speed figures a reader can re-measure with one command (`disco perf`): the PRT and the
//! renderer on the synthetic bedroom and banquet hall, the actor runtime's overhead against the
//! same agents called directly, and batch throughput against a fake model of fixed latency.
//!
//! Each timing is the median of as many runs as fit in a small budget (at least five). The
//! criterion benches (`cargo bench`) measure the same operations with more statistical care.
//!
//! Then the growth curve: `generate` with the offline agents on crowded rooms of 10 to 3,000
//! objects (30% of the floor covered, [`synth::crowded_room`]), once each, with the seconds, the
//! peak memory of each run and the quality of the result, beside `refine` alone on the layout
//! it made.

use std::fmt::Write as _;
use std::hint::black_box;
use std::sync::Arc;
use std::time::{Duration, Instant};

use serde::Serialize;

use crate::agents::rules::{RuleDesigner, RulePlanner};
use crate::config::GraphConfig;
use crate::error::Result;
use crate::layout::{Layout, PlacedObject};
use crate::registry::Registry;
use crate::render::{RenderOptions, render, render_png};

use crate::roles::Refined;
use crate::runtime::Runtime;
use crate::scene::SceneSpec;
use crate::synth;
use crate::tools::prt::{PhysicalRefiner, PrtConfig};
use crate::trace::Trace;

/// What to measure and how long to spend.
#[derive(Debug, Clone)]
pub struct PerfOptions {
    /// Time spent on each micro-measurement.
    pub budget: Duration,
    /// Scenes in the throughput run.
    pub throughput_scenes: usize,
    /// The fake model's latency.
    pub model_latency: Duration,
    /// Requests in flight to the fake model.
    pub in_flight: usize,
    /// The largest scene of the growth curve (sizes of [`GROWTH_SIZES`] up to this).
    pub max_objects: usize,
}

/// Object counts of the growth curve.
pub const GROWTH_SIZES: [usize; 6] = [10, 30, 100, 300, 1000, 3000];

/// Share of the floor the growth curve's furniture covers.
const GROWTH_COVER: f64 = 0.3;

impl Default for PerfOptions {
    fn default() -> Self {
        PerfOptions {
            budget: Duration::from_millis(700),
            throughput_scenes: 300,
            model_latency: Duration::from_millis(100),
            in_flight: 32,
            max_objects: 3000,
        }
    }
}

/// One measured figure.
#[derive(Debug, Clone, Serialize)]
pub struct Figure {
    /// What was measured.
    pub name: String,
    /// The value.
    pub value: f64,
    /// Its unit.
    pub unit: String,
    /// How to read it.
    pub note: String,
}

/// One point of the growth curve: a crowded room of `objects` furnished by the offline agents.
#[derive(Debug, Clone, Serialize)]
pub struct GrowthPoint {
    /// Objects in the scene.
    pub objects: usize,
    /// Wall time of `generate`, in seconds.
    pub seconds: f64,
    /// Peak resident memory during `generate`, in MiB (Linux only).
    pub peak_rss_mib: Option<f64>,
    /// Wall time of `refine` alone on the generated layout (what `disco refine` does with it).
    pub refine_seconds: f64,
    /// Col of the generated layout (%).
    pub collision_pct: f64,
    /// OOB of the generated layout (%).
    pub oob_pct: f64,
    /// Objects dropped.
    pub dropped: usize,
    /// Constraints met (%).
    pub constraint_pct: f64,
    /// Objects reachable (%).
    pub reach_pct: f64,
}

/// All figures of one `disco perf` run.
#[derive(Debug, Clone, Serialize)]
pub struct PerfReport {
    /// Logical CPUs of the machine.
    pub cpus: usize,
    /// The figures.
    pub figures: Vec<Figure>,
    /// The growth curve, smallest scene first.
    pub growth: Vec<GrowthPoint>,
}

impl PerfReport {
    /// A Markdown table of the figures.
    pub fn to_markdown(&self) -> String {
        let mut s = format!(
            "Measured on {} logical CPUs.\n\n| figure | value | note |\n|---|---|---|\n",
            self.cpus
        );
        for f in &self.figures {
            let _ = writeln!(
                s,
                "| {} | {} {} | {} |",
                f.name,
                fmt_value(f.value),
                f.unit,
                f.note
            );
        }
        if !self.growth.is_empty() {
            s.push_str(
                "\nGrowth: `generate` with the offline agents on crowded rooms (30% of the floor covered).\n\n\
                 | objects | generate | peak memory | refine alone | Col | OOB | dropped | constraints | reach |\n\
                 |---|---|---|---|---|---|---|---|---|\n",
            );
            for g in &self.growth {
                let rss = g
                    .peak_rss_mib
                    .map_or_else(|| "?".to_string(), |m| format!("{} MiB", fmt_value(m)));
                let _ = writeln!(
                    s,
                    "| {} | {} s | {rss} | {} s | {:.1}% | {:.2}% | {} | {:.1}% | {:.1}% |",
                    g.objects,
                    fmt_value(g.seconds),
                    fmt_value(g.refine_seconds),
                    g.collision_pct,
                    g.oob_pct,
                    g.dropped,
                    g.constraint_pct,
                    g.reach_pct
                );
            }
        }
        s
    }
}

fn fmt_value(v: f64) -> String {
    if v.abs() >= 100.0 {
        format!("{v:.0}")
    } else if v.abs() >= 10.0 {
        format!("{v:.1}")
    } else {
        format!("{v:.2}")
    }
}

/// Median wall time of `f`, run as often as fits in `budget` (at least five times).
pub fn median_time<T>(budget: Duration, mut f: impl FnMut() -> T) -> Duration {
    let started = Instant::now();
    let mut samples = Vec::new();
    while samples.len() < 5 || started.elapsed() < budget {
        let t = Instant::now();
        black_box(f());
        samples.push(t.elapsed());
        if samples.len() >= 100_000 {
            break;
        }
    }
    samples.sort();
    samples[samples.len() / 2]
}

/// The rule agents called one after the other, without actors: planner, designer group by
/// group, a final PRT. The baseline the runtime's overhead is measured against.
pub fn design_directly(scene: &SceneSpec) -> Refined {
    let plan = RulePlanner::new().make_plan(scene);
    let designer = RuleDesigner::new();
    let mut placed: Vec<PlacedObject> = Vec::new();
    for g in &plan.groups {
        let assets: Vec<_> = g.iter().filter_map(|n| scene.asset(n)).collect();
        let out = designer.design_group(scene, &plan, &assets, &placed);
        placed.extend(out);
    }
    PhysicalRefiner::new(PrtConfig::default()).refine(&scene.room, &placed, &plan)
}

/// Starts measuring the peak resident memory afresh (Linux only; elsewhere the peak stays the
/// process's).
pub fn reset_peak_rss() {
    // "5" resets the high-water mark of the resident set (proc(5), clear_refs).
    let _ = std::fs::write("/proc/self/clear_refs", "5");
}

/// Peak resident memory of this process, in KiB (Linux only).
pub fn peak_rss_kib() -> Option<u64> {
    let status = std::fs::read_to_string("/proc/self/status").ok()?;
    let line = status.lines().find(|l| l.starts_with("VmHWM:"))?;
    line.split_whitespace().nth(1)?.parse().ok()
}

fn figure(name: &str, value: f64, unit: &str, note: &str) -> Figure {
    Figure {
        name: name.into(),
        value,
        unit: unit.into(),
        note: note.into(),
    }
}

fn ms(d: Duration) -> f64 {
    d.as_secs_f64() * 1000.0
}

/// Measures every figure. Runs on the caller's tokio runtime; the CPU-bound parts block it.
pub async fn measure(options: &PerfOptions) -> Result<PerfReport> {
    let (bedroom_scene, bedroom) = synth::bedroom();
    let (_, hall) = synth::banquet_hall();
    let mut figures = prt_figures(options.budget, &bedroom, &hall);
    figures.extend(render_figures(options.budget, &bedroom, &hall)?);
    figures.extend(overhead_figures(options.budget, &bedroom_scene).await?);
    figures.extend(throughput_figures(options, &bedroom_scene).await?);
    let growth = growth_curve(options.max_objects).await?;
    Ok(PerfReport {
        cpus: std::thread::available_parallelism().map_or(1, |n| n.get()),
        figures,
        growth,
    })
}

/// The growth curve for the sizes of [`GROWTH_SIZES`] up to `max_objects`: each crowded room
/// generated once by the default (offline) graph with a trace that keeps nothing, then its
/// layout refined alone.
pub async fn growth_curve(max_objects: usize) -> Result<Vec<GrowthPoint>> {
    let runtime = Runtime::new(GraphConfig::load(None, &[])?, Registry::builtin())?;
    let mut points = Vec::new();
    for objects in GROWTH_SIZES.into_iter().filter(|&n| n <= max_objects) {
        let scene = synth::crowded_room(objects, GROWTH_COVER);
        reset_peak_rss();
        let t = Instant::now();
        let layout = runtime
            .generate(scene.clone(), Arc::new(Trace::discarding()))
            .await?;
        let seconds = t.elapsed().as_secs_f64();
        let peak_rss_mib = peak_rss_kib().map(|k| k as f64 / 1024.0);
        let m = crate::metrics::measure(&layout);
        let t = Instant::now();
        black_box(crate::refine::refine_layout(
            &scene,
            layout.clone(),
            &[],
            PrtConfig::default(),
        ));
        points.push(GrowthPoint {
            objects,
            seconds,
            peak_rss_mib,
            refine_seconds: t.elapsed().as_secs_f64(),
            collision_pct: m.collision_pct,
            oob_pct: m.oob_pct,
            dropped: layout.dropped.len(),
            constraint_pct: m.constraint_pct,
            reach_pct: m.reach_pct,
        });
    }
    Ok(points)
}

/// The PRT on a jittered bedroom and banquet hall.
fn prt_figures(budget: Duration, bedroom: &Layout, hall: &Layout) -> Vec<Figure> {
    let refiner = PhysicalRefiner::new(PrtConfig::default());
    let mut figures = Vec::new();
    for (name, layout, target) in [
        ("PRT, noisy 10-object bedroom", bedroom, "target < 1 ms"),
        ("PRT, noisy 120-object banquet hall", hall, "target < 50 ms"),
    ] {
        let noisy = synth::jitter(layout, 7, 40.0, 20.0);
        let t = median_time(budget, || {
            refiner.refine(&noisy.room, &noisy.objects, &noisy.plan)
        });
        figures.push(figure(name, ms(t), "ms", target));
    }
    figures
}

/// The renderer on both rooms, then with PNG encoding as the agents receive it.
fn render_figures(budget: Duration, bedroom: &Layout, hall: &Layout) -> Result<Vec<Figure>> {
    let opts = RenderOptions::default();
    let mut figures = Vec::new();
    for (name, layout) in [
        ("render 1024 px, bedroom", bedroom),
        ("render 1024 px, banquet hall", hall),
    ] {
        render(layout, &opts)?;
        let t = median_time(budget, || render(layout, &opts));
        figures.push(figure(name, ms(t), "ms", "target < 20 ms"));
    }
    let t = median_time(budget, || render_png(bedroom, &opts));
    figures.push(figure(
        "render 1024 px + PNG encode, bedroom",
        ms(t),
        "ms",
        "what the designer and evaluator get",
    ));
    Ok(figures)
}

/// Runtime overhead: the same agents through supervisor and role actors, and directly.
async fn overhead_figures(budget: Duration, scene: &SceneSpec) -> Result<Vec<Figure>> {
    let runtime = Runtime::new(GraphConfig::load(None, &[])?, Registry::builtin())?;
    let mut samples = Vec::new();
    let started = Instant::now();
    while samples.len() < 5 || started.elapsed() < budget {
        let t = Instant::now();
        runtime
            .generate(scene.clone(), Arc::new(Trace::default()))
            .await?;
        samples.push(t.elapsed());
    }
    samples.sort();
    let actors = samples[samples.len() / 2];
    let direct = median_time(budget, || design_directly(scene));
    Ok(vec![
        figure(
            "10-object bedroom through the actors",
            ms(actors),
            "ms",
            "rule agents, supervisor + role actors + evaluate/SRT/PRT rounds",
        ),
        figure(
            "same agents called directly",
            ms(direct),
            "ms",
            "planner, designer, one PRT pass: no actors, no evaluation rounds",
        ),
    ])
}

/// Throughput: `options.throughput_scenes` copies of `scene` at once against a fake model,
/// then the process's peak memory.
async fn throughput_figures(options: &PerfOptions, scene: &SceneSpec) -> Result<Vec<Figure>> {
    let n = options.throughput_scenes;
    let fake = disco_runtime::simulated::simulated_model_runtime(
        options.model_latency,
        options.in_flight,
    )?;
    let rss_before = peak_rss_kib().unwrap_or(0);
    let t = Instant::now();
    let runs = (0..n).map(|i| {
        let fake = fake.clone();
        let mut scene = scene.clone();
        scene.id = format!("bedroom-{i}");
        async move { fake.generate(scene, Arc::new(Trace::default())).await }
    });
    let layouts = futures::future::join_all(runs).await;
    let wall = t.elapsed();
    let calls: u64 = layouts
        .iter()
        .map(|l| l.as_ref().map_or(0, |l| l.stats.llm_calls))
        .sum();
    let failed = layouts.iter().filter(|l| l.is_err()).count();
    let ideal = options.model_latency.as_secs_f64() * calls as f64 / options.in_flight as f64;
    let mut figures = vec![figure(
        &format!(
            "{n} scenes vs a {} ms fake model, {} in flight",
            ms(options.model_latency),
            options.in_flight
        ),
        wall.as_secs_f64(),
        "s",
        &format!(
            "{calls} model calls, ideal {ideal:.2} s ({:+.1}%), {failed} failed",
            100.0 * (wall.as_secs_f64() / ideal.max(1e-9) - 1.0)
        ),
    )];
    if let Some(peak) = peak_rss_kib() {
        figures.push(figure(
            "peak resident memory",
            peak as f64 / 1024.0,
            "MiB",
            &format!(
                "whole process; the throughput run added {:.0} KiB per scene",
                peak.saturating_sub(rss_before) as f64 / n.max(1) as f64
            ),
        ));
    }
    Ok(figures)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[tokio::test(flavor = "multi_thread", worker_threads = 2)]
    async fn every_figure_is_measured_and_positive() {
        let options = PerfOptions {
            budget: Duration::from_millis(1),
            throughput_scenes: 8,
            model_latency: Duration::from_millis(5),
            in_flight: 4,
            max_objects: 30,
        };
        let report = measure(&options).await.unwrap();
        assert!(report.figures.len() >= 8, "{:?}", report.figures);
        assert!(
            report
                .figures
                .iter()
                .all(|f| f.value > 0.0 && f.value.is_finite())
        );
        let throughput = report
            .figures
            .iter()
            .find(|f| f.name.starts_with("8 scenes"))
            .unwrap();
        assert!(throughput.note.contains("0 failed"), "{}", throughput.note);
        assert!(report.to_markdown().lines().count() >= 10);
        let sizes: Vec<usize> = report.growth.iter().map(|g| g.objects).collect();
        assert_eq!(sizes, vec![10, 30]);
        for g in &report.growth {
            assert!(g.seconds > 0.0 && g.refine_seconds > 0.0, "{g:?}");
            assert_eq!((g.collision_pct, g.dropped), (0.0, 0), "{g:?}");
        }
        assert!(report.to_markdown().contains("| 30 |"));
    }
}
