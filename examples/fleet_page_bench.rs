//! The fleet page (`GET /`) under concurrent viewers: a database seeded
//! with `--robots` robots (each with two approved sets carrying the sample
//! report, a succeeded calibration job and a failed re-check; every tenth
//! robot's newest job failed, every twentieth has one running), then
//! `--viewers` clients each loading the page in a loop. Prints pages/s and
//! the latency percentiles.
//!
//! ```sh
//! cargo run --release --example fleet_page_bench -- --robots 1000 --viewers 16 --pages 800
//! cargo run --release --example fleet_page_bench -- --backend postgres --pg-url postgres://postgres@127.0.0.1:5432/test
//! ```

use std::sync::Arc;
use std::time::{Duration, Instant};

use clap::Parser;
use robocal::config::ServeConfig;
use robocal::domain::{now_unix_ms, CalibratedSet, JobKind, JobSummary, ParameterSet};
use robocal::report::sample::sample_report;
use robocal::schema::job::JobOptions;
use robocal::store::{self, DynStore, JobOutcome, NewJob, NewParameterSet, RobotRecord};
use serde_json::json;
use sqlx::{Connection, PgConnection};

#[derive(Parser)]
struct Args {
    #[arg(long, default_value_t = 1000)]
    robots: usize,
    /// Concurrent viewers.
    #[arg(long, default_value_t = 16)]
    viewers: usize,
    /// Pages loaded in all, after one warm-up load.
    #[arg(long, default_value_t = 800)]
    pages: usize,
    /// `sqlite` or `postgres`.
    #[arg(long, default_value = "sqlite")]
    backend: String,
    /// Administrative URL of the PostgreSQL server (a database is created per run).
    #[arg(
        long,
        env = "ROBOCAL_TEST_PG_URL",
        default_value = "postgres://postgres@127.0.0.1:5432/test"
    )]
    pg_url: String,
}

fn robot(serial: &str) -> RobotRecord {
    let joints: Vec<_> = [
        (100.0, -90.0, 615.0),
        (705.0, 0.0, 0.0),
        (135.0, -90.0, 0.0),
        (0.0, 90.0, 755.0),
        (0.0, -90.0, 0.0),
        (0.0, 0.0, 85.0),
    ]
    .iter()
    .map(|(a, alpha, d)| {
        json!({"type":"revolute","a_mm":a,"alpha_deg":alpha,"d_mm":d,
            "theta_offset_deg":0.0,"min_deg":-170.0,"max_deg":170.0})
    })
    .collect();
    let now = robocal::domain::now_rfc3339();
    RobotRecord {
        serial: serial.to_string(),
        model: "IRB 2400".into(),
        preset: None,
        kinematics: json!({ "convention": "dh", "joints": joints }),
        controller: None,
        prior: None,
        created_at: now.clone(),
        updated_at: now,
    }
}

/// Enqueues a `kind` job of `session` and, unless `outcome` is `None`
/// (left running), finishes it so.
async fn job(
    store: &DynStore,
    serial: &str,
    session: &str,
    kind: JobKind,
    outcome: Option<JobOutcome>,
) {
    let options = match kind {
        JobKind::Calibration => JobOptions::Calibration(Default::default()),
        JobKind::Check => JobOptions::Check(Default::default()),
    };
    let new = NewJob {
        session_id: session.into(),
        serial: serial.into(),
        options,
        max_attempts: 1,
    };
    store.enqueue_job(&new, i64::MAX).await.unwrap();
    let hour_ms = 3_600_000;
    let claimed = store
        .claim_job("bench", now_unix_ms(), now_unix_ms() + hour_ms)
        .await
        .unwrap()
        .expect("the job just queued");
    if let Some(outcome) = outcome {
        store
            .finish_job(&claimed.id, "bench", &outcome)
            .await
            .unwrap();
    }
}

async fn seed(store: &DynStore, robots: usize) {
    let report = serde_json::to_value(sample_report()).unwrap();
    let session_body = serde_json::from_value(json!({
        "instrument": "camera",
        "target": {"rows": 7, "cols": 9, "pitch_mm": 20.0, "dot_diameter_mm": 8.0, "origin_marker_diameter_mm": 12.0},
        "camera": {"width": 64, "height": 48, "pixel_size_um": 5.5, "nominal_focal_mm": 8.0}
    }))
    .unwrap();
    for i in 0..robots {
        let serial = format!("R{i:05}");
        store.put_robot(&robot(&serial)).await.unwrap();
        for _ in 0..2 {
            let set = NewParameterSet::approved(
                CalibratedSet::Kinematic(ParameterSet::placeholder(serial.as_str())),
                report.clone(),
            );
            store
                .insert_parameter_set(&serial, None, &set)
                .await
                .unwrap();
        }
        let session = store
            .create_session(&serial, "camera", &session_body)
            .await
            .unwrap()
            .id;
        let succeeded = JobOutcome::Succeeded {
            parameter_set: None,
            summary: JobSummary::default(),
            detections: vec![],
            check: None,
        };
        job(
            store,
            &serial,
            &session,
            JobKind::Calibration,
            Some(succeeded),
        )
        .await;
        let failed = |e: &str| Some(JobOutcome::Failed { error: e.into() });
        job(store, &serial, &session, JobKind::Check, failed("no poses")).await;
        if i % 10 == 0 {
            job(
                store,
                &serial,
                &session,
                JobKind::Calibration,
                failed("bad input"),
            )
            .await;
        }
        if i % 20 == 0 {
            job(store, &serial, &session, JobKind::Calibration, None).await;
        }
    }
}

fn percentile(sorted: &[Duration], p: f64) -> f64 {
    let i = ((sorted.len() as f64 - 1.0) * p).round() as usize;
    sorted[i].as_secs_f64() * 1000.0
}

#[tokio::main]
async fn main() {
    let args = Args::parse();
    let dir = tempfile::tempdir().unwrap();
    let database_url = match args.backend.as_str() {
        "sqlite" => format!("sqlite://{}/fleet.db", dir.path().display()),
        "postgres" => {
            let name = format!("fleet_page_bench_{}", std::process::id());
            let mut admin = PgConnection::connect(&args.pg_url).await.unwrap();
            sqlx::query(&format!("CREATE DATABASE \"{name}\""))
                .execute(&mut admin)
                .await
                .unwrap();
            let mut url = reqwest::Url::parse(&args.pg_url).unwrap();
            url.set_path(&name);
            url.to_string()
        }
        other => panic!("unknown backend {other}"),
    };
    let store = store::connect(&database_url).await.unwrap();
    let seeding = Instant::now();
    seed(&store, args.robots).await;
    println!(
        "seeded {} robots in {:.1} s",
        args.robots,
        seeding.elapsed().as_secs_f64()
    );

    let mut config = ServeConfig::for_database(&database_url);
    config.bind = "127.0.0.1:0".parse().unwrap();
    config.workers = Some(1);
    config.upload_dir = Some(dir.path().to_path_buf());
    let server = robocal::server::start(config).await.unwrap();
    let url = format!("http://{}/", server.addr);
    let client = reqwest::Client::new();
    let first = client.get(&url).send().await.unwrap();
    assert_eq!(first.status(), 200);
    let body = first.text().await.unwrap();
    assert!(
        body.contains(&format!("R{:05}", args.robots.min(500) - 1)),
        "every robot shown"
    );

    let next = Arc::new(std::sync::atomic::AtomicUsize::new(0));
    let start = Instant::now();
    let viewers: Vec<_> = (0..args.viewers)
        .map(|_| {
            let (client, url, next, pages) =
                (client.clone(), url.clone(), next.clone(), args.pages);
            tokio::spawn(async move {
                let mut took = Vec::new();
                while next.fetch_add(1, std::sync::atomic::Ordering::SeqCst) < pages {
                    let t = Instant::now();
                    let r = client.get(&url).send().await.unwrap();
                    assert_eq!(r.status(), 200);
                    r.bytes().await.unwrap();
                    took.push(t.elapsed());
                }
                took
            })
        })
        .collect();
    let mut all = Vec::new();
    for v in viewers {
        all.extend(v.await.unwrap());
    }
    let wall = start.elapsed().as_secs_f64();
    all.sort();
    println!(
        "{} robots, {} viewers, {} pages ({} bytes each) on {}: {:.1} pages/s, p50 {:.0} ms, p90 {:.0} ms, p99 {:.0} ms, max {:.0} ms",
        args.robots,
        args.viewers,
        all.len(),
        body.len(),
        args.backend,
        all.len() as f64 / wall,
        percentile(&all, 0.5),
        percentile(&all, 0.9),
        percentile(&all, 0.99),
        all.last().unwrap().as_secs_f64() * 1000.0
    );
    server.shutdown().await;
    if args.backend == "postgres" {
        drop(store);
        let name = format!("fleet_page_bench_{}", std::process::id());
        let mut admin = PgConnection::connect(&args.pg_url).await.unwrap();
        let _ = sqlx::query(&format!("DROP DATABASE IF EXISTS \"{name}\" WITH (FORCE)"))
            .execute(&mut admin)
            .await;
    }
}
