//! The predicted-uncertainty map of the workspace: a top view of the
//! report's slice (flange positions in the base frame at one height and
//! orientation), each grid cell shaded by the predicted 1σ of the tool
//! position there, the calibration poses drawn on top. Where the shading
//! darkens the calibration is extrapolating.

use super::chart_frame::{no_data, plot_area, LEGEND_Y, MARGIN_LEFT, SMALL_FONT, TITLE_Y};
use super::model::{Report, UncertaintyMapReport};
use super::plot::*;

/// Room right of the map for the colour bar.
const KEY_WIDTH: f64 = 150.0;
const BAR_WIDTH: f64 = 14.0;
/// Gap between the map and the colour bar, and the bar and its labels.
const KEY_GAP: f64 = 24.0;
const LABEL_GAP: f64 = 5.0;
/// Colour-bar steps drawn.
const BAR_STEPS: usize = 24;
/// Darkest shade: light yellow (low σ) to dark red (high σ).
const LOW: [f64; 3] = [255.0, 247.0, 188.0];
const HIGH: [f64; 3] = [189.0, 0.0, 38.0];
const POSE_COLOR: &str = "#1f5fa8";
const POSE_RADIUS: f64 = 2.6;

/// The shade of `t` in [0, 1].
fn shade(t: f64) -> String {
    let t = if t.is_finite() {
        t.clamp(0.0, 1.0)
    } else {
        0.0
    };
    let c: Vec<u8> = (0..3)
        .map(|i| (LOW[i] + t * (HIGH[i] - LOW[i])).round() as u8)
        .collect();
    format!("#{:02x}{:02x}{:02x}", c[0], c[1], c[2])
}

/// Height of the chart at `width` (a square map).
pub fn uncertainty_height(width: f64) -> f64 {
    let area = plot_area(width, width, 0.0, KEY_WIDTH);
    width - area.h + area.w
}

pub fn uncertainty_chart(report: &Report, width: f64, height: f64) -> Svg {
    let mut svg = Svg::default();
    svg.title(
        MARGIN_LEFT,
        TITLE_Y,
        "Predicted uncertainty over the workspace (1σ of the tool position, 3-D)",
    );
    let area = plot_area(width, height, 0.0, KEY_WIDTH);
    let side = area.w.min(area.h);
    let area = Area {
        w: side,
        h: side,
        ..area
    };
    let Some(map) = &report.uncertainty_map else {
        no_data(&mut svg, area, "no uncertainty map in this report");
        return svg;
    };
    svg.text(
        MARGIN_LEFT,
        LEGEND_Y,
        "start",
        SMALL_FONT,
        MUTED_COLOR,
        &format!(
            "flange at z = {:.0} mm (base frame), orientation {:.0}/{:.0}/{:.0}°; blank: out of reach",
            map.z_mm, map.rotation_deg[0], map.rotation_deg[1], map.rotation_deg[2]
        ),
    );
    draw_map(&mut svg, area, map);
    svg
}

fn draw_map(svg: &mut Svg, area: Area, map: &UncertaintyMapReport) {
    let half = map.step_mm / 2.0;
    let (x_lo, x_hi) = bounds(map.cells.iter().map(|c| c.x_mm));
    let (y_lo, y_hi) = bounds(map.cells.iter().map(|c| c.y_mm));
    let span = (x_hi - x_lo).max(y_hi - y_lo) + map.step_mm;
    let (x0, y0) = (
        (x_lo + x_hi) / 2.0 - span / 2.0,
        (y_lo + y_hi) / 2.0 - span / 2.0,
    );
    let xs = Scale::exact(x0, x0 + span, area.x, area.right());
    // Base-frame y up the page.
    let ys = Scale::exact(y0, y0 + span, area.bottom(), area.y);
    let (s_lo, s_hi) = bounds(map.cells.iter().map(|c| c.position_std_mm));
    let t = |s: f64| {
        if s_hi > s_lo {
            (s - s_lo) / (s_hi - s_lo)
        } else {
            0.0
        }
    };
    for c in &map.cells {
        let (left, right) = (xs.map(c.x_mm - half), xs.map(c.x_mm + half));
        let (top, bottom) = (ys.map(c.y_mm + half), ys.map(c.y_mm - half));
        svg.rect(
            left,
            top,
            right - left + 0.5,
            bottom - top + 0.5,
            &shade(t(c.position_std_mm)),
            1.0,
        );
    }
    for p in &map.poses_xy_mm {
        if (x0..=x0 + span).contains(&p[0]) && (y0..=y0 + span).contains(&p[1]) {
            svg.circle(xs.map(p[0]), ys.map(p[1]), POSE_RADIUS, POSE_COLOR);
        }
    }
    svg.outline(area.x, area.y, area.w, area.h, AXIS_COLOR);
    x_axis(svg, area, &xs, "x [mm] (robot base frame)");
    y_axis(svg, area, &ys, "y [mm]");
    // The colour bar, low at the bottom.
    let bar_x = area.right() + KEY_GAP;
    let step_h = area.h / BAR_STEPS as f64;
    for k in 0..BAR_STEPS {
        let y = area.bottom() - (k + 1) as f64 * step_h;
        let tk = (k as f64 + 0.5) / BAR_STEPS as f64;
        svg.rect(bar_x, y, BAR_WIDTH, step_h + 0.5, &shade(tk), 1.0);
    }
    svg.outline(bar_x, area.y, BAR_WIDTH, area.h, AXIS_COLOR);
    let label_x = bar_x + BAR_WIDTH + LABEL_GAP;
    for (y, value) in [(area.bottom(), s_lo), (area.y + FONT_SIZE, s_hi)] {
        svg.text(
            label_x,
            y,
            "start",
            FONT_SIZE,
            TEXT_COLOR,
            &format!("{value:.3} mm"),
        );
    }
    svg.rotated_text(
        label_x + 2.0 * FONT_SIZE,
        area.y + area.h / 2.0,
        -90.0,
        "middle",
        "predicted 1σ",
    );
    legend(
        svg,
        bar_x - KEY_GAP / 2.0,
        area.bottom() + 2.0 * FONT_SIZE,
        &[(Mark::Dot(POSE_COLOR), "calibration poses")],
    );
}

fn bounds(values: impl Iterator<Item = f64>) -> (f64, f64) {
    values.fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), v| {
        (lo.min(v), hi.max(v))
    })
}

/// A synthetic map for the sample report: σ growing away from the posed
/// region, a corner out of reach.
pub fn sample_map() -> UncertaintyMapReport {
    const POINTS: usize = 13;
    const STEP_MM: f64 = 60.0;
    const ORIGIN_MM: [f64; 2] = [700.0, -360.0];
    const CENTRE_MM: [f64; 2] = [1060.0, 0.0];
    let mut cells = Vec::new();
    for iy in 0..POINTS {
        for ix in 0..POINTS {
            let (x, y) = (
                ORIGIN_MM[0] + ix as f64 * STEP_MM,
                ORIGIN_MM[1] + iy as f64 * STEP_MM,
            );
            let r = ((x - CENTRE_MM[0]).powi(2) + (y - CENTRE_MM[1]).powi(2)).sqrt();
            if ix + iy > 2 * POINTS - 4 {
                continue;
            }
            cells.push(super::model::UncertaintyCell {
                x_mm: x,
                y_mm: y,
                position_std_mm: 0.012 + 1e-7 * r * r,
            });
        }
    }
    UncertaintyMapReport {
        z_mm: 1150.0,
        rotation_deg: [180.0, 0.0, 0.0],
        step_mm: STEP_MM,
        cells,
        poses_xy_mm: (0..24)
            .map(|k| {
                let a = k as f64 * 0.7;
                [
                    CENTRE_MM[0] + 150.0 * a.cos(),
                    CENTRE_MM[1] + 150.0 * a.sin(),
                ]
            })
            .collect(),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::report::sample::sample_report;
    use crate::report::xml_check::check_balanced;

    #[test]
    fn every_reachable_cell_is_shaded_and_the_key_spans_the_values() {
        let report = sample_report();
        let map = report.uncertainty_map.as_ref().unwrap();
        let h = uncertainty_height(880.0);
        let svg = uncertainty_chart(&report, 880.0, h);
        let doc = standalone(880.0, h, "map", &svg.body);
        check_balanced(&doc, false).unwrap();
        let cells = map.cells.len();
        let rects = doc.matches("<rect").count();
        // Cells, plus the colour bar's steps (outlines are paths or rects).
        assert!(
            rects >= cells + BAR_STEPS,
            "{rects} rects for {cells} cells"
        );
        let lo = map
            .cells
            .iter()
            .map(|c| c.position_std_mm)
            .fold(f64::INFINITY, f64::min);
        assert!(doc.contains(&format!("{lo:.3} mm")), "low end of the key");
        assert!(doc.contains(&shade(0.0)) && doc.contains(&shade(1.0)));
        let mut without = report.clone();
        without.uncertainty_map = None;
        let empty = uncertainty_chart(&without, 880.0, h);
        assert!(empty.body.contains("no uncertainty map"));
    }
}
