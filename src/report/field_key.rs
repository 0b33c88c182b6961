//! The key beside the residual field chart: what an arrow means, its
//! magnification with a reference arrow, the principal point marker, and
//! the colour bar of the per-cell RMS shading.

use super::field_marks::{arrow, ramp, MIN_CELL_SAMPLES};
use super::format::significant;
use super::model::{CameraReport, ResidualSample};
use super::plot::*;

const COLOUR_BAR_WIDTH: f64 = 14.0;
const COLOUR_BAR_STEPS: usize = 24;
const KEY_LINE: f64 = 16.0;
/// Gap between the image and the key.
const KEY_GAP: f64 = 24.0;
const MARKER_HALF: f64 = 6.0;

/// How the field was drawn, for the key to explain.
#[derive(Clone, Copy)]
pub struct FieldKey<'a> {
    /// Residuals averaged per cell (else drawn one by one).
    pub averaged: bool,
    /// Arrow magnification.
    pub factor: f64,
    pub cell_px: f64,
    /// Shading scale of the cell RMS (0..1 output).
    pub shade: &'a Scale,
}

pub fn principal_point(svg: &mut Svg, camera: &CameraReport, xs: &Scale, ys: &Scale) {
    let (x, y) = (xs.map(camera.intrinsics.cx), ys.map(camera.intrinsics.cy));
    svg.line(x - MARKER_HALF, y, x + MARKER_HALF, y, AFTER_COLOR, 1.5);
    svg.line(x, y - MARKER_HALF, x, y + MARKER_HALF, AFTER_COLOR, 1.5);
}

/// The explanatory key right of the image: what an arrow means, its
/// magnification and a reference arrow, the shading colour bar.
pub fn key(
    svg: &mut Svg,
    area: Area,
    camera: &CameraReport,
    samples: &[ResidualSample],
    field: &FieldKey,
) {
    let FieldKey {
        averaged,
        factor,
        cell_px,
        shade,
    } = *field;
    let x = area.right() + KEY_GAP;
    let mut y = area.y + 8.0;
    let mut line = |svg: &mut Svg, text: &str| {
        svg.text(x, y, "start", FONT_SIZE, TEXT_COLOR, text);
        y += KEY_LINE;
    };
    let rms = (samples
        .iter()
        .map(|s| s.dx_px * s.dx_px + s.dy_px * s.dy_px)
        .sum::<f64>()
        / samples.len().max(1) as f64)
        .sqrt();
    line(svg, &format!("{} residuals", samples.len()));
    line(svg, "(observed − predicted dot centre)");
    line(svg, &format!("RMS {} px", significant(rms, 2)));
    line(
        svg,
        &format!("image {} x {} px", camera.image_width, camera.image_height),
    );
    if averaged {
        line(
            svg,
            &format!("arrow: mean per {0:.0} x {0:.0} px cell", cell_px),
        );
        line(
            svg,
            &format!("(no arrow under {MIN_CELL_SAMPLES} residuals in a cell)"),
        );
    } else {
        line(svg, "arrow: one residual");
    }
    svg.bold_text(
        x,
        y,
        "start",
        FONT_SIZE,
        &format!("arrows magnified {}x", significant(factor, 3)),
    );
    y += KEY_LINE + 6.0;
    // A reference arrow of a round residual length.
    let reference_px = nice_step(0.6 * cell_px / factor);
    let px_per_image_px = area.w / f64::from(camera.image_width.max(1));
    let len = reference_px * factor * px_per_image_px;
    arrow(svg, x, y - 4.0, x + len, y - 4.0);
    svg.text(
        x + len + 6.0,
        y,
        "start",
        FONT_SIZE,
        TEXT_COLOR,
        &format!("= {} px residual", significant(reference_px, 2)),
    );
    y += KEY_LINE + 6.0;
    svg.line(x, y - 4.0, x + 10.0, y - 4.0, AFTER_COLOR, 1.5);
    svg.line(x + 5.0, y - 9.0, x + 5.0, y + 1.0, AFTER_COLOR, 1.5);
    svg.text(
        x + 16.0,
        y,
        "start",
        FONT_SIZE,
        TEXT_COLOR,
        "principal point (cx, cy)",
    );
    y += KEY_LINE + 10.0;
    if !averaged {
        return;
    }
    svg.bold_text(x, y, "start", FONT_SIZE, "cell RMS residual [px]");
    y += 8.0;
    let bar_h = (area.bottom() - y).min(160.0);
    let bar = Area {
        x,
        y,
        w: COLOUR_BAR_WIDTH,
        h: bar_h,
    };
    let step_h = bar_h / COLOUR_BAR_STEPS as f64;
    for i in 0..COLOUR_BAR_STEPS {
        let t = (i as f64 + 0.5) / COLOUR_BAR_STEPS as f64;
        svg.rect(
            x,
            bar.bottom() - (i as f64 + 1.0) * step_h,
            COLOUR_BAR_WIDTH,
            step_h + 0.3,
            &ramp(t),
            1.0,
        );
    }
    svg.outline(x, y, COLOUR_BAR_WIDTH, bar_h, AXIS_COLOR);
    let bar_scale = Scale {
        start: bar.bottom(),
        end: bar.y,
        ..*shade
    };
    for tick in bar_scale.ticks() {
        let ty = bar_scale.map(tick.value);
        svg.line(
            bar.right(),
            ty,
            bar.right() + TICK_LENGTH,
            ty,
            AXIS_COLOR,
            1.0,
        );
        if let Some(label) = tick.label {
            svg.text(
                bar.right() + TICK_LENGTH + 3.0,
                ty + 4.0,
                "start",
                FONT_SIZE,
                TEXT_COLOR,
                &label,
            );
        }
    }
}
