//! The image-level selection on the simulator (issue 19): a camera
//! campaign whose true robot has the switch's terms, and one without.

use super::*;
use crate::sim::camera_terms::run_camera_terms;

fn run(seed: u64, switch: bool) -> crate::sim::camera_terms::CameraTermsOutcome {
    run_camera_terms(seed, switch).unwrap()
}

/// Seeds of the campaigns with terms, and of those without (issue 19:
/// false positives at most 5% of campaigns).
const SEEDS_WITH: [u64; 4] = [1, 2, 3, 4];
const SEEDS_WITHOUT: std::ops::RangeInclusive<u64> = 1..=20;

#[test]
fn terms_on_the_images_bring_the_error_towards_the_floor() {
    let (mut with, mut floor, mut geometric, mut pose_level) = (0.0, 0.0, 0.0, 0.0);
    for seed in SEEDS_WITH {
        let o = run(seed, true);
        let plain = run(seed, false);
        eprintln!(
            "seed {seed}: val {:.4} mm with the image-level terms, {:.4} pose-level selection, {:.4} geometric; floor (no terms in the robot) {:.4}",
            o.val_mm, o.pose_level_val_mm, o.geometric_val_mm, plain.val_mm
        );
        assert!(o.val_mm < 0.8 * o.geometric_val_mm, "seed {seed}");
        let s = &o.selected.selection;
        assert!(!s.terms.terms.is_empty(), "seed {seed}: nothing kept");
        assert_eq!(o.selected.refinement.terms.as_ref().unwrap().terms, s.terms);
        // The elbow-roll gear term (periodic_4.cos2, 60 µrad) is separable
        // from a camera campaign: recovered within 3σ every time.
        let wrist = s
            .report
            .iter()
            .find(|l| l.name == "periodic_4.cos2")
            .unwrap();
        let truth = o.truth.values[o.truth.terms.iter().position(|k| *k == wrist.term).unwrap()];
        assert_eq!(wrist.verdict, Verdict::Kept, "seed {seed}");
        assert!(
            (wrist.value - truth).abs() < 3.0 * wrist.std_dev,
            "seed {seed}: {wrist:?}"
        );
        with += o.val_mm;
        floor += plain.val_mm;
        geometric += o.geometric_val_mm;
        pose_level += o.pose_level_val_mm;
    }
    eprintln!(
        "sums over seeds: {with:.4} with terms, {pose_level:.4} pose-level selection, {geometric:.4} geometric, floor {floor:.4}"
    );
    assert!(with < 0.5 * geometric);
    assert!(with < 0.6 * pose_level);
    assert!(with < 2.5 * floor);
}

#[test]
fn a_robot_without_terms_keeps_none_on_the_images() {
    let mut kept = Vec::new();
    for seed in SEEDS_WITHOUT {
        let o = run(seed, false);
        if !o.selected.selection.terms.terms.is_empty() {
            kept.push((seed, o.selected.selection.terms.terms.clone()));
        }
        // Without terms the final refinement is the geometric one.
        assert!(o.selected.refinement.terms.is_none() || !kept.is_empty());
    }
    eprintln!("campaigns keeping a term: {kept:?}");
    assert!(kept.len() <= 1, "{kept:?}");
}
