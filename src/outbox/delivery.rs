//! The delivery loop: claims due outbox rows (any replica may; a claim is a
//! lease, so a killed process's deliveries are taken up again when it
//! expires), sends each on its own task under a bound of
//! [`MAX_IN_FLIGHT`], and records the answer. A receiver that hangs costs
//! one permit for [`DeliveryPolicy::timeout`], never an API request.

use std::net::SocketAddr;
use std::sync::Arc;
use std::time::Duration;

use reqwest::header::CONTENT_TYPE;
use tokio::sync::{watch, Semaphore};
use tokio::task::JoinHandle;

use super::address_guard::AddressGuard;
use super::signature::{sign, DELIVERY_HEADER, EVENT_HEADER, SIGNATURE_HEADER};
use crate::domain::now_unix_ms;
use crate::store::{DynStore, OutboxDelivery};

/// Deliveries in flight at once, per process.
pub const MAX_IN_FLIGHT: usize = 8;
/// Attempts of one event before it is given up (`failed`): with a 2 s
/// base and the one-hour cap, about seven hours of retries.
pub const MAX_ATTEMPTS: i64 = 15;
/// The longest wait between two attempts.
pub const MAX_BACKOFF: Duration = Duration::from_secs(3600);
/// How long a connection to a receiver may take to open.
const CONNECT_TIMEOUT: Duration = Duration::from_secs(5);
/// A claim lasts this many request timeouts, so a slow answer is
/// recorded before another replica may take the event again.
const LEASE_TIMEOUTS: u32 = 2;
/// Longest error text kept with a failed attempt.
const MAX_ERROR_CHARS: usize = 300;

/// How deliveries are paced (from the server configuration).
#[derive(Debug, Clone, Copy)]
pub struct DeliveryPolicy {
    /// How often the outbox is read for due events.
    pub poll: Duration,
    /// Wait before the first retry; doubled after each failed attempt.
    pub retry_base: Duration,
    /// Longest a receiver may take to answer.
    pub timeout: Duration,
}

impl DeliveryPolicy {
    /// Wait after `attempts` failed attempts: `retry_base · 2^(attempts-1)`,
    /// at most [`MAX_BACKOFF`].
    pub fn backoff(&self, attempts: i64) -> Duration {
        let doublings = attempts.clamp(1, 32) as u32 - 1;
        self.retry_base
            .saturating_mul(2u32.saturating_pow(doublings))
            .min(MAX_BACKOFF)
    }
}

/// Starts the loop; it stops at `shutdown` (deliveries in flight are
/// abandoned: their claims expire and they are sent again).
pub fn spawn(
    store: DynStore,
    policy: DeliveryPolicy,
    guard: AddressGuard,
    mut shutdown: watch::Receiver<bool>,
) -> JoinHandle<()> {
    let guard = Arc::new(guard);
    tokio::spawn(async move {
        let permits = Arc::new(Semaphore::new(MAX_IN_FLIGHT));
        let lease = policy.timeout * LEASE_TIMEOUTS;
        while !*shutdown.borrow() {
            let free = permits.available_permits();
            if free > 0 {
                let now = now_unix_ms();
                let until = now + lease.as_millis() as i64;
                match store.claim_deliveries(now, until, free as i64).await {
                    Ok(claimed) => {
                        for d in claimed {
                            let Ok(permit) = permits.clone().acquire_owned().await else {
                                return;
                            };
                            let (store, guard) = (store.clone(), guard.clone());
                            tokio::spawn(async move {
                                deliver(&store, &guard, &policy, d).await;
                                drop(permit);
                            });
                        }
                    }
                    Err(e) => tracing::warn!(error = %e, "claiming webhook deliveries failed"),
                }
            }
            tokio::select! {
                _ = tokio::time::sleep(policy.poll) => {}
                changed = shutdown.changed() => {
                    if changed.is_err() {
                        break;
                    }
                }
            }
        }
    })
}

/// A client that connects to `host` only at `addrs` (checked), follows no
/// redirect, and gives up after the policy's timeouts.
fn pinned_client(
    policy: &DeliveryPolicy,
    host: &str,
    addrs: &[SocketAddr],
) -> reqwest::Result<reqwest::Client> {
    reqwest::Client::builder()
        .timeout(policy.timeout)
        .connect_timeout(CONNECT_TIMEOUT.min(policy.timeout))
        .redirect(reqwest::redirect::Policy::none())
        .resolve_to_addrs(host, addrs)
        .build()
}

/// Resolves and checks the receiver, then POSTs to the checked addresses.
async fn send(
    guard: &AddressGuard,
    policy: &DeliveryPolicy,
    d: &OutboxDelivery,
) -> Result<reqwest::Response, String> {
    let url = reqwest::Url::parse(&d.url).map_err(|e| format!("bad URL: {e}"))?;
    let host = url.host_str().ok_or("the URL names no host")?.to_string();
    let port = url.port_or_known_default().ok_or("the URL names no port")?;
    let addrs = guard.resolve(&host, port).await?;
    let client = pinned_client(policy, &host, &addrs).map_err(|e| e.to_string())?;
    client
        .post(url)
        .header(CONTENT_TYPE, "application/json")
        .header(EVENT_HEADER, &d.event)
        .header(DELIVERY_HEADER, &d.event_id)
        .header(SIGNATURE_HEADER, sign(&d.secret, d.body.as_bytes()))
        .body(d.body.clone())
        .send()
        .await
        .map_err(|e| format!("sending failed: {e}"))
}

/// Sends one event and records the outcome.
async fn deliver(
    store: &DynStore,
    guard: &AddressGuard,
    policy: &DeliveryPolicy,
    d: OutboxDelivery,
) {
    let answer = send(guard, policy, &d).await;
    let error = match answer {
        Ok(r) if r.status().is_success() => {
            if let Err(e) = store.mark_delivered(&d.id).await {
                // It stays claimed until the lease ends, then goes again.
                tracing::warn!(delivery = %d.id, error = %e, "recording a delivery failed");
            }
            return;
        }
        Ok(r) => format!("the receiver answered {}", r.status()),
        Err(e) => e,
    };
    let attempts = d.attempts + 1;
    let retry_at = (attempts < MAX_ATTEMPTS)
        .then(|| now_unix_ms() + policy.backoff(attempts).as_millis() as i64);
    tracing::info!(delivery = %d.id, url = %d.url, attempts, %error, retry = retry_at.is_some(), "webhook delivery failed");
    let error: String = error.chars().take(MAX_ERROR_CHARS).collect();
    if let Err(e) = store.mark_attempt_failed(&d.id, &error, retry_at).await {
        tracing::warn!(delivery = %d.id, error = %e, "recording a failed delivery failed");
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn backoff_doubles_up_to_the_cap() {
        let p = DeliveryPolicy {
            poll: Duration::from_millis(500),
            retry_base: Duration::from_secs(2),
            timeout: Duration::from_secs(10),
        };
        assert_eq!(p.backoff(1), Duration::from_secs(2));
        assert_eq!(p.backoff(2), Duration::from_secs(4));
        assert_eq!(p.backoff(5), Duration::from_secs(32));
        assert_eq!(p.backoff(20), MAX_BACKOFF);
        assert_eq!(p.backoff(i64::MAX), MAX_BACKOFF);
    }
}
