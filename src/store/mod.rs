//! Storage: one repository trait object, [`Store`], used by the HTTP handlers
//! and the job workers. Every SQL statement lives under `store/`, so adding a
//! backend touches nothing outside `store/` and `migrations/<backend>/`.
//!
//! The trait is split by area ([`RobotStore`], [`SessionStore`], [`JobStore`],
//! [`ResultStore`], [`AuthStore`]); each area is implemented once, in
//! `repo/<area>.rs`, for every backend (`backend::Backend`: `sqlite/`,
//! `postgres/`), which supplies only its dialect. [`Store`] is their sum and
//! is what the rest of the program holds (`Arc<dyn Store>`).

use std::sync::Arc;

use async_trait::async_trait;
use serde_json::Value;
use tokio::sync::{watch, Notify};

use crate::domain::*;
use crate::schema::session::SessionBody;

mod backend;
mod migrations;
pub mod postgres;
mod records;
mod repo;
pub use repo::{CheckHead, CurrentReport, FleetRow, JobHead, SetHead};
mod rows;
pub mod sqlite;
mod statement;
pub mod write_guard;
pub mod writer;

#[derive(Debug, thiserror::Error)]
pub enum StoreError {
    /// The referenced parent row (robot, session) does not exist.
    #[error("{0} not found")]
    NotFound(&'static str),
    /// The write conflicts with the current state (e.g. cancelling a finished job).
    #[error("conflict: {0}")]
    Conflict(String),
    /// The queue holds `--max-queued` jobs already.
    #[error("queue full")]
    QueueFull,
    /// The database failed (connection, I/O, constraint we did not expect).
    #[error("database error: {0}")]
    Backend(String),
}

pub use records::{
    ClaimedJob, JobFilter, JobOutcome, JobRecord, NewJob, NewParameterSet, NewPose, OutboxDelivery,
    ParameterSetRecord, PoseDetection, PoseRecord, RobotRecord, SessionRecord, TrackerMeasurement,
    WebhookRecord,
};

pub type StoreResult<T> = Result<T, StoreError>;

#[async_trait]
pub trait RobotStore: Send + Sync {
    /// Create or replace; returns `true` when the robot was created.
    async fn put_robot(&self, robot: &RobotRecord) -> StoreResult<bool>;
    async fn get_robot(&self, serial: &str) -> StoreResult<Option<RobotRecord>>;
    async fn list_robots(&self, limit: i64, after: Option<&str>) -> StoreResult<Page<RobotRecord>>;
    /// Deletes the robot with everything it had: sessions, poses, jobs
    /// (with their results), parameter sets with their reports, and the
    /// images no other pose names. A robot created later under the same
    /// serial starts empty. `false` if absent.
    async fn delete_robot(&self, serial: &str) -> StoreResult<bool>;
    /// Sets the robot's controller identity (`None`: removes it) and, when
    /// that changes it, records the change in its history, in one
    /// transaction; `true` when it changed. `NotFound("robot")` when absent.
    async fn set_robot_controller(
        &self,
        serial: &str,
        controller: Option<&ControllerIdentity>,
        at: &str,
    ) -> StoreResult<bool>;
    /// The robot's controller changes, oldest first.
    async fn list_controller_changes(&self, serial: &str) -> StoreResult<Vec<ControllerChange>>;
}

#[async_trait]
pub trait SessionStore: Send + Sync {
    /// `NotFound("robot")` when the serial is unknown.
    async fn create_session(
        &self,
        serial: &str,
        instrument: &str,
        spec: &SessionBody,
    ) -> StoreResult<SessionRecord>;
    async fn get_session(&self, id: &str) -> StoreResult<Option<SessionRecord>>;
    async fn list_sessions(
        &self,
        serial: &str,
        limit: i64,
        after: Option<&str>,
    ) -> StoreResult<Page<SessionRecord>>;
    /// Stores image bytes under their sha256 (idempotent); durable on
    /// return. Storing again renews the image's grace against
    /// [`collect_blobs`](Self::collect_blobs).
    async fn put_blob(&self, meta: &ImageMeta, data: &[u8]) -> StoreResult<()>;
    /// Deletes those of `sha256s` that no pose names (the images of an
    /// upload that was refused, or of deleted poses); returns how many.
    async fn discard_blobs(&self, sha256s: &[String]) -> StoreResult<u64>;
    /// Deletes every image no pose names that was last stored before
    /// `touched_before_ms` (unix ms); returns how many. The grace keeps the
    /// images of uploads in progress, stored but not yet attached to poses.
    async fn collect_blobs(&self, touched_before_ms: i64) -> StoreResult<u64>;
    /// Deletes every image no pose names whose last writer is a process
    /// known to be gone ([`writer::is_gone`]: killed mid-upload); returns
    /// how many. Run at start-up, so a crash's images go at once.
    async fn collect_orphan_blobs(&self) -> StoreResult<u64>;
    async fn get_blob(&self, sha256: &str) -> StoreResult<Option<Vec<u8>>>;
    /// Inserts all poses in one transaction (all or none), in order.
    /// `Conflict` when an image was collected meanwhile (the only other
    /// poses naming it were deleted): the client uploads it again.
    async fn add_poses(&self, session_id: &str, poses: &[NewPose]) -> StoreResult<Vec<PoseRecord>>;
    async fn get_pose(&self, session_id: &str, pose_id: &str) -> StoreResult<Option<PoseRecord>>;
    async fn list_poses(
        &self,
        session_id: &str,
        limit: i64,
        after: Option<&str>,
    ) -> StoreResult<Page<PoseRecord>>;
}

#[async_trait]
pub trait JobStore: Send + Sync {
    /// Inserts a queued job unless `max_queued` jobs are queued already
    /// (`QueueFull`), atomically.
    async fn enqueue_job(&self, job: &NewJob, max_queued: i64) -> StoreResult<JobRecord>;
    async fn get_job(&self, id: &str) -> StoreResult<Option<JobRecord>>;
    /// The jobs `filter` lets through, newest first; `before` is the
    /// `next_cursor` (a job id) of the previous page.
    async fn list_jobs(
        &self,
        filter: &JobFilter,
        limit: i64,
        before: Option<&str>,
    ) -> StoreResult<Page<JobRecord>>;
    /// Queued or running -> cancelled (with its `job.finished` event).
    /// `Conflict` when already finished.
    async fn cancel_job(&self, id: &str) -> StoreResult<Option<JobRecord>>;
    /// Fails running jobs whose lease expired and that have no attempt left.
    async fn fail_exhausted_jobs(&self, now_ms: i64) -> StoreResult<u64>;
    /// Atomically takes the oldest queued job, or a running one whose lease
    /// expired, with a lease until `lease_until_ms`; counts an attempt.
    async fn claim_job(
        &self,
        worker_id: &str,
        now_ms: i64,
        lease_until_ms: i64,
    ) -> StoreResult<Option<ClaimedJob>>;
    /// Extends the lease and records progress, if the worker still holds it.
    async fn renew_lease(
        &self,
        job_id: &str,
        worker_id: &str,
        lease_until_ms: i64,
        stage: &str,
        progress: f64,
    ) -> StoreResult<LeaseStatus>;
    /// Records the outcome (and its parameter set and pose detections) if
    /// the worker still holds the lease.
    async fn finish_job(
        &self,
        job_id: &str,
        worker_id: &str,
        outcome: &JobOutcome,
    ) -> StoreResult<LeaseStatus>;
    /// Replaces the image points every pose of the job's session shows
    /// (`detections`; poses not listed are cleared) in one transaction, if
    /// the worker still holds the job's lease.
    async fn record_detections(
        &self,
        job_id: &str,
        worker_id: &str,
        detections: &[PoseDetection],
    ) -> StoreResult<LeaseStatus>;
    /// Gives a running job back to the queue without counting the attempt (shutdown).
    async fn release_job(&self, job_id: &str, worker_id: &str) -> StoreResult<()>;
    /// Number of jobs per state (for metrics).
    async fn job_counts(&self) -> StoreResult<Vec<(JobState, i64)>>;
}

#[async_trait]
pub trait ResultStore: Send + Sync {
    /// Stores a parameter set and its report as the serial's next version.
    async fn insert_parameter_set(
        &self,
        serial: &str,
        job_id: Option<&str>,
        set: &NewParameterSet,
    ) -> StoreResult<i64>;
    /// Newest first.
    async fn list_parameter_sets(
        &self,
        serial: &str,
        limit: i64,
        before_version: Option<i64>,
    ) -> StoreResult<Page<ParameterSetRecord>>;
    /// `version = None` means the latest **approved** set (the release gate).
    async fn get_parameter_set(
        &self,
        serial: &str,
        version: Option<i64>,
    ) -> StoreResult<Option<ParameterSetRecord>>;
    async fn get_report(&self, serial: &str, version: i64) -> StoreResult<Option<Value>>;
}

/// The release gate: status changes with who and when, and a
/// robot's finished re-checks.
#[async_trait]
pub trait ReleaseStore: Send + Sync {
    /// Gives set `serial`/`version` the status `release`, decided by
    /// `actor`, and logs the decision; `None` when there is no such set.
    async fn set_release(
        &self,
        serial: &str,
        version: i64,
        release: &Release,
        actor: &str,
    ) -> StoreResult<Option<ParameterSetRecord>>;
    /// Every decision on the serial's sets, oldest first.
    async fn list_decisions(&self, serial: &str) -> StoreResult<Vec<Decision>>;
    /// The serial's succeeded re-check jobs, newest first.
    async fn list_checks(&self, serial: &str, limit: i64) -> StoreResult<Vec<JobRecord>>;
}

/// The fleet page's reads: a constant number of statements whatever the
/// number of robots.
#[async_trait]
pub trait FleetStore: Send + Sync {
    /// The first `limit` robots by serial, each with the set `latest`
    /// serves, its newest succeeded re-check and its newest job.
    async fn fleet_rows(&self, limit: i64) -> StoreResult<Vec<FleetRow>>;
    /// The reports of those robots' current sets.
    async fn fleet_reports(&self, limit: i64) -> StoreResult<Vec<CurrentReport>>;
}

#[async_trait]
pub trait AuthStore: Send + Sync {
    /// A token that never expires.
    async fn create_token(
        &self,
        name: &str,
        token_hash: &str,
        scope: Scope,
    ) -> StoreResult<TokenRecord> {
        self.create_token_expiring(name, token_hash, scope, None)
            .await
    }
    /// `expires_ms`: Unix ms after which the token is refused.
    async fn create_token_expiring(
        &self,
        name: &str,
        token_hash: &str,
        scope: Scope,
        expires_ms: Option<i64>,
    ) -> StoreResult<TokenRecord>;
    /// Any token with this hash, also revoked or expired ones (the caller
    /// says which, see [`TokenRecord::check_usable`]).
    async fn find_token(&self, token_hash: &str) -> StoreResult<Option<TokenRecord>>;
    /// Every token, revoked and expired ones included, oldest first.
    async fn list_tokens(&self) -> StoreResult<Vec<TokenRecord>>;
    /// Tokens ever created, revoked and expired ones included: anonymous
    /// access ends with the first token and does not come back.
    async fn count_tokens(&self) -> StoreResult<i64>;
    /// Marks the token revoked (its row stays); `None` when no token has
    /// this id. Revoking a revoked token keeps the first revocation.
    async fn revoke_token(&self, id: &str) -> StoreResult<Option<TokenRecord>>;
    /// [`revoke_token`](Self::revoke_token) over the API: refused
    /// ([`StoreError::Conflict`]) when it would leave no usable admin
    /// token, so the service cannot lock its administrators out.
    async fn revoke_token_keeping_an_admin(&self, id: &str) -> StoreResult<Option<TokenRecord>>;
    /// Records a use at `now_ms` unless one was recorded after
    /// `now_ms - min_interval_ms` (so a busy token costs one write a minute).
    async fn touch_token(&self, id: &str, now_ms: i64, min_interval_ms: i64) -> StoreResult<()>;
    /// The secret `name`, shared by every replica: the stored one, or
    /// `fresh` stored now when there is none yet (the first writer wins).
    async fn server_secret(&self, name: &str, fresh: &str) -> StoreResult<String>;
    /// Registers a key as in flight (held by `scope.holder` until
    /// `lease_until_ms`), or reports it running, used elsewhere or done.
    async fn claim_idempotency(
        &self,
        scope: &IdempotencyScope,
        lease_until_ms: i64,
    ) -> StoreResult<IdempotencyClaim>;
    /// Extends the holder's lease on a pending key.
    async fn renew_idempotency(
        &self,
        scope: &IdempotencyScope,
        lease_until_ms: i64,
    ) -> StoreResult<()>;
    /// Stores the response of the holder's request and its fingerprint.
    async fn complete_idempotency(
        &self,
        scope: &IdempotencyScope,
        fingerprint: Option<&str>,
        response: &StoredResponse,
    ) -> StoreResult<()>;
    /// Forgets a pending key (the request failed before producing a storable response).
    async fn abandon_idempotency(&self, scope: &IdempotencyScope) -> StoreResult<()>;
}

/// A stored campaign plan: the request and the plan documents.
#[derive(Debug, Clone, PartialEq)]
pub struct CampaignPlanRecord {
    pub id: String,
    pub serial: String,
    pub request: Value,
    pub plan: Value,
    pub created_at: String,
}

#[async_trait]
pub trait CampaignPlanStore: Send + Sync {
    async fn insert_campaign_plan(&self, plan: &CampaignPlanRecord) -> StoreResult<()>;
    /// The plan `id` of robot `serial`.
    async fn get_campaign_plan(
        &self,
        serial: &str,
        id: &str,
    ) -> StoreResult<Option<CampaignPlanRecord>>;
}

/// Webhooks and their durable outbox (`repo/webhooks.rs`).
#[async_trait]
pub trait WebhookStore: Send + Sync {
    async fn create_webhook(&self, webhook: &WebhookRecord) -> StoreResult<()>;
    /// Oldest first.
    async fn list_webhooks(&self) -> StoreResult<Vec<WebhookRecord>>;
    async fn get_webhook(&self, id: &str) -> StoreResult<Option<WebhookRecord>>;
    /// Deletes it with its undelivered events; `false` if absent.
    async fn delete_webhook(&self, id: &str) -> StoreResult<bool>;
    /// Writes `event` to the outbox of every subscribed webhook, in its own
    /// transaction: call it before the change it reports is committed (or
    /// record inside that change's transaction with `record_event_tx`).
    async fn record_event(&self, event: &DomainEvent, now_ms: i64) -> StoreResult<()>;
    /// Takes up to `limit` due, unclaimed deliveries until `lease_until_ms`.
    async fn claim_deliveries(
        &self,
        now_ms: i64,
        lease_until_ms: i64,
        limit: i64,
    ) -> StoreResult<Vec<OutboxDelivery>>;
    /// The receiver answered 2xx: never sent again.
    async fn mark_delivered(&self, id: &str) -> StoreResult<()>;
    /// An attempt failed: try again at `retry_at_ms`, or (`None`) give up.
    async fn mark_attempt_failed(
        &self,
        id: &str,
        error: &str,
        retry_at_ms: Option<i64>,
    ) -> StoreResult<()>;
    /// The webhook's outbox rows per state (`pending`, `delivered`, `failed`).
    async fn outbox_counts(&self, webhook_id: &str) -> StoreResult<Vec<(String, i64)>>;
}

#[async_trait]
pub trait Store:
    RobotStore
    + SessionStore
    + JobStore
    + ResultStore
    + ReleaseStore
    + FleetStore
    + AuthStore
    + CampaignPlanStore
    + WebhookStore
{
    /// Readiness probe: the database answers.
    async fn ping(&self) -> StoreResult<()>;
    /// Backend name for logs ("sqlite", "postgres").
    fn backend(&self) -> &'static str;
    /// Gives the space of deleted rows back to the file system (SQLite:
    /// incremental vacuum and a checkpoint, so the file shrinks after a
    /// robot's images are deleted; PostgreSQL's autovacuum reuses it).
    async fn reclaim_space(&self) -> StoreResult<()>;
    /// Wakes `wake` (one idle worker) whenever another process makes a job
    /// claimable, until `shutdown`. Returns `false` when the backend has no
    /// such events (SQLite: one process, whose own enqueues wake it); workers
    /// poll in any case, as the fallback.
    fn watch_jobs(&self, _wake: Arc<Notify>, _shutdown: watch::Receiver<bool>) -> bool {
        false
    }
}

pub type DynStore = Arc<dyn Store>;

/// Opens the store named by a database URL and runs its migrations:
/// `sqlite://path.db` (one node) or `postgres://user@host/db` (a fleet).
pub async fn connect(database_url: &str) -> StoreResult<DynStore> {
    if database_url.starts_with("sqlite:") {
        let store = sqlite::SqliteStore::connect(database_url).await?;
        Ok(Arc::new(store))
    } else if database_url.starts_with("postgres:") || database_url.starts_with("postgresql:") {
        let store = postgres::PgStore::connect(database_url).await?;
        Ok(Arc::new(store))
    } else {
        Err(StoreError::Backend(format!(
            "unsupported database URL scheme in {database_url:?} (supported: sqlite:, postgres:)"
        )))
    }
}

impl From<sqlx::Error> for StoreError {
    fn from(e: sqlx::Error) -> Self {
        StoreError::Backend(e.to_string())
    }
}

impl From<serde_json::Error> for StoreError {
    fn from(e: serde_json::Error) -> Self {
        StoreError::Backend(format!("stored JSON unreadable: {e}"))
    }
}
