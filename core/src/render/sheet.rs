//! A contact sheet: several renders side by side in a grid, each with a caption, in one PNG, so
//! a whole run's sequence of steps can be seen at a glance (the paper's Figures 4 and 5).

use tiny_skia::{Pixmap, PixmapPaint, Transform};

use super::text::{Anchor, TextPainter};
use super::{BACKGROUND, Error, Result};

/// Height of the caption strip under each tile, in pixels.
pub const CAPTION_PX: u32 = 30;
/// Gap between tiles, in pixels.
pub const GAP_PX: u32 = 8;

/// `tiles` (caption, image) in rows of `columns`, each cell as large as the largest tile.
pub fn contact_sheet(tiles: &[(String, Pixmap)], columns: usize) -> Result<Pixmap> {
    if tiles.is_empty() {
        return Err(Error::Render(
            "a contact sheet needs at least one image".into(),
        ));
    }
    let columns = columns.clamp(1, tiles.len()) as u32;
    let rows = (tiles.len() as u32).div_ceil(columns);
    let cell_w = tiles.iter().map(|(_, p)| p.width()).max().unwrap_or(1);
    let cell_h = tiles.iter().map(|(_, p)| p.height()).max().unwrap_or(1) + CAPTION_PX;
    let width = columns * cell_w + (columns + 1) * GAP_PX;
    let height = rows * cell_h + (rows + 1) * GAP_PX;
    let mut sheet = Pixmap::new(width, height)
        .ok_or_else(|| Error::Render(format!("cannot allocate a {width} x {height} sheet")))?;
    let [r, g, b] = BACKGROUND;
    sheet.fill(tiny_skia::Color::from_rgba8(r, g, b, 255));
    let text = TextPainter::new()?;
    for (i, (caption, tile)) in tiles.iter().enumerate() {
        let (col, row) = (i as u32 % columns, i as u32 / columns);
        let x = GAP_PX + col * (cell_w + GAP_PX);
        let y = GAP_PX + row * (cell_h + GAP_PX);
        sheet.draw_pixmap(
            x as i32,
            y as i32,
            tile.as_ref(),
            &PixmapPaint::default(),
            Transform::identity(),
            None,
        );
        let size = text.fit_size(caption, cell_w as f32 - 8.0, 9.0, 16.0);
        text.draw(
            &mut sheet,
            caption,
            Anchor::Centre((x + cell_w / 2) as f32),
            (y + cell_h - CAPTION_PX / 2) as f32,
            size,
            [235, 235, 240],
        );
    }
    Ok(sheet)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn tiles_land_in_a_grid_with_captions_below() {
        let tile = |rgb: [u8; 3]| {
            let mut p = Pixmap::new(100, 80).unwrap();
            p.fill(tiny_skia::Color::from_rgba8(rgb[0], rgb[1], rgb[2], 255));
            p
        };
        let tiles = vec![
            ("one".to_string(), tile([255, 0, 0])),
            ("two".to_string(), tile([0, 255, 0])),
            ("three".to_string(), tile([0, 0, 255])),
        ];
        let sheet = contact_sheet(&tiles, 2).unwrap();
        assert_eq!(sheet.width(), 2 * 100 + 3 * GAP_PX);
        assert_eq!(sheet.height(), 2 * (80 + CAPTION_PX) + 3 * GAP_PX);
        let at = |x: u32, y: u32| {
            let c = sheet.pixel(x, y).unwrap();
            [c.red(), c.green(), c.blue()]
        };
        assert_eq!(at(GAP_PX + 50, GAP_PX + 40), [255, 0, 0]);
        assert_eq!(at(2 * GAP_PX + 150, GAP_PX + 40), [0, 255, 0]);
        let second_row = 2 * GAP_PX + 80 + CAPTION_PX;
        assert_eq!(at(GAP_PX + 50, second_row + 40), [0, 0, 255]);
        // Something (the caption) is drawn in the strip under the first tile.
        let strip = GAP_PX + 80..GAP_PX + 80 + CAPTION_PX;
        assert!(
            strip
                .into_iter()
                .any(|y| (GAP_PX..GAP_PX + 100).any(|x| at(x, y) != BACKGROUND))
        );
        assert!(contact_sheet(&[], 3).is_err());
    }
}
