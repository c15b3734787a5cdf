//! Writes the growth curve's crowded room of `disco perf` as a scene file, for profiling one size
//! with `disco generate`: `cargo run --example write_crowded -- DIR 3000` writes
//! `DIR/crowded-3000.json` (30% of the floor covered, as the curve has it).

fn main() -> anyhow::Result<()> {
    let mut args = std::env::args().skip(1);
    let dir = std::path::PathBuf::from(args.next().unwrap_or_else(|| ".".into()));
    let objects: usize = args.next().map_or(Ok(3000), |n| n.parse())?;
    let scene = disco_layout::synth::crowded_room(objects, 0.3);
    disco_layout::io::write_json(&dir.join(format!("crowded-{objects}.json")), &scene)?;
    Ok(())
}
