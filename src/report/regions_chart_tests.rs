//! The regions charts, on their own and on the report sheet and page.

use super::*;
use crate::report::sample::sample_report;
use crate::report::sample_regions::{region_stats, sample_regions_report, REGION_POSES};
use crate::report::svg::{HALF_WIDTH, SMALL_CHART_HEIGHT};
use crate::report::xml_check::check_balanced;
use crate::report::{render_html, render_svg};

/// The value labels over the bars, in drawing order.
fn value_labels(chart: &Svg) -> Vec<String> {
    chart
        .body
        .lines()
        .filter(|l| l.contains(&format!("font-size=\"{SMALL_FONT}\"")))
        .map(|l| {
            let text = l.rsplit_once("\">").unwrap().1;
            text.trim_end_matches("</text>").to_string()
        })
        .collect()
}

fn bars(chart: &Svg, color: &str) -> usize {
    chart
        .body
        .matches(&format!("fill=\"{color}\" fill-opacity=\"{BAR_OPACITY}\""))
        .count()
}

#[test]
fn the_sheet_draws_both_figures_and_stays_well_formed() {
    let report = sample_regions_report();
    let svg = render_svg(&report);
    check_balanced(&svg, false).unwrap();
    for title in [REGION_CHART_TITLE, VOLUME_CHART_TITLE] {
        assert!(svg.contains(title), "{title}");
    }
    for name in ["front", "left", "right", "upper", "lower"] {
        assert!(svg.contains(&format!(">{name}</text>")), "{name}");
    }
    // The sheet grows by one row of half-width charts.
    let plain = render_svg(&sample_report());
    let height = |s: &str| -> f64 {
        let start = s.find(" height=\"").unwrap() + " height=\"".len();
        s[start..].split('"').next().unwrap().parse().unwrap()
    };
    assert_eq!(height(&svg) - height(&plain), SMALL_CHART_HEIGHT);
    assert!(!plain.contains(REGION_CHART_TITLE) && !plain.contains(VOLUME_CHART_TITLE));
}

#[test]
fn the_page_embeds_the_same_figures() {
    let report = sample_regions_report();
    let html = render_html(&report);
    check_balanced(&html, true).unwrap();
    let regions = region_chart(&report, HALF_WIDTH, SMALL_CHART_HEIGHT).body;
    let volumes = volume_chart(&report, HALF_WIDTH, SMALL_CHART_HEIGHT).body;
    assert!(html.contains(&regions) && html.contains(&volumes));
    assert!(!render_html(&sample_report()).contains(REGION_CHART_TITLE));
}

#[test]
fn a_region_has_before_global_and_its_local_bar_where_it_has_a_local_set() {
    let chart = region_chart(&sample_regions_report(), HALF_WIDTH, SMALL_CHART_HEIGHT);
    // Three regions, local sets in two of them.
    assert_eq!(bars(&chart, BEFORE_COLOR), 3);
    assert_eq!(bars(&chart, AFTER_COLOR), 3);
    assert_eq!(bars(&chart, LOCAL_COLOR), 2);
    assert_eq!(
        value_labels(&chart),
        ["2.10", "0.0610", "0.0520", "1.60", "0.0480", "0.0470", "3.40", "0.0750"]
    );
}

#[test]
fn a_volume_pools_its_regions_poses() {
    let mut report = sample_regions_report();
    // "upper" is front + left; give left twice the poses to see the weights.
    report.regions[1].before.norm.n = 2 * REGION_POSES;
    let chart = volume_chart(&report, HALF_WIDTH, SMALL_CHART_HEIGHT);
    let before_upper = (2.1 + 2.0 * 1.6) / 3.0;
    let labels = value_labels(&chart);
    assert_eq!(labels[0], mm(before_upper));
    // Both upper regions have local sets: the volume has a local bar;
    // "lower" has none.
    assert_eq!(
        labels,
        [mm(before_upper), mm(0.0545), mm(0.0495), mm(3.4), mm(0.075)]
    );
    assert_eq!(bars(&chart, LOCAL_COLOR), 1);
    // A volume with a region without a local set gets no local bar.
    report.regions[2].volume = Some("upper".into());
    let chart = volume_chart(&report, HALF_WIDTH, SMALL_CHART_HEIGHT);
    assert_eq!(bars(&chart, LOCAL_COLOR), 0);
    assert_eq!(bars(&chart, BEFORE_COLOR), 1);
}

#[test]
fn regions_without_names_volumes_or_poses_still_draw() {
    let mut report = sample_regions_report();
    for r in &mut report.regions {
        r.region = None;
        r.volume = None;
        r.local = None;
    }
    let chart = volume_chart(&report, HALF_WIDTH, SMALL_CHART_HEIGHT);
    assert!(chart.body.contains(&format!(">{NO_VOLUME}</text>")));
    let chart = region_chart(&report, HALF_WIDTH, SMALL_CHART_HEIGHT);
    assert!(chart.body.contains(">s-front</text>"));
    assert!(
        !chart.body.contains(">local</text>"),
        "no local legend entry"
    );
    for r in &mut report.regions {
        r.before = region_stats(f64::NAN, f64::NAN);
        r.after = Default::default();
    }
    let svg = render_svg(&report);
    check_balanced(&svg, false).unwrap();
    assert!(svg.contains("no regions in this report") && !svg.contains("NaN"));
}

#[test]
fn many_regions_keep_their_labels_apart() {
    let mut report = sample_regions_report();
    let template = report.regions[0].clone();
    report.regions = (0..12)
        .map(|i| RegionReport {
            session_id: format!("s{i}"),
            region: Some(format!("a very long region name number {i}")),
            ..template.clone()
        })
        .collect();
    let chart = region_chart(&report, HALF_WIDTH, SMALL_CHART_HEIGHT);
    // The bars are too narrow for their values: the axis gives them.
    assert!(value_labels(&chart).is_empty());
    assert_eq!(bars(&chart, LOCAL_COLOR), 12);
    let area = plot_area(HALF_WIDTH, SMALL_CHART_HEIGHT, 0.0, MARGIN_RIGHT);
    let slot = area.w / 12.0;
    let names: Vec<&str> = chart
        .body
        .lines()
        .filter(|l| l.contains("a very") || l.contains('…'))
        .collect();
    assert_eq!(names.len(), 12, "{names:?}");
    for line in names {
        let text = line
            .rsplit_once("\">")
            .unwrap()
            .1
            .trim_end_matches("</text>");
        assert!(text.chars().count() as f64 * CHAR_WIDTH <= slot, "{text}");
    }
}
