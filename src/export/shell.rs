//! The room's shell in 3D: the floor and the walls around it.
//!
//! A plain rectangle gets the floor slab and four wall boxes it always had. Any other room (a
//! polygon outline, or a rectangle with doors or windows) gets its floor as the outline
//! triangulated (ear clipping) and extruded down by the wall thickness, and one wall node per
//! outline edge (`wall-0`, `wall-1`, ... in the outline's order) standing outside the room, its
//! corners mitred, split into blocks around its openings: a door is cut from the floor up to the
//! door height, a window from its sill to its sill plus its height.

use glam::DVec2;
use gltf_json as json;

use super::{Builder, ExportOptions, Triangles, WALL_COLOUR};
use crate::scene::Room;

/// A block of wall: its footprint (floor-plan cm, any order around it) from `bottom` to `top` cm.
struct Block {
    footprint: [DVec2; 4],
    bottom: f64,
    top: f64,
}

impl Builder {
    /// The floor (its top at Y = 0) and, unless their height is 0, the walls standing outside
    /// the room.
    pub(super) fn floor_and_walls(
        &mut self,
        room: &Room,
        options: &ExportOptions,
    ) -> Vec<json::Index<json::Node>> {
        if room.is_rectangle() && !room.has_openings() {
            return self.rectangle_shell(room, options);
        }
        let floor = self.mesh(
            "floor",
            &floor_triangles(room, options),
            crate::render::FLOOR,
        );
        let mut nodes = vec![self.placed_mesh("floor", floor)];
        if options.wall_height_cm > 0.0 {
            for (i, blocks) in wall_blocks(room, options).into_iter().enumerate() {
                let name = format!("wall-{i}");
                let mut t = Triangles::default();
                for b in &blocks {
                    add_block(&mut t, b);
                }
                let mesh = self.mesh(&name, &t, WALL_COLOUR);
                nodes.push(self.placed_mesh(&name, mesh));
            }
        }
        nodes
    }

    /// A node holding `mesh` as it is (its vertices already in the room's place).
    fn placed_mesh(
        &mut self,
        name: &str,
        mesh: json::Index<json::Mesh>,
    ) -> json::Index<json::Node> {
        self.root.push(json::Node {
            name: Some(name.to_string()),
            mesh: Some(mesh),
            ..Default::default()
        })
    }

    /// The rectangle's floor slab and four walls as boxes, as before rooms had outlines.
    fn rectangle_shell(
        &mut self,
        room: &Room,
        options: &ExportOptions,
    ) -> Vec<json::Index<json::Node>> {
        let t = options.wall_thickness_cm;
        let floor_mesh = self.box_mesh(crate::render::FLOOR);
        let mut nodes = vec![self.node(
            "floor",
            floor_mesh,
            [room.width / 2.0, -t, room.depth / 2.0],
            0.0,
            [room.width, t, room.depth],
            None,
        )];
        if options.wall_height_cm > 0.0 {
            let h = options.wall_height_cm;
            let wall_mesh = self.box_mesh(WALL_COLOUR);
            let (w, d) = (room.width, room.depth);
            for (name, centre, size) in [
                ("wall-bottom", [w / 2.0, -t / 2.0], [w + 2.0 * t, t]),
                ("wall-top", [w / 2.0, d + t / 2.0], [w + 2.0 * t, t]),
                ("wall-left", [-t / 2.0, d / 2.0], [t, d]),
                ("wall-right", [w + t / 2.0, d / 2.0], [t, d]),
            ] {
                nodes.push(self.node(
                    name,
                    wall_mesh,
                    [centre[0], 0.0, centre[1]],
                    0.0,
                    [size[0], h, size[1]],
                    None,
                ));
            }
        }
        nodes
    }
}

/// A floor-plan point at `height` cm, in glTF's Y-up metres (plan y becomes -Z).
fn gltf_point(p: DVec2, height: f64) -> [f32; 3] {
    [
        (p.x / 100.0) as f32,
        (height / 100.0) as f32,
        (-p.y / 100.0) as f32,
    ]
}

/// A floor-plan direction (or straight up for `up`) as a glTF normal.
fn gltf_normal(n: DVec2, up: f64) -> [f32; 3] {
    [n.x as f32, up as f32, -n.y as f32]
}

impl Triangles {
    /// Adds the convex, planar polygon `points` facing `normal` (fanned from its first point),
    /// each triangle wound counter-clockwise seen from the side `normal` points to.
    fn face(&mut self, points: &[[f32; 3]], normal: [f32; 3]) {
        for i in 1..points.len().saturating_sub(1) {
            self.triangle([points[0], points[i], points[i + 1]], normal);
        }
    }

    /// Adds one triangle facing `normal`; a degenerate one is left out.
    fn triangle(&mut self, mut corners: [[f32; 3]; 3], normal: [f32; 3]) {
        let [a, b, c] = corners.map(glam::Vec3::from);
        let cross = (b - a).cross(c - a);
        if cross.length() < 1e-9 {
            return;
        }
        if cross.dot(glam::Vec3::from(normal)) < 0.0 {
            corners.swap(1, 2);
        }
        let base = self.positions.len() as u32;
        self.positions.extend(corners);
        self.normals.extend([normal; 3]);
        self.indices.extend([base, base + 1, base + 2]);
    }
}

/// The floor: the outline's triangles on top (Y = 0) and underneath (the wall thickness lower),
/// and a side face along every edge.
fn floor_triangles(room: &Room, options: &ExportOptions) -> Triangles {
    let outline = room.outline();
    let below = -options.wall_thickness_cm;
    let mut t = Triangles::default();
    for [a, b, c] in ear_clip(&outline) {
        let top = [a, b, c].map(|p| gltf_point(p, 0.0));
        t.triangle(top, [0.0, 1.0, 0.0]);
        let bottom = [a, b, c].map(|p| gltf_point(p, below));
        t.triangle(bottom, [0.0, -1.0, 0.0]);
    }
    for edge in room.walls() {
        let side = [
            gltf_point(edge.start, 0.0),
            gltf_point(edge.end, 0.0),
            gltf_point(edge.end, below),
            gltf_point(edge.start, below),
        ];
        t.face(&side, gltf_normal(-edge.inward_normal(), 0.0));
    }
    t
}

/// Adds a block's six faces.
fn add_block(t: &mut Triangles, block: &Block) {
    let f = block.footprint;
    let top = f.map(|p| gltf_point(p, block.top));
    let bottom = f.map(|p| gltf_point(p, block.bottom));
    t.face(&top, [0.0, 1.0, 0.0]);
    t.face(&bottom, [0.0, -1.0, 0.0]);
    let centre = f.iter().copied().sum::<DVec2>() / 4.0;
    for i in 0..4 {
        let (a, b) = (f[i], f[(i + 1) % 4]);
        let mut n = (b - a).perp().normalize_or_zero();
        if n.dot((a + b) / 2.0 - centre) < 0.0 {
            n = -n;
        }
        let side = [
            gltf_point(a, block.bottom),
            gltf_point(b, block.bottom),
            gltf_point(b, block.top),
            gltf_point(a, block.top),
        ];
        t.face(&side, gltf_normal(n, 0.0));
    }
}

/// Where the outer faces of the two walls meeting at each vertex meet: vertex `i` pushed out by
/// the wall thickness along both walls' outward normals (a mitred corner).
fn outer_corners(room: &Room, thickness: f64) -> Vec<DVec2> {
    let walls = room.walls();
    let n = walls.len();
    (0..n)
        .map(|i| {
            let before = walls[(i + n - 1) % n].inward_normal();
            let after = walls[i].inward_normal();
            let along = 1.0 + before.dot(after);
            if along < 0.2 {
                // A hairpin: mitring would shoot far out; square it off instead.
                return walls[i].start - after * thickness;
            }
            walls[i].start - (before + after) * thickness / along
        })
        .collect()
}

/// Every wall's blocks: full height between its openings, and below and above each opening.
fn wall_blocks(room: &Room, options: &ExportOptions) -> Vec<Vec<Block>> {
    let height = options.wall_height_cm;
    let thickness = options.wall_thickness_cm;
    let outer = outer_corners(room, thickness);
    let walls = room.walls();
    let n = walls.len();
    let mut all = Vec::with_capacity(n);
    for edge in &walls {
        let length = edge.length();
        let out = -edge.inward_normal() * thickness;
        let footprint = |from: f64, to: f64| {
            let outer_from = if from <= 0.0 {
                outer[edge.index]
            } else {
                edge.point(from) + out
            };
            let outer_to = if to >= length {
                outer[(edge.index + 1) % n]
            } else {
                edge.point(to) + out
            };
            [edge.point(from), edge.point(to), outer_to, outer_from]
        };
        // Each opening as (start, end, bottom, top) along this wall.
        let mut openings: Vec<(f64, f64, f64, f64)> = room
            .doors
            .iter()
            .filter(|d| d.wall == edge.index)
            .map(|d| {
                (
                    d.at - d.width / 2.0,
                    d.at + d.width / 2.0,
                    0.0,
                    options.door_height_cm,
                )
            })
            .chain(
                room.windows
                    .iter()
                    .filter(|w| w.wall == edge.index)
                    .map(|w| {
                        (
                            w.at - w.width / 2.0,
                            w.at + w.width / 2.0,
                            w.sill,
                            w.sill + w.height,
                        )
                    }),
            )
            .collect();
        openings.sort_by(|a, b| a.0.total_cmp(&b.0));
        let mut blocks = Vec::new();
        let mut solid = |from: f64, to: f64, bottom: f64, top: f64| {
            let top = top.min(height);
            if to - from > 1e-6 && top - bottom > 1e-6 {
                blocks.push(Block {
                    footprint: footprint(from, to),
                    bottom,
                    top,
                });
            }
        };
        let mut from = 0.0;
        for &(start, end, bottom, top) in &openings {
            solid(from, start, 0.0, height);
            solid(start, end, 0.0, bottom);
            solid(start, end, top, height);
            from = end;
        }
        solid(from, length, 0.0, height);
        all.push(blocks);
    }
    all
}

/// The triangles of the simple counter-clockwise polygon `v`, by ear clipping.
fn ear_clip(v: &[DVec2]) -> Vec<[DVec2; 3]> {
    let mut left: Vec<usize> = (0..v.len()).collect();
    let mut out = Vec::with_capacity(v.len().saturating_sub(2));
    while left.len() > 3 {
        let n = left.len();
        let ear = (0..n).find(|&i| {
            let (a, b, c) = (v[left[(i + n - 1) % n]], v[left[i]], v[left[(i + 1) % n]]);
            (b - a).perp_dot(c - b) > 1e-9
                && left
                    .iter()
                    .all(|&k| [a, b, c].contains(&v[k]) || !in_triangle(v[k], a, b, c))
        });
        // A simple polygon always has an ear; should rounding hide every one, take any corner.
        let i = ear.unwrap_or(0);
        out.push([v[left[(i + n - 1) % n]], v[left[i]], v[left[(i + 1) % n]]]);
        left.remove(i);
    }
    if let [a, b, c] = left[..] {
        out.push([v[a], v[b], v[c]]);
    }
    out
}

/// Whether `p` is inside or on the counter-clockwise triangle `a`, `b`, `c`.
fn in_triangle(p: DVec2, a: DVec2, b: DVec2, c: DVec2) -> bool {
    (b - a).perp_dot(p - a) >= 0.0
        && (c - b).perp_dot(p - b) >= 0.0
        && (a - c).perp_dot(p - c) >= 0.0
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn ear_clipping_covers_an_l_exactly() {
        let l = [
            [0.0, 0.0],
            [400.0, 0.0],
            [400.0, 200.0],
            [250.0, 200.0],
            [250.0, 300.0],
            [0.0, 300.0],
        ]
        .map(|[x, y]| DVec2::new(x, y));
        let tris = ear_clip(&l);
        assert_eq!(tris.len(), 4);
        let area: f64 = tris
            .iter()
            .map(|[a, b, c]| (*b - *a).perp_dot(*c - *a) / 2.0)
            .sum();
        assert!(
            (area - (400.0 * 200.0 + 250.0 * 100.0)).abs() < 1e-6,
            "{area}"
        );
        assert!(
            tris.iter()
                .all(|[a, b, c]| (*b - *a).perp_dot(*c - *a) > 0.0)
        );
    }

    /// Whether some block of `blocks` holds the floor-plan point `p` at `height`.
    fn solid_at(blocks: &[Block], p: DVec2, height: f64) -> bool {
        blocks.iter().any(|b| {
            let f = b.footprint;
            let inside = (0..4).all(|i| (f[(i + 1) % 4] - f[i]).perp_dot(p - f[i]) >= 0.0)
                || (0..4).all(|i| (f[(i + 1) % 4] - f[i]).perp_dot(p - f[i]) <= 0.0);
            inside && height > b.bottom && height < b.top
        })
    }

    #[test]
    fn doors_and_windows_are_cut_through_their_walls() {
        use disco_core::room::{Door, Window};
        let mut room = Room::rect(400.0, 300.0);
        room.doors.push(Door::new(0, 100.0, 90.0));
        room.windows.push(Window {
            wall: 1,
            at: 150.0,
            width: 100.0,
            sill: 90.0,
            height: 120.0,
        });
        let blocks = wall_blocks(&room, &ExportOptions::default());
        assert_eq!(blocks.len(), 4);
        // In the middle of wall 0's thickness, under the door's centre: open to 210 cm.
        let door = DVec2::new(100.0, -5.0);
        assert!(!solid_at(&blocks[0], door, 100.0));
        assert!(solid_at(&blocks[0], door, 230.0));
        assert!(solid_at(&blocks[0], DVec2::new(300.0, -5.0), 100.0));
        // Wall 1 (x = 400 to 410): solid below the sill and above the window, open between.
        let window = DVec2::new(405.0, 150.0);
        assert!(solid_at(&blocks[1], window, 50.0));
        assert!(!solid_at(&blocks[1], window, 150.0));
        assert!(solid_at(&blocks[1], window, 240.0));
        // Walls without openings are one block each.
        assert_eq!(blocks[2].len(), 1);
    }

    #[test]
    fn mitred_corners_meet_at_the_walls_outer_faces() {
        let room = Room::rect(400.0, 300.0);
        let outer = outer_corners(&room, 10.0);
        assert!((outer[0] - DVec2::new(-10.0, -10.0)).length() < 1e-9);
        assert!((outer[2] - DVec2::new(410.0, 310.0)).length() < 1e-9);
    }
}
