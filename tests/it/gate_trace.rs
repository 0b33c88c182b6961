//! The release gate's "before" can be traced: re-running the same job on
//! the same images gives the same set, which the gate finds the same as
//! the approved one (not "better than before"); its report shows both
//! figures, how the gate figured them, and the approved set's own report
//! figure with its session.

use serde_json::json;

use crate::support::*;

const SERIAL: &str = "GATE-TRACE";
/// The gate's tolerance for "the same figure" (mm; `pipeline::gate`).
const SAME_WITHIN_MM: f64 = 1e-6;

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn the_same_job_on_the_same_images_is_the_same_set_not_a_better_one() {
    let dir = tempfile::tempdir().unwrap();
    robocal::cli::campaign::simulate("irb2400", dir.path(), 24, 8, 1).unwrap();
    let app = spawn_app_with(|c| c.test_validate_only = false).await;
    let job1 = upload_and_calibrate(&app, SERIAL, dir.path()).await;
    let session = job1["session_id"].as_str().unwrap().to_string();
    let job2 = app
        .finished_job(
            &format!("/v1/sessions/{session}/calibrations"),
            &json!({}),
            CAMPAIGN_WAIT,
        )
        .await;
    assert_eq!(job2["state"], "succeeded", "{job2}");
    let sets = format!("/v1/robots/{SERIAL}/parameter-sets");
    let set1 = app.get_ok(&format!("{sets}/1")).await;
    let set2 = app.get_ok(&format!("{sets}/2")).await;
    assert_eq!(set1["status"], "approved", "{}", set1["status_reason"]);
    // The scenario: the two jobs gave the same parameters.
    assert!(set1["parameters"].is_array(), "{set1}");
    assert_eq!(set1["parameters"], set2["parameters"]);
    assert_eq!(set1["kinematics"], set2["kinematics"]);
    let report1 = app.get_ok(&format!("{sets}/1/report")).await;
    let report2 = app.get_ok(&format!("{sets}/2/report")).await;
    let gate = &report2["gate"];
    eprintln!("gate of the re-run: {gate}");
    assert_eq!(gate["compared_with"], format!("{SERIAL}/1"), "{gate}");
    let (ours, theirs) = (
        gate["mean_mm"].as_f64().unwrap(),
        gate["compared_mean_mm"].as_f64().unwrap(),
    );
    assert!((ours - theirs).abs() <= SAME_WITHIN_MM, "{gate}");
    assert_eq!(gate["status"], "candidate", "{gate}");
    assert_eq!(gate["worse"], false, "{gate}");
    let reason = gate["reason"].as_str().unwrap();
    assert!(reason.contains("the same as before"), "{reason}");
    assert!(!reason.contains("better than before"), "{reason}");
    assert_eq!(set2["status"], "candidate", "{}", set2["status_reason"]);
    // Traceable: the approved set's own report figure and session beside
    // the gate's, and how the gate figured both.
    assert_eq!(gate["compared_own_mean_mm"], report1["after"]["mean_mm"]);
    assert_eq!(gate["compared_own_session_id"], session.as_str());
    assert!(
        gate["basis"].as_str().is_some_and(|b| b.contains("held")),
        "{gate}"
    );
    let html = app
        .get(&format!("/v1/robots/{SERIAL}/parameter-sets/2/report.html"))
        .await
        .text()
        .await
        .unwrap();
    let section = html
        .split("id=\"release-gate\"")
        .nth(1)
        .expect("the HTML report has a release-gate section");
    let own = robocal::report::format::mm(report1["after"]["mean_mm"].as_f64().unwrap());
    assert!(
        section.contains(&format!("id=\"gate-compared-own\">{own} mm")),
        "{section}"
    );
    app.shutdown().await;
}
