//! Wall elevation sheets: every wall of the room unrolled and drawn flat, as a person standing in
//! the room and facing it sees it (its start vertex on the right), so heights can be read where
//! the top-down render cannot show them.
//!
//! Each wall is a strip as long as the wall and as high as the room ([`ROOM_HEIGHT_CM`], or the
//! tallest thing drawn plus [`HEADROOM_CM`]). On it: its doors (openings to
//! [`DOOR_HEIGHT_CM`]) and windows (glass from the sill to its top); the floor pieces that stand
//! within [`NEAR_WALL_CM`] of it, seen from the front (their extent along the wall, from the floor
//! to their top); what stands on those pieces, at its height; and the objects that hang on the
//! wall, at their elevation. Each piece is filled in its group's colour (as in the top-down
//! render), named, and, when it is off the floor, edged in white dashes. A height scale (every
//! 100 cm) runs up the strip's left, the walls at its two corners are named above its ends, and
//! a caption (`wall-0 (bottom) · 400 cm`) sits under it. All strips share one scale, in a grid.

use std::collections::HashMap;

use glam::DVec2;
use tiny_skia::{Color, Pixmap, Rect, Transform};

use super::text::{Anchor, TextPainter};
use super::{
    BACKGROUND, DOOR_LEAF, FLOOR, WHITE, WINDOW_GLASS, fill, object_colour, outline, paint,
    polygon, stroke,
};
use crate::error::{Error, Result};
use crate::geometry::Wall;
use crate::geometry3d::DOOR_HEIGHT_CM;
use crate::layout::{Layout, PlacedObject};

/// The height of the room drawn when nothing is taller, in cm.
pub const ROOM_HEIGHT_CM: f64 = 260.0;

/// Space left above the tallest thing drawn when it reaches past [`ROOM_HEIGHT_CM`], in cm.
pub const HEADROOM_CM: f64 = 20.0;

/// How close (cm) a floor piece's footprint must come to a wall to be drawn on its strip.
pub const NEAR_WALL_CM: f64 = 15.0;

/// The face of a wall.
pub const WALL_FACE: [u8; 3] = [236, 231, 222];

/// A door's opening: the dark of the room beyond.
pub const DOOR_OPENING: [u8; 3] = [78, 74, 72];

/// The outlines of walls and of furniture.
const EDGE: [u8; 3] = [20, 20, 24];
/// The faint lines across a wall at each labelled height.
const GUIDE: [u8; 3] = [212, 206, 196];
/// A window's frame.
const WINDOW_FRAME: [u8; 3] = [30, 70, 110];
/// Scales, end labels and captions.
const INK: [u8; 3] = [215, 215, 222];

/// Pixels left of a strip, for its height scale.
const MARGIN_LEFT: f64 = 50.0;
/// Pixels right of a strip.
const MARGIN_RIGHT: f64 = 18.0;
/// Pixels above a strip, for the names of the walls at its ends.
const MARGIN_TOP: f64 = 24.0;
/// The floor drawn under a strip, in pixels.
const FLOOR_PX: f64 = 7.0;
/// The caption under a strip, in pixels.
const CAPTION_PX: f64 = 28.0;
/// Between cells and around the sheet, in pixels.
const GAP_PX: f64 = 10.0;
/// The sheet's title line, in pixels.
const TITLE_PX: f64 = 30.0;
/// The most pixels per cm: a small room is not blown up past this.
const MAX_SCALE: f64 = 4.0;
/// The tallest a sheet is drawn, in pixels: a room of many walls gets smaller strips instead.
const MAX_SHEET_PX: f64 = 16384.0;

/// How to draw a sheet of walls.
#[derive(Debug, Clone, PartialEq)]
pub struct ElevationOptions {
    /// The sheet's width in pixels (the strips are scaled to fit it, at most 4 px per cm, and the
    /// sheet is at most 16 384 px tall).
    pub width_px: u32,
    /// Strips per row; 0 chooses by the number of walls: one for one or two, two up to 8, three
    /// up to 18, four beyond.
    pub columns: usize,
    /// Write the pieces' names on them.
    pub labels: bool,
    /// The title's first part; the layout's id when `None`.
    pub title: Option<String>,
}

impl Default for ElevationOptions {
    fn default() -> Self {
        ElevationOptions {
            width_px: 1280,
            columns: 0,
            labels: true,
            title: None,
        }
    }
}

/// Where one wall's strip lies on a sheet: the pixel of the wall's start vertex at floor level
/// (the strip's bottom-right corner, since the wall is seen from inside the room) and the scale.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Strip {
    /// The wall's index.
    pub wall: usize,
    /// The wall's length, in cm.
    pub length: f64,
    /// The pixel of the wall's start vertex at floor level.
    pub start_px: DVec2,
    /// Pixels per cm.
    pub scale: f64,
}

impl Strip {
    /// The pixel of the point `along` cm from the wall's start vertex, `z` cm above the floor.
    pub fn to_px(&self, along: f64, z: f64) -> DVec2 {
        DVec2::new(
            self.start_px.x - along * self.scale,
            self.start_px.y - z * self.scale,
        )
    }
}

/// The geometry of a sheet: its size, the height of the room it draws and each wall's strip.
#[derive(Debug, Clone, PartialEq)]
pub struct SheetGeometry {
    /// Width in pixels.
    pub width: u32,
    /// Height in pixels.
    pub height: u32,
    /// The height (cm) every strip shows, from the floor up.
    pub room_height: f64,
    /// One strip per wall, in wall order.
    pub strips: Vec<Strip>,
}

/// One thing seen on a wall: which object, where along the wall (cm from its start vertex) and
/// how high (cm above the floor).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Seen<'a> {
    /// The object.
    pub object: &'a PlacedObject,
    /// Its extent along the wall, `(from, to)` with `from <= to`, clipped to the wall.
    pub along: (f64, f64),
    /// Its bottom and top above the floor.
    pub z: (f64, f64),
    /// How far its footprint's centre is from the wall's line (cm): what is nearer the wall is
    /// drawn first, what stands further into the room in front of it.
    pub depth: f64,
}

/// The object at the bottom of `o`'s stack: what it stands on, what that stands on, and so on
/// (`o` itself when it stands on nothing; a broken chain stops where it breaks).
fn base<'a>(o: &'a PlacedObject, by_name: &HashMap<&str, &'a PlacedObject>) -> &'a PlacedObject {
    let mut at = o;
    // A chain longer than the layout has come back round on itself: stop there.
    for _ in 0..by_name.len() {
        match at.on.as_deref().and_then(|n| by_name.get(n)) {
            Some(next) => at = next,
            None => break,
        }
    }
    at
}

/// Where the footprint of `o` lies against `wall`: its extent along it (unclipped) and the
/// distances from the wall's line to its nearest corner and to its centre.
fn against(o: &PlacedObject, wall: &Wall) -> ((f64, f64), f64, f64) {
    let fp = o.footprint();
    let corners = fp.corners();
    let along = corners.iter().map(|&c| wall.along(c));
    let lo = along.clone().fold(f64::INFINITY, f64::min);
    let hi = along.fold(f64::NEG_INFINITY, f64::max);
    let offset = |p: DVec2| (p - wall.edge.start).dot(wall.inward_normal());
    let nearest = corners
        .iter()
        .map(|&c| offset(c))
        .fold(f64::INFINITY, f64::min);
    ((lo, hi), nearest, offset(fp.center))
}

/// Everything drawn on wall `index` of `layout`, nearest the wall first: the objects hanging on
/// it; the floor pieces (not floor coverings) whose footprint comes within [`NEAR_WALL_CM`] of
/// it, seen from the front; and whatever stands on either, at its height.
pub fn seen_on_wall(layout: &Layout, index: usize) -> Vec<Seen<'_>> {
    let Some(wall) = Wall::get(&layout.room, index) else {
        return Vec::new();
    };
    let by_name = layout.by_name();
    let length = wall.length();
    let mut seen: Vec<Seen<'_>> = layout
        .objects
        .iter()
        .filter(|o| !o.is_flat())
        .filter_map(|o| {
            let root = base(o, &by_name);
            let ((lo, hi), _, depth) = against(o, &wall);
            let shown = match root.wall {
                Some(w) => w == index,
                None if root.is_flat() => false,
                None => {
                    let ((rlo, rhi), nearest, _) = against(root, &wall);
                    (-NEAR_WALL_CM..=NEAR_WALL_CM).contains(&nearest)
                        && rlo < length - 1.0
                        && rhi > 1.0
                }
            };
            let along = (lo.max(0.0), hi.min(length));
            (shown && along.1 > along.0).then_some(Seen {
                object: o,
                along,
                z: (o.elevation, o.top()),
                depth,
            })
        })
        .collect();
    seen.sort_by(|a, b| a.depth.total_cmp(&b.depth).then(a.z.0.total_cmp(&b.z.0)));
    seen
}

/// The height every strip of `layout`'s sheet shows: [`ROOM_HEIGHT_CM`], or the top of the
/// tallest thing drawn (or of the highest window) plus [`HEADROOM_CM`].
fn room_height(layout: &Layout) -> f64 {
    let objects = layout.objects.iter().map(PlacedObject::top);
    let windows = layout.room.windows.iter().map(|w| w.sill + w.height);
    let tallest = objects.chain(windows).fold(0.0, f64::max);
    if tallest + HEADROOM_CM > ROOM_HEIGHT_CM {
        tallest + HEADROOM_CM
    } else {
        ROOM_HEIGHT_CM
    }
}

/// How many strips go in a row: `options.columns`, or by the number of walls: one for one or
/// two, two up to 8, three up to 18, four beyond (a room of many short walls).
fn columns(options: &ElevationOptions, walls: usize) -> usize {
    let chosen = match (options.columns, walls) {
        (0, 0..=2) => 1,
        (0, 3..=8) => 2,
        (0, 9..=18) => 3,
        (0, _) => 4,
        (n, _) => n,
    };
    chosen.clamp(1, walls.max(1))
}

/// Where each wall of `layout` goes on its sheet at `options`, and how large the sheet is.
pub fn sheet_geometry(layout: &Layout, options: &ElevationOptions) -> SheetGeometry {
    let walls = Wall::all(&layout.room);
    let columns = columns(options, walls.len());
    let rows = walls.len().div_ceil(columns);
    let longest = walls.iter().map(Wall::length).fold(1.0, f64::max);
    let width = f64::from(options.width_px.max(200));
    let cell_room = (width - GAP_PX * (columns as f64 + 1.0)) / columns as f64;
    let height_cm = room_height(layout);
    // As wide as the sheet allows, but no taller than MAX_SHEET_PX in all.
    let row_px = (MAX_SHEET_PX - TITLE_PX - GAP_PX) / rows as f64;
    let tallest = (row_px - GAP_PX - MARGIN_TOP - FLOOR_PX - CAPTION_PX) / height_cm;
    let scale = ((cell_room - MARGIN_LEFT - MARGIN_RIGHT) / longest)
        .min(tallest)
        .clamp(0.01, MAX_SCALE);
    let cell_w = MARGIN_LEFT + longest * scale + MARGIN_RIGHT;
    let cell_h = MARGIN_TOP + height_cm * scale + FLOOR_PX + CAPTION_PX;
    let strips = walls
        .iter()
        .enumerate()
        .map(|(i, w)| {
            let (col, row) = ((i % columns) as f64, (i / columns) as f64);
            let left = GAP_PX + col * (cell_w + GAP_PX) + MARGIN_LEFT;
            let floor =
                TITLE_PX + GAP_PX + row * (cell_h + GAP_PX) + MARGIN_TOP + height_cm * scale;
            Strip {
                wall: w.index(),
                length: w.length(),
                start_px: DVec2::new(left + w.length() * scale, floor),
                scale,
            }
        })
        .collect();
    SheetGeometry {
        width: (GAP_PX + columns as f64 * (cell_w + GAP_PX)).round() as u32,
        height: (TITLE_PX + GAP_PX + rows as f64 * (cell_h + GAP_PX)).round() as u32,
        room_height: height_cm,
        strips,
    }
}

/// Whether `layout` has anything off the floor (on another object or on a wall): the layouts
/// whose walls are worth a sheet.
pub fn has_objects_off_the_floor(layout: &Layout) -> bool {
    layout.objects.iter().any(|o| !o.on_floor())
}

/// Draws every wall of `layout` unrolled, as seen from inside the room, on one sheet.
pub fn render_walls(layout: &Layout, options: &ElevationOptions) -> Result<Pixmap> {
    let geometry = sheet_geometry(layout, options);
    let (w, h) = (geometry.width, geometry.height);
    let mut pixmap = Pixmap::new(w, h)
        .ok_or_else(|| Error::Render(format!("cannot allocate a {w} x {h} sheet of walls")))?;
    let [r, g, b] = BACKGROUND;
    pixmap.fill(Color::from_rgba8(r, g, b, 255));
    let text = TextPainter::new()?;
    let walls = Wall::all(&layout.room);
    for (strip, wall) in geometry.strips.iter().zip(&walls) {
        let painter = StripPainter {
            strip,
            wall,
            room_height: geometry.room_height,
            text: &text,
            layout,
            walls: walls.len(),
        };
        painter.draw(&mut pixmap, options.labels);
    }
    let title = options.title.as_deref().unwrap_or(&layout.id);
    let title = format!("{title}  ·  each wall as seen from inside the room  ·  heights in cm");
    text.draw(
        &mut pixmap,
        &title,
        Anchor::Left(GAP_PX as f32 + 4.0),
        (TITLE_PX / 2.0 + GAP_PX / 2.0) as f32,
        14.0,
        [235, 235, 240],
    );
    Ok(pixmap)
}

/// Draws the sheet of walls of `layout` and encodes it as PNG.
pub fn render_walls_png(layout: &Layout, options: &ElevationOptions) -> Result<Vec<u8>> {
    super::encode_png(&render_walls(layout, options)?)
}

/// Draws one wall's strip.
struct StripPainter<'a> {
    strip: &'a Strip,
    wall: &'a Wall,
    room_height: f64,
    text: &'a TextPainter,
    layout: &'a Layout,
    walls: usize,
}

impl StripPainter<'_> {
    fn draw(&self, pixmap: &mut Pixmap, labels: bool) {
        self.draw_wall(pixmap);
        self.draw_openings(pixmap);
        let seen = seen_on_wall(self.layout, self.strip.wall);
        for s in &seen {
            self.draw_piece(pixmap, s);
        }
        if labels {
            for s in &seen {
                self.draw_label(pixmap, s);
            }
        }
        self.draw_scale(pixmap);
        self.draw_ends(pixmap);
        self.draw_caption(pixmap);
    }

    /// The closed path of the box from `(a0, z0)` to `(a1, z1)` (cm along, cm up).
    fn rect(&self, (a0, a1): (f64, f64), (z0, z1): (f64, f64)) -> Option<tiny_skia::Path> {
        let s = self.strip;
        polygon(&[
            s.to_px(a0, z0),
            s.to_px(a1, z0),
            s.to_px(a1, z1),
            s.to_px(a0, z1),
        ])
    }

    /// The wall's face, faint lines at every 100 cm, its outline and the floor under it.
    fn draw_wall(&self, pixmap: &mut Pixmap) {
        let s = self.strip;
        let full = (0.0, s.length);
        if let Some(face) = self.rect(full, (0.0, self.room_height)) {
            fill(pixmap, &face, WALL_FACE, 255);
        }
        let mut z = 100.0;
        while z < self.room_height {
            if let Some(line) = polygon(&[s.to_px(0.0, z), s.to_px(s.length, z)]) {
                let mut st = stroke(1.0);
                st.dash = tiny_skia::StrokeDash::new(vec![6.0, 5.0], 0.0);
                outline(pixmap, &line, GUIDE, &st);
            }
            z += 100.0;
        }
        let (l, r) = (s.to_px(s.length, 0.0), s.to_px(0.0, 0.0));
        if let Some(floor) =
            Rect::from_ltrb(l.x as f32, l.y as f32, r.x as f32, (r.y + FLOOR_PX) as f32)
        {
            pixmap.fill_rect(floor, &paint(FLOOR, 255), Transform::identity(), None);
        }
        if let Some(face) = self.rect(full, (0.0, self.room_height)) {
            outline(pixmap, &face, EDGE, &stroke(1.5));
        }
    }

    /// Doors as dark openings to their top, windows as glass from sill to top with a frame and a
    /// mullion; each named in small letters.
    fn draw_openings(&self, pixmap: &mut Pixmap) {
        let room = &self.layout.room;
        let index = self.strip.wall;
        let door_top = DOOR_HEIGHT_CM.min(self.room_height);
        for d in room.doors.iter().filter(|d| d.wall == index) {
            let along = (d.at - d.width / 2.0, d.at + d.width / 2.0);
            if let Some(hole) = self.rect(along, (0.0, door_top)) {
                fill(pixmap, &hole, DOOR_OPENING, 255);
                outline(pixmap, &hole, DOOR_LEAF, &stroke(2.0));
            }
            self.small_label(pixmap, "door", along, door_top);
        }
        for w in room.windows.iter().filter(|w| w.wall == index) {
            let along = (w.at - w.width / 2.0, w.at + w.width / 2.0);
            let z = (w.sill, (w.sill + w.height).min(self.room_height));
            if let Some(glass) = self.rect(along, z) {
                fill(pixmap, &glass, WINDOW_GLASS, 255);
                outline(pixmap, &glass, WINDOW_FRAME, &stroke(2.0));
            }
            let s = self.strip;
            if let Some(mullion) = polygon(&[s.to_px(w.at, z.0), s.to_px(w.at, z.1)]) {
                outline(pixmap, &mullion, WINDOW_FRAME, &stroke(1.5));
            }
            // The sill: a thicker line under the glass.
            if let Some(sill) = polygon(&[s.to_px(along.0, z.0), s.to_px(along.1, z.0)]) {
                outline(pixmap, &sill, WINDOW_FRAME, &stroke(3.5));
            }
            self.small_label(pixmap, "window", along, z.1);
        }
    }

    /// A small word just under the top edge `top` of the opening spanning `along` (left out
    /// when the opening is too narrow for it).
    fn small_label(&self, pixmap: &mut Pixmap, word: &str, along: (f64, f64), top: f64) {
        let s = self.strip;
        let width = (along.1 - along.0) * s.scale;
        if self.text.width(word, 10.0) > width as f32 - 4.0 {
            return;
        }
        let at = s.to_px((along.0 + along.1) / 2.0, top);
        self.text.draw(
            pixmap,
            word,
            Anchor::Centre(at.x as f32),
            (at.y + 10.0) as f32,
            10.0,
            WHITE,
        );
    }

    /// One piece: its box in its group's colour, a dark edge, and a white dashed one when it is
    /// off the floor.
    fn draw_piece(&self, pixmap: &mut Pixmap, seen: &Seen<'_>) {
        let Some(body) = self.rect(seen.along, seen.z) else {
            return;
        };
        fill(pixmap, &body, object_colour(self.layout, seen.object), 255);
        outline(pixmap, &body, EDGE, &stroke(1.5));
        if !seen.object.on_floor() {
            let mut s = stroke(2.0);
            s.dash = tiny_skia::StrokeDash::new(vec![4.0, 3.0], 0.0);
            outline(pixmap, &body, WHITE, &s);
        }
    }

    /// The piece's name on it (above it when it is too low to hold a line), and for a piece off
    /// the floor its bottom's height under the name when there is room.
    fn draw_label(&self, pixmap: &mut Pixmap, seen: &Seen<'_>) {
        let s = self.strip;
        let o = seen.object;
        let width = ((seen.along.1 - seen.along.0) * s.scale) as f32;
        let height = ((seen.z.1 - seen.z.0) * s.scale) as f32;
        let size = self.text.fit_size(&o.name, width * 0.92, 9.0, 15.0);
        let centre = s.to_px(
            (seen.along.0 + seen.along.1) / 2.0,
            (seen.z.0 + seen.z.1) / 2.0,
        );
        let note_size = 10.0f32;
        // Off the floor, its height under its name, when the piece is wide enough for it.
        let note = Some(format!("at {} cm", round_cm(o.elevation)))
            .filter(|n| !o.on_floor() && self.text.width(n, note_size) <= width);
        let two_lines = note.is_some() && height >= size + note_size + 6.0;
        let y = if height < size + 2.0 {
            // Too low for a line: just above the piece.
            (s.to_px(0.0, seen.z.1).y - f64::from(size) * 0.7) as f32
        } else if two_lines {
            centre.y as f32 - note_size * 0.6
        } else {
            centre.y as f32
        };
        self.text.draw(
            pixmap,
            &o.name,
            Anchor::Centre(centre.x as f32),
            y,
            size,
            WHITE,
        );
        if let (true, Some(note)) = (two_lines, note) {
            self.text.draw(
                pixmap,
                &note,
                Anchor::Centre(centre.x as f32),
                y + size * 0.5 + note_size * 0.7,
                note_size,
                WHITE,
            );
        }
    }

    /// Ticks up the strip's left every 50 cm, labelled every 100 cm, with `cm` on top.
    fn draw_scale(&self, pixmap: &mut Pixmap) {
        let s = self.strip;
        let x = s.to_px(s.length, 0.0).x - 6.0;
        let axis = [
            DVec2::new(x, s.start_px.y),
            DVec2::new(x, s.to_px(0.0, self.room_height).y),
        ];
        if let Some(line) = polygon(&axis) {
            outline(pixmap, &line, INK, &stroke(1.0));
        }
        let mut z = 0.0;
        while z <= self.room_height + 1e-9 {
            let y = s.to_px(0.0, z).y;
            let major = (z % 100.0).abs() < 1e-9;
            let tick = if major { 7.0 } else { 4.0 };
            if let Some(t) = polygon(&[DVec2::new(x - tick, y), DVec2::new(x, y)]) {
                outline(pixmap, &t, INK, &stroke(1.0));
            }
            if major && s.scale * 100.0 >= 14.0 {
                let label = format!("{z}");
                self.text.draw(
                    pixmap,
                    &label,
                    Anchor::Right((x - 10.0) as f32),
                    y as f32,
                    11.0,
                    INK,
                );
            }
            z += 50.0;
        }
        let top = s.to_px(0.0, self.room_height).y;
        self.text.draw(
            pixmap,
            "cm",
            Anchor::Right((x - 10.0) as f32),
            (top - 12.0) as f32,
            10.0,
            INK,
        );
    }

    /// The walls met at each end, above the strip: the next wall on the left, the one before on
    /// the right (seen from inside, a wall runs from right to left).
    fn draw_ends(&self, pixmap: &mut Pixmap) {
        if self.walls < 2 {
            return;
        }
        let s = self.strip;
        let next = (s.wall + 1) % self.walls;
        let before = (s.wall + self.walls - 1) % self.walls;
        let y = (s.to_px(0.0, self.room_height).y - MARGIN_TOP / 2.0) as f32;
        let left = s.to_px(s.length, 0.0).x as f32;
        let right = s.start_px.x as f32;
        self.text.draw(
            pixmap,
            &format!("← wall-{next}"),
            Anchor::Left(left),
            y,
            11.0,
            INK,
        );
        self.text.draw(
            pixmap,
            &format!("wall-{before} →"),
            Anchor::Right(right),
            y,
            11.0,
            INK,
        );
    }

    /// `wall-0 (bottom) · 400 cm` under the strip (a polygon's walls have no names).
    fn draw_caption(&self, pixmap: &mut Pixmap) {
        let s = self.strip;
        let name = match self.layout.room.is_rectangle() {
            true => format!("wall-{} ({})", s.wall, self.wall.name()),
            false => format!("wall-{}", s.wall),
        };
        let caption = format!("{name}  ·  {} cm", round_cm(s.length));
        let centre = s.to_px(s.length / 2.0, 0.0);
        let y = centre.y + FLOOR_PX + CAPTION_PX / 2.0;
        let room = (s.length * s.scale + MARGIN_LEFT) as f32;
        let size = self.text.fit_size(&caption, room, 9.0, 14.0);
        self.text.draw(
            pixmap,
            &caption,
            Anchor::Centre(centre.x as f32),
            y as f32,
            size,
            [235, 235, 240],
        );
    }
}

/// A length in cm as people write it: whole numbers without decimals, others to one place.
fn round_cm(v: f64) -> String {
    let r = (v * 10.0).round() / 10.0;
    if r.fract() == 0.0 {
        format!("{r:.0}")
    } else {
        format!("{r:.1}")
    }
}

#[cfg(test)]
mod tests;
