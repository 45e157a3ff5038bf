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

/// Where the legend goes.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Legend {
    /// Inside the plotting area, upper right (plotters' default).
    #[default]
    Inside,
    /// In a panel to the right of the plotting area: it hides no data (the picture is
    /// widened by [`LEGEND_PANEL`] pixels).
    Outside,
}

/// Width of the legend panel of [`Legend::Outside`] \[px\].
pub const LEGEND_PANEL: u32 = 420;
/// Size of a plot without a legend panel \[px\].
const SIZE: (u32, u32) = (960, 640);

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
    /// Equal scales on both axes (one unit as long on x as on y: a polar or vector plot,
    /// whose directions and magnitudes must read true); the shorter range is widened about
    /// its centre.
    pub equal_axes: bool,
    /// Where the legend goes.
    pub legend: Legend,
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
        title: impl Into<String>, x_label: impl Into<String>, y_label: impl Into<String>,
    ) -> Self {
        Self {
            title: title.into(),
            x_label: x_label.into(),
            y_label: y_label.into(),
            series: Vec::new(),
            bands: Vec::new(),
            equal_axes: false,
            legend: Legend::Inside,
        }
    }

    /// Equal scales on both axes (builder style; [`LinePlot::equal_axes`]).
    pub fn with_equal_axes(mut self) -> Self {
        self.equal_axes = true;
        self
    }

    /// Place the legend (builder style).
    pub fn with_legend(mut self, legend: Legend) -> Self {
        self.legend = legend;
        self
    }

    /// Picture size \[px\].
    fn size(&self) -> (u32, u32) {
        match self.legend {
            Legend::Inside => SIZE,
            Legend::Outside => (SIZE.0 + LEGEND_PANEL, SIZE.1),
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
            let root = BitMapBackend::new(&png_part, self.size()).into_drawing_area();
            self.draw(&root).map_err(|m| CliError::write(&png, m))?;
            root.present()
                .map_err(|e| CliError::write(&png, e.to_string()))?;
        }
        std::fs::rename(&png_part, &png).map_err(|e| CliError::write(&png, e.to_string()))?;
        {
            let root = SVGBackend::new(&svg_part, self.size()).into_drawing_area();
            self.draw(&root).map_err(|m| CliError::write(&svg, m))?;
            root.present()
                .map_err(|e| CliError::write(&svg, e.to_string()))?;
        }
        std::fs::rename(&svg_part, &svg).map_err(|e| CliError::write(&svg, e.to_string()))?;
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

    fn draw<DB: DrawingBackend>(&self, whole: &DrawingArea<DB, Shift>) -> Result<(), String> {
        let e = |e: DrawingAreaErrorKind<DB::ErrorType>| e.to_string();
        whole.fill(&WHITE).map_err(e)?;
        let (root, panel) = match self.legend {
            Legend::Inside => (whole.clone(), None),
            Legend::Outside => {
                let (a, b) = whole.split_horizontally(SIZE.0);
                (a, Some(b))
            }
        };
        let ((mut x0, mut x1), (mut y0, mut y1)) = self.ranges();
        let build = |x0: f64, x1: f64, y0: f64, y1: f64| {
            ChartBuilder::on(&root)
                .caption(&self.title, (FONT, 24))
                .margin(16)
                .x_label_area_size(48)
                .y_label_area_size(80)
                .build_cartesian_2d(x0..x1, y0..y1)
        };
        if self.equal_axes {
            // the plotting area's size in pixels from a first build, then the shorter range
            // widened about its centre to the same metres (newtons, ...) per pixel
            let (w, h) = build(x0, x1, y0, y1)
                .map_err(e)?
                .plotting_area()
                .dim_in_pixel();
            root.fill(&WHITE).map_err(e)?;
            ((x0, x1), (y0, y1)) = equalised(((x0, x1), (y0, y1)), (w, h));
        }
        let mut chart = build(x0, x1, y0, y1).map_err(e)?;
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
        if let Some(panel) = panel {
            // one row per named band and series: its swatch and its name
            let font = (FONT, 14).into_font();
            let mut y = 40;
            let shade = RGBColor(230, 80, 60).mix(0.18);
            let rows = self
                .bands
                .iter()
                .map(|b| (b.name.as_str(), None))
                .chain(
                    self.series
                        .iter()
                        .enumerate()
                        .map(|(i, s)| (s.name.as_str(), Some((i, s.style)))),
                )
                .filter(|(name, _)| !name.is_empty());
            for (name, what) in rows {
                if y > SIZE.1 as i32 - 20 {
                    panel
                        .draw(&Text::new("…", (8, y), font.clone()))
                        .map_err(e)?;
                    break;
                }
                match what {
                    None => panel
                        .draw(&Rectangle::new([(8, y - 6), (32, y + 6)], shade.filled()))
                        .map_err(e)?,
                    Some((i, style)) => {
                        let color = Palette99::pick(i).to_rgba();
                        if style != Style::Points {
                            panel
                                .draw(&PathElement::new(
                                    vec![(8, y), (32, y)],
                                    color.stroke_width(2),
                                ))
                                .map_err(e)?;
                        }
                        if style != Style::Line {
                            panel
                                .draw(&Circle::new((20, y), 4, color.filled()))
                                .map_err(e)?;
                        }
                    }
                }
                let text: String = name.chars().take(56).collect();
                panel
                    .draw(&Text::new(text, (40, y - 8), font.clone()))
                    .map_err(e)?;
                y += 20;
            }
        } else if self.series.iter().any(|s| !s.name.is_empty()) || !self.bands.is_empty() {
            draw_legend(&mut chart, 15)?;
        }
        Ok(())
    }
}

/// Draw the legend of `chart` the plots' way: labels of `font_size` px in a box with a
/// translucent white background and a black border (errors as text).
pub fn draw_legend<'a, DB: DrawingBackend + 'a, CT: plotters::coord::CoordTranslate>(
    chart: &mut ChartContext<'a, DB, CT>, font_size: u32,
) -> Result<(), String> {
    chart
        .configure_series_labels()
        .label_font((FONT, font_size))
        .background_style(WHITE.mix(0.85))
        .border_style(BLACK)
        .draw()
        .map_err(|e| e.to_string())
}

/// The ranges `((x0, x1), (y0, y1))` with the shorter widened about its centre so that both
/// have the same units per pixel on a plotting area of `px` = (width, height) pixels.
fn equalised(r: ((f64, f64), (f64, f64)), px: (u32, u32)) -> ((f64, f64), (f64, f64)) {
    let ((x0, x1), (y0, y1)) = r;
    let (w, h) = (f64::from(px.0.max(1)), f64::from(px.1.max(1)));
    let per_px = ((x1 - x0) / w).max((y1 - y0) / h);
    let (cx, cy) = (0.5 * (x0 + x1), 0.5 * (y0 + y1));
    (
        (cx - 0.5 * per_px * w, cx + 0.5 * per_px * w),
        (cy - 0.5 * per_px * h, cy + 0.5 * per_px * h),
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The PNG bytes and SVG text of `plot` saved into a fresh folder `tag` (removed again).
    fn saved(plot: &LinePlot, tag: &str) -> (Vec<u8>, String) {
        let dir = crate::testing::fresh_dir("flowmbd-cli", tag);
        let files = plot.save(&dir.join("p")).unwrap();
        let png = std::fs::read(&files[0]).unwrap();
        let svg = std::fs::read_to_string(&files[1]).unwrap();
        std::fs::remove_dir_all(&dir).unwrap();
        (png, svg)
    }

    #[test]
    fn writes_png_and_svg_with_text() {
        let plot = LinePlot::new("sine", "t [s]", "x [m]")
            .with(Series::line(
                "sin",
                (0..50)
                    .map(|i| (i as f64 * 0.1, (i as f64 * 0.1).sin()))
                    .collect(),
            ))
            .with(Series::points("samples", vec![(0.0, 0.0), (1.0, 0.5)]));
        let (png, svg) = saved(&plot, "plot");
        assert_eq!(&png[1..4], b"PNG");
        assert!(
            svg.contains("<svg") && svg.contains("sin"),
            "legend text present in SVG"
        );
    }

    // a shaded band is drawn and labelled (its legend text is in the SVG)
    #[test]
    fn bands_are_shaded_and_labelled() {
        let plot = LinePlot::new("f", "v [m/s]", "f [Hz]")
            .with(Series::line("f1", vec![(0.0, 20.0), (50.0, 0.0)]))
            .with_band("unstable (v > c)", 40.0, 60.0);
        let (_, svg) = saved(&plot, "band");
        assert!(svg.contains("unstable (v &gt; c)") || svg.contains("unstable (v > c)"));
        // the band's fill colour (230, 80, 60): the band and its legend swatch
        assert!(
            svg.to_uppercase().matches("E6503C").count() >= 2,
            "a shaded rectangle and its legend entry"
        );
    }

    // Equal axes: the drawn x and y ranges have the same units per pixel (the data of a
    // 10:1 range are widened in y); an outside legend widens the picture by the panel and
    // writes every series' name.
    #[test]
    fn equal_axes_and_outside_legend() {
        let plot = LinePlot::new("polar", "F_x [N]", "F_y [N]")
            .with(Series::line("a", vec![(0.0, 0.0), (100.0, 10.0)]))
            .with(Series::points("b", vec![(50.0, 5.0)]))
            .with_equal_axes()
            .with_legend(Legend::Outside);
        let (_, svg) = saved(&plot, "eq");
        assert!(
            svg.contains(&format!("width=\"{}\"", SIZE.0 + LEGEND_PANEL)),
            "panel width"
        );
        assert!(
            svg.contains("\na\n</text>") && svg.contains("\nb\n</text>"),
            "legend names in the panel"
        );
        // equal units per pixel, the data range kept (definition)
        for (r, px) in [
            (((0.0, 100.0), (0.0, 10.0)), (800, 500)),
            (((-1.0, 1.0), (-50.0, 50.0)), (800, 500)),
        ] {
            let ((x0, x1), (y0, y1)) = equalised(r, px);
            let (sx, sy) = ((x1 - x0) / f64::from(px.0), (y1 - y0) / f64::from(px.1));
            assert!((sx / sy - 1.0).abs() < 1e-12, "{sx} {sy}");
            assert!(x0 <= r.0.0 && x1 >= r.0.1 && y0 <= r.1.0 && y1 >= r.1.1);
        }
    }

    #[test]
    fn degenerate_ranges_are_padded() {
        let plot =
            LinePlot::new("c", "x", "y").with(Series::line("c", vec![(1.0, 2.0), (1.0, 2.0)]));
        let ((x0, x1), (y0, y1)) = plot.ranges();
        assert!(x1 > x0 && y1 > y0);
    }
}
