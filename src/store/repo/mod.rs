//! The repository traits of `store/mod.rs`, implemented once for every
//! [`Backend`](super::backend::Backend): each operation's logic (statements,
//! transactions, lease checks, error mapping) lives here, and the backends
//! supply only their dialect (`backend.rs`).

use std::sync::Arc;

use async_trait::async_trait;
use tokio::sync::{watch, Notify};

use super::backend::Backend;
use super::statement::query;
use super::{Store, StoreResult};

mod auth;
mod campaign_plans;
mod detections;
mod fleet;
mod job_success;
mod jobs;
mod release;
mod results;
mod robots;
mod sessions;
mod webhooks;

pub use fleet::{CheckHead, CurrentReport, FleetRow, JobHead, SetHead};
pub use robots::{prior_text, UPSERT_ROBOT};

#[async_trait]
impl<B: Backend> Store for B {
    async fn ping(&self) -> StoreResult<()> {
        query("SELECT 1").execute(self.pool()).await?;
        Ok(())
    }

    fn backend(&self) -> &'static str {
        B::NAME
    }

    async fn reclaim_space(&self) -> StoreResult<()> {
        Backend::reclaim_space(self).await
    }

    fn watch_jobs(&self, wake: Arc<Notify>, shutdown: watch::Receiver<bool>) -> bool {
        self.listen_for_jobs(wake, shutdown)
    }
}

/// The cursor of a full page is its last key; a short page is the last one.
fn page_cursor<T>(items: &[T], limit: i64, key: impl Fn(&T) -> String) -> Option<String> {
    if items.len() as i64 == limit {
        items.last().map(key)
    } else {
        None
    }
}
