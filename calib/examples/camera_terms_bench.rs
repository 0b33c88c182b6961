//! Issue 19 on simulated camera campaigns (PUMA 560, 80 + 30 poses): the
//! terms selected on the image points, false positives on robots without
//! terms, validation error against the geometric refinement and the floor,
//! and the selection's cost against one joint refinement.
//!
//! `cargo run --release -p robocal-calib --example camera_terms_bench [seeds]`

use robocal_calib::kinematics::image_term_selection::IMAGE_CRITERION;
use robocal_calib::sim::camera_terms::run_camera_terms;

const DEFAULT_SEEDS: u64 = 20;

fn main() {
    let seeds: u64 = std::env::args()
        .nth(1)
        .and_then(|s| s.parse().ok())
        .unwrap_or(DEFAULT_SEEDS);
    println!("criterion: {IMAGE_CRITERION}");
    for switch in [false, true] {
        let (mut kept_any, mut with, mut geo, mut pose, mut sel_s, mut ref_s, mut n) =
            (0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0);
        for seed in 1..=seeds {
            let Ok(o) = run_camera_terms(seed, switch) else {
                eprintln!("seed {seed}: campaign failed");
                continue;
            };
            let kept: Vec<String> = o
                .selected
                .selection
                .terms
                .terms
                .iter()
                .map(|t| t.name())
                .collect();
            if !kept.is_empty() {
                kept_any += 1;
            }
            println!(
                "switch {switch} seed {seed}: val {:.4} mm image-level terms, {:.4} pose-level, {:.4} geometric; kept {kept:?}; selection {:.2} s, one refinement {:.2} s",
                o.val_mm, o.pose_level_val_mm, o.geometric_val_mm, o.selection_seconds, o.refinement_seconds
            );
            with += o.val_mm;
            geo += o.geometric_val_mm;
            pose += o.pose_level_val_mm;
            sel_s += o.selection_seconds;
            ref_s += o.refinement_seconds;
            n += 1.0;
        }
        println!(
            "switch {switch}: {kept_any} of {n} campaigns kept a term; mean val {:.4} mm with image-level terms, {:.4} pose-level selection, {:.4} geometric; selection {:.2} s vs one refinement {:.2} s (mean)",
            with / n, pose / n, geo / n, sel_s / n, ref_s / n
        );
    }
}
