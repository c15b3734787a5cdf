//! Real rooms end to end: the default graph on every scene of `bench/rooms` (L, U and T shapes,
//! slanted walls, doors and windows) must give layouts with nothing colliding, nothing outside
//! the outline, no door's keep-clear zone entered by anything but a floor covering, no window's
//! zone entered by a piece taller than its sill and nothing dropped; and every object reachable
//! by a person walking in through a door.

use std::path::Path;

use disco_layout::Layout;
use disco_layout::geometry3d;
use disco_layout::metrics::{REACH_CELL_CM, unreachable_objects};

use crate::harness::{disco, stderr};

/// What one layout breaks, in words (empty when it keeps every rule); reach apart. Collisions are
/// 3D (a painting above a bench does not collide with it); the room's outline and zones bind what
/// stands on the floor; anything off the floor must be held where it is and clear of the openings
/// of its wall.
pub(crate) fn faults(layout: &Layout) -> Vec<String> {
    let room = &layout.room;
    let mut out = Vec::new();
    let solid: Vec<_> = layout.objects.iter().filter(|o| !o.is_flat()).collect();
    for (i, a) in solid.iter().enumerate() {
        for b in &solid[i + 1..] {
            if geometry3d::collide(a, b) {
                out.push(format!("{} collides with {}", a.name, b.name));
            }
        }
    }
    out.extend(geometry3d::unsupported(&layout.objects, room));
    out.extend(geometry3d::over_openings(&layout.objects, room));
    let zones = room.keep_clear();
    for o in layout.objects.iter().filter(|o| o.on_floor()) {
        let fp = o.footprint();
        let outside = fp.area_outside(room);
        if outside > 1.0 {
            out.push(format!("{} has {outside:.0} cm² outside the room", o.name));
        }
        for z in zones.iter().filter(|z| fp.intrudes(z, o.size[2])) {
            out.push(format!("{} stands in the zone of {:?}", o.name, z.kind));
        }
    }
    for d in &layout.dropped {
        out.push(format!("{} was dropped", d.name));
    }
    out
}

#[test]
fn the_default_graph_keeps_real_rooms_walkable() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("out");
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let (rooms, config) = (root.join("bench/rooms"), root.join("config/default.toml"));
    let o = disco(&[
        "bench",
        "--scenes",
        rooms.to_str().unwrap(),
        "--config",
        config.to_str().unwrap(),
        "--out",
        out.to_str().unwrap(),
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    let mut layouts = 0;
    let mut all = Vec::new();
    let (mut solid, mut unreachable) = (0, Vec::new());
    for entry in std::fs::read_dir(out.join("layouts")).unwrap() {
        let path = entry.unwrap().path();
        let layout: Layout =
            serde_json::from_str(&std::fs::read_to_string(&path).unwrap()).unwrap();
        assert!(
            !layout.room.is_rectangle() || layout.room.has_openings(),
            "{}",
            layout.id
        );
        layouts += 1;
        solid += layout.objects.iter().filter(|o| !o.is_flat()).count();
        unreachable.extend(
            unreachable_objects(&layout.room, &layout.objects, REACH_CELL_CM)
                .into_iter()
                .map(|name| format!("{}: {name}", layout.id)),
        );
        all.extend(
            faults(&layout)
                .into_iter()
                .map(|f| format!("{}: {f}", layout.id)),
        );
    }
    assert!(layouts >= 30, "only {layouts} rooms");
    assert!(all.is_empty(), "{} faults:\n{}", all.len(), all.join("\n"));
    assert!(
        unreachable.is_empty(),
        "{} of {solid} objects walled in: {}",
        unreachable.len(),
        unreachable.join(", ")
    );
}
