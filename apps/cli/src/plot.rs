//! Line and scatter plots written as PNG and SVG (plotters, with an embedded DejaVu font so that
//! no system font is needed).

use crate::error::CliError;
use crate::output::part_path;
use plotters::coord::Shift;
use plotters::prelude::*;
use std::path::{Path, PathBuf};
use std::sync::Once;

/// How a series is drawn.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Style {
    /// A polyline through the points.
    Line,
    /// Markers only.
    Points,
    /// A polyline with markers.
    LinePoints,
}

/// One named data series.
#[derive(Debug, Clone)]
pub struct Series {
    /// Legend label.
    pub name: String,
    /// (x, y) points.
    pub points: Vec<(f64, f64)>,
    /// Drawing style.
    pub style: Style,
}

impl Series {
    /// A line series.
    pub fn line(name: impl Into<String>, points: Vec<(f64, f64)>) -> Self {
        Self {
            name: name.into(),
            points,
            style: Style::Line,
        }
    }

    /// A marker-only series.
    pub fn points(name: impl Into<String>, points: Vec<(f64, f64)>) -> Self {
        Self {
            name: name.into(),
            points,
            style: Style::Points,
        }
    }
}

/// A shaded interval of the x axis (e.g. an unstable speed range), drawn behind the series.
#[derive(Debug, Clone)]
pub struct Band {
    /// Legend label.
    pub name: String,
    /// From `x.0` to `x.1` (clipped to the plotted range).
    pub x: (f64, f64),
}

/// A 2D plot with axis labels and a legend.
#[derive(Debug, Clone)]
pub struct LinePlot {
    /// Caption.
    pub title: String,
    /// x-axis label (with unit).
    pub x_label: String,
    /// y-axis label (with unit).
    pub y_label: String,
    /// The series.
    pub series: Vec<Series>,
    /// Shaded x intervals.
    pub bands: Vec<Band>,
}

/// Font family name of the embedded font (after [`register_font`]).
pub const FONT: &str = "sans-serif";
static REGISTER_FONT: Once = Once::new();

/// Register the embedded DejaVu font under [`FONT`] (idempotent); call before drawing text
/// with plotters directly.
pub fn register_font() {
    REGISTER_FONT.call_once(|| {
        // The embedded font is valid TrueType; registration cannot fail for it, and if it did the
        // plot would be drawn without text rather than abort the study.
        let _ = plotters::style::register_font(FONT, FontStyle::Normal, dejavu::sans::regular());
    });
}

impl LinePlot {
    /// A plot with labels and no series yet.
    pub fn new(
        title: impl Into<String>,
        x_label: impl Into<String>,
        y_label: impl Into<String>,
    ) -> Self {
        Self {
            title: title.into(),
            x_label: x_label.into(),
            y_label: y_label.into(),
            series: Vec::new(),
            bands: Vec::new(),
        }
    }

    /// Shade the x interval `[x0, x1]` behind the series, labelled `name` (builder style).
    pub fn with_band(mut self, name: impl Into<String>, x0: f64, x1: f64) -> Self {
        self.bands.push(Band {
            name: name.into(),
            x: (x0.min(x1), x0.max(x1)),
        });
        self
    }

    /// Add a series (builder style).
    pub fn with(mut self, series: Series) -> Self {
        self.series.push(series);
        self
    }

    /// Write `<stem>.png` and `<stem>.svg`; returns both paths.
    pub fn save(&self, stem: &Path) -> Result<Vec<PathBuf>, CliError> {
        register_font();
        let png = stem.with_extension("png");
        let svg = stem.with_extension("svg");
        // drawn under a temporary name, renamed when complete (crate::output::write_atomic)
        let (png_part, svg_part) = (part_path(&png, true), part_path(&svg, true));
        {
            let root = BitMapBackend::new(&png_part, (960, 640)).into_drawing_area();
            self.draw(&root).map_err(|m| err(&png, m))?;
            root.present().map_err(|e| err(&png, e.to_string()))?;
        }
        std::fs::rename(&png_part, &png).map_err(|e| err(&png, e.to_string()))?;
        {
            let root = SVGBackend::new(&svg_part, (960, 640)).into_drawing_area();
            self.draw(&root).map_err(|m| err(&svg, m))?;
            root.present().map_err(|e| err(&svg, e.to_string()))?;
        }
        std::fs::rename(&svg_part, &svg).map_err(|e| err(&svg, e.to_string()))?;
        Ok(vec![png, svg])
    }

    fn ranges(&self) -> ((f64, f64), (f64, f64)) {
        let finite = self
            .series
            .iter()
            .flat_map(|s| s.points.iter())
            .filter(|(x, y)| x.is_finite() && y.is_finite());
        let (mut x0, mut x1, mut y0, mut y1) = (
            f64::INFINITY,
            f64::NEG_INFINITY,
            f64::INFINITY,
            f64::NEG_INFINITY,
        );
        for &(x, y) in finite {
            x0 = x0.min(x);
            x1 = x1.max(x);
            y0 = y0.min(y);
            y1 = y1.max(y);
        }
        if !x0.is_finite() {
            return ((0.0, 1.0), (0.0, 1.0));
        }
        let pad = |a: f64, b: f64, frac: f64| {
            let span = b - a;
            let d = if span > 0.0 {
                span * frac
            } else {
                a.abs().max(1.0) * 0.05
            };
            (a - d, b + d)
        };
        let xr = if x1 > x0 { (x0, x1) } else { pad(x0, x1, 0.0) };
        (xr, pad(y0, y1, 0.05))
    }

    fn draw<DB: DrawingBackend>(&self, root: &DrawingArea<DB, Shift>) -> Result<(), String> {
        let e = |e: DrawingAreaErrorKind<DB::ErrorType>| e.to_string();
        root.fill(&WHITE).map_err(e)?;
        let ((x0, x1), (y0, y1)) = self.ranges();
        let mut chart = ChartBuilder::on(root)
            .caption(&self.title, (FONT, 24))
            .margin(16)
            .x_label_area_size(48)
            .y_label_area_size(80)
            .build_cartesian_2d(x0..x1, y0..y1)
            .map_err(e)?;
        chart
            .configure_mesh()
            .x_desc(&self.x_label)
            .y_desc(&self.y_label)
            .label_style((FONT, 15))
            .axis_desc_style((FONT, 17))
            .draw()
            .map_err(e)?;
        let shade = RGBColor(230, 80, 60).mix(0.18);
        for b in &self.bands {
            let (a, z) = (b.x.0.max(x0), b.x.1.min(x1));
            if a < z {
                chart
                    .draw_series(std::iter::once(Rectangle::new(
                        [(a, y0), (z, y1)],
                        shade.filled(),
                    )))
                    .map_err(e)?
                    .label(b.name.clone())
                    .legend(move |(x, y)| {
                        Rectangle::new([(x, y - 6), (x + 20, y + 6)], shade.filled())
                    });
            }
        }
        for (i, s) in self.series.iter().enumerate() {
            let color = Palette99::pick(i).to_rgba();
            let pts = s
                .points
                .iter()
                .copied()
                .filter(|(x, y)| x.is_finite() && y.is_finite());
            let anno = match s.style {
                Style::Line => chart
                    .draw_series(LineSeries::new(pts, color.stroke_width(2)))
                    .map_err(e)?,
                Style::Points => chart
                    .draw_series(pts.map(|p| Circle::new(p, 4, color.filled())))
                    .map_err(e)?,
                Style::LinePoints => chart
                    .draw_series(LineSeries::new(pts, color.stroke_width(2)).point_size(4))
                    .map_err(e)?,
            };
            anno.label(s.name.clone()).legend(move |(x, y)| {
                PathElement::new(vec![(x, y), (x + 20, y)], color.stroke_width(2))
            });
        }
        if self.series.iter().any(|s| !s.name.is_empty()) || !self.bands.is_empty() {
            chart
                .configure_series_labels()
                .label_font((FONT, 15))
                .background_style(WHITE.mix(0.85))
                .border_style(BLACK)
                .draw()
                .map_err(e)?;
        }
        Ok(())
    }
}

fn err(path: &Path, message: String) -> CliError {
    CliError::Write {
        path: path.to_path_buf(),
        message,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn writes_png_and_svg_with_text() {
        let dir = std::env::temp_dir().join(format!("flowmbd-cli-plot-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let plot = LinePlot::new("sine", "t [s]", "x [m]")
            .with(Series::line(
                "sin",
                (0..50)
                    .map(|i| (i as f64 * 0.1, (i as f64 * 0.1).sin()))
                    .collect(),
            ))
            .with(Series::points("samples", vec![(0.0, 0.0), (1.0, 0.5)]));
        let files = plot.save(&dir.join("p")).unwrap();
        let png = std::fs::read(&files[0]).unwrap();
        assert_eq!(&png[1..4], b"PNG");
        let svg = std::fs::read_to_string(&files[1]).unwrap();
        assert!(
            svg.contains("<svg") && svg.contains("sin"),
            "legend text present in SVG"
        );
        std::fs::remove_dir_all(&dir).unwrap();
    }

    // a shaded band is drawn and labelled (its legend text is in the SVG)
    #[test]
    fn bands_are_shaded_and_labelled() {
        let dir = std::env::temp_dir().join(format!("flowmbd-cli-band-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let plot = LinePlot::new("f", "v [m/s]", "f [Hz]")
            .with(Series::line("f1", vec![(0.0, 20.0), (50.0, 0.0)]))
            .with_band("unstable (v > c)", 40.0, 60.0);
        let files = plot.save(&dir.join("b")).unwrap();
        let svg = std::fs::read_to_string(&files[1]).unwrap();
        assert!(svg.contains("unstable (v &gt; c)") || svg.contains("unstable (v > c)"));
        // the band's fill colour (230, 80, 60): the band and its legend swatch
        assert!(
            svg.to_uppercase().matches("E6503C").count() >= 2,
            "a shaded rectangle and its legend entry"
        );
        std::fs::remove_dir_all(&dir).unwrap();
    }

    #[test]
    fn degenerate_ranges_are_padded() {
        let plot =
            LinePlot::new("c", "x", "y").with(Series::line("c", vec![(1.0, 2.0), (1.0, 2.0)]));
        let ((x0, x1), (y0, y1)) = plot.ranges();
        assert!(x1 > x0 && y1 > y0);
    }
}
