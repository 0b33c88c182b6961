//! The real binary, killed and restarted on the same database.

use std::time::Duration;

use serde_json::Value;

use crate::support::*;

const WAIT: Duration = Duration::from_secs(30);

#[tokio::test]
async fn job_survives_kill_9_and_uploads_are_byte_identical_after_restart() {
    let dir = tempfile::tempdir().unwrap();
    let db = fresh_database(&dir);
    let args = [
        "--database-url",
        &db,
        "--bind",
        "127.0.0.1:0",
        "--workers",
        "1",
        "--lease-secs",
        "1",
        "--poll-ms",
        "50",
    ];
    let c = reqwest::Client::new();
    let mut first = spawn_binary(&args, &[("ROBOCAL_TEST_STAGE_DELAY_MS", "1500")]);
    let (session, pose, image) = robot_with_session(&c, &first.base, "K1", 42, "cal").await;
    let r = c
        .post(format!("{}/v1/sessions/{session}/calibrations", first.base))
        .send()
        .await
        .unwrap();
    assert_eq!(r.status(), 202);
    let job = r.json::<Value>().await.unwrap()["job_id"]
        .as_str()
        .unwrap()
        .to_string();
    let running = wait_job_at(&c, &first.base, &job, WAIT, |v| {
        v["state"] == "running" && v["progress"].as_f64().unwrap() > 0.0
    })
    .await;
    assert_eq!(running["attempts"], 1);

    first.child.kill().unwrap(); // SIGKILL: no cleanup at all
    first.child.wait().unwrap();

    let mut second = spawn_binary(&args, &[("ROBOCAL_TEST_STAGE_DELAY_MS", "10")]);
    let done = wait_job_at(&c, &second.base, &job, WAIT, is_finished).await;
    assert_eq!(done["state"], "succeeded", "{done}");
    assert_eq!(done["attempts"], 2, "reclaimed after the lease expired");
    let bytes = c
        .get(format!(
            "{}/v1/sessions/{session}/poses/{pose}/image",
            second.base
        ))
        .send()
        .await
        .unwrap()
        .bytes()
        .await
        .unwrap();
    assert_eq!(sha256_hex(&bytes), sha256_hex(&image));
    second.child.kill().unwrap();
    second.child.wait().unwrap();
}

#[tokio::test]
async fn sigterm_releases_the_running_job_and_exits_cleanly() {
    let dir = tempfile::tempdir().unwrap();
    let db = fresh_database(&dir);
    let args = [
        "--database-url",
        &db,
        "--bind",
        "127.0.0.1:0",
        "--workers",
        "1",
        "--lease-secs",
        "30",
        "--poll-ms",
        "50",
        "--shutdown-grace-secs",
        "0",
    ];
    let c = reqwest::Client::new();
    let mut first = spawn_binary(&args, &[("ROBOCAL_TEST_STAGE_DELAY_MS", "3000")]);
    let (session, _, _) = robot_with_session(&c, &first.base, "K1", 1, "cal").await;
    let r = c
        .post(format!("{}/v1/sessions/{session}/calibrations", first.base))
        .send()
        .await
        .unwrap();
    let job = r.json::<Value>().await.unwrap()["job_id"]
        .as_str()
        .unwrap()
        .to_string();
    wait_job_at(&c, &first.base, &job, WAIT, |v| v["state"] == "running").await;
    let pid = first.pid().to_string();
    assert!(std::process::Command::new("kill")
        .args(["-TERM", &pid])
        .status()
        .unwrap()
        .success());
    let status = first.child.wait().unwrap();
    assert!(status.success(), "clean exit on SIGTERM: {status:?}");

    // Released, not abandoned: the next process runs it at once (no 30 s lease wait).
    let mut second = spawn_binary(&args, &[("ROBOCAL_TEST_STAGE_DELAY_MS", "10")]);
    let done = wait_job_at(&c, &second.base, &job, Duration::from_secs(10), is_finished).await;
    assert_eq!(done["state"], "succeeded", "{done}");
    assert_eq!(
        done["attempts"], 1,
        "a released job's attempt is not counted"
    );
    second.child.kill().unwrap();
    second.child.wait().unwrap();
}

#[tokio::test]
async fn a_key_in_flight_at_kill_9_is_free_after_restart() {
    use tokio::io::AsyncWriteExt;

    let dir = tempfile::tempdir().unwrap();
    let db = fresh_database(&dir);
    let args = [
        "--database-url",
        &db,
        "--bind",
        "127.0.0.1:0",
        "--lease-secs",
        "1",
        "--body-idle-timeout-secs",
        "60",
    ];
    let c = reqwest::Client::new();
    let mut first = spawn_binary(&args, &[]);
    // A keyed request whose body never finishes: in flight until the kill.
    let body = serde_json::to_vec(&robot_body()).unwrap();
    let mut stuck = crate::raw_http::connect(&first.base).await;
    let head = format!(
        "PUT /v1/robots/K9 HTTP/1.1\r\nHost: {host}\r\nIdempotency-Key: k9\r\n\
         Content-Type: application/json\r\nContent-Length: {}\r\n\r\n",
        body.len(),
        host = crate::raw_http::addr_of(&first.base)
    );
    stuck.write_all(head.as_bytes()).await.unwrap();
    stuck.write_all(&body[..10]).await.unwrap();
    // Let it claim the key before anything else can.
    tokio::time::sleep(Duration::from_millis(500)).await;
    let put = |base: &str| {
        c.put(format!("{base}/v1/robots/K9"))
            .header("idempotency-key", "k9")
            .json(&robot_body())
            .send()
    };
    let deadline = std::time::Instant::now() + WAIT;
    loop {
        let r = put(&first.base).await.unwrap();
        let status = r.status();
        if status == 409 {
            break;
        }
        let body = r.text().await.unwrap();
        assert!(
            std::time::Instant::now() < deadline,
            "the stuck request never claimed its key: {status} {body}"
        );
        tokio::time::sleep(Duration::from_millis(50)).await;
    }
    first.child.kill().unwrap(); // SIGKILL: the key's mark stays behind
    first.child.wait().unwrap();
    drop(stuck);

    let mut second = spawn_binary(&args, &[]);
    // The dead holder's lease (5 s, the shortest for keys) lapses; the retry
    // then runs (before: 409 for 10 minutes).
    let deadline = std::time::Instant::now() + Duration::from_secs(15);
    let answer = loop {
        let r = put(&second.base).await.unwrap();
        if r.status() != 409 || std::time::Instant::now() > deadline {
            break r;
        }
        tokio::time::sleep(Duration::from_millis(100)).await;
    };
    assert_eq!(answer.status(), 201, "{}", answer.text().await.unwrap());
    second.child.kill().unwrap();
    second.child.wait().unwrap();
}

#[tokio::test]
async fn a_keyed_write_that_committed_before_a_crash_is_not_run_again() {
    let dir = tempfile::tempdir().unwrap();
    let db = fresh_database(&dir);
    let args = [
        "--database-url",
        &db,
        "--bind",
        "127.0.0.1:0",
        "--lease-secs",
        "1",
    ];
    let c = reqwest::Client::new();
    // The process aborts after handling a keyed request, before storing its
    // answer: the write has committed, the key is still pending.
    let mut first = spawn_binary(
        &args,
        &[("ROBOCAL_TEST_CRASH_BEFORE_IDEMPOTENT_ANSWER", "true")],
    );
    let (session, _, _) = robot_with_session(&c, &first.base, "K10", 3, "cal").await;
    let poses_now = |base: String| {
        let c = c.clone();
        let session = session.clone();
        async move {
            let s: Value = c
                .get(format!("{base}/v1/sessions/{session}"))
                .send()
                .await
                .unwrap()
                .json()
                .await
                .unwrap();
            s["pose_count"].as_i64().unwrap()
        }
    };
    let before = poses_now(first.base.clone()).await;
    let post = |base: &str| {
        c.post(format!("{base}/v1/sessions/{session}/poses"))
            .header("idempotency-key", "crash-1")
            .json(&point_pose(7, "cal"))
            .send()
    };
    assert!(post(&first.base).await.is_err(), "the process answered");
    let _ = first.child.wait();

    let mut second = spawn_binary(&args, &[]);
    assert_eq!(
        poses_now(second.base.clone()).await,
        before + 1,
        "the write committed"
    );
    // Past the dead holder's lease (5 s, the shortest for keys) the retry
    // used to run the write again; now it is told the request was done.
    let deadline = std::time::Instant::now() + Duration::from_secs(15);
    let answer = loop {
        let r = post(&second.base).await.unwrap();
        let status = r.status();
        let body: Value = r.json().await.unwrap();
        let in_flight = status == 409 && body["type"] == "urn:robocal:problem:conflict";
        if !in_flight || std::time::Instant::now() > deadline {
            break body;
        }
        tokio::time::sleep(Duration::from_millis(200)).await;
    };
    assert_eq!(
        answer["type"], "urn:robocal:problem:idempotent-request-done",
        "{answer}"
    );
    assert_eq!(answer["status"], 409, "{answer}");
    assert_eq!(
        poses_now(second.base.clone()).await,
        before + 1,
        "run twice"
    );
    second.child.kill().unwrap();
    second.child.wait().unwrap();
}
