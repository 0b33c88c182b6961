//! Server configuration: flags and environment, validated once at start.

use std::net::SocketAddr;
use std::path::PathBuf;
use std::time::Duration;

use clap::{Args, ValueEnum};

const MIB: u64 = 1024 * 1024;

#[derive(Debug, Clone, Copy, PartialEq, Eq, ValueEnum)]
pub enum LogFormat {
    Text,
    Json,
}

#[derive(Debug, Clone, Args)]
pub struct ServeConfig {
    /// Address to listen on. Anonymous access is allowed only on a loopback address.
    #[arg(long, env = "ROBOCAL_BIND", default_value = "127.0.0.1:8080")]
    pub bind: SocketAddr,

    /// Database URL: `sqlite://path.db` (the file is created) or `postgres://user@host/db`
    /// (a fleet of replicas sharing one database); migrated at start.
    #[arg(long, env = "DATABASE_URL", default_value = "sqlite://robocal.db")]
    pub database_url: String,

    /// Worker threads running calibration jobs (default: number of CPUs).
    #[arg(long, env = "ROBOCAL_WORKERS")]
    pub workers: Option<usize>,

    /// Attempts of a job before it is failed (a killed worker counts as an attempt).
    #[arg(long, env = "ROBOCAL_MAX_ATTEMPTS", default_value_t = 3)]
    pub max_attempts: i64,

    /// Queued jobs accepted before `POST .../calibrations` answers 429.
    #[arg(long, env = "ROBOCAL_MAX_QUEUED", default_value_t = 64)]
    pub max_queued: i64,

    /// Lease length in seconds of a running job and of a request in flight
    /// under an `Idempotency-Key` (at least 5 s); the holder renews it while
    /// working, so after a crash (kill -9) the job or key is free again then.
    #[arg(long, env = "ROBOCAL_LEASE_SECS", default_value_t = 30)]
    pub lease_secs: u64,

    /// How often an idle worker looks for jobs, in milliseconds.
    #[arg(long, env = "ROBOCAL_POLL_MS", default_value_t = 500)]
    pub poll_ms: u64,

    /// Largest accepted image, bytes (per image, also inside archives).
    #[arg(long, env = "ROBOCAL_MAX_IMAGE_BYTES", default_value_t = 64 * MIB)]
    pub max_image_bytes: u64,

    /// Largest session camera, pixels (width × height): an image is
    /// checked against its session's camera before it is decoded, so this
    /// bounds what one decode may allocate.
    #[arg(long, env = "ROBOCAL_MAX_CAMERA_PIXELS", default_value_t = 50_000_000)]
    pub max_camera_pixels: u64,

    /// Most bytes one image decode may hold (grey output, decoder buffers,
    /// the detector's copy), priced from the header's size, bit depth and
    /// channels before decoding; an image over it is refused with a 422
    /// naming its part. The decode gate holds one such decode per worker.
    #[arg(long, env = "ROBOCAL_MAX_DECODE_BYTES", default_value_t = 512 * MIB)]
    pub max_decode_bytes: u64,

    /// Largest accepted dataset archive, bytes (compressed upload and unpacked total).
    #[arg(long, env = "ROBOCAL_MAX_ARCHIVE_BYTES", default_value_t = 2048 * MIB)]
    pub max_archive_bytes: u64,

    /// Largest accepted JSON request body, bytes.
    #[arg(long, env = "ROBOCAL_MAX_JSON_BYTES", default_value_t = 8 * MIB)]
    pub max_json_bytes: u64,

    /// Seconds a client may take to send a request's head (request line and
    /// headers); the connection is closed after that. Also the keep-alive idle limit.
    #[arg(long, env = "ROBOCAL_HEADER_TIMEOUT_SECS", default_value_t = 15)]
    pub header_timeout_secs: u64,

    /// Seconds a request body may go without sending a byte before the
    /// request is answered 408 and the connection closed.
    #[arg(long, env = "ROBOCAL_BODY_IDLE_TIMEOUT_SECS", default_value_t = 30)]
    pub body_idle_timeout_secs: u64,

    /// Average bytes per second a request body must reach once it has
    /// waited `--body-idle-timeout-secs` for the client (time the handler
    /// spends working does not count); a slower body is answered 408.
    #[arg(long, env = "ROBOCAL_MIN_BODY_BYTES_PER_SEC", default_value_t = 1024)]
    pub min_body_bytes_per_sec: u64,

    /// Connections served at once. When all are open, a new one displaces
    /// the oldest idle one (keep-alive or still sending its head); when all
    /// are in requests, it takes the reserved lane, else it gets 503.
    #[arg(long, env = "ROBOCAL_MAX_CONNECTIONS", default_value_t = 1024)]
    pub max_connections: usize,

    /// Connections beyond `--max-connections` kept for `/healthz`, `/readyz`
    /// and authenticated requests (others on them are answered 503).
    #[arg(long, env = "ROBOCAL_RESERVED_CONNECTIONS", default_value_t = 32)]
    pub reserved_connections: usize,

    /// Connections one client address may hold (event streams included).
    #[arg(
        long,
        env = "ROBOCAL_MAX_CONNECTIONS_PER_ADDRESS",
        default_value_t = 64
    )]
    pub max_connections_per_address: usize,

    /// Open event streams (`/v1/jobs/{id}/events`), counted apart from `--max-connections`.
    #[arg(long, env = "ROBOCAL_MAX_EVENT_STREAMS", default_value_t = 512)]
    pub max_event_streams: usize,

    /// Open event streams per client address.
    #[arg(
        long,
        env = "ROBOCAL_MAX_EVENT_STREAMS_PER_ADDRESS",
        default_value_t = 32
    )]
    pub max_event_streams_per_address: usize,

    /// Directory for streamed uploads being checked (default: the system temp dir).
    #[arg(long, env = "ROBOCAL_UPLOAD_DIR")]
    pub upload_dir: Option<PathBuf>,

    /// Seconds a SIGTERM waits for running jobs before releasing them to the queue.
    #[arg(long, env = "ROBOCAL_SHUTDOWN_GRACE_SECS", default_value_t = 20)]
    pub shutdown_grace_secs: u64,

    /// Wait before a failed webhook delivery is tried again, milliseconds;
    /// doubled after every failed attempt (up to an hour, 15 attempts).
    #[arg(long, env = "ROBOCAL_WEBHOOK_RETRY_BASE_MS", default_value_t = 2000)]
    pub webhook_retry_base_ms: u64,

    /// Seconds a webhook receiver may take to answer before the attempt
    /// counts as failed (and is retried later).
    #[arg(long, env = "ROBOCAL_WEBHOOK_TIMEOUT_SECS", default_value_t = 10)]
    pub webhook_timeout_secs: u64,

    /// Internal address ranges webhooks may be delivered to (comma-separated
    /// `address/prefix`, e.g. `10.0.0.0/8,127.0.0.1`). Loopback, private and
    /// shared ranges are refused without it; link-local (cloud metadata)
    /// addresses and this service itself are always refused.
    #[arg(long, env = "ROBOCAL_WEBHOOK_ALLOW_NETWORKS", value_delimiter = ',')]
    pub webhook_allow_networks: Vec<crate::outbox::address_guard::Network>,

    /// The service's public URL (`https://robocal.plant.example`): signed
    /// report links are built on it instead of on the request's `Host`.
    #[arg(long, env = "ROBOCAL_PUBLIC_BASE_URL")]
    pub public_base_url: Option<String>,

    /// Log format.
    #[arg(long, env = "ROBOCAL_LOG_FORMAT", value_enum, default_value = "text")]
    pub log_format: LogFormat,

    /// Serve `/metrics` without a token. Off by default: once tokens exist a
    /// scraper needs a `read` token (Prometheus `authorization` setting).
    #[arg(long, env = "ROBOCAL_PUBLIC_METRICS")]
    pub public_metrics: bool,

    /// PEM certificate chain: serve HTTPS (with `--tls-key`) instead of HTTP.
    #[arg(long, env = "ROBOCAL_TLS_CERT", requires = "tls_key")]
    pub tls_cert: Option<PathBuf>,

    /// PEM private key (PKCS#8, PKCS#1 or SEC1) of `--tls-cert`.
    #[arg(long, env = "ROBOCAL_TLS_KEY", requires = "tls_cert")]
    pub tls_key: Option<PathBuf>,

    /// Test hook: the validation stage sleeps this long per pose (0 = off).
    #[arg(
        long,
        env = "ROBOCAL_TEST_STAGE_DELAY_MS",
        default_value_t = 0,
        hide = true
    )]
    pub test_stage_delay_ms: u64,

    /// Test hook: a dataset upload pauses this long after each stored
    /// image (0 = off), so a kill test finds images stored and no pose.
    #[arg(
        long,
        env = "ROBOCAL_TEST_UPLOAD_DELAY_MS",
        default_value_t = 0,
        hide = true
    )]
    pub test_upload_delay_ms: u64,

    /// Test hook: a succeeded job whose pipeline identified no parameter set
    /// stores a marker set (naming the job) as the serial's next version, so
    /// the fleet tests can check versions and exactly-once completion.
    #[arg(long, env = "ROBOCAL_TEST_PARAMETER_SETS", hide = true)]
    pub test_parameter_sets: bool,

    /// Test hook: the process aborts (as under kill -9) once a request under
    /// an `Idempotency-Key` has been handled, before its answer is stored.
    #[arg(long, env = "ROBOCAL_TEST_CRASH_BEFORE_IDEMPOTENT_ANSWER", hide = true)]
    pub test_crash_before_idempotent_answer: bool,

    /// Test hook: calibration jobs stop after the input-validation stage, so
    /// queue, lease and restart tests run on tiny synthetic sessions; the
    /// end-to-end tests run the real stages.
    #[arg(long, env = "ROBOCAL_TEST_VALIDATE_ONLY", hide = true)]
    pub test_validate_only: bool,
}

impl ServeConfig {
    /// Defaults as the CLI would give them, for embedding and tests.
    pub fn for_database(database_url: &str) -> ServeConfig {
        use clap::Parser;
        #[derive(Parser)]
        struct Wrapper {
            #[command(flatten)]
            config: ServeConfig,
        }
        let mut config = Wrapper::parse_from(["robocal"]).config;
        config.database_url = database_url.to_string();
        config
    }

    pub fn validate(&self) -> Result<(), String> {
        let positive = [
            ("max_attempts", self.max_attempts),
            ("max_queued", self.max_queued),
            ("lease_secs", self.lease_secs as i64),
            ("poll_ms", self.poll_ms as i64),
            (
                "max_image_bytes",
                self.max_image_bytes.min(i64::MAX as u64) as i64,
            ),
            (
                "max_archive_bytes",
                self.max_archive_bytes.min(i64::MAX as u64) as i64,
            ),
            (
                "max_json_bytes",
                self.max_json_bytes.min(i64::MAX as u64) as i64,
            ),
            (
                "max_camera_pixels",
                self.max_camera_pixels.min(i64::MAX as u64) as i64,
            ),
            (
                "max_decode_bytes",
                self.max_decode_bytes.min(i64::MAX as u64) as i64,
            ),
            ("header_timeout_secs", self.header_timeout_secs as i64),
            ("body_idle_timeout_secs", self.body_idle_timeout_secs as i64),
            ("max_connections", self.max_connections as i64),
            ("min_body_bytes_per_sec", self.min_body_bytes_per_sec as i64),
            (
                "max_connections_per_address",
                self.max_connections_per_address as i64,
            ),
            ("max_event_streams", self.max_event_streams as i64),
            (
                "max_event_streams_per_address",
                self.max_event_streams_per_address as i64,
            ),
            ("webhook_retry_base_ms", self.webhook_retry_base_ms as i64),
            ("webhook_timeout_secs", self.webhook_timeout_secs as i64),
        ];
        for (name, value) in positive {
            if value < 1 {
                return Err(format!("--{} must be at least 1", name.replace('_', "-")));
            }
        }
        if self.tls_cert.is_some() != self.tls_key.is_some() {
            return Err("--tls-cert and --tls-key go together".into());
        }
        if let Some(base) = &self.public_base_url {
            let ok = reqwest::Url::parse(base)
                .is_ok_and(|u| matches!(u.scheme(), "http" | "https") && u.host().is_some());
            if !ok {
                return Err(format!("--public-base-url {base:?} is not an http(s) URL"));
            }
        }
        if self.workers == Some(0) {
            return Err("--workers must be at least 1".into());
        }
        Ok(())
    }

    pub fn worker_count(&self) -> usize {
        self.workers.unwrap_or_else(|| {
            std::thread::available_parallelism()
                .map(|n| n.get())
                .unwrap_or(1)
        })
    }

    pub fn lease(&self) -> Duration {
        Duration::from_secs(self.lease_secs)
    }

    /// How webhook deliveries are paced.
    pub fn delivery_policy(&self) -> crate::outbox::delivery::DeliveryPolicy {
        crate::outbox::delivery::DeliveryPolicy {
            poll: Duration::from_millis(self.poll_ms),
            retry_base: Duration::from_millis(self.webhook_retry_base_ms),
            timeout: Duration::from_secs(self.webhook_timeout_secs),
        }
    }

    /// Where webhooks may be delivered.
    pub fn address_guard(&self) -> crate::outbox::address_guard::AddressGuard {
        crate::outbox::address_guard::AddressGuard {
            bind: self.bind,
            allow: self.webhook_allow_networks.clone(),
        }
    }

    pub fn header_timeout(&self) -> Duration {
        Duration::from_secs(self.header_timeout_secs)
    }

    pub fn body_idle_timeout(&self) -> Duration {
        Duration::from_secs(self.body_idle_timeout_secs)
    }

    /// What the listener's connection table enforces.
    pub fn connection_limits(&self) -> crate::listen::registry::ConnLimits {
        crate::listen::registry::ConnLimits {
            max_connections: self.max_connections,
            reserved_connections: self.reserved_connections,
            max_per_address: self.max_connections_per_address,
            max_streams: self.max_event_streams,
            max_streams_per_address: self.max_event_streams_per_address,
        }
    }

    pub fn upload_dir(&self) -> PathBuf {
        self.upload_dir.clone().unwrap_or_else(std::env::temp_dir)
    }

    /// HTTPS (`--tls-cert`, `--tls-key`) rather than plain HTTP.
    pub fn tls_enabled(&self) -> bool {
        self.tls_cert.is_some()
    }

    /// Anonymous requests are possible only when nobody else can reach the socket.
    pub fn is_loopback(&self) -> bool {
        self.bind.ip().is_loopback()
    }
}
