//! Throughput of the runtime against a fake model: N scenes (default 1000) whose designer calls a
//! model that takes 100 ms, through one gateway with 32 requests in flight. Prints the wall time
//! against the ideal (model calls / 32 x 100 ms) and the process's peak memory.
//!
//! `cargo run --release --example throughput -- [SCENES]`

use std::sync::Arc;
use std::time::{Duration, Instant};

use async_trait::async_trait;
use disco_layout::agents::rules::RuleDesigner;
use disco_layout::config::GraphConfig;
use disco_layout::gateway::ModelGateway;
use disco_layout::layout::PlacedObject;
use disco_layout::registry::Registry;
use disco_layout::roles::{DesignRequest, Designer, RoleImpl, RoleKind, RoleResult, Usage};
use disco_layout::trace::Trace;
use disco_layout::{Runtime, synth};

const LATENCY: Duration = Duration::from_millis(100);
const IN_FLIGHT: usize = 32;

/// The rules designer behind a fake model call of fixed latency.
struct FakeModel {
    gateway: Arc<ModelGateway>,
}

#[async_trait]
impl Designer for FakeModel {
    async fn design(&self, req: &DesignRequest) -> RoleResult<Vec<PlacedObject>> {
        let _permit = self.gateway.acquire().await;
        tokio::time::sleep(LATENCY).await;
        let mut out = RuleDesigner::new().design(req).await?;
        out.usage = Usage {
            calls: 1,
            prompt_tokens: 0,
            completion_tokens: 0,
        };
        Ok(out)
    }
}

fn peak_rss_kib() -> Option<u64> {
    let status = std::fs::read_to_string("/proc/self/status").ok()?;
    let line = status.lines().find(|l| l.starts_with("VmHWM:"))?;
    line.split_whitespace().nth(1)?.parse().ok()
}

fn main() -> anyhow::Result<()> {
    let n: usize = std::env::args()
        .nth(1)
        .map(|s| s.parse())
        .transpose()?
        .unwrap_or(1000);
    let mut registry = Registry::builtin();
    registry.register(RoleKind::Designer, "fake-model", |ctx| {
        let gateway = ctx.gateway.clone().ok_or("needs a model")?;
        Ok(RoleImpl::Designer(Arc::new(FakeModel { gateway })))
    });
    let sets = [
        "agents.designer.impl=fake-model".to_string(),
        "agents.designer.model=fake".to_string(),
        format!("models.fake.max_in_flight={IN_FLIGHT}"),
    ];
    let runtime = Runtime::new(GraphConfig::load(None, &sets)?, registry)?;
    let rt = tokio::runtime::Builder::new_multi_thread()
        .enable_all()
        .build()?;
    let before = peak_rss_kib().unwrap_or(0);
    let t0 = Instant::now();
    let layouts = rt.block_on(async {
        let runs = (0..n).map(|i| {
            let runtime = runtime.clone();
            let mut scene = synth::bedroom().0;
            scene.id = format!("bedroom-{i}");
            async move { runtime.generate(scene, Arc::new(Trace::default())).await }
        });
        futures::future::join_all(runs).await
    });
    let wall = t0.elapsed();
    let calls: u64 = layouts
        .iter()
        .map(|l| l.as_ref().map_or(0, |l| l.stats.llm_calls))
        .sum();
    let failed = layouts.iter().filter(|l| l.is_err()).count();
    let ideal = LATENCY.as_secs_f64() * (calls as f64 / IN_FLIGHT as f64);
    let peak = runtime
        .gateways()
        .get("fake")
        .map_or(0, |g| g.peak_in_flight());
    println!("scenes {n} (failed {failed}), model calls {calls}, peak in flight {peak}");
    println!(
        "wall {:.2} s, ideal {:.2} s, overhead {:+.1}%",
        wall.as_secs_f64(),
        ideal,
        100.0 * (wall.as_secs_f64() / ideal - 1.0)
    );
    if let Some(after) = peak_rss_kib() {
        println!(
            "peak RSS {:.1} MiB; {:.1} KiB per scene in flight",
            after as f64 / 1024.0,
            after.saturating_sub(before) as f64 / n as f64
        );
    }
    Ok(())
}
