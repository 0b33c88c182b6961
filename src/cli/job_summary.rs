//! What `robocal calibrate --wait` prints when the job succeeded: the set
//! it stored, its release status and why, the accuracy, and how to see the
//! report, instead of the whole job document (`GET /v1/jobs/{id}` has it).

use serde::Deserialize;

/// The finished job's fields a summary shows.
#[derive(Debug, Default, Deserialize)]
struct FinishedJob {
    #[serde(default)]
    result: FinishedResult,
}

#[derive(Debug, Default, Deserialize)]
struct FinishedResult {
    serial: Option<String>,
    version: Option<i64>,
    status: Option<String>,
    status_reason: Option<String>,
    #[serde(default)]
    summary: FinishedSummary,
}

#[derive(Debug, Default, Deserialize)]
struct FinishedSummary {
    #[serde(default)]
    calibration_poses: usize,
    #[serde(default)]
    validation_poses: usize,
    before_mean_mm: Option<f64>,
    after_mean_mm: Option<f64>,
    outliers: Option<usize>,
}

/// What `calibrate --wait` prints at the end: the set it stored, its
/// release status and why, the accuracy, and how to see the report (the
/// whole job document is `GET /v1/jobs/{id}`).
pub fn summary_of(job_id: &str, job: &str) -> String {
    let done: FinishedJob = serde_json::from_str(job).unwrap_or_default();
    let r = &done.result;
    let mm = |v: Option<f64>| v.map_or_else(|| "n/a".to_string(), crate::report::format::mm);
    let mut out = format!("job {job_id} succeeded");
    if let (Some(serial), Some(version)) = (&r.serial, r.version) {
        out.push_str(&format!(
            ": {serial} parameter set v{version}, {}",
            r.status.as_deref().unwrap_or("stored")
        ));
        if let Some(why) = &r.status_reason {
            out.push_str(&format!(" ({why})"));
        }
    }
    let s = &r.summary;
    out.push_str(&format!(
        "\n  mean 3-D error at {} validation poses: {} mm before, {} mm after ({} calibration poses",
        s.validation_poses,
        mm(s.before_mean_mm),
        mm(s.after_mean_mm),
        s.calibration_poses
    ));
    if let Some(n) = s.outliers.filter(|n| *n > 0) {
        out.push_str(&format!(", {n} left out as outliers"));
    }
    out.push(')');
    if let (Some(serial), Some(version)) = (&r.serial, r.version) {
        out.push_str(&format!(
            "\n  report: robocal report --serial {serial} --version {version}"
        ));
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_finished_calibration_prints_a_summary_not_the_job_document() {
        let job = r#"{"id": "j-1", "state": "succeeded", "result": {"serial": "IRB-001",
            "version": 2, "status": "candidate", "status_reason": "worse than IRB-001/1",
            "summary": {"calibration_poses": 24, "validation_poses": 8,
            "before_mean_mm": 10.512, "after_mean_mm": 0.0934}}, "options": {"a": 1}}"#;
        let text = summary_of("j-1", job);
        assert_eq!(
            text,
            "job j-1 succeeded: IRB-001 parameter set v2, candidate (worse than IRB-001/1)\n  \
             mean 3-D error at 8 validation poses: 10.5 mm before, 0.0934 mm after (24 calibration poses)\n  \
             report: robocal report --serial IRB-001 --version 2"
        );
    }
}
