//! What the shared repository code (`repo/`) needs from a database backend:
//! a pool, a way to open a writing transaction, and the few places where
//! the SQLite and PostgreSQL dialects (or their concurrency models) differ.
//! Each repository operation is written once, in `repo/`, over [`Backend`];
//! `sqlite/` and `postgres/` only implement it.
//!
//! Why the differences are this few: statements use `$n` placeholders,
//! which both drivers read (see `statement.rs`), and only portable SQL
//! (`RETURNING`, `ON CONFLICT`, `CAST`, `CASE`). What remains is row locking
//! (PostgreSQL replicas lock rows; SQLite's `BEGIN IMMEDIATE` already
//! excludes every other writer) and the writes whose race-freedom needs
//! backend-specific SQL.

use std::sync::Arc;

use async_trait::async_trait;
use sqlx::{Pool, Transaction};
use tokio::sync::{watch, Notify};

use super::statement::Driver;
use super::StoreResult;
use crate::store::RobotRecord;

#[async_trait]
pub trait Backend: Send + Sync + 'static {
    type Db: Driver;

    /// Backend name for logs ("sqlite", "postgres").
    const NAME: &'static str;
    /// Row-lock clause for a row this transaction will update.
    const FOR_UPDATE: &'static str;
    /// Row-lock clause that skips rows another transaction holds (a claim
    /// never waits for, nor takes, a job another replica is claiming).
    const FOR_UPDATE_SKIP_LOCKED: &'static str;
    /// Row-lock clause that keeps a parent row from being deleted meanwhile.
    const FOR_KEY_SHARE: &'static str;
    /// Takes the serial's next parameter-set version (`$1` = serial) inside
    /// the writing transaction; returns it as column `version`.
    const NEXT_VERSION: &'static str;
    /// Forgets the serial's version counter (`$1` = serial) when its robot
    /// is deleted, so a robot re-created under the serial starts again at
    /// version 1; `None` where versions are counted from the sets themselves.
    const FORGET_VERSIONS: Option<&'static str> = None;

    fn pool(&self) -> &Pool<Self::Db>;

    /// Opens a transaction that is going to write (backend-specific).
    async fn open_write(&self) -> StoreResult<Transaction<'static, Self::Db>>;

    /// Opens a transaction that is going to write; inside a keyed request
    /// it marks the request's `Idempotency-Key` as written ([`super::write_guard`]).
    async fn begin_write(&self) -> StoreResult<Transaction<'static, Self::Db>> {
        let mut tx = self.open_write().await?;
        super::write_guard::mark(&mut tx).await?;
        Ok(tx)
    }

    /// Serialises enqueues (the `--max-queued` bound is a count, then an
    /// insert) inside the enqueue's transaction. Nothing to do where the
    /// writing transaction excludes other writers already.
    async fn serialise_enqueue(_tx: &mut Transaction<'static, Self::Db>) -> StoreResult<()> {
        Ok(())
    }

    /// Creates or replaces the robot; `true` when it was created, answered
    /// once even when two processes create the same serial at once.
    async fn upsert_robot(&self, robot: &RobotRecord) -> StoreResult<bool>;

    /// See [`Store::reclaim_space`](super::Store::reclaim_space); nothing
    /// where the database reuses freed space by itself.
    async fn reclaim_space(&self) -> StoreResult<()> {
        Ok(())
    }

    /// See [`Store::watch_jobs`](super::Store::watch_jobs).
    fn listen_for_jobs(&self, _wake: Arc<Notify>, _shutdown: watch::Receiver<bool>) -> bool {
        false
    }
}

/// True when `e` is a foreign-key violation (a parent row deleted
/// concurrently, or never there).
pub fn is_foreign_key_violation(e: &sqlx::Error) -> bool {
    e.as_database_error()
        .is_some_and(|d| d.is_foreign_key_violation())
}
