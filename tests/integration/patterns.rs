//! The arrangement test set (`bench/patterns/`): the default graph (offline rule agents) builds
//! the arrangement each prompt names, with no collision, nothing out of the room and nothing
//! dropped. Run with `-- --nocapture` to see the per-pattern table of bench/RESULTS.md.

use std::path::Path;
use std::sync::Arc;

use disco_layout::bench::patterns::{PatternResult, check, load_expectations, to_markdown};
use disco_layout::config::GraphConfig;
use disco_layout::registry::Registry;
use disco_layout::trace::Trace;
use disco_layout::{Runtime, SceneSpec, metrics};

/// The share of pattern predicates the default graph must meet. The issue asks for 90%; the
/// rule agents reach 33 of 34 (97%; 62% before the arrangement generators), and this floor
/// holds them there: only the L of two desks (the first desk's chair keeps the second from the
/// corner) is still missed.
const MIN_MET_PCT: f64 = 97.0;

#[test]
fn the_default_graph_builds_the_named_arrangements() {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("bench/patterns");
    let expect = load_expectations(&dir.join("expect.toml")).unwrap();
    let runtime = Runtime::new(GraphConfig::load(None, &[]).unwrap(), Registry::builtin()).unwrap();
    let rt = tokio::runtime::Builder::new_multi_thread()
        .enable_all()
        .build()
        .unwrap();
    let mut results = Vec::new();
    let mut faults = Vec::new();
    for (id, e) in &expect {
        let scene = SceneSpec::load(&dir.join(format!("{id}.json"))).unwrap();
        let layout = rt
            .block_on(runtime.generate(scene, Arc::new(Trace::default())))
            .unwrap();
        let m = metrics::measure(&layout);
        if m.collision_pct > 0.0 || m.oob_pct > 0.0 || !layout.dropped.is_empty() {
            faults.push(format!(
                "{id}: Col {:.1} OOB {:.1} dropped {:?} {:?}",
                m.collision_pct, m.oob_pct, layout.dropped, m.colliding_pairs
            ));
        }
        let verdict = check(&layout, e);
        println!(
            "{id:24} {:14} {}",
            format!("{:?}", e.pattern),
            if verdict.met {
                "met".to_string()
            } else {
                format!("NOT MET: {}", verdict.why)
            }
        );
        results.push(PatternResult {
            id: id.clone(),
            pattern: e.pattern,
            verdict,
        });
    }
    println!("\n{}", to_markdown(&results));
    assert!(faults.is_empty(), "{faults:#?}");
    let met = results.iter().filter(|r| r.verdict.met).count();
    let pct = 100.0 * met as f64 / results.len() as f64;
    assert!(
        pct >= MIN_MET_PCT,
        "{met} of {} predicates met ({pct:.0}%)",
        results.len()
    );
}
