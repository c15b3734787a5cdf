//! Text on pixmaps with ab_glyph and the bundled DejaVu Sans Condensed Bold (free licence, see
//! `font/LICENSE-DejaVu.txt`), drawn white-on-dark-halo so names stay legible on any colour.

use ab_glyph::{Font, FontRef, PxScale, ScaleFont, point};
use tiny_skia::{Pixmap, PremultipliedColorU8};

use crate::error::{Error, Result};

static FONT_BYTES: &[u8] = include_bytes!("font/DejaVuSansCondensed-Bold.ttf");

/// Where a line of text sits horizontally: its left end, centre or right end at this x.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Anchor {
    /// The text starts here.
    Left(f32),
    /// The text is centred here.
    Centre(f32),
    /// The text ends here.
    Right(f32),
}

/// Draws short strings onto a pixmap.
pub struct TextPainter {
    font: FontRef<'static>,
}

impl TextPainter {
    /// Loads the bundled font.
    pub fn new() -> Result<Self> {
        let font = FontRef::try_from_slice(FONT_BYTES)
            .map_err(|e| Error::Render(format!("bundled font: {e}")))?;
        Ok(TextPainter { font })
    }

    /// Width in pixels of `text` at `size` px.
    pub fn width(&self, text: &str, size: f32) -> f32 {
        let scaled = self.font.as_scaled(PxScale::from(size));
        let mut w = 0.0;
        let mut prev = None;
        for c in text.chars() {
            let id = self.font.glyph_id(c);
            if let Some(p) = prev {
                w += scaled.kern(p, id);
            }
            w += scaled.h_advance(id);
            prev = Some(id);
        }
        w
    }

    /// The largest size in `[min, max]` at which `text` fits `width` px (`min` if none does).
    pub fn fit_size(&self, text: &str, width: f32, min: f32, max: f32) -> f32 {
        let at_max = self.width(text, max);
        if at_max <= 0.0 {
            return max;
        }
        (max * width / at_max).clamp(min, max)
    }

    /// Draws `text` vertically centred on `cy`, placed horizontally by `anchor`.
    pub fn draw(
        &self,
        pixmap: &mut Pixmap,
        text: &str,
        anchor: Anchor,
        cy: f32,
        size: f32,
        rgb: [u8; 3],
    ) {
        let x = match anchor {
            Anchor::Left(x) => x,
            Anchor::Centre(x) => x - self.width(text, size) / 2.0,
            Anchor::Right(x) => x - self.width(text, size),
        };
        self.draw_from(pixmap, text, x, cy, size, rgb);
    }

    fn draw_from(&self, pixmap: &mut Pixmap, text: &str, x: f32, cy: f32, size: f32, rgb: [u8; 3]) {
        let scaled = self.font.as_scaled(PxScale::from(size));
        let baseline = cy + (scaled.ascent() + scaled.descent()) / 2.0;
        let coverage = self.rasterize(text, x, baseline, size);
        // A dark halo (the glyphs stamped at eight offsets), then the text itself.
        let halo = [16, 16, 20];
        for (dx, dy) in [
            (-1, -1),
            (0, -1),
            (1, -1),
            (-1, 0),
            (1, 0),
            (-1, 1),
            (0, 1),
            (1, 1),
        ] {
            for &(px, py, c) in &coverage {
                blend(pixmap, px + dx, py + dy, halo, c * 0.8);
            }
        }
        for &(px, py, c) in &coverage {
            blend(pixmap, px, py, rgb, c);
        }
    }

    /// Pixel coverage of `text` laid out from `(x, baseline)`: (x, y, coverage in 0..=1).
    fn rasterize(&self, text: &str, x: f32, baseline: f32, size: f32) -> Vec<(i64, i64, f32)> {
        let scaled = self.font.as_scaled(PxScale::from(size));
        let mut out = Vec::new();
        let mut caret = x;
        let mut prev = None;
        for c in text.chars() {
            let id = self.font.glyph_id(c);
            if let Some(p) = prev {
                caret += scaled.kern(p, id);
            }
            let glyph = id.with_scale_and_position(size, point(caret, baseline));
            caret += scaled.h_advance(id);
            prev = Some(id);
            let Some(outline) = self.font.outline_glyph(glyph) else {
                continue;
            };
            let b = outline.px_bounds();
            outline.draw(|gx, gy, coverage| {
                if coverage > 0.0 {
                    out.push((
                        b.min.x as i64 + i64::from(gx),
                        b.min.y as i64 + i64::from(gy),
                        coverage,
                    ));
                }
            });
        }
        out
    }
}

/// Source-over blend of an opaque colour at `alpha` onto one pixel (ignored outside the image).
fn blend(pixmap: &mut Pixmap, x: i64, y: i64, rgb: [u8; 3], alpha: f32) {
    if x < 0 || y < 0 || x >= i64::from(pixmap.width()) || y >= i64::from(pixmap.height()) {
        return;
    }
    let idx = y as usize * pixmap.width() as usize + x as usize;
    let a = alpha.clamp(0.0, 1.0);
    let dst = pixmap.pixels()[idx];
    let mix = |s: u8, d: u8| (f32::from(s) * a + f32::from(d) * (1.0 - a)).round() as u8;
    let out_a = (255.0 * a + f32::from(dst.alpha()) * (1.0 - a)).round() as u8;
    // Sources are opaque colours, so premultiplied source = colour * a.
    let r = mix(rgb[0], dst.red()).min(out_a);
    let g = mix(rgb[1], dst.green()).min(out_a);
    let bl = mix(rgb[2], dst.blue()).min(out_a);
    if let Some(c) = PremultipliedColorU8::from_rgba(r, g, bl, out_a) {
        pixmap.pixels_mut()[idx] = c;
    }
}
