//! The printable, self-contained HTML report (issue 6): inline CSS with an
//! A4 print layout, the SVG charts inline, no external assets. Every string
//! from the report is escaped. The sections live in `html_sections.rs`.

use super::format::{before_fit, escape_xml, improvement_text, mm, release_line};
use super::hand_eye_section::{hand_eye_section, hand_eye_verdict};
use super::html_sections::*;
use super::model::Report;
use super::svg::{
    axis_errors_svg, histogram_svg, pose_errors_svg, residual_field_svg, uncertainty_map_svg,
};
use std::fmt::Write;

/// Inline style sheet: compact tables, charts scaled to the page width,
/// A4 pages with sections kept together where they fit.
const STYLE: &str = r#"
:root { --before: #d9730d; --after: #1f5fa8; --rule: #c8c8c8; --muted: #666; }
* { box-sizing: border-box; }
body { font-family: 'DejaVu Sans', 'Helvetica Neue', Arial, sans-serif; font-size: 10.5pt;
  color: #222; max-width: 1060px; margin: 24px auto; padding: 0 24px; line-height: 1.35; }
h1 { font-size: 18pt; margin: 0 0 4px 0; }
h2 { font-size: 13pt; margin: 22px 0 8px 0; padding-bottom: 3px; border-bottom: 2px solid #222;
  break-after: avoid; }
h3 { font-size: 11pt; margin: 14px 0 6px 0; break-after: avoid; }
p { margin: 6px 0; }
.muted { color: var(--muted); }
.meta { border-collapse: collapse; margin: 8px 0; }
.meta th { text-align: left; font-weight: normal; color: var(--muted); padding: 1px 14px 1px 0; }
.meta td { padding: 1px 22px 1px 0; font-weight: bold; white-space: nowrap; }
.meta td.id { white-space: normal; overflow-wrap: anywhere; font-weight: normal; font-size: 9pt; }
thead { display: table-header-group; }
.verdict { display: flex; gap: 32px; align-items: baseline; flex-wrap: wrap; border: 1.5px solid #222;
  padding: 10px 16px; margin: 12px 0; break-inside: avoid; }
.verdict .big { font-size: 20pt; font-weight: bold; white-space: nowrap; }
.verdict .label { max-width: 11em; }
.before { color: var(--before); }
.after { color: var(--after); }
table.data { border-collapse: collapse; margin: 6px 0 10px 0; font-size: 9.5pt; }
table.data th, table.data td { padding: 2px 9px; border-bottom: 1px solid var(--rule); }
table.data th { text-align: left; border-bottom: 1.5px solid #222; background: #f3f3f3; }
table.data caption { text-align: left; caption-side: top; padding-bottom: 2px; }
table.kv th { background: none; border-bottom: 1px solid var(--rule); font-weight: normal; color: var(--muted); }
table.data td.num, table.data th.num { text-align: right; font-variant-numeric: tabular-nums; }
table.data tr { break-inside: avoid; }
table.compact { font-size: 8.5pt; }
table.compact th, table.compact td { padding: 1px 6px; }
.tables { display: flex; gap: 28px; flex-wrap: wrap; align-items: flex-start; }
figure { margin: 8px 0 14px 0; break-inside: avoid; }
figure svg { width: 100%; height: auto; display: block; }
.pair { display: flex; gap: 0; }
.pair svg { width: 50%; }
figcaption { font-size: 9pt; color: var(--muted); margin-top: 2px; }
.flag { font-weight: bold; }
.release { border-left: 5px solid #222; padding: 6px 10px; margin: 0 0 10px 0; }
.release.status-candidate, .release.status-unknown { border-color: #d9730d; background: #fdf3e7; }
.release.status-rejected { border-color: #a33; background: #fbeaea; }
.gate { margin: 6px 0 10px 0; }
.release.status-approved { border-color: #2e7d32; background: #edf6ee; }
.warn { color: #a33; }
ul.notes li { margin: 3px 0; }
.signoff { display: grid; grid-template-columns: repeat(3, 1fr); gap: 28px; margin-top: 30px;
  break-inside: avoid; }
.signoff div { border-top: 1px solid #222; padding-top: 3px; font-size: 9pt; color: var(--muted); }
footer { margin-top: 18px; font-size: 8.5pt; color: var(--muted); }
@page { size: A4; margin: 13mm 12mm 14mm 12mm;
  @bottom-right { content: "page " counter(page) " of " counter(pages);
  font-family: 'DejaVu Sans', Arial, sans-serif; font-size: 8pt; color: #666; } }
tr.val td { background: #f5f8fc; }
@media print {
  body { max-width: none; margin: 0; padding: 0; font-size: 9pt; }
  h1 { font-size: 16pt; }
  h2 { margin-top: 12px; font-size: 12pt; }
  .verdict .big { font-size: 15pt; }
  .verdict { padding: 6px 12px; gap: 22px; }
  table.data { font-size: 8.5pt; }
  table.data th, table.data td { padding: 1px 5px; }
  table.compact { font-size: 8pt; }
  table.compact th, table.compact td { padding: 0 5px; line-height: 1.2; }
  .tables { gap: 18px; }
  figure { margin: 4px 0 8px 0; }
  .pagebreak { break-before: page; }
  a { color: inherit; text-decoration: none; }
}
"#;

/// The whole report as one self-contained HTML document.
pub fn render_html(report: &Report) -> String {
    let serial = escape_xml(&report.serial);
    let mut page = String::new();
    let _ = write!(
        page,
        "<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n\
         <meta name=\"viewport\" content=\"width=device-width, initial-scale=1\">\n\
         <title>Calibration report {serial} v{}</title>\n<style>{STYLE}{}</style>\n</head>\n<body>\n",
        report.version,
        page_footer_rule(report)
    );
    header(&mut page, report);
    accuracy(&mut page, report);
    super::stage_section::measurement_accuracy(&mut page, report);
    super::regions_section::regions(&mut page, report);
    camera(&mut page, report);
    parameters(&mut page, report);
    identifiability(&mut page, report);
    if let Some(m) = &report.model_selection {
        super::model_selection::html(&mut page, m);
    }
    notes_and_signoff(&mut page, report);
    per_pose(&mut page, report);
    let _ = write!(
        page,
        "<footer>Generated by robocal {} from parameter set v{} of {serial}. Lengths in mm, angles in \
         degrees, image quantities in pixels. Errors are positions in the target (world) frame.</footer>\n\
         </body>\n</html>\n",
        env!("CARGO_PKG_VERSION"),
        report.version
    );
    page
}

/// Characters allowed in the printed page footer (a CSS string): the
/// serial is put there as text, so anything that could end the string or
/// the style element is replaced.
fn css_safe(text: &str) -> String {
    let allowed = |c: char| c.is_ascii_alphanumeric() || " -_.:/+#".contains(c);
    text.chars()
        .map(|c| if allowed(c) { c } else { '?' })
        .collect()
}

fn page_footer_rule(report: &Report) -> String {
    format!(
        "@page {{ @bottom-left {{ content: \"robocal calibration report, robot {} parameter set v{}\"; \
         font-family: 'DejaVu Sans', Arial, sans-serif; font-size: 8pt; color: #666; }} }}\n",
        css_safe(&report.serial),
        report.version
    )
}

fn header(page: &mut String, report: &Report) {
    if let Some(line) = release_line(report) {
        let status = report.release.status.map_or("unknown", |s| s.as_str());
        let _ = writeln!(
            page,
            "<p class=\"release status-{status}\" id=\"release-status\"><strong>{}</strong></p>",
            escape_xml(&line)
        );
    }
    let _ = write!(
        page,
        "<header>\n<h1>Robot calibration accuracy report</h1>\n<table class=\"meta\">\
         <tr><th>Robot serial</th><td>{}</td><th>Parameter set</th><td>v{}</td><th>Created</th><td>{}</td></tr>\
         <tr><th>Instrument</th><td>{} ({})</td><th>Job</th><td class=\"id\">{}</td><th>Session</th><td class=\"id\">{}</td></tr>\
         <tr><th>Status</th><td id=\"status\">{}</td></tr>\
         </table>\n</header>\n",
        escape_xml(&report.serial),
        report.version,
        escape_xml(&report.created_at),
        escape_xml(&report.instrument),
        escape_xml(&report.measurement),
        escape_xml(&report.job_id),
        escape_xml(&report.session_id),
        report.release.status.map_or("not recorded", |s| s.as_str())
    );
    if let Some(he) = &report.hand_eye {
        hand_eye_verdict(page, report, he);
        hand_eye_section(page, he);
        return;
    }
    let (b, a) = (&report.before.norm, &report.after.norm);
    let _ = writeln!(
        page,
        "<div class=\"verdict\"><div class=\"label\">Mean 3-D error at {} validation poses</div>\
         <div class=\"big\"><span class=\"before\">{} mm</span> → <span class=\"after\">{} mm</span></div>\
         <div class=\"big\">{} smaller</div><div class=\"muted\">max {} → {} mm</div></div>",
        a.n,
        mm(b.mean_mm),
        mm(a.mean_mm),
        escape_xml(&improvement_text(report)),
        mm(b.max_mm),
        mm(a.max_mm)
    );
    super::gate_section::gate_section(page, report);
}

fn accuracy(page: &mut String, report: &Report) {
    page.push_str("<section>\n<h2>1. Accuracy at the validation poses</h2>\n");
    if report.hand_eye.is_some() {
        page.push_str(
            "<p>Camera positions predicted from the controller's flange poses with the identified \
             hand–eye transform, against those the images measure. No kinematics were identified, \
             so \"before\" and \"after\" are the same model and cannot differ.</p>\n<div class=\"tables\">",
        );
    } else {
        let _ = writeln!(
        page,
        "<p>Before: nominal kinematics with only the base frame and {} fitted. After: the identified \
         parameter set. Validation poses are not used for identification.</p>\n<div class=\"tables\">",
            before_fit(report)
        );
    }
    stats_table(page, report);
    axis_table(page, report);
    page.push_str("</div>\n");
    let _ = write!(
        page,
        "<figure>{}</figure>\n<figure><div class=\"pair\">{}{}</div></figure>\n",
        pose_errors_svg(report),
        histogram_svg(report),
        axis_errors_svg(report)
    );
    if report.uncertainty_map.is_some() {
        let _ = writeln!(page, "<figure>{}</figure>", uncertainty_map_svg(report));
    }
    page.push_str("</section>\n");
}

fn camera(page: &mut String, report: &Report) {
    // With a camera, sections 2 (camera) and 3 (parameters) each fill a page.
    let class = if report.camera.is_some() {
        " class=\"pagebreak\""
    } else {
        ""
    };
    let _ = write!(page, "<section{class}>\n<h2>2. Camera</h2>\n");
    match &report.camera {
        None => page.push_str(&format!(
            "<p class=\"muted\">No camera in this session (instrument: {}).</p>\n",
            escape_xml(&report.instrument)
        )),
        Some(camera) => {
            detection(page, report);
            page.push_str("<div class=\"tables\">\n");
            intrinsics_table(page, camera);
            views_table(page, camera);
            page.push_str("</div>\n");
            view_warnings_table(page, camera);
            let _ = writeln!(page, "<figure>{}</figure>", residual_field_svg(report));
        }
    }
    page.push_str("</section>\n");
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::report::sample::{sample_report, sample_tracker_report};
    use crate::report::xml_check::check_balanced;

    #[test]
    fn page_is_self_contained_and_balanced() {
        for report in [sample_report(), sample_tracker_report()] {
            let html = render_html(&report);
            // The only URL allowed is the SVG namespace identifier.
            let without_ns = html.replace("xmlns=\"http://www.w3.org/2000/svg\"", "");
            assert!(!without_ns.contains("http://") && !without_ns.contains("https://"));
            for forbidden in ["<link", "<script", "<img", "@import", "url("] {
                assert!(!html.contains(forbidden), "{forbidden}");
            }
            check_balanced(&html, true).unwrap();
        }
    }

    #[test]
    fn every_pose_and_parameter_appears() {
        let report = sample_report();
        let html = render_html(&report);
        for pose in &report.per_pose {
            assert!(
                html.contains(&format!(">{}<", pose.label)),
                "{}",
                pose.label
            );
        }
        for p in &report.parameters {
            assert!(html.contains(&p.name), "{}", p.name);
        }
        for note in &report.notes {
            assert!(html.contains(&escape_xml(note)));
        }
    }

    #[test]
    fn hostile_text_is_escaped() {
        let mut report = sample_report();
        report.serial = "<script>alert(1)</script>".into();
        report.per_pose[0].label = "\"><img src=x onerror=alert(1)>".into();
        report.notes.push("</li></ul><script>".into());
        let html = render_html(&report);
        assert!(!html.contains("<script") && !html.contains("<img"));
        assert!(html.contains("&lt;script&gt;alert(1)&lt;/script&gt;"));
        assert!(html.contains("robot ?script?alert?1??/script? parameter set"));
        check_balanced(&html, true).unwrap();
    }

    #[test]
    fn tracker_session_says_there_is_no_camera() {
        let html = render_html(&sample_tracker_report());
        assert!(html.contains("No camera in this session"));
    }
}
