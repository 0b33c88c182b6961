//! The paper's Fig. 5 for a stage session's report (issue 18): the mean,
//! median and standard deviation of the measurement system's 3-D position
//! error (per-axis figures of Table 1 combined as a root sum of squares)
//! against the distance from the camera to the board's centre.

use super::chart_frame::{no_data, plot_area, LEGEND_Y, MARGIN_RIGHT, TITLE_Y};
use super::measurement_accuracy::SequenceAccuracyReport;
use super::model::Report;
use super::plot::*;

const MEAN_COLOR: &str = "#1f5fa8";
const MEDIAN_COLOR: &str = "#2e8b57";
const STD_COLOR: &str = "#d9730d";
const POINT_RADIUS: f64 = 3.5;
const LINE_WIDTH: f64 = 1.5;
/// The distance axis reaches this far beyond the sequences (mm).
const DISTANCE_PAD_MM: f64 = 50.0;
/// The chart's title, on the report sheet and the page alike.
pub const STAGE_CHART_TITLE: &str = "3-D position accuracy against distance (paper Fig. 5)";

/// One plotted statistic of a sequence (mm).
type Statistic = fn(&SequenceAccuracyReport) -> f64;

/// `|[x, y, z]|`: a Table-1 statistic as one 3-D figure.
fn rss(v: [f64; 3]) -> f64 {
    v.iter().map(|c| c * c).sum::<f64>().sqrt()
}

/// Whether the report is a stage set's, with sequences to draw.
pub fn has_stage_sequences(report: &Report) -> bool {
    report
        .measurement_accuracy
        .as_ref()
        .is_some_and(|m| !m.sequences.is_empty())
}

/// The chart; "no data" when the report has no stage section.
pub fn stage_chart(report: &Report, width: f64, height: f64) -> Svg {
    let mut svg = Svg::default();
    svg.title(TITLE_X, TITLE_Y, STAGE_CHART_TITLE);
    let series: [(&str, &str, Statistic); 3] = [
        ("mean", MEAN_COLOR, |s| rss(s.mean_mm)),
        ("median", MEDIAN_COLOR, |s| rss(s.median_mm)),
        ("std. dev.", STD_COLOR, |s| rss(s.std_mm)),
    ];
    let entries: Vec<(Mark, &str)> = series.iter().map(|(n, c, _)| (Mark::Dot(c), *n)).collect();
    legend(&mut svg, TITLE_X, LEGEND_Y, &entries);
    let area = plot_area(width, height, 0.0, MARGIN_RIGHT);
    let rows = report
        .measurement_accuracy
        .as_ref()
        .map_or(&[][..], |m| m.sequences.as_slice());
    if rows.is_empty() {
        no_data(&mut svg, area, "no stage sequences in this report");
        return svg;
    }
    let distances: Vec<f64> = rows.iter().map(|r| r.distance_mm).collect();
    let lo = distances.iter().copied().fold(f64::INFINITY, f64::min) - DISTANCE_PAD_MM;
    let hi = distances.iter().copied().fold(f64::NEG_INFINITY, f64::max) + DISTANCE_PAD_MM;
    let x = Scale::linear(lo, hi, area.x, area.right());
    let top = rows
        .iter()
        .flat_map(|r| series.iter().map(move |(_, _, f)| f(r)))
        .fold(0.0, f64::max);
    let y = Scale::linear(0.0, top.max(f64::MIN_POSITIVE), area.bottom(), area.y);
    y_axis(&mut svg, area, &y, "position error [mm]");
    x_axis(
        &mut svg,
        area,
        &x,
        "distance from the camera to the board centre [mm]",
    );
    let mut order: Vec<&SequenceAccuracyReport> = rows.iter().collect();
    order.sort_by(|a, b| a.distance_mm.total_cmp(&b.distance_mm));
    for (_, color, value) in &series {
        let points: Vec<(f64, f64)> = order
            .iter()
            .map(|r| (x.map(r.distance_mm), y.map(value(r))))
            .collect();
        let d: String = points
            .iter()
            .enumerate()
            .map(|(i, (px, py))| format!("{}{px:.1},{py:.1} ", if i == 0 { "M" } else { "L" }))
            .collect();
        svg.path(d.trim_end(), color, LINE_WIDTH, "none");
        for (px, py) in points {
            svg.circle(px, py, POINT_RADIUS, color);
        }
    }
    svg
}

#[cfg(test)]
#[path = "stage_chart_tests.rs"]
mod tests;
