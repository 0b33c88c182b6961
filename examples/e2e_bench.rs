//! Issue 6 benchmark: a whole simulated campaign through the real service,
//! upload to report, in wall seconds; the server process's peak memory; and
//! the latency of API reads while two campaigns calibrate at once.
//!
//! ```text
//! cargo build --release && cargo run --release --example e2e_bench -- [--cal 45 --val 15]
//! ```
//! The server is the `robocal` binary next to this example (same profile),
//! started as its own process on a fresh SQLite database.

use std::io::{BufRead, BufReader};
use std::path::{Path, PathBuf};
use std::process::{Child, Command, Stdio};
use std::time::{Duration, Instant};

use clap::Parser;
use robocal::cli::client::Client;

#[derive(Parser)]
struct Args {
    #[arg(long, default_value = "irb2400")]
    robot: String,
    #[arg(long, default_value_t = 45)]
    cal: usize,
    #[arg(long, default_value_t = 15)]
    val: usize,
}

/// Reads answered between two job polls, while campaigns calibrate.
const READ_INTERVAL: Duration = Duration::from_millis(20);
const JOB_TIMEOUT: Duration = Duration::from_secs(600);

struct Server {
    child: Child,
    base: String,
}

impl Drop for Server {
    fn drop(&mut self) {
        let _ = self.child.kill();
        let _ = self.child.wait();
    }
}

fn start_server(db_dir: &Path) -> Server {
    let exe = std::env::current_exe().unwrap();
    let binary: PathBuf = exe.parent().unwrap().parent().unwrap().join("robocal");
    let mut child = Command::new(&binary)
        .args(["serve", "--bind", "127.0.0.1:0", "--database-url"])
        .arg(format!("sqlite://{}", db_dir.join("bench.db").display()))
        .env("RUST_LOG", "warn")
        .stdout(Stdio::piped())
        .stderr(Stdio::inherit())
        .spawn()
        .unwrap_or_else(|e| panic!("{}: {e} (build the binary first)", binary.display()));
    let mut line = String::new();
    BufReader::new(child.stdout.take().unwrap())
        .read_line(&mut line)
        .unwrap();
    let base = line
        .trim()
        .trim_start_matches("robocal listening on ")
        .to_string();
    Server { child, base }
}

/// Peak resident memory of a process (Linux `VmHWM`), MiB.
fn peak_rss_mib(pid: u32) -> Option<f64> {
    let status = std::fs::read_to_string(format!("/proc/{pid}/status")).ok()?;
    let line = status.lines().find(|l| l.starts_with("VmHWM:"))?;
    let kib: f64 = line.split_whitespace().nth(1)?.parse().ok()?;
    Some(kib / 1024.0)
}

fn percentile(sorted: &[f64], p: f64) -> f64 {
    sorted[((sorted.len() - 1) as f64 * p).round() as usize]
}

async fn wait_done(client: &Client, job: &str) -> serde_json::Value {
    let start = Instant::now();
    loop {
        let state: serde_json::Value =
            serde_json::from_str(&client.job(job).await.unwrap()).unwrap();
        if matches!(
            state["state"].as_str(),
            Some("succeeded" | "failed" | "cancelled")
        ) || start.elapsed() > JOB_TIMEOUT
        {
            return state;
        }
        tokio::time::sleep(READ_INTERVAL).await;
    }
}

#[tokio::main]
async fn main() {
    let args = Args::parse();
    let work = tempfile::tempdir().unwrap();
    let campaign = work.path().join("campaign");
    robocal::cli::campaign::simulate(&args.robot, &campaign, args.cal, args.val, 7).unwrap();
    let server = start_server(work.path());
    let client = Client::new(&server.base, None).unwrap();

    // 1. One campaign, upload to report.
    let t0 = Instant::now();
    let session = robocal::cli::upload(
        &client,
        "BENCH-1",
        &campaign,
        robocal::cli::RobotPolicy::CreateIfMissing,
    )
    .await
    .unwrap();
    let t_upload = t0.elapsed();
    let job = client
        .start_calibration(&session, &serde_json::json!({}))
        .await
        .unwrap();
    let done = wait_done(&client, &job).await;
    assert_eq!(done["state"], "succeeded", "{done}");
    let report = client.report("BENCH-1", None).await.unwrap();
    let total = t0.elapsed();
    println!(
        "e2e_bench: {} ({}+{} poses, {}x{}): upload {:.2} s, upload to report {:.2} s; before {:.3} mm -> after {:.4} mm",
        args.robot,
        args.cal,
        args.val,
        report.camera.as_ref().map_or(0, |c| c.image_width),
        report.camera.as_ref().map_or(0, |c| c.image_height),
        t_upload.as_secs_f64(),
        total.as_secs_f64(),
        report.before.norm.mean_mm,
        report.after.norm.mean_mm,
    );

    // 2. Two campaigns calibrating at once; reads timed meanwhile.
    let s2 = robocal::cli::upload(
        &client,
        "BENCH-2",
        &campaign,
        robocal::cli::RobotPolicy::CreateIfMissing,
    )
    .await
    .unwrap();
    let s3 = robocal::cli::upload(
        &client,
        "BENCH-3",
        &campaign,
        robocal::cli::RobotPolicy::CreateIfMissing,
    )
    .await
    .unwrap();
    let j2 = client
        .start_calibration(&s2, &serde_json::json!({}))
        .await
        .unwrap();
    let j3 = client
        .start_calibration(&s3, &serde_json::json!({}))
        .await
        .unwrap();
    let mut latencies_ms = Vec::new();
    loop {
        let t = Instant::now();
        let a: serde_json::Value = serde_json::from_str(&client.job(&j2).await.unwrap()).unwrap();
        latencies_ms.push(t.elapsed().as_secs_f64() * 1e3);
        let t = Instant::now();
        let b: serde_json::Value = serde_json::from_str(&client.job(&j3).await.unwrap()).unwrap();
        latencies_ms.push(t.elapsed().as_secs_f64() * 1e3);
        let finished =
            |v: &serde_json::Value| matches!(v["state"].as_str(), Some("succeeded" | "failed"));
        if finished(&a) && finished(&b) {
            break;
        }
        tokio::time::sleep(READ_INTERVAL).await;
    }
    latencies_ms.sort_by(f64::total_cmp);
    println!(
        "e2e_bench: {} reads during two concurrent calibrations: median {:.1} ms, p95 {:.1} ms, max {:.1} ms",
        latencies_ms.len(),
        percentile(&latencies_ms, 0.5),
        percentile(&latencies_ms, 0.95),
        latencies_ms.last().unwrap()
    );
    println!(
        "e2e_bench: server peak resident memory {:.0} MiB",
        peak_rss_mib(server.child.id()).unwrap_or(f64::NAN)
    );
}
