//! What every chart of the report shares: the plot area inside its
//! margins, the title and legend lines, the poses the statistics judge,
//! axis labels and the empty-chart note.

use super::model::{PoseReport, Report};
use super::plot::*;

/// Room left of the plot area for tick labels and the rotated axis label.
pub const MARGIN_LEFT: f64 = 66.0;
pub const MARGIN_RIGHT: f64 = 24.0;
/// Room above the plot area for the title and legend.
pub const MARGIN_TOP: f64 = 54.0;
pub const MARGIN_BOTTOM: f64 = 50.0;
pub const TITLE_Y: f64 = 20.0;
pub const LEGEND_Y: f64 = 40.0;
pub const SMALL_FONT: f64 = 9.5;
/// Approximate width of a digit in [`SMALL_FONT`], to see if a label fits.
pub const SMALL_CHAR_WIDTH: f64 = 5.6;

pub fn plot_area(width: f64, height: f64, extra_bottom: f64, margin_right: f64) -> Area {
    Area {
        x: MARGIN_LEFT,
        y: MARGIN_TOP,
        w: width - MARGIN_LEFT - margin_right,
        h: height - MARGIN_TOP - MARGIN_BOTTOM - extra_bottom,
    }
}

/// The poses the accuracy statistics are about: the validation set, or
/// every pose when the campaign has none (the title says which); never
/// the poses the screening left out.
pub fn judged_poses(report: &Report) -> (Vec<&PoseReport>, &'static str) {
    // Outliers were left out of the fit and count in no statistic.
    let kept = || report.per_pose.iter().filter(|p| !p.outlier);
    let val: Vec<&PoseReport> = kept().filter(|p| p.set == "val").collect();
    if val.is_empty() {
        (kept().collect(), "all poses (no validation set)")
    } else {
        (val, "validation poses")
    }
}

pub fn axis_label(what: &str, scale: &Scale) -> String {
    if scale.log {
        format!("{what} [mm] (log scale)")
    } else {
        format!("{what} [mm]")
    }
}

pub fn no_data(svg: &mut Svg, area: Area, text: &str) {
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
