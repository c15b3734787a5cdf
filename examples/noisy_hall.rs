//! Writes a noisy banquet hall, and the same hall after the Physical Refinement Tool, as layouts.
//!
//! `cargo run --example noisy_hall -- OUT_DIR` then `disco render OUT_DIR/hall-refined.json -o hall.png`.

use disco_layout::layout::Layout;
use disco_layout::{PhysicalRefiner, PrtConfig, io, synth};

fn main() -> anyhow::Result<()> {
    let out = std::path::PathBuf::from(std::env::args().nth(1).unwrap_or_else(|| ".".into()));
    let (scene, layout) = synth::banquet_hall();
    let noisy = synth::jitter(&layout, 7, 40.0, 20.0);
    let refined =
        PhysicalRefiner::new(PrtConfig::default()).refine(&scene.room, &noisy.objects, &noisy.plan);
    let after = Layout {
        objects: refined.objects.clone(),
        dropped: refined.dropped.clone(),
        stats: disco_layout::Stats {
            prt: Some(refined.stats()),
            ..Default::default()
        },
        ..noisy.clone()
    };
    io::write_json(&out.join("hall-noisy.json"), &noisy)?;
    io::write_json(&out.join("hall-refined.json"), &after)?;
    println!("{}", disco_layout::metrics::measure(&after));
    Ok(())
}
