use glam::{Quat, Vec3};

use super::*;
use crate::layout::PlacedObject;
use crate::scene::Room;

fn parse(bytes: &[u8]) -> gltf::Gltf {
    gltf::Gltf::from_slice(bytes).expect("a valid glb")
}

fn node<'a>(g: &'a gltf::Gltf, name: &str) -> gltf::Node<'a> {
    g.nodes()
        .find(|n| n.name() == Some(name))
        .unwrap_or_else(|| panic!("no node {name}"))
}

fn positions(g: &gltf::Gltf, mesh: gltf::Mesh<'_>) -> Vec<Vec3> {
    let blob = g.blob.as_deref();
    mesh.primitives()
        .flat_map(|p| {
            p.reader(|_| blob)
                .read_positions()
                .unwrap()
                .map(Vec3::from)
                .collect::<Vec<_>>()
        })
        .collect()
}

#[test]
fn every_object_is_a_named_box_with_its_pose_in_y_up_metres() {
    let (_, mut layout) = crate::synth::bedroom();
    // A lamp on the first object's top stands at that height: its node's Y is its elevation.
    let support = layout.objects[0].clone();
    layout.objects.push(crate::PlacedObject {
        name: "lamp-0".into(),
        category: "table lamp".into(),
        size: [25.0, 25.0, 45.0],
        position: support.position,
        rotation: support.rotation,
        elevation: support.top(),
        on: Some(support.name.clone()),
        ..Default::default()
    });
    let bytes = export_glb(&layout, &HashMap::new(), &ExportOptions::default()).unwrap();
    let g = parse(&bytes);
    assert_eq!(g.nodes().count(), 1 + 1 + 4 + layout.objects.len());
    let scene = g.default_scene().unwrap();
    let root = scene.nodes().next().unwrap();
    assert_eq!(root.name(), Some(layout.id.as_str()));
    assert_eq!(root.children().count(), 5 + layout.objects.len());
    for o in &layout.objects {
        let n = node(&g, &o.name);
        let (t, r, s) = n.transform().decomposed();
        let [x, y] = o.position;
        let [w, d, h] = o.size;
        let close = |a: f32, b: f64| (a as f64 - b).abs() < 1e-4;
        assert!(
            close(t[0], x / 100.0) && close(t[1], o.elevation / 100.0) && close(t[2], -y / 100.0),
            "{}",
            o.name
        );
        assert!(close(s[0], w / 100.0) && close(s[1], h / 100.0) && close(s[2], d / 100.0));
        // The front (-Z at rotation 0) turns the way the layout says: 90 faces +x = glTF +X.
        let front = Quat::from_array(r) * Vec3::NEG_Z;
        let rad = o.rotation.to_radians();
        let expected = Vec3::new(rad.sin() as f32, 0.0, -(rad.cos() as f32));
        assert!(
            (front - expected).length() < 1e-4,
            "{}: {front} vs {expected}",
            o.name
        );
        let extras: serde_json::Value =
            serde_json::from_str(n.extras().as_ref().unwrap().get()).unwrap();
        assert_eq!(extras["category"], o.category);
        if o.name == "lamp-0" {
            assert!(t[1] > 0.3, "the lamp is up on {}: {}", support.name, t[1]);
            assert_eq!(extras["elevation_cm"], support.top());
            assert_eq!(extras["on"], support.name);
        } else {
            assert!(extras.get("elevation_cm").is_none() && extras.get("on").is_none());
        }
        // The unit box stands on the floor.
        let ps = positions(&g, n.mesh().unwrap());
        let min_y = ps.iter().map(|p| p.y).fold(f32::MAX, f32::min);
        assert_eq!(min_y, 0.0);
    }
    // Walls of the configured height; none at height 0.
    let wall = node(&g, "wall-top");
    assert!((wall.transform().decomposed().2[1] - 2.5).abs() < 1e-6);
    let low = export_glb(
        &layout,
        &HashMap::new(),
        &ExportOptions {
            wall_height_cm: 0.0,
            ..Default::default()
        },
    )
    .unwrap();
    assert_eq!(parse(&low).nodes().count(), 1 + 1 + layout.objects.len());
}

/// A lopsided tetrahedron whose tip points to +Z (a glTF model's front), off the origin.
fn wedge_glb() -> Vec<u8> {
    let mut b = Builder::default();
    let t = Triangles {
        positions: vec![
            [5.0, 5.0, 5.0],
            [7.0, 5.0, 5.0],
            [5.0, 6.0, 5.0],
            [5.0, 5.0, 9.0],
        ],
        normals: vec![[0.0, 1.0, 0.0]; 4],
        indices: vec![0, 2, 1, 0, 1, 3, 0, 3, 2, 1, 2, 3],
    };
    let mesh = b.mesh("wedge", &t, [200, 10, 10]);
    let n = b.root.push(json::Node {
        mesh: Some(mesh),
        ..Default::default()
    });
    let s = b.root.push(json::Scene {
        extensions: None,
        extras: None,
        name: None,
        nodes: vec![n],
    });
    b.root.scene = Some(s);
    b.finish().unwrap()
}

#[test]
fn an_asset_mesh_is_fitted_to_the_asset_and_turned_to_its_front() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("wedge.glb");
    std::fs::write(&path, wedge_glb()).unwrap();
    let mut layout = crate::synth::bedroom().1;
    layout.objects.truncate(1);
    let o: PlacedObject = layout.objects[0].clone();
    let meshes = HashMap::from([(o.name.clone(), path.clone())]);
    let g = parse(&export_glb(&layout, &meshes, &ExportOptions::default()).unwrap());
    let n = node(&g, &o.name);
    let ps = positions(&g, n.mesh().unwrap());
    let lo = ps.iter().fold(Vec3::MAX, |a, p| a.min(*p));
    let hi = ps.iter().fold(Vec3::MIN, |a, p| a.max(*p));
    assert!((lo - Vec3::new(-0.5, 0.0, -0.5)).length() < 1e-5, "{lo}");
    assert!((hi - Vec3::new(0.5, 1.0, 0.5)).length() < 1e-5, "{hi}");
    // The tip was the model's front (+Z); now it is at -Z, the object's front before its turn.
    let tip = ps.iter().min_by(|a, b| a.z.total_cmp(&b.z)).unwrap();
    assert!((tip.z + 0.5).abs() < 1e-5);
    assert_eq!(ps.iter().filter(|p| (p.z + 0.5).abs() < 1e-5).count(), 1);
    // Its colour came along.
    let m = n.mesh().unwrap().primitives().next().unwrap().material();
    assert_eq!(m.name(), Some("#c80a0a"));

    // A mesh that is not a glb is an error naming the file.
    std::fs::write(&path, b"not a model").unwrap();
    let e = export_glb(&layout, &meshes, &ExportOptions::default())
        .unwrap_err()
        .to_string();
    assert!(e.contains("wedge.glb"), "{e}");
}

/// The synthetic bedroom in an L-shaped room (its top-right corner cut away) with a door on
/// wall 0 and a window on the slanted wall 2.
fn l_shaped_bedroom() -> Layout {
    use disco_core::room::{Door, Hinge, Swing, Window};
    let mut layout = crate::synth::bedroom().1;
    let mut room = Room::from_polygon(vec![
        [0.0, 0.0],
        [layout.room.width, 0.0],
        [layout.room.width, 200.0],
        [layout.room.width - 100.0, layout.room.depth],
        [0.0, layout.room.depth],
    ]);
    room.doors.push(Door {
        wall: 0,
        at: 60.0,
        width: 90.0,
        swing: Swing::In,
        hinge: Hinge::Right,
    });
    room.windows.push(Window {
        wall: 2,
        at: 60.0,
        width: 60.0,
        sill: 90.0,
        height: 100.0,
    });
    layout.room = room;
    layout
}

#[test]
fn a_polygon_room_has_a_wall_per_edge_and_a_floor_of_its_outline() {
    let layout = l_shaped_bedroom();
    let bytes = export_glb(&layout, &HashMap::new(), &ExportOptions::default()).unwrap();
    if let Ok(dir) = std::env::var("DISCO_GLB_DUMP") {
        std::fs::write(format!("{dir}/l-shaped.glb"), &bytes).unwrap();
    }
    let g = parse(&bytes);
    assert_eq!(g.nodes().count(), 1 + 1 + 5 + layout.objects.len());
    let walls: Vec<String> = g
        .nodes()
        .filter_map(|n| {
            n.name()
                .filter(|s| s.starts_with("wall-"))
                .map(String::from)
        })
        .collect();
    assert_eq!(walls, ["wall-0", "wall-1", "wall-2", "wall-3", "wall-4"]);
    // The floor's top is the outline: nothing of it lies in the cut-away corner.
    let floor = positions(&g, node(&g, "floor").mesh().unwrap());
    let (w, d) = (
        layout.room.width as f32 / 100.0,
        layout.room.depth as f32 / 100.0,
    );
    assert!(
        floor
            .iter()
            .any(|p| (p.x - w).abs() < 1e-5 && (p.z + 2.0).abs() < 1e-5)
    );
    assert!(
        !floor
            .iter()
            .any(|p| (p.x - w).abs() < 1e-5 && (p.z + d).abs() < 1e-5)
    );
    // Wall 0 has its door cut out: some vertex sits at the door's top, 2.1 m up.
    let wall0 = positions(&g, node(&g, "wall-0").mesh().unwrap());
    assert!(wall0.iter().any(|p| (p.y - 2.1).abs() < 1e-5));
    let top = wall0.iter().map(|p| p.y).fold(f32::MIN, f32::max);
    assert!((top - 2.5).abs() < 1e-6);
    // The slanted wall 2 holds the window's sill and lintel heights.
    let wall2 = positions(&g, node(&g, "wall-2").mesh().unwrap());
    for h in [0.9, 1.9] {
        assert!(wall2.iter().any(|p| (p.y - h).abs() < 1e-5), "{h}");
    }
}
