//! Speed × frequency maps of the cleat-test spectra (Ribaric Figs. 8-7, 8-8, 8-14): a contour
//! (colour) map and a waterfall plot, each written as PNG and SVG with plotters.

use flowmbd_cli::StudyError;
use flowmbd_cli::plot::{FONT, draw_legend, register_font};
use plotters::coord::Shift;
use plotters::coord::types::RangedCoordf64;
use plotters::prelude::*;
use std::path::Path;

/// Spectrum amplitudes on a speed × frequency grid.
pub struct SpectrumMap<'a> {
    /// Title of the plot.
    pub title: String,
    /// Speeds \[km/h\] (rows).
    pub speeds: &'a [f64],
    /// Frequencies \[Hz\] (columns).
    pub freqs: &'a [f64],
    /// Amplitudes \[N\], `amp[row][col]`.
    pub amp: &'a [Vec<f64>],
}

fn io(path: &Path, m: impl ToString) -> StudyError {
    StudyError::numerical(format!("{}: {}", path.display(), m.to_string()))
}

/// Colour of a normalised value `t ∈ [0, 1]` (blue → red).
fn colour(t: f64) -> RGBColor {
    let t = t.clamp(0.0, 1.0);
    let HSLColor(h, s, l) = HSLColor(0.66 * (1.0 - t), 0.9, 0.25 + 0.35 * t.sqrt());
    let c = HSLColor(h, s, l).to_rgba();
    RGBColor(c.0, c.1, c.2)
}

/// A chart with frequency \[Hz\] across and speed \[km/h\] up.
type SpeedFrequencyChart<'a, DB> =
    ChartContext<'a, DB, Cartesian2d<RangedCoordf64, RangedCoordf64>>;

impl SpectrumMap<'_> {
    fn max_amp(&self) -> f64 {
        self.amp
            .iter()
            .flatten()
            .copied()
            .filter(|a| a.is_finite())
            .fold(0.0, f64::max)
            .max(1e-300)
    }

    fn steps(&self) -> (f64, f64) {
        let df = if self.freqs.len() > 1 {
            self.freqs[1] - self.freqs[0]
        } else {
            1.0
        };
        let dv = if self.speeds.len() > 1 {
            (self.speeds[self.speeds.len() - 1] - self.speeds[0]) / (self.speeds.len() - 1) as f64
        } else {
            10.0
        };
        (df, dv)
    }

    /// Frequency axis range \[Hz\]: first to last frequency.
    fn freq_range(&self) -> (f64, f64) {
        (
            self.freqs.first().copied().unwrap_or(0.0),
            self.freqs.last().copied().unwrap_or(1.0),
        )
    }

    /// Speed axis range \[km/h\]: half a speed step `dv` below the first speed to `above`
    /// steps above the last.
    fn speed_range(&self, dv: f64, above: f64) -> (f64, f64) {
        (
            self.speeds.first().copied().unwrap_or(0.0) - 0.5 * dv,
            self.speeds.last().copied().unwrap_or(1.0) + above * dv,
        )
    }

    /// The frame shared by the contour map and the waterfall on `area`: frequency \[Hz\]
    /// across, speed \[km/h\] up from half a speed step below the first speed to `above`
    /// steps above the last (axis title `speed_axis`), the same caption font, margin, label
    /// areas and label styles; a grid when `grid`.
    fn frame<'b, DB: DrawingBackend>(
        &self, area: &'b DrawingArea<DB, Shift>, caption: &str, above: f64, speed_axis: &str,
        grid: bool,
    ) -> Result<SpeedFrequencyChart<'b, DB>, String> {
        let e = |e: DrawingAreaErrorKind<DB::ErrorType>| e.to_string();
        let (_, dv) = self.steps();
        let (f0, f1) = self.freq_range();
        let (v0, v1) = self.speed_range(dv, above);
        let mut chart = ChartBuilder::on(area)
            .caption(caption, (FONT, 22))
            .margin(16)
            .x_label_area_size(48)
            .y_label_area_size(70)
            .build_cartesian_2d(f0..f1, v0..v1)
            .map_err(e)?;
        let mut mesh = chart.configure_mesh();
        if !grid {
            mesh.disable_mesh();
        }
        mesh.x_desc("f [Hz]")
            .y_desc(speed_axis)
            .label_style((FONT, 15))
            .axis_desc_style((FONT, 17))
            .draw()
            .map_err(e)?;
        Ok(chart)
    }

    fn draw_contour<DB: DrawingBackend>(
        &self, root: &DrawingArea<DB, Shift>,
    ) -> Result<(), String> {
        let e = |e: DrawingAreaErrorKind<DB::ErrorType>| e.to_string();
        let (df, dv) = self.steps();
        let (main, bar) = root.split_horizontally(860);
        let mut chart = self.frame(&main, &self.title, 0.5, "v [km/h]", false)?;
        let amax = self.max_amp();
        let cells = self.speeds.iter().enumerate().flat_map(|(i, &v)| {
            self.freqs.iter().enumerate().map(move |(j, &f)| {
                let t = self.amp[i][j] / amax;
                Rectangle::new(
                    [(f - 0.5 * df, v - 0.5 * dv), (f + 0.5 * df, v + 0.5 * dv)],
                    colour(t).filled(),
                )
            })
        });
        chart.draw_series(cells).map_err(e)?;
        // colour bar
        let mut cb = ChartBuilder::on(&bar)
            .margin_top(60)
            .margin_bottom(64)
            .margin_right(8)
            .y_label_area_size(60)
            .build_cartesian_2d(0.0..1.0, 0.0..amax)
            .map_err(e)?;
        cb.configure_mesh()
            .disable_mesh()
            .disable_x_axis()
            .y_desc("amplitude [N]")
            .label_style((FONT, 13))
            .axis_desc_style((FONT, 15))
            .draw()
            .map_err(e)?;
        let n = 100;
        cb.draw_series((0..n).map(|k| {
            let a = k as f64 / n as f64;
            Rectangle::new(
                [(0.0, a * amax), (1.0, (a + 1.0 / n as f64) * amax)],
                colour(a).filled(),
            )
        }))
        .map_err(e)?;
        Ok(())
    }

    fn draw_waterfall<DB: DrawingBackend>(
        &self, root: &DrawingArea<DB, Shift>,
    ) -> Result<(), String> {
        let e = |e: DrawingAreaErrorKind<DB::ErrorType>| e.to_string();
        let (_, dv) = self.steps();
        let amax = self.max_amp();
        // each spectrum is drawn at the height of its speed, scaled so that the largest peak
        // spans 1.6 speed steps
        let scale = 1.6 * dv / amax;
        let (f0, f1) = self.freq_range();
        let caption = format!("{} (largest peak {:.0} N)", self.title, amax);
        let mut chart = self.frame(
            root,
            &caption,
            2.0,
            "v [km/h] (baseline of each spectrum)",
            true,
        )?;
        // back to front so that lower speeds overlap the higher ones
        for (i, &v) in self.speeds.iter().enumerate().rev() {
            let pts: Vec<(f64, f64)> = self
                .freqs
                .iter()
                .zip(&self.amp[i])
                .map(|(&f, &a)| (f, v + scale * a))
                .collect();
            let mut poly = pts.clone();
            poly.push((f1, v));
            poly.push((f0, v));
            chart
                .draw_series(std::iter::once(Polygon::new(poly, WHITE.filled())))
                .map_err(e)?;
            let c = Palette99::pick(i).to_rgba();
            chart
                .draw_series(LineSeries::new(pts, c.stroke_width(2)))
                .map_err(e)?
                .label(format!("{v:.0} km/h"))
                .legend(move |(x, y)| {
                    PathElement::new(vec![(x, y), (x + 20, y)], c.stroke_width(2))
                });
        }
        draw_legend(&mut chart, 13)
    }

    /// Draw the `kind` plot (`contour` or `waterfall`) on `root` and write it to `path` (the
    /// backend's file, named in errors).
    fn render<DB: DrawingBackend>(
        &self, kind: &str, root: &DrawingArea<DB, Shift>, path: &Path,
    ) -> Result<(), StudyError> {
        root.fill(&WHITE).map_err(|m| io(path, m))?;
        match kind {
            "contour" => self.draw_contour(root),
            _ => self.draw_waterfall(root),
        }
        .map_err(|m| io(path, m))?;
        root.present().map_err(|m| io(path, m))
    }

    /// Write `<stem>_contour.{png,svg}` and `<stem>_waterfall.{png,svg}`.
    pub fn save(&self, stem: &Path) -> Result<(), StudyError> {
        register_font();
        let name = stem
            .file_name()
            .map(|s| s.to_string_lossy().into_owned())
            .unwrap_or_default();
        for kind in ["contour", "waterfall"] {
            let base = stem.with_file_name(format!("{name}_{kind}"));
            let png = base.with_extension("png");
            let svg = base.with_extension("svg");
            self.render(
                kind,
                &BitMapBackend::new(&png, (960, 640)).into_drawing_area(),
                &png,
            )?;
            self.render(
                kind,
                &SVGBackend::new(&svg, (960, 640)).into_drawing_area(),
                &svg,
            )?;
        }
        Ok(())
    }
}
