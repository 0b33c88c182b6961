//! The report's charts as SVG (issue 6): 3-D error per validation pose,
//! error histogram, per-axis errors, and the reprojection residual field
//! (in `field.rs`). [`render_svg`] puts them on one self-contained sheet
//! under a header; the HTML report embeds the charts one by one.

use super::field::{field_height, residual_field_chart};
use super::format::{fixed, headline, mm};
use super::model::{PoseReport, Report};
use super::plot::*;

/// Width of the whole sheet and of full-width charts.
pub const SHEET_WIDTH: f64 = 1000.0;
/// Width of the two charts side by side.
pub const HALF_WIDTH: f64 = SHEET_WIDTH / 2.0;
const HEADER_HEIGHT: f64 = 78.0;
pub const POSE_CHART_HEIGHT: f64 = 330.0;
pub const SMALL_CHART_HEIGHT: f64 = 310.0;
/// Room left of the plot area for tick labels and the rotated axis label.
const MARGIN_LEFT: f64 = 66.0;
const MARGIN_RIGHT: f64 = 24.0;
/// Room above the plot area for the title and legend.
const MARGIN_TOP: f64 = 54.0;
const MARGIN_BOTTOM: f64 = 50.0;
/// Extra room under the pose chart for rotated pose ids.
const POSE_LABEL_ROOM: f64 = 18.0;
/// Room right of the pose chart for the mean labels.
const MEAN_LABEL_ROOM: f64 = 70.0;
const TITLE_Y: f64 = 20.0;
const LEGEND_Y: f64 = 40.0;
const DOT_RADIUS: f64 = 3.6;
/// Most pose ids written under the pose axis before thinning them out.
const MAX_POSE_LABELS: usize = 40;
const SMALL_FONT: f64 = 9.5;
/// Histogram bins per decade on a log axis, and bins on a linear axis.
const BINS_PER_DECADE: usize = 8;
const LINEAR_BINS: usize = 12;
const HISTOGRAM_OPACITY: f64 = 0.6;
/// Count axis ends at least here so that its ticks are whole numbers.
const MIN_COUNT_AXIS: f64 = 5.0;
/// Relative width of a bar inside its slot in the per-axis chart.
const AXIS_BAR_FILL: f64 = 0.32;
const WHISKER_CAP: f64 = 7.0;

/// The whole report as one standalone SVG document.
pub fn render_svg(report: &Report) -> String {
    let mut sheet = Svg::default();
    header(&mut sheet, report);
    let mut y = HEADER_HEIGHT;
    place(
        &mut sheet,
        0.0,
        y,
        &pose_chart(report, SHEET_WIDTH, POSE_CHART_HEIGHT),
    );
    y += POSE_CHART_HEIGHT;
    place(
        &mut sheet,
        0.0,
        y,
        &histogram_chart(report, HALF_WIDTH, SMALL_CHART_HEIGHT),
    );
    place(
        &mut sheet,
        HALF_WIDTH,
        y,
        &axis_chart(report, HALF_WIDTH, SMALL_CHART_HEIGHT),
    );
    y += SMALL_CHART_HEIGHT;
    let field_h = field_height(report, SHEET_WIDTH);
    place(
        &mut sheet,
        0.0,
        y,
        &residual_field_chart(report, SHEET_WIDTH, field_h),
    );
    standalone(SHEET_WIDTH, y + field_h, &sheet.body)
}

/// Standalone chart documents, for embedding one by one in the HTML page.
pub fn pose_errors_svg(report: &Report) -> String {
    standalone(
        SHEET_WIDTH,
        POSE_CHART_HEIGHT,
        &pose_chart(report, SHEET_WIDTH, POSE_CHART_HEIGHT).body,
    )
}
pub fn histogram_svg(report: &Report) -> String {
    standalone(
        HALF_WIDTH,
        SMALL_CHART_HEIGHT,
        &histogram_chart(report, HALF_WIDTH, SMALL_CHART_HEIGHT).body,
    )
}
pub fn axis_errors_svg(report: &Report) -> String {
    standalone(
        HALF_WIDTH,
        SMALL_CHART_HEIGHT,
        &axis_chart(report, HALF_WIDTH, SMALL_CHART_HEIGHT).body,
    )
}
pub fn residual_field_svg(report: &Report) -> String {
    let h = field_height(report, SHEET_WIDTH);
    standalone(
        SHEET_WIDTH,
        h,
        &residual_field_chart(report, SHEET_WIDTH, h).body,
    )
}

fn place(sheet: &mut Svg, x: f64, y: f64, chart: &Svg) {
    sheet.body.push_str(&format!(
        "<g transform=\"translate({x} {y})\">\n{}</g>\n",
        chart.body
    ));
}

fn header(svg: &mut Svg, report: &Report) {
    let title = format!(
        "Calibration accuracy report: robot {}, parameter set v{}",
        report.serial, report.version
    );
    svg.bold_text(MARGIN_LEFT / 3.0, 26.0, "start", 18.0, &title);
    let meta = format!(
        "created {} · job {} · session {} · {} ({})",
        report.created_at, report.job_id, report.session_id, report.instrument, report.measurement
    );
    svg.text(
        MARGIN_LEFT / 3.0,
        46.0,
        "start",
        FONT_SIZE,
        MUTED_COLOR,
        &meta,
    );
    svg.bold_text(MARGIN_LEFT / 3.0, 66.0, "start", 12.5, &headline(report));
}

fn plot_area(width: f64, height: f64, extra_bottom: f64, margin_right: f64) -> Area {
    Area {
        x: MARGIN_LEFT,
        y: MARGIN_TOP,
        w: width - MARGIN_LEFT - margin_right,
        h: height - MARGIN_TOP - MARGIN_BOTTOM - extra_bottom,
    }
}

/// The poses the accuracy statistics are about: the validation set, or
/// every pose when the campaign has none (the title says which).
fn judged_poses(report: &Report) -> (Vec<&PoseReport>, &'static str) {
    let val: Vec<&PoseReport> = report.per_pose.iter().filter(|p| p.set == "val").collect();
    if val.is_empty() {
        (
            report.per_pose.iter().collect(),
            "all poses (no validation set)",
        )
    } else {
        (val, "validation poses")
    }
}

fn axis_label(what: &str, scale: &Scale) -> String {
    if scale.log {
        format!("{what} [mm] (log scale)")
    } else {
        format!("{what} [mm]")
    }
}

fn no_data(svg: &mut Svg, area: Area, text: &str) {
    svg.outline(area.x, area.y, area.w, area.h, GRID_COLOR);
    svg.text(
        area.x + area.w / 2.0,
        area.y + area.h / 2.0,
        "middle",
        FONT_SIZE,
        MUTED_COLOR,
        text,
    );
}

/// Dumbbell plot: before and after error of each judged pose joined by a
/// line, with both means as dashed lines.
fn pose_chart(report: &Report, width: f64, height: f64) -> Svg {
    let mut svg = Svg::default();
    let (poses, which) = judged_poses(report);
    svg.title(
        MARGIN_LEFT,
        TITLE_Y,
        &format!("3-D position error per pose, {which}"),
    );
    legend(
        &mut svg,
        MARGIN_LEFT,
        LEGEND_Y,
        &[
            (
                Mark::Dot(BEFORE_COLOR),
                "before (nominal kinematics; base and hand–eye fitted)",
            ),
            (Mark::Dot(AFTER_COLOR), "after calibration"),
            (Mark::Dash(MUTED_COLOR), "mean"),
        ],
    );
    let area = plot_area(width, height, POSE_LABEL_ROOM, MEAN_LABEL_ROOM);
    if poses.is_empty() {
        no_data(&mut svg, area, "no poses in this report");
        return svg;
    }
    let values: Vec<f64> = poses
        .iter()
        .flat_map(|p| [p.before_mm, p.after_mm])
        .collect();
    let scale = Scale::for_magnitudes(&values, area.bottom(), area.y);
    y_axis(&mut svg, area, &scale, &axis_label("3-D error", &scale));
    svg.line(
        area.x,
        area.bottom(),
        area.right(),
        area.bottom(),
        AXIS_COLOR,
        1.0,
    );
    let band = area.w / poses.len() as f64;
    let label_every = poses.len().div_ceil(MAX_POSE_LABELS);
    for (i, pose) in poses.iter().enumerate() {
        let x = area.x + band * (i as f64 + 0.5);
        let (yb, ya) = (scale.map(pose.before_mm), scale.map(pose.after_mm));
        svg.line(x, yb, x, ya, "#bbb", 1.5);
        svg.circle(x, yb, DOT_RADIUS, BEFORE_COLOR);
        svg.circle(x, ya, DOT_RADIUS, AFTER_COLOR);
        svg.line(
            x,
            area.bottom(),
            x,
            area.bottom() + TICK_LENGTH,
            AXIS_COLOR,
            1.0,
        );
        if i % label_every == 0 {
            let y = area.bottom() + TICK_LENGTH + 4.0;
            svg.rotated_text(x + 3.0, y, -60.0, "end", &pose.pose_id);
        }
    }
    let stats = [
        (report.before.three_d.mean_mm, BEFORE_COLOR),
        (report.after.three_d.mean_mm, AFTER_COLOR),
    ];
    for (mean, color) in stats {
        if mean.is_finite() && mean > 0.0 {
            let y = scale.map(mean);
            svg.dashed_line(area.x, y, area.right(), y, color);
            svg.text(
                area.right() + 4.0,
                y - 2.0,
                "start",
                SMALL_FONT,
                color,
                "mean",
            );
            svg.text(
                area.right() + 4.0,
                y + SMALL_FONT,
                "start",
                SMALL_FONT,
                color,
                &format!("{} mm", mm(mean)),
            );
        }
    }
    let x_label = "pose id";
    svg.text(
        area.x + area.w / 2.0,
        height - 8.0,
        "middle",
        FONT_SIZE,
        TEXT_COLOR,
        x_label,
    );
    svg
}

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
fn histogram_chart(report: &Report, width: f64, height: f64) -> Svg {
    let mut svg = Svg::default();
    let (poses, which) = judged_poses(report);
    svg.title(MARGIN_LEFT, TITLE_Y, &format!("Error histogram, {which}"));
    legend(
        &mut svg,
        MARGIN_LEFT,
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
fn axis_chart(report: &Report, width: f64, height: f64) -> Svg {
    let mut svg = Svg::default();
    let (_, which) = judged_poses(report);
    svg.title(MARGIN_LEFT, TITLE_Y, &format!("Error per axis, {which}"));
    legend(
        &mut svg,
        MARGIN_LEFT,
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
        ("3-D", &b.three_d, &a.three_d),
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
            if area.bottom() - top > 2.0 * SMALL_FONT {
                svg.text(
                    xm,
                    top + SMALL_FONT + 2.0,
                    "middle",
                    SMALL_FONT,
                    "white",
                    &mm(stats.mean_mm),
                );
            }
        }
        let y = area.bottom() + TICK_LENGTH + FONT_SIZE + 3.0;
        svg.text(centre, y, "middle", FONT_SIZE, TEXT_COLOR, name);
    }
    let factor = if a.three_d.mean_mm > 0.0 {
        b.three_d.mean_mm / a.three_d.mean_mm
    } else {
        f64::NAN
    };
    let note = format!(
        "mean 3-D error {}x smaller after calibration",
        fixed(factor, 1)
    );
    svg.text(
        area.x + area.w / 2.0,
        area.bottom() + 34.0,
        "middle",
        FONT_SIZE,
        MUTED_COLOR,
        &note,
    );
    svg
}
