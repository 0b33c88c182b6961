//! Fig. 5 on its own, on the report sheet and on the page.

use super::*;
use crate::report::sample::sample_report;
use crate::report::sample_stage::sample_stage_report;
use crate::report::svg::{HALF_WIDTH, SMALL_CHART_HEIGHT};
use crate::report::xml_check::check_balanced;
use crate::report::{render_html, render_svg};

/// The sheet's height (its root element's `height`).
fn height(svg: &str) -> f64 {
    let start = svg.find(" height=\"").unwrap() + " height=\"".len();
    svg[start..].split('"').next().unwrap().parse().unwrap()
}

#[test]
fn every_sequence_is_a_point_of_each_series() {
    assert!(
        stage_chart(&sample_report(), HALF_WIDTH, SMALL_CHART_HEIGHT)
            .body
            .contains("no stage sequences")
    );
    let body = stage_chart(&sample_stage_report(), HALF_WIDTH, SMALL_CHART_HEIGHT).body;
    assert_eq!(
        body.matches("<circle").count(),
        3 * 3 + 3,
        "points and legend dots"
    );
    assert_eq!(body.matches("<path").count(), 3);
}

#[test]
fn the_sheet_draws_fig_5_for_a_stage_set_and_stays_well_formed() {
    let report = sample_stage_report();
    let svg = render_svg(&report);
    check_balanced(&svg, false).unwrap();
    assert!(svg.contains(STAGE_CHART_TITLE));
    let chart = stage_chart(&report, HALF_WIDTH, SMALL_CHART_HEIGHT).body;
    assert!(svg.contains(&chart), "the sheet places the chart as drawn");
    // One more row of half-width charts than a set without sequences.
    let plain = render_svg(&sample_report());
    assert!(!plain.contains(STAGE_CHART_TITLE));
    assert_eq!(height(&svg) - height(&plain), SMALL_CHART_HEIGHT);
}

#[test]
fn the_page_embeds_the_same_figure() {
    let report = sample_stage_report();
    let html = render_html(&report);
    check_balanced(&html, true).unwrap();
    let chart = stage_chart(&report, HALF_WIDTH, SMALL_CHART_HEIGHT).body;
    assert!(html.contains(&chart));
    assert!(!render_html(&sample_report()).contains(STAGE_CHART_TITLE));
}
