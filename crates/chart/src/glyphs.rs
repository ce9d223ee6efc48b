//! [`Glyphs`]: the PNG's text, placed glyph by glyph from the embedded Noto Sans.

use ab_glyph::{Font, ScaleFont};
use plotters::prelude::DrawingBackend;
use plotters::style::text_anchor::HPos;
use plotters_backend::{
    BackendColor, BackendCoord, BackendStyle, BackendTextStyle, DrawingErrorKind,
};

/// plotters' bitmap back end with text placed char by char: plotters 0.3.7's `ab_glyph` text
/// drops each glyph's left side bearing, so each char goes to the inner back end at the pen
/// position (Noto Sans' advances and kerning) plus its bearing. The rest is forwarded, or left
/// to `DrawingBackend`'s defaults (as the bitmap back end does), which draw through these.
pub(crate) struct Glyphs<DB>(pub(crate) DB, pub(crate) ab_glyph::FontRef<'static>);

// Shorthands for the forwarding signatures.
type Drawn<DB> = Result<(), DrawingErrorKind<<DB as DrawingBackend>::ErrorType>>;
type At = BackendCoord;

impl<DB: DrawingBackend> DrawingBackend for Glyphs<DB> {
    type ErrorType = DB::ErrorType;
    fn get_size(&self) -> (u32, u32) {
        self.0.get_size()
    }
    fn ensure_prepared(&mut self) -> Drawn<DB> {
        self.0.ensure_prepared()
    }
    fn present(&mut self) -> Drawn<DB> {
        self.0.present()
    }
    fn draw_pixel(&mut self, at: At, color: BackendColor) -> Drawn<DB> {
        self.0.draw_pixel(at, color)
    }
    fn draw_line<S: BackendStyle>(&mut self, a: At, b: At, s: &S) -> Drawn<DB> {
        self.0.draw_line(a, b, s)
    }
    fn draw_rect<S: BackendStyle>(&mut self, a: At, b: At, s: &S, fill: bool) -> Drawn<DB> {
        self.0.draw_rect(a, b, s, fill)
    }
    fn draw_text<T: BackendTextStyle>(&mut self, text: &str, style: &T, at: At) -> Drawn<DB> {
        // plotters shifts a text left by its anchor (its box's width, whole or half; the box's
        // height is the font's for any text): the whole text's shift, not each char's.
        let shift = |text: &str| {
            let ((x0, _), (x1, _)) = style
                .layout_box(text)
                .map_err(|e| DrawingErrorKind::FontError(Box::new(e)))?;
            Ok::<_, DrawingErrorKind<DB::ErrorType>>(match style.anchor().h_pos {
                HPos::Left => 0,
                HPos::Center => -(x1 - x0) / 2,
                HPos::Right => -(x1 - x0),
            })
        };
        let (font, whole) = (self.1.as_scaled(style.size() as f32), shift(text)?);
        let (mut pen, mut prev) = (0.0, None);
        for c in text.chars() {
            let id = font.glyph_id(c);
            pen += prev.map_or(0.0, |p| font.kern(p, id));
            prev = Some(id);
            let glyph = font.outline_glyph(font.scaled_glyph(c));
            let x = (pen + glyph.map_or(0.0, |g| g.px_bounds().min.x)).round() as i32;
            let c = &c.to_string();
            let (x, y) = style.transform().transform(whole - shift(c)? + x, 0);
            self.0.draw_text(c, style, (at.0 + x, at.1 + y))?;
            pen += font.h_advance(id);
        }
        Ok(())
    }
}
