//! The reprojection residual field chart: residuals (observed minus
//! predicted dot centres) drawn as magnified arrows over the image
//! rectangle. Thousands of residuals are averaged per grid cell so that a
//! systematic pattern (unmodelled distortion, a decentred lens) stands out
//! of the detection noise; the cells are shaded by their RMS residual.

use super::field_key::{key, principal_point, FieldKey};
use super::field_marks::{arrow, ramp, MIN_CELL_SAMPLES};
use super::model::{CameraReport, Report, ResidualSample};
use super::plot::*;

const MARGIN_LEFT: f64 = 66.0;
const MARGIN_TOP: f64 = 54.0;
const MARGIN_BOTTOM: f64 = 48.0;
/// Room right of the image for the colour bar and the arrow key.
const KEY_WIDTH: f64 = 250.0;
const MAX_PLOT_HEIGHT: f64 = 560.0;
/// Height of the chart when there is no camera (just a note).
const NOTE_HEIGHT: f64 = 80.0;
const CHART_TITLE_Y: f64 = 20.0;
/// Baseline of the no-camera note.
const NOTE_Y: f64 = 46.0;
/// Grid cells across the image width when averaging.
const GRID_COLUMNS: usize = 16;
/// Arrow magnification is set by this quantile of arrow lengths, so a
/// single wild cell cannot shrink all the others to dots.
const LENGTH_QUANTILE: f64 = 0.95;
/// Up to this many residuals are drawn one by one instead of averaged.
const RAW_ARROW_LIMIT: usize = 400;
/// The longest arrow fills at most this fraction of a cell.
const ARROW_FILL: f64 = 0.9;
/// Cells overlap by this much so that no anti-aliasing seams show.
const CELL_OVERLAP: f64 = 0.6;
/// Height of the chart at `width` (image aspect preserved).
pub fn field_height(report: &Report, width: f64) -> f64 {
    match &report.camera {
        Some(camera) => MARGIN_TOP + plot_size(camera, width).1 + MARGIN_BOTTOM,
        None => NOTE_HEIGHT,
    }
}

fn plot_size(camera: &CameraReport, width: f64) -> (f64, f64) {
    let (iw, ih) = (
        f64::from(camera.image_width.max(1)),
        f64::from(camera.image_height.max(1)),
    );
    let w = width - MARGIN_LEFT - KEY_WIDTH;
    let h = w * ih / iw;
    if h > MAX_PLOT_HEIGHT {
        (MAX_PLOT_HEIGHT * iw / ih, MAX_PLOT_HEIGHT)
    } else {
        (w, h)
    }
}

/// One averaged arrow: where, the mean residual, the cell RMS, how many.
struct Cell {
    x_px: f64,
    y_px: f64,
    dx_px: f64,
    dy_px: f64,
    rms_px: f64,
    n: usize,
}

fn is_finite(s: &ResidualSample) -> bool {
    s.x_px.is_finite() && s.y_px.is_finite() && s.dx_px.is_finite() && s.dy_px.is_finite()
}

/// Averages residuals on a grid of `cell_px` squares.
fn grid_cells(samples: &[ResidualSample], camera: &CameraReport, cell_px: f64) -> Vec<Cell> {
    let cols = (f64::from(camera.image_width) / cell_px).ceil().max(1.0) as usize;
    let rows = (f64::from(camera.image_height) / cell_px).ceil().max(1.0) as usize;
    // Per cell: count, sum dx, sum dy, sum of squared magnitudes.
    let mut sums = vec![(0usize, 0.0, 0.0, 0.0); cols * rows];
    for s in samples {
        let (c, r) = ((s.x_px / cell_px).floor(), (s.y_px / cell_px).floor());
        if c < 0.0 || r < 0.0 || c as usize >= cols || r as usize >= rows {
            continue;
        }
        let sum = &mut sums[r as usize * cols + c as usize];
        *sum = (
            sum.0 + 1,
            sum.1 + s.dx_px,
            sum.2 + s.dy_px,
            sum.3 + s.dx_px * s.dx_px + s.dy_px * s.dy_px,
        );
    }
    sums.iter()
        .enumerate()
        .filter(|(_, s)| s.0 > 0)
        .map(|(i, &(n, sx, sy, ss))| Cell {
            x_px: ((i % cols) as f64 + 0.5) * cell_px,
            y_px: ((i / cols) as f64 + 0.5) * cell_px,
            dx_px: sx / n as f64,
            dy_px: sy / n as f64,
            rms_px: (ss / n as f64).sqrt(),
            n,
        })
        .collect()
}

/// The largest 1-2-5 magnification that keeps the longest arrow inside
/// [`ARROW_FILL`] of a cell.
fn magnification(max_residual_px: f64, cell_px: f64) -> f64 {
    if max_residual_px.is_nan() || max_residual_px <= 0.0 {
        return 1.0;
    }
    let raw = ARROW_FILL * cell_px / max_residual_px;
    let power = 10f64.powf(raw.log10().floor());
    let mantissa = [5.0, 2.0, 1.0]
        .into_iter()
        .find(|m| m * power <= raw)
        .unwrap_or(1.0);
    (mantissa * power).max(1.0)
}

/// The residual field chart, or a note when the session has no camera.
pub fn residual_field_chart(report: &Report, width: f64, _height: f64) -> Svg {
    let mut svg = Svg::default();
    svg.title(
        TITLE_X,
        CHART_TITLE_Y,
        "Reprojection residual field over the image",
    );
    let Some(camera) = &report.camera else {
        let note = format!(
            "No camera in this session (instrument: {}): there are no reprojection residuals to show.",
            report.instrument
        );
        svg.text(TITLE_X, NOTE_Y, "start", FONT_SIZE, MUTED_COLOR, &note);
        return svg;
    };
    let (pw, ph) = plot_size(camera, width);
    let area = Area {
        x: MARGIN_LEFT,
        y: MARGIN_TOP,
        w: pw,
        h: ph,
    };
    let (iw, ih) = (
        f64::from(camera.image_width.max(1)),
        f64::from(camera.image_height.max(1)),
    );
    let xs = Scale::exact(0.0, iw, area.x, area.right());
    let ys = Scale::exact(0.0, ih, area.y, area.bottom());
    let samples: Vec<ResidualSample> = report
        .residual_field
        .iter()
        .copied()
        .filter(is_finite)
        .collect();
    let averaged = samples.len() > RAW_ARROW_LIMIT;
    let cell_px = iw / GRID_COLUMNS as f64;
    let cells: Vec<Cell> = if averaged {
        grid_cells(&samples, camera, cell_px)
    } else {
        let to_cell = |s: &ResidualSample| Cell {
            x_px: s.x_px,
            y_px: s.y_px,
            dx_px: s.dx_px,
            dy_px: s.dy_px,
            rms_px: 0.0,
            n: 1,
        };
        samples.iter().map(to_cell).collect()
    };
    let max_rms = cells.iter().map(|c| c.rms_px).fold(0.0, f64::max);
    let shade_scale = Scale::linear(0.0, max_rms, 0.0, 1.0);
    x_axis(&mut svg, area, &xs, "image x [px]");
    y_axis(&mut svg, area, &ys, "image y [px] (down)");
    svg.rect(area.x, area.y, area.w, area.h, "#fcfcfc", 1.0);
    if averaged {
        let (cw, ch) = (xs.map(cell_px) - area.x, ys.map(cell_px) - area.y);
        for c in &cells {
            let (x, y) = (xs.map(c.x_px) - cw / 2.0, ys.map(c.y_px) - ch / 2.0);
            svg.rect(
                x,
                y,
                (cw + CELL_OVERLAP).min(area.right() - x),
                (ch + CELL_OVERLAP).min(area.bottom() - y),
                &ramp((c.rms_px - shade_scale.lo) / (shade_scale.hi - shade_scale.lo)),
                1.0,
            );
        }
    }
    svg.outline(area.x, area.y, area.w, area.h, AXIS_COLOR);
    let min_samples = if averaged { MIN_CELL_SAMPLES } else { 1 };
    let mut lengths: Vec<f64> = cells
        .iter()
        .filter(|c| c.n >= min_samples)
        .map(|c| c.dx_px.hypot(c.dy_px))
        .collect();
    lengths.sort_by(f64::total_cmp);
    let typical_max = lengths.get(
        ((lengths.len() as f64 - 1.0) * LENGTH_QUANTILE)
            .round()
            .max(0.0) as usize,
    );
    let factor = magnification(typical_max.copied().unwrap_or(0.0), cell_px);
    for c in cells.iter().filter(|c| c.n >= min_samples) {
        let (x0, y0) = (xs.map(c.x_px), ys.map(c.y_px));
        let (x1, y1) = (
            xs.map(c.x_px + factor * c.dx_px),
            ys.map(c.y_px + factor * c.dy_px),
        );
        arrow(&mut svg, x0, y0, x1, y1);
    }
    principal_point(&mut svg, camera, &xs, &ys);
    let field_key = FieldKey {
        averaged,
        factor,
        cell_px,
        shade: &shade_scale,
    };
    key(&mut svg, area, camera, &samples, &field_key);
    svg
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn magnification_is_a_round_number_that_fits_the_cell() {
        assert_eq!(magnification(0.1, 64.0), 500.0);
        assert_eq!(magnification(0.3, 64.0), 100.0);
        assert_eq!(magnification(0.0, 64.0), 1.0);
    }

    #[test]
    fn grid_averages_a_constant_residual_exactly() {
        let camera = crate::report::sample::sample_report().camera.unwrap();
        let samples: Vec<ResidualSample> = (0..200)
            .map(|i| ResidualSample {
                x_px: (i * 6) as f64,
                y_px: (i * 5) as f64,
                dx_px: 0.1,
                dy_px: -0.2,
            })
            .collect();
        let cells = grid_cells(&samples, &camera, 64.0);
        assert!(!cells.is_empty());
        for c in cells {
            assert!((c.dx_px - 0.1).abs() < 1e-12 && (c.dy_px + 0.2).abs() < 1e-12);
            assert!((c.rms_px - 0.05f64.sqrt()).abs() < 1e-12);
        }
    }
}
