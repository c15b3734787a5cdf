//! Writes the synthetic scenes (`bedroom-synth`, `banquet-hall-synth`) as scene files, for trying
//! the runtime on a large room: `cargo run --example write_synth -- DIR`, then
//! `disco generate DIR/banquet-hall-synth.json -o hall.json --renders renders/`.

fn main() -> anyhow::Result<()> {
    let dir = std::path::PathBuf::from(std::env::args().nth(1).unwrap_or_else(|| ".".into()));
    for (scene, _) in [
        disco_layout::synth::bedroom(),
        disco_layout::synth::banquet_hall(),
    ] {
        disco_layout::io::write_json(&dir.join(format!("{}.json", scene.id)), &scene)?;
    }
    Ok(())
}
