//! The HTML section of a multi-session set's report (issue 18): the
//! paper's Figs 7 and 9 (mean error before and after calibration in each
//! region, the local model beside the global one where the robot had one)
//! and Fig. 10 (the same per volume), as grouped bar charts and a table.

use std::fmt::Write;

use super::format::{escape_xml, mm};
use super::model::Report;
use super::regions::RegionReport;
use super::svg::{HALF_WIDTH, SMALL_CHART_HEIGHT};
use super::svg_writer::{
    standalone, Svg, AFTER_COLOR, AXIS_COLOR, BEFORE_COLOR, FONT_SIZE, TITLE_X,
};

/// The local model's bars (green, distinct from before and after).
const LOCAL_COLOR: &str = "#2e8b57";
/// Chart margins (px): left for the axis labels, bottom for the group names.
const MARGIN_LEFT: f64 = 50.0;
const MARGIN_TOP: f64 = 40.0;
const MARGIN_BOTTOM: f64 = 40.0;
const MARGIN_RIGHT: f64 = 10.0;

/// One group of bars: its name and (label, value mm, colour) bars.
struct Group {
    name: String,
    bars: Vec<(&'static str, f64, &'static str)>,
}

fn region_name(r: &RegionReport) -> String {
    r.region.clone().unwrap_or_else(|| r.session_id.clone())
}

fn bars(r: &[&RegionReport]) -> Vec<(&'static str, f64, &'static str)> {
    let mean = |f: &dyn Fn(&RegionReport) -> Option<f64>| {
        let v: Vec<f64> = r.iter().filter_map(|x| f(x)).collect();
        (!v.is_empty()).then(|| v.iter().sum::<f64>() / v.len() as f64)
    };
    let mut out = vec![
        (
            "before",
            mean(&|x| Some(x.before.norm.mean_mm)).unwrap_or(0.0),
            BEFORE_COLOR,
        ),
        (
            "global",
            mean(&|x| Some(x.after.norm.mean_mm)).unwrap_or(0.0),
            AFTER_COLOR,
        ),
    ];
    if let Some(local) = mean(&|x| x.local.as_ref().map(|l| l.after.norm.mean_mm)) {
        out.push(("local", local, LOCAL_COLOR));
    }
    out
}

/// A grouped bar chart of mean errors (mm).
fn bar_chart(title: &str, groups: &[Group]) -> String {
    let (w, h) = (HALF_WIDTH, SMALL_CHART_HEIGHT);
    let mut svg = Svg::default();
    svg.title(TITLE_X, 18.0, title);
    let top = groups
        .iter()
        .flat_map(|g| g.bars.iter().map(|b| b.1))
        .fold(0.0_f64, f64::max)
        .max(f64::MIN_POSITIVE)
        * 1.1;
    let (x0, y0) = (MARGIN_LEFT, h - MARGIN_BOTTOM);
    let plot_h = h - MARGIN_TOP - MARGIN_BOTTOM;
    svg.line(x0, MARGIN_TOP, x0, y0, AXIS_COLOR, 1.0);
    svg.line(x0, y0, w - MARGIN_RIGHT, y0, AXIS_COLOR, 1.0);
    svg.text(
        x0 - 4.0,
        MARGIN_TOP + 4.0,
        "end",
        FONT_SIZE,
        AXIS_COLOR,
        &mm(top),
    );
    svg.text(x0 - 4.0, y0, "end", FONT_SIZE, AXIS_COLOR, "0");
    svg.rotated_text(
        14.0,
        MARGIN_TOP + plot_h / 2.0,
        -90.0,
        "middle",
        "mean 3-D error (mm)",
    );
    let slot = (w - MARGIN_LEFT - MARGIN_RIGHT) / groups.len().max(1) as f64;
    for (k, g) in groups.iter().enumerate() {
        let bar_w = slot * 0.8 / g.bars.len().max(1) as f64;
        let left = x0 + slot * k as f64 + slot * 0.1;
        for (j, (label, value, colour)) in g.bars.iter().enumerate() {
            let bh = plot_h * value / top;
            let x = left + bar_w * j as f64;
            svg.rect(x, y0 - bh, bar_w * 0.9, bh, colour, 1.0);
            svg.text(
                x + bar_w * 0.45,
                y0 - bh - 3.0,
                "middle",
                FONT_SIZE - 2.0,
                AXIS_COLOR,
                label,
            );
        }
        svg.text(
            left + slot * 0.4,
            y0 + 16.0,
            "middle",
            FONT_SIZE,
            AXIS_COLOR,
            &g.name,
        );
    }
    standalone(w, h, title, &svg.body)
}

/// Nothing for a one-session report.
pub fn regions(page: &mut String, report: &Report) {
    if report.regions.is_empty() {
        return;
    }
    page.push_str(
        "<section>\n<h2>Regions (paper Figs 7, 9 and 10)</h2>\n\
         <p>One model over every board placement (session): each region's validation poses \
         judged with its own board. <em>before</em>: the nominal model, its frames fitted on the \
         region; <em>global</em>: this set; <em>local</em>: the region's own one-session set, \
         where the robot had one (its own report's figures on the same poses). The paper found \
         local models 3–6x better locally; the ratio column says what this robot shows.</p>\n\
         <table class=\"data\"><tr><th>region</th><th>volume</th><th>session</th>\
         <th class=\"num\">before mean</th><th class=\"num\">global mean</th><th class=\"num\">global max</th>\
         <th class=\"num\">local mean</th><th class=\"num\">global / local</th></tr>\n",
    );
    for r in &report.regions {
        let local = r
            .local
            .as_ref()
            .map(|l| format!("{} (v{})", mm(l.after.norm.mean_mm), l.version));
        let _ = writeln!(
            page,
            "<tr><td>{}</td><td>{}</td><td>{}</td><td class=\"num\">{}</td><td class=\"num\">{}</td>\
             <td class=\"num\">{}</td><td class=\"num\">{}</td><td class=\"num\">{}</td></tr>",
            escape_xml(&region_name(r)),
            escape_xml(r.volume.as_deref().unwrap_or("")),
            escape_xml(&r.session_id),
            mm(r.before.norm.mean_mm),
            mm(r.after.norm.mean_mm),
            mm(r.after.norm.max_mm),
            local.unwrap_or_else(|| "—".into()),
            r.global_over_local()
                .map(|x| format!("{x:.2}x"))
                .unwrap_or_else(|| "—".into()),
        );
    }
    page.push_str("</table>\n");
    let per_region: Vec<Group> = report
        .regions
        .iter()
        .map(|r| Group {
            name: region_name(r),
            bars: bars(&[r]),
        })
        .collect();
    let mut volumes: Vec<String> = Vec::new();
    for r in &report.regions {
        let v = r.volume.clone().unwrap_or_else(|| "(no volume)".into());
        if !volumes.contains(&v) {
            volumes.push(v);
        }
    }
    let per_volume: Vec<Group> = volumes
        .iter()
        .map(|v| {
            let members: Vec<&RegionReport> = report
                .regions
                .iter()
                .filter(|r| r.volume.as_deref().unwrap_or("(no volume)") == v)
                .collect();
            Group {
                name: v.clone(),
                bars: bars(&members),
            }
        })
        .collect();
    let _ = writeln!(
        page,
        "<figure>{}</figure>\n<figure>{}</figure>\n</section>",
        bar_chart("Error per region, before and after", &per_region),
        bar_chart("Error per volume, before and after", &per_volume)
    );
}
