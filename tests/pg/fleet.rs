//! A fleet: several real `robocal` processes on one PostgreSQL database,
//! killed and restarted while they work, and hammered by concurrent writers.

use std::collections::{BTreeMap, BTreeSet};
use std::process::Command;
use std::sync::Arc;
use std::time::{Duration, Instant};

use futures_util::future::join_all;
use serde_json::{json, Value};
use sqlx::{Connection, PgConnection};
use tokio::sync::Notify;

use robocal::schema::session::SessionBody;
use robocal::store;
use robocal::store::NewJob;

use crate::on_postgres;
use crate::processes::{spawn_binaries, BinaryServer};
use crate::support::*;

const WAIT: Duration = Duration::from_secs(60);

fn replica_args<'a>(db: &'a str, workers: &'a str) -> [&'a str; 14] {
    [
        "--database-url",
        db,
        "--bind",
        "127.0.0.1:0",
        "--workers",
        workers,
        "--lease-secs",
        "2",
        "--poll-ms",
        "250",
        "--max-queued",
        "1000",
        "--shutdown-grace-secs",
        "0",
    ]
}

/// `n` replicas on `db`, started together (so they migrate together);
/// jobs stop after validation and store a parameter set.
fn start_replicas(n: usize, db: &str, workers: &str, stage_delay_ms: &str) -> Vec<BinaryServer> {
    spawn_binaries(
        n,
        &replica_args(db, workers),
        &[
            ("ROBOCAL_TEST_STAGE_DELAY_MS", stage_delay_ms),
            ("ROBOCAL_TEST_PARAMETER_SETS", "true"),
            // Every writer of these tests connects from 127.0.0.1, where a
            // plant's clients come from many addresses: the per-address cap
            // (a hostile client's limit, 64 by default) is not under test.
            (
                "ROBOCAL_MAX_CONNECTIONS_PER_ADDRESS",
                FLEET_CONNECTIONS_PER_ADDRESS,
            ),
        ],
    )
}

/// Connections one address may hold on a test replica: above the 300
/// concurrent requests of [`two_hundred_concurrent_writers_across_replicas`].
const FLEET_CONNECTIONS_PER_ADDRESS: &str = "512";

/// Waits until every job is finished; returns them by id.
async fn wait_all(c: &reqwest::Client, base: &str, jobs: &[String]) -> BTreeMap<String, Value> {
    let start = Instant::now();
    loop {
        let states = join_all(jobs.iter().map(|j| async move {
            let v: Value = c
                .get(format!("{base}/v1/jobs/{j}"))
                .send()
                .await
                .unwrap()
                .json()
                .await
                .unwrap();
            (j.clone(), v)
        }))
        .await;
        if states.iter().all(|(_, v)| is_finished(v)) {
            return states.into_iter().collect();
        }
        assert!(
            start.elapsed() < WAIT,
            "jobs still unfinished after {WAIT:?}"
        );
        tokio::time::sleep(Duration::from_millis(200)).await;
    }
}

/// Every parameter set of `serial` (newest first over HTTP, all pages).
async fn parameter_sets(c: &reqwest::Client, base: &str, serial: &str) -> Vec<Value> {
    let v: Value = c
        .get(format!(
            "{base}/v1/robots/{serial}/parameter-sets?limit=1000"
        ))
        .send()
        .await
        .unwrap()
        .json()
        .await
        .unwrap();
    v["items"].as_array().cloned().unwrap_or_default()
}

/// Checks versions 1..n with no gap or duplicate, and that the sets name
/// exactly the given jobs, each once.
fn assert_versions_and_jobs(serial: &str, sets: &[Value], jobs: &BTreeSet<String>) {
    let mut versions: Vec<i64> = sets
        .iter()
        .map(|s| s["version"].as_i64().unwrap())
        .collect();
    versions.sort();
    assert_eq!(
        versions,
        (1..=jobs.len() as i64).collect::<Vec<_>>(),
        "{serial}: versions"
    );
    let mut named: Vec<String> = sets
        .iter()
        .map(|s| s["job_id"].as_str().unwrap().to_string())
        .collect();
    named.sort();
    let expected: Vec<String> = jobs.iter().cloned().collect();
    assert_eq!(named, expected, "{serial}: one parameter set per job");
}

async fn running_on(db: &str, pid: u32) -> i64 {
    let mut conn = PgConnection::connect(db).await.unwrap();
    sqlx::query_scalar("SELECT count(*) FROM jobs WHERE state = 'running' AND worker_id LIKE $1")
        .bind(format!("{pid}-%"))
        .fetch_one(&mut conn)
        .await
        .unwrap()
}

#[tokio::test]
async fn three_replicas_survive_kill_9_and_restart_every_job_succeeds_once() {
    if !on_postgres("three_replicas_survive_kill_9_and_restart_every_job_succeeds_once") {
        return;
    }
    const SERIALS: usize = 5;
    const JOBS: usize = 30;
    let dir = tempfile::tempdir().unwrap();
    let db = fresh_database(&dir);
    let c = reqwest::Client::new();
    // 5 poses x 150 ms: each job runs ~0.75 s, long enough to be killed mid-run.
    let mut fleet = start_replicas(3, &db, "2", "150");

    let mut sessions = Vec::new();
    for i in 0..SERIALS {
        let base = &fleet[i % 3].base;
        sessions.push(robot_with_session(&c, base, &format!("F{i}"), i as u8, "val").await);
    }
    let submitted = join_all((0..JOBS).map(|i| {
        let (c, base, session) = (
            &c,
            fleet[i % 3].base.clone(),
            sessions[i % SERIALS].0.clone(),
        );
        async move {
            let r = c
                .post(format!("{base}/v1/sessions/{session}/calibrations"))
                .send()
                .await
                .unwrap();
            assert_eq!(r.status(), 202);
            (
                format!("F{}", i % SERIALS),
                r.json::<Value>().await.unwrap()["job_id"]
                    .as_str()
                    .unwrap()
                    .to_string(),
            )
        }
    }))
    .await;

    // kill -9 replica 0 while it holds running jobs.
    let start = Instant::now();
    while running_on(&db, fleet[0].pid()).await == 0 {
        assert!(start.elapsed() < WAIT, "replica 0 never ran a job");
        tokio::time::sleep(Duration::from_millis(20)).await;
    }
    let mut victim = fleet.remove(0);
    victim.child.kill().unwrap(); // SIGKILL
    victim.child.wait().unwrap();
    // What it held when it died stays "running" under its lease until reclaimed.
    let mut conn = PgConnection::connect(&db).await.unwrap();
    let killed_jobs: Vec<String> =
        sqlx::query_scalar("SELECT id FROM jobs WHERE state = 'running' AND worker_id LIKE $1")
            .bind(format!("{}-%", victim.pid()))
            .fetch_all(&mut conn)
            .await
            .unwrap();
    assert!(!killed_jobs.is_empty(), "killed mid-run");

    // Restart replica 1: SIGTERM (running jobs released), then a new process.
    let pid = fleet[0].pid().to_string();
    assert!(Command::new("kill")
        .args(["-TERM", &pid])
        .status()
        .unwrap()
        .success());
    let status = fleet[0].child.wait().unwrap();
    assert!(status.success(), "clean exit on SIGTERM: {status:?}");
    fleet.remove(0);
    fleet.extend(start_replicas(1, &db, "2", "150"));

    let all_jobs: Vec<String> = submitted.iter().map(|(_, j)| j.clone()).collect();
    let done = wait_all(&c, &fleet[0].base, &all_jobs).await;
    for (id, job) in &done {
        assert_eq!(job["state"], "succeeded", "{id}: {job}");
    }
    for id in &killed_jobs {
        assert!(
            done[id]["attempts"].as_i64().unwrap() >= 2,
            "{id} was reclaimed after kill -9"
        );
    }
    let mut by_serial: BTreeMap<String, BTreeSet<String>> = BTreeMap::new();
    for (serial, job) in &submitted {
        by_serial
            .entry(serial.clone())
            .or_default()
            .insert(job.clone());
    }
    for (serial, jobs) in &by_serial {
        let sets = parameter_sets(&c, &fleet[1].base, serial).await;
        assert_versions_and_jobs(serial, &sets, jobs);
        for j in jobs {
            let version = done[j]["result"]["version"].as_i64().unwrap();
            let set = sets.iter().find(|s| s["version"] == version).unwrap();
            assert_eq!(
                set["job_id"],
                json!(j),
                "{serial} v{version} belongs to the job that reports it"
            );
        }
    }
    // Every accepted upload reads back byte-identical, from every replica.
    for (session, pose, image) in &sessions {
        for r in &fleet {
            let bytes = c
                .get(format!(
                    "{}/v1/sessions/{session}/poses/{pose}/image",
                    r.base
                ))
                .send()
                .await
                .unwrap()
                .bytes()
                .await
                .unwrap();
            assert_eq!(sha256_hex(&bytes), sha256_hex(image));
        }
    }
}

#[tokio::test]
async fn two_hundred_concurrent_writers_across_replicas() {
    if !on_postgres("two_hundred_concurrent_writers_across_replicas") {
        return;
    }
    const WRITERS: usize = 200;
    let dir = tempfile::tempdir().unwrap();
    let db = fresh_database(&dir);
    let c = reqwest::Client::new();
    let fleet = start_replicas(3, &db, "1", "0");
    let mut sessions = Vec::new();
    for (i, replica) in fleet.iter().take(2).enumerate() {
        let serial = format!("W{i}");
        sessions.push(
            robot_with_session(&c, &replica.base, &serial, 100 + i as u8, "val")
                .await
                .0,
        );
    }
    // Even writers create sessions (each sent twice, to two replicas, with one
    // Idempotency-Key, as a client retrying on another replica would); odd
    // writers start calibration jobs, each of which stores a parameter set.
    let outcomes = join_all((0..WRITERS).map(|i| {
        let c = &c;
        let sessions = &sessions;
        let fleet = &fleet;
        async move {
            let serial = format!("W{}", (i / 2) % 2);
            if i % 2 == 0 {
                let key = format!("writer-{i}");
                let send = |r: usize| {
                    c.post(format!("{}/v1/robots/{serial}/sessions", fleet[r].base))
                        .header("Idempotency-Key", key.clone())
                        .json(&session_body())
                        .send()
                };
                let (a, b) = tokio::join!(send(i % 3), send((i + 1) % 3));
                let mut ids = Vec::new();
                for r in [a.unwrap(), b.unwrap()] {
                    let status = r.status().as_u16();
                    assert!(
                        status == 201 || status == 409,
                        "session write {i}: {status}"
                    );
                    if status == 201 {
                        ids.push(
                            r.json::<Value>().await.unwrap()["id"]
                                .as_str()
                                .unwrap()
                                .to_string(),
                        );
                    }
                }
                ids.dedup();
                assert!(ids.len() <= 1, "one key, one session: {ids:?}");
                (serial, "session", ids)
            } else {
                let session = &sessions[(i / 2) % 2];
                let r = c
                    .post(format!(
                        "{}/v1/sessions/{session}/calibrations",
                        fleet[i % 3].base
                    ))
                    .send()
                    .await
                    .unwrap();
                assert_eq!(r.status(), 202, "job write {i}");
                let job = r.json::<Value>().await.unwrap()["job_id"]
                    .as_str()
                    .unwrap()
                    .to_string();
                (serial, "job", vec![job])
            }
        }
    }))
    .await;
    // Sessions: every acknowledged one is there, and only those (plus the two
    // made in setup); a key that got only 409s (both in flight) made one too.
    for (k, serial) in ["W0", "W1"].iter().enumerate() {
        let listed: Value = c
            .get(format!(
                "{}/v1/robots/{serial}/sessions?limit=1000",
                fleet[2].base
            ))
            .send()
            .await
            .unwrap()
            .json()
            .await
            .unwrap();
        let listed: BTreeSet<String> = listed["items"]
            .as_array()
            .unwrap()
            .iter()
            .map(|s| s["id"].as_str().unwrap().to_string())
            .collect();
        let acknowledged: BTreeSet<String> = outcomes
            .iter()
            .filter(|(s, kind, _)| s == serial && *kind == "session")
            .flat_map(|(_, _, ids)| ids.iter().cloned())
            .collect();
        assert!(
            acknowledged.is_subset(&listed),
            "{serial}: no acknowledged session lost"
        );
        assert_eq!(
            listed.len(),
            1 + WRITERS / 4,
            "{serial}: one session per key, none doubled"
        );
        assert!(listed.contains(&sessions[k]));
    }
    // Jobs: all succeed; parameter-set versions per serial are 1..n, one per job.
    let jobs: Vec<(String, String)> = outcomes
        .iter()
        .filter(|(_, kind, _)| *kind == "job")
        .map(|(s, _, ids)| (s.clone(), ids[0].clone()))
        .collect();
    let ids: Vec<String> = jobs.iter().map(|(_, j)| j.clone()).collect();
    let done = wait_all(&c, &fleet[0].base, &ids).await;
    assert!(done.values().all(|j| j["state"] == "succeeded"));
    for serial in ["W0", "W1"] {
        let mine: BTreeSet<String> = jobs
            .iter()
            .filter(|(s, _)| s == serial)
            .map(|(_, j)| j.clone())
            .collect();
        let sets = parameter_sets(&c, &fleet[1].base, serial).await;
        assert_versions_and_jobs(serial, &sets, &mine);
    }
}

/// A job enqueued by one process is claimed by another within a fraction of
/// its idle poll: the wake-up came over LISTEN/NOTIFY, not from polling.
#[tokio::test]
async fn notify_wakes_other_replicas_without_polling() {
    if !on_postgres("notify_wakes_other_replicas_without_polling") {
        return;
    }
    let dir = tempfile::tempdir().unwrap();
    let db = fresh_database(&dir);
    let a = store::connect(&db).await.unwrap();
    let b = store::connect(&db).await.unwrap();
    let wake = Arc::new(Notify::new());
    let (_stop, stop_rx) = tokio::sync::watch::channel(false);
    assert!(b.watch_jobs(wake.clone(), stop_rx));
    a.put_robot(&robocal::store::RobotRecord {
        serial: "N1".into(),
        model: "m".into(),
        preset: None,
        kinematics: json!({}),
        controller: None,
        prior: None,
        created_at: "t".into(),
        updated_at: "t".into(),
    })
    .await
    .unwrap();
    let session = a
        .create_session("N1", "camera", &SessionBody::default())
        .await
        .unwrap();
    // The listener connects in the background; enqueue until it hears one.
    let start = Instant::now();
    loop {
        let job = NewJob {
            session_id: session.id.clone(),
            serial: "N1".into(),
            options: robocal::schema::job::JobOptions::Calibration(Default::default()),
            max_attempts: 1,
        };
        a.enqueue_job(&job, 1000).await.unwrap();
        if tokio::time::timeout(Duration::from_millis(500), wake.notified())
            .await
            .is_ok()
        {
            break;
        }
        assert!(
            start.elapsed() < Duration::from_secs(10),
            "no notification arrived"
        );
    }
    // And a second one arrives promptly once listening (after the first
    // round's stray wake-ups are drained).
    tokio::time::sleep(Duration::from_millis(300)).await;
    let _ = tokio::time::timeout(Duration::from_millis(10), wake.notified()).await;
    let t = Instant::now();
    let job = NewJob {
        session_id: session.id.clone(),
        serial: "N1".into(),
        options: robocal::schema::job::JobOptions::Calibration(Default::default()),
        max_attempts: 1,
    };
    a.enqueue_job(&job, 1000).await.unwrap();
    tokio::time::timeout(Duration::from_secs(2), wake.notified())
        .await
        .expect("notified");
    assert!(t.elapsed() < Duration::from_secs(2));
}
