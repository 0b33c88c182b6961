use super::*;
use crate::kinematics::presets;
use crate::sim::tracker_campaign::{simulate_tracker, TrackerSpec};

fn truth() -> TermModel {
    let c = simulate_tracker(
        &presets::ur10(),
        &TrackerSpec {
            poses: 1,
            noise_mm: 0.01,
            seed: 5,
            non_geometric: true,
            orientation_noise_rad: None,
        },
    );
    let sds = vec![1e-6; c.true_terms.terms.len()];
    TermModel {
        model: c.truth,
        terms: c.true_terms,
        term_std_devs: sds,
        covariance: None,
        ranges: Vec::new(),
    }
}

const Q: [f64; 6] = [0.3, -1.1, 1.2, -0.7, 1.4, 0.2];

#[test]
fn commanded_joints_invert_the_deflections() {
    let m = truth();
    let commanded = m.commanded(&Q).unwrap();
    let back = m.deflected(&commanded).unwrap();
    for (b, q) in back.iter().zip(Q) {
        assert!((b - q).abs() < 1e-12, "{back:?} vs {Q:?}");
    }
    // The terms are tens of µrad: the commanded joints differ by that much.
    let moved = commanded
        .iter()
        .zip(Q)
        .map(|(c, q)| (c - q).abs())
        .fold(0.0, f64::max);
    assert!(moved > 1e-6 && moved < 1e-3, "{moved}");
}

#[test]
fn inverse_kinematics_with_terms_reaches_the_target_through_them() {
    let m = truth();
    let target = m.world_to_tool(&Q).unwrap();
    let solution = m.nearest_within_limits(&target, &Q).unwrap();
    let reached = m.world_to_tool(&solution.joints_rad).unwrap();
    assert!((reached.translation.vector - target.translation.vector).norm() < 1e-6);
    assert!(solution.residual_mm < 1e-6);
    // The geometric model alone at those joints misses by the deflections.
    let geometric = m.model.world_to_tool(&solution.joints_rad).unwrap();
    assert!((geometric.translation.vector - target.translation.vector).norm() > 1e-2);
}

#[test]
fn term_variance_is_the_squared_change_of_a_one_sigma_term() {
    let mut m = truth();
    // One term at a time: its variance is the squared move of the tool
    // when its value changes by its σ (linear to 1e-6 relative).
    for k in 0..m.terms.terms.len() {
        let mut one = m.clone();
        one.terms = m.terms.subset(&[k]);
        one.term_std_devs = vec![1e-5];
        let v = one.term_variance(&one.model, &Q).unwrap();
        let p0 = one.world_to_tool(&Q).unwrap().translation.vector;
        one.terms.values[0] += 1e-5;
        let p1 = one.world_to_tool(&Q).unwrap().translation.vector;
        let moved2 = (p1 - p0).norm_squared();
        assert!(
            (v.position_mm2 - moved2).abs() <= 1e-3 * moved2,
            "{}: {} vs {moved2}",
            m.terms.terms[k].name(),
            v.position_mm2
        );
    }
    m.terms = m.terms.subset(&[]);
    m.term_std_devs.clear();
    assert_eq!(
        m.term_variance(&m.model, &Q).unwrap(),
        TermVariance::default()
    );
}
