//! Benchmarks of the deterministic foundation: the PRT on noisy rooms and the renderer.
//!
//! Run with `cargo bench --bench foundation`. Targets on a 2-core machine: PRT on the 10-object
//! bedroom under 1 ms, on the 120-object banquet hall under 50 ms; a 1024 px render under 20 ms.

use std::hint::black_box;

use criterion::{Criterion, criterion_group, criterion_main};
use disco_layout::render::{RenderOptions, render, render_png};
use disco_layout::synth;
use disco_layout::{PhysicalRefiner, PrtConfig};

fn prt(c: &mut Criterion) {
    let refiner = PhysicalRefiner::new(PrtConfig::default());
    for (name, (scene, layout)) in [
        ("bedroom-10", synth::bedroom()),
        ("banquet-hall-120", synth::banquet_hall()),
    ] {
        let noisy = synth::jitter(&layout, 7, 40.0, 20.0);
        c.bench_function(&format!("prt/{name}-noisy"), |b| {
            b.iter(|| {
                refiner.refine(
                    black_box(&scene.room),
                    black_box(&noisy.objects),
                    &noisy.plan,
                )
            })
        });
    }
}

fn renderer(c: &mut Criterion) {
    let (_, bedroom) = synth::bedroom();
    let (_, hall) = synth::banquet_hall();
    let opts = RenderOptions::default();
    c.bench_function("render/bedroom-1024px", |b| {
        b.iter(|| render(black_box(&bedroom), &opts).unwrap())
    });
    c.bench_function("render/banquet-hall-1024px", |b| {
        b.iter(|| render(black_box(&hall), &opts).unwrap())
    });
    c.bench_function("render/bedroom-1024px-png", |b| {
        b.iter(|| render_png(black_box(&bedroom), &opts).unwrap())
    });
}

criterion_group!(benches, prt, renderer);
criterion_main!(benches);
