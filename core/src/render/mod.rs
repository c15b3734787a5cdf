//! Top-down pictures of a layout, for people and for vision models alike.
//!
//! Brown floor, white walls, every object a filled rectangle in its group's colour with its name
//! written on it and a white arrowhead on its front edge, axis ticks in centimetres. Floor
//! coverings are drawn translucent, under the furniture. 1024 px on the long side by default.
//! A room with an outline or openings also shows the part of its bounding box that is not floor
//! (hatched), door gaps with their leaves and swing arcs, windows as double lines in the wall and,
//! unless it is a rectangle, each wall's index in a badge on the wall.
//!
//! Heights are drawn on a second kind of picture, the wall elevation sheet ([`render_walls`]):
//! each wall unrolled as seen from inside the room, with its openings, the pieces against it and
//! what hangs on it or stands on them, at their heights.

mod elevation;
mod room;
mod sheet;
mod text;

pub use elevation::{
    DOOR_OPENING, ElevationOptions, HEADROOM_CM, NEAR_WALL_CM, ROOM_HEIGHT_CM, Seen, SheetGeometry,
    Strip, WALL_FACE, has_objects_off_the_floor, render_walls, render_walls_png, seen_on_wall,
    sheet_geometry,
};
pub use room::{DOOR_LEAF, NOT_FLOOR, WINDOW_GLASS};
pub use sheet::contact_sheet;

use glam::DVec2;
use tiny_skia::{Color, FillRule, Paint, PathBuilder, Pixmap, Rect, Stroke, Transform};

use crate::error::{Error, Result};
use crate::geometry::Footprint;
use crate::layout::{Layout, PlacedObject};

pub use text::{Anchor, TextPainter};

/// Background around the room.
pub const BACKGROUND: [u8; 3] = [40, 42, 48];
/// The floor.
pub const FLOOR: [u8; 3] = [150, 105, 70];
/// The walls.
pub const WALL: [u8; 3] = [255, 255, 255];
/// Objects that belong to no group.
pub const UNGROUPED: [u8; 3] = [170, 170, 170];
/// Group colours, in group order (cycled); chosen to stand apart from the floor and each other.
pub const GROUP_COLOURS: [[u8; 3]; 10] = [
    [66, 133, 244],
    [52, 168, 83],
    [234, 67, 53],
    [251, 188, 5],
    [171, 71, 188],
    [0, 172, 193],
    [255, 112, 67],
    [158, 157, 36],
    [92, 107, 192],
    [240, 98, 146],
];

/// How to draw.
#[derive(Debug, Clone, PartialEq)]
pub struct RenderOptions {
    /// Pixels on the image's long side.
    pub long_side_px: u32,
    /// Draw object names.
    pub labels: bool,
    /// Draw axis ticks and the title.
    pub axes: bool,
    /// The title's first part; the layout's id when `None`.
    pub title: Option<String>,
}

impl Default for RenderOptions {
    fn default() -> Self {
        RenderOptions {
            long_side_px: 1024,
            labels: true,
            axes: true,
            title: None,
        }
    }
}

/// Maps floor coordinates (cm, y up) to image pixels (y down).
#[derive(Debug, Clone, Copy)]
pub struct View {
    /// Pixels per cm.
    pub scale: f64,
    /// Pixel position of the room's bottom-left corner.
    pub origin: DVec2,
}

impl View {
    /// The pixel where floor point `p` lands.
    pub fn to_px(&self, p: DVec2) -> DVec2 {
        DVec2::new(
            self.origin.x + p.x * self.scale,
            self.origin.y - p.y * self.scale,
        )
    }
}

const MARGIN_LEFT: f64 = 64.0;
const MARGIN_RIGHT: f64 = 24.0;
const MARGIN_TOP: f64 = 40.0;
const MARGIN_BOTTOM: f64 = 52.0;

/// The image size and floor-to-pixel mapping for `layout` at `long_side_px`.
pub fn view_for(layout: &Layout, long_side_px: u32) -> (u32, u32, View) {
    let (w, d) = (layout.room.width, layout.room.depth);
    let long = f64::from(long_side_px.max(200));
    let scale = if w >= d {
        (long - MARGIN_LEFT - MARGIN_RIGHT) / w
    } else {
        (long - MARGIN_TOP - MARGIN_BOTTOM) / d
    };
    let width = (w * scale + MARGIN_LEFT + MARGIN_RIGHT).round() as u32;
    let height = (d * scale + MARGIN_TOP + MARGIN_BOTTOM).round() as u32;
    let origin = DVec2::new(MARGIN_LEFT, MARGIN_TOP + d * scale);
    (width, height, View { scale, origin })
}

/// The fill colour of `object`: its group's colour, or [`UNGROUPED`].
pub fn object_colour(layout: &Layout, object: &PlacedObject) -> [u8; 3] {
    match layout.plan.group_of(&object.name) {
        Some(g) => GROUP_COLOURS[g % GROUP_COLOURS.len()],
        None => UNGROUPED,
    }
}

fn paint(rgb: [u8; 3], alpha: u8) -> Paint<'static> {
    let mut p = Paint::default();
    p.set_color(Color::from_rgba8(rgb[0], rgb[1], rgb[2], alpha));
    p.anti_alias = true;
    p
}

fn polygon(points: &[DVec2]) -> Option<tiny_skia::Path> {
    let mut pb = PathBuilder::new();
    let (first, rest) = points.split_first()?;
    pb.move_to(first.x as f32, first.y as f32);
    for p in rest {
        pb.line_to(p.x as f32, p.y as f32);
    }
    pb.close();
    pb.finish()
}

/// Draws `layout` into a new pixmap.
pub fn render(layout: &Layout, options: &RenderOptions) -> Result<Pixmap> {
    let (width, height, view) = view_for(layout, options.long_side_px);
    let mut pixmap = Pixmap::new(width, height)
        .ok_or_else(|| Error::Render(format!("cannot allocate a {width} x {height} image")))?;
    pixmap.fill(Color::from_rgba8(
        BACKGROUND[0],
        BACKGROUND[1],
        BACKGROUND[2],
        255,
    ));
    let text = TextPainter::new()?;

    // A plain rectangle is drawn as it always was; any other room by `room`.
    let plain = layout.room.is_rectangle() && !layout.room.has_openings();
    let room_px = Rect::from_ltrb(
        view.origin.x as f32,
        (view.origin.y - layout.room.depth * view.scale) as f32,
        (view.origin.x + layout.room.width * view.scale) as f32,
        view.origin.y as f32,
    )
    .ok_or_else(|| Error::Render("the room has no area".into()))?;
    if plain {
        pixmap.fill_rect(room_px, &paint(FLOOR, 255), Transform::identity(), None);
    } else {
        room::draw_floor(&mut pixmap, &view, &layout.room)?;
    }

    // Floor coverings first, then furniture from the floor up (what stands on another object or
    // hangs on a wall after what is under it); each level in layout order.
    let (flat, mut solid): (Vec<&PlacedObject>, Vec<&PlacedObject>) =
        layout.objects.iter().partition(|o| o.is_flat());
    solid.sort_by(|a, b| a.elevation.total_cmp(&b.elevation));
    for o in flat.iter().chain(&solid) {
        draw_object(&mut pixmap, &view, layout, o);
    }

    // Walls on top, so objects poking through them show it.
    let wall_px = (view.scale * 6.0).clamp(3.0, 8.0) as f32;
    if plain {
        let walls = PathBuilder::from_rect(
            room_px
                .outset(wall_px / 2.0, wall_px / 2.0)
                .unwrap_or(room_px),
        );
        outline(&mut pixmap, &walls, WALL, &stroke(wall_px));
    } else {
        room::draw_walls(&mut pixmap, &view, &layout.room, wall_px)?;
    }

    if options.labels {
        // Names go at the objects' centres; one off the floor whose name would fall on a name
        // already written (a lamp's on its nightstand's) moves a line or more away from it.
        let mut written: Vec<LabelBox> = Vec::new();
        for o in flat.iter().chain(&solid) {
            let c = view.to_px(DVec2::new(o.position[0], o.position[1]));
            let fp = o.footprint();
            let box_w = (fp.aabb_half().x * 2.0 * view.scale) as f32;
            let size = text.fit_size(&o.name, box_w * 0.92, 10.0, 17.0);
            let mut label =
                LabelBox::centred(c.x as f32, c.y as f32, text.width(&o.name, size), size);
            if !o.on_floor() {
                label = label.clear_of(&written);
            }
            written.push(label);
            text.draw(
                &mut pixmap,
                &o.name,
                Anchor::Centre(c.x as f32),
                label.centre_y(),
                size,
                WHITE,
            );
        }
    }
    if !layout.room.is_rectangle() {
        room::draw_wall_labels(&mut pixmap, &view, &layout.room, &text, wall_px);
    }
    if options.axes {
        let title = options.title.as_deref().unwrap_or(&layout.id);
        draw_axes(&mut pixmap, &view, layout, &text, wall_px, title);
    }
    Ok(pixmap)
}

/// Where a name is written: its box in pixels.
#[derive(Debug, Clone, Copy, PartialEq)]
struct LabelBox {
    left: f32,
    top: f32,
    right: f32,
    bottom: f32,
}

impl LabelBox {
    /// The box of a line `width` wide and `size` high centred on `(x, y)`.
    fn centred(x: f32, y: f32, width: f32, size: f32) -> LabelBox {
        LabelBox {
            left: x - width / 2.0,
            top: y - size / 2.0,
            right: x + width / 2.0,
            bottom: y + size / 2.0,
        }
    }

    fn centre_y(&self) -> f32 {
        (self.top + self.bottom) / 2.0
    }

    fn meets(&self, other: &LabelBox) -> bool {
        self.left < other.right
            && other.left < self.right
            && self.top < other.bottom
            && other.top < self.bottom
    }

    /// This box, or the nearest one a whole line below or above it (below first) that meets
    /// none of `written`; itself when none of the nearest few is clear.
    fn clear_of(self, written: &[LabelBox]) -> LabelBox {
        let line = (self.bottom - self.top) + 3.0;
        [0.0, 1.0, -1.0, 2.0, -2.0, 3.0, -3.0]
            .into_iter()
            .map(|k| LabelBox {
                top: self.top + k * line,
                bottom: self.bottom + k * line,
                ..self
            })
            .find(|b| !written.iter().any(|w| b.meets(w)))
            .unwrap_or(self)
    }
}

/// Draws `layout` and encodes it as PNG.
pub fn render_png(layout: &Layout, options: &RenderOptions) -> Result<Vec<u8>> {
    encode_png(&render(layout, options)?)
}

/// Encodes a pixmap as an RGBA PNG with fast compression (our flat-colour pictures compress well
/// anyway; the default level triples the time).
pub fn encode_png(pixmap: &Pixmap) -> Result<Vec<u8>> {
    let err = |e: png::EncodingError| Error::Render(format!("PNG encoding failed: {e}"));
    let rgba: Vec<u8> = pixmap
        .pixels()
        .iter()
        .flat_map(|p| {
            let c = p.demultiply();
            [c.red(), c.green(), c.blue(), c.alpha()]
        })
        .collect();
    let mut out = Vec::new();
    let mut encoder = png::Encoder::new(&mut out, pixmap.width(), pixmap.height());
    encoder.set_color(png::ColorType::Rgba);
    encoder.set_depth(png::BitDepth::Eight);
    encoder.set_compression(png::Compression::Fast);
    let mut writer = encoder.write_header().map_err(err)?;
    writer.write_image_data(&rgba).map_err(err)?;
    writer.finish().map_err(err)?;
    Ok(out)
}

/// Draws one object: its body in its group's colour and, for solid objects, a front marker.
fn draw_object(pixmap: &mut Pixmap, view: &View, layout: &Layout, o: &PlacedObject) {
    let fp = o.footprint();
    let corners = fp.corners().map(|c| view.to_px(c));
    let Some(path) = polygon(&corners) else {
        return;
    };
    draw_body(pixmap, &path, object_colour(layout, o), o.is_flat());
    if !o.is_flat() {
        draw_front_marker(pixmap, view, &fp);
    }
    if !o.on_floor() {
        // Off the floor (on another object or on a wall): a white dashed edge says so.
        let mut s = stroke(2.0);
        s.dash = tiny_skia::StrokeDash::new(vec![4.0, 3.0], 0.0);
        outline(pixmap, &path, WHITE, &s);
    }
}

/// Fills an object's outline `path` with `colour` and strokes it: floor coverings translucent
/// with a light dashed edge, furniture opaque with a dark solid one.
fn draw_body(pixmap: &mut Pixmap, path: &tiny_skia::Path, colour: [u8; 3], flat: bool) {
    let (fill_alpha, edge) = if flat {
        (110, [230, 230, 230])
    } else {
        (255, DARK_EDGE)
    };
    fill(pixmap, path, colour, fill_alpha);
    let mut s = stroke(1.5);
    if flat {
        s.dash = tiny_skia::StrokeDash::new(vec![6.0, 4.0], 0.0);
    }
    outline(pixmap, path, edge, &s);
}

/// Marks where the object at `fp` faces: a thick white front edge and a white arrowhead on it,
/// pointing out, sized to the object.
fn draw_front_marker(pixmap: &mut Pixmap, view: &View, fp: &Footprint) {
    let (fl, fr) = fp.front_edge();
    if let Some(edge) = polygon(&[view.to_px(fl), view.to_px(fr)]) {
        outline(pixmap, &edge, WHITE, &stroke(3.0));
    }
    let depth_px = fp.half.y * 2.0 * view.scale;
    let width_px = fp.half.x * 2.0 * view.scale;
    let len = (depth_px * 0.35).min(width_px * 0.5).clamp(4.0, 22.0);
    let tip = view.to_px(fp.front_center());
    let inward = view.to_px(fp.front_center() - fp.front) - tip;
    let inward = inward.normalize_or_zero();
    let side = DVec2::new(-inward.y, inward.x);
    // A narrow head (its point sharper than its back corners), so it reads as pointing out
    // of the front edge at any angle, not along it.
    let base = tip + inward * len * 1.2;
    let arrow = [tip, base + side * len * 0.45, base - side * len * 0.45];
    if let Some(p) = polygon(&arrow) {
        fill(pixmap, &p, WHITE, 255);
        outline(pixmap, &p, DARK_EDGE, &stroke(1.0));
    }
}

/// White: front markers and names.
const WHITE: [u8; 3] = [255, 255, 255];

/// The dark edge of furniture and of front arrowheads.
const DARK_EDGE: [u8; 3] = [20, 20, 24];

/// A solid stroke `width` px wide.
fn stroke(width: f32) -> Stroke {
    Stroke {
        width,
        ..Stroke::default()
    }
}

/// Fills `path` with `rgb` at `alpha`.
fn fill(pixmap: &mut Pixmap, path: &tiny_skia::Path, rgb: [u8; 3], alpha: u8) {
    pixmap.fill_path(
        path,
        &paint(rgb, alpha),
        FillRule::Winding,
        Transform::identity(),
        None,
    );
}

/// Strokes `path` in opaque `rgb`.
fn outline(pixmap: &mut Pixmap, path: &tiny_skia::Path, rgb: [u8; 3], s: &Stroke) {
    pixmap.stroke_path(path, &paint(rgb, 255), s, Transform::identity(), None);
}

/// A tick spacing (cm) that leaves at least `min_px` between labels.
fn tick_step(scale: f64, min_px: f64) -> f64 {
    const STEPS: [f64; 10] = [
        10.0, 20.0, 25.0, 50.0, 100.0, 200.0, 250.0, 500.0, 1000.0, 2000.0,
    ];
    STEPS
        .into_iter()
        .find(|s| s * scale >= min_px)
        .unwrap_or(5000.0)
}

/// The grey of the axes, their ticks and labels.
const AXIS_GREY: [u8; 3] = [200, 200, 205];

/// The cm ticks and labels along the bottom and left edges, the axis name and the title line.
fn draw_axes(
    pixmap: &mut Pixmap,
    view: &View,
    layout: &Layout,
    text: &TextPainter,
    wall_px: f32,
    title: &str,
) {
    let off = f64::from(wall_px) + 2.0;
    draw_ticks(pixmap, view, text, layout.room.width, off, Axis::X);
    draw_ticks(pixmap, view, text, layout.room.depth, off, Axis::Y);
    let bottom = view.origin.y + off + 36.0;
    let centre_x = view.origin.x + layout.room.width * view.scale / 2.0;
    text.draw(
        pixmap,
        "x (cm)",
        Anchor::Centre(centre_x as f32),
        bottom as f32,
        12.0,
        AXIS_GREY,
    );
    let size = if layout.room.is_rectangle() {
        format!("{} × {} cm", layout.room.width, layout.room.depth)
    } else {
        format!(
            "{} walls in {} × {} cm",
            layout.room.walls().len(),
            layout.room.width,
            layout.room.depth
        )
    };
    let title = format!("{title}  ·  {size}  ·  y (cm) up, x (cm) right; arrowheads mark fronts");
    text.draw(
        pixmap,
        &title,
        Anchor::Left(MARGIN_LEFT as f32 - 40.0),
        18.0,
        14.0,
        [235, 235, 240],
    );
}

/// Which edge of the picture a scale runs along.
#[derive(Clone, Copy, PartialEq)]
enum Axis {
    /// Along the bottom, labels under the ticks.
    X,
    /// Up the left side, labels left of the ticks.
    Y,
}

/// Ticks and their cm labels from 0 to `length` along one axis, `off` pixels outside the room.
fn draw_ticks(
    pixmap: &mut Pixmap,
    view: &View,
    text: &TextPainter,
    length: f64,
    off: f64,
    axis: Axis,
) {
    let step = tick_step(view.scale, if axis == Axis::X { 56.0 } else { 28.0 });
    let mut at = 0.0;
    while at <= length + 1e-9 {
        let (p, out, anchor, label_y) = match axis {
            Axis::X => {
                let p = view.to_px(DVec2::new(at, 0.0));
                (
                    p,
                    DVec2::new(0.0, 1.0),
                    Anchor::Centre(p.x as f32),
                    p.y + off + 16.0,
                )
            }
            Axis::Y => {
                let p = view.to_px(DVec2::new(0.0, at));
                let anchor = Anchor::Right((p.x - off - 9.0) as f32);
                (p, DVec2::new(-1.0, 0.0), anchor, p.y)
            }
        };
        if let Some(line) = polygon(&[p + out * off, p + out * (off + 6.0)]) {
            outline(pixmap, &line, AXIS_GREY, &stroke(1.0));
        }
        text.draw(
            pixmap,
            &format!("{at}"),
            anchor,
            label_y as f32,
            12.0,
            AXIS_GREY,
        );
        at += step;
    }
}

#[cfg(test)]
mod tests;

#[cfg(test)]
mod label_tests {
    use super::LabelBox;

    #[test]
    fn a_name_that_falls_on_another_moves_a_line_away_and_a_clear_one_stays() {
        let nightstand = LabelBox::centred(100.0, 100.0, 80.0, 12.0);
        let lamp = LabelBox::centred(100.0, 100.0, 40.0, 12.0);
        let moved = lamp.clear_of(&[nightstand]);
        assert_eq!(
            moved.centre_y(),
            115.0,
            "one line (12 px and 3 between) below"
        );
        assert!(!moved.meets(&nightstand));
        // With the line below taken too, it goes above.
        let below = LabelBox::centred(100.0, 115.0, 80.0, 12.0);
        assert_eq!(lamp.clear_of(&[nightstand, below]).centre_y(), 85.0);
        let apart = LabelBox::centred(300.0, 100.0, 40.0, 12.0);
        assert_eq!(apart.clear_of(&[nightstand]), apart);
    }
}
