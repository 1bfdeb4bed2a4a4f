//! PNG plots of the sweeps, drawn with `plotters` on its bitmap backend.
//!
//! Text needs a TrueType font. plotters is built without system font
//! libraries (no fontconfig/freetype), so a TTF is loaded at run time and
//! registered as "sans-serif": `$ASTER_FONT` if set, else DejaVu Sans from
//! Debian's fonts-dejavu-core (installed by scripts/setup.sh).
//!
//! Log axes are drawn as linear axes of log10 values with labels written
//! back as powers of ten: one code path serves all four axis combinations.

use std::path::Path;
use std::sync::OnceLock;

use plotters::prelude::*;

/// The family name under which [`ensure_font`] registers the font; every
/// PNG of aster (sweeps, `aster plot`) draws its text with it.
pub const FONT: &str = "sans-serif";
const FONT_CANDIDATES: &[&str] = &[
    "/usr/share/fonts/truetype/dejavu/DejaVuSans.ttf",
    "/usr/share/fonts/TTF/DejaVuSans.ttf",
    "/usr/share/fonts/dejavu/DejaVuSans.ttf",
    "/usr/share/fonts/truetype/dejavu-sans/DejaVuSans.ttf",
];

/// Registers the font once; the error says how to get one.
pub fn ensure_font() -> Result<(), String> {
    static LOADED: OnceLock<Result<(), String>> = OnceLock::new();
    LOADED
        .get_or_init(|| {
            let from_env = std::env::var_os("ASTER_FONT").map(std::path::PathBuf::from);
            let candidates: Vec<std::path::PathBuf> = from_env
                .into_iter()
                .chain(FONT_CANDIDATES.iter().map(std::path::PathBuf::from))
                .collect();
            for p in &candidates {
                if let Ok(bytes) = std::fs::read(p) {
                    // plotters keeps fonts for the life of the process.
                    let bytes: &'static [u8] = Box::leak(bytes.into_boxed_slice());
                    return plotters::style::register_font(FONT, FontStyle::Normal, bytes)
                        .map_err(|_| format!("'{}' is not a usable TrueType font", p.display()));
                }
            }
            Err(format!(
                "no TrueType font for the plots (looked for {}); install fonts-dejavu-core \
                 (scripts/setup.sh does) or set ASTER_FONT to a .ttf file",
                candidates
                    .iter()
                    .map(|p| p.display().to_string())
                    .collect::<Vec<_>>()
                    .join(", ")
            ))
        })
        .clone()
}

/// How a series is drawn.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Style {
    Line,
    Points,
    /// Points joined by a line.
    LinePoints,
    /// A dashed-looking thin line (fits, references).
    Thin,
}

/// A named series.
#[derive(Debug, Clone)]
pub struct Series {
    pub label: String,
    pub points: Vec<(f64, f64)>,
    pub style: Style,
}

/// What to draw.
#[derive(Debug, Clone)]
pub struct Figure {
    pub title: String,
    pub x_label: String,
    pub y_label: String,
    pub log_x: bool,
    pub log_y: bool,
    pub series: Vec<Series>,
    /// Text labels at data points (e.g. "5x20 1us").
    pub annotations: Vec<((f64, f64), String)>,
    /// A fixed y range (axis units, before any log): values outside are
    /// drawn clamped to its edges, to zoom on the small curves.
    pub y_range: Option<(f64, f64)>,
}

fn color(i: usize) -> RGBColor {
    const C: [RGBColor; 8] = [
        RGBColor(31, 119, 180),
        RGBColor(214, 39, 40),
        RGBColor(44, 160, 44),
        RGBColor(255, 127, 14),
        RGBColor(148, 103, 189),
        RGBColor(140, 86, 75),
        RGBColor(23, 190, 207),
        RGBColor(127, 127, 127),
    ];
    C[i % C.len()]
}

fn axis_value(v: f64, log: bool) -> Option<f64> {
    if !v.is_finite() {
        return None;
    }
    if log {
        (v > 0.0).then(|| v.log10())
    } else {
        Some(v)
    }
}

/// A tick or colour-bar label: three significant digits, powers of ten on
/// log axes.
pub fn tick_label(v: f64, log: bool) -> String {
    let x = if log { 10f64.powf(v) } else { v };
    if log && (v - v.round()).abs() < 1e-9 {
        return format!("1e{}", v.round() as i64);
    }
    if x == 0.0 {
        return "0".into();
    }
    if x.abs() >= 1e4 || x.abs() < 1e-3 {
        return format!("{x:.2e}");
    }
    // Three significant digits, without trailing zeros.
    let decimals = (2 - x.abs().log10().floor() as i32).max(0) as usize;
    let s = format!("{x:.decimals$}");
    if s.contains('.') {
        s.trim_end_matches('0').trim_end_matches('.').to_string()
    } else {
        s
    }
}

/// A series with its colour index and its points in axis space.
type Placed<'a> = (usize, &'a Series, Vec<(f64, f64)>);

/// Draws `fig` into a PNG of `size` pixels.
pub fn draw(fig: &Figure, path: &Path, size: (u32, u32)) -> Result<(), String> {
    ensure_font()?;
    let err = |e: &dyn std::fmt::Display| format!("plot '{}': {e}", path.display());
    // Data in axis space; non-finite (and non-positive on log axes) points
    // are left out of the plot, never drawn as garbage.
    let series: Vec<Placed> = fig
        .series
        .iter()
        .enumerate()
        .map(|(i, s)| {
            let pts = s
                .points
                .iter()
                .filter_map(|&(x, y)| {
                    let y = match fig.y_range {
                        Some((lo, hi)) if y.is_finite() => y.clamp(lo, hi),
                        _ => y,
                    };
                    Some((axis_value(x, fig.log_x)?, axis_value(y, fig.log_y)?))
                })
                .collect();
            (i, s, pts)
        })
        .collect();
    let all: Vec<(f64, f64)> = series.iter().flat_map(|s| s.2.iter().copied()).collect();
    let (mut x0, mut x1, mut y0, mut y1) = all.iter().fold(
        (
            f64::INFINITY,
            f64::NEG_INFINITY,
            f64::INFINITY,
            f64::NEG_INFINITY,
        ),
        |(a, b, c, d), &(x, y)| (a.min(x), b.max(x), c.min(y), d.max(y)),
    );
    if all.is_empty() {
        (x0, x1, y0, y1) = (0.0, 1.0, 0.0, 1.0);
    }
    let pad = |lo: f64, hi: f64| {
        let span = if hi > lo { hi - lo } else { lo.abs().max(1.0) };
        (lo - 0.06 * span, hi + 0.06 * span)
    };
    let (x0, x1) = pad(x0, x1);
    let (y0, y1) = match fig.y_range {
        Some((lo, hi)) if hi > lo => match (axis_value(lo, fig.log_y), axis_value(hi, fig.log_y)) {
            (Some(a), Some(b)) => pad(a, b),
            _ => pad(y0, y1),
        },
        _ => pad(y0, y1),
    };

    let root = BitMapBackend::new(path, size).into_drawing_area();
    root.fill(&WHITE).map_err(|e| err(&e))?;
    let mut chart = ChartBuilder::on(&root)
        .caption(&fig.title, (FONT, 22))
        .margin(14)
        .x_label_area_size(48)
        .y_label_area_size(78)
        .build_cartesian_2d(x0..x1, y0..y1)
        .map_err(|e| err(&e))?;
    let (lx, ly) = (fig.log_x, fig.log_y);
    let fx = move |v: &f64| tick_label(*v, lx);
    let fy = move |v: &f64| tick_label(*v, ly);
    chart
        .configure_mesh()
        .x_desc(&fig.x_label)
        .y_desc(&fig.y_label)
        .x_label_formatter(&fx)
        .y_label_formatter(&fy)
        .label_style((FONT, 14))
        .axis_desc_style((FONT, 16))
        .light_line_style(RGBColor(235, 235, 235))
        .draw()
        .map_err(|e| err(&e))?;
    for (i, s, pts) in &series {
        let c = color(*i);
        let line = matches!(s.style, Style::Line | Style::LinePoints | Style::Thin);
        let dots = matches!(s.style, Style::Points | Style::LinePoints);
        let width = if s.style == Style::Thin { 1 } else { 2 };
        if line {
            let anno = chart
                .draw_series(LineSeries::new(pts.iter().copied(), c.stroke_width(width)))
                .map_err(|e| err(&e))?;
            anno.label(s.label.clone()).legend(move |(x, y)| {
                PathElement::new(vec![(x, y), (x + 18, y)], c.stroke_width(2))
            });
        }
        if dots {
            let anno = chart
                .draw_series(pts.iter().map(|&p| Circle::new(p, 4, c.filled())))
                .map_err(|e| err(&e))?;
            if !line {
                anno.label(s.label.clone())
                    .legend(move |(x, y)| Circle::new((x + 9, y), 4, c.filled()));
            }
        }
    }
    let notes: Vec<((f64, f64), &str)> = fig
        .annotations
        .iter()
        .filter_map(|((x, y), t)| Some(((axis_value(*x, lx)?, axis_value(*y, ly)?), t.as_str())))
        .collect();
    chart
        .draw_series(notes.iter().map(|&(p, t)| {
            EmptyElement::at(p) + Text::new(t.to_string(), (6, -14), (FONT, 12).into_font())
        }))
        .map_err(|e| err(&e))?;
    chart
        .configure_series_labels()
        .background_style(WHITE.mix(0.85))
        .border_style(BLACK)
        .label_font((FONT, 14))
        .position(SeriesLabelPosition::UpperRight)
        .draw()
        .map_err(|e| err(&e))?;
    root.present().map_err(|e| err(&e))?;
    Ok(())
}
