//! Overhead of the actor runtime itself. Run with `cargo bench --bench runtime`.
//!
//! - `runtime/role-round-trip`: one request to a role actor with an instant implementation and
//!   its answer (target: under 50 µs);
//! - `runtime/scene-bedroom-rules`: a whole 10-object scene through supervisor and role actors
//!   with the rule-based agents;
//! - `runtime/scene-bedroom-direct`: the same agents called directly, without actors, for
//!   comparison.

use std::hint::black_box;
use std::sync::Arc;

use async_trait::async_trait;
use criterion::{Criterion, criterion_group, criterion_main};
use disco_layout::bench::perf::design_directly;
use disco_layout::config::GraphConfig;
use disco_layout::layout::PlacedObject;
use disco_layout::registry::Registry;
use disco_layout::roles::{Output, PatchRequest, Patcher, RoleImpl, RoleResult, SceneContext};
use disco_layout::runtime::supervisor::messages::pending;
use disco_layout::runtime::{RoleActor, RoleMsg};
use disco_layout::trace::Trace;
use disco_layout::{Runtime, synth};
use ractor::Actor;

struct Instant;

#[async_trait]
impl Patcher for Instant {
    async fn patch(&self, _req: &PatchRequest) -> RoleResult<Vec<PlacedObject>> {
        Ok(Output::free(Vec::new()))
    }
}

fn runtime_overhead(c: &mut Criterion) {
    let rt = tokio::runtime::Builder::new_multi_thread()
        .worker_threads(2)
        .enable_all()
        .build()
        .unwrap();
    let (scene, layout) = synth::bedroom();
    let call = Arc::new(PatchRequest {
        ctx: SceneContext::new(Arc::new(scene.clone()), Arc::clone(&layout.plan)),
        layout: layout.clone(),
        group: vec!["bed-0".into()],
    });
    let (actor, _) = rt
        .block_on(Actor::spawn(
            None,
            RoleActor,
            RoleImpl::Patch(Arc::new(Instant)),
        ))
        .unwrap();
    c.bench_function("runtime/role-round-trip", |b| {
        b.iter(|| {
            rt.block_on(async {
                let (job, answer) = pending(Arc::clone(&call));
                actor.send_message(RoleMsg::Invoke(job)).unwrap();
                black_box(answer.await.unwrap())
            })
        })
    });

    let runtime = Runtime::new(GraphConfig::load(None, &[]).unwrap(), Registry::builtin()).unwrap();
    c.bench_function("runtime/scene-bedroom-rules", |b| {
        b.iter(|| {
            rt.block_on(runtime.generate(scene.clone(), Arc::new(Trace::default())))
                .unwrap()
        })
    });
    c.bench_function("runtime/scene-bedroom-direct", |b| {
        b.iter(|| black_box(design_directly(&scene)))
    });
}

criterion_group!(benches, runtime_overhead);
criterion_main!(benches);
