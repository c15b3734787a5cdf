//! Cost of an agent outside the binary. Run with `cargo bench --bench agents`.
//!
//! - `agents/process-round-trip`: one patch request to a Python agent over its stdin and stdout
//!   (`impl = "process"`, the process already running) and its reply, read and checked (target:
//!   under 1 ms). The request carries the whole bedroom scene and layout, as in a real run.

use std::hint::black_box;
use std::sync::Arc;
use std::time::Duration;

use criterion::{Criterion, criterion_group, criterion_main};
use disco_layout::roles::{PatchRequest, RoleImpl, RoleKind, SceneContext};
use disco_layout::runtime::external::ExternalAgent;
use disco_layout::runtime::external::process::ProcessTransport;
use disco_layout::{Layout, PlacedObject, SceneSpec};

/// A patch stage that moves nothing: the round trip is all there is.
const IDLE_AGENT: &str = r#"
import json, sys
for line in sys.stdin:
    request = json.loads(line)
    sys.stdout.write(json.dumps({"protocol": 1, "id": request["id"], "reply": {"objects": []}}) + "\n")
    sys.stdout.flush()
"#;

fn process_round_trip(c: &mut Criterion) {
    let rt = tokio::runtime::Builder::new_multi_thread()
        .worker_threads(2)
        .enable_all()
        .build()
        .unwrap();
    let scene = SceneSpec::load("examples/scenes/bedroom.json".as_ref()).unwrap();
    // Every asset placed (where does not matter to the round trip).
    let objects = scene
        .assets
        .iter()
        .enumerate()
        .map(|(i, a)| PlacedObject {
            name: a.name.clone(),
            category: a.category.clone(),
            size: a.size,
            position: [50.0 + 40.0 * i as f64, 100.0],
            rotation: 0.0,
            ..Default::default()
        })
        .collect();
    let layout = Layout {
        id: scene.id.clone(),
        room: scene.room.clone(),
        objects,
        dropped: Vec::new(),
        plan: Default::default(),
        stats: Default::default(),
    };
    let command = ["python3", "-c", IDLE_AGENT].map(String::from).to_vec();
    let transport = ProcessTransport::new("idle", command, Duration::from_secs(10)).unwrap();
    let RoleImpl::Patch(agent) =
        ExternalAgent::new("idle", RoleKind::Patch, Box::new(transport), false).into_role_impl()
    else {
        unreachable!("a patch agent")
    };
    let req = PatchRequest {
        ctx: SceneContext::new(Arc::new(scene), Arc::new(Default::default())),
        group: layout.objects.iter().map(|o| o.name.clone()).collect(),
        layout,
    };
    // Start the process before measuring.
    rt.block_on(agent.patch(&req)).unwrap();
    c.bench_function("agents/process-round-trip", |b| {
        b.iter(|| black_box(rt.block_on(agent.patch(&req)).unwrap()))
    });
}

criterion_group!(benches, process_round_trip);
criterion_main!(benches);
