//! The two distribution charts of the report: the before/after histogram
//! of 3-D errors and the per-axis mean/max errors.

use super::chart_frame::{
    axis_label, judged_poses, no_data, plot_area, LEGEND_Y, MARGIN_RIGHT, SMALL_CHAR_WIDTH,
    SMALL_FONT, TITLE_Y,
};
use super::format::{fixed, mm};
use super::model::Report;
use super::plot::*;

/// Histogram bins per decade on a log axis, and bins on a linear axis.
const BINS_PER_DECADE: usize = 8;
const LINEAR_BINS: usize = 12;
const HISTOGRAM_OPACITY: f64 = 0.6;
/// Count axis ends at least here so that its ticks are whole numbers.
const MIN_COUNT_AXIS: f64 = 5.0;
/// Relative width of a bar inside its slot in the per-axis chart.
const AXIS_BAR_FILL: f64 = 0.4;
const WHISKER_CAP: f64 = 7.0;
/// Offset of the note under the per-axis chart.
const NOTE_OFFSET: f64 = 34.0;

/// Bin edges over the scale's domain: equal width in log or linear space.
fn bin_edges(scale: &Scale) -> Vec<f64> {
    if scale.log {
        let decades = (scale.hi.log10() - scale.lo.log10()).round() as usize;
        let count = decades * BINS_PER_DECADE;
        let step = (scale.hi.log10() - scale.lo.log10()) / count as f64;
        (0..=count)
            .map(|i| 10f64.powf(scale.lo.log10() + i as f64 * step))
            .collect()
    } else {
        let step = (scale.hi - scale.lo) / LINEAR_BINS as f64;
        (0..=LINEAR_BINS)
            .map(|i| scale.lo + i as f64 * step)
            .collect()
    }
}

fn histogram(values: impl Iterator<Item = f64>, edges: &[f64]) -> Vec<usize> {
    let mut counts = vec![0; edges.len().saturating_sub(1)];
    for v in values.filter(|v| v.is_finite()) {
        let bin = edges.partition_point(|e| *e <= v).saturating_sub(1);
        if let Some(c) = counts.get_mut(bin.min(edges.len().saturating_sub(2))) {
            *c += 1;
        }
    }
    counts
}

/// Overlaid histograms of the before and after 3-D errors.
pub fn histogram_chart(report: &Report, width: f64, height: f64) -> Svg {
    let mut svg = Svg::default();
    let (poses, which) = judged_poses(report);
    svg.title(TITLE_X, TITLE_Y, &format!("Error histogram, {which}"));
    legend(
        &mut svg,
        TITLE_X,
        LEGEND_Y,
        &[
            (Mark::Swatch(BEFORE_COLOR), "before"),
            (Mark::Swatch(AFTER_COLOR), "after"),
        ],
    );
    let area = plot_area(width, height, 0.0, MARGIN_RIGHT);
    if poses.is_empty() {
        no_data(&mut svg, area, "no poses in this report");
        return svg;
    }
    let values: Vec<f64> = poses
        .iter()
        .flat_map(|p| [p.before_mm, p.after_mm])
        .collect();
    let x_scale = Scale::for_magnitudes(&values, area.x, area.right());
    let edges = bin_edges(&x_scale);
    let before = histogram(poses.iter().map(|p| p.before_mm), &edges);
    let after = histogram(poses.iter().map(|p| p.after_mm), &edges);
    let max_count = before.iter().chain(&after).copied().max().unwrap_or(0) as f64;
    let y_scale = Scale::linear(0.0, max_count.max(MIN_COUNT_AXIS), area.bottom(), area.y);
    y_axis(&mut svg, area, &y_scale, "number of poses");
    x_axis(&mut svg, area, &x_scale, &axis_label("3-D error", &x_scale));
    for (counts, color) in [(&before, BEFORE_COLOR), (&after, AFTER_COLOR)] {
        for (i, &count) in counts.iter().enumerate().filter(|(_, c)| **c > 0) {
            let (x0, x1) = (x_scale.map(edges[i]), x_scale.map(edges[i + 1]));
            let top = y_scale.map(count as f64);
            svg.rect(
                x0 + 0.5,
                top,
                x1 - x0 - 1.0,
                area.bottom() - top,
                color,
                HISTOGRAM_OPACITY,
            );
        }
    }
    svg
}

/// Mean (bar) and maximum (whisker) absolute error per axis and 3-D,
/// before and after.
pub fn axis_chart(report: &Report, width: f64, height: f64) -> Svg {
    let mut svg = Svg::default();
    let (_, which) = judged_poses(report);
    svg.title(TITLE_X, TITLE_Y, &format!("Error per axis, {which}"));
    legend(
        &mut svg,
        TITLE_X,
        LEGEND_Y,
        &[
            (Mark::Swatch(BEFORE_COLOR), "before"),
            (Mark::Swatch(AFTER_COLOR), "after"),
            (Mark::Text, "(bar: mean, whisker: max)"),
        ],
    );
    let area = plot_area(width, height, 0.0, MARGIN_RIGHT);
    let (b, a) = (&report.before, &report.after);
    let groups = [
        ("|x|", &b.x, &a.x),
        ("|y|", &b.y, &a.y),
        ("|z|", &b.z, &a.z),
        ("3-D", &b.norm, &a.norm),
    ];
    let values: Vec<f64> = groups
        .iter()
        .flat_map(|(_, b, a)| [b.mean_mm, b.max_mm, a.mean_mm, a.max_mm])
        .collect();
    if !values.iter().any(|v| v.is_finite() && *v > 0.0) {
        no_data(&mut svg, area, "no error statistics in this report");
        return svg;
    }
    let scale = Scale::for_magnitudes(&values, area.bottom(), area.y);
    y_axis(
        &mut svg,
        area,
        &scale,
        &axis_label("absolute error", &scale),
    );
    svg.line(
        area.x,
        area.bottom(),
        area.right(),
        area.bottom(),
        AXIS_COLOR,
        1.0,
    );
    let slot = area.w / groups.len() as f64;
    for (g, (name, before, after)) in groups.iter().enumerate() {
        let centre = area.x + slot * (g as f64 + 0.5);
        let bar_w = slot * AXIS_BAR_FILL;
        for (k, (stats, color)) in [(before, BEFORE_COLOR), (after, AFTER_COLOR)]
            .iter()
            .enumerate()
        {
            let x = centre + (k as f64 - 1.0) * bar_w - 1.0 + 2.0 * k as f64;
            let top = scale.map(stats.mean_mm);
            svg.rect(x, top, bar_w, area.bottom() - top, color, 0.85);
            let (xm, ymax) = (x + bar_w / 2.0, scale.map(stats.max_mm));
            svg.line(xm, top, xm, ymax, AXIS_COLOR, 1.2);
            svg.line(
                xm - WHISKER_CAP / 2.0,
                ymax,
                xm + WHISKER_CAP / 2.0,
                ymax,
                AXIS_COLOR,
                1.2,
            );
            svg.text(
                xm,
                ymax - 4.0,
                "middle",
                SMALL_FONT,
                TEXT_COLOR,
                &mm(stats.max_mm),
            );
            let label = mm(stats.mean_mm);
            let fits = label.len() as f64 * SMALL_CHAR_WIDTH < bar_w;
            if fits && area.bottom() - top > 2.0 * SMALL_FONT {
                let y = top + SMALL_FONT + 2.0;
                svg.text(xm, y, "middle", SMALL_FONT, "white", &label);
            }
        }
        let y = area.bottom() + TICK_LENGTH + FONT_SIZE + 3.0;
        svg.text(centre, y, "middle", FONT_SIZE, TEXT_COLOR, name);
    }
    let factor = if a.norm.mean_mm > 0.0 {
        b.norm.mean_mm / a.norm.mean_mm
    } else {
        f64::NAN
    };
    let note = format!(
        "mean 3-D error {}x smaller after calibration",
        fixed(factor, 1)
    );
    svg.text(
        area.x + area.w / 2.0,
        area.bottom() + NOTE_OFFSET,
        "middle",
        FONT_SIZE,
        MUTED_COLOR,
        &note,
    );
    svg
}
