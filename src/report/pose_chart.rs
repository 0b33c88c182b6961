//! The report's pose chart: before and after error of every judged pose,
//! named under the axis by its label (ellipsized and thinned so that 5 to
//! 200 poses stay readable).

use super::chart_frame::{
    axis_label, judged_poses, no_data, plot_area, LEGEND_Y, SMALL_FONT, TITLE_Y,
};
use super::format::{before_fit, ellipsize, mm};
use super::model::{PoseReport, Report};
use super::plot::*;

/// Most characters of a pose name under the pose axis; longer names lose
/// their middle (a 36-character id or a long file name would run into the
/// charts below).
pub(super) const CHART_NAME_CHARS: usize = 18;
/// Pose names are written slanted, reading upwards to their tick.
pub(super) const POSE_NAME_ANGLE_DEG: f64 = -60.0;
/// Average advance of a character of the chart font (sans-serif, 11 px).
pub(super) const CHAR_WIDTH: f64 = FONT_SIZE * 0.6;
/// Gaps above and below the slanted names.
pub(super) const POSE_NAME_PADDING: f64 = 8.0;
/// Room right of the pose chart for the mean labels.
pub(super) const MEAN_LABEL_ROOM: f64 = 70.0;
pub(super) const DOT_RADIUS: f64 = 3.6;
/// Dots shrink to this fraction of the per-pose band when poses are many.
pub(super) const DOT_BAND_FRACTION: f64 = 0.3;
/// Most pose names written under the pose axis before thinning them out.
pub(super) const MAX_POSE_LABELS: usize = 40;
/// Least horizontal distance between two slanted names (they would
/// overlap closer than one line height across their slant).
pub(super) const MIN_POSE_LABEL_SPACING: f64 = FONT_SIZE * 1.35;
/// Height of the pose chart without the room its pose names take
/// ([`pose_chart_height`] adds that).
pub const POSE_CHART_HEIGHT: f64 = 312.0;

/// A pose's name as written under the pose axis.
pub(super) fn chart_name(pose: &PoseReport) -> String {
    ellipsize(pose.name(), CHART_NAME_CHARS)
}

/// Room under the pose axis for the slanted names: as deep as the longest
/// name written reaches.
pub(super) fn pose_label_room(report: &Report) -> f64 {
    let longest = judged_poses(report)
        .0
        .iter()
        .map(|p| chart_name(p).chars().count())
        .max()
        .unwrap_or(0);
    let slant = POSE_NAME_ANGLE_DEG.to_radians().sin().abs();
    TICK_LENGTH + 2.0 * POSE_NAME_PADDING + longest as f64 * CHAR_WIDTH * slant
}

/// Height of the pose chart with room for its pose names.
pub fn pose_chart_height(report: &Report) -> f64 {
    POSE_CHART_HEIGHT + pose_label_room(report)
}

/// Every how many poses a name is written: at most [`MAX_POSE_LABELS`]
/// names, never closer than [`MIN_POSE_LABEL_SPACING`].
pub(super) fn label_every(poses: usize, band: f64) -> usize {
    let by_count = poses.div_ceil(MAX_POSE_LABELS);
    let by_spacing = (MIN_POSE_LABEL_SPACING / band).ceil() as usize;
    by_count.max(by_spacing).max(1)
}

/// Dumbbell plot: before and after error of each judged pose joined by a
/// line, with both means as dashed lines.
pub(super) fn pose_chart(report: &Report, width: f64, height: f64) -> Svg {
    let mut svg = Svg::default();
    let (poses, which) = judged_poses(report);
    svg.title(
        TITLE_X,
        TITLE_Y,
        &format!("3-D position error per pose, {which}"),
    );
    let before_label = format!(
        "before (nominal kinematics; base and {} fitted)",
        before_fit(report)
    );
    legend(
        &mut svg,
        TITLE_X,
        LEGEND_Y,
        &[
            (Mark::Dot(BEFORE_COLOR), &before_label),
            (Mark::Dot(AFTER_COLOR), "after calibration"),
            (Mark::Dash(MUTED_COLOR), "mean"),
        ],
    );
    let area = plot_area(width, height, pose_label_room(report), MEAN_LABEL_ROOM);
    if poses.is_empty() {
        no_data(&mut svg, area, "no poses in this report");
        return svg;
    }
    // The means are drawn too, so the axis covers them.
    let means = [report.before.norm.mean_mm, report.after.norm.mean_mm];
    let values: Vec<f64> = poses
        .iter()
        .flat_map(|p| [p.before_mm, p.after_mm])
        .chain(means)
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
    let radius = DOT_RADIUS.min(band * DOT_BAND_FRACTION);
    let label_every = label_every(poses.len(), band);
    for (i, pose) in poses.iter().enumerate() {
        let x = area.x + band * (i as f64 + 0.5);
        let (yb, ya) = (scale.map(pose.before_mm), scale.map(pose.after_mm));
        svg.line(x, yb, x, ya, "#bbb", 1.5);
        svg.circle(x, yb, radius, BEFORE_COLOR);
        svg.circle(x, ya, radius, AFTER_COLOR);
        svg.line(
            x,
            area.bottom(),
            x,
            area.bottom() + TICK_LENGTH,
            AXIS_COLOR,
            1.0,
        );
        if i % label_every == 0 {
            let y = area.bottom() + TICK_LENGTH + POSE_NAME_PADDING / 2.0;
            svg.rotated_text(x + 3.0, y, POSE_NAME_ANGLE_DEG, "end", &chart_name(pose));
        }
    }
    let stats = [
        (report.before.norm.mean_mm, BEFORE_COLOR),
        (report.after.norm.mean_mm, AFTER_COLOR),
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
    let x_label = if label_every > 1 {
        format!("pose (one name per {label_every} poses; all names in the table)")
    } else {
        "pose".to_string()
    };
    svg.text(
        area.x + area.w / 2.0,
        height - 8.0,
        "middle",
        FONT_SIZE,
        TEXT_COLOR,
        &x_label,
    );
    svg
}
