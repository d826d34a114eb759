//! The benchmark's plots (plotters, SVG or PNG): squared depth error against GPU time and
//! against evaluations per pixel, one line per tracer through its step budgets, as in Bálint &
//! Valasek's Figure 3. PNG text uses DejaVu Sans, embedded (`runtime/assets/`, its licence
//! beside it), so no system fonts are needed.

use super::Cell;
use plotters::prelude::*;
use std::path::Path;

/// Smallest error drawn (the log axis has no 0).
const FLOOR: f64 = 1e-12;

const SIZE: (u32, u32) = (1200, 480);

/// Why a plot was not written.
#[derive(Debug, thiserror::Error)]
pub enum PlotError {
    /// Drawing failed.
    #[error("error: cannot draw `{}`: {message}", path.display())]
    Draw {
        /// The plot's file.
        path: std::path::PathBuf,
        /// What went wrong.
        message: String,
    },
    /// Writing the file failed.
    #[error("error: cannot write `{}`: {source}", path.display())]
    Write {
        /// The plot's file.
        path: std::path::PathBuf,
        /// The I/O error.
        source: std::io::Error,
    },
}

static FONT: &[u8] = include_bytes!("../../assets/DejaVuSans.ttf");

/// Draws the cells to `path` (SVG for `.svg`, PNG for `.png`).
pub fn write(path: &Path, title: &str, cells: &[Cell]) -> Result<(), PlotError> {
    let fail = |message: String| PlotError::Draw {
        path: path.to_path_buf(),
        message,
    };
    // Text is laid out with the embedded font for both formats.
    plotters::style::register_font("sans-serif", FontStyle::Normal, FONT)
        .map_err(|_| fail("the embedded font does not load".into()))?;
    if path.extension().is_some_and(|e| e == "png") {
        let root = BitMapBackend::new(path, SIZE).into_drawing_area();
        draw(&root, title, cells).map_err(|e| fail(e.to_string()))
    } else {
        // Drawn to a string and written whole, so that a write error is reported (the SVG
        // backend writing to the path itself swallowed it).
        let mut svg = String::new();
        {
            let root = SVGBackend::with_string(&mut svg, SIZE).into_drawing_area();
            draw(&root, title, cells).map_err(|e| fail(e.to_string()))?;
        }
        crate::files::write_file(path, svg.as_bytes()).map_err(|source| PlotError::Write {
            path: path.to_path_buf(),
            source,
        })
    }
}

type Axis = (&'static str, fn(&Cell) -> f64);

fn draw<'a, DB: DrawingBackend + 'a>(
    root: &DrawingArea<DB, plotters::coord::Shift>,
    title: &str,
    cells: &[Cell],
) -> Result<(), Box<dyn std::error::Error + 'a>>
where
    DB::ErrorType: 'static,
{
    root.fill(&WHITE)?;
    let root = root.titled(title, ("sans-serif", 20))?;
    let (left, right) = root.split_horizontally(600);
    let axes: [Axis; 2] = [
        ("GPU time per frame (ms)", |c| c.seconds * 1e3),
        ("evaluations per pixel", |c| c.evals_mean),
    ];
    let mut tracers: Vec<&str> = Vec::new();
    for c in cells {
        if !tracers.contains(&c.tracer.as_str()) {
            tracers.push(&c.tracer);
        }
    }
    let err = |c: &Cell| c.mse.max(FLOOR);
    let range = |f: &dyn Fn(&Cell) -> f64| {
        let lo = cells.iter().map(f).fold(f64::INFINITY, f64::min);
        let hi = cells.iter().map(f).fold(0.0, f64::max);
        (lo / 1.5)..(hi * 1.5)
    };
    for (area, (label, x)) in [left, right].into_iter().zip(axes) {
        let mut chart = ChartBuilder::on(&area)
            .margin(14)
            .x_label_area_size(40)
            .y_label_area_size(70)
            .build_cartesian_2d(range(&x).log_scale(), range(&err).log_scale())?;
        chart
            .configure_mesh()
            .x_desc(label)
            .y_desc("mean squared depth error")
            .y_label_formatter(&|v| format!("{v:.0e}"))
            .draw()?;
        for (k, tracer) in tracers.iter().enumerate() {
            let color = Palette99::pick(k).to_rgba();
            let mut pts: Vec<(u32, f64, f64)> = cells
                .iter()
                .filter(|c| c.tracer == *tracer)
                .map(|c| (c.steps, x(c), err(c)))
                .collect();
            pts.sort_by_key(|p| p.0);
            let line: Vec<(f64, f64)> = pts.iter().map(|p| (p.1, p.2)).collect();
            chart
                .draw_series(LineSeries::new(line.clone(), color.stroke_width(2)))?
                .label(*tracer)
                .legend(move |(x, y)| PathElement::new(vec![(x, y), (x + 20, y)], color));
            chart.draw_series(line.iter().map(|&p| Circle::new(p, 3, color.filled())))?;
        }
        chart
            .configure_series_labels()
            .border_style(BLACK)
            .background_style(WHITE.mix(0.9))
            .draw()?;
    }
    root.present()?;
    Ok(())
}
