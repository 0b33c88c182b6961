//! Issue 5's accuracy targets through the service (issue 6): whole rendered
//! campaigns (60 cal + 30 val poses) uploaded, calibrated by the default
//! job and by the two-step job (`joint_refinement: false`), and the served
//! parameter sets judged against the simulator's truth and the campaign's
//! oracle floor (`robocal::testkit::accuracy`). Means over a few campaigns keep one
//! unlucky draw from deciding; the Monte-Carlo figures come from the
//! `pipeline_accuracy` example (BENCHMARKS.md "End to end").

use std::time::Duration;

use robocal::cli::campaign::simulate;
use robocal::cli::client::Client;
use robocal::testkit::accuracy::{
    compare_with_truth, dot_noise_px, oracle_floors, TruthComparison,
};
use serde_json::{json, Value};

use crate::e2e_points::assert_warns_iff_worse;
use crate::support::{is_finished, spawn_app_with, TestApp};

const WAIT: Duration = Duration::from_secs(600);
const CAL_POSES: usize = 60;
const VAL_POSES: usize = 30;
/// Campaign seeds per preset (the first ones: not chosen).
const SEEDS: std::ops::RangeInclusive<u64> = 1..=4;
/// Noise draws averaged for the oracle floor of each campaign.
const FLOOR_DRAWS: u64 = 3;
/// The served model against the image-level oracle floor (issue 5).
const ORACLE_FACTOR: f64 = 1.1;
/// The two-step job must be worse than the default job by this on the
/// mean of these campaigns (1.47x IRB over 8, 2.64x PUMA over 24 in the
/// benchmark; one campaign can go either way, IRB seed 1 does).
const TWO_STEP_MARGIN: f64 = 1.2;
const MIN_IMPROVEMENT: f64 = 12.0;
/// Reported sigmas: RMS of (estimate - truth) / sigma over all identified
/// parameters of all campaigns (1 when right; the z of one campaign are
/// correlated, so a few campaigns scatter by some tens of percent).
const Z_RMS_RANGE: std::ops::RangeInclusive<f64> = 0.7..=1.3;
/// Share of identified parameters within 3 sigma of the truth (99.7 %
/// with exact sigmas), and the largest miss tolerated among ~120.
const MIN_SHARE_WITHIN_3_SIGMA: f64 = 0.98;
const MAX_ABS_Z: f64 = 4.0;

/// Runs a job on `session` with `options` and returns the served set.
async fn served_set(
    app: &TestApp,
    client: &Client,
    serial: &str,
    session: &str,
    options: Value,
) -> Value {
    let job = client.start_calibration(session, &options).await.unwrap();
    let job = app.wait_job(&job, WAIT, is_finished).await;
    assert_eq!(job["state"], "succeeded", "{job}");
    let version = job["result"]["version"].as_i64().unwrap();
    let r = app
        .get(&format!("/v1/robots/{serial}/parameter-sets/{version}"))
        .await;
    assert_eq!(r.status(), 200);
    r.json().await.unwrap()
}

/// The report of a served set.
async fn report_of(app: &TestApp, serial: &str, set: &Value) -> Value {
    let path = format!(
        "/v1/robots/{serial}/parameter-sets/{}/report",
        set["version"]
    );
    let r = app.get(&path).await;
    assert_eq!(r.status(), 200, "{path}");
    r.json().await.unwrap()
}

async fn targets_hold(preset: &str) {
    let app = spawn_app_with(|c| c.test_validate_only = false).await;
    let client = Client::new(&app.base, None).unwrap();
    let (mut before, mut after, mut two_step, mut floor) = (0.0, 0.0, 0.0, 0.0);
    let mut z: Vec<f64> = Vec::new();
    for seed in SEEDS {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().to_path_buf();
        let preset_owned = preset.to_string();
        let (spec, campaign) = tokio::task::spawn_blocking(move || {
            simulate(&preset_owned, &path, CAL_POSES, VAL_POSES, seed).unwrap()
        })
        .await
        .unwrap();
        let serial = format!("{}-ACC-{seed}", preset.to_uppercase());
        let session = robocal::cli::upload(
            &client,
            &serial,
            dir.path(),
            robocal::cli::RobotPolicy::CreateIfMissing,
        )
        .await
        .unwrap();
        let set = served_set(&app, &client, &serial, &session, json!({})).await;
        let two = served_set(
            &app,
            &client,
            &serial,
            &session,
            json!({"joint_refinement": false}),
        )
        .await;
        if seed == *SEEDS.start() {
            // Paper mode, reported beside (BENCHMARKS.md): on these lenses
            // it is worse than the nominal model, and its report says so.
            let paper = served_set(
                &app,
                &client,
                &serial,
                &session,
                json!({"refine_intrinsics": false}),
            )
            .await;
            let report = report_of(&app, &serial, &paper).await;
            assert_eq!(report["camera"]["mode"], "paper");
            assert!(
                report["after"]["mean_mm"].as_f64() > report["before"]["mean_mm"].as_f64(),
                "{preset}: paper mode now beats the nominal model: update BENCHMARKS.md"
            );
            assert_warns_iff_worse(&report);
        }
        let report = report_of(&app, &serial, &set).await;
        let sigma_px = dot_noise_px(&serde_json::from_value(report.clone()).unwrap()).unwrap();
        let (served, two, floors) = tokio::task::spawn_blocking(move || {
            let typed = |v: Value| serde_json::from_value(v).expect("a calibrated parameter set");
            let served: TruthComparison = compare_with_truth(&typed(set), &campaign).unwrap();
            let two = compare_with_truth(&typed(two), &campaign).unwrap();
            let floors =
                oracle_floors(&spec, &campaign, sigma_px, &served.free, FLOOR_DRAWS).unwrap();
            (served, two, floors)
        })
        .await
        .unwrap();
        println!(
            "{preset} seed {seed}: before {:.4} | served {:.4} | two-step {:.4} | image floor {:.4} mm | worst {:?}",
            report["before"]["mean_mm"],
            served.validation.norm.mean_mm,
            two.validation.norm.mean_mm,
            floors.image_mm,
            served.worst()
        );
        assert_eq!(served.free.len(), 30, "{preset} seed {seed}");
        before += report["before"]["mean_mm"].as_f64().unwrap();
        after += served.validation.norm.mean_mm;
        two_step += two.validation.norm.mean_mm;
        floor += floors.image_mm;
        z.extend(served.z.iter().map(|(_, z)| *z));
    }
    assert!(
        after <= ORACLE_FACTOR * floor,
        "{preset}: served {after} vs floor {floor} (sums)"
    );
    assert!(
        after * TWO_STEP_MARGIN <= two_step,
        "{preset}: served {after} vs two-step {two_step}"
    );
    assert!(
        before >= MIN_IMPROVEMENT * after,
        "{preset}: before {before} after {after}"
    );
    let z_rms = (z.iter().map(|z| z * z).sum::<f64>() / z.len() as f64).sqrt();
    let within = z.iter().filter(|z| z.abs() <= 3.0).count() as f64 / z.len() as f64;
    let worst = z.iter().fold(0.0f64, |m, z| m.max(z.abs()));
    assert!(Z_RMS_RANGE.contains(&z_rms), "{preset}: z rms {z_rms}");
    assert!(
        within >= MIN_SHARE_WITHIN_3_SIGMA,
        "{preset}: {within} within 3 sigma"
    );
    assert!(worst <= MAX_ABS_Z, "{preset}: worst |z| {worst}");
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn irb2400_accuracy_targets_hold_through_the_service() {
    if !crate::support::numerics_run_here("irb2400_accuracy") {
        return;
    }
    targets_hold("irb2400").await;
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn puma560_accuracy_targets_hold_through_the_service() {
    if !crate::support::numerics_run_here("puma560_accuracy") {
        return;
    }
    targets_hold("puma560").await;
}
