//! The report as plain text for the terminal (`robocal report`): aligned
//! columns, no colour, control characters from the report replaced so
//! that a hostile serial cannot drive the terminal.

use super::format::{
    decimals_for_std, ellipsize, fixed, headline, mm, significant, with_precision_of,
    NOT_AVAILABLE, STAT_ROWS, TABLE_NAME_CHARS,
};
use super::model::Report;
use super::text_table::{heading, printable, Align, TextTable, INDENT};
use std::fmt::Write;

fn ratio(before: f64, after: f64) -> String {
    if after > 0.0 && before.is_finite() {
        format!("{}x", significant(before / after, 3))
    } else {
        NOT_AVAILABLE.to_string()
    }
}

/// The whole report as an aligned plain-text table.
pub fn render_table(report: &Report) -> String {
    use Align::{Left, Right};
    let mut out = String::new();
    let _ = writeln!(
        out,
        "Calibration report: robot {}, parameter set v{}\ncreated {}, job {}, session {}, {} ({})\n{}",
        printable(&report.serial),
        report.version,
        printable(&report.created_at),
        printable(&report.job_id),
        printable(&report.session_id),
        printable(&report.instrument),
        printable(&report.measurement),
        headline(report)
    );

    heading(
        &mut out,
        "Accuracy at the validation poses [mm], target frame",
    );
    let mut t = TextTable::new(&[
        ("", Left),
        ("before", Right),
        ("after", Right),
        ("ratio", Right),
    ]);
    let (b, a) = (&report.before.norm, &report.after.norm);
    t.row(vec![
        "poses".into(),
        b.n.to_string(),
        a.n.to_string(),
        String::new(),
    ]);
    for (name, get) in STAT_ROWS {
        t.row(vec![
            name.into(),
            mm(get(b)),
            mm(get(a)),
            ratio(get(b), get(a)),
        ]);
    }
    t.render(&mut out);

    heading(&mut out, "Absolute error per axis [mm]");
    let mut t = TextTable::new(&[
        ("axis", Left),
        ("before mean", Right),
        ("before max", Right),
        ("after mean", Right),
        ("after max", Right),
        ("ratio", Right),
    ]);
    let (b, a) = (&report.before, &report.after);
    for (name, before, after) in [
        ("x", &b.x, &a.x),
        ("y", &b.y, &a.y),
        ("z", &b.z, &a.z),
        ("3-D", &b.norm, &a.norm),
    ] {
        let cells = [before.mean_mm, before.max_mm, after.mean_mm, after.max_mm].map(mm);
        let mut row = vec![name.to_string()];
        row.extend(cells);
        row.push(ratio(before.mean_mm, after.mean_mm));
        t.row(row);
    }
    t.render(&mut out);

    super::regions_table::regions(&mut out, report);
    camera(&mut out, report);
    parameters(&mut out, report);
    per_pose(&mut out, report);
    if !report.notes.is_empty() {
        heading(&mut out, "Notes");
        for note in &report.notes {
            let _ = writeln!(out, "{INDENT}- {}", printable(note));
        }
    }
    out
}

fn camera(out: &mut String, report: &Report) {
    use Align::{Left, Right};
    let Some(c) = &report.camera else {
        heading(
            out,
            &format!(
                "Camera: none (instrument: {})",
                printable(&report.instrument)
            ),
        );
        return;
    };
    heading(
        out,
        &format!(
            "Camera ({} model, {} x {} px)",
            printable(&c.mode_label()),
            c.image_width,
            c.image_height
        ),
    );
    let std = c.std.unwrap_or_default();
    let has_std = c.std.is_some();
    let mut t = TextTable::new(&[
        ("", Left),
        ("value", Right),
        ("std dev", Right),
        ("unit", Left),
    ]);
    let rows = [
        ("fx", c.intrinsics.fx, std.fx, "px"),
        ("fy", c.intrinsics.fy, std.fy, "px"),
        ("cx", c.intrinsics.cx, std.cx, "px"),
        ("cy", c.intrinsics.cy, std.cy, "px"),
        ("k1", c.intrinsics.k1, std.k1, ""),
        ("k2", c.intrinsics.k2, std.k2, ""),
        ("p1", c.intrinsics.p1, std.p1, ""),
        ("p2", c.intrinsics.p2, std.p2, ""),
        ("k3", c.intrinsics.k3, f64::NAN, ""),
    ];
    for (name, value, sd, unit) in rows {
        let sd = if has_std { sd } else { f64::NAN };
        let sd_text = if sd.is_finite() {
            significant(sd, 2)
        } else {
            "-".into()
        };
        t.row(vec![
            name.into(),
            with_precision_of(value, sd),
            sd_text,
            unit.into(),
        ]);
    }
    t.row(vec![
        "reprojection RMS".into(),
        fixed(c.reprojection_rms_px, 3),
        String::new(),
        "px".into(),
    ]);
    t.render(out);
    let warned: Vec<_> = c.views.iter().filter(|v| v.warning.is_some()).collect();
    let _ = writeln!(
        out,
        "{INDENT}{} views, {} outliers dropped, {} views with warnings",
        c.views.len(),
        c.outliers_dropped,
        warned.len()
    );
    for v in warned {
        let warning = v.warning.as_deref().unwrap_or_default();
        let _ = writeln!(
            out,
            "{INDENT}  {}: {}",
            printable(&ellipsize(v.name(), TABLE_NAME_CHARS)),
            printable(warning)
        );
    }
    if let Some(d) = &report.detection {
        let _ = writeln!(
            out,
            "{INDENT}detection: {} of {} images, {} dots per image",
            d.images_detected, d.images, d.dots_per_image
        );
        for f in &d.failures {
            let _ = writeln!(
                out,
                "{INDENT}  {} not used: {}",
                printable(&ellipsize(f.name(), TABLE_NAME_CHARS)),
                printable(&f.reason)
            );
        }
    }
}

fn parameters(out: &mut String, report: &Report) {
    use Align::{Left, Right};
    heading(out, "Identified parameters");
    let mut t = TextTable::new(&[
        ("parameter", Left),
        ("unit", Left),
        ("nominal", Right),
        ("identified", Right),
        ("change", Right),
        ("std dev", Right),
        ("status", Left),
    ]);
    for p in &report.parameters {
        let d = decimals_for_std(p.std);
        let (std, status) = if p.fixed {
            ("-".into(), "held fixed")
        } else {
            (significant(p.std, 2), "")
        };
        t.row(vec![
            p.name.clone(),
            p.unit.clone(),
            fixed(p.nominal, d),
            fixed(p.identified, d),
            fixed(p.identified - p.nominal, d),
            std,
            status.into(),
        ]);
    }
    t.render(out);
    let id = &report.identifiability;
    let held = if id.fixed.is_empty() {
        "none".to_string()
    } else {
        printable(&id.fixed.join(", "))
    };
    let _ = writeln!(
        out,
        "{INDENT}rank {} of {} parameters, condition number {}, observability index {}\n{INDENT}held fixed: {held}",
        id.rank,
        id.parameters,
        significant(id.condition_number, 4),
        significant(id.observability_index, 3)
    );
}

fn per_pose(out: &mut String, report: &Report) {
    use Align::{Left, Right};
    heading(
        out,
        "Error at every pose [mm] (val: validation, cal: used for identification)",
    );
    let mut t = TextTable::new(&[
        ("pose", Left),
        ("set", Left),
        ("before", Right),
        ("after", Right),
        ("after x", Right),
        ("after y", Right),
        ("after z", Right),
        ("reproj px", Right),
    ]);
    for p in &report.per_pose {
        let [x, y, z] = p.after_error_mm.map(|v| fixed(v, 3));
        let rms = p
            .reprojection_rms_px
            .map_or("-".to_string(), |r| fixed(r, 3));
        t.row(vec![
            ellipsize(p.name(), TABLE_NAME_CHARS),
            if p.outlier {
                format!("{} OUTLIER", p.set)
            } else {
                p.set.clone()
            },
            fixed(p.before_mm, 3),
            fixed(p.after_mm, 3),
            x,
            y,
            z,
            rms,
        ]);
    }
    t.render(out);
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::report::sample::{sample_report, sample_tracker_report};

    #[test]
    fn columns_align_and_every_pose_is_listed() {
        let report = sample_report();
        let text = render_table(&report);
        for pose in &report.per_pose {
            assert!(
                text.lines()
                    .any(|l| l.trim_start().starts_with(&pose.label)),
                "{}",
                pose.label
            );
        }
        // Every row of the per-pose table has the same width (right-aligned last column).
        let rows: Vec<&str> = text
            .lines()
            .filter(|l| l.trim_start().starts_with("IRB2400_") && l.contains("val"))
            .collect();
        assert_eq!(rows.len(), report.after.norm.n);
        assert!(rows
            .iter()
            .all(|r| r.chars().count() == rows[0].chars().count()));
        assert!(text.contains(&format!("{} mm before", mm(report.before.norm.mean_mm))));
    }

    #[test]
    fn control_characters_cannot_reach_the_terminal() {
        let mut report = sample_tracker_report();
        report.serial = "\u{1b}[2J\u{1b}]0;pwned\u{7}".into();
        let text = render_table(&report);
        assert!(!text.chars().any(|c| c.is_control() && c != '\n'));
        assert!(text.contains("Camera: none"));
    }
}
