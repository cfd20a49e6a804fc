//! Text in the PNG, drawn glyph by glyph with ab_glyph from the embedded DejaVu Sans.
//!
//! plotters 0.3.7 puts each glyph's bounding box at the pen position, dropping the left side
//! bearing, so letters are unevenly spaced ("Syn th etic"), and it places no combining mark, so
//! `l̄` (l + U+0304) loses its bar or has it cut through the ascender. [`Bitmap`] draws every glyph
//! at its own outline bounds and puts a combining mark (U+0300..U+036F) centred over the glyph
//! before it, clear of its top. The SVG keeps the text as text; a viewer's font shaping places
//! the marks there.

use ab_glyph::{Font as _, FontRef, GlyphId, ScaleFont as _};
use plotters::prelude::*;
use plotters_backend::text_anchor::{HPos, VPos};
use plotters_backend::{BackendColor, BackendStyle, BackendTextStyle, DrawingErrorKind};

use super::font;
use crate::model::{Chart, Figure};

/// DejaVu Sans, regular or bold, as ab_glyph reads it.
pub fn glyph_font(bold: bool) -> Option<&'static FontRef<'static>> {
    static FONTS: std::sync::OnceLock<Option<(FontRef<'static>, FontRef<'static>)>> =
        std::sync::OnceLock::new();
    let fonts = FONTS
        .get_or_init(|| {
            let regular = FontRef::try_from_slice(dejavu::sans::regular()).ok()?;
            Some((regular, FontRef::try_from_slice(dejavu::sans::bold()).ok()?))
        })
        .as_ref()?;
    Some(if bold { &fonts.1 } else { &fonts.0 })
}

/// Every character of the figure's text (caption, titles, labels, legend entries, categories)
/// that the embedded font has no glyph for, in order of appearance, each once.
pub fn missing_glyphs(figure: &Figure) -> Vec<char> {
    let Some(font) = glyph_font(false) else { return Vec::new() };
    let mut texts: Vec<&str> = vec![&figure.caption];
    for chart in &figure.panels {
        match chart {
            Chart::Lines(p) => {
                texts.extend([p.title.as_str(), &p.x_label, &p.y_label]);
                texts.extend(p.series.iter().map(|s| s.name.as_str()));
            }
            Chart::Heat(h) => {
                texts.extend([h.title.as_str(), &h.x_label, &h.y_label, &h.value_label]);
                texts.extend(h.categories.iter().map(String::as_str));
            }
            Chart::Chain(d) => texts.push(&d.title),
            Chart::Network(d) => texts.push(&d.title),
        }
    }
    let mut missing = Vec::new();
    for c in texts.iter().flat_map(|t| t.chars()) {
        if !c.is_whitespace() && font.glyph_id(c) == GlyphId(0) && !missing.contains(&c) {
            missing.push(c);
        }
    }
    missing
}

/// The subscript form of `c`, where Unicode has one.
fn subscript(c: char) -> Option<char> {
    const PLAIN: &str = "0123456789+-−=()aehijklmnoprstuvx";
    const SUB: &str = "₀₁₂₃₄₅₆₇₈₉₊₋₋₌₍₎ₐₑₕᵢⱼₖₗₘₙₒₚᵣₛₜᵤᵥₓ";
    PLAIN.chars().position(|p| p == c).and_then(|i| SUB.chars().nth(i))
}

/// Text as it is drawn: a subscript written `x_i`, `x_{i+1}` or `E_min` in Unicode subscripts
/// (`xᵢ`, `xᵢ₊₁`, `Eₘᵢₙ`) when every character of it has one in Unicode and in the embedded font;
/// otherwise (`l_critical`: no subscript c) as written.
pub fn math(text: &str) -> String {
    let font = glyph_font(false);
    let drawable = |c: char| font.is_none_or(|f| f.glyph_id(c) != GlyphId(0));
    let convert = |group: &str| -> Option<String> {
        group.chars().map(|c| subscript(c).filter(|&s| drawable(s))).collect::<Option<String>>()
    };
    let mut out = String::with_capacity(text.len());
    let mut rest = text;
    while let Some(at) = rest.find('_') {
        out.push_str(&rest[..at]);
        let after = &rest[at + 1..];
        let (group, written, len) =
            match after.strip_prefix('{').and_then(|g| g.find('}').map(|end| (&g[..end], end))) {
                Some((group, end)) => (group, &rest[at..at + end + 3], end + 2),
                None => {
                    let end = after.find(|c: char| !c.is_ascii_alphanumeric()).unwrap_or(after.len());
                    (&after[..end], &rest[at..at + 1 + end], end)
                }
            };
        match convert(group).filter(|g| !g.is_empty()) {
            Some(sub) => out.push_str(&sub),
            None => out.push_str(written),
        }
        rest = &after[len..];
    }
    out.push_str(rest);
    out
}

/// A copy of `figure` with every text as drawn ([`math`]).
pub fn displayed(figure: &Figure) -> Figure {
    let mut f = figure.clone();
    f.caption = math(&f.caption);
    for chart in &mut f.panels {
        match chart {
            Chart::Lines(p) => {
                for text in [&mut p.title, &mut p.x_label, &mut p.y_label] {
                    *text = math(text);
                }
                for s in &mut p.series {
                    s.name = math(&s.name);
                }
            }
            Chart::Heat(h) => {
                for text in [&mut h.title, &mut h.x_label, &mut h.y_label, &mut h.value_label] {
                    *text = math(text);
                }
                for c in &mut h.categories {
                    *c = math(c);
                }
            }
            Chart::Chain(d) => d.title = math(&d.title),
            Chart::Network(d) => d.title = math(&d.title),
        }
    }
    f
}

/// A combining mark, placed over the glyph before it.
fn is_combining(c: char) -> bool {
    ('\u{0300}'..='\u{036F}').contains(&c)
}

/// Break `text` into lines at most `width` pixels wide in the font of `size`.
pub fn wrap(text: &str, size: f64, width: u32) -> Vec<String> {
    let fits = |line: &str| font(size, FontStyle::Normal).box_size(line).map_or(true, |(w, _)| w <= width);
    let mut lines: Vec<String> = Vec::new();
    for word in text.split_whitespace() {
        match lines.last_mut() {
            Some(line) if fits(&format!("{line} {word}")) => {
                line.push(' ');
                line.push_str(word);
            }
            _ => lines.push(word.to_owned()),
        }
    }
    lines
}

/// The pixels of `text` at `size`, as `(x, y, coverage)` with the pen starting at `(0, 0)` on
/// the line `size / 2` above the baseline (plotters' placement), combining marks over their base.
pub fn glyph_pixels(text: &str, size: f32, bold: bool) -> Vec<(i32, i32, f32)> {
    let Some(font) = glyph_font(bold) else { return Vec::new() };
    let font = font.as_scaled(size);
    let (mut pen, mut previous, mut coverage) = (0.0f32, None, Vec::new());
    // The pixel bounds of the last base glyph: `(min x, min y, max x)`.
    let mut base: Option<(f32, f32, f32)> = None;
    for c in text.chars() {
        let id = font.glyph_id(c);
        if is_combining(c) {
            let glyph = id.with_scale_and_position(font.scale(), ab_glyph::point(pen, size / 2.0));
            if let (Some(outline), Some((left, top, right))) = (font.outline_glyph(glyph), base) {
                let b = outline.px_bounds();
                // Centred over the base, its lowest pixel a tenth of the size above the base's top.
                let dx = (0.5 * (left + right) - 0.5 * (b.min.x + b.max.x)).round();
                let dy = (top - 0.1 * size - b.max.y).min(0.0).round();
                let at = (b.min.x + dx, b.min.y + dy);
                outline.draw(|x, y, c| coverage.push((at.0 as i32 + x as i32, at.1 as i32 + y as i32, c)));
            }
            continue;
        }
        pen += previous.map_or(0.0, |p| font.kern(p, id));
        let glyph = id.with_scale_and_position(font.scale(), ab_glyph::point(pen, size / 2.0));
        base = None;
        if let Some(outline) = font.outline_glyph(glyph) {
            let b = outline.px_bounds();
            base = Some((b.min.x, b.min.y, b.max.x));
            outline.draw(|x, y, c| coverage.push((b.min.x as i32 + x as i32, b.min.y as i32 + y as i32, c)));
        }
        pen += font.h_advance(id);
        previous = Some(id);
    }
    coverage
}

/// plotters' bitmap backend with text drawn by [`glyph_pixels`]. Everything else is the bitmap
/// backend's; the text's layout box and anchoring are plotters', so the charts are laid out as
/// plotters lays them out.
pub struct Bitmap<'a>(BitMapBackend<'a>);

impl<'a> Bitmap<'a> {
    pub fn new(pixels: &'a mut [u8], size: (u32, u32)) -> Self {
        Bitmap(BitMapBackend::with_buffer(pixels, size))
    }
}

impl<'a> DrawingBackend for Bitmap<'a> {
    type ErrorType = <BitMapBackend<'a> as DrawingBackend>::ErrorType;
    fn get_size(&self) -> (u32, u32) {
        self.0.get_size()
    }
    fn ensure_prepared(&mut self) -> Result<(), DrawingErrorKind<Self::ErrorType>> {
        self.0.ensure_prepared()
    }
    fn present(&mut self) -> Result<(), DrawingErrorKind<Self::ErrorType>> {
        self.0.present()
    }
    fn draw_pixel(
        &mut self,
        p: (i32, i32),
        c: BackendColor,
    ) -> Result<(), DrawingErrorKind<Self::ErrorType>> {
        self.0.draw_pixel(p, c)
    }
    fn draw_line<S: BackendStyle>(
        &mut self,
        a: (i32, i32),
        b: (i32, i32),
        s: &S,
    ) -> Result<(), DrawingErrorKind<Self::ErrorType>> {
        self.0.draw_line(a, b, s)
    }
    fn draw_rect<S: BackendStyle>(
        &mut self,
        a: (i32, i32),
        b: (i32, i32),
        s: &S,
        fill: bool,
    ) -> Result<(), DrawingErrorKind<Self::ErrorType>> {
        self.0.draw_rect(a, b, s, fill)
    }
    fn draw_path<S: BackendStyle, I: IntoIterator<Item = (i32, i32)>>(
        &mut self,
        path: I,
        s: &S,
    ) -> Result<(), DrawingErrorKind<Self::ErrorType>> {
        self.0.draw_path(path, s)
    }
    fn draw_circle<S: BackendStyle>(
        &mut self,
        c: (i32, i32),
        r: u32,
        s: &S,
        fill: bool,
    ) -> Result<(), DrawingErrorKind<Self::ErrorType>> {
        self.0.draw_circle(c, r, s, fill)
    }
    fn fill_polygon<S: BackendStyle, I: IntoIterator<Item = (i32, i32)>>(
        &mut self,
        vertices: I,
        s: &S,
    ) -> Result<(), DrawingErrorKind<Self::ErrorType>> {
        self.0.fill_polygon(vertices, s)
    }

    fn draw_text<S: BackendTextStyle>(
        &mut self,
        text: &str,
        style: &S,
        pos: (i32, i32),
    ) -> Result<(), DrawingErrorKind<Self::ErrorType>> {
        let colour = style.color();
        if colour.alpha <= 0.0 {
            return Ok(());
        }
        let bold = matches!(style.style(), plotters_backend::FontStyle::Bold);
        let ((min_x, min_y), (max_x, max_y)) =
            style.layout_box(text).map_err(|e| DrawingErrorKind::FontError(Box::new(e)))?;
        // Anchor as plotters' default `draw_text` does.
        let dx = match style.anchor().h_pos {
            HPos::Left => 0,
            HPos::Right => min_x - max_x,
            HPos::Center => (min_x - max_x) / 2,
        };
        let dy = match style.anchor().v_pos {
            VPos::Top => 0,
            VPos::Center => (min_y - max_y) / 2,
            VPos::Bottom => min_y - max_y,
        };
        let transform = style.transform();
        for (x, y, c) in glyph_pixels(text, style.size() as f32, bold) {
            let (x, y) = transform.transform(x + dx - min_x, y + dy - min_y);
            let colour = BackendColor { alpha: colour.alpha * f64::from(c), rgb: colour.rgb };
            self.0.draw_pixel((pos.0 + x, pos.1 + y), colour)?;
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// `(lowest row, highest row)` of the inked pixels of columns `x0..x1` (y grows downwards).
    fn rows(pixels: &[(i32, i32, f32)], x0: i32, x1: i32) -> (i32, i32) {
        let ys = pixels.iter().filter(|p| p.2 > 0.3 && (x0..x1).contains(&p.0)).map(|p| p.1);
        ys.clone().fold((i32::MAX, i32::MIN), |(lo, hi), y| (lo.min(y), hi.max(y)))
    }

    #[test]
    fn a_combining_macron_sits_above_a_tall_letter() {
        let plain = glyph_pixels("l", 40.0, false);
        let barred = glyph_pixels("l\u{304}", 40.0, false);
        let (top, _) = rows(&plain, -100, 100);
        // The bar adds ink strictly above the l's top, and nothing else changes width much.
        let above: Vec<_> = barred.iter().filter(|p| p.2 > 0.3 && p.1 < top).collect();
        assert!(above.len() > 20, "no bar above the l: {} pixels", above.len());
        let (l_left, l_right) = plain
            .iter()
            .filter(|p| p.2 > 0.3)
            .fold((i32::MAX, i32::MIN), |(a, b), p| (a.min(p.0), b.max(p.0)));
        let bar_centre = above.iter().map(|p| p.0).sum::<i32>() as f64 / above.len() as f64;
        assert!(
            (bar_centre - 0.5 * f64::from(l_left + l_right)).abs() < 3.0,
            "bar not centred: {bar_centre}"
        );
        // Theta gets its bar too, and the letters after a mark keep their place.
        let (t_top, _) = rows(&glyph_pixels("θ", 40.0, false), -100, 100);
        assert!(glyph_pixels("θ\u{304}", 40.0, false).iter().any(|p| p.2 > 0.3 && p.1 < t_top));
        let after = |s: &str| glyph_pixels(s, 40.0, false).iter().filter(|p| p.2 > 0.3).map(|p| p.0).max();
        assert_eq!(after("l\u{304}x"), after("lx"));
    }

    #[test]
    fn subscripts_become_unicode_where_every_character_has_one() {
        assert_eq!(math("θ_i (rad)"), "θᵢ (rad)");
        assert_eq!(math("θ_{i+1} = θ_i"), "θᵢ₊₁ = θᵢ");
        assert_eq!(math("l_p − l̄ (a)"), "lₚ − l̄ (a)");
        assert_eq!(math("E_min, E_c, l_critical, V_PNB"), "Eₘᵢₙ, E_c, l_critical, V_PNB");
        assert_eq!(math("k_i/k = 0.1"), "kᵢ/k = 0.1");
        assert_eq!(math("a_ b_{} c_{x"), "a_ b_{} c_{x");
        assert_eq!(math("no subscript"), "no subscript");
    }

    #[test]
    fn missing_glyphs_are_reported() {
        let figure = Figure {
            label: "fig:t",
            caption: "θ̄ = 0.58, l_p − l̄, ω/√(k/M), ‖K‖, ε, ∓, ≈, ², ᵀ, θᵢ₊₁, lₚ, ₀, \u{4E2D}".into(),
            panels: Vec::new(),
            rows: Vec::new(),
        };
        assert_eq!(missing_glyphs(&figure), vec!['\u{4E2D}']);
    }
}
