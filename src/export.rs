//! 3D export: a layout as a binary glTF (`.glb`) that Blender, three.js and game engines open.
//!
//! The file holds one root node named after the layout, with the floor, the walls (standing
//! outside the room, so its inside is exactly the layout's room: four boxes for a plain
//! rectangle, else one node per outline edge with its doors and windows cut out)
//! and one node per placed object, named after it. An object is a box of its size in its render colour, or, when its asset has a
//! `mesh` (a `.glb`), that mesh: turned so its front faces the object's front, scaled to the
//! asset's size and set on the floor. Geometry and base colours carry over; textures do not.
//!
//! Axes: glTF is Y-up, right-handed, in metres, and a model's front faces +Z. Our floor plan's x
//! becomes glTF X, its y becomes -Z, heights become Y; centimetres become metres. Rotation (our
//! degrees clockwise seen from above) becomes a turn of minus that angle about +Y, so an object
//! at rotation 0 (front to +y) faces -Z. Each object node carries `extras` with its category and
//! its pose in the layout's own units.

use std::collections::HashMap;
use std::path::{Path, PathBuf};

use gltf_json as json;
use json::validation::Checked::Valid;
use json::validation::USize64;
use serde_json::json as value;

use crate::error::{Error, Result};
use crate::layout::Layout;
use crate::render::object_colour;
use crate::scene::SceneSpec;

/// The colour of the walls (sRGB).
const WALL_COLOUR: [u8; 3] = [225, 225, 220];

/// What the export adds around the objects.
#[derive(Debug, Clone)]
pub struct ExportOptions {
    /// Height of the walls, in cm (0 leaves them out).
    pub wall_height_cm: f64,
    /// Thickness of walls and floor, in cm.
    pub wall_thickness_cm: f64,
    /// How high a door is cut into its wall, in cm.
    pub door_height_cm: f64,
}

impl Default for ExportOptions {
    fn default() -> Self {
        ExportOptions {
            wall_height_cm: 250.0,
            wall_thickness_cm: 10.0,
            door_height_cm: 210.0,
        }
    }
}

/// The largest mesh file read (a regular file only: a FIFO or device is refused, not read).
pub const MAX_MESH_BYTES: u64 = 256 * 1024 * 1024;

/// Mesh files by object name: the scene's `mesh` entries, relative paths resolved against the
/// scene file's folder.
pub fn meshes_of(scene: &SceneSpec, scene_path: Option<&Path>) -> HashMap<String, PathBuf> {
    let base = scene_path
        .and_then(Path::parent)
        .map(Path::to_path_buf)
        .unwrap_or_default();
    scene
        .assets
        .iter()
        .filter_map(|a| a.mesh.as_ref().map(|m| (a.name.clone(), base.join(m))))
        .collect()
}

/// The layout as a `.glb` file's bytes. `meshes` maps object names to `.glb` files to use instead
/// of boxes; a mesh that cannot be read is an error naming the file.
pub fn export_glb(
    layout: &Layout,
    meshes: &HashMap<String, PathBuf>,
    options: &ExportOptions,
) -> Result<Vec<u8>> {
    let mut b = Builder::default();
    let mut children = b.floor_and_walls(&layout.room, options);
    children.extend(b.objects(layout, meshes)?);
    let root = b.root.push(json::Node {
        name: Some(layout.id.clone()),
        children: Some(children),
        ..Default::default()
    });
    let scene = b.root.push(json::Scene {
        extensions: None,
        extras: None,
        name: Some(layout.id.clone()),
        nodes: vec![root],
    });
    b.root.scene = Some(scene);
    b.finish()
}

/// Accumulates the document and its binary buffer.
#[derive(Default)]
struct Builder {
    root: json::Root,
    bin: Vec<u8>,
    materials: HashMap<[u8; 3], json::Index<json::Material>>,
    boxes: HashMap<[u8; 3], json::Index<json::Mesh>>,
}

/// Triangles with a normal per vertex: an object's in its unit space (X and Z in [-0.5, 0.5], Y in
/// [0, 1], front to -Z), the room shell's in place.
#[derive(Default)]
struct Triangles {
    positions: Vec<[f32; 3]>,
    normals: Vec<[f32; 3]>,
    indices: Vec<u32>,
}

impl Builder {
    /// One node per placed object: its asset's mesh if `meshes` names one (each file read
    /// once), else a box in its render colour; `extras` keep its category and pose in cm.
    fn objects(
        &mut self,
        layout: &Layout,
        meshes: &HashMap<String, PathBuf>,
    ) -> Result<Vec<json::Index<json::Node>>> {
        let mut loaded: HashMap<PathBuf, json::Index<json::Mesh>> = HashMap::new();
        let mut nodes = Vec::new();
        for o in &layout.objects {
            let colour = object_colour(layout, o);
            let mesh = match meshes.get(&o.name) {
                Some(path) => match loaded.get(path) {
                    Some(m) => *m,
                    None => {
                        let m = self.imported_mesh(path, colour).map_err(|e| {
                            Error::invalid(
                                path,
                                format!("mesh of {:?} in layout {:?}", o.name, layout.id),
                                e.to_string(),
                            )
                        })?;
                        loaded.insert(path.clone(), m);
                        m
                    }
                },
                None => self.box_mesh(colour),
            };
            let [w, d, h] = o.size;
            let mut extras = value!({
                "category": o.category,
                "size_cm": o.size,
                "position_cm": o.position,
                "rotation_deg": o.rotation,
            });
            // Objects off the floor say how high and on what (floor objects export as before).
            if o.elevation != 0.0 {
                extras["elevation_cm"] = value!(o.elevation);
            }
            if let Some(on) = &o.on {
                extras["on"] = value!(on);
            }
            if let Some(wall) = o.wall {
                extras["wall"] = value!(wall);
            }
            nodes.push(self.node(
                &o.name,
                mesh,
                [o.position[0], o.elevation, o.position[1]],
                o.rotation,
                [w, h, d],
                Some(extras),
            ));
        }
        Ok(nodes)
    }

    /// A node for something `size` cm (X, Y, Z extents) standing at floor-plan `at` = [x, y0, y]
    /// (y0 the height of its base), turned `rotation` degrees clockwise from above.
    fn node(
        &mut self,
        name: &str,
        mesh: json::Index<json::Mesh>,
        at: [f64; 3],
        rotation: f64,
        size: [f64; 3],
        extras: Option<serde_json::Value>,
    ) -> json::Index<json::Node> {
        let half = (-rotation.to_radians() / 2.0) as f32;
        self.root.push(json::Node {
            name: Some(name.to_string()),
            mesh: Some(mesh),
            translation: Some([
                (at[0] / 100.0) as f32,
                (at[1] / 100.0) as f32,
                (-at[2] / 100.0) as f32,
            ]),
            rotation: (rotation != 0.0).then_some(json::scene::UnitQuaternion([
                0.0,
                half.sin(),
                0.0,
                half.cos(),
            ])),
            scale: Some(size.map(|v| (v / 100.0) as f32)),
            extras: extras.and_then(|e| serde_json::value::to_raw_value(&e).ok()),
            ..Default::default()
        })
    }

    fn material(&mut self, rgb: [u8; 3]) -> json::Index<json::Material> {
        if let Some(m) = self.materials.get(&rgb) {
            return *m;
        }
        let linear = rgb.map(|c| {
            let c = c as f32 / 255.0;
            if c <= 0.04045 {
                c / 12.92
            } else {
                ((c + 0.055) / 1.055).powf(2.4)
            }
        });
        let mut material = json::Material {
            name: Some(format!("#{:02x}{:02x}{:02x}", rgb[0], rgb[1], rgb[2])),
            ..Default::default()
        };
        material.pbr_metallic_roughness.base_color_factor =
            json::material::PbrBaseColorFactor([linear[0], linear[1], linear[2], 1.0]);
        material.pbr_metallic_roughness.metallic_factor = json::material::StrengthFactor(0.0);
        material.pbr_metallic_roughness.roughness_factor = json::material::StrengthFactor(0.8);
        let index = self.root.push(material);
        self.materials.insert(rgb, index);
        index
    }

    /// The unit box (X, Z in [-0.5, 0.5], Y in [0, 1]) in one colour, shared by every object of it.
    fn box_mesh(&mut self, rgb: [u8; 3]) -> json::Index<json::Mesh> {
        if let Some(m) = self.boxes.get(&rgb) {
            return *m;
        }
        let mut t = Triangles {
            positions: Vec::new(),
            normals: Vec::new(),
            indices: Vec::new(),
        };
        // Per face: its normal axis and sign; four corners each.
        for axis in 0..3 {
            for sign in [-1.0f32, 1.0] {
                let (u, v) = ((axis + 1) % 3, (axis + 2) % 3);
                let base = t.positions.len() as u32;
                let mut normal = [0.0; 3];
                normal[axis] = sign;
                for (a, b) in [(-1.0f32, -1.0f32), (1.0, -1.0), (1.0, 1.0), (-1.0, 1.0)] {
                    let mut p = [0.0f32; 3];
                    p[axis] = sign * 0.5;
                    p[u] = a * 0.5;
                    p[v] = b * 0.5;
                    p[1] += 0.5; // Y from 0 to 1
                    t.positions.push(p);
                    t.normals.push(normal);
                }
                // Counter-clockwise seen from outside.
                if sign > 0.0 {
                    t.indices
                        .extend([base, base + 1, base + 2, base, base + 2, base + 3]);
                } else {
                    t.indices
                        .extend([base, base + 2, base + 1, base, base + 3, base + 2]);
                }
            }
        }
        let mesh = self.mesh(&format!("box {rgb:?}"), &t, rgb);
        self.boxes.insert(rgb, mesh);
        mesh
    }

    /// A mesh read from a `.glb`, normalised into the unit box with its front (+Z) turned to -Z,
    /// in the colour of its first material (`fallback` when it has none).
    fn imported_mesh(&mut self, path: &Path, fallback: [u8; 3]) -> Result<json::Index<json::Mesh>> {
        let raw = RawMesh::read(path)?;
        let name = path
            .file_stem()
            .map(|s| s.to_string_lossy().into_owned())
            .unwrap_or_default();
        let colour = raw.colour.unwrap_or(fallback);
        Ok(self.mesh(&name, &raw.into_unit_box(), colour))
    }

    /// Appends `t` to the buffer (positions, normals, indices) and makes a one-primitive mesh.
    fn mesh(&mut self, name: &str, t: &Triangles, rgb: [u8; 3]) -> json::Index<json::Mesh> {
        let (lo, hi) =
            t.positions
                .iter()
                .fold(([f32::MAX; 3], [f32::MIN; 3]), |(mut lo, mut hi), p| {
                    for i in 0..3 {
                        lo[i] = lo[i].min(p[i]);
                        hi[i] = hi[i].max(p[i]);
                    }
                    (lo, hi)
                });
        let positions = self.accessor(
            bytes_of(&t.positions),
            t.positions.len(),
            json::accessor::Type::Vec3,
            json::accessor::ComponentType::F32,
            json::buffer::Target::ArrayBuffer,
            Some((value!(lo), value!(hi))),
        );
        let normals = self.accessor(
            bytes_of(&t.normals),
            t.normals.len(),
            json::accessor::Type::Vec3,
            json::accessor::ComponentType::F32,
            json::buffer::Target::ArrayBuffer,
            None,
        );
        let indices = self.accessor(
            t.indices.iter().flat_map(|i| i.to_le_bytes()).collect(),
            t.indices.len(),
            json::accessor::Type::Scalar,
            json::accessor::ComponentType::U32,
            json::buffer::Target::ElementArrayBuffer,
            None,
        );
        let material = self.material(rgb);
        let mut attributes = std::collections::BTreeMap::new();
        attributes.insert(Valid(json::mesh::Semantic::Positions), positions);
        attributes.insert(Valid(json::mesh::Semantic::Normals), normals);
        self.root.push(json::Mesh {
            extensions: None,
            extras: None,
            name: Some(name.to_string()),
            primitives: vec![json::mesh::Primitive {
                attributes,
                extensions: None,
                extras: None,
                indices: Some(indices),
                material: Some(material),
                mode: Valid(json::mesh::Mode::Triangles),
                targets: None,
            }],
            weights: None,
        })
    }

    fn accessor(
        &mut self,
        data: Vec<u8>,
        count: usize,
        type_: json::accessor::Type,
        component: json::accessor::ComponentType,
        target: json::buffer::Target,
        bounds: Option<(serde_json::Value, serde_json::Value)>,
    ) -> json::Index<json::Accessor> {
        while !self.bin.len().is_multiple_of(4) {
            self.bin.push(0);
        }
        let offset = self.bin.len();
        self.bin.extend_from_slice(&data);
        let view = self.root.push(json::buffer::View {
            buffer: json::Index::new(0),
            byte_length: USize64::from(data.len()),
            byte_offset: Some(USize64::from(offset)),
            byte_stride: None,
            name: None,
            target: Some(Valid(target)),
            extensions: None,
            extras: None,
        });
        let (min, max) = bounds.unzip();
        self.root.push(json::Accessor {
            buffer_view: Some(view),
            byte_offset: None,
            count: USize64::from(count),
            component_type: Valid(json::accessor::GenericComponentType(component)),
            extensions: None,
            extras: None,
            type_: Valid(type_),
            min,
            max,
            name: None,
            normalized: false,
            sparse: None,
        })
    }

    fn finish(mut self) -> Result<Vec<u8>> {
        while !self.bin.len().is_multiple_of(4) {
            self.bin.push(0);
        }
        self.root.push(json::Buffer {
            byte_length: USize64::from(self.bin.len()),
            name: None,
            uri: None,
            extensions: None,
            extras: None,
        });
        self.root.asset.generator = Some(format!("disco-layout {}", env!("CARGO_PKG_VERSION")));
        let text = json::serialize::to_vec(&self.root).map_err(|e| Error::Render(e.to_string()))?;
        let glb = gltf::binary::Glb {
            header: gltf::binary::Header {
                magic: *b"glTF",
                version: 2,
                length: 0,
            },
            json: std::borrow::Cow::Owned(text),
            bin: Some(std::borrow::Cow::Owned(self.bin)),
        };
        glb.to_vec().map_err(|e| Error::Render(e.to_string()))
    }
}

/// The triangles of a `.glb` file, every node's transform applied, in the file's own units and
/// axes; with the colour of the first material met.
struct RawMesh {
    positions: Vec<glam::Vec3>,
    normals: Vec<glam::Vec3>,
    indices: Vec<u32>,
    colour: Option<[u8; 3]>,
}

impl RawMesh {
    /// Reads `path`: its default scene (else its first), node by node. An unreadable file, one
    /// without a scene or without triangles is an error naming the file.
    fn read(path: &Path) -> Result<RawMesh> {
        let bad = |reason: String| Error::invalid(path, "mesh", reason);
        let bytes = disco_core::io::read_bytes(path, MAX_MESH_BYTES)?;
        let gltf = gltf::Gltf::from_slice(&bytes).map_err(|e| bad(e.to_string()))?;
        let blob = gltf.blob.as_deref();
        let scene = gltf
            .default_scene()
            .or_else(|| gltf.scenes().next())
            .ok_or_else(|| bad("the file has no scene".into()))?;
        let mut raw = RawMesh {
            positions: Vec::new(),
            normals: Vec::new(),
            indices: Vec::new(),
            colour: None,
        };
        let mut stack: Vec<(gltf::Node, glam::Mat4)> =
            scene.nodes().map(|n| (n, glam::Mat4::IDENTITY)).collect();
        while let Some((node, parent)) = stack.pop() {
            let m = parent * glam::Mat4::from_cols_array_2d(&node.transform().matrix());
            if let Some(mesh) = node.mesh() {
                for prim in mesh.primitives() {
                    raw.add_primitive(&prim, m, blob);
                }
            }
            stack.extend(node.children().map(|c| (c, m)));
        }
        if raw.positions.is_empty() || raw.indices.is_empty() {
            return Err(bad("the file has no triangles with positions".into()));
        }
        Ok(raw)
    }

    /// Appends one primitive's triangles, transformed by `m`; one without positions is skipped.
    /// Missing normals point up; missing indices take the vertices in order.
    fn add_primitive(&mut self, prim: &gltf::Primitive, m: glam::Mat4, blob: Option<&[u8]>) {
        let reader = prim.reader(|buffer| match buffer.source() {
            gltf::buffer::Source::Bin => blob,
            gltf::buffer::Source::Uri(_) => None,
        });
        let Some(ps) = reader.read_positions() else {
            return;
        };
        let base = self.positions.len() as u32;
        let ps: Vec<glam::Vec3> = ps
            .map(|p| m.transform_point3(glam::Vec3::from(p)))
            .collect();
        let normal_m = glam::Mat3::from_mat4(m).inverse().transpose();
        match reader.read_normals() {
            Some(ns) => self
                .normals
                .extend(ns.map(|n| (normal_m * glam::Vec3::from(n)).normalize_or_zero())),
            None => self
                .normals
                .extend(std::iter::repeat_n(glam::Vec3::Y, ps.len())),
        }
        match reader.read_indices() {
            Some(ix) => self.indices.extend(ix.into_u32().map(|i| base + i)),
            None => self.indices.extend(base..base + ps.len() as u32),
        }
        self.positions.extend(ps);
        if self.colour.is_none() {
            let [r, g, b, _] = prim.material().pbr_metallic_roughness().base_color_factor();
            self.colour = Some([linear_to_srgb(r), linear_to_srgb(g), linear_to_srgb(b)]);
        }
    }

    /// Normalised to the unit box, then turned 180 degrees about Y: front +Z becomes -Z.
    fn into_unit_box(self) -> Triangles {
        let (lo, hi) = self.positions.iter().fold(
            (glam::Vec3::splat(f32::MAX), glam::Vec3::splat(f32::MIN)),
            |(lo, hi), p| (lo.min(*p), hi.max(*p)),
        );
        let extent = (hi - lo).max(glam::Vec3::splat(1e-6));
        let centre = (lo + hi) / 2.0;
        Triangles {
            positions: self
                .positions
                .iter()
                .map(|p| {
                    let q = (*p - centre) / extent;
                    [-q.x, q.y + 0.5, -q.z]
                })
                .collect(),
            normals: self
                .normals
                .iter()
                .map(|n| {
                    let n = (*n / extent).normalize_or_zero();
                    [-n.x, n.y, -n.z]
                })
                .collect(),
            indices: self.indices,
        }
    }
}

/// A linear colour channel (glTF's base colour) as an sRGB byte.
fn linear_to_srgb(c: f32) -> u8 {
    let s = if c <= 0.003_130_8 {
        c * 12.92
    } else {
        1.055 * c.powf(1.0 / 2.4) - 0.055
    };
    (s.clamp(0.0, 1.0) * 255.0).round() as u8
}

fn bytes_of(v: &[[f32; 3]]) -> Vec<u8> {
    v.iter()
        .flat_map(|p| p.iter().flat_map(|c| c.to_le_bytes()))
        .collect()
}

mod shell;
#[cfg(test)]
mod tests;
