//! The one entry point that tells the outside world something happened
//! (issue 17's webhooks): [`record`] writes a [`DomainEvent`] to the durable
//! outbox of every subscribed webhook; `src/outbox/` delivers it at least
//! once. Call it *before* committing the change it reports (a crash in
//! between then sends an event for a change that did not happen, never
//! loses one), or record inside the change's own store transaction with
//! `record_event_tx` in `store/repo/webhooks.rs` (what `finish_job` does for `job.finished`).
//!
//! ```ignore
//! events::record(&store, DomainEvent::SetApproved { serial, version, approved_by }).await?;
//! ```
//!
//! The delivery loop finds a recorded event at its next poll (`--poll-ms`).

use super::error::ServiceResult;
use crate::domain::now_unix_ms;
pub use crate::domain::DomainEvent;
use crate::store::DynStore;

/// Writes `event` to the outbox (durable on return).
pub async fn record(store: &DynStore, event: DomainEvent) -> ServiceResult<()> {
    store.record_event(&event, now_unix_ms()).await?;
    Ok(())
}
