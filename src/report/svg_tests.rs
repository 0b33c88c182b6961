//! The report sheet and its pose chart.

use super::*;
use crate::report::chart_frame::*;
use crate::report::pose_chart::*;
use crate::report::sample::{sample_report, sample_report_sized, sample_tracker_report};
use crate::report::xml_check::check_balanced;
use crate::report::ErrorStats;

#[test]
fn sheet_is_well_formed_and_shows_every_validation_pose() {
    let report = sample_report();
    let svg = render_svg(&report);
    check_balanced(&svg, false).unwrap();
    assert!(svg.starts_with("<svg xmlns=\"http://www.w3.org/2000/svg\""));
    assert!(!svg.contains("href") && !svg.contains("url(") && !svg.contains("<image"));
    for pose in report.per_pose.iter().filter(|p| p.set == "val") {
        let name = chart_name(pose);
        assert!(svg.contains(&format!(">{name}</text>")), "{name}");
        assert!(name.ends_with("_pose_") || name.ends_with(".png"), "{name}");
    }
    // One before and one after dot per validation pose.
    let dots = |color: &str| {
        svg.matches(&format!("r=\"{DOT_RADIUS}\" fill=\"{color}\""))
            .count()
    };
    assert_eq!((dots(BEFORE_COLOR), dots(AFTER_COLOR)), (30, 30));
    for title in [
        "per pose",
        "histogram",
        "per axis",
        "residual field",
        "magnified",
    ] {
        assert!(svg.contains(title), "{title}");
    }
    for chart in [
        pose_errors_svg,
        histogram_svg,
        axis_errors_svg,
        residual_field_svg,
    ] {
        check_balanced(&chart(&report), false).unwrap();
    }
}

/// The slanted pose names of the pose chart: (x, y, text).
fn pose_names(chart: &Svg) -> Vec<(f64, f64, String)> {
    let attr = |line: &str, name: &str| -> f64 {
        let start = line.find(&format!(" {name}=\"")).unwrap() + name.len() + 3;
        line[start..].split('"').next().unwrap().parse().unwrap()
    };
    chart
        .body
        .lines()
        .filter(|l| l.contains(&format!("rotate({POSE_NAME_ANGLE_DEG} ")))
        .map(|l| {
            let text = l.rsplit_once("\">").unwrap().1.trim_end_matches("</text>");
            (attr(l, "x"), attr(l, "y"), text.to_string())
        })
        .collect()
}

#[test]
fn pose_names_stay_inside_the_chart_and_apart_from_5_to_200_poses() {
    let slant = POSE_NAME_ANGLE_DEG.to_radians();
    for poses in [5, 61, 200] {
        for stored_before_labels in [false, true] {
            let mut report = sample_report_sized(poses - poses / 2, poses / 2);
            if stored_before_labels {
                // Old reports: 36-character ids only.
                report.per_pose.iter_mut().for_each(|p| p.label.clear());
            }
            let height = pose_chart_height(&report);
            let chart = pose_chart(&report, SHEET_WIDTH, height);
            let names = pose_names(&chart);
            let case = format!("{poses} poses, labels cleared: {stored_before_labels}");
            assert!(
                !names.is_empty() && names.len() <= MAX_POSE_LABELS,
                "{case}"
            );
            for pair in names.windows(2) {
                assert!(pair[1].0 - pair[0].0 >= MIN_POSE_LABEL_SPACING, "{case}");
            }
            for (x, y, text) in &names {
                let chars = text.chars().count();
                assert!(chars <= CHART_NAME_CHARS, "{case}: {text}");
                let length = chars as f64 * CHAR_WIDTH;
                // Above the axis title, right of the sheet's edge.
                assert!(
                    y + length * slant.sin().abs() < height - FONT_SIZE - 8.0,
                    "{case}"
                );
                assert!(x - length * slant.cos() > 0.0, "{case}: {text}");
            }
            let judged = judged_poses(&report).0;
            let area = plot_area(
                SHEET_WIDTH,
                height,
                pose_label_room(&report),
                MEAN_LABEL_ROOM,
            );
            let every = label_every(judged.len(), area.w / judged.len() as f64);
            let expected: Vec<String> = judged.into_iter().step_by(every).map(chart_name).collect();
            let named: Vec<&str> = names.iter().map(|n| n.2.as_str()).collect();
            assert_eq!(named, expected, "{case}");
        }
    }
}

#[test]
fn hostile_serial_and_pose_ids_are_escaped() {
    let mut report = sample_report();
    report.serial = "<script>alert('x')</script>".into();
    report.per_pose.last_mut().unwrap().label = "a&b<\"c\">".into();
    let svg = render_svg(&report);
    assert!(!svg.contains("<script"));
    assert!(svg.contains("&lt;script&gt;alert(&#39;x&#39;)&lt;/script&gt;"));
    assert!(svg.contains("a&amp;b&lt;&quot;c&quot;&gt;"));
    check_balanced(&svg, false).unwrap();
}

#[test]
fn tracker_session_gets_a_note_instead_of_the_field() {
    let svg = render_svg(&sample_tracker_report());
    check_balanced(&svg, false).unwrap();
    assert!(svg.contains("No camera in this session (instrument: tracker)"));
    assert!(!svg.contains("magnified"));
}

#[test]
fn empty_and_non_finite_reports_render_without_panicking() {
    let mut empty = sample_tracker_report();
    empty.per_pose.clear();
    empty.before = Default::default();
    empty.after = Default::default();
    let svg = render_svg(&empty);
    check_balanced(&svg, false).unwrap();
    assert!(svg.contains("no poses in this report") && !svg.contains("NaN"));

    let mut broken = sample_report();
    broken.per_pose[40].before_mm = f64::NAN;
    broken.per_pose[41].after_mm = f64::INFINITY;
    broken.after.norm = ErrorStats {
        mean_mm: f64::NAN,
        ..Default::default()
    };
    broken.residual_field[0].dx_px = f64::NAN;
    if let Some(camera) = broken.camera.as_mut() {
        camera.image_width = 0;
    }
    let svg = render_svg(&broken);
    check_balanced(&svg, false).unwrap();
    assert!(!svg.contains("NaN") && !svg.contains("inf"));
    check_balanced(&crate::report::render_html(&broken), true).unwrap();
    assert!(!crate::report::render_table(&broken).is_empty());
}
