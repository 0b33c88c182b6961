//! Text escaping and number formatting shared by the report renderings.
//! Every string that comes from a report (serial, pose ids, notes, warnings)
//! goes through [`escape_xml`] before it reaches SVG or HTML.

use super::model::{ErrorStats, ReleaseView, Report};
use crate::domain::ReleaseStatus;

/// Escapes the five XML special characters so that arbitrary text is safe
/// in SVG/HTML element content and in double- or single-quoted attributes.
pub fn escape_xml(text: &str) -> String {
    let mut out = String::with_capacity(text.len());
    for c in text.chars() {
        match c {
            '&' => out.push_str("&amp;"),
            '<' => out.push_str("&lt;"),
            '>' => out.push_str("&gt;"),
            '"' => out.push_str("&quot;"),
            '\'' => out.push_str("&#39;"),
            // Control characters are not allowed in XML 1.0 documents.
            c if c.is_control() && c != '\n' && c != '\t' => out.push('\u{FFFD}'),
            c => out.push(c),
        }
    }
    out
}

/// Most characters of a pose name in tables: a name is a file name or a
/// 36-character id, and a table row must stay one line.
pub const TABLE_NAME_CHARS: usize = 32;

/// `text` cut to `max_chars` characters with an ellipsis in the middle.
/// The end is kept longer than the start: numbered shots
/// (`campaign_2024_pose_017.png`) differ in their last characters.
pub fn ellipsize(text: &str, max_chars: usize) -> String {
    let count = text.chars().count();
    if count <= max_chars || max_chars < 3 {
        return text
            .chars()
            .take(max_chars.max(count.min(max_chars)))
            .collect();
    }
    let head = (max_chars - 1) / 3;
    let tail = max_chars - 1 - head;
    let start: String = text.chars().take(head).collect();
    let end: String = text.chars().skip(count - tail).collect();
    format!("{start}…{end}")
}

/// Placeholder printed for a value that is missing or not finite.
pub const NOT_AVAILABLE: &str = "n/a";

/// A fixed-point number, or [`NOT_AVAILABLE`] when not finite.
pub fn fixed(value: f64, decimals: usize) -> String {
    if value.is_finite() {
        let text = format!("{value:.decimals$}");
        // A value that rounds to zero prints without a sign ("-0.000").
        match text.strip_prefix('-') {
            Some(unsigned) if unsigned.chars().all(|c| c == '0' || c == '.') => {
                unsigned.to_string()
            }
            _ => text,
        }
    } else {
        NOT_AVAILABLE.to_string()
    }
}

/// Significant digits kept for a length error in mm (0.0934, 1.84, 12.3).
const ERROR_SIGNIFICANT_DIGITS: i32 = 3;

/// A length error in mm with three significant digits (at most 4 decimals).
pub fn mm(value: f64) -> String {
    significant(value, ERROR_SIGNIFICANT_DIGITS)
}

/// `value` rounded to `digits` significant digits, plain notation for
/// ordinary magnitudes and scientific for very large or small ones.
pub fn significant(value: f64, digits: i32) -> String {
    if !value.is_finite() {
        return NOT_AVAILABLE.to_string();
    }
    if value == 0.0 {
        return "0".to_string();
    }
    let magnitude = value.abs().log10().floor() as i32;
    if !(-4..6).contains(&magnitude) {
        return format!("{:.*e}", (digits - 1).max(0) as usize, value);
    }
    let decimals = (digits - 1 - magnitude).max(0) as usize;
    format!("{value:.decimals$}")
}

/// Significant digits of a standard deviation when quoting `value ± std`.
const STD_SIGNIFICANT_DIGITS: i32 = 2;
/// Most decimals printed for a value quoted with its standard deviation.
const MAX_VALUE_DECIMALS: i32 = 9;
/// Decimals of a value without a usable standard deviation (held fixed).
const DECIMALS_WITHOUT_STD: usize = 3;

/// Decimals that show a standard deviation to two significant digits; the
/// value is printed to the same decimals (metrology convention).
pub fn decimals_for_std(std: f64) -> usize {
    if !std.is_finite() || std <= 0.0 {
        return DECIMALS_WITHOUT_STD;
    }
    let magnitude = std.log10().floor() as i32;
    (STD_SIGNIFICANT_DIGITS - 1 - magnitude).clamp(0, MAX_VALUE_DECIMALS) as usize
}

/// `value` printed to the precision its standard deviation supports.
pub fn with_precision_of(value: f64, std: f64) -> String {
    if std.is_finite() && std > 0.0 {
        fixed(value, decimals_for_std(std))
    } else {
        significant(value, 6)
    }
}

/// Reads one statistic out of [`ErrorStats`].
pub type StatGetter = fn(&ErrorStats) -> f64;

/// The statistics quoted in the report tables, in order (method.md §7).
pub const STAT_ROWS: [(&str, StatGetter); 5] = [
    ("mean", |s| s.mean_mm),
    ("median", |s| s.median_mm),
    ("std dev", |s| s.std_mm),
    ("RMS", |s| s.rms_mm),
    ("max", |s| s.max_mm),
];

/// Before/after mean ratio ("how many times smaller the error became").
pub fn improvement_factor(report: &Report) -> Option<f64> {
    let (before, after) = (report.before.norm.mean_mm, report.after.norm.mean_mm);
    (before.is_finite() && after.is_finite() && after > 0.0).then(|| before / after)
}

/// The improvement factor as text ("19.6x"), or "n/a".
pub fn improvement_text(report: &Report) -> String {
    match improvement_factor(report) {
        Some(f) => format!("{}x", significant(f, 3)),
        None => NOT_AVAILABLE.to_string(),
    }
}

/// What the "before" model fits besides the base frame (method.md §7):
/// the hand–eye transform with a flange camera, the tool point otherwise.
pub fn before_fit(report: &Report) -> &'static str {
    if report.camera.is_some() {
        "hand–eye transform"
    } else {
        "tool point"
    }
}

/// The one-line summary used as the header of every rendering. The set's
/// release status opens it (see [`release_line`]).
pub fn headline(report: &Report) -> String {
    let line = match &report.hand_eye {
        Some(he) => super::hand_eye_section::hand_eye_headline(report, he),
        None => before_after_line(report),
    };
    match release_line(report) {
        Some(status) => format!("{status} {line}"),
        None => line,
    }
}

/// "mean 3-D error … before → … after (…x smaller)".
fn before_after_line(report: &Report) -> String {
    format!(
        "mean 3-D error at {} validation poses: {} mm before → {} mm after ({} smaller)",
        report.after.norm.n,
        mm(report.before.norm.mean_mm),
        mm(report.after.norm.mean_mm),
        improvement_text(report)
    )
}

/// The gate's finding when it judged the set worse than before.
fn gate_worse(report: &Report) -> Option<String> {
    let gate = report.gate.as_ref().filter(|g| g.worse)?;
    Some(format!(
        "{} mm against {} mm for {} on the same validation poses",
        mm(gate.mean_mm.unwrap_or(f64::NAN)),
        mm(gate.compared_mean_mm.unwrap_or(f64::NAN)),
        gate.compared_with
    ))
}

/// "by {who} at {when}", or what a set approved before the gate existed says.
fn decided_by(release: &ReleaseView) -> String {
    match (&release.status_by, &release.status_at) {
        (Some(by), Some(at)) => format!("by {by} at {at}"),
        (Some(by), None) => format!("by {by}"),
        (None, _) => "before the release gate existed".into(),
    }
}

/// The reason as a clause (`: why`), or nothing.
fn because(release: &ReleaseView) -> String {
    match release.status_reason.as_deref().map(str::trim) {
        Some(why) if !why.is_empty() => format!(": {why}"),
        _ => String::new(),
    }
}

/// The sentence that opens every rendering: the set's *current* release
/// status, who gave it, when and why. A set the gate held back and a
/// person approved says both (the person's decision first). A report read
/// without its set's status (`release.status` absent) falls back to the
/// gate's own warning, as stored at the end of the job.
pub fn release_line(report: &Report) -> Option<String> {
    let release = &report.release;
    let worse = gate_worse(report);
    let Some(status) = release.status else {
        return worse.map(|w| {
            format!("WORSE THAN BEFORE: {w}; held back as a candidate, not served as latest.")
        });
    };
    Some(match status {
        ReleaseStatus::Candidate => match worse {
            Some(w) => format!(
                "CANDIDATE, not served as latest: WORSE THAN BEFORE: {w} (held back {}).",
                decided_by(release)
            ),
            None => format!(
                "CANDIDATE, not served as latest (held back {}){}.",
                decided_by(release),
                because(release)
            ),
        },
        ReleaseStatus::Rejected => format!(
            "REJECTED {}{}; never served as latest.",
            decided_by(release),
            because(release)
        ),
        ReleaseStatus::Approved => match worse {
            Some(w) => format!(
                "APPROVED {}{}. The release gate had held it back: {w}.",
                decided_by(release),
                because(release)
            ),
            None => format!("Approved {}{}.", decided_by(release), because(release)),
        },
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn escapes_markup_and_quotes() {
        assert_eq!(
            escape_xml(r#"<script>alert('x' & "y")</script>"#),
            "&lt;script&gt;alert(&#39;x&#39; &amp; &quot;y&quot;)&lt;/script&gt;"
        );
        assert_eq!(escape_xml("a\u{1}b"), "a\u{FFFD}b");
    }

    #[test]
    fn significant_digits() {
        assert_eq!(significant(0.093_41, 3), "0.0934");
        assert_eq!(significant(1.8449, 3), "1.84");
        assert_eq!(significant(123.46, 3), "123");
        assert_eq!(significant(-2.5e-7, 2), "-2.5e-7");
        assert_eq!(significant(f64::NAN, 3), NOT_AVAILABLE);
        assert_eq!(fixed(-0.0004, 3), "0.000");
        assert_eq!(fixed(-0.0006, 3), "-0.001");
    }

    #[test]
    fn value_follows_std_precision() {
        assert_eq!(with_precision_of(1403.2461, 0.41), "1403.25");
        assert_eq!(with_precision_of(-0.213_456, 0.0012), "-0.2135");
        assert_eq!(with_precision_of(640.0, 12.0), "640");
    }

    #[test]
    fn the_headline_opens_with_the_current_status_not_the_gates_old_one() {
        use crate::report::sample::sample_report;
        use crate::report::GateReport;
        let mut report = sample_report();
        report.gate = Some(GateReport {
            status: "candidate".into(),
            reason: "worse".into(),
            compared_with: "R/1".into(),
            compared_mean_mm: Some(0.011),
            mean_mm: Some(0.012),
            worse: true,
            basis: None,
            compared_own_mean_mm: None,
            compared_own_session_id: None,
        });
        // Read without its set: the gate's own warning.
        assert!(headline(&report).starts_with("WORSE THAN BEFORE"));
        report.release = ReleaseView {
            status: Some(ReleaseStatus::Approved),
            status_reason: Some("re-measured".into()),
            status_by: Some("token:7 (ana)".into()),
            status_at: Some("2026-11-27T10:00:00Z".into()),
        };
        let line = headline(&report);
        assert!(
            line.starts_with(
                "APPROVED by token:7 (ana) at 2026-11-27T10:00:00Z: re-measured. \
                 The release gate had held it back: "
            ),
            "{line}"
        );
        assert!(!line.contains("not served as latest"));
        report.release.status = Some(ReleaseStatus::Rejected);
        assert!(headline(&report).starts_with("REJECTED by token:7 (ana)"));
        report.gate = None;
        report.release.status = Some(ReleaseStatus::Candidate);
        report.release.status_by = Some("gate".into());
        assert!(headline(&report).starts_with(
            "CANDIDATE, not served as latest (held back by gate at 2026-11-27T10:00:00Z): re-measured."
        ));
        report.release.status = Some(ReleaseStatus::Approved);
        report.release.status_by = None;
        assert!(
            headline(&report).starts_with("Approved before the release gate existed: re-measured.")
        );
    }
}
