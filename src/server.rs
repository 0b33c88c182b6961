//! Starting and stopping the service: store, workers, HTTP listener.

use std::net::SocketAddr;
use std::sync::Arc;
use std::time::Duration;

use tokio::sync::{watch, Notify};
use tokio::task::JoinHandle;

use crate::api::{self, AppState, QUEUE_FULL_RETRY_AFTER_SECS};
use crate::config::ServeConfig;
use crate::imaging::{DecodeBudget, DecodeGate};
use crate::jobs::pool::{PoolConfig, WorkerPool};
use crate::jobs::queue::QueuePolicy;
use crate::listen;
use crate::metrics::Metrics;
use crate::store::{self, StoreError};

#[derive(Debug, thiserror::Error)]
pub enum StartError {
    #[error("configuration: {0}")]
    Config(String),
    #[error("database: {0}")]
    Store(#[from] StoreError),
    #[error("{0}")]
    Refused(String),
    #[error("cannot listen on {addr}: {source}")]
    Bind {
        addr: SocketAddr,
        source: std::io::Error,
    },
}

/// A started server; drop-safe, but call [`RunningServer::shutdown`] to stop cleanly.
pub struct RunningServer {
    pub addr: SocketAddr,
    /// `https` with `--tls-cert`, else `http`.
    pub scheme: &'static str,
    shutdown: watch::Sender<bool>,
    handle: JoinHandle<()>,
}

pub async fn start(mut config: ServeConfig) -> Result<RunningServer, StartError> {
    config.validate().map_err(StartError::Config)?;
    let tls = match (&config.tls_cert, &config.tls_key) {
        (Some(cert), Some(key)) => {
            Some(crate::listen::tls::server_config(cert, key).map_err(StartError::Config)?)
        }
        _ => None,
    };
    let store = store::connect(&config.database_url).await?;
    let tokens = store.count_tokens().await?;
    if tokens == 0 {
        if !config.is_loopback() {
            return Err(StartError::Refused(format!(
                "refusing to listen on {} without tokens: anonymous access is allowed only on a \
                 loopback address. Create one with `robocal token create --scope admin` or bind 127.0.0.1",
                config.bind
            )));
        }
        tracing::warn!(bind = %config.bind, "no tokens configured: accepting anonymous requests (loopback bind only)");
    } else {
        tracing::info!(tokens, "bearer tokens required");
    }
    let listener = tokio::net::TcpListener::bind(config.bind)
        .await
        .map_err(|source| StartError::Bind {
            addr: config.bind,
            source,
        })?;
    let addr = listener.local_addr().map_err(|source| StartError::Bind {
        addr: config.bind,
        source,
    })?;
    // The bound port (port 0 asks for any): anonymous mode checks `Host` against it.
    config.bind = addr;
    let policy = QueuePolicy {
        lease: config.lease(),
        max_attempts: config.max_attempts,
        max_queued: config.max_queued,
        retry_after_secs: QUEUE_FULL_RETRY_AFTER_SECS,
    };
    let (shutdown_tx, shutdown_rx) = watch::channel(false);
    let wake = Arc::new(Notify::new());
    // Cross-process wake-ups (PostgreSQL LISTEN/NOTIFY); polling stays as the fallback.
    let listening = store.watch_jobs(wake.clone(), shutdown_rx.clone());
    // One decode per worker at a time, uploads and jobs together.
    let decode_gate = Arc::new(DecodeGate::with_budget(
        config.worker_count(),
        DecodeBudget {
            max_pixels: config.max_camera_pixels,
            max_bytes: config.max_decode_bytes,
        },
    ));
    let pool = WorkerPool::start(
        store.clone(),
        PoolConfig {
            workers: config.worker_count(),
            policy,
            poll: Duration::from_millis(config.poll_ms),
            grace: Duration::from_secs(config.shutdown_grace_secs),
            test_stage_delay: Duration::from_millis(config.test_stage_delay_ms),
            test_parameter_sets: config.test_parameter_sets,
            test_validate_only: config.test_validate_only,
            decode_gate: decode_gate.clone(),
        },
        wake.clone(),
        shutdown_rx.clone(),
    );
    // Spool files of killed uploads and images no pose names: at start, then periodically.
    let housekeeping =
        crate::housekeeping::spawn(store.clone(), config.upload_dir(), shutdown_rx.clone());
    // Webhook events from the durable outbox, off every request's path.
    let deliveries = crate::outbox::delivery::spawn(
        store.clone(),
        config.delivery_policy(),
        config.address_guard(),
        shutdown_rx.clone(),
    );
    // Open event streams end when their token is revoked or expires.
    let (tokens, token_watch) = api::token_watch::spawn(store.clone(), shutdown_rx.clone());
    // How a worker learns of a job another process queued: PostgreSQL's
    // notifications, else its own poll (SQLite is one process).
    let job_wakeups = if listening {
        "notify (PostgreSQL LISTEN/NOTIFY; polling as the fallback)".to_string()
    } else {
        format!(
            "polling every {} ms (no cross-process notifications)",
            config.poll_ms
        )
    };
    tracing::info!(%addr, backend = store.backend(), workers = config.worker_count(), job_wakeups = %job_wakeups, "robocal listening");
    let scheme = if config.tls_enabled() {
        "https"
    } else {
        "http"
    };
    let state = AppState {
        store,
        config: Arc::new(config),
        policy,
        metrics: Arc::new(Metrics::default()),
        wake,
        workers_alive: pool.alive.clone(),
        decode_gate,
        tokens,
        fleet_cache: Arc::new(crate::service::fleet::SummaryCache::new()),
    };
    let limits = listen::Limits {
        header_timeout: state.config.header_timeout(),
        connections: state.config.connection_limits(),
    };
    let app = api::app(state);
    let handle = tokio::spawn(async move {
        listen::serve(listener, app, limits, tls, shutdown_rx).await;
        pool.join().await;
        let _ = housekeeping.await;
        let _ = deliveries.await;
        let _ = token_watch.await;
        tracing::info!("robocal stopped");
    });
    Ok(RunningServer {
        addr,
        scheme,
        shutdown: shutdown_tx,
        handle,
    })
}

impl RunningServer {
    /// Stops claiming jobs and accepting requests, lets running jobs finish
    /// (or releases them after the grace period), then returns.
    pub async fn shutdown(self) {
        let _ = self.shutdown.send(true);
        let _ = self.handle.await;
    }
}

/// Runs until SIGTERM or Ctrl-C, then shuts down cleanly.
pub async fn run(config: ServeConfig) -> Result<(), StartError> {
    let server = start(config).await?;
    println!("robocal listening on {}://{}", server.scheme, server.addr);
    wait_for_signal().await;
    tracing::info!("shutdown signal: no new jobs are claimed; running jobs finish or are released");
    server.shutdown().await;
    Ok(())
}

async fn wait_for_signal() {
    #[cfg(unix)]
    {
        use tokio::signal::unix::{signal, SignalKind};
        match signal(SignalKind::terminate()) {
            Ok(mut term) => {
                tokio::select! {
                    _ = term.recv() => {}
                    _ = tokio::signal::ctrl_c() => {}
                }
            }
            Err(_) => {
                let _ = tokio::signal::ctrl_c().await;
            }
        }
    }
    #[cfg(not(unix))]
    {
        let _ = tokio::signal::ctrl_c().await;
    }
}
