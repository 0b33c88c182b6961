//! The HTML section of a stage session's report (issue 18): the paper's
//! Table 1 per sequence with the travel check, and Fig. 5
//! ([`super::stage_chart`]).

use std::fmt::Write;

use super::format::mm;
use super::measurement_accuracy::SequenceAccuracyReport;
use super::model::Report;
use super::svg::stage_accuracy_svg;

fn cells(v: [f64; 3]) -> String {
    v.iter()
        .map(|c| format!("<td class=\"num\">{}</td>", mm(*c)))
        .collect()
}

/// The per-axis figures against the stage (absent in older reports).
fn stage_referenced_table(page: &mut String, rows: &[SequenceAccuracyReport]) {
    if rows.iter().all(|s| s.stage_referenced_mm.is_none()) {
        return;
    }
    page.push_str(
        "<p>Against the stage: each image's camera position less the stage's readings \
         fitted rigidly to its sequence. These figures hold each image's depth noise, which \
         the average-rotation method cannot see; neither sees an offset common to a whole \
         sequence (that needs the board's pose on the stage); its σ, propagated from the \
         dots' errors through the intrinsics and each image's pose fit, is the last three \
         columns.</p>\n\
         <table class=\"data\"><tr><th>sequence</th>\
         <th class=\"num\">mean x</th><th class=\"num\">y</th><th class=\"num\">z</th>\
         <th class=\"num\">median x</th><th class=\"num\">y</th><th class=\"num\">z</th>\
         <th class=\"num\">std x</th><th class=\"num\">y</th><th class=\"num\">z</th>\
         <th class=\"num\">offset σ x</th><th class=\"num\">y</th><th class=\"num\">z</th></tr>\n",
    );
    for s in rows {
        if let Some(t) = &s.stage_referenced_mm {
            let _ = writeln!(
                page,
                "<tr><td>{}</td>{}{}{}{}</tr>",
                s.sequence,
                cells(t.mean),
                cells(t.median),
                cells(t.std),
                s.offset_sd_mm
                    .map(cells)
                    .unwrap_or_else(|| "<td></td>".repeat(3)),
            );
        }
    }
    page.push_str("</table>\n");
}

/// Nothing for a report without stage sequences.
pub fn measurement_accuracy(page: &mut String, report: &Report) {
    let Some(m) = &report.measurement_accuracy else {
        return;
    };
    page.push_str(
        "<section>\n<h2>Measurement accuracy on the stage (paper Table 1, Fig. 5)</h2>\n\
         <p>Per sequence, the position error of each image's camera position by the paper's \
         average-rotation method (absolute, per target axis), and the measured travel between \
         every two images against the stage's.</p>\n\
         <table class=\"data\"><tr><th>sequence</th><th class=\"num\">distance</th><th class=\"num\">images</th>\
         <th class=\"num\">mean x</th><th class=\"num\">y</th><th class=\"num\">z</th>\
         <th class=\"num\">median x</th><th class=\"num\">y</th><th class=\"num\">z</th>\
         <th class=\"num\">std x</th><th class=\"num\">y</th><th class=\"num\">z</th>\
         <th class=\"num\">max 3-D</th><th class=\"num\">travel mean</th><th class=\"num\">travel max</th></tr>\n",
    );
    for s in &m.sequences {
        let _ = writeln!(
            page,
            "<tr><td>{}</td><td class=\"num\">{}</td><td class=\"num\">{}</td>{}{}{}\
             <td class=\"num\">{}</td><td class=\"num\">{}</td><td class=\"num\">{}</td></tr>",
            s.sequence,
            mm(s.distance_mm),
            s.images,
            cells(s.mean_mm),
            cells(s.median_mm),
            cells(s.std_mm),
            mm(s.max_3d_mm),
            mm(s.travelled_distance_error_mm.mean),
            mm(s.travelled_distance_error_mm.max),
        );
    }
    page.push_str("</table>\n");
    stage_referenced_table(page, &m.sequences);
    let _ = writeln!(
        page,
        "<figure>{}</figure>\n</section>",
        stage_accuracy_svg(report)
    );
}
