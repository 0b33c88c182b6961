//! What the service tells the outside world (issue 17): the events a
//! webhook subscribes to, one typed enum. Each event is written to the
//! durable outbox (`webhook_outbox`) in the same transaction as the state
//! change it reports, or before it, and delivered from there at least once
//! (`src/outbox/`). Record one with `service::events::record`, or inside a
//! store transaction with `record_event_tx` (`store/repo/webhooks.rs`).

use serde::Serialize;

use super::JobState;

/// One thing that happened. Its serde form (`{"type", "data"}`) is the
/// webhook body's `type` and `data`.
#[derive(Debug, Clone, PartialEq, Serialize)]
#[serde(tag = "type", content = "data")]
pub enum DomainEvent {
    /// A job ended: succeeded, failed for good, or was cancelled.
    #[serde(rename = "job.finished")]
    JobFinished {
        job_id: String,
        kind: String,
        serial: String,
        session_id: String,
        state: JobState,
        /// The parameter set the job stored, if any.
        #[serde(skip_serializing_if = "Option::is_none")]
        version: Option<i64>,
        #[serde(skip_serializing_if = "Option::is_none")]
        error: Option<String>,
    },
    /// A quick re-check of a robot was judged (`pass`, `drift`, `base_moved`).
    #[serde(rename = "check.finished")]
    CheckFinished {
        job_id: String,
        serial: String,
        verdict: String,
        /// The approved set the check was judged against.
        version: i64,
    },
    /// A parameter set was approved (by the gate or by a person).
    #[serde(rename = "set.approved")]
    SetApproved {
        serial: String,
        version: i64,
        /// Who approved it: a token id, or `"gate"` for the automatic gate.
        approved_by: String,
    },
}

impl DomainEvent {
    /// Every event name a webhook may subscribe to.
    pub const NAMES: [&'static str; 3] = ["job.finished", "check.finished", "set.approved"];

    /// The event's name (`type` in the body, `X-Robocal-Event` header).
    pub fn name(&self) -> &'static str {
        match self {
            DomainEvent::JobFinished { .. } => Self::NAMES[0],
            DomainEvent::CheckFinished { .. } => Self::NAMES[1],
            DomainEvent::SetApproved { .. } => Self::NAMES[2],
        }
    }

    /// True for a name in [`Self::NAMES`].
    pub fn is_name(name: &str) -> bool {
        Self::NAMES.contains(&name)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn serde_type_is_the_name() {
        let events = [
            DomainEvent::JobFinished {
                job_id: "j".into(),
                kind: "calibration".into(),
                serial: "S".into(),
                session_id: "s".into(),
                state: JobState::Succeeded,
                version: Some(2),
                error: None,
            },
            DomainEvent::CheckFinished {
                job_id: "j".into(),
                serial: "S".into(),
                verdict: "pass".into(),
                version: 1,
            },
            DomainEvent::SetApproved {
                serial: "S".into(),
                version: 3,
                approved_by: "gate".into(),
            },
        ];
        for e in events {
            let v = serde_json::to_value(&e).unwrap();
            assert_eq!(v["type"], e.name());
            assert!(DomainEvent::is_name(e.name()));
            assert!(v["data"]["serial"] == "S", "{v}");
        }
        assert!(!DomainEvent::is_name("job.started"));
    }
}
