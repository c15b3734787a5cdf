//! Benchmarks of real rooms (polygon outlines with doors and windows). Run with
//! `cargo bench --bench rooms`.
//!
//! - `rooms/prt-rect-hall-120-noisy` and `rooms/prt-l-hall-120-doors-noisy`: the PRT on the
//!   120-object banquet hall jittered as in `benches/foundation.rs`, in its 24 x 18 m rectangle
//!   and in an L-shaped hall (the same rectangle with a 6 x 9 m wing, two doors and a window in
//!   the wing's walls, so the same objects fit). Target: the L-shaped hall within 2x of the
//!   rectangle.
//! - `rooms/generate-dining-room-l-10-door`: `disco generate` on `bench/rooms/dining-room-l-01`
//!   (an L-shaped room with a door and windows, 10 objects) with the built-in rule agents, through
//!   the actor runtime. Target: under 20 ms.

use std::hint::black_box;
use std::path::Path;
use std::sync::Arc;

use criterion::{Criterion, criterion_group, criterion_main};
use disco_core::room::{Door, Hinge, Swing, Window};
use disco_layout::config::GraphConfig;
use disco_layout::registry::Registry;
use disco_layout::trace::Trace;
use disco_layout::{PhysicalRefiner, PrtConfig, Room, Runtime, SceneSpec, synth};

/// The banquet hall's 2400 x 1800 cm rectangle with a 600 x 900 cm wing on the right, a door in
/// the wing's outer wall and in the floor's bottom wall under the wing, and a window in the
/// wing's top wall: six walls, no object of the hall in an opening's zone.
fn l_hall() -> Room {
    let mut room = Room::from_polygon(vec![
        [0.0, 0.0],
        [3000.0, 0.0],
        [3000.0, 900.0],
        [2400.0, 900.0],
        [2400.0, 1800.0],
        [0.0, 1800.0],
    ]);
    let door = |wall, at| Door {
        wall,
        at,
        width: 100.0,
        swing: Swing::In,
        hinge: Hinge::Left,
    };
    room.doors = vec![door(1, 450.0), door(0, 2700.0)];
    room.windows = vec![Window {
        wall: 2,
        at: 300.0,
        width: 200.0,
        sill: 90.0,
        height: 120.0,
    }];
    room
}

fn prt(c: &mut Criterion) {
    let refiner = PhysicalRefiner::new(PrtConfig::default());
    let (scene, layout) = synth::banquet_hall();
    let noisy = synth::jitter(&layout, 7, 40.0, 20.0);
    let l = l_hall();
    for (name, room) in [
        ("rooms/prt-rect-hall-120-noisy", &scene.room),
        ("rooms/prt-l-hall-120-doors-noisy", &l),
    ] {
        c.bench_function(name, |b| {
            b.iter(|| refiner.refine(black_box(room), black_box(&noisy.objects), &noisy.plan))
        });
    }
}

fn generate(c: &mut Criterion) {
    let rt = tokio::runtime::Builder::new_multi_thread()
        .worker_threads(2)
        .enable_all()
        .build()
        .unwrap();
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("bench/rooms/dining-room-l-01.json");
    let scene = SceneSpec::load(&path).unwrap();
    assert!(!scene.room.doors.is_empty());
    let runtime = Runtime::new(GraphConfig::load(None, &[]).unwrap(), Registry::builtin()).unwrap();
    c.bench_function("rooms/generate-dining-room-l-10-door", |b| {
        b.iter(|| {
            rt.block_on(runtime.generate(scene.clone(), Arc::new(Trace::default())))
                .unwrap()
        })
    });
}

criterion_group!(benches, prt, generate);
criterion_main!(benches);
