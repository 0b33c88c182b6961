//! The accuracy the fleet pages show per parameter set, read once from
//! the set's report and kept: a report never changes once stored (the
//! release status the pages show is read from the set itself), so a
//! summary keyed by the set's identity (serial, version, creation time:
//! a re-created robot's version 1 is another set) stays true. Without it
//! every view of the fleet page parsed every robot's report.

use std::collections::HashMap;
use std::sync::Mutex;

use serde::Deserialize;

use crate::report::AccuracySummary;

/// Summaries kept before the cache starts over (a few hundred bytes each).
const MAX_ENTRIES: usize = 20_000;

/// What the pages show of a set's validation.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Accuracy {
    pub validation_poses: usize,
    pub before_mean_mm: f64,
    pub after_mean_mm: f64,
    /// A hand–eye set's reprojection RMS (px): such a set identified no
    /// kinematics, so its before and after are the same model and the
    /// pages show what it measured instead.
    pub hand_eye_rms_px: Option<f64>,
}

/// The report's validation statistics, read without the rest of it.
#[derive(Deserialize)]
struct ReportAccuracy {
    before: AccuracySummary,
    after: AccuracySummary,
    #[serde(default)]
    hand_eye: Option<HandEyeFit>,
}

/// The part of a report's hand–eye section the pages show.
#[derive(Deserialize)]
struct HandEyeFit {
    reprojection_rms_px: f64,
}

/// The key of a report's validation figures after calibration.
const AFTER_KEY: &str = "after";

/// The accuracy of a report given as text (`None`: no validation in it,
/// e.g. a test marker; an error when its figures do not read).
pub fn accuracy_of(report: &str) -> Result<Option<Accuracy>, serde_json::Error> {
    accuracy_of_value(serde_json::from_str(report)?)
}

/// The accuracy of a report given as a JSON value (as [`accuracy_of`]).
pub fn accuracy_of_value(report: serde_json::Value) -> Result<Option<Accuracy>, serde_json::Error> {
    if report.get(AFTER_KEY).is_none() {
        return Ok(None);
    }
    Ok(Some(Accuracy::from(serde_json::from_value::<
        ReportAccuracy,
    >(report)?)))
}

impl From<ReportAccuracy> for Accuracy {
    fn from(r: ReportAccuracy) -> Accuracy {
        Accuracy {
            validation_poses: r.after.norm.n,
            before_mean_mm: r.before.norm.mean_mm,
            after_mean_mm: r.after.norm.mean_mm,
            hand_eye_rms_px: r.hand_eye.map(|h| h.reprojection_rms_px),
        }
    }
}

/// A set's identity as the cache keys it.
pub type SetKey = (String, i64, String);

/// Accuracy summaries by set identity, shared by every request.
#[derive(Debug, Default)]
pub struct SummaryCache {
    entries: Mutex<HashMap<SetKey, Option<Accuracy>>>,
}

impl SummaryCache {
    pub fn new() -> SummaryCache {
        SummaryCache::default()
    }

    /// The summary of set `key`, when known (`Some(None)`: known to have
    /// no validation).
    pub fn get(&self, key: &SetKey) -> Option<Option<Accuracy>> {
        self.lock().get(key).copied()
    }

    pub fn put(&self, key: SetKey, accuracy: Option<Accuracy>) {
        let mut entries = self.lock();
        if entries.len() >= MAX_ENTRIES {
            entries.clear();
        }
        entries.insert(key, accuracy);
    }

    fn lock(&self) -> std::sync::MutexGuard<'_, HashMap<SetKey, Option<Accuracy>>> {
        self.entries.lock().unwrap_or_else(|e| e.into_inner())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_set_s_summary_is_kept_under_its_identity() {
        let cache = SummaryCache::new();
        let key = ("R1".to_string(), 1, "2026-01-01T00:00:00.000Z".to_string());
        assert_eq!(cache.get(&key), None);
        cache.put(key.clone(), None);
        assert_eq!(cache.get(&key), Some(None));
        let recreated = ("R1".to_string(), 1, "2026-01-02T00:00:00.000Z".to_string());
        assert_eq!(
            cache.get(&recreated),
            None,
            "a re-created robot's v1 is another set"
        );
    }
}
