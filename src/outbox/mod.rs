//! Webhook delivery from the durable outbox (`webhook_outbox`): a loop per
//! process claims due events under a lease, POSTs each, signed
//! (`signature.rs`), with a bounded timeout and at most
//! [`delivery::MAX_IN_FLIGHT`] at once, off every request's path; a 2xx
//! marks it delivered, anything else schedules a retry with exponential
//! backoff. Events are written by `service::events::record` or inside the
//! store transaction of the change they report. Receivers' addresses are
//! checked at every attempt (`address_guard.rs`).

pub mod address_guard;
pub mod delivery;
pub mod signature;
