//! Furnish a room from Rust code: build a scene in memory, run the default (offline, rule-based)
//! agent graph through the actor runtime, then read the metrics and write the layout, a picture,
//! a 3D file and a report.
//!
//! `cargo run --release --example furnish -- OUT_DIR`

use std::path::PathBuf;
use std::sync::Arc;

use disco_layout::config::GraphConfig;
use disco_layout::export::{ExportOptions, export_glb};
use disco_layout::registry::Registry;
use disco_layout::render::{RenderOptions, render_png};
use disco_layout::report::html::scene_report;
use disco_layout::trace::Trace;
use disco_layout::{Asset, Room, Runtime, SceneSpec, io, metrics};

#[tokio::main]
async fn main() -> anyhow::Result<()> {
    let out: PathBuf = std::env::args()
        .nth(1)
        .unwrap_or_else(|| "furnished".into())
        .into();
    std::fs::create_dir_all(&out)?;

    // 1. The scene: a sentence, a room and the furniture, in centimetres.
    let scene = SceneSpec {
        id: "study-01".into(),
        prompt: "a quiet study with a desk facing the window wall and a reading chair".into(),
        room_type: "study".into(),
        room: Room::rect(360.0, 300.0),
        assets: vec![
            Asset::new("desk-0", "desk", [140.0, 70.0, 75.0]),
            Asset::new("office chair-0", "office chair", [60.0, 60.0, 100.0]),
            Asset::new("bookshelf-0", "bookshelf", [100.0, 35.0, 200.0]),
            Asset::new("armchair-0", "armchair", [80.0, 80.0, 95.0]),
            Asset::new("floor lamp-0", "floor lamp", [35.0, 35.0, 160.0]),
            Asset::new("rug-0", "rug", [160.0, 120.0, 1.0]),
        ],
    };

    // 2. The agent graph: the built-in offline default. `GraphConfig::load(Some(path), &sets)`
    //    reads a TOML graph instead (a model preset, an ablation, your own roles).
    let graph = GraphConfig::load(None, &[])?;
    let runtime = Runtime::new(graph, Registry::builtin())?;

    // 3. Generate, keeping step snapshots for the report.
    let trace = Arc::new(Trace::with_snapshots());
    let layout = runtime.generate(scene.clone(), Arc::clone(&trace)).await?;

    // 4. Read the result.
    let m = metrics::measure(&layout);
    println!(
        "{}: {} of {} placed, Col {:.1}%, OOB {:.2}%, constraints {:.1}%, reach {:.1}%",
        layout.id, m.placed, m.assets, m.collision_pct, m.oob_pct, m.constraint_pct, m.reach_pct
    );
    for o in &layout.objects {
        println!(
            "  {:<16} at ({:>5.0}, {:>5.0}) cm, facing {:>3.0}°",
            o.name, o.position[0], o.position[1], o.rotation
        );
    }

    // 5. Write it out: JSON, PNG, GLB, HTML.
    io::write_json(&out.join("study-01.json"), &layout)?;
    io::write_atomic(
        &out.join("study-01.png"),
        &render_png(&layout, &RenderOptions::default())?,
    )?;
    io::write_atomic(
        &out.join("study-01.glb"),
        &export_glb(&layout, &Default::default(), &ExportOptions::default())?,
    )?;
    let html = scene_report(&scene, &layout, &trace.events())?;
    io::write_atomic(&out.join("study-01.html"), html.as_bytes())?;
    println!("wrote {}/study-01.{{json,png,glb,html}}", out.display());
    Ok(())
}
