//! Drawing a [`Figure`] to PNG and SVG with plotters, in pure Rust: the font (DejaVu Sans) is
//! embedded, so no system font or graphics library is needed.
//!
//! A figure is its caption above a grid of panels, one column for a single panel and two
//! otherwise: [`SINGLE`] pixels for one panel, [`CELL`] per panel for more. A line panel has its
//! title, axis labels with their units, one colour per series (solid, dashed, dots, or line and
//! dots as its [`Style`] says; on a log axis the points with `y <= 0` are left out and the line is
//! broken there) and a legend placed where it hides the least of the curves; a heat map has a
//! viridis colour bar beside it (continuous values) or one colour per category with their names.

use std::error::Error;
use std::ops::Range;
use std::path::{Path, PathBuf};
use std::sync::OnceLock;

use ab_glyph::{Font as _, FontRef, ScaleFont as _};
use image::ImageEncoder as _;
use plotters::coord::Shift;
use plotters::coord::ranged1d::{AsRangedCoord, ValueFormatter};
use plotters::element::DashedPathElement;
use plotters::element::{Drawable, PointCollection};
use plotters::prelude::*;
use plotters_backend::text_anchor::{HPos, VPos};
use plotters_backend::{BackendColor, BackendTextStyle, DrawingErrorKind};

use crate::data::{WriteError, category_index, file_stem, write_atomic};
use crate::model::{Chart, Figure, Heatmap, Panel, Style};

/// Why a figure could not be rendered.
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum RenderError {
    #[error("the embedded font could not be loaded")]
    Font,
    #[error("cannot draw {}: {message}", path.display())]
    Draw { path: PathBuf, message: String },
    #[error(transparent)]
    Write(#[from] WriteError),
}

/// Size of a figure with one panel; with more, each panel gets [`CELL`].
pub const SINGLE: (u32, u32) = (1000, 700);
/// Size of one panel of a figure with several.
pub const CELL: (u32, u32) = (800, 560);
/// Heat maps are drawn with at most this many cells along each axis (neighbouring cells are
/// merged), which keeps the SVG small; the CSV keeps every cell.
const MAX_CELLS: usize = 256;
/// Qualitative colours for series and categories (Tableau 10): distinct, readable on white.
const PALETTE: [RGBColor; 10] = [
    RGBColor(31, 119, 180),
    RGBColor(255, 127, 14),
    RGBColor(44, 160, 44),
    RGBColor(214, 39, 40),
    RGBColor(148, 103, 189),
    RGBColor(140, 86, 75),
    RGBColor(227, 119, 194),
    RGBColor(127, 127, 127),
    RGBColor(188, 189, 34),
    RGBColor(23, 190, 207),
];
/// Cells without a value (NaN, or not a category).
const MISSING: RGBColor = RGBColor(220, 220, 220);
const CAPTION_FONT: f64 = 17.0;
const TITLE_FONT: f64 = 21.0;
const LABEL_FONT: f64 = 17.0;
const TICK_FONT: f64 = 14.0;

type Drawn = Result<(), Box<dyn Error>>;

/// The figure with every text spelled so the font can draw it: plotters places no combining mark,
/// so `θ̄` (theta + combining macron) would show as a plain `θ`; it is written `θbar` instead.
fn drawable_text(figure: &Figure) -> Figure {
    let fix = |s: &str| s.replace("θ\u{304}", "θbar");
    let mut f = figure.clone();
    f.caption = fix(&f.caption);
    for panel in &mut f.panels {
        match panel {
            Chart::Lines(p) => {
                p.title = fix(&p.title);
                p.x_label = fix(&p.x_label);
                p.y_label = fix(&p.y_label);
                for s in &mut p.series {
                    s.name = fix(&s.name);
                }
            }
            Chart::Heat(h) => {
                h.title = fix(&h.title);
                h.x_label = fix(&h.x_label);
                h.y_label = fix(&h.y_label);
                h.value_label = fix(&h.value_label);
                for c in &mut h.categories {
                    *c = fix(c);
                }
            }
        }
    }
    f
}

/// Render `figure` to `dir/<name>.png` and `dir/<name>.svg`, `name` its label without `fig:`.
/// Each file is written atomically. Returns the two paths.
pub fn render(figure: &Figure, dir: &Path) -> Result<Vec<PathBuf>, RenderError> {
    register_fonts()?;
    let figure = &drawable_text(figure);
    let stem = file_stem(figure.label);
    let (png, svg) = (dir.join(format!("{stem}.png")), dir.join(format!("{stem}.svg")));
    let (width, panels_height) = panels_size(figure);
    let caption = wrap(&figure.caption, CAPTION_FONT, width - 40);
    let height = panels_height + caption_height(caption.len());
    let failed = |path: &Path| {
        let path = path.to_owned();
        move |e: Box<dyn Error>| RenderError::Draw { path, message: e.to_string() }
    };

    let mut pixels = vec![0u8; 3 * width as usize * height as usize];
    let root = Bitmap(BitMapBackend::with_buffer(&mut pixels, (width, height))).into_drawing_area();
    draw_figure(&root, figure, &caption).and_then(|()| Ok(root.present()?)).map_err(failed(&png))?;
    drop(root);
    let mut encoded = Vec::new();
    image::codecs::png::PngEncoder::new(&mut encoded)
        .write_image(&pixels, width, height, image::ColorType::Rgb8)
        .map_err(|e| failed(&png)(e.into()))?;
    write_atomic(&png, &encoded)?;

    let mut text = String::new();
    let root = SVGBackend::with_string(&mut text, (width, height)).into_drawing_area();
    draw_figure(&root, figure, &caption).and_then(|()| Ok(root.present()?)).map_err(failed(&svg))?;
    drop(root);
    write_atomic(&svg, text.as_bytes())?;
    Ok(vec![png, svg])
}

/// Register DejaVu Sans as plotters' `sans-serif`, once per process.
fn register_fonts() -> Result<(), RenderError> {
    static REGISTERED: OnceLock<bool> = OnceLock::new();
    let ok = REGISTERED.get_or_init(|| {
        let family = FontFamily::SansSerif.as_str();
        plotters::style::register_font(family, FontStyle::Normal, dejavu::sans::regular()).is_ok()
            && plotters::style::register_font(family, FontStyle::Bold, dejavu::sans::bold()).is_ok()
            && glyph_fonts().is_some()
    });
    if *ok { Ok(()) } else { Err(RenderError::Font) }
}

/// DejaVu Sans regular and bold, for [`Bitmap`]'s text.
fn glyph_fonts() -> Option<&'static (FontRef<'static>, FontRef<'static>)> {
    static FONTS: OnceLock<Option<(FontRef<'static>, FontRef<'static>)>> = OnceLock::new();
    FONTS
        .get_or_init(|| {
            let regular = FontRef::try_from_slice(dejavu::sans::regular()).ok()?;
            Some((regular, FontRef::try_from_slice(dejavu::sans::bold()).ok()?))
        })
        .as_ref()
}

/// plotters' bitmap backend with text drawn glyph by glyph at the glyph's own bounds. plotters
/// 0.3.7 puts each glyph's bounding box at the pen position, dropping the left side bearing, so
/// letters are unevenly spaced ("Syn th etic"). Everything else is the bitmap backend's; the
/// text's layout box and vertical placement are plotters' (baseline half the font size below the
/// top), so the charts are laid out as plotters lays them out.
struct Bitmap<'a>(BitMapBackend<'a>);

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
    fn draw_line<S: plotters_backend::BackendStyle>(
        &mut self,
        a: (i32, i32),
        b: (i32, i32),
        s: &S,
    ) -> Result<(), DrawingErrorKind<Self::ErrorType>> {
        self.0.draw_line(a, b, s)
    }
    fn draw_rect<S: plotters_backend::BackendStyle>(
        &mut self,
        a: (i32, i32),
        b: (i32, i32),
        s: &S,
        fill: bool,
    ) -> Result<(), DrawingErrorKind<Self::ErrorType>> {
        self.0.draw_rect(a, b, s, fill)
    }
    fn draw_path<S: plotters_backend::BackendStyle, I: IntoIterator<Item = (i32, i32)>>(
        &mut self,
        path: I,
        s: &S,
    ) -> Result<(), DrawingErrorKind<Self::ErrorType>> {
        self.0.draw_path(path, s)
    }
    fn draw_circle<S: plotters_backend::BackendStyle>(
        &mut self,
        c: (i32, i32),
        r: u32,
        s: &S,
        fill: bool,
    ) -> Result<(), DrawingErrorKind<Self::ErrorType>> {
        self.0.draw_circle(c, r, s, fill)
    }
    fn fill_polygon<S: plotters_backend::BackendStyle, I: IntoIterator<Item = (i32, i32)>>(
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
        let (Some((regular, bold)), true) = (glyph_fonts(), colour.alpha > 0.0) else { return Ok(()) };
        let font = if matches!(style.style(), plotters_backend::FontStyle::Bold) { bold } else { regular };
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
        let size = style.size() as f32;
        let font = font.as_scaled(size);
        let (mut pen, mut previous, mut coverage) = (0.0f32, None, Vec::new());
        for c in text.chars() {
            let id = font.glyph_id(c);
            pen += previous.map_or(0.0, |p| font.kern(p, id));
            let glyph = id.with_scale_and_position(font.scale(), ab_glyph::point(pen, size / 2.0));
            if let Some(outline) = font.outline_glyph(glyph) {
                let at = outline.px_bounds().min;
                outline.draw(|x, y, c| coverage.push((at.x as i32 + x as i32, at.y as i32 + y as i32, c)));
            }
            pen += font.h_advance(id);
            previous = Some(id);
        }
        let transform = style.transform();
        for (x, y, c) in coverage {
            let (x, y) = transform.transform(x + dx - min_x, y + dy - min_y);
            let colour = BackendColor { alpha: colour.alpha * f64::from(c), rgb: colour.rgb };
            self.0.draw_pixel((pos.0 + x, pos.1 + y), colour)?;
        }
        Ok(())
    }
}

fn font(size: f64, style: FontStyle) -> FontDesc<'static> {
    FontDesc::new(FontFamily::SansSerif, size, style)
}

/// Columns and rows of the panel grid.
fn grid(panels: usize) -> (usize, usize) {
    let cols = if panels <= 1 { 1 } else { 2 };
    (cols, panels.max(1).div_ceil(cols))
}

fn caption_height(lines: usize) -> u32 {
    if lines == 0 { 0 } else { 12 + 22 * lines as u32 }
}

/// Pixel size of the figure's grid of panels (the caption goes above).
fn panels_size(figure: &Figure) -> (u32, u32) {
    let (cols, rows) = grid(figure.panels.len());
    let (w, h) = if figure.panels.len() <= 1 { SINGLE } else { CELL };
    (w * cols as u32, h * rows as u32)
}

/// A panel title's font: bold, smaller for a title too wide for its panel.
fn title_font(title: &str, panel_width: u32) -> FontDesc<'static> {
    let room = f64::from(panel_width.saturating_sub(40).max(1));
    let width = font(TITLE_FONT, FontStyle::Bold).box_size(title).map_or(0.0, |(w, _)| f64::from(w));
    let size = if width > room { (TITLE_FONT * room / width).max(11.0) } else { TITLE_FONT };
    font(size, FontStyle::Bold)
}

/// Break `text` into lines at most `width` pixels wide in the caption font.
fn wrap(text: &str, size: f64, width: u32) -> Vec<String> {
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

fn draw_figure<DB: DrawingBackend>(
    root: &DrawingArea<DB, Shift>,
    figure: &Figure,
    caption: &[String],
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
    let (cols, rows) = grid(figure.panels.len());
    for (area, chart) in body.split_evenly((rows, cols)).iter().zip(&figure.panels) {
        match chart {
            Chart::Lines(panel) => draw_lines(area, panel)?,
            Chart::Heat(map) => draw_heatmap(area, map)?,
        }
    }
    Ok(())
}

/// The drawable stretches of a series: maximal runs of finite points (and, on a log axis,
/// positive `y`). A line is broken where a point is skipped.
fn runs(points: &[(f64, f64)], log_y: bool) -> Vec<Vec<(f64, f64)>> {
    let shown = |&(x, y): &(f64, f64)| x.is_finite() && y.is_finite() && (!log_y || y > 0.0);
    let mut runs = vec![Vec::new()];
    for p in points {
        match (shown(p), runs.last_mut()) {
            (true, Some(run)) => run.push(*p),
            (false, Some(run)) if !run.is_empty() => runs.push(Vec::new()),
            _ => {}
        }
    }
    runs.retain(|run| !run.is_empty());
    runs
}

/// `[min, max]` of the values, `None` if there are none.
fn extent(values: impl Iterator<Item = f64>) -> Option<(f64, f64)> {
    values.fold(None, |acc, v| match acc {
        None => Some((v, v)),
        Some((lo, hi)) => Some((lo.min(v), hi.max(v))),
    })
}

/// An axis range around `[lo, hi]` with 3% room on each side (a factor on a log axis); a single
/// value gets a unit-wide (a decade-wide) range, no values the range `[0, 1]` (`[1, 10]`).
fn padded(extent: Option<(f64, f64)>, log: bool) -> Range<f64> {
    match (extent, log) {
        (None, false) => 0.0..1.0,
        (None, true) => 1.0..10.0,
        (Some((lo, hi)), false) if lo == hi => lo - 0.5..hi + 0.5,
        (Some((lo, hi)), true) if lo == hi => lo / 10f64.sqrt()..hi * 10f64.sqrt(),
        (Some((lo, hi)), false) => lo - 0.03 * (hi - lo)..hi + 0.03 * (hi - lo),
        (Some((lo, hi)), true) => lo / (hi / lo).powf(0.03)..hi * (hi / lo).powf(0.03),
    }
}

/// A tick label: at most four significant digits, scientific notation for very large or small.
fn tick(v: &f64) -> String {
    let rounded: f64 = format!("{v:.3e}").parse().unwrap_or(*v);
    let a = rounded.abs();
    if a == 0.0 || (1e-3..1e5).contains(&a) { format!("{rounded}") } else { format!("{rounded:e}") }
}

/// Tick labels of a linear axis over `range`: [`tick`], with the rounding noise of a tick at
/// zero (`-2.2e-16`) shown as `0`.
fn linear_ticks(range: &Range<f64>) -> impl Fn(&f64) -> String + use<> {
    let noise = 1e-9 * (range.end - range.start).abs();
    move |v| if v.abs() < noise { "0".to_owned() } else { tick(v) }
}

fn draw_lines<DB: DrawingBackend>(area: &DrawingArea<DB, Shift>, panel: &Panel) -> Drawn
where
    DB::ErrorType: 'static,
{
    let series: Vec<_> = panel.series.iter().map(|s| runs(&s.points, panel.log_y)).collect();
    let points = || series.iter().flatten().flatten();
    let x = padded(extent(points().map(|p| p.0)), false);
    let y = padded(extent(points().map(|p| p.1)), panel.log_y);
    if panel.log_y {
        let log = y.start.log10()..y.end.log10();
        lines_chart(area, panel, &series, x, y.log_scale(), log, &tick)
    } else {
        lines_chart(area, panel, &series, x, y.clone(), y.clone(), &linear_ticks(&y))
    }
}

/// The line panel on the y axis `y_axis`, labelled by `y_ticks`; `y_linear` is its range where
/// the plot is linear (`log10 y` on a log axis), for placing the legend.
fn lines_chart<'a, DB, Y>(
    area: &'a DrawingArea<DB, Shift>,
    panel: &Panel,
    series: &[Vec<Vec<(f64, f64)>>],
    x: Range<f64>,
    y_axis: Y,
    y_linear: Range<f64>,
    y_ticks: &dyn Fn(&f64) -> String,
) -> Drawn
where
    DB: DrawingBackend + 'a,
    DB::ErrorType: 'static,
    Y: AsRangedCoord<Value = f64>,
    Y::CoordDescType: ValueFormatter<f64>,
{
    // The curves in plot fractions, for placing the legend.
    let fraction = |v: f64, r: &Range<f64>| (v - r.start) / (r.end - r.start);
    let curves: Vec<(Vec<(f64, f64)>, bool)> = series
        .iter()
        .zip(&panel.series)
        .flat_map(|(runs, s)| runs.iter().map(move |run| (run, s.style != Style::Points)))
        .map(|(run, line)| {
            let y = |v: f64| if panel.log_y { v.log10() } else { v };
            (run.iter().map(|&(px, py)| (fraction(px, &x), fraction(y(py), &y_linear))).collect(), line)
        })
        .collect();
    let x_ticks = linear_ticks(&x);
    let mut chart = ChartBuilder::on(area)
        .caption(&panel.title, title_font(&panel.title, area.dim_in_pixel().0))
        .margin(12)
        .x_label_area_size(55)
        .y_label_area_size(80)
        .build_cartesian_2d(x, y_axis)?;
    chart
        .configure_mesh()
        .light_line_style(WHITE.mix(0.0))
        .bold_line_style(BLACK.mix(0.12))
        .x_desc(panel.x_label.as_str())
        .y_desc(panel.y_label.as_str())
        .axis_desc_style(font(LABEL_FONT, FontStyle::Normal))
        .label_style(font(TICK_FONT, FontStyle::Normal))
        .x_label_formatter(&x_ticks)
        .y_label_formatter(y_ticks)
        .draw()?;
    for (i, (runs, s)) in series.iter().zip(&panel.series).enumerate() {
        let colour = PALETTE[i % PALETTE.len()];
        let line = colour.stroke_width(2);
        let dots = || runs.iter().flatten().map(|&p| Circle::new(p, 3, colour.filled()));
        // The first call draws the series' lines (or dots) and carries its legend entry.
        let drawn = match s.style {
            Style::Line | Style::LinePoints => {
                chart.draw_series(runs.iter().map(|r| PathElement::new(r.clone(), line)))?
            }
            Style::Dashed => {
                chart.draw_series(runs.iter().map(|r| DashedPathElement::new(r.clone(), 9, 6, line)))?
            }
            Style::Points => chart.draw_series(dots())?,
        };
        if !s.name.is_empty() {
            let style = s.style;
            drawn.label(s.name.as_str()).legend(move |at| LegendMark { at, style, colour });
        }
        if s.style == Style::LinePoints {
            chart.draw_series(dots())?;
        }
    }
    let names: Vec<&str> = panel.series.iter().map(|s| s.name.as_str()).filter(|n| !n.is_empty()).collect();
    if !names.is_empty() {
        let (w, h) = chart.plotting_area().dim_in_pixel();
        chart
            .configure_series_labels()
            .position(legend_position(&curves, (f64::from(w), f64::from(h)), &names))
            .margin(LEGEND_PADDING)
            .label_font(font(TICK_FONT, FontStyle::Normal))
            .background_style(WHITE.mix(0.85))
            .border_style(BLACK.mix(0.4))
            .draw()?;
    }
    Ok(())
}

/// The legend's sample of a series: a short line, dashed line, dot, or line with a dot, its left
/// end at `at`. (plotters' own composed elements carry the backend's type, which then has to be
/// `'static`; the bitmap backend borrows its pixel buffer.)
struct LegendMark {
    at: (i32, i32),
    style: Style,
    colour: RGBColor,
}

impl<'a> PointCollection<'a, (i32, i32)> for &'a LegendMark {
    type Point = &'a (i32, i32);
    type IntoIter = std::iter::Once<&'a (i32, i32)>;
    fn point_iter(self) -> Self::IntoIter {
        std::iter::once(&self.at)
    }
}

impl<DB: DrawingBackend> Drawable<DB> for LegendMark {
    fn draw<I: Iterator<Item = (i32, i32)>>(
        &self,
        mut pos: I,
        backend: &mut DB,
        _: (u32, u32),
    ) -> Result<(), DrawingErrorKind<DB::ErrorType>> {
        let Some((x, y)) = pos.next() else { return Ok(()) };
        let line = self.colour.stroke_width(2);
        let segments: &[(i32, i32)] = match self.style {
            Style::Line | Style::LinePoints => &[(0, 20)],
            Style::Dashed => &[(0, 7), (13, 20)],
            Style::Points => &[],
        };
        for &(from, to) in segments {
            backend.draw_line((x + from, y), (x + to, y), &line)?;
        }
        if matches!(self.style, Style::Points | Style::LinePoints) {
            backend.draw_circle((x + 10, y), 3, &self.colour.filled(), true)?;
        }
        Ok(())
    }
}

/// Inner padding of the legend box.
const LEGEND_PADDING: u32 = 8;

/// Where the legend hides the least of the curves: of eight places along the edges of the plot
/// (`plot` pixels), the one whose box covers the fewest samples of the curves, ties going to the
/// earlier place (upper right first). `curves` are in plot fractions (`0..1`, y up), each with
/// whether it is drawn as a line: lines are sampled every few pixels, dots where they are.
fn legend_position(
    curves: &[(Vec<(f64, f64)>, bool)],
    plot: (f64, f64),
    names: &[&str],
) -> SeriesLabelPosition {
    use SeriesLabelPosition::*;
    // The legend box as plotters lays it out: 30 pixels of marks, the names, the padding, 5
    // pixels from the plot's edges.
    let text = |n: &str| font(TICK_FONT, FontStyle::Normal).box_size(n).map_or(0.0, |(w, _)| f64::from(w));
    let pad = f64::from(2 * LEGEND_PADDING);
    let size = (
        30.0 + pad + names.iter().map(|n| text(n)).fold(0.0, f64::max),
        pad + 1.25 * TICK_FONT * names.len() as f64,
    );
    let places = [
        (UpperRight, 2, 0),
        (UpperLeft, 0, 0),
        (LowerRight, 2, 2),
        (LowerLeft, 0, 2),
        (MiddleRight, 2, 1),
        (MiddleLeft, 0, 1),
        (UpperMiddle, 1, 0),
        (LowerMiddle, 1, 2),
    ];
    let start = |at: u8, size: f64, extent: f64| match at {
        0 => 5.0,
        1 => 0.5 * (extent - size),
        _ => extent - size - 5.0,
    };
    let boxes: Vec<(f64, f64)> =
        places.iter().map(|&(_, h, v)| (start(h, size.0, plot.0), start(v, size.1, plot.1))).collect();
    let mut covered = [0usize; 8];
    let mut sample = |(x, y): (f64, f64)| {
        for (count, &(x0, y0)) in covered.iter_mut().zip(&boxes) {
            *count += usize::from((x0..=x0 + size.0).contains(&x) && (y0..=y0 + size.1).contains(&y));
        }
    };
    for (curve, line) in curves {
        let pixels: Vec<(f64, f64)> =
            curve.iter().map(|&(fx, fy)| (fx * plot.0, (1.0 - fy) * plot.1)).collect();
        pixels.iter().for_each(|&p| sample(p));
        for pair in pixels.windows(2).filter(|_| *line) {
            let (a, b) = (pair[0], pair[1]);
            let steps = ((b.0 - a.0).hypot(b.1 - a.1) / 4.0).ceil().clamp(1.0, 1000.0) as usize;
            (1..steps).for_each(|k| {
                let t = k as f64 / steps as f64;
                sample((a.0 + t * (b.0 - a.0), a.1 + t * (b.1 - a.1)));
            });
        }
    }
    let best = (0..places.len()).min_by_key(|&i| covered[i]).unwrap_or(0);
    places[best].0.clone()
}

/// Cell boundaries around the centres `c`: midpoints between neighbours, the ends as far out as
/// the nearest midpoint (a single centre gets a unit-wide cell).
fn edges(c: &[f64]) -> Vec<f64> {
    match c {
        [] => vec![0.0, 1.0],
        [only] => vec![only - 0.5, only + 0.5],
        _ => {
            let mid: Vec<f64> = c.windows(2).map(|w| 0.5 * (w[0] + w[1])).collect();
            let first = c[0] - (mid[0] - c[0]);
            let last = c[c.len() - 1] + (c[c.len() - 1] - mid[mid.len() - 1]);
            [vec![first], mid, vec![last]].concat()
        }
    }
}

/// The axis range of a map: its outer cell edges, without room around them.
fn cell_range(edges: &[f64]) -> Range<f64> {
    let (lo, hi) = extent(edges.iter().copied()).unwrap_or((0.0, 1.0));
    if lo < hi { lo..hi } else { lo - 0.5..hi + 0.5 }
}

/// Split `0..n` into consecutive groups, at most [`MAX_CELLS`] of them.
fn groups(n: usize) -> Vec<Range<usize>> {
    let size = n.div_ceil(MAX_CELLS).max(1);
    (0..n).step_by(size).map(|start| start..(start + size).min(n)).collect()
}

/// Consecutive ranges of one colour merged into one range.
fn merge_runs(cells: impl Iterator<Item = (Range<usize>, RGBColor)>) -> Vec<(Range<usize>, RGBColor)> {
    let mut runs: Vec<(Range<usize>, RGBColor)> = Vec::new();
    for (range, colour) in cells {
        match runs.last_mut() {
            Some((run, same)) if *same == colour && run.end == range.start => run.end = range.end,
            _ => runs.push((range, colour)),
        }
    }
    runs
}

/// The value drawn for a block of cells: the mean of its finite values (continuous map), or its
/// middle cell's value (categorical map).
fn block_value(map: &Heatmap, rows: &Range<usize>, cols: &Range<usize>) -> f64 {
    let value =
        |r: usize, c: usize| map.values.get(r).and_then(|row| row.get(c)).copied().unwrap_or(f64::NAN);
    if !map.categories.is_empty() {
        return value((rows.start + rows.end) / 2, (cols.start + cols.end) / 2);
    }
    let finite: Vec<f64> =
        rows.clone().flat_map(|r| cols.clone().map(move |c| value(r, c))).filter(|v| v.is_finite()).collect();
    if finite.is_empty() { f64::NAN } else { finite.iter().sum::<f64>() / finite.len() as f64 }
}

fn draw_heatmap<DB: DrawingBackend>(area: &DrawingArea<DB, Shift>, map: &Heatmap) -> Drawn
where
    DB::ErrorType: 'static,
{
    let categorical = !map.categories.is_empty();
    let side_width = if categorical {
        let widest =
            map.categories.iter().filter_map(|c| font(TICK_FONT, FontStyle::Normal).box_size(c).ok());
        (widest.map(|(w, _)| w).max().unwrap_or(0) + 60).clamp(120, 300)
    } else {
        150
    };
    let (main, side) = area.split_horizontally(area.dim_in_pixel().0.saturating_sub(side_width));
    let (xe, ye) = (&edges(&map.x), &edges(&map.y));
    let (x, y) = (cell_range(xe), cell_range(ye));
    let (x_ticks, y_ticks) = (linear_ticks(&x), linear_ticks(&y));
    let mut chart = ChartBuilder::on(&main)
        .caption(&map.title, title_font(&map.title, main.dim_in_pixel().0))
        .margin(12)
        .x_label_area_size(55)
        .y_label_area_size(80)
        .build_cartesian_2d(x, y)?;
    chart
        .configure_mesh()
        .disable_mesh()
        .x_desc(map.x_label.as_str())
        .y_desc(map.y_label.as_str())
        .axis_desc_style(font(LABEL_FONT, FontStyle::Normal))
        .label_style(font(TICK_FONT, FontStyle::Normal))
        .x_label_formatter(&x_ticks)
        .y_label_formatter(&y_ticks)
        .draw()?;

    let range = extent(map.values.iter().flatten().copied().filter(|v| v.is_finite()));
    let (lo, hi) = match range {
        Some((lo, hi)) if lo < hi => (lo, hi),
        Some((v, _)) => (v - 0.5, v + 0.5),
        None => (0.0, 1.0),
    };
    let colour = |v: f64| -> RGBColor {
        if categorical {
            category_index(v, map.categories.len()).map_or(MISSING, |i| PALETTE[i % PALETTE.len()])
        } else if v.is_finite() {
            ViridisRGB.get_color_normalized(v, lo, hi)
        } else {
            MISSING
        }
    };
    // Neighbouring cells of one colour in a row are drawn as one rectangle: much smaller SVGs of
    // phase diagrams.
    let (rows, cols) = (groups(map.y.len().min(map.values.len())), groups(map.x.len()));
    chart.draw_series(rows.iter().flat_map(|r| {
        merge_runs(cols.iter().map(|c| (c.clone(), colour(block_value(map, r, c))))).into_iter().map(
            move |(c, colour)| {
                Rectangle::new([(xe[c.start], ye[r.start]), (xe[c.end], ye[r.end])], colour.filled())
            },
        )
    }))?;

    // The side panel lines up with the plot area of the map.
    let (_, plot_y) = chart.plotting_area().get_pixel_range();
    let side_top = side.get_base_pixel().1;
    let top = (plot_y.start - side_top).max(0);
    let bottom = (side.dim_in_pixel().1 as i32 - (plot_y.end - side_top)).max(0);
    let side = side.margin(top, bottom, 8, 20);
    if categorical {
        category_legend(&side, &map.categories)
    } else {
        colour_bar(&side, &map.value_label, lo..hi)
    }
}

/// A vertical viridis bar from `range.start` (bottom) to `range.end`, with ticks and `label`.
fn colour_bar<DB: DrawingBackend>(area: &DrawingArea<DB, Shift>, label: &str, range: Range<f64>) -> Drawn
where
    DB::ErrorType: 'static,
{
    let (lo, hi) = (range.start, range.end);
    let mut bar = ChartBuilder::on(area)
        .set_label_area_size(LabelAreaPosition::Right, 80)
        .build_cartesian_2d(0.0..1.0, range.clone())?;
    let ticks = linear_ticks(&range);
    bar.configure_mesh()
        .disable_x_axis()
        .disable_mesh()
        .y_desc(label)
        .axis_desc_style(font(LABEL_FONT, FontStyle::Normal))
        .label_style(font(TICK_FONT, FontStyle::Normal))
        .y_label_formatter(&ticks)
        .draw()?;
    const STEPS: usize = 128;
    let at = |i: usize| lo + (hi - lo) * i as f64 / STEPS as f64;
    bar.draw_series((0..STEPS).map(|i| {
        let colour: RGBColor = ViridisRGB.get_color_normalized(at(i) + 0.5 * (at(1) - lo), lo, hi);
        Rectangle::new([(0.0, at(i)), (1.0, at(i + 1))], colour.filled())
    }))?;
    bar.draw_series(std::iter::once(Rectangle::new([(0.0, lo), (1.0, hi)], BLACK.stroke_width(1))))?;
    Ok(())
}

/// One coloured square and name per category, top to bottom.
fn category_legend<DB: DrawingBackend>(area: &DrawingArea<DB, Shift>, categories: &[String]) -> Drawn
where
    DB::ErrorType: 'static,
{
    for (i, name) in categories.iter().enumerate() {
        let top = 4 + 26 * i as i32;
        let swatch = [(0, top), (18, top + 18)];
        area.draw(&Rectangle::new(swatch, PALETTE[i % PALETTE.len()].filled()))?;
        area.draw(&Rectangle::new(swatch, BLACK.mix(0.5).stroke_width(1)))?;
        area.draw(&Text::new(name.as_str(), (26, top + 1), font(TICK_FONT, FontStyle::Normal)))?;
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn lines_break_at_points_that_cannot_be_drawn() {
        let points = [(0.0, 1.0), (1.0, -1.0), (2.0, 2.0), (3.0, 3.0), (f64::NAN, 1.0)];
        assert_eq!(runs(&points, true), vec![vec![(0.0, 1.0)], vec![(2.0, 2.0), (3.0, 3.0)]]);
        assert_eq!(runs(&points, false).len(), 1);
    }

    #[test]
    fn cells_surround_their_centres() {
        assert_eq!(edges(&[0.0, 1.0, 3.0]), vec![-0.5, 0.5, 2.0, 4.0]);
        assert_eq!(edges(&[2.0]), vec![1.5, 2.5]);
        let g = groups(1000);
        assert!(g.len() <= MAX_CELLS && g[0] == (0..4) && g.last().unwrap().end == 1000);
        assert_eq!(groups(3), vec![0..1, 1..2, 2..3]);
        let (a, b) = (PALETTE[0], PALETTE[1]);
        let merged = merge_runs([(0..1, a), (1..2, a), (2..4, b), (4..5, a)].into_iter());
        assert_eq!(merged, vec![(0..2, a), (2..4, b), (4..5, a)]);
    }

    #[test]
    fn ticks_are_short() {
        assert_eq!(tick(&0.30000000000000004), "0.3");
        assert_eq!(tick(&1.0e-5), "1e-5");
        assert_eq!(tick(&123456.0), "1.235e5");
        assert_eq!(tick(&-2.0), "-2");
    }

    #[test]
    fn panels_are_laid_out_in_at_most_two_columns() {
        assert_eq!(grid(1), (1, 1));
        assert_eq!(grid(2), (2, 1));
        assert_eq!(grid(5), (2, 3));
    }
}
