//! Fleet benchmark: jobs per minute and claim latency (submit → running) with
//! 1, 2 and 3 replicas, SQLite against PostgreSQL. Every replica is a real
//! process (this program re-executed as `fleet_bench replica <serve flags>`)
//! with one worker, i.e. the "one core per replica" deployment.
//!
//! ```sh
//! cargo run --release --example fleet_bench            # both backends, 1..3 replicas
//! cargo run --release --example fleet_bench -- --jobs 60 --latency-jobs 30 --pg-url postgres://postgres@127.0.0.1:5432/test
//! ```
//!
//! The job is today's calibration job (input validation: it decodes every
//! image of the session), on a session of `--images` 1280x1024 PNG photos, so
//! each job is CPU-bound like the real pipeline. Latency is measured with idle
//! workers, one job at a time (created_at → started_at, as the database
//! records them); throughput with a burst of `--jobs` jobs spread over the
//! replicas (first created_at → last finished_at).

use std::io::{BufRead, BufReader};
use std::process::{Child, Command, Stdio};
use std::time::{Duration, SystemTime};

use clap::Parser;
use robocal::config::ServeConfig;
use robocal::store;
use serde_json::{json, Value};
use sqlx::{Connection, PgConnection};

#[derive(Parser)]
struct Args {
    /// Jobs in the throughput burst.
    #[arg(long, default_value_t = 60)]
    jobs: usize,
    /// Jobs submitted one at a time for the latency figures.
    #[arg(long, default_value_t = 20)]
    latency_jobs: usize,
    /// Images per session (each job decodes all of them).
    #[arg(long, default_value_t = 6)]
    images: usize,
    /// Replica counts to measure.
    #[arg(long, value_delimiter = ',', default_value = "1,2,3")]
    replicas: Vec<usize>,
    /// Backends to measure.
    #[arg(long, value_delimiter = ',', default_value = "sqlite,postgres")]
    backends: Vec<String>,
    /// Administrative URL of the PostgreSQL server (a database is created per run).
    #[arg(
        long,
        env = "ROBOCAL_TEST_PG_URL",
        default_value = "postgres://postgres@127.0.0.1:5432/test"
    )]
    pg_url: String,
    /// Idle poll of each replica's worker, ms (the fallback behind LISTEN/NOTIFY).
    #[arg(long, default_value_t = 500)]
    poll_ms: u64,
}

#[derive(Parser)]
struct ReplicaCli {
    #[command(flatten)]
    config: ServeConfig,
}

const WIDTH: u32 = 1280;
const HEIGHT: u32 = 1024;

fn main() {
    let argv: Vec<String> = std::env::args().collect();
    if argv.get(1).map(String::as_str) == Some("replica") {
        let cli = ReplicaCli::parse_from(argv[1..].iter());
        let rt = tokio::runtime::Runtime::new().unwrap();
        if let Err(e) = rt.block_on(robocal::server::run(cli.config)) {
            eprintln!("replica: {e}");
            std::process::exit(1);
        }
        return;
    }
    let args = Args::parse();
    let rt = tokio::runtime::Runtime::new().unwrap();
    rt.block_on(bench(args));
}

struct Row {
    backend: String,
    replicas: usize,
    jobs_per_min: f64,
    latency_ms: Vec<f64>,
}

async fn bench(args: Args) {
    let cores = std::thread::available_parallelism()
        .map(|n| n.get())
        .unwrap_or(1);
    println!("fleet_bench: {cores} cores, {} images of {WIDTH}x{HEIGHT} per job, 1 worker per replica, poll {} ms", args.images, args.poll_ms);
    let images: Vec<Vec<u8>> = (0..args.images).map(|i| png(i as u8)).collect();
    let mut rows = Vec::new();
    for backend in &args.backends {
        for &n in &args.replicas {
            let (url, cleanup) = fresh_database(backend, &args.pg_url, n).await;
            let row = run_one(&args, backend, &url, n, &images).await;
            cleanup.await;
            println!(
                "{:<9} replicas={} jobs/min={:>7.1} claim latency ms: median={:>6.1} p95={:>6.1} max={:>6.1}",
                row.backend,
                row.replicas,
                row.jobs_per_min,
                percentile(&row.latency_ms, 0.5),
                percentile(&row.latency_ms, 0.95),
                percentile(&row.latency_ms, 1.0)
            );
            rows.push(row);
        }
    }
    println!();
    println!(
        "| backend | replicas | jobs/min | vs 1 replica | claim latency median / p95 / max (ms) |"
    );
    println!("| --- | --- | --- | --- | --- |");
    for r in &rows {
        let base = rows
            .iter()
            .find(|b| b.backend == r.backend && b.replicas == 1)
            .map(|b| b.jobs_per_min)
            .unwrap_or(r.jobs_per_min);
        println!(
            "| {} | {} | {:.1} | {:.2}x | {:.1} / {:.1} / {:.1} |",
            r.backend,
            r.replicas,
            r.jobs_per_min,
            r.jobs_per_min / base,
            percentile(&r.latency_ms, 0.5),
            percentile(&r.latency_ms, 0.95),
            percentile(&r.latency_ms, 1.0)
        );
    }
}

type Cleanup = std::pin::Pin<Box<dyn std::future::Future<Output = ()>>>;

async fn fresh_database(backend: &str, pg_url: &str, n: usize) -> (String, Cleanup) {
    match backend {
        "sqlite" => {
            let dir = tempfile::tempdir().unwrap();
            let url = format!("sqlite://{}/bench.db", dir.path().display());
            (url, Box::pin(async move { drop(dir) }))
        }
        "postgres" => {
            let name = format!("robocal_bench_{}_{n}", std::process::id());
            let mut admin = PgConnection::connect(pg_url)
                .await
                .expect("PostgreSQL server");
            sqlx::query(&format!("DROP DATABASE IF EXISTS \"{name}\" WITH (FORCE)"))
                .execute(&mut admin)
                .await
                .unwrap();
            sqlx::query(&format!("CREATE DATABASE \"{name}\""))
                .execute(&mut admin)
                .await
                .unwrap();
            let mut url = reqwest::Url::parse(pg_url).unwrap();
            url.set_path(&name);
            let admin_url = pg_url.to_string();
            (
                url.to_string(),
                Box::pin(async move {
                    let mut admin = PgConnection::connect(&admin_url).await.unwrap();
                    let _ =
                        sqlx::query(&format!("DROP DATABASE IF EXISTS \"{name}\" WITH (FORCE)"))
                            .execute(&mut admin)
                            .await;
                }),
            )
        }
        other => panic!("unknown backend {other:?} (sqlite, postgres)"),
    }
}

struct Replica {
    child: Child,
    base: String,
}

impl Drop for Replica {
    fn drop(&mut self) {
        let _ = Command::new("kill")
            .args(["-TERM", &self.child.id().to_string()])
            .status();
        let _ = self.child.wait();
    }
}

fn start_replicas(url: &str, n: usize, poll_ms: u64) -> Vec<Replica> {
    let exe = std::env::current_exe().unwrap();
    let children: Vec<Child> = (0..n)
        .map(|_| {
            Command::new(&exe)
                .args([
                    "replica",
                    "--database-url",
                    url,
                    "--bind",
                    "127.0.0.1:0",
                    "--workers",
                    "1",
                ])
                .args([
                    "--poll-ms",
                    &poll_ms.to_string(),
                    "--max-queued",
                    "100000",
                    "--shutdown-grace-secs",
                    "5",
                    // A queue benchmark: jobs validate their inputs only.
                    "--test-validate-only",
                ])
                .env("RUST_LOG", "warn")
                .stdout(Stdio::piped())
                .stderr(Stdio::inherit())
                .spawn()
                .unwrap()
        })
        .collect();
    children
        .into_iter()
        .map(|mut child| {
            let mut line = String::new();
            BufReader::new(child.stdout.take().unwrap())
                .read_line(&mut line)
                .unwrap();
            let base = line
                .trim()
                .strip_prefix("robocal listening on ")
                .expect("replica address")
                .to_string();
            Replica { child, base }
        })
        .collect()
}

async fn run_one(args: &Args, backend: &str, url: &str, n: usize, images: &[Vec<u8>]) -> Row {
    let fleet = start_replicas(url, n, args.poll_ms);
    let c = reqwest::Client::new();
    let session = setup(&c, &fleet[0].base, images).await;
    let store = store::connect(url).await.unwrap();
    // Warm-up (connections, caches).
    let j = submit(&c, &fleet[0].base, &session).await;
    wait_done(&c, &fleet[0].base, &j).await;

    // Claim latency with idle workers: one job at a time, round robin.
    let mut latency_ms = Vec::new();
    for i in 0..args.latency_jobs {
        let base = &fleet[i % n].base;
        let j = submit(&c, base, &session).await;
        wait_done(&c, base, &j).await;
        let rec = store.get_job(&j).await.unwrap().unwrap();
        latency_ms.push(ms_between(
            &rec.created_at,
            rec.started_at.as_deref().unwrap(),
        ));
    }

    // Throughput: a burst spread over the replicas.
    let jobs = futures_util::future::join_all((0..args.jobs).map(|i| {
        let (c, base, session) = (&c, fleet[i % n].base.clone(), session.clone());
        async move { submit(c, &base, &session).await }
    }))
    .await;
    for j in &jobs {
        wait_done(&c, &fleet[0].base, j).await;
    }
    let mut first = f64::MAX;
    let mut last = f64::MIN;
    for j in &jobs {
        let rec = store.get_job(j).await.unwrap().unwrap();
        first = first.min(unix_ms(&rec.created_at));
        last = last.max(unix_ms(rec.finished_at.as_deref().unwrap()));
    }
    let wall_min = ((last - first) / 60_000.0).max(1e-9);
    drop(fleet);
    Row {
        backend: backend.to_string(),
        replicas: n,
        jobs_per_min: args.jobs as f64 / wall_min,
        latency_ms,
    }
}

async fn setup(c: &reqwest::Client, base: &str, images: &[Vec<u8>]) -> String {
    let joints: Vec<Value> = [(100.0, -90.0, 615.0), (705.0, 0.0, 0.0), (135.0, -90.0, 0.0), (0.0, 90.0, 755.0), (0.0, -90.0, 0.0), (0.0, 0.0, 85.0)]
        .iter()
        .map(|(a, alpha, d)| json!({"type":"revolute","a_mm":a,"alpha_deg":alpha,"d_mm":d,"theta_offset_deg":0.0,"min_deg":-170.0,"max_deg":170.0}))
        .collect();
    let r = c
        .put(format!("{base}/v1/robots/B1"))
        .json(&json!({"model": "bench", "kinematics": {"joints": joints}}))
        .send()
        .await
        .unwrap();
    assert!(r.status().is_success(), "{}", r.text().await.unwrap());
    let s: Value = c
        .post(format!("{base}/v1/robots/B1/sessions"))
        .json(&json!({
            "instrument": "camera",
            "target": {"rows": 7, "cols": 9, "pitch_mm": 20.0, "dot_diameter_mm": 8.0, "origin_marker_diameter_mm": 12.0},
            "camera": {"width": WIDTH, "height": HEIGHT, "pixel_size_um": 5.3, "nominal_focal_mm": 8.0}
        }))
        .send()
        .await
        .unwrap()
        .json()
        .await
        .unwrap();
    let session = s["id"].as_str().unwrap().to_string();
    for (i, img) in images.iter().enumerate() {
        let set = if i + 1 < images.len() { "cal" } else { "val" };
        let form = reqwest::multipart::Form::new()
            .text("joints_deg", format!("[{i},1,2,3,4,5]"))
            .text("set", set)
            .part(
                "image",
                reqwest::multipart::Part::bytes(img.clone())
                    .file_name("p.png")
                    .mime_str("image/png")
                    .unwrap(),
            );
        let r = c
            .post(format!("{base}/v1/sessions/{session}/poses"))
            .multipart(form)
            .send()
            .await
            .unwrap();
        assert_eq!(r.status(), 201, "{}", r.text().await.unwrap());
    }
    session
}

async fn submit(c: &reqwest::Client, base: &str, session: &str) -> String {
    loop {
        let r = c
            .post(format!("{base}/v1/sessions/{session}/calibrations"))
            .send()
            .await
            .unwrap();
        if r.status() == 202 {
            return r.json::<Value>().await.unwrap()["job_id"]
                .as_str()
                .unwrap()
                .to_string();
        }
        assert!(r.status() == 429, "submit: {}", r.status());
        tokio::time::sleep(Duration::from_millis(50)).await;
    }
}

async fn wait_done(c: &reqwest::Client, base: &str, job: &str) {
    loop {
        let v: Value = c
            .get(format!("{base}/v1/jobs/{job}"))
            .send()
            .await
            .unwrap()
            .json()
            .await
            .unwrap();
        match v["state"].as_str() {
            Some("succeeded") => return,
            Some("failed" | "cancelled") => panic!("job {job}: {v}"),
            _ => tokio::time::sleep(Duration::from_millis(5)).await,
        }
    }
}

fn unix_ms(rfc3339: &str) -> f64 {
    let t = humantime::parse_rfc3339(rfc3339).unwrap();
    t.duration_since(SystemTime::UNIX_EPOCH)
        .unwrap()
        .as_secs_f64()
        * 1000.0
}

fn ms_between(a: &str, b: &str) -> f64 {
    unix_ms(b) - unix_ms(a)
}

fn percentile(v: &[f64], q: f64) -> f64 {
    if v.is_empty() {
        return f64::NAN;
    }
    let mut s = v.to_vec();
    s.sort_by(|a, b| a.total_cmp(b));
    s[((s.len() - 1) as f64 * q).round() as usize]
}

/// A photo-sized PNG with texture (so it does not compress to nothing).
fn png(seed: u8) -> Vec<u8> {
    let img = image::GrayImage::from_fn(WIDTH, HEIGHT, |x, y| {
        let v = (x.wrapping_mul(7) ^ y.wrapping_mul(13)).wrapping_add(seed as u32 * 31);
        image::Luma([(v % 251) as u8])
    });
    let mut out = std::io::Cursor::new(Vec::new());
    img.write_to(&mut out, image::ImageFormat::Png).unwrap();
    out.into_inner()
}
