//! Every form of a report says the set's current release status, who gave
//! it and why, and names its own version and job: the page a click on the
//! robot page reaches (`/robots/{serial}/reports/{v}`), `report.html`,
//! `report.svg` and the JSON; the robot page's versions table has a status
//! column. Sets are stored as a job leaves them: the report without its
//! version or job (the pipeline cannot know them), the gate's decision.

use robocal::domain::{Release, ReleaseStatus};
use robocal::report::sample::sample_report;
use robocal::report::GateReport;
use robocal::store::{self, NewParameterSet};
use serde_json::json;

use crate::support::*;

/// The headline v1's own report gave, as v2's gate section shows it (mm).
pub const GATE_OWN_MEAN_MM: f64 = 0.00743;

/// The job ids of the stored sets v1..v4.
pub fn job_of(version: i64) -> String {
    format!("0193a5c2-0000-7000-8000-00000000000{version}")
}

/// Robot `serial` with four sets: v1 approved by the gate; v2 held back by
/// the gate as worse, then approved by a person ("re-measured on the
/// cell"); v3 a paper-mode candidate; v4 a candidate a person rejected
/// ("wrong board on the cell").
pub async fn robot_with_decided_sets(app: &TestApp, serial: &str) {
    let r = app
        .put_json(&format!("/v1/robots/{serial}"), &robot_body())
        .await;
    assert_eq!(r.status(), 201);
    let s = store::connect(&app.database_url).await.unwrap();
    for version in 1..=4 {
        let mut report = sample_report();
        // As the pipeline stores it: no version, no job.
        report.version = 0;
        report.job_id = String::new();
        let (status, reason) = match version {
            1 => (ReleaseStatus::Approved, "better than nominal"),
            2 => (ReleaseStatus::Candidate, "worse than before"),
            3 => (
                ReleaseStatus::Candidate,
                "paper-mode intrinsics: a person decides",
            ),
            _ => (ReleaseStatus::Candidate, "a person decides"),
        };
        if version == 2 {
            report.gate = Some(GateReport {
                status: "candidate".into(),
                reason: reason.into(),
                compared_with: format!("{serial}/1"),
                compared_mean_mm: Some(0.011),
                mean_mm: Some(0.012),
                worse: true,
                basis: Some("both sets' kinematics held, frames re-fitted".into()),
                compared_own_mean_mm: Some(GATE_OWN_MEAN_MM),
                compared_own_session_id: Some("session-of-v1".into()),
            });
        }
        let set = NewParameterSet {
            parameters: crate::support::placeholder_set("s"),
            report: serde_json::to_value(&report).unwrap(),
            release: Release {
                status,
                reason: Some(reason.into()),
            },
        };
        s.insert_parameter_set(serial, Some(&job_of(version)), &set)
            .await
            .unwrap();
    }
    let decide = |v: i64, verb: &'static str, reason: &'static str| {
        let path = format!("/v1/robots/{serial}/parameter-sets/{v}/{verb}");
        async move {
            let r = app.post_json(&path, &json!({ "reason": reason })).await;
            assert_eq!(r.status(), 200, "{verb} v{v}");
        }
    };
    decide(2, "approve", "re-measured on the cell").await;
    decide(4, "reject", "wrong board on the cell").await;
}

#[tokio::test]
async fn every_report_form_names_its_version_job_and_current_status() {
    let app = spawn_app().await;
    robot_with_decided_sets(&app, "REL-1").await;

    // The page the robot page links to: its own version and job.
    for v in 1..=4 {
        let page = app
            .get(&format!("/robots/REL-1/reports/{v}"))
            .await
            .text()
            .await
            .unwrap();
        assert!(
            page.contains(&format!("<th>Parameter set</th><td>v{v}</td>")),
            "v{v}: {page}"
        );
        assert!(page.contains(&job_of(v)), "v{v} names its job");
    }

    // v2: held back by the gate, approved by a person: the person's
    // decision opens it, the gate's finding follows; no "held back" claim.
    let v2 = app
        .get("/robots/REL-1/reports/2")
        .await
        .text()
        .await
        .unwrap();
    assert!(
        v2.contains("APPROVED by anonymous at ")
            && v2.contains(": re-measured on the cell. The release gate had held it back: "),
        "{v2}"
    );
    assert!(!v2.contains("not served as latest"), "{v2}");
    assert!(v2.contains("<td id=\"status\">approved</td>"));

    let v3 = app
        .get("/robots/REL-1/reports/3")
        .await
        .text()
        .await
        .unwrap();
    assert!(
        v3.contains("CANDIDATE, not served as latest (held back by gate at ")
            && v3.contains("paper-mode intrinsics: a person decides"),
        "{v3}"
    );
    let v4 = app
        .get("/robots/REL-1/reports/4")
        .await
        .text()
        .await
        .unwrap();
    assert!(
        v4.contains("REJECTED by anonymous at ")
            && v4.contains(": wrong board on the cell; never served as latest."),
        "{v4}"
    );

    // The API's forms say the same.
    let html = app
        .get("/v1/robots/REL-1/parameter-sets/4/report.html")
        .await
        .text()
        .await
        .unwrap();
    assert!(html.contains("REJECTED by anonymous"), "{html}");
    let svg = app
        .get("/v1/robots/REL-1/parameter-sets/4/report.svg")
        .await
        .text()
        .await
        .unwrap();
    assert!(svg.contains("REJECTED by anonymous"), "the SVG headline");
    let json = app.get_ok("/v1/robots/REL-1/parameter-sets/2/report").await;
    assert_eq!(json["status"], "approved");
    assert_eq!(json["status_by"], "anonymous");
    assert_eq!(json["status_reason"], "re-measured on the cell");
    assert_eq!(json["job_id"], job_of(2));

    // The robot page: one status per version, who gave it.
    let robot = app.get("/robots/REL-1").await.text().await.unwrap();
    for (v, status, by) in [
        (1, "approved", "gate"),
        (2, "approved", "anonymous"),
        (3, "candidate", "gate"),
        (4, "rejected", "anonymous"),
    ] {
        let row = robot
            .split(&format!("<tr id=\"v{v}\">"))
            .nth(1)
            .and_then(|r| r.split("</tr>").next())
            .unwrap_or_else(|| panic!("a row for v{v}: {robot}"));
        assert!(
            row.contains(&format!(">{status}</span> · by {by}")),
            "v{v}: {row}"
        );
    }
}
