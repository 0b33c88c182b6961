//! Prompt pickup across replicas: `LISTEN robocal_jobs` on a dedicated
//! connection; every notification (sent by the `jobs_claimable` trigger on
//! commit) wakes one idle worker of this replica. The workers' idle poll stays
//! on as the fallback: it covers lease expiry (no event) and the moments the
//! listener is reconnecting.

use std::sync::Arc;
use std::time::Duration;

use sqlx::postgres::{PgListener, PgPool};
use tokio::sync::{watch, Notify};

/// The channel the `jobs_claimable` trigger notifies (migrations/postgres).
pub const JOBS_CHANNEL: &str = "robocal_jobs";

/// Wait before trying again when the listener cannot connect.
const RETRY: Duration = Duration::from_secs(2);

/// Runs the listener until `shutdown` turns true (or its sender is dropped).
pub fn spawn(pool: PgPool, wake: Arc<Notify>, mut shutdown: watch::Receiver<bool>) {
    tokio::spawn(async move {
        loop {
            tokio::select! {
                _ = listen(&pool, &wake) => {}
                changed = shutdown.changed() => {
                    if changed.is_err() || *shutdown.borrow() {
                        break;
                    }
                    continue;
                }
            }
            // The listener failed: workers poll meanwhile; try again shortly.
            tokio::select! {
                _ = tokio::time::sleep(RETRY) => {}
                changed = shutdown.changed() => {
                    if changed.is_err() || *shutdown.borrow() {
                        break;
                    }
                }
            }
        }
        tracing::debug!("job listener stopped");
    });
}

/// Listens until the connection fails for good; returns after logging why.
async fn listen(pool: &PgPool, wake: &Notify) {
    let mut listener = match PgListener::connect_with(pool).await {
        Ok(l) => l,
        Err(e) => {
            tracing::warn!(error = %e, "job listener cannot connect; workers poll");
            return;
        }
    };
    if let Err(e) = listener.listen(JOBS_CHANNEL).await {
        tracing::warn!(error = %e, "LISTEN failed; workers poll");
        return;
    }
    tracing::debug!(channel = JOBS_CHANNEL, "listening for claimable jobs");
    loop {
        match listener.try_recv().await {
            Ok(Some(_notification)) => wake.notify_one(),
            // The connection was lost and has been re-established: anything
            // sent meanwhile was missed, so let a worker look now.
            Ok(None) => {
                tracing::info!("job listener reconnected");
                wake.notify_one();
            }
            Err(e) => {
                tracing::warn!(error = %e, "job listener failed; workers poll");
                return;
            }
        }
    }
}
