//! Revocation reaches open event streams: one task per process reads the
//! tokens every [`POLL`] (so a revocation made on another replica counts
//! too) and publishes them; a stream opened with a token ends within a
//! second once that token is revoked or expires.

use std::sync::Arc;
use std::time::Duration;

use tokio::sync::watch;
use tokio::task::JoinHandle;

use crate::domain::{now_unix_ms, TokenRecord};
use crate::store::DynStore;

/// How often the tokens are read; a stream ends at most this long (plus
/// [`RECHECK`]) after its token stops being usable.
const POLL: Duration = Duration::from_millis(500);
/// How often a stream looks again without news (for expiry).
const RECHECK: Duration = Duration::from_millis(500);

/// The tokens as last read; `None` until the first read.
pub type Tokens = watch::Receiver<Option<Arc<Vec<TokenRecord>>>>;

/// Starts the reader; it stops with `shutdown`.
pub fn spawn(store: DynStore, mut shutdown: watch::Receiver<bool>) -> (Tokens, JoinHandle<()>) {
    let (tx, rx) = watch::channel(None);
    let task = tokio::spawn(async move {
        loop {
            match store.list_tokens().await {
                Ok(tokens) => {
                    tx.send_if_modified(|seen| {
                        let changed = seen.as_deref() != Some(&tokens);
                        if changed {
                            *seen = Some(Arc::new(tokens));
                        }
                        changed
                    });
                }
                Err(e) => tracing::debug!(error = %e, "reading tokens for open streams failed"),
            }
            tokio::select! {
                _ = tokio::time::sleep(POLL) => {}
                _ = shutdown.wait_for(|stop| *stop) => return,
            }
        }
    });
    (rx, task)
}

/// Resolves once token `id` is revoked or expired. A token the last read
/// did not see yet (created since) counts as usable: tokens are never
/// deleted, only revoked.
pub async fn unusable(mut tokens: Tokens, id: String) {
    loop {
        let usable = match tokens.borrow_and_update().as_deref() {
            None => true,
            Some(all) => all
                .iter()
                .find(|t| t.id == id)
                .is_none_or(|t| t.check_usable(now_unix_ms()).is_ok()),
        };
        if !usable {
            return;
        }
        tokio::select! {
            changed = tokens.changed() => {
                if changed.is_err() {
                    // The reader stopped (shutdown): streams end with the server.
                    return;
                }
            }
            _ = tokio::time::sleep(RECHECK) => {}
        }
    }
}
