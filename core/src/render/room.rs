//! The room itself when it is more than a plain rectangle: its floor (the outline filled, the rest
//! of its bounding box hatched as "not floor"), its walls outside the outline, door openings as
//! gaps with the leaf and, for doors that swing in, the arc it sweeps, windows as a double line in
//! the wall, and each wall's index (people and models name walls by index).

use glam::DVec2;
use tiny_skia::{FillRule, LineJoin, Mask, Path, PathBuilder, Pixmap, Rect, Stroke, Transform};

use super::text::{Anchor, TextPainter};
use super::{BACKGROUND, FLOOR, View, WALL, fill, outline, paint, polygon, stroke};
use crate::error::{Error, Result};
use crate::room::{Door, Edge, Room};

/// The part of the room's bounding box that is not floor.
pub const NOT_FLOOR: [u8; 3] = [66, 62, 60];
/// The hatching over [`NOT_FLOOR`].
const HATCH: [u8; 3] = [92, 86, 82];
/// A door's leaf and its swing arc.
pub const DOOR_LEAF: [u8; 3] = [250, 250, 250];
/// The glass of a window, between its two lines.
pub const WINDOW_GLASS: [u8; 3] = [160, 205, 235];
/// The two lines of a window.
const WINDOW_LINE: [u8; 3] = [30, 70, 110];
/// The digits of wall labels.
const LABEL_TEXT: [u8; 3] = [255, 214, 90];

/// The outline in pixels, as a closed path.
fn outline_path(view: &View, room: &Room) -> Result<Path> {
    let points: Vec<DVec2> = room.outline().into_iter().map(|p| view.to_px(p)).collect();
    polygon(&points).ok_or_else(|| Error::Render("the room's outline has no area".into()))
}

/// Fills the floor: the bounding box hatched as not floor, then the outline in [`FLOOR`].
pub(super) fn draw_floor(pixmap: &mut Pixmap, view: &View, room: &Room) -> Result<()> {
    let top_left = view.to_px(DVec2::new(0.0, room.depth));
    let bottom_right = view.to_px(DVec2::new(room.width, 0.0));
    let bbox = Rect::from_ltrb(
        top_left.x as f32,
        top_left.y as f32,
        bottom_right.x as f32,
        bottom_right.y as f32,
    )
    .ok_or_else(|| Error::Render("the room has no area".into()))?;
    pixmap.fill_rect(bbox, &paint(NOT_FLOOR, 255), Transform::identity(), None);
    let mut clip = Mask::new(pixmap.width(), pixmap.height())
        .ok_or_else(|| Error::Render("cannot allocate a mask".into()))?;
    clip.fill_path(
        &PathBuilder::from_rect(bbox),
        FillRule::Winding,
        false,
        Transform::identity(),
    );
    let mut hatch = PathBuilder::new();
    let (w, h) = (bbox.width(), bbox.height());
    let mut x = -h;
    while x < w {
        hatch.move_to(bbox.left() + x, bbox.bottom());
        hatch.line_to(bbox.left() + x + h, bbox.top());
        x += 10.0;
    }
    if let Some(lines) = hatch.finish() {
        pixmap.stroke_path(
            &lines,
            &paint(HATCH, 255),
            &stroke(1.5),
            Transform::identity(),
            Some(&clip),
        );
    }
    fill(pixmap, &outline_path(view, room)?, FLOOR, 255);
    Ok(())
}

/// Draws the walls `wall_px` thick just outside the outline, then each door's gap and leaf and
/// each window's double line.
pub(super) fn draw_walls(
    pixmap: &mut Pixmap,
    view: &View,
    room: &Room,
    wall_px: f32,
) -> Result<()> {
    let floor = outline_path(view, room)?;
    let mut outside = Mask::new(pixmap.width(), pixmap.height())
        .ok_or_else(|| Error::Render("cannot allocate a mask".into()))?;
    outside.fill_path(&floor, FillRule::Winding, true, Transform::identity());
    outside.invert();
    // A stroke twice as wide as the wall, centred on the outline, keeps its outer half.
    let walls = Stroke {
        width: wall_px * 2.0,
        line_join: LineJoin::Miter,
        ..Stroke::default()
    };
    pixmap.stroke_path(
        &floor,
        &paint(WALL, 255),
        &walls,
        Transform::identity(),
        Some(&outside),
    );
    let edges = room.walls();
    for door in &room.doors {
        if let Some(edge) = edges.get(door.wall) {
            draw_door(pixmap, view, room, edge, door, wall_px, &outside);
        }
    }
    for window in &room.windows {
        if let Some(edge) = edges.get(window.wall) {
            let (a, b) = (
                edge.point(window.at - window.width / 2.0),
                edge.point(window.at + window.width / 2.0),
            );
            draw_window(pixmap, view, edge, (a, b), wall_px, &outside);
        }
    }
    Ok(())
}

/// The four pixel corners of the stretch of wall from `a` to `b` (floor points on `edge`),
/// from the outline out to `depth_px` beyond it.
fn wall_band(view: &View, edge: &Edge, (a, b): (DVec2, DVec2), depth_px: f64) -> [DVec2; 4] {
    let out = outward_px(view, edge) * depth_px;
    let (a, b) = (view.to_px(a), view.to_px(b));
    [a, b, b + out, a + out]
}

/// The unit vector, in pixels, pointing from `edge` away from the room.
fn outward_px(view: &View, edge: &Edge) -> DVec2 {
    (view.to_px(edge.start) - view.to_px(edge.start + edge.inward_normal())).normalize_or_zero()
}

/// A door: the wall cut away over its width (floor shows through) and its leaf: open at a right
/// angle with the quarter circle it sweeps when it swings in, else a line across the opening.
fn draw_door(
    pixmap: &mut Pixmap,
    view: &View,
    room: &Room,
    edge: &Edge,
    door: &Door,
    wall_px: f32,
    outside: &Mask,
) {
    let ends = (
        edge.point(door.at - door.width / 2.0),
        edge.point(door.at + door.width / 2.0),
    );
    let gap = wall_band(view, edge, ends, f64::from(wall_px) + 0.5);
    if let Some(path) = polygon(&gap) {
        pixmap.fill_path(
            &path,
            &paint(FLOOR, 255),
            FillRule::Winding,
            Transform::identity(),
            Some(outside),
        );
    }
    let leaf = stroke(3.0);
    let Some((hinge, free, radius)) = room.door_sweep(door) else {
        // Out or sliding: the closed leaf, across the middle of the wall.
        let mid = outward_px(view, edge) * f64::from(wall_px) / 2.0;
        let closed = [view.to_px(ends.0) + mid, view.to_px(ends.1) + mid];
        if let Some(line) = polygon(&closed) {
            outline(pixmap, &line, DOOR_LEAF, &leaf);
        }
        return;
    };
    let open = hinge + edge.inward_normal() * radius;
    if let Some(line) = polygon(&[view.to_px(hinge), view.to_px(open)]) {
        outline(pixmap, &line, DOOR_LEAF, &leaf);
    }
    let from = free - hinge;
    let to = open - hinge;
    let mut arc = PathBuilder::new();
    const STEPS: usize = 24;
    for i in 0..=STEPS {
        let t = i as f64 / STEPS as f64;
        // Slerp between two perpendicular vectors of equal length: a quarter circle.
        let angle = t * std::f64::consts::FRAC_PI_2;
        let p = view.to_px(hinge + from * angle.cos() + to * angle.sin());
        if i == 0 {
            arc.move_to(p.x as f32, p.y as f32);
        } else {
            arc.line_to(p.x as f32, p.y as f32);
        }
    }
    if let Some(arc) = arc.finish() {
        let mut s = stroke(1.5);
        s.dash = tiny_skia::StrokeDash::new(vec![5.0, 4.0], 0.0);
        outline(pixmap, &arc, DOOR_LEAF, &s);
    }
}

/// A window: glass over the wall's thickness along its span, between two dark lines.
fn draw_window(
    pixmap: &mut Pixmap,
    view: &View,
    edge: &Edge,
    ends: (DVec2, DVec2),
    wall_px: f32,
    outside: &Mask,
) {
    let depth = f64::from(wall_px);
    if let Some(glass) = polygon(&wall_band(view, edge, ends, depth)) {
        pixmap.fill_path(
            &glass,
            &paint(WINDOW_GLASS, 255),
            FillRule::Winding,
            Transform::identity(),
            Some(outside),
        );
    }
    let out = outward_px(view, edge);
    for share in [0.2, 0.8] {
        let off = out * depth * share;
        if let Some(line) = polygon(&[view.to_px(ends.0) + off, view.to_px(ends.1) + off]) {
            outline(pixmap, &line, WINDOW_LINE, &stroke(1.5));
        }
    }
}

/// Writes each wall's index in a small badge on the wall, at the middle of its longest stretch
/// without openings (its middle when openings leave none).
pub(super) fn draw_wall_labels(
    pixmap: &mut Pixmap,
    view: &View,
    room: &Room,
    text: &TextPainter,
    wall_px: f32,
) {
    let radius = 9.0f32;
    for edge in room.walls() {
        let along = label_spot(room, &edge);
        let at = view.to_px(edge.point(along)) + outward_px(view, &edge) * f64::from(wall_px) / 2.0;
        if let Some(badge) = PathBuilder::from_circle(at.x as f32, at.y as f32, radius) {
            fill(pixmap, &badge, BACKGROUND, 255);
            outline(pixmap, &badge, LABEL_TEXT, &stroke(1.0));
        }
        let label = edge.index.to_string();
        let size = text.fit_size(&label, radius * 1.6, 9.0, 12.0);
        text.draw(
            pixmap,
            &label,
            Anchor::Centre(at.x as f32),
            at.y as f32,
            size,
            LABEL_TEXT,
        );
    }
}

/// Where along `edge` its label goes: the middle of its longest stretch clear of openings.
fn label_spot(room: &Room, edge: &Edge) -> f64 {
    let mut openings = room.openings_on(edge.index);
    openings.sort_by(|a, b| a.0.total_cmp(&b.0));
    let mut best = (0.0, edge.length() / 2.0);
    let mut from = 0.0;
    for (start, end) in openings.into_iter().chain([(edge.length(), edge.length())]) {
        if start - from > best.0 {
            best = (start - from, (from + start) / 2.0);
        }
        from = from.max(end);
    }
    best.1
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn labels_sit_on_the_longest_clear_stretch() {
        let mut room = Room::rect(400.0, 300.0);
        room.doors.push(Door::new(0, 100.0, 80.0));
        let walls = room.walls();
        // Wall 0: clear from 0 to 60 and from 140 to 400: the label goes at 270.
        assert_eq!(label_spot(&room, &walls[0]), 270.0);
        assert_eq!(label_spot(&room, &walls[1]), 150.0);
    }
}
