//! The fleet page and a robot's page, rendered from the service's views
//! (`service::fleet`). Every text is escaped; serials are URL-safe by
//! their rule (`Serial`), so they go into links as they are.

use std::fmt::Write;

use super::frame::{ago, old, page};
use crate::report::format::{escape_xml, mm};
use crate::service::fleet::{JobBrief, RobotDetail, RobotSummary, SetSummary, MAX_ROBOTS};

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
            "<span class=\"verdict {0}\">{0}</span> · {1}",
            escape_xml(&c.verdict),
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
            "<section class=\"card robot\" id=\"robot-{0}\">\n<h2><a href=\"{1}\">{0}</a></h2>\n{2}</section>\n",
            escape_xml(&r.serial),
            robot_href(&r.serial),
            state_list(r, now_ms)
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
         <th class=\"num\">Mean error mm<br>nominal → set</th><th>Created</th></tr></thead>\n<tbody>\n",
    );
    for v in versions {
        let mark = if Some(v.version) == current {
            " <strong>(current)</strong>"
        } else {
            ""
        };
        let accuracy = match &v.accuracy {
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
            "<tr><td>v{}{mark}</td><td>{report}</td><td class=\"num\">{accuracy}</td><td>{}</td></tr>",
            v.version,
            escape_xml(&ago(&v.created_at, now_ms))
        );
    }
    t.push_str("</tbody></table></div>\n");
    t
}

fn jobs_table(jobs: &[JobBrief], now_ms: i64) -> String {
    if jobs.is_empty() {
        return "<p class=\"muted\">No jobs yet.</p>\n".into();
    }
    let mut t = String::from(
        "<div class=\"scroll\"><table id=\"jobs\">\n<thead><tr><th>Job</th><th>Kind</th><th>State</th>\
         <th>Stage</th><th class=\"num\">Progress</th><th>Created</th></tr></thead>\n<tbody>\n",
    );
    for j in jobs {
        let _ = writeln!(
            t,
            "<tr><td title=\"{0}\">{1}</td><td>{2}</td><td class=\"state-{3}\">{3}</td><td>{4}</td>\
             <td class=\"num\">{5:.0}%</td><td>{6}</td></tr>",
            escape_xml(&j.id),
            escape_xml(&j.id[j.id.len().saturating_sub(8)..]),
            escape_xml(&j.kind),
            j.state.as_str(),
            escape_xml(j.stage.as_deref().unwrap_or("—")),
            j.progress * 100.0,
            escape_xml(&ago(&j.created_at, now_ms))
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
    use crate::domain::JobState;
    use crate::service::fleet::Accuracy;

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
                }),
            }),
            last_check: None,
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
}
