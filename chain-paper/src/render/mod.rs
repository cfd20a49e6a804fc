//! Drawing a [`Figure`] to PNG and SVG with plotters, in pure Rust: the font (DejaVu Sans) is
//! embedded, so no system font or graphics library is needed.
//!
//! A figure is its caption above rows of panels ([`layout`]): line panels and heat maps two to a
//! row ([`CELL`] each; [`SINGLE`] for a figure of one panel), drawings of the chain two to a
//! shorter row, or alone across the whole width. The parts, one file each:
//! - `lines`: line panels (colours by quantity from [`crate::palette`], a y axis of a
//!   non-negative quantity that does not start at zero marked broken);
//! - `legend`: legends where the data leave room, outside the plot otherwise;
//! - `heatmap`: heat maps (diverging colours centred on zero for signed values) and colour bars;
//!   `log_axis`: their axis of `log10` values, labelled with the values;
//! - `chain`: drawings of the chain;
//! - `network`: drawings of a network's patch (equal scales, like the chain's);
//! - `text`: text drawn glyph by glyph, combining marks (`θ̄`, `l̄`) placed over their letter.

use std::error::Error;
use std::path::{Path, PathBuf};
use std::sync::OnceLock;

use image::ImageEncoder as _;
use plotters::coord::Shift;
use plotters::prelude::*;

use crate::data::file_stem;
use crate::model::{Chart, Figure};
use crate::output::{WriteError, write_atomic};

mod chain;
mod heatmap;
mod legend;
mod lines;
mod log_axis;
mod network;
mod text;

pub use text::{glyph_font, missing_glyphs};

/// Why a figure could not be rendered.
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum RenderError {
    #[error("the embedded font could not be loaded")]
    /// The embedded font could not be loaded.
    Font,
    #[error("cannot draw {}: {source}", path.display())]
    /// plotters could not draw the figure.
    Draw {
        /// The figure's file.
        path: PathBuf,
        #[source]
        /// plotters' error.
        source: Box<dyn Error + Send + Sync>,
    },
    #[error("cannot encode {}: {source}", path.display())]
    /// The PNG could not be encoded.
    Encode {
        /// The figure's file.
        path: PathBuf,
        #[source]
        /// The encoder's error.
        source: image::ImageError,
    },
    #[error(transparent)]
    /// The file could not be written.
    Write(#[from] WriteError),
}

/// Size of a figure with one panel.
pub const SINGLE: (u32, u32) = (1000, 700);
/// Size of one panel of a figure with several.
pub const CELL: (u32, u32) = (800, 560);
/// Height of a row of chain drawings.
pub const CHAIN_ROW: u32 = 250;
const CAPTION_FONT: f64 = 17.0;
const TITLE_FONT: f64 = 21.0;
const LABEL_FONT: f64 = 17.0;
const TICK_FONT: f64 = 14.0;

type Drawn = Result<(), Box<dyn Error>>;

/// Where each panel goes: `(panel index, left, top, width, height)` in pixels below the caption,
/// and the size of the whole grid.
#[derive(Debug, PartialEq)]
pub struct Layout {
    /// Size of the whole grid, pixels `(width, height)`.
    pub size: (u32, u32),
    /// Per panel: `(panel index, left, top, width, height)`, pixels.
    pub slots: Vec<(usize, u32, u32, u32, u32)>,
}

/// The rows of panels, in reading order. A figure of one panel is [`SINGLE`]. Otherwise the
/// width is two [`CELL`]s: consecutive drawings of the chain share a row of height [`CHAIN_ROW`];
/// a drawing followed by another kind of panel has such a row to itself, across the width if it
/// is the figure's only drawing; other panels go two to a row of height `CELL.1`, lowered for a row
/// of network drawings to what the taller one fills at equal scale (`render::network::natural_height`).
pub fn layout(panels: &[Chart]) -> Layout {
    if panels.len() <= 1 {
        let size = match panels.first() {
            Some(Chart::Chain(_)) => (2 * CELL.0, CHAIN_ROW),
            Some(Chart::Network(d)) => (SINGLE.0, network::natural_height(d, SINGLE.0, SINGLE.1)),
            _ => SINGLE,
        };
        return Layout {
            size,
            slots: panels.iter().enumerate().map(|(i, _)| (i, 0, 0, size.0, size.1)).collect(),
        };
    }
    let width = 2 * CELL.0;
    let is_chain = |i: usize| matches!(panels.get(i), Some(Chart::Chain(_)));
    // A figure's only drawing spans the width; several drawings keep one size, a cell each.
    let drawings = (0..panels.len()).filter(|&i| is_chain(i)).count();
    let (mut slots, mut top, mut i) = (Vec::new(), 0, 0);
    while i < panels.len() {
        let pair = i + 1 < panels.len() && is_chain(i) == is_chain(i + 1);
        // A row of network drawings is as tall as its taller drawing needs at a cell's width.
        let natural = |k: usize| match panels.get(k) {
            Some(Chart::Network(d)) => network::natural_height(d, CELL.0, CELL.1),
            _ => CELL.1,
        };
        let height = if is_chain(i) {
            CHAIN_ROW
        } else if pair {
            natural(i).max(natural(i + 1))
        } else {
            natural(i)
        };
        if pair {
            slots.push((i, 0, top, CELL.0, height));
            slots.push((i + 1, CELL.0, top, CELL.0, height));
            i += 2;
        } else {
            let w = if is_chain(i) && drawings == 1 { width } else { CELL.0 };
            slots.push((i, 0, top, w, height));
            i += 1;
        }
        top += height;
    }
    Layout { size: (width, top), slots }
}

/// Render `figure` to `dir/<name>.png` and `dir/<name>.svg`, `name` its label without `fig:`.
/// Each file is written atomically. Returns the two paths.
pub fn render(figure: &Figure, dir: &Path) -> Result<Vec<PathBuf>, RenderError> {
    register_fonts()?;
    let figure = &text::displayed(figure);
    let stem = file_stem(figure.label);
    let (png, svg) = (dir.join(format!("{stem}.png")), dir.join(format!("{stem}.svg")));
    let failed = |path: &Path| {
        let path = path.to_owned();
        // plotters' errors are not `Send`: their text is kept.
        move |e: Box<dyn Error>| RenderError::Draw { path, source: e.to_string().into() }
    };
    let (width, height, pixels) = raster(figure, &png)?;
    let (layout, caption) = frame(figure);
    let mut encoded = Vec::new();
    image::codecs::png::PngEncoder::new(&mut encoded)
        .write_image(&pixels, width, height, image::ColorType::Rgb8)
        .map_err(|source| RenderError::Encode { path: png.clone(), source })?;
    write_atomic(&png, &encoded)?;

    let mut svg_text = String::new();
    let root = SVGBackend::with_string(&mut svg_text, (width, height)).into_drawing_area();
    draw_figure(&root, figure, &caption, &layout).and_then(|()| Ok(root.present()?)).map_err(failed(&svg))?;
    drop(root);
    write_atomic(&svg, svg_text.as_bytes())?;
    Ok(vec![png, svg])
}

/// The figure's layout and its caption's lines.
fn frame(figure: &Figure) -> (Layout, Vec<String>) {
    let layout = layout(&figure.panels);
    let caption = text::wrap(&figure.caption, CAPTION_FONT, layout.size.0 - 40);
    (layout, caption)
}

/// `figure` rendered to RGB pixels in memory (the PNG's): `(width, height, pixels)`; `path`
/// names the file in an error. For frames of an animation ([`crate::network::write_gif`]).
pub fn pixels(figure: &Figure, path: &Path) -> Result<(u32, u32, Vec<u8>), RenderError> {
    register_fonts()?;
    raster(&text::displayed(figure), path)
}

fn raster(figure: &Figure, path: &Path) -> Result<(u32, u32, Vec<u8>), RenderError> {
    let (layout, caption) = frame(figure);
    let width = layout.size.0;
    let height = layout.size.1 + caption_height(caption.len());
    let mut pixels = vec![0u8; 3 * width as usize * height as usize];
    let root = text::Bitmap::new(&mut pixels, (width, height)).into_drawing_area();
    draw_figure(&root, figure, &caption, &layout)
        .and_then(|()| Ok(root.present()?))
        .map_err(|e| RenderError::Draw { path: path.to_owned(), source: e.to_string().into() })?;
    drop(root);
    Ok((width, height, pixels))
}

/// Register DejaVu Sans as plotters' `sans-serif`, once per process.
fn register_fonts() -> Result<(), RenderError> {
    static REGISTERED: OnceLock<bool> = OnceLock::new();
    let ok = REGISTERED.get_or_init(|| {
        let family = FontFamily::SansSerif.as_str();
        plotters::style::register_font(family, FontStyle::Normal, dejavu::sans::regular()).is_ok()
            && plotters::style::register_font(family, FontStyle::Bold, dejavu::sans::bold()).is_ok()
            && glyph_font(false).is_some()
    });
    if *ok { Ok(()) } else { Err(RenderError::Font) }
}

fn font(size: f64, style: FontStyle) -> FontDesc<'static> {
    FontDesc::new(FontFamily::SansSerif, size, style)
}

/// The pixel width of `text` in the tick font (legends, category names).
fn text_width(text: &str, size: f64) -> f64 {
    font(size, FontStyle::Normal).box_size(text).map_or(0.0, |(w, _)| f64::from(w))
}

fn caption_height(lines: usize) -> u32 {
    if lines == 0 { 0 } else { 12 + 22 * lines as u32 }
}

/// A panel title's font: bold, smaller for a title too wide for its panel.
fn title_font(title: &str, panel_width: u32) -> FontDesc<'static> {
    let room = f64::from(panel_width.saturating_sub(40).max(1));
    let width = font(TITLE_FONT, FontStyle::Bold).box_size(title).map_or(0.0, |(w, _)| f64::from(w));
    let size = if width > room { (TITLE_FONT * room / width).max(11.0) } else { TITLE_FONT };
    font(size, FontStyle::Bold)
}

fn draw_figure<DB: DrawingBackend>(
    root: &DrawingArea<DB, Shift>,
    figure: &Figure,
    caption: &[String],
    layout: &Layout,
) -> Drawn
where
    DB::ErrorType: 'static,
{
    root.fill(&WHITE)?;
    let (header, body) = root.split_vertically(caption_height(caption.len()));
    for (i, line) in caption.iter().enumerate() {
        header.draw(&Text::new(
            line.as_str(),
            (20, 10 + 22 * i as i32),
            font(CAPTION_FONT, FontStyle::Normal),
        ))?;
    }
    for &(index, left, top, width, height) in &layout.slots {
        let area = body.clone().shrink((left, top), (width, height));
        match &figure.panels[index] {
            Chart::Lines(panel) => lines::draw(&area, panel)?,
            Chart::Heat(map) => heatmap::draw(&area, map)?,
            Chart::Chain(drawing) => chain::draw(&area, drawing)?,
            Chart::Network(drawing) => network::draw(&area, drawing)?,
        }
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::model::{Heatmap, Panel};

    fn lines() -> Chart {
        Chart::Lines(Panel::new("", "x", "y", Vec::new()))
    }

    fn drawing() -> Chart {
        let model = rotor_chain::RuntimeChain::builder(4, 0.8, 1.0, 0.5).build().unwrap();
        Chart::Chain(crate::drawing::ChainDrawing::new("", &model, &[0.5; 4], 0..4).unwrap())
    }

    #[test]
    fn panels_are_laid_out_in_rows_of_two_and_drawings_apart() {
        assert_eq!(layout(&[lines()]).size, SINGLE);
        let l = layout(&[lines(), lines(), lines()]);
        assert_eq!(l.size, (2 * CELL.0, 2 * CELL.1));
        assert_eq!(l.slots[2], (2, 0, CELL.1, CELL.0, CELL.1));
        // A drawing before two plots: across the width, then the plots side by side.
        let l = layout(&[drawing(), lines(), lines()]);
        assert_eq!(
            l.slots,
            vec![
                (0, 0, 0, 2 * CELL.0, CHAIN_ROW),
                (1, 0, CHAIN_ROW, CELL.0, CELL.1),
                (2, CELL.0, CHAIN_ROW, CELL.0, CELL.1)
            ]
        );
        // Two drawings share a row.
        let l = layout(&[
            drawing(),
            drawing(),
            Chart::Heat(Heatmap {
                title: String::new(),
                x_label: String::new(),
                y_label: String::new(),
                x: vec![0.0],
                y: vec![0.0],
                values: vec![vec![0.0]],
                categories: Vec::new(),
                value_label: String::new(),
                log_x: false,
                colour_limit: None,
            }),
        ]);
        assert_eq!(l.size, (2 * CELL.0, CHAIN_ROW + CELL.1));
        assert_eq!(l.slots[1], (1, CELL.0, 0, CELL.0, CHAIN_ROW));
    }

    fn patch(width: f64, height: f64) -> Chart {
        let nodes = vec![(0.0, 0.0), (width, height)];
        Chart::Network(crate::network::NetworkDrawing { nodes, ..Default::default() })
    }

    #[test]
    fn a_row_of_wide_network_drawings_is_as_tall_as_they_fill() {
        // 10 x 1 drawn, no arrows, margins of 5 % of 10 on each side: 11 x 2 at 800 - 24 pixels
        // wide is 141.1 pixels tall, plus 40 above and 12 below.
        let wide = 40 + 12 + (776.0_f64 * 2.0 / 11.0).ceil() as u32;
        assert_eq!(wide, 194);
        let l = layout(&[patch(10.0, 1.0), patch(10.0, 1.0), lines(), lines()]);
        assert_eq!(l.slots[1], (1, CELL.0, 0, CELL.0, wide));
        assert_eq!(l.slots[2], (2, 0, wide, CELL.0, CELL.1));
        assert_eq!(l.size, (2 * CELL.0, wide + CELL.1));
        // The taller of a pair sets the row; a square drawing keeps the cell.
        let l = layout(&[patch(10.0, 1.0), patch(1.0, 1.0)]);
        assert_eq!(l.size, (2 * CELL.0, CELL.1));
        // A single wide drawing: 1000 - 24 pixels wide.
        let single = 40 + 12 + (976.0_f64 * 2.0 / 11.0).ceil() as u32;
        assert_eq!(layout(&[patch(10.0, 1.0)]).size, (SINGLE.0, single));
    }
}
