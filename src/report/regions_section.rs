//! The HTML section of a multi-session set's report (issue 18): the
//! paper's Figs 7 and 9 (mean error before and after calibration in each
//! region, the local model beside the global one where the robot had one)
//! and Fig. 10 (the same per volume), as a table and the charts report.svg
//! draws too (`regions_chart.rs`).

use std::fmt::Write;

use super::format::{escape_xml, mm};
use super::model::Report;
use super::regions_chart::region_name;
use super::svg::{regions_svg, volumes_svg};

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
    let _ = writeln!(
        page,
        "<figure><div class=\"pair\">{}{}</div></figure>\n</section>",
        regions_svg(report),
        volumes_svg(report)
    );
}
