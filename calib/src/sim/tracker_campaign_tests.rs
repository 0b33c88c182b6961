use super::*;
use crate::kinematics::identify::{validate, IdentifyMode};
use crate::kinematics::nongeometric::{CandidateOptions, NonGeometricError};
use crate::kinematics::presets;
use crate::kinematics::term_selection::{identify_with_terms, Verdict};
use crate::kinematics::term_validate::validate_with_terms;
use crate::kinematics::{identify::IdentifyError, Instrument};

const CAL_POSES: usize = 300;
const VAL_POSES: usize = 200;
const NOISE_MM: f64 = 0.01;
const RECOVERY_SIGMAS: f64 = 3.0;
/// Seeds of the false-positive run (the example runs more).
const NULL_SEEDS: u64 = 20;
const NULL_POSES: usize = 150;

fn campaign(seed: u64, switch: bool, poses: usize) -> TrackerCampaign {
    simulate_tracker(
        &presets::ur10(),
        &TrackerSpec {
            poses,
            noise_mm: NOISE_MM,
            seed,
            non_geometric: switch,
            orientation_noise_rad: None,
        },
    )
}

#[test]
fn compliance_and_periodic_errors_are_recovered_within_three_sigma() {
    let c = campaign(7, true, CAL_POSES + VAL_POSES);
    let (cal, val) = c.measurements.split_at(CAL_POSES);
    let candidates = CandidateOptions::for_robot(&c.start.robot);
    let id = identify_with_terms(
        &c.start,
        Instrument::Tracker,
        cal,
        IdentifyMode::Weighted.into(),
        &candidates,
    )
    .unwrap();
    for line in &id.report {
        eprintln!(
            "{:28} {:?} {:.3e} ± {:.1e}: {}",
            line.name, line.verdict, line.value, line.std_dev, line.why
        );
    }
    for (term, truth) in c.true_terms.terms.iter().zip(&c.true_terms.values) {
        let k = id
            .terms
            .terms
            .iter()
            .position(|t| t == term)
            .unwrap_or_else(|| panic!("{} not kept", term.name()));
        let (v, sd) = (id.terms.values[k], id.term_std_devs[k]);
        assert!(
            (v - truth).abs() <= RECOVERY_SIGMAS * sd,
            "{}: {v:.3e} ± {sd:.1e} vs truth {truth:.3e}",
            term.name()
        );
    }
    let (geo, _) = validate(&id.geometric.model, val).unwrap();
    let (with, _) = validate_with_terms(&id.model, &id.terms, val).unwrap();
    // Noise floor: rms of a 3-D error with σ per axis is √3 σ.
    let floor = 3f64.sqrt() * NOISE_MM;
    eprintln!(
        "validation rms: geometric {:.4} mm, with terms {:.4} mm, floor {floor:.4}",
        geo.norm.rms_mm, with.norm.rms_mm
    );
    assert!(
        with.norm.rms_mm < 1.2 * floor,
        "{} vs floor {floor}",
        with.norm.rms_mm
    );
    assert!(geo.norm.rms_mm > 3.0 * with.norm.rms_mm);
}

#[test]
fn a_robot_without_terms_keeps_none_in_at_least_95_percent_of_campaigns() {
    let candidates = CandidateOptions::for_robot(&presets::ur10());
    let mut false_positive = 0;
    for seed in 0..NULL_SEEDS {
        let c = campaign(1000 + seed, false, NULL_POSES);
        let id = identify_with_terms(
            &c.start,
            Instrument::Tracker,
            &c.measurements,
            IdentifyMode::Weighted.into(),
            &candidates,
        )
        .unwrap();
        if !id.terms.terms.is_empty() {
            eprintln!("seed {seed}: kept {:?}", id.terms.terms);
            false_positive += 1;
        }
    }
    assert!(
        false_positive as f64 <= 0.05 * NULL_SEEDS as f64,
        "{false_positive} campaigns kept a term"
    );
}

#[test]
fn a_term_the_campaign_cannot_see_is_reported_and_left_out() {
    // The reflector on the wrist-3 axis: turning joint 6 moves nothing, so
    // its periodic errors cannot be seen.
    let mut c = campaign(3, true, CAL_POSES);
    let on_axis = Pose::translation(0.0, 0.0, 100.0);
    c.truth.flange_to_tool = on_axis;
    c.start.flange_to_tool = on_axis;
    for m in &mut c.measurements {
        let p = c.true_terms.world_to_tool(&c.truth, &m.joints_rad).unwrap();
        m.observed = Observed::Position {
            position_mm: p.translation.vector,
            covariance: None,
        };
    }
    let id = identify_with_terms(
        &c.start,
        Instrument::Tracker,
        &c.measurements,
        IdentifyMode::Weighted.into(),
        &CandidateOptions::for_robot(&c.start.robot),
    )
    .unwrap();
    let periodic_4: Vec<_> = id
        .report
        .iter()
        .filter(|l| l.name.starts_with("periodic_6."))
        .collect();
    assert_eq!(periodic_4.len(), 4);
    assert!(periodic_4
        .iter()
        .all(|l| l.verdict == Verdict::NotIdentifiable));
    assert!(id.terms.terms.iter().all(|t| t.joint() != 5));
}

#[test]
fn a_negative_or_nan_payload_is_an_error() {
    let c = campaign(1, false, 30);
    for payload_kg in [-1.0, f64::NAN, f64::INFINITY] {
        let mut candidates = CandidateOptions::for_robot(&c.start.robot);
        candidates.payload_kg = payload_kg;
        let err = identify_with_terms(
            &c.start,
            Instrument::Tracker,
            &c.measurements,
            IdentifyMode::Weighted.into(),
            &candidates,
        )
        .unwrap_err();
        assert!(matches!(
            err,
            IdentifyError::NonGeometric(NonGeometricError::BadPayload(_))
        ));
    }
}
