//! PostgreSQL backend: the fleet deployment, several robocal replicas on one
//! database. Runtime-checked `sqlx` queries, READ COMMITTED transactions.
//!
//! What keeps replicas correct (see each file):
//! - jobs are claimed with `FOR UPDATE SKIP LOCKED` under a lease (`jobs.rs`);
//! - the queue bound and parameter-set versions serialise on a row or an
//!   advisory lock inside the writing transaction (`jobs.rs`, `results.rs`);
//! - an idempotency key is claimed by a unique insert (`auth.rs`);
//! - migrations run under `sqlx`'s migrator, which holds
//!   `pg_advisory_lock` (keyed on the database name) while it checks and
//!   applies them, so replicas starting together do not race;
//! - a trigger `NOTIFY`s `robocal_jobs` when a job becomes claimable, and
//!   [`listen`] wakes this replica's idle workers on it.

use crate::store::rows::json;
use std::borrow::Cow;
use std::str::FromStr;
use std::sync::Arc;
use std::time::Duration;

use async_trait::async_trait;
use sqlx::migrate::{Migration, MigrationType, Migrator};
use sqlx::postgres::{PgConnectOptions, PgPool, PgPoolOptions};
use tokio::sync::{watch, Notify};

use super::{Store, StoreError, StoreResult};

mod auth;
mod jobs;
mod listen;
mod results;
mod robots;
mod sessions;

pub use listen::JOBS_CHANNEL;

/// Migrations compiled into the binary, so a deployed binary needs no files.
const MIGRATIONS: &[(i64, &str, &str)] = &[
    (
        1,
        "init",
        include_str!("../../../migrations/postgres/0001_init.sql"),
    ),
    (
        2,
        "pose detection",
        include_str!("../../../migrations/postgres/0002_pose_detection.sql"),
    ),
];

/// Connections per replica. Each worker holds at most one while it claims or
/// finishes; HTTP handlers share the rest.
const MAX_CONNECTIONS: u32 = 10;
/// How long a request waits for a free connection before failing.
const ACQUIRE_TIMEOUT: Duration = Duration::from_secs(10);

/// SQLSTATE of a foreign-key violation (the parent row vanished).
const FOREIGN_KEY_VIOLATION: &str = "23503";

pub struct PgStore {
    pool: PgPool,
}

impl PgStore {
    pub async fn connect(url: &str) -> StoreResult<Self> {
        let options = PgConnectOptions::from_str(url)?.application_name("robocal");
        let pool = PgPoolOptions::new()
            .max_connections(MAX_CONNECTIONS)
            .acquire_timeout(ACQUIRE_TIMEOUT)
            .connect_with(options)
            .await?;
        // `Migrator::run` takes `pg_advisory_lock` before it creates its table
        // and releases it after the last migration (sqlx 0.8, `locking` on by
        // default): concurrent starts wait for each other.
        migrator()
            .run(&pool)
            .await
            .map_err(|e| StoreError::Backend(format!("migrations failed: {e}")))?;
        Ok(PgStore { pool })
    }

    /// The connection pool (tests and benchmarks inspect the database through it).
    pub fn pool(&self) -> &PgPool {
        &self.pool
    }
}

fn migrator() -> Migrator {
    let migrations: Vec<Migration> = MIGRATIONS
        .iter()
        .map(|(version, name, sql)| {
            Migration::new(
                *version,
                Cow::Borrowed(*name),
                MigrationType::Simple,
                Cow::Borrowed(*sql),
                false,
            )
        })
        .collect();
    Migrator {
        migrations: Cow::Owned(migrations),
        ..Migrator::DEFAULT
    }
}

/// True when `e` is a foreign-key violation (a parent deleted concurrently).
fn is_foreign_key_violation(e: &sqlx::Error) -> bool {
    e.as_database_error()
        .and_then(|d| d.code())
        .is_some_and(|c| c == FOREIGN_KEY_VIOLATION)
}

#[async_trait]
impl Store for PgStore {
    async fn ping(&self) -> StoreResult<()> {
        sqlx::query("SELECT 1").execute(&self.pool).await?;
        Ok(())
    }

    fn backend(&self) -> &'static str {
        "postgres"
    }

    fn watch_jobs(&self, wake: Arc<Notify>, shutdown: watch::Receiver<bool>) -> bool {
        listen::spawn(self.pool.clone(), wake, shutdown);
        true
    }
}
