//! PostgreSQL backend: the fleet deployment, several robocal replicas on one
//! database. Runtime-checked `sqlx` queries, READ COMMITTED transactions.
//!
//! The repository operations are shared with SQLite (`store/repo/`); this
//! module supplies the PostgreSQL side of [`Backend`]. What keeps replicas
//! correct:
//! - jobs are claimed with `FOR UPDATE SKIP LOCKED` under a lease
//!   (`repo/jobs.rs`, with [`Backend::FOR_UPDATE_SKIP_LOCKED`]);
//! - the queue bound and parameter-set versions serialise on an advisory
//!   lock or a counter row inside the writing transaction
//!   (`serialise_enqueue`, `NEXT_VERSION` below);
//! - an idempotency key is claimed by a unique insert (`repo/auth.rs`);
//! - migrations run under `sqlx`'s migrator, which holds
//!   `pg_advisory_lock` (keyed on the database name) while it checks and
//!   applies them, so replicas starting together do not race;
//! - a trigger `NOTIFY`s `robocal_jobs` when a job becomes claimable, and
//!   [`listen`] wakes this replica's idle workers on it.

use std::str::FromStr;
use std::sync::Arc;
use std::time::Duration;

use async_trait::async_trait;
use sqlx::postgres::{PgConnectOptions, PgPool, PgPoolOptions};
use sqlx::{Postgres, Transaction};
use tokio::sync::{watch, Notify};

use super::backend::Backend;
use super::migrations::{migrator, Embedded};
use super::repo::{prior_text, UPSERT_ROBOT};
use super::statement::{run_statements, Driver};
use super::{StoreError, StoreResult};
use crate::store::RobotRecord;

mod listen;

pub use listen::JOBS_CHANNEL;

/// Migrations compiled into the binary, so a deployed binary needs no files.
const MIGRATIONS: &[Embedded] = &[
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
    (
        3,
        "image detection",
        include_str!("../../../migrations/postgres/0003_image_detection.sql"),
    ),
    (
        4,
        "labels and storage",
        include_str!("../../../migrations/postgres/0004_labels_and_storage.sql"),
    ),
    (
        5,
        "idempotency fingerprint",
        include_str!("../../../migrations/postgres/0005_idempotency_fingerprint.sql"),
    ),
    (
        6,
        "token lifecycle",
        include_str!("../../../migrations/postgres/0006_token_lifecycle.sql"),
    ),
    (
        7,
        "flange pose",
        include_str!("../../../migrations/postgres/0007_flange_pose.sql"),
    ),
    (
        8,
        "campaign plans",
        include_str!("../../../migrations/postgres/0008_campaign_plans.sql"),
    ),
    (
        9,
        "release gate",
        include_str!("../../../migrations/postgres/0009_release_gate.sql"),
    ),
    (
        10,
        "webhooks",
        include_str!("../../../migrations/postgres/0010_webhooks.sql"),
    ),
    (
        12,
        "stage reading",
        include_str!("../../../migrations/postgres/0012_stage_reading.sql"),
    ),
    (
        30,
        "controller identity",
        include_str!("../../../migrations/postgres/0030_controller_identity.sql"),
    ),
    (
        32,
        "idempotency wrote",
        include_str!("../../../migrations/postgres/0032_idempotency_wrote.sql"),
    ),
    (
        40,
        "robot prior",
        include_str!("../../../migrations/postgres/0040_robot_prior.sql"),
    ),
    (
        70,
        "fleet index and blob writer",
        include_str!("../../../migrations/postgres/0070_fleet_index_and_blob_writer.sql"),
    ),
    (
        80,
        "pose group",
        include_str!("../../../migrations/postgres/0080_pose_group.sql"),
    ),
];

/// Connections per replica. Each worker holds at most one while it claims or
/// finishes; HTTP handlers share the rest.
const MAX_CONNECTIONS: u32 = 10;
/// How long a request waits for a free connection before failing.
const ACQUIRE_TIMEOUT: Duration = Duration::from_secs(10);

/// Advisory lock key serialising enqueues (the `--max-queued` bound is a
/// count-then-insert, which READ COMMITTED alone would let replicas overrun).
const ENQUEUE_LOCK: i64 = 0x726f_626f_6361_6c01; // "robocal" + 1

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
        migrator(MIGRATIONS)
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

/// READ COMMITTED transactions; concurrent replicas are kept apart by row
/// locks in the statements and by the two backend-specific writes below.
#[async_trait]
impl Backend for PgStore {
    type Db = Postgres;

    const NAME: &'static str = "postgres";
    const FOR_UPDATE: &'static str = " FOR UPDATE";
    const FOR_UPDATE_SKIP_LOCKED: &'static str = " FOR UPDATE SKIP LOCKED";
    const FOR_KEY_SHARE: &'static str = " FOR KEY SHARE";
    /// The version comes from the serial's counter row, bumped by an upsert:
    /// the row lock it takes makes concurrent writers (any replica) wait for
    /// each other's commit, so versions are 1, 2, 3... with no duplicate, and a
    /// transaction that rolls back takes its bump with it (no gap).
    const NEXT_VERSION: &'static str =
        "INSERT INTO parameter_set_counters (serial, last_version) VALUES ($1, 1)
         ON CONFLICT (serial) DO UPDATE
           SET last_version = parameter_set_counters.last_version + 1
         RETURNING last_version AS version";
    const FORGET_VERSIONS: Option<&'static str> =
        Some("DELETE FROM parameter_set_counters WHERE serial = $1");

    fn pool(&self) -> &PgPool {
        &self.pool
    }

    async fn open_write(&self) -> StoreResult<Transaction<'static, Postgres>> {
        Ok(self.pool.begin().await?)
    }

    async fn serialise_enqueue(tx: &mut Transaction<'static, Postgres>) -> StoreResult<()> {
        sqlx::query("SELECT pg_advisory_xact_lock($1)")
            .bind(ENQUEUE_LOCK)
            .execute(&mut **tx)
            .await?;
        Ok(())
    }

    /// One statement; `xmax = 0` is true only for a freshly inserted row,
    /// so two replicas creating the same serial at once answer 201 once.
    async fn upsert_robot(&self, r: &RobotRecord) -> StoreResult<bool> {
        let inserted: bool = sqlx::query_scalar(&format!("{UPSERT_ROBOT} RETURNING (xmax = 0)"))
            .bind(&r.serial)
            .bind(&r.model)
            .bind(&r.preset)
            .bind(r.kinematics.to_string())
            .bind(&r.created_at)
            .bind(&r.updated_at)
            .bind(prior_text(r)?)
            .fetch_one(&self.pool)
            .await?;
        Ok(inserted)
    }

    fn listen_for_jobs(&self, wake: Arc<Notify>, shutdown: watch::Receiver<bool>) -> bool {
        listen::spawn(self.pool.clone(), wake, shutdown);
        true
    }
}

impl Driver for Postgres {
    run_statements!();
}
