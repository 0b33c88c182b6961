//! The report's account of the release gate: what this set was compared
//! with, both figures and how they were figured, and the figure the
//! compared set's own report gave, so a reader can trace the gate's
//! "before" to a report (and see why the two may differ).

use std::fmt::Write;

use super::format::{escape_xml, mm};
use super::model::{GateReport, Report};

/// Why the gate's figure of the compared set can differ from the one its
/// own report shows.
const WHY_THEY_DIFFER: &str = "The compared set's own report measured its own session with its own headline rule; the gate measures both sets on this session's poses by one rule, so identical sets give identical figures.";

/// The gate's rows: this set, the compared one by the gate's rule, and the
/// compared one as its own report gives it.
pub fn gate_section(page: &mut String, report: &Report) {
    let Some(gate) = &report.gate else {
        return;
    };
    let _ = write!(
        page,
        "<div class=\"gate\" id=\"release-gate\"><strong>Release gate</strong>: {}\n<table class=\"meta\">\
         <tr><th>This set</th><td id=\"gate-mean\">{} mm</td></tr>\
         <tr><th>{}</th><td id=\"gate-compared\">{} mm</td></tr>",
        escape_xml(&gate.reason),
        figure(gate.mean_mm),
        escape_xml(&compared_label(gate)),
        figure(gate.compared_mean_mm),
    );
    if gate.compared_own_mean_mm.is_some() {
        let _ = write!(
            page,
            "<tr><th>{} in its own report{}</th><td id=\"gate-compared-own\">{} mm</td></tr>",
            escape_xml(&gate.compared_with),
            gate.compared_own_session_id
                .as_deref()
                .map(|s| format!(" (session {})", escape_xml(s)))
                .unwrap_or_default(),
            figure(gate.compared_own_mean_mm),
        );
    }
    page.push_str("</table>\n");
    if let Some(basis) = &gate.basis {
        let _ = write!(
            page,
            "<p class=\"muted\">Both gate figures: {}. {WHY_THEY_DIFFER}</p>",
            escape_xml(basis)
        );
    }
    page.push_str("</div>\n");
}

fn compared_label(gate: &GateReport) -> String {
    if gate.basis.is_some() {
        format!("{} on these poses", gate.compared_with)
    } else {
        format!("{} (headline before)", gate.compared_with)
    }
}

fn figure(value: Option<f64>) -> String {
    value.map_or_else(|| "—".to_string(), mm)
}
