//! The report's charts as SVG (issue 6): 3-D error per validation pose,
//! error histogram, per-axis errors, a multi-session set's errors per
//! region and per volume (`regions_chart.rs`, issue 18), a stage set's
//! error against distance (`stage_chart.rs`, paper Fig. 5), and the
//! reprojection residual field (in `field.rs`). [`render_svg`] puts them on one self-contained sheet
//! under a header; the HTML report embeds the charts one by one.

use super::distribution::{axis_chart, histogram_chart};
use super::field::{field_height, residual_field_chart};
use super::format::headline;
use super::model::Report;
use super::plot::*;
use super::pose_chart::pose_chart;
pub use super::pose_chart::{pose_chart_height, POSE_CHART_HEIGHT};
use super::regions_chart::{region_chart, volume_chart, REGION_CHART_TITLE, VOLUME_CHART_TITLE};
use super::stage_chart::{has_stage_sequences, stage_chart, STAGE_CHART_TITLE};
use super::uncertainty_chart::{uncertainty_chart, uncertainty_height};

/// Width of the whole sheet and of full-width charts.
pub const SHEET_WIDTH: f64 = 880.0;
/// Width of the two charts side by side.
pub const HALF_WIDTH: f64 = SHEET_WIDTH / 2.0;
const HEADER_HEIGHT: f64 = 78.0;
/// Baselines of the header's title, metadata and summary lines.
const HEADER_LINES: [f64; 3] = [26.0, 46.0, 66.0];
const HEADER_TITLE_SIZE: f64 = 18.0;
const HEADER_SUMMARY_SIZE: f64 = 12.5;
pub const SMALL_CHART_HEIGHT: f64 = 310.0;

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
    if !report.regions.is_empty() {
        place(
            &mut sheet,
            0.0,
            y,
            &region_chart(report, HALF_WIDTH, SMALL_CHART_HEIGHT),
        );
        place(
            &mut sheet,
            HALF_WIDTH,
            y,
            &volume_chart(report, HALF_WIDTH, SMALL_CHART_HEIGHT),
        );
        y += SMALL_CHART_HEIGHT;
    }
    if has_stage_sequences(report) {
        place(
            &mut sheet,
            0.0,
            y,
            &stage_chart(report, HALF_WIDTH, SMALL_CHART_HEIGHT),
        );
        y += SMALL_CHART_HEIGHT;
    }
    let field_h = field_height(report, SHEET_WIDTH);
    place(
        &mut sheet,
        0.0,
        y,
        &residual_field_chart(report, SHEET_WIDTH, field_h),
    );
    y += field_h;
    if report.uncertainty_map.is_some() {
        let map_h = uncertainty_height(SHEET_WIDTH);
        place(
            &mut sheet,
            0.0,
            y,
            &uncertainty_chart(report, SHEET_WIDTH, map_h),
        );
        y += map_h;
    }
    let title = format!(
        "Calibration accuracy report, robot {} v{}",
        report.serial, report.version
    );
    standalone(SHEET_WIDTH, y, &title, &sheet.body)
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
/// The paper's Figs 7 and 9 (errors per region) of a multi-session set.
pub fn regions_svg(report: &Report) -> String {
    standalone(
        HALF_WIDTH,
        SMALL_CHART_HEIGHT,
        REGION_CHART_TITLE,
        &region_chart(report, HALF_WIDTH, SMALL_CHART_HEIGHT).body,
    )
}
/// The paper's Fig. 10 (errors per volume) of a multi-session set.
pub fn volumes_svg(report: &Report) -> String {
    standalone(
        HALF_WIDTH,
        SMALL_CHART_HEIGHT,
        VOLUME_CHART_TITLE,
        &volume_chart(report, HALF_WIDTH, SMALL_CHART_HEIGHT).body,
    )
}
/// The paper's Fig. 5 (error against distance) of a stage set.
pub fn stage_accuracy_svg(report: &Report) -> String {
    standalone(
        HALF_WIDTH,
        SMALL_CHART_HEIGHT,
        STAGE_CHART_TITLE,
        &stage_chart(report, HALF_WIDTH, SMALL_CHART_HEIGHT).body,
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

pub fn uncertainty_map_svg(report: &Report) -> String {
    let h = uncertainty_height(SHEET_WIDTH);
    standalone(
        SHEET_WIDTH,
        h,
        "Predicted uncertainty over the workspace",
        &uncertainty_chart(report, SHEET_WIDTH, h).body,
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

#[cfg(test)]
#[path = "svg_tests.rs"]
mod tests;
