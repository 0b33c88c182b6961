//! Tables and sections of the HTML report (see `html.rs` for the page).
//! All text from the report is escaped with [`escape_xml`].

use super::format::{
    decimals_for_std, ellipsize, escape_xml, fixed, mm, significant, with_precision_of,
    NOT_AVAILABLE, STAT_ROWS, TABLE_NAME_CHARS,
};
use super::model::{CameraReport, PoseReport, Report};
use std::fmt::Write;

/// Board-to-image angle range quoted for the views, and the RMS range.
const ANGLE_DECIMALS: usize = 1;
const RMS_DECIMALS: usize = 3;

fn ratio(before: f64, after: f64) -> String {
    if after > 0.0 && before.is_finite() && after.is_finite() {
        format!("{}x", significant(before / after, 3))
    } else {
        NOT_AVAILABLE.to_string()
    }
}

pub fn stats_table(page: &mut String, report: &Report) {
    let (b, a) = (&report.before.norm, &report.after.norm);
    page.push_str(
        "<table class=\"data\"><caption class=\"muted\">3-D position error [mm]</caption>\
         <tr><th></th><th class=\"num before\">before</th><th class=\"num after\">after</th><th class=\"num\">ratio</th></tr>\n",
    );
    let _ = writeln!(
        page,
        "<tr><td>poses</td><td class=\"num\">{}</td><td class=\"num\">{}</td><td></td></tr>",
        b.n, a.n
    );
    for (name, get) in STAT_ROWS {
        let _ = writeln!(
            page,
            "<tr><td>{name}</td><td class=\"num\">{}</td><td class=\"num\">{}</td><td class=\"num\">{}</td></tr>",
            mm(get(b)),
            mm(get(a)),
            ratio(get(b), get(a))
        );
    }
    page.push_str("</table>\n");
}

pub fn axis_table(page: &mut String, report: &Report) {
    let (b, a) = (&report.before, &report.after);
    page.push_str(
        "<table class=\"data\"><caption class=\"muted\">Absolute error per axis, target frame [mm]</caption>\
         <tr><th>axis</th><th class=\"num before\">before mean</th><th class=\"num before\">before max</th>\
         <th class=\"num after\">after mean</th><th class=\"num after\">after max</th><th class=\"num\">ratio</th></tr>\n",
    );
    for (name, before, after) in [
        ("x", &b.x, &a.x),
        ("y", &b.y, &a.y),
        ("z", &b.z, &a.z),
        ("3-D", &b.norm, &a.norm),
    ] {
        let _ = writeln!(
            page,
            "<tr><td>{name}</td><td class=\"num\">{}</td><td class=\"num\">{}</td><td class=\"num\">{}</td>\
             <td class=\"num\">{}</td><td class=\"num\">{}</td></tr>",
            mm(before.mean_mm),
            mm(before.max_mm),
            mm(after.mean_mm),
            mm(after.max_mm),
            ratio(before.mean_mm, after.mean_mm)
        );
    }
    page.push_str("</table>\n");
}

pub fn intrinsics_table(page: &mut String, camera: &CameraReport) {
    let std = camera.std;
    let s = |f: fn(&super::model::CameraStd) -> f64| std.as_ref().map(f).unwrap_or(f64::NAN);
    let rows = [
        ("f<sub>x</sub>", camera.intrinsics.fx, s(|d| d.fx), "px"),
        ("f<sub>y</sub>", camera.intrinsics.fy, s(|d| d.fy), "px"),
        ("c<sub>x</sub>", camera.intrinsics.cx, s(|d| d.cx), "px"),
        ("c<sub>y</sub>", camera.intrinsics.cy, s(|d| d.cy), "px"),
        ("k<sub>1</sub>", camera.intrinsics.k1, s(|d| d.k1), ""),
        ("k<sub>2</sub>", camera.intrinsics.k2, s(|d| d.k2), ""),
        ("p<sub>1</sub>", camera.intrinsics.p1, s(|d| d.p1), ""),
        ("p<sub>2</sub>", camera.intrinsics.p2, s(|d| d.p2), ""),
        ("k<sub>3</sub>", camera.intrinsics.k3, f64::NAN, ""),
    ];
    let _ = writeln!(
        page,
        "<table class=\"data\"><caption class=\"muted\">Intrinsics ({} model, {} x {} px)</caption>\
         <tr><th>parameter</th><th class=\"num\">value</th><th class=\"num\">std dev</th><th>unit</th></tr>",
        escape_xml(&camera.mode_label()),
        camera.image_width,
        camera.image_height
    );
    for (name, value, sd, unit) in rows {
        let sd_text = if sd.is_finite() {
            significant(sd, 2)
        } else {
            "–".to_string()
        };
        let _ = writeln!(
            page,
            "<tr><td>{name}</td><td class=\"num\">{}</td><td class=\"num\">{sd_text}</td><td>{unit}</td></tr>",
            with_precision_of(value, sd)
        );
    }
    let _ = writeln!(
        page,
        "<tr><td>reprojection RMS</td><td class=\"num\">{}</td><td></td><td>px</td></tr>\
         <tr><td>outliers dropped</td><td class=\"num\">{}</td><td></td><td>dots</td></tr></table>",
        fixed(camera.reprojection_rms_px, RMS_DECIMALS),
        camera.outliers_dropped
    );
}

fn range(values: impl Iterator<Item = f64>, decimals: usize) -> String {
    let v: Vec<f64> = values.filter(|v| v.is_finite()).collect();
    let lo = v.iter().copied().fold(f64::INFINITY, f64::min);
    let hi = v.iter().copied().fold(f64::NEG_INFINITY, f64::max);
    if v.is_empty() {
        NOT_AVAILABLE.to_string()
    } else {
        format!("{} – {}", fixed(lo, decimals), fixed(hi, decimals))
    }
}

/// Summary of all views.
pub fn views_table(page: &mut String, camera: &CameraReport) {
    let warned: Vec<_> = camera
        .views
        .iter()
        .filter(|v| v.warning.is_some())
        .collect();
    let _ = writeln!(
        page,
        "<div><table class=\"data kv\"><caption class=\"muted\">Views</caption>\
         <tr><th>views used</th><td class=\"num\">{}</td></tr>\
         <tr><th>RMS per view [px]</th><td class=\"num\">{}</td></tr>\
         <tr><th>board-to-image angle [°]</th><td class=\"num\">{}</td></tr>\
         <tr><th>views with warnings</th><td class=\"num\">{}</td></tr></table></div>",
        camera.views.len(),
        range(camera.views.iter().map(|v| v.rms_px), RMS_DECIMALS),
        range(
            camera.views.iter().map(|v| v.board_angle_deg),
            ANGLE_DECIMALS
        ),
        warned.len()
    );
}

/// A row for every view with a warning.
pub fn view_warnings_table(page: &mut String, camera: &CameraReport) {
    let warned: Vec<_> = camera
        .views
        .iter()
        .filter(|v| v.warning.is_some())
        .collect();
    if !warned.is_empty() {
        page.push_str(
            "<table class=\"data compact\"><tr><th>pose</th><th class=\"num\">RMS [px]</th>\
             <th class=\"num\">angle [°]</th><th>warning</th></tr>\n",
        );
        for v in warned {
            let _ = writeln!(
                page,
                "<tr>{}<td class=\"num\">{}</td><td class=\"num\">{}</td><td class=\"warn\">{}</td></tr>",
                name_cell(v.name()),
                fixed(v.rms_px, RMS_DECIMALS),
                fixed(v.board_angle_deg, ANGLE_DECIMALS),
                escape_xml(v.warning.as_deref().unwrap_or_default())
            );
        }
        page.push_str("</table>\n");
    }
}

pub fn detection(page: &mut String, report: &Report) {
    let Some(d) = &report.detection else { return };
    let _ = writeln!(
        page,
        "<p><b>Dot detection:</b> {} of {} images detected, {} dots per image.</p>",
        d.images_detected, d.images, d.dots_per_image
    );
    if !d.failures.is_empty() {
        page.push_str("<table class=\"data compact\"><tr><th>pose</th><th>why the image was not used</th></tr>\n");
        for f in &d.failures {
            let _ = writeln!(
                page,
                "<tr>{}<td class=\"warn\">{}</td></tr>",
                name_cell(f.name()),
                escape_xml(&f.reason)
            );
        }
        page.push_str("</table>\n");
    }
}

pub fn parameters(page: &mut String, report: &Report) {
    let class = if report.camera.is_some() {
        " class=\"pagebreak\""
    } else {
        ""
    };
    let _ = writeln!(page, "<section{class}>");
    page.push_str(
        "<h2>3. Identified parameters</h2>\n<table class=\"data compact\"><thead><tr><th>parameter</th>\
         <th class=\"num\">nominal</th><th class=\"num\">identified</th><th class=\"num\">change</th>\
         <th class=\"num\">std dev</th><th>unit</th><th>status</th></tr></thead>\n",
    );
    for p in &report.parameters {
        let decimals = decimals_for_std(p.std);
        let (status, std) = if p.fixed {
            ("<span class=\"flag\">held fixed</span>", "–".to_string())
        } else {
            ("identified", significant(p.std, 2))
        };
        let _ = writeln!(
            page,
            "<tr><td>{}</td><td class=\"num\">{}</td><td class=\"num\">{}</td><td class=\"num\">{}</td>\
             <td class=\"num\">{std}</td><td>{}</td><td>{status}</td></tr>",
            escape_xml(&p.name),
            fixed(p.nominal, decimals),
            fixed(p.identified, decimals),
            fixed(p.identified - p.nominal, decimals),
            escape_xml(&p.unit)
        );
    }
    page.push_str("</table>\n</section>\n");
}

pub fn identifiability(page: &mut String, report: &Report) {
    let id = &report.identifiability;
    let fixed_list = if id.fixed.is_empty() {
        "none".to_string()
    } else {
        id.fixed
            .iter()
            .map(|f| escape_xml(f))
            .collect::<Vec<_>>()
            .join(", ")
    };
    let _ = write!(
        page,
        "<section>\n<h2>4. Identifiability</h2>\n<table class=\"data kv\">\
         <tr><th>parameters in the model</th><td class=\"num\">{}</td></tr>\
         <tr><th>rank of the identification Jacobian</th><td class=\"num\">{}</td></tr>\
         <tr><th>condition number (scaled Jacobian)</th><td class=\"num\">{}</td></tr>\
         <tr><th>observability index</th><td class=\"num\">{}</td></tr>\
         <tr><th>held fixed (not identifiable)</th><td>{fixed_list}</td></tr></table>\n</section>\n",
        id.parameters,
        id.rank,
        significant(id.condition_number, 4),
        significant(id.observability_index, 3)
    );
}

/// A table cell naming a pose: cut to one line, the whole name on hover.
fn name_cell(name: &str) -> String {
    format!(
        "<td title=\"{}\">{}</td>",
        escape_xml(name),
        escape_xml(&ellipsize(name, TABLE_NAME_CHARS))
    )
}

pub fn per_pose(page: &mut String, report: &Report) {
    page.push_str(
        "<section class=\"pagebreak\">\n<h2>Appendix: error at every pose [mm]</h2>\n<p>Error = measured − predicted \
         position, target frame. <i>val</i> (shaded): validation pose, in the statistics, <i>cal</i>: used for identification.</p>\n\
         <table class=\"data compact\"><thead><tr><th>pose</th><th>set</th>\
         <th class=\"num before\">before x</th><th class=\"num before\">y</th><th class=\"num before\">z</th><th class=\"num before\">|3-D|</th>\
         <th class=\"num after\">after x</th><th class=\"num after\">y</th><th class=\"num after\">z</th><th class=\"num after\">|3-D|</th>\
         <th class=\"num\">reproj. RMS [px]</th></tr></thead>\n",
    );
    for p in &report.per_pose {
        let [bx, by, bz] = p.before_error_mm;
        let [ax, ay, az] = p.after_error_mm;
        let rms = p
            .reprojection_rms_px
            .map_or("–".to_string(), |r| fixed(r, RMS_DECIMALS));
        let row_class = if p.set == "val" { " class=\"val\"" } else { "" };
        let _ = write!(
            page,
            "<tr{row_class}>{}<td>{}</td>",
            name_cell(p.name()),
            escape_xml(&set_cell(p))
        );
        for v in [bx, by, bz] {
            let _ = write!(page, "<td class=\"num\">{}</td>", fixed(v, 3));
        }
        let _ = write!(
            page,
            "<td class=\"num\"><b>{}</b></td>",
            fixed(p.before_mm, 3)
        );
        for v in [ax, ay, az] {
            let _ = write!(page, "<td class=\"num\">{}</td>", fixed(v, 3));
        }
        let _ = writeln!(
            page,
            "<td class=\"num\"><b>{}</b></td><td class=\"num\">{rms}</td></tr>",
            fixed(p.after_mm, 3)
        );
    }
    page.push_str("</table>\n</section>\n");
}

pub fn notes_and_signoff(page: &mut String, report: &Report) {
    page.push_str("<section>\n<h2>5. Notes and sign-off</h2>\n");
    if report.notes.is_empty() {
        page.push_str("<p class=\"muted\">None.</p>\n");
    } else {
        page.push_str("<ul class=\"notes\">\n");
        for note in &report.notes {
            let _ = writeln!(page, "<li>{}</li>", escape_xml(note));
        }
        page.push_str("</ul>\n");
    }
    page.push_str(
        "<div class=\"signoff\"><div>Checked by (name)</div><div>Date</div><div>Signature</div></div>\n</section>\n",
    );
}

/// The "set" cell: an outlier says it was left out, and why.
pub fn set_cell(p: &PoseReport) -> String {
    match (&p.reason, p.outlier) {
        (Some(why), true) => format!("{}, left out: {why}", p.set),
        (None, true) => format!("{}, left out", p.set),
        _ => p.set.clone(),
    }
}
