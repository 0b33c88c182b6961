//! How a hand–eye set (a session of controller flange poses; no
//! kinematics identified) reads: what it measured (the camera in the
//! flange frame, the board in the base frame, the board's scale, the
//! camera's residuals) instead of a before/after that cannot move: with
//! the kinematics untouched, "before" and "after" are the same model.

use super::format::{escape_xml, fixed, mm, significant, with_precision_of};
use super::hand_eye::{FrameReport, HandEyeReport};
use super::model::Report;
use std::fmt::Write;

/// Decimals of a pixel residual.
const PX_DECIMALS: usize = 3;

/// Largest of three standard deviations (the frame's worst axis).
fn worst(std: &[f64; 3]) -> f64 {
    std.iter().copied().fold(0.0, f64::max)
}

/// The headline of a hand–eye set: what it identified and how well the
/// images agree with it, and that the kinematics were not identified.
pub fn hand_eye_headline(report: &Report, he: &HandEyeReport) -> String {
    format!(
        "hand–eye calibration (kinematics not identified): camera in the flange frame to \
         ±{} mm, ±{}°; reprojection RMS {} px over {} poses; camera positions from the flange \
         poses and the images agree to {} mm mean at {} validation poses",
        mm(worst(&he.flange_to_camera.std_translation_mm)),
        significant(worst(&he.flange_to_camera.std_rotation_deg), 2),
        fixed(he.reprojection_rms_px, PX_DECIMALS),
        he.poses_used,
        mm(report.after.norm.mean_mm),
        report.after.norm.n
    )
}

/// The verdict box of a hand–eye set (replaces the before → after one).
pub fn hand_eye_verdict(page: &mut String, report: &Report, he: &HandEyeReport) {
    let _ = writeln!(
        page,
        "<div class=\"verdict hand-eye\"><div class=\"label\">Hand–eye calibration from controller \
         flange poses: the kinematics were not identified, so there is no before and after</div>\
         <div class=\"big\">{} px</div><div class=\"label\">reprojection RMS over {} poses \
         ({} image points)</div><div class=\"big\">{} mm</div><div class=\"label\">mean distance \
         between the camera positions the flange poses predict and those the images measure, at \
         {} validation poses</div></div>",
        fixed(he.reprojection_rms_px, PX_DECIMALS),
        he.poses_used,
        he.points,
        mm(report.after.norm.mean_mm),
        report.after.norm.n
    );
}

fn frame_row(page: &mut String, name: &str, f: &FrameReport) {
    let t: Vec<String> = (0..3)
        .map(|i| with_precision_of(f.translation_mm[i], f.std_translation_mm[i]))
        .collect();
    let r: Vec<String> = (0..3)
        .map(|i| with_precision_of(f.rotation_deg[i], f.std_rotation_deg[i]))
        .collect();
    let _ = writeln!(
        page,
        "<tr><td>{name}</td><td class=\"num\">{}</td><td class=\"num\">±{}</td>\
         <td class=\"num\">{}</td><td class=\"num\">±{}</td></tr>",
        t.join(", "),
        mm(worst(&f.std_translation_mm)),
        r.join(", "),
        significant(worst(&f.std_rotation_deg), 2)
    );
}

/// Section "What this hand–eye set measured".
pub fn hand_eye_section(page: &mut String, he: &HandEyeReport) {
    page.push_str(
        "<section id=\"hand-eye\">\n<h2>What this hand–eye set measured</h2>\n\
         <p>The controller's flange poses were taken as exact: this set identifies where the camera \
         sits on the flange and where the board lies in the base frame, not the robot's \
         kinematics (use a session of joint angles for those).</p>\n\
         <table class=\"data\"><tr><th>frame</th><th class=\"num\">translation x, y, z [mm]</th>\
         <th class=\"num\">σ</th><th class=\"num\">rotation x, y, z [deg]</th><th class=\"num\">σ</th></tr>\n",
    );
    frame_row(page, "camera in the flange frame", &he.flange_to_camera);
    frame_row(page, "board in the base frame", &he.base_to_target);
    let s = &he.board_scale;
    let _ = writeln!(
        page,
        "</table>\n<p>Board scale {} ± {} (spacing as printed {} ± {} mm, configured {} mm); \
         residual σ {} px per image axis; standard deviations: {}.</p>\n</section>",
        with_precision_of(s.scale, s.std),
        significant(s.std, 2),
        with_precision_of(s.pitch_mm, s.pitch_std_mm),
        significant(s.pitch_std_mm, 2),
        mm(s.configured_pitch_mm),
        fixed(he.sigma_px, PX_DECIMALS),
        escape_xml(&he.std_source)
    );
}
