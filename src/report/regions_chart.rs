//! The paper's Figs 7, 9 and 10 for a multi-session set (issue 18): the
//! mean 3-D validation error before and after calibration in each region
//! (Fig. 7), the region's own local model beside the global one where the
//! robot had one (Fig. 9), and the same per volume (Fig. 10), as grouped
//! bar charts. One function per figure: report.svg places them on its
//! sheet and report.html embeds them, so both draw the same charts.

use super::chart_frame::{
    no_data, plot_area, LEGEND_Y, MARGIN_RIGHT, SMALL_CHAR_WIDTH, SMALL_FONT, TITLE_Y,
};
use super::format::{ellipsize, mm};
use super::model::{ErrorStats, Report};
use super::plot::*;
use super::pose_chart::CHAR_WIDTH;
use super::regions::RegionReport;

pub const REGION_CHART_TITLE: &str = "Error per region, before and after (paper Figs 7 and 9)";
pub const VOLUME_CHART_TITLE: &str = "Error per volume, before and after (paper Fig. 10)";
/// The group of the regions that named no volume.
pub const NO_VOLUME: &str = "(no volume)";
/// The local model's bars: green, apart from before (orange) and after (blue).
pub const LOCAL_COLOR: &str = "#2e8b57";
/// Relative width of a group's bars inside its slot.
const GROUP_FILL: f64 = 0.8;
/// Relative width of a bar inside its share of the group.
const BAR_FILL: f64 = 0.9;
const BAR_OPACITY: f64 = 0.85;
/// Gap between a bar's top and its value label.
const VALUE_LABEL_GAP: f64 = 3.0;
/// How far a value label may reach past its bar's share of the group
/// (px) before it is left out (then the axis alone gives the value).
const VALUE_LABEL_OVERHANG: f64 = 4.0;

/// The bars of every group, in this order (legend and bars agree).
const SERIES: [(&str, &str); 3] = [
    ("before", BEFORE_COLOR),
    ("global", AFTER_COLOR),
    ("local", LOCAL_COLOR),
];

/// One group of bars: its name and the mean error (mm) of each of
/// [`SERIES`], `None` for a bar not drawn (no local set).
struct Group {
    name: String,
    means: [Option<f64>; 3],
}

/// The region's name on the charts and in the tables: its `region`, or
/// its session's id when it named none.
pub fn region_name(r: &RegionReport) -> String {
    r.region.clone().unwrap_or_else(|| r.session_id.clone())
}

/// The mean over the members' poses (each region's mean weighted by its
/// pose count); `None` when a member lacks the figure or there are no poses.
fn pooled_mean(
    members: &[&RegionReport],
    stats: fn(&RegionReport) -> Option<&ErrorStats>,
) -> Option<f64> {
    let all: Option<Vec<&ErrorStats>> = members.iter().map(|r| stats(r)).collect();
    let all = all?;
    let poses: usize = all.iter().map(|s| s.n).sum();
    (poses > 0).then(|| all.iter().map(|s| s.mean_mm * s.n as f64).sum::<f64>() / poses as f64)
}

fn group(name: String, members: &[&RegionReport]) -> Group {
    Group {
        name,
        means: [
            pooled_mean(members, |r| Some(&r.before.norm)),
            pooled_mean(members, |r| Some(&r.after.norm)),
            pooled_mean(members, |r| r.local.as_ref().map(|l| &l.after.norm)),
        ],
    }
}

/// Figs 7 and 9: one group per region.
pub fn region_chart(report: &Report, width: f64, height: f64) -> Svg {
    let groups: Vec<Group> = report
        .regions
        .iter()
        .map(|r| group(region_name(r), &[r]))
        .collect();
    bar_chart(REGION_CHART_TITLE, &groups, width, height)
}

/// Fig. 10: one group per volume (in the order of first appearance), its
/// regions' poses pooled; the local bar only when every region of the
/// volume had a local set, so that both bars are over the same poses.
pub fn volume_chart(report: &Report, width: f64, height: f64) -> Svg {
    let volume = |r: &RegionReport| r.volume.clone().unwrap_or_else(|| NO_VOLUME.into());
    let mut volumes: Vec<String> = Vec::new();
    for r in &report.regions {
        let v = volume(r);
        if !volumes.contains(&v) {
            volumes.push(v);
        }
    }
    let groups: Vec<Group> = volumes
        .into_iter()
        .map(|v| {
            let members: Vec<&RegionReport> =
                report.regions.iter().filter(|r| volume(r) == v).collect();
            group(v, &members)
        })
        .collect();
    bar_chart(VOLUME_CHART_TITLE, &groups, width, height)
}

/// Grouped bars of mean errors on the report's usual value axis (log when
/// before and after are far apart, as in the per-axis chart).
fn bar_chart(title: &str, groups: &[Group], width: f64, height: f64) -> Svg {
    let mut svg = Svg::default();
    svg.title(TITLE_X, TITLE_Y, title);
    let has_local = groups.iter().any(|g| g.means[2].is_some());
    let shown = if has_local {
        SERIES.len()
    } else {
        SERIES.len() - 1
    };
    let entries: Vec<(Mark, &str)> = SERIES[..shown]
        .iter()
        .map(|(label, color)| (Mark::Swatch(color), *label))
        .collect();
    legend(&mut svg, TITLE_X, LEGEND_Y, &entries);
    let area = plot_area(width, height, 0.0, MARGIN_RIGHT);
    let values: Vec<f64> = groups
        .iter()
        .flat_map(|g| g.means.iter().flatten().copied())
        .collect();
    if groups.is_empty() || !values.iter().any(|v| v.is_finite() && *v > 0.0) {
        no_data(&mut svg, area, "no regions in this report");
        return svg;
    }
    let scale = Scale::for_magnitudes(&values, area.bottom(), area.y);
    let label = if scale.log {
        "mean 3-D error [mm] (log scale)"
    } else {
        "mean 3-D error [mm]"
    };
    y_axis(&mut svg, area, &scale, label);
    svg.line(
        area.x,
        area.bottom(),
        area.right(),
        area.bottom(),
        AXIS_COLOR,
        1.0,
    );
    let slot = area.w / groups.len() as f64;
    let bar_w = slot * GROUP_FILL / shown as f64;
    for (k, g) in groups.iter().enumerate() {
        let left = area.x + slot * k as f64 + slot * (1.0 - GROUP_FILL) / 2.0;
        for (j, (mean, (_, color))) in g.means.iter().zip(SERIES).take(shown).enumerate() {
            let Some(mean) = mean else { continue };
            let x = left + bar_w * j as f64;
            let top = scale.map(*mean);
            svg.rect(
                x,
                top,
                bar_w * BAR_FILL,
                area.bottom() - top,
                color,
                BAR_OPACITY,
            );
            let label = mm(*mean);
            if label.len() as f64 * SMALL_CHAR_WIDTH > bar_w + VALUE_LABEL_OVERHANG {
                continue;
            }
            let centre = x + bar_w * BAR_FILL / 2.0;
            svg.text(
                centre,
                top - VALUE_LABEL_GAP,
                "middle",
                SMALL_FONT,
                TEXT_COLOR,
                &label,
            );
        }
        let y = area.bottom() + TICK_LENGTH + FONT_SIZE + VALUE_LABEL_GAP;
        svg.text(
            left + slot * GROUP_FILL / 2.0,
            y,
            "middle",
            FONT_SIZE,
            TEXT_COLOR,
            &ellipsize(&g.name, (slot / CHAR_WIDTH) as usize),
        );
    }
    svg
}

#[cfg(test)]
#[path = "regions_chart_tests.rs"]
mod tests;
