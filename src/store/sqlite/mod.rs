//! SQLite backend (the default, single-node deployment): the SQLite side of
//! [`Backend`]; the repository operations are shared (`store/repo/`).
//! Runtime-checked `sqlx` queries; WAL journal with `synchronous = FULL`, so
//! a write is on disk when the call returns. Writers that read before they
//! write open their transaction with `BEGIN IMMEDIATE` so two writers never
//! deadlock on a lock upgrade.

use std::str::FromStr;
use std::time::Duration;

use async_trait::async_trait;
use sqlx::sqlite::{
    SqliteAutoVacuum, SqliteConnectOptions, SqliteJournalMode, SqlitePool, SqlitePoolOptions,
    SqliteSynchronous,
};
use sqlx::{Sqlite, Transaction};

use super::backend::Backend;
use super::migrations::{migrator, Embedded};
use super::repo::{prior_text, UPSERT_ROBOT};
use super::statement::query;
use super::statement::{run_statements, Driver};
use super::{StoreError, StoreResult};
use crate::store::RobotRecord;

/// Migrations compiled into the binary, so a deployed binary needs no files.
const MIGRATIONS: &[Embedded] = &[
    (
        1,
        "init",
        include_str!("../../../migrations/sqlite/0001_init.sql"),
    ),
    (
        2,
        "pose detection",
        include_str!("../../../migrations/sqlite/0002_pose_detection.sql"),
    ),
    (
        3,
        "image detection",
        include_str!("../../../migrations/sqlite/0003_image_detection.sql"),
    ),
    (
        4,
        "labels and storage",
        include_str!("../../../migrations/sqlite/0004_labels_and_storage.sql"),
    ),
    (
        5,
        "idempotency fingerprint",
        include_str!("../../../migrations/sqlite/0005_idempotency_fingerprint.sql"),
    ),
    (
        6,
        "token lifecycle",
        include_str!("../../../migrations/sqlite/0006_token_lifecycle.sql"),
    ),
    (
        7,
        "flange pose",
        include_str!("../../../migrations/sqlite/0007_flange_pose.sql"),
    ),
    (
        8,
        "campaign plans",
        include_str!("../../../migrations/sqlite/0008_campaign_plans.sql"),
    ),
    (
        9,
        "release gate",
        include_str!("../../../migrations/sqlite/0009_release_gate.sql"),
    ),
    (
        10,
        "webhooks",
        include_str!("../../../migrations/sqlite/0010_webhooks.sql"),
    ),
    (
        12,
        "stage reading",
        include_str!("../../../migrations/sqlite/0012_stage_reading.sql"),
    ),
    (
        30,
        "controller identity",
        include_str!("../../../migrations/sqlite/0030_controller_identity.sql"),
    ),
    (
        32,
        "idempotency wrote",
        include_str!("../../../migrations/sqlite/0032_idempotency_wrote.sql"),
    ),
    (
        40,
        "robot prior",
        include_str!("../../../migrations/sqlite/0040_robot_prior.sql"),
    ),
    (
        70,
        "fleet index and blob writer",
        include_str!("../../../migrations/sqlite/0070_fleet_index_and_blob_writer.sql"),
    ),
    (
        80,
        "pose group",
        include_str!("../../../migrations/sqlite/0080_pose_group.sql"),
    ),
];

/// How long a statement waits for a competing writer before giving up.
const BUSY_TIMEOUT: Duration = Duration::from_secs(10);
/// Migration attempts after a lost race with another starting process.
const MIGRATION_RETRIES: u32 = 5;
const MIGRATION_RETRY_WAIT: Duration = Duration::from_millis(200);
/// Connections in the pool (SQLite serialises writers anyway).
const MAX_CONNECTIONS: u32 = 8;

pub struct SqliteStore {
    pool: SqlitePool,
}

impl SqliteStore {
    pub async fn connect(url: &str) -> StoreResult<Self> {
        let options = SqliteConnectOptions::from_str(url)?
            .create_if_missing(true)
            .journal_mode(SqliteJournalMode::Wal)
            .synchronous(SqliteSynchronous::Full)
            .foreign_keys(true)
            .auto_vacuum(SqliteAutoVacuum::Incremental)
            .busy_timeout(BUSY_TIMEOUT);
        // Switching a new file to WAL takes an exclusive lock that does not
        // wait on `busy_timeout`: processes opening one new file at the same
        // moment retry instead of failing with "database is locked".
        let mut attempt = 0;
        let pool = loop {
            match SqlitePoolOptions::new()
                .max_connections(MAX_CONNECTIONS)
                .connect_with(options.clone())
                .await
            {
                Ok(pool) => break pool,
                Err(e) if attempt < MIGRATION_RETRIES => {
                    tracing::debug!(error = %e, "opening the database raced another process; retrying");
                    attempt += 1;
                    tokio::time::sleep(MIGRATION_RETRY_WAIT).await;
                }
                Err(e) => return Err(e.into()),
            }
        };
        let migrator = migrator(MIGRATIONS);
        // sqlx takes no lock on SQLite: a second process starting at the same
        // moment can lose the race to apply a migration ("table ... already
        // exists"). Its retry then finds the migration applied and goes on.
        let mut attempt = 0;
        loop {
            match migrator.run(&pool).await {
                Ok(()) => break,
                Err(e) if attempt < MIGRATION_RETRIES => {
                    tracing::debug!(error = %e, "migration raced another process; retrying");
                    attempt += 1;
                    tokio::time::sleep(MIGRATION_RETRY_WAIT).await;
                }
                Err(e) => return Err(StoreError::Backend(format!("migrations failed: {e}"))),
            }
        }
        incremental_vacuum_on(&pool).await;
        Ok(SqliteStore { pool })
    }
}

/// `PRAGMA auto_vacuum` value of incremental vacuum.
const AUTO_VACUUM_INCREMENTAL: i64 = 2;

/// Turns incremental vacuum on for a file made without it: one `VACUUM`
/// rewrites it (new files have it from their first connection). A failure
/// (another process holds the file) is logged; the next start retries.
async fn incremental_vacuum_on(pool: &SqlitePool) {
    let mode: Result<i64, _> = sqlx::query_scalar("PRAGMA auto_vacuum")
        .fetch_one(pool)
        .await;
    if matches!(mode, Ok(AUTO_VACUUM_INCREMENTAL)) {
        return;
    }
    tracing::info!("turning on incremental vacuum (one VACUUM of the database file)");
    let mut conn = match pool.acquire().await {
        Ok(conn) => conn,
        Err(e) => return tracing::warn!(error = %e, "cannot turn on incremental vacuum"),
    };
    for step in ["PRAGMA auto_vacuum = INCREMENTAL", "VACUUM"] {
        if let Err(e) = sqlx::query(step).execute(&mut *conn).await {
            return tracing::warn!(error = %e, "cannot turn on incremental vacuum");
        }
    }
}

/// SQLite serialises writers: a writing transaction holds the database
/// write lock from `BEGIN IMMEDIATE` to its end, so no row locks are needed
/// and a read-then-write inside it (the next version, the robot's existence)
/// cannot race another writer.
#[async_trait]
impl Backend for SqliteStore {
    type Db = Sqlite;

    const NAME: &'static str = "sqlite";
    const FOR_UPDATE: &'static str = "";
    const FOR_UPDATE_SKIP_LOCKED: &'static str = "";
    const FOR_KEY_SHARE: &'static str = "";
    const NEXT_VERSION: &'static str =
        "SELECT coalesce(max(version), 0) + 1 AS version FROM parameter_sets WHERE serial = $1";

    fn pool(&self) -> &SqlitePool {
        &self.pool
    }

    /// Frees the file's unused pages, then checkpoints the WAL so the
    /// database file itself is truncated (a passive checkpoint: it never
    /// waits for readers; one they hold back is finished by a later one).
    async fn reclaim_space(&self) -> StoreResult<()> {
        let mut conn = self.pool.acquire().await?;
        sqlx::query("PRAGMA incremental_vacuum")
            .execute(&mut *conn)
            .await?;
        sqlx::query("PRAGMA wal_checkpoint(PASSIVE)")
            .execute(&mut *conn)
            .await?;
        Ok(())
    }

    /// `BEGIN IMMEDIATE`: takes the write lock up front, so two writers that
    /// read before they write never deadlock on a lock upgrade.
    async fn open_write(&self) -> StoreResult<Transaction<'static, Sqlite>> {
        Ok(self.pool.begin_with("BEGIN IMMEDIATE").await?)
    }

    async fn upsert_robot(&self, r: &RobotRecord) -> StoreResult<bool> {
        let mut tx = self.begin_write().await?;
        let existed = query("SELECT 1 FROM robots WHERE serial = $1")
            .bind(&r.serial)
            .fetch_optional(&mut tx)
            .await?;
        query(UPSERT_ROBOT)
            .bind(&r.serial)
            .bind(&r.model)
            .bind(r.preset.as_deref())
            .bind(r.kinematics.to_string())
            .bind(&r.created_at)
            .bind(&r.updated_at)
            .bind(prior_text(r)?)
            .execute(&mut tx)
            .await?;
        tx.commit().await?;
        Ok(existed.is_none())
    }
}

impl Driver for Sqlite {
    run_statements!();
}
