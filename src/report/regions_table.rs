//! The regions of a multi-session set in the terminal report (issue 18;
//! the table behind the paper's Figs 7, 9 and 10): one row per session
//! (board placement) with its validation error before and after, and its
//! own local set's error on the same poses where the robot had one.

use super::format::{mm, significant};
use super::model::Report;
use super::regions_chart::region_name;
use super::text_table::{heading, Align, TextTable, INDENT};
use std::fmt::Write;

/// A cell with nothing to show (no volume, no local set).
const ABSENT: &str = "-";
/// Significant digits of the global / local ratio.
const RATIO_DIGITS: i32 = 3;

/// Nothing for a one-session report.
pub fn regions(out: &mut String, report: &Report) {
    use Align::{Left, Right};
    if report.regions.is_empty() {
        return;
    }
    heading(
        out,
        "Regions: error at each session's validation poses [mm] (paper Figs 7, 9 and 10)",
    );
    let mut t = TextTable::new(&[
        ("region", Left),
        ("volume", Left),
        ("session", Left),
        ("before mean", Right),
        ("before max", Right),
        ("after mean", Right),
        ("after max", Right),
        ("local mean", Right),
        ("local set", Right),
        ("global/local", Right),
    ]);
    for r in &report.regions {
        let local = r.local.as_ref();
        t.row(vec![
            region_name(r),
            r.volume.clone().unwrap_or_else(|| ABSENT.into()),
            r.session_id.clone(),
            mm(r.before.norm.mean_mm),
            mm(r.before.norm.max_mm),
            mm(r.after.norm.mean_mm),
            mm(r.after.norm.max_mm),
            local.map_or(ABSENT.into(), |l| mm(l.after.norm.mean_mm)),
            local.map_or(ABSENT.into(), |l| format!("v{}", l.version)),
            r.global_over_local().map_or(ABSENT.into(), |x| {
                format!("{}x", significant(x, RATIO_DIGITS))
            }),
        ]);
    }
    t.render(out);
    let _ = writeln!(
        out,
        "{INDENT}after: this (global) set with the session's board; local: the session's own \
         one-session set.\n{INDENT}global/local above 1: the local model is better in its region \
         (the paper found local models 3-6x better)."
    );
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::report::render_table;
    use crate::report::sample::sample_report;
    use crate::report::sample_regions::{sample_regions_report, SAMPLE_REGIONS};

    /// The cells of the regions table's body rows.
    fn region_rows(text: &str) -> Vec<Vec<String>> {
        let section = text.split("\nRegions: ").nth(1).expect("a regions section");
        section
            .lines()
            .skip(3) // its heading, the column names and the rule
            .take_while(|l| l.starts_with(INDENT) && !l.contains("after: this"))
            .map(|l| l.split_whitespace().map(String::from).collect())
            .collect()
    }

    #[test]
    fn one_row_per_region_with_its_figures() {
        let text = render_table(&sample_regions_report());
        let rows = region_rows(&text);
        assert_eq!(rows.len(), SAMPLE_REGIONS.len(), "{text}");
        for (row, (session, region, volume, before, after, local)) in
            rows.iter().zip(SAMPLE_REGIONS)
        {
            let (local_mean, version, ratio) = match local {
                Some((v, [mean, _])) => (
                    mm(mean),
                    format!("v{v}"),
                    format!("{}x", significant(after[0] / mean, RATIO_DIGITS)),
                ),
                None => (ABSENT.into(), ABSENT.into(), ABSENT.into()),
            };
            let expected = [
                region.to_string(),
                volume.to_string(),
                session.to_string(),
                mm(before[0]),
                mm(before[1]),
                mm(after[0]),
                mm(after[1]),
                local_mean,
                version,
                ratio,
            ];
            assert_eq!(row, &expected, "{text}");
        }
        // Spot checks against the literal figures, not only the formatter.
        assert_eq!(rows[0][3..8], ["2.10", "4.20", "0.0610", "0.140", "0.0520"]);
        assert_eq!(rows[0][9], "1.17x");
        assert_eq!(rows[2][7..], ["-", "-", "-"]);
    }

    #[test]
    fn a_one_session_report_has_no_regions_section() {
        assert!(!render_table(&sample_report()).contains("\nRegions: "));
    }

    #[test]
    fn hostile_region_names_cannot_reach_the_terminal() {
        let mut report = sample_regions_report();
        report.regions[0].region = Some("\u{1b}[2Jfront".into());
        let text = render_table(&report);
        assert!(!text.chars().any(|c| c.is_control() && c != '\n'));
        assert!(text.contains("?[2Jfront"));
    }
}
