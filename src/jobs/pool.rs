//! A bounded pool of workers. Each worker claims one job at a time, runs the
//! CPU-heavy pipeline on a blocking thread (so the API stays responsive while
//! every worker is busy) and, meanwhile, renews its lease and publishes
//! progress every heartbeat. On shutdown workers stop claiming, give a
//! running job `grace` to finish, then cancel it and release it to the queue.

use std::sync::atomic::{AtomicBool, AtomicUsize, Ordering};
use std::sync::{Arc, Mutex};
use std::time::Duration;

use tokio::sync::{watch, Notify};
use tokio::task::JoinHandle;
use tokio::time::Instant;

use super::load::{load_input, LoadError};
use super::queue::{claim_next, Lease, QueuePolicy};
use crate::domain::{CalibratedSet, LeaseStatus, ParameterSet};
use crate::imaging::DecodeGate;
use crate::pipeline::{self, PipelineError, Stage};
use crate::store::DynStore;
use crate::store::{JobOutcome, PoseDetection};

#[derive(Debug, Clone)]
pub struct PoolConfig {
    pub workers: usize,
    pub policy: QueuePolicy,
    /// Idle poll interval (a local enqueue wakes a worker at once).
    pub poll: Duration,
    pub grace: Duration,
    pub test_stage_delay: Duration,
    /// Test hook (`--test-parameter-sets`): see [`mark_test_parameter_set`].
    pub test_parameter_sets: bool,
    /// Test hook (`--test-validate-only`): jobs run the validation stage only.
    pub test_validate_only: bool,
    /// The process's image decode gate (shared with upload detection).
    pub decode_gate: Arc<DecodeGate>,
}

pub struct WorkerPool {
    handles: Vec<JoinHandle<()>>,
    /// Workers whose loop is running (for `/readyz`).
    pub alive: Arc<AtomicUsize>,
}

/// Identifies this process's workers in the jobs table.
fn process_tag() -> String {
    format!("{}-{}", std::process::id(), &crate::domain::new_id()[24..])
}

impl WorkerPool {
    pub fn start(
        store: DynStore,
        config: PoolConfig,
        wake: Arc<Notify>,
        shutdown: watch::Receiver<bool>,
    ) -> WorkerPool {
        let alive = Arc::new(AtomicUsize::new(0));
        let tag = process_tag();
        let handles = (0..config.workers)
            .map(|i| {
                let worker = Worker {
                    id: format!("{tag}-w{i}"),
                    store: store.clone(),
                    config: config.clone(),
                    wake: wake.clone(),
                    shutdown: shutdown.clone(),
                };
                let alive = alive.clone();
                alive.fetch_add(1, Ordering::SeqCst);
                tokio::spawn(async move {
                    worker.run().await;
                    alive.fetch_sub(1, Ordering::SeqCst);
                })
            })
            .collect();
        WorkerPool { handles, alive }
    }

    /// Waits for every worker to stop (after shutdown was signalled).
    pub async fn join(self) {
        for h in self.handles {
            let _ = h.await;
        }
    }
}

struct Worker {
    id: String,
    store: DynStore,
    config: PoolConfig,
    wake: Arc<Notify>,
    shutdown: watch::Receiver<bool>,
}

impl Worker {
    async fn run(mut self) {
        tracing::debug!(worker = %self.id, "worker started");
        while !*self.shutdown.borrow() {
            match claim_next(&self.store, &self.config.policy, &self.id).await {
                Ok(Some(lease)) => self.run_job(lease).await,
                Ok(None) => {
                    tokio::select! {
                        _ = tokio::time::sleep(self.config.poll) => {}
                        _ = self.wake.notified() => {}
                        changed = self.shutdown.changed() => {
                            if changed.is_err() {
                                break; // the server is gone
                            }
                        }
                    }
                }
                Err(e) => {
                    tracing::error!(worker = %self.id, error = %e, "claiming a job failed");
                    tokio::time::sleep(self.config.poll).await;
                }
            }
        }
        tracing::debug!(worker = %self.id, "worker stopped");
    }

    async fn run_job(&mut self, lease: Lease) {
        let job_id = lease.job.id.clone();
        let span = tracing::info_span!("job", job_id = %job_id, attempt = lease.job.attempt);
        let _enter = span.enter();
        tracing::info!("job claimed");
        drop(_enter);
        let input = match load_input(
            &self.store,
            &lease.job,
            self.config.test_stage_delay,
            self.config.decode_gate.clone(),
        )
        .await
        {
            Ok(mut input) => {
                input.validate_only = self.config.test_validate_only;
                input
            }
            Err(LoadError::Gone(error)) => {
                self.finish(&lease, JobOutcome::Failed { error }).await;
                return;
            }
            Err(LoadError::Store(e)) => {
                let error = format!("loading inputs: {e}");
                self.finish(&lease, JobOutcome::Retry { error }).await;
                return;
            }
        };
        let progress = Arc::new(Mutex::new((Stage::Validate.as_str(), 0.0_f64)));
        let cancel = Arc::new(AtomicBool::new(false));
        let mut task = {
            let (progress, cancel) = (progress.clone(), cancel.clone());
            let (store, job_id, worker_id) = (self.store.clone(), job_id.clone(), self.id.clone());
            let runtime = tokio::runtime::Handle::current();
            tokio::task::spawn_blocking(move || {
                let report = |stage: Stage, _message: &str, fraction: f64| {
                    if let Ok(mut p) = progress.lock() {
                        *p = (stage.as_str(), fraction.clamp(0.0, 1.0));
                    }
                };
                // The detect stage's points go to the pose rows at once: a
                // later stage may fail, and they show what was seen.
                let detected = |detections: Vec<PoseDetection>| {
                    let detections = stamp(&job_id, detections);
                    let written =
                        runtime.block_on(store.record_detections(&job_id, &worker_id, &detections));
                    match written {
                        Ok(LeaseStatus::Held) => {}
                        Ok(_) => cancel.store(true, Ordering::SeqCst),
                        Err(e) => tracing::warn!(error = %e, "storing detected points failed"),
                    }
                };
                pipeline::run_observed(&input, &report, &detected, &cancel)
            })
        };
        let mut ticker = tokio::time::interval(self.config.policy.heartbeat());
        let mut stopped: Option<LeaseStatus> = None;
        let mut deadline: Option<Instant> = None;
        let mut releasing = false;
        let result = loop {
            tokio::select! {
                res = &mut task => break res,
                _ = ticker.tick() => {
                    let (stage, fraction) = *progress.lock().unwrap_or_else(|e| e.into_inner());
                    match lease.renew(stage, fraction).await {
                        Ok(LeaseStatus::Held) => {}
                        Ok(status) => {
                            stopped = Some(status);
                            cancel.store(true, Ordering::SeqCst);
                        }
                        Err(e) => tracing::warn!(error = %e, "lease renewal failed"),
                    }
                }
                changed = self.shutdown.changed(), if deadline.is_none() => {
                    if changed.is_err() || *self.shutdown.borrow() {
                        deadline = Some(Instant::now() + self.config.grace);
                    }
                }
            }
            if deadline.is_some_and(|d| Instant::now() >= d) && !releasing {
                releasing = true;
                cancel.store(true, Ordering::SeqCst);
            }
        };
        if let Some(status) = stopped {
            tracing::info!(?status, "job stopped: lease no longer held");
            return;
        }
        let outcome = match result {
            Ok(Ok(out)) => JobOutcome::Succeeded {
                parameter_set: out.parameter_set,
                summary: out.summary,
                detections: stamp(&job_id, out.detections),
                check: out.check.map(Box::new),
            },
            Ok(Err(PipelineError::Cancelled)) if releasing => {
                tracing::info!("shutdown: job released to the queue");
                if let Err(e) = lease.release().await {
                    tracing::error!(error = %e, "releasing job failed; its lease will expire");
                }
                return;
            }
            Ok(Err(PipelineError::Cancelled)) => return,
            Ok(Err(e)) => JobOutcome::Failed {
                error: e.to_string(),
            },
            Err(join) => JobOutcome::Retry {
                error: format!("pipeline crashed: {}", panic_message(join)),
            },
        };
        self.finish(&lease, outcome).await;
    }

    async fn finish(&self, lease: &Lease, mut outcome: JobOutcome) {
        if self.config.test_parameter_sets {
            mark_test_parameter_set(&mut outcome, &lease.job);
        }
        match &outcome {
            JobOutcome::Succeeded { .. } => tracing::info!(job_id = %lease.job.id, "job succeeded"),
            JobOutcome::Failed { error } | JobOutcome::Retry { error } => {
                tracing::warn!(job_id = %lease.job.id, %error, "job failed")
            }
        }
        match lease.finish(&outcome).await {
            Ok(LeaseStatus::Held) => {}
            Ok(status) => tracing::info!(job_id = %lease.job.id, ?status, "outcome not recorded"),
            Err(e) => {
                tracing::error!(job_id = %lease.job.id, error = %e, "recording outcome failed")
            }
        }
    }
}

/// Names the job in each pose's detection document (which job's points a
/// pose shows).
fn stamp(job_id: &str, mut detections: Vec<PoseDetection>) -> Vec<PoseDetection> {
    for d in &mut detections {
        d.detection.job_id = Some(job_id.to_string());
    }
    detections
}

fn panic_message(join: tokio::task::JoinError) -> String {
    match join.try_into_panic() {
        Ok(payload) => payload
            .downcast_ref::<&str>()
            .map(|s| s.to_string())
            .or_else(|| payload.downcast_ref::<String>().cloned())
            .unwrap_or_else(|| "panic".into()),
        Err(e) => e.to_string(),
    }
}

/// Test hook: gives a succeeded job without a parameter set a marker one
/// ([`ParameterSet::placeholder`], its report `{"test_marker": true,
/// "job_id", "attempt"}`), stored like a real result.
fn mark_test_parameter_set(outcome: &mut JobOutcome, job: &crate::store::ClaimedJob) {
    if let JobOutcome::Succeeded {
        parameter_set: set @ None,
        ..
    } = outcome
    {
        *set = Some(crate::store::NewParameterSet::approved(
            CalibratedSet::Kinematic(ParameterSet::placeholder(&job.session_id)),
            serde_json::json!({
                "test_marker": true,
                "job_id": job.id,
                "attempt": job.attempt,
            }),
        ));
    }
}
