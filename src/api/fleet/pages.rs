//! The fleet page and a robot's page, rendered from the service's views
//! (`service::fleet`). Every text is escaped; serials are URL-safe by
//! their rule (`Serial`), so they go into links as they are.

use std::fmt::Write;

use super::frame::{ago, old, page};
use crate::report::format::{escape_xml, fixed, mm};
use crate::service::fleet::{
    Accuracy, JobBrief, RobotDetail, RobotSummary, SetSummary, MAX_ROBOTS,
};

/// Decimals of a reprojection RMS in pixels.
const PX_DECIMALS: usize = 3;

/// What a robot that was never re-checked shows.
pub const NO_CHECKS: &str = "no checks";

fn robot_href(serial: &str) -> String {
    format!("/robots/{serial}")
}

fn report_href(serial: &str, version: i64) -> String {
    format!("/robots/{serial}/reports/{version}")
}

fn accuracy_text(set: &SetSummary) -> String {
    match &set.accuracy {
        Some(Accuracy {
            hand_eye_rms_px: Some(px),
            validation_poses,
            after_mean_mm,
            ..
        }) => format!(
            "hand–eye set (kinematics not identified): reprojection {} px; camera {} mm mean \
             at {validation_poses} validation poses",
            fixed(*px, PX_DECIMALS),
            mm(*after_mean_mm)
        ),
        Some(a) => format!(
            "{} mm mean at {} validation poses (nominal {} mm)",
            mm(a.after_mean_mm),
            a.validation_poses,
            mm(a.before_mean_mm)
        ),
        None => "no accuracy report".into(),
    }
}

fn job_text(j: &JobBrief) -> String {
    let stage = j.stage.as_deref().unwrap_or("waiting");
    format!(
        "{} {} — {} {:.0}%",
        j.kind,
        j.state.as_str(),
        stage,
        j.progress * 100.0
    )
}

/// Which set a check judged, said when it is not the current one.
fn checked_against(checked: Option<i64>, current: Option<i64>) -> String {
    match checked {
        Some(v) if Some(v) == current => format!(" · on v{v}"),
        Some(v) => match current {
            Some(c) => format!(" · <span class=\"stale\">on v{v}, not the current v{c}</span>"),
            None => format!(" · on v{v}"),
        },
        None => String::new(),
    }
}

/// The `<dl>` of a robot's state, shared by both pages.
fn state_list(r: &RobotSummary, now_ms: i64) -> String {
    let mut dl = String::from("<dl>\n");
    let (set, accuracy) = match &r.current {
        Some(s) => (
            format!(
                "v{} · {}",
                s.version,
                escape_xml(&old(&s.created_at, now_ms))
            ),
            escape_xml(&accuracy_text(s)),
        ),
        None => ("not calibrated".into(), "—".into()),
    };
    let check = match &r.last_check {
        Some(c) => format!(
            "<span class=\"verdict {0}\">{0}</span>{1} · {2}",
            escape_xml(&c.verdict),
            checked_against(c.checked_version, r.current.as_ref().map(|s| s.version)),
            escape_xml(&ago(&c.at, now_ms))
        ),
        None => format!("<span class=\"muted\">{NO_CHECKS}</span>"),
    };
    let jobs = if r.jobs_in_progress.is_empty() {
        "<span class=\"muted\">none in progress</span>".to_string()
    } else {
        r.jobs_in_progress
            .iter()
            .map(|j| {
                format!(
                    "<span class=\"state-{}\">{}</span>",
                    j.state.as_str(),
                    escape_xml(&job_text(j))
                )
            })
            .collect::<Vec<_>>()
            .join("<br>")
    };
    let _ = writeln!(dl, "<dt>Model</dt><dd>{}</dd>", escape_xml(&r.model));
    let controller = match &r.controller {
        Some(c) => escape_xml(&c.describe()),
        None => "<span class=\"muted\">not given</span>".into(),
    };
    let _ = writeln!(
        dl,
        "<dt>Controller</dt><dd class=\"controller\">{controller}</dd>"
    );
    let _ = writeln!(dl, "<dt>Parameter set</dt><dd class=\"set\">{set}</dd>");
    let _ = writeln!(
        dl,
        "<dt>Accuracy</dt><dd class=\"accuracy\">{accuracy}</dd>"
    );
    let _ = writeln!(dl, "<dt>Last check</dt><dd class=\"check\">{check}</dd>");
    let _ = writeln!(dl, "<dt>Jobs</dt><dd class=\"jobs\">{jobs}</dd>");
    if let Some(j) = &r.last_failed {
        let _ = writeln!(
            dl,
            "<dt>Last job</dt><dd class=\"failed\"><span class=\"state-failed\">{} failed</span>: {} \
             (<a href=\"{2}#job-{3}\">job {3}</a>, {4})</dd>",
            escape_xml(&j.kind),
            escape_xml(j.error.as_deref().unwrap_or("no reason recorded")),
            robot_href(&j.serial),
            escape_xml(&j.id),
            escape_xml(&ago(&j.created_at, now_ms))
        );
    }
    dl.push_str("</dl>\n");
    dl
}

/// `GET /`: one card per robot.
pub fn fleet_page(robots: &[RobotSummary], now_ms: i64, logout: bool) -> String {
    let mut body = String::new();
    let running: usize = robots.iter().map(|r| r.jobs_in_progress.len()).sum();
    let _ = writeln!(
        body,
        "<h1>Fleet</h1>\n<p class=\"muted\" id=\"fleet-summary\">{} robot{} · {} job{} in progress</p>",
        robots.len(),
        if robots.len() == 1 { "" } else { "s" },
        running,
        if running == 1 { "" } else { "s" }
    );
    if robots.is_empty() {
        body.push_str(
            "<p>No robots yet. Add one with <code>robocal upload</code> or \
             <code>PUT /v1/robots/{serial}</code>.</p>",
        );
    }
    if robots.len() as i64 >= MAX_ROBOTS {
        let _ = writeln!(
            body,
            "<p class=\"muted\">Showing the first {MAX_ROBOTS} robots by serial.</p>"
        );
    }
    body.push_str("<div class=\"cards\">\n");
    for r in robots {
        let _ = write!(
            body,
            "<section class=\"card robot{3}\" id=\"robot-{0}\">\n<h2><a href=\"{1}\">{0}</a></h2>\n{2}</section>\n",
            escape_xml(&r.serial),
            robot_href(&r.serial),
            state_list(r, now_ms),
            if r.last_failed.is_some() { " failed" } else { "" }
        );
    }
    body.push_str("</div>");
    page("Fleet · robocal", &body, logout)
}

fn versions_table(
    serial: &str,
    versions: &[SetSummary],
    current: Option<i64>,
    now_ms: i64,
) -> String {
    if versions.is_empty() {
        return "<p class=\"muted\">No parameter sets yet.</p>\n".into();
    }
    let mut t = String::from(
        "<div class=\"scroll\"><table id=\"versions\">\n<thead><tr><th>Version</th><th>Report</th>\
         <th>Status</th><th class=\"num\">Mean error mm<br>nominal → set</th><th>Created</th></tr></thead>\n<tbody>\n",
    );
    for v in versions {
        let mark = if Some(v.version) == current {
            " <strong>(current)</strong>"
        } else {
            ""
        };
        let accuracy = match &v.accuracy {
            Some(a) if a.hand_eye_rms_px.is_some() => {
                format!("hand–eye: {} (no kinematics)", mm(a.after_mean_mm))
            }
            Some(a) => format!("{} → {}", mm(a.before_mean_mm), mm(a.after_mean_mm)),
            None => "—".into(),
        };
        let report = if v.accuracy.is_some() {
            format!(
                "<a href=\"{}\">report v{}</a>",
                report_href(serial, v.version),
                v.version
            )
        } else {
            "<span class=\"muted\">none</span>".into()
        };
        let _ = writeln!(
            t,
            "<tr id=\"v{0}\"><td>v{0}{mark}</td><td>{report}</td><td class=\"status\">{1}</td>\
             <td class=\"num\">{accuracy}</td><td>{2}</td></tr>",
            v.version,
            status_cell(v),
            escape_xml(&ago(&v.created_at, now_ms))
        );
    }
    t.push_str("</tbody></table></div>\n");
    t
}

/// A version's release status, who gave it (and why, on hover).
fn status_cell(v: &SetSummary) -> String {
    let by = match &v.status_by {
        Some(by) => format!(" · by {}", escape_xml(by)),
        None => String::new(),
    };
    format!(
        "<span class=\"release-{0}\" title=\"{1}\">{0}</span>{by}",
        v.status.as_str(),
        escape_xml(v.status_reason.as_deref().unwrap_or(""))
    )
}

fn jobs_table(jobs: &[JobBrief], now_ms: i64) -> String {
    if jobs.is_empty() {
        return "<p class=\"muted\">No jobs yet.</p>\n".into();
    }
    let mut t = String::from(
        "<div class=\"scroll\"><table id=\"jobs\">\n<thead><tr><th>Job</th><th>Kind</th><th>State</th>\
         <th>Stage</th><th class=\"num\">Progress</th><th>Created</th><th>Error</th></tr></thead>\n<tbody>\n",
    );
    for j in jobs {
        // The whole id: what `robocal jobs` prints and `/v1/jobs/{id}` takes.
        let _ = writeln!(
            t,
            "<tr id=\"job-{0}\"><td class=\"id\">{0}</td><td>{1}</td><td class=\"state-{2}\">{2}</td><td>{3}</td>\
             <td class=\"num\">{4:.0}%</td><td>{5}</td><td class=\"error\">{6}</td></tr>",
            escape_xml(&j.id),
            escape_xml(&j.kind),
            j.state.as_str(),
            escape_xml(j.stage.as_deref().unwrap_or("—")),
            j.progress * 100.0,
            escape_xml(&ago(&j.created_at, now_ms)),
            escape_xml(j.error.as_deref().unwrap_or(""))
        );
    }
    t.push_str("</tbody></table></div>\n");
    t
}

/// `GET /robots/{serial}`: its state, versions (with their reports) and jobs.
pub fn robot_page(detail: &RobotDetail, now_ms: i64, logout: bool) -> String {
    let r = &detail.summary;
    let mut body = String::new();
    let _ = write!(
        body,
        "<p><a href=\"/\">← Fleet</a></p>\n<h1>{}</h1>\n<section class=\"card robot\">\n{}</section>\n",
        escape_xml(&r.serial),
        state_list(r, now_ms)
    );
    body.push_str("<h2>Versions</h2>\n");
    body.push_str(&versions_table(
        &r.serial,
        &detail.versions,
        r.current.as_ref().map(|s| s.version),
        now_ms,
    ));
    body.push_str("<h2>Recent jobs</h2>\n");
    body.push_str(&jobs_table(&detail.recent_jobs, now_ms));
    page(&format!("{} · robocal", r.serial), &body, logout)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::domain::{JobState, ReleaseStatus};

    fn robot(serial: &str) -> RobotSummary {
        RobotSummary {
            serial: serial.into(),
            model: "UR<5>".into(),
            controller: None,
            current: Some(SetSummary {
                version: 3,
                created_at: "2026-11-20T10:00:00.000Z".into(),
                job_id: Some("j".into()),
                accuracy: Some(Accuracy {
                    validation_poses: 12,
                    before_mean_mm: 11.36,
                    after_mean_mm: 0.0841,
                    hand_eye_rms_px: None,
                }),
                status: ReleaseStatus::Approved,
                status_by: Some("gate".into()),
                status_reason: Some("better than nominal".into()),
            }),
            last_check: None,
            last_failed: None,
            jobs_in_progress: vec![JobBrief {
                id: "0193-job".into(),
                serial: serial.into(),
                kind: "calibration".into(),
                state: JobState::Running,
                stage: Some("detect".into()),
                progress: 0.42,
                created_at: "2026-11-20T10:00:00.000Z".into(),
                error: None,
            }],
        }
    }

    #[test]
    fn fleet_page_shows_each_robot_with_link_set_accuracy_check_and_jobs() {
        let html = fleet_page(&[robot("R-1"), robot("R-2")], 0, false);
        assert!(html.contains("href=\"/robots/R-1\""));
        assert!(html.contains("v3"));
        assert!(
            html.contains("0.0841 mm mean at 12 validation poses"),
            "{html}"
        );
        assert!(html.contains(NO_CHECKS));
        assert!(html.contains("calibration running — detect 42%"));
        assert!(html.contains("UR&lt;5&gt;"), "model escaped");
        assert!(html.contains("2 robots · 2 jobs in progress"));
        assert!(!html.contains("https://") && !html.contains("<script"));
    }

    #[test]
    fn robot_page_links_its_reports() {
        let detail = RobotDetail {
            versions: robot("R-1").current.into_iter().collect(),
            recent_jobs: robot("R-1").jobs_in_progress,
            summary: robot("R-1"),
        };
        let html = robot_page(&detail, 0, true);
        assert!(html.contains("href=\"/robots/R-1/reports/3\""));
        assert!(html.contains("(current)"));
        assert!(html.contains("action=\"/logout\""));
    }

    #[test]
    fn a_check_on_an_older_set_says_which() {
        use crate::service::fleet::CheckSummary;
        let mut r = robot("R-1");
        r.last_check = Some(CheckSummary {
            verdict: "pass".into(),
            at: "2026-11-20T10:00:00.000Z".into(),
            checked_version: Some(1),
        });
        let html = fleet_page(&[r.clone()], 0, false);
        assert!(
            html.contains(">pass</span> · <span class=\"stale\">on v1, not the current v3</span>"),
            "{html}"
        );
        r.last_check.as_mut().unwrap().checked_version = Some(3);
        let html = fleet_page(&[r], 0, false);
        assert!(html.contains(">pass</span> · on v3 · "), "{html}");
    }
}
