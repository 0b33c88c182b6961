//! The report's charts as SVG (issue 6): 3-D error per validation pose,
//! error histogram, per-axis errors, and the reprojection residual field
//! (in `field.rs`). [`render_svg`] puts them on one self-contained sheet
//! under a header; the HTML report embeds the charts one by one.

use super::distribution::{axis_chart, histogram_chart};
use super::field::{field_height, residual_field_chart};
use super::format::{before_fit, ellipsize, headline, mm};
use super::model::{PoseReport, Report};
use super::plot::*;

/// Width of the whole sheet and of full-width charts.
pub const SHEET_WIDTH: f64 = 880.0;
/// Width of the two charts side by side.
pub const HALF_WIDTH: f64 = SHEET_WIDTH / 2.0;
const HEADER_HEIGHT: f64 = 78.0;
/// Baselines of the header's title, metadata and summary lines.
const HEADER_LINES: [f64; 3] = [26.0, 46.0, 66.0];
const HEADER_TITLE_SIZE: f64 = 18.0;
const HEADER_SUMMARY_SIZE: f64 = 12.5;
/// Height of the pose chart without the room its pose names take
/// ([`pose_chart_height`] adds that).
pub const POSE_CHART_HEIGHT: f64 = 312.0;
pub const SMALL_CHART_HEIGHT: f64 = 310.0;
/// Room left of the plot area for tick labels and the rotated axis label.
pub(super) const MARGIN_LEFT: f64 = 66.0;
pub(super) const MARGIN_RIGHT: f64 = 24.0;
/// Room above the plot area for the title and legend.
const MARGIN_TOP: f64 = 54.0;
const MARGIN_BOTTOM: f64 = 50.0;
/// Most characters of a pose name under the pose axis; longer names lose
/// their middle (a 36-character id or a long file name would run into the
/// charts below).
const CHART_NAME_CHARS: usize = 18;
/// Pose names are written slanted, reading upwards to their tick.
const POSE_NAME_ANGLE_DEG: f64 = -60.0;
/// Average advance of a character of the chart font (sans-serif, 11 px).
const CHAR_WIDTH: f64 = FONT_SIZE * 0.6;
/// Gaps above and below the slanted names.
const POSE_NAME_PADDING: f64 = 8.0;
/// Room right of the pose chart for the mean labels.
const MEAN_LABEL_ROOM: f64 = 70.0;
pub(super) const TITLE_Y: f64 = 20.0;
pub(super) const LEGEND_Y: f64 = 40.0;
const DOT_RADIUS: f64 = 3.6;
/// Dots shrink to this fraction of the per-pose band when poses are many.
const DOT_BAND_FRACTION: f64 = 0.3;
/// Most pose names written under the pose axis before thinning them out.
const MAX_POSE_LABELS: usize = 40;
/// Least horizontal distance between two slanted names (they would
/// overlap closer than one line height across their slant).
const MIN_POSE_LABEL_SPACING: f64 = FONT_SIZE * 1.35;
pub(super) const SMALL_FONT: f64 = 9.5;

/// The whole report as one standalone SVG document.
pub fn render_svg(report: &Report) -> String {
    let mut sheet = Svg::default();
    header(&mut sheet, report);
    let mut y = HEADER_HEIGHT;
    let pose_h = pose_chart_height(report);
    place(&mut sheet, 0.0, y, &pose_chart(report, SHEET_WIDTH, pose_h));
    y += pose_h;
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
    let title = format!(
        "Calibration accuracy report, robot {} v{}",
        report.serial, report.version
    );
    standalone(SHEET_WIDTH, y + field_h, &title, &sheet.body)
}

/// Standalone chart documents, for embedding one by one in the HTML page.
pub fn pose_errors_svg(report: &Report) -> String {
    let h = pose_chart_height(report);
    standalone(
        SHEET_WIDTH,
        h,
        "3-D position error per pose",
        &pose_chart(report, SHEET_WIDTH, h).body,
    )
}
pub fn histogram_svg(report: &Report) -> String {
    standalone(
        HALF_WIDTH,
        SMALL_CHART_HEIGHT,
        "Error histogram",
        &histogram_chart(report, HALF_WIDTH, SMALL_CHART_HEIGHT).body,
    )
}
pub fn axis_errors_svg(report: &Report) -> String {
    standalone(
        HALF_WIDTH,
        SMALL_CHART_HEIGHT,
        "Error per axis",
        &axis_chart(report, HALF_WIDTH, SMALL_CHART_HEIGHT).body,
    )
}
pub fn residual_field_svg(report: &Report) -> String {
    let h = field_height(report, SHEET_WIDTH);
    standalone(
        SHEET_WIDTH,
        h,
        "Reprojection residual field",
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
    svg.bold_text(TITLE_X, HEADER_LINES[0], "start", HEADER_TITLE_SIZE, &title);
    let meta = format!(
        "created {} · job {} · session {} · {} ({})",
        report.created_at, report.job_id, report.session_id, report.instrument, report.measurement
    );
    svg.text(
        TITLE_X,
        HEADER_LINES[1],
        "start",
        FONT_SIZE,
        MUTED_COLOR,
        &meta,
    );
    let summary = headline(report);
    svg.bold_text(
        TITLE_X,
        HEADER_LINES[2],
        "start",
        HEADER_SUMMARY_SIZE,
        &summary,
    );
}

pub(super) fn plot_area(width: f64, height: f64, extra_bottom: f64, margin_right: f64) -> Area {
    Area {
        x: MARGIN_LEFT,
        y: MARGIN_TOP,
        w: width - MARGIN_LEFT - margin_right,
        h: height - MARGIN_TOP - MARGIN_BOTTOM - extra_bottom,
    }
}

/// The poses the accuracy statistics are about: the validation set, or
/// every pose when the campaign has none (the title says which).
pub(super) fn judged_poses(report: &Report) -> (Vec<&PoseReport>, &'static str) {
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

pub(super) fn axis_label(what: &str, scale: &Scale) -> String {
    if scale.log {
        format!("{what} [mm] (log scale)")
    } else {
        format!("{what} [mm]")
    }
}

pub(super) fn no_data(svg: &mut Svg, area: Area, text: &str) {
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

/// A pose's name as written under the pose axis.
fn chart_name(pose: &PoseReport) -> String {
    ellipsize(pose.name(), CHART_NAME_CHARS)
}

/// Room under the pose axis for the slanted names: as deep as the longest
/// name written reaches.
fn pose_label_room(report: &Report) -> f64 {
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
fn label_every(poses: usize, band: f64) -> usize {
    let by_count = poses.div_ceil(MAX_POSE_LABELS);
    let by_spacing = (MIN_POSE_LABEL_SPACING / band).ceil() as usize;
    by_count.max(by_spacing).max(1)
}

/// Dumbbell plot: before and after error of each judged pose joined by a
/// line, with both means as dashed lines.
fn pose_chart(report: &Report, width: f64, height: f64) -> Svg {
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

#[cfg(test)]
mod tests {
    use super::*;
    use crate::report::sample::{sample_report, sample_report_sized, sample_tracker_report};
    use crate::report::xml_check::check_balanced;
    use crate::report::ErrorStats;

    #[test]
    fn sheet_is_well_formed_and_shows_every_validation_pose() {
        let report = sample_report();
        let svg = render_svg(&report);
        check_balanced(&svg, false).unwrap();
        assert!(svg.starts_with("<svg xmlns=\"http://www.w3.org/2000/svg\""));
        assert!(!svg.contains("href") && !svg.contains("url(") && !svg.contains("<image"));
        for pose in report.per_pose.iter().filter(|p| p.set == "val") {
            let name = chart_name(pose);
            assert!(svg.contains(&format!(">{name}</text>")), "{name}");
            assert!(name.ends_with("_pose_") || name.ends_with(".png"), "{name}");
        }
        // One before and one after dot per validation pose.
        let dots = |color: &str| {
            svg.matches(&format!("r=\"{DOT_RADIUS}\" fill=\"{color}\""))
                .count()
        };
        assert_eq!((dots(BEFORE_COLOR), dots(AFTER_COLOR)), (30, 30));
        for title in [
            "per pose",
            "histogram",
            "per axis",
            "residual field",
            "magnified",
        ] {
            assert!(svg.contains(title), "{title}");
        }
        for chart in [
            pose_errors_svg,
            histogram_svg,
            axis_errors_svg,
            residual_field_svg,
        ] {
            check_balanced(&chart(&report), false).unwrap();
        }
    }

    /// The slanted pose names of the pose chart: (x, y, text).
    fn pose_names(chart: &Svg) -> Vec<(f64, f64, String)> {
        let attr = |line: &str, name: &str| -> f64 {
            let start = line.find(&format!(" {name}=\"")).unwrap() + name.len() + 3;
            line[start..].split('"').next().unwrap().parse().unwrap()
        };
        chart
            .body
            .lines()
            .filter(|l| l.contains(&format!("rotate({POSE_NAME_ANGLE_DEG} ")))
            .map(|l| {
                let text = l.rsplit_once("\">").unwrap().1.trim_end_matches("</text>");
                (attr(l, "x"), attr(l, "y"), text.to_string())
            })
            .collect()
    }

    #[test]
    fn pose_names_stay_inside_the_chart_and_apart_from_5_to_200_poses() {
        let slant = POSE_NAME_ANGLE_DEG.to_radians();
        for poses in [5, 61, 200] {
            for stored_before_labels in [false, true] {
                let mut report = sample_report_sized(poses - poses / 2, poses / 2);
                if stored_before_labels {
                    // Old reports: 36-character ids only.
                    report.per_pose.iter_mut().for_each(|p| p.label.clear());
                }
                let height = pose_chart_height(&report);
                let chart = pose_chart(&report, SHEET_WIDTH, height);
                let names = pose_names(&chart);
                let case = format!("{poses} poses, labels cleared: {stored_before_labels}");
                assert!(
                    !names.is_empty() && names.len() <= MAX_POSE_LABELS,
                    "{case}"
                );
                for pair in names.windows(2) {
                    assert!(pair[1].0 - pair[0].0 >= MIN_POSE_LABEL_SPACING, "{case}");
                }
                for (x, y, text) in &names {
                    let chars = text.chars().count();
                    assert!(chars <= CHART_NAME_CHARS, "{case}: {text}");
                    let length = chars as f64 * CHAR_WIDTH;
                    // Above the axis title, right of the sheet's edge.
                    assert!(
                        y + length * slant.sin().abs() < height - FONT_SIZE - 8.0,
                        "{case}"
                    );
                    assert!(x - length * slant.cos() > 0.0, "{case}: {text}");
                }
                let judged = judged_poses(&report).0;
                let area = plot_area(
                    SHEET_WIDTH,
                    height,
                    pose_label_room(&report),
                    MEAN_LABEL_ROOM,
                );
                let every = label_every(judged.len(), area.w / judged.len() as f64);
                let expected: Vec<String> =
                    judged.into_iter().step_by(every).map(chart_name).collect();
                let named: Vec<&str> = names.iter().map(|n| n.2.as_str()).collect();
                assert_eq!(named, expected, "{case}");
            }
        }
    }

    #[test]
    fn hostile_serial_and_pose_ids_are_escaped() {
        let mut report = sample_report();
        report.serial = "<script>alert('x')</script>".into();
        report.per_pose.last_mut().unwrap().label = "a&b<\"c\">".into();
        let svg = render_svg(&report);
        assert!(!svg.contains("<script"));
        assert!(svg.contains("&lt;script&gt;alert(&#39;x&#39;)&lt;/script&gt;"));
        assert!(svg.contains("a&amp;b&lt;&quot;c&quot;&gt;"));
        check_balanced(&svg, false).unwrap();
    }

    #[test]
    fn tracker_session_gets_a_note_instead_of_the_field() {
        let svg = render_svg(&sample_tracker_report());
        check_balanced(&svg, false).unwrap();
        assert!(svg.contains("No camera in this session (instrument: tracker)"));
        assert!(!svg.contains("magnified"));
    }

    #[test]
    fn empty_and_non_finite_reports_render_without_panicking() {
        let mut empty = sample_tracker_report();
        empty.per_pose.clear();
        empty.before = Default::default();
        empty.after = Default::default();
        let svg = render_svg(&empty);
        check_balanced(&svg, false).unwrap();
        assert!(svg.contains("no poses in this report") && !svg.contains("NaN"));

        let mut broken = sample_report();
        broken.per_pose[40].before_mm = f64::NAN;
        broken.per_pose[41].after_mm = f64::INFINITY;
        broken.after.norm = ErrorStats {
            mean_mm: f64::NAN,
            ..Default::default()
        };
        broken.residual_field[0].dx_px = f64::NAN;
        if let Some(camera) = broken.camera.as_mut() {
            camera.image_width = 0;
        }
        let svg = render_svg(&broken);
        check_balanced(&svg, false).unwrap();
        assert!(!svg.contains("NaN") && !svg.contains("inf"));
        check_balanced(&crate::report::render_html(&broken), true).unwrap();
        assert!(!crate::report::render_table(&broken).is_empty());
    }
}
