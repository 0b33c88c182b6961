//! Every store operation, called directly, on the backend of this test binary
//! (SQLite in `tests/it`, PostgreSQL in `tests/pg`), and the writes that must
//! stay correct when several processes share the database: each "replica"
//! here is its own store (own connection pool) on one database.

use std::collections::BTreeMap;

use futures_util::future::join_all;
use serde_json::json;

use robocal::domain::{
    new_id, now_rfc3339, now_unix_ms, IdempotencyClaim, IdempotencyScope, ImageMeta, JobState,
    JointsDeg, LeaseStatus, Scope, StoredResponse,
};
use robocal::schema::job::JobOptions;
use robocal::schema::pose_body::ImagePointDoc;
use robocal::schema::session::{PoseSet, SessionBody};
use robocal::store::{self, DynStore, StoreError};
use robocal::store::{JobOutcome, NewJob, NewParameterSet, NewPose, RobotRecord};

use crate::support::*;

fn robot(serial: &str) -> RobotRecord {
    RobotRecord {
        serial: serial.to_string(),
        model: "Test arm".into(),
        preset: None,
        kinematics: json!({"joints": []}),
        controller: None,
        prior: None,
        created_at: now_rfc3339(),
        updated_at: now_rfc3339(),
    }
}

fn new_job(session_id: &str, serial: &str) -> NewJob {
    NewJob {
        session_id: session_id.to_string(),
        serial: serial.to_string(),
        options: JobOptions::Calibration(Default::default()),
        max_attempts: 2,
    }
}

fn set(n: usize) -> NewParameterSet {
    NewParameterSet::approved(
        placeholder_set(&format!("n{n}")),
        json!({"rms_mm": n as f64 * 0.01}),
    )
}

fn pose(sha: Option<&ImageMeta>) -> NewPose {
    NewPose {
        joints_deg: JointsDeg::stored(vec![1.0, 2.0, 3.0, 4.0, 5.0, 6.5]),
        set: PoseSet::Cal,
        image: sha.cloned(),
        points: vec![ImagePointDoc {
            row: 0,
            col: 1,
            x: 1.5,
            y: 2.25,
        }],
        measured: None,
        label: None,
        image_detection: None,
        flange_pose: None,
        stage_reading: None,
        group: None,
    }
}

/// `n` stores on one fresh database, connected (and migrating) all at once.
async fn replicas(db: &str, n: usize) -> Vec<DynStore> {
    join_all((0..n).map(|_| store::connect(db)))
        .await
        .into_iter()
        .map(|s| s.expect("store connects and migrates"))
        .collect()
}

#[tokio::test]
async fn every_store_operation_round_trips() {
    let dir = tempfile::tempdir().unwrap();
    let db = fresh_database(&dir);
    let s = store::connect(&db).await.unwrap();
    s.ping().await.unwrap();

    // Robots: create, replace, page, delete.
    assert!(s.put_robot(&robot("R2")).await.unwrap(), "created");
    assert!(!s.put_robot(&robot("R2")).await.unwrap(), "replaced");
    assert!(s.put_robot(&robot("R1")).await.unwrap());
    assert!(s.put_robot(&robot("R-3")).await.unwrap());
    let page = s.list_robots(2, None).await.unwrap();
    let serials: Vec<_> = page.items.iter().map(|r| r.serial.as_str()).collect();
    assert_eq!(serials, ["R-3", "R1"], "byte order");
    let rest = s.list_robots(2, page.next_cursor.as_deref()).await.unwrap();
    assert_eq!(rest.items.len(), 1);
    assert!(rest.next_cursor.is_none());
    assert_eq!(
        s.get_robot("R1").await.unwrap().unwrap().kinematics,
        json!({"joints": []})
    );
    assert!(s.delete_robot("R-3").await.unwrap());
    assert!(!s.delete_robot("R-3").await.unwrap());
    assert!(s.get_robot("R-3").await.unwrap().is_none());

    // Sessions.
    // Text beyond ASCII survives the round trip.
    let spec = SessionBody {
        camera_calibration_id: Some("Zürich-1/3".into()),
        ..SessionBody::default()
    };
    let session = s.create_session("R1", "camera", &spec).await.unwrap();
    assert!(matches!(
        s.create_session("nope", "camera", &spec).await,
        Err(StoreError::NotFound("robot"))
    ));
    let got = s.get_session(&session.id).await.unwrap().unwrap();
    assert_eq!((got.spec, got.pose_count), (spec.clone(), 0));
    let second = s
        .create_session("R1", "tracker", &SessionBody::default())
        .await
        .unwrap();
    let listed = s.list_sessions("R1", 10, None).await.unwrap();
    assert_eq!(listed.items.len(), 2);
    let after = s.list_sessions("R1", 10, Some(&session.id)).await.unwrap();
    assert_eq!(after.items[0].id, second.id);

    // Blobs (content-addressed, idempotent) and poses.
    let bytes: Vec<u8> = (0..=255u8).cycle().take(70_000).collect();
    let meta = ImageMeta {
        sha256: sha256_hex(&bytes),
        size_bytes: bytes.len() as i64,
        content_type: "image/png".into(),
        width: 4,
        height: 3,
    };
    s.put_blob(&meta, &bytes).await.unwrap();
    s.put_blob(&meta, &bytes).await.unwrap();
    assert_eq!(s.get_blob(&meta.sha256).await.unwrap().unwrap(), bytes);
    assert!(s.get_blob("0000").await.unwrap().is_none());
    let poses = s
        .add_poses(&session.id, &[pose(Some(&meta)), pose(None), pose(None)])
        .await
        .unwrap();
    assert!(matches!(
        s.add_poses("nope", &[pose(None)]).await,
        Err(StoreError::NotFound("session"))
    ));
    let p0 = s
        .get_pose(&session.id, &poses[0].id)
        .await
        .unwrap()
        .unwrap();
    assert_eq!(p0.image, Some(meta.clone()));
    assert_eq!(p0.joints_deg, vec![1.0, 2.0, 3.0, 4.0, 5.0, 6.5]);
    assert!(s
        .get_pose(&second.id, &poses[0].id)
        .await
        .unwrap()
        .is_none());
    let page = s.list_poses(&session.id, 2, None).await.unwrap();
    let rest = s
        .list_poses(&session.id, 2, page.next_cursor.as_deref())
        .await
        .unwrap();
    assert_eq!(page.items.len() + rest.items.len(), 3);
    assert_eq!(
        s.get_session(&session.id)
            .await
            .unwrap()
            .unwrap()
            .pose_count,
        3
    );

    // Jobs: bound, claim, renew, finish with a parameter set, retry, release, cancel.
    let j1 = s.enqueue_job(&new_job(&session.id, "R1"), 2).await.unwrap();
    let j2 = s.enqueue_job(&new_job(&session.id, "R1"), 2).await.unwrap();
    assert!(matches!(
        s.enqueue_job(&new_job(&session.id, "R1"), 2).await,
        Err(StoreError::QueueFull)
    ));
    assert_eq!(
        s.get_job(&j1.id).await.unwrap().unwrap().state,
        JobState::Queued
    );
    let now = now_unix_ms();
    let c1 = s.claim_job("w1", now, now + 60_000).await.unwrap().unwrap();
    assert_eq!(
        (c1.id.as_str(), c1.attempt),
        (j1.id.as_str(), 1),
        "oldest first"
    );
    assert_eq!(
        s.renew_lease(&c1.id, "w1", now + 90_000, "validate", 0.5)
            .await
            .unwrap(),
        LeaseStatus::Held
    );
    assert_eq!(
        s.renew_lease(&c1.id, "other", now + 90_000, "validate", 0.5)
            .await
            .unwrap(),
        LeaseStatus::Lost
    );
    let running = s.get_job(&c1.id).await.unwrap().unwrap();
    assert_eq!(
        (running.stage.as_deref(), running.progress),
        (Some("validate"), 0.5)
    );
    let done = JobOutcome::Succeeded {
        parameter_set: Some(set(1)),
        summary: Default::default(),
        detections: vec![],
        check: None,
    };
    assert_eq!(
        s.finish_job(&c1.id, "w1", &done).await.unwrap(),
        LeaseStatus::Held
    );
    let finished = s.get_job(&c1.id).await.unwrap().unwrap();
    assert_eq!(finished.state, JobState::Succeeded);
    assert_eq!(finished.result.unwrap().calibration().version, Some(1));
    assert_eq!(
        s.finish_job(&c1.id, "w1", &done).await.unwrap(),
        LeaseStatus::Lost
    );

    let c2 = s.claim_job("w2", now, now + 60_000).await.unwrap().unwrap();
    assert_eq!(c2.id, j2.id);
    let retry = JobOutcome::Retry {
        error: "flaky".into(),
    };
    s.finish_job(&c2.id, "w2", &retry).await.unwrap();
    assert_eq!(
        s.get_job(&c2.id).await.unwrap().unwrap().state,
        JobState::Queued
    );
    let c2 = s.claim_job("w2", now, now + 60_000).await.unwrap().unwrap();
    assert_eq!(c2.attempt, 2);
    s.release_job(&c2.id, "w2").await.unwrap();
    let released = s.claim_job("w3", now, now + 60_000).await.unwrap().unwrap();
    assert_eq!(
        (released.id.as_str(), released.attempt),
        (j2.id.as_str(), 2)
    );
    // Lease expired on the last attempt: failed by the sweep, not reclaimed.
    let later = now + 120_000;
    assert!(s.claim_job("w4", later, later + 1).await.unwrap().is_none());
    assert_eq!(s.fail_exhausted_jobs(later).await.unwrap(), 1);
    let failed = s.get_job(&j2.id).await.unwrap().unwrap();
    assert_eq!(failed.state, JobState::Failed);
    assert!(failed.error.unwrap().contains("flaky"));
    let j3 = s.enqueue_job(&new_job(&session.id, "R1"), 2).await.unwrap();
    assert_eq!(
        s.cancel_job(&j3.id).await.unwrap().unwrap().state,
        JobState::Cancelled
    );
    assert!(matches!(
        s.cancel_job(&j3.id).await,
        Err(StoreError::Conflict(_))
    ));
    assert!(s.cancel_job("nope").await.unwrap().is_none());
    let counts: BTreeMap<_, _> = s
        .job_counts()
        .await
        .unwrap()
        .into_iter()
        .map(|(st, n)| (st.as_str(), n))
        .collect();
    assert_eq!(counts["succeeded"], 1);
    assert_eq!(counts["failed"], 1);
    assert_eq!(counts["cancelled"], 1);
    assert_eq!(counts["queued"] + counts["running"], 0);

    // Results.
    assert_eq!(
        s.insert_parameter_set("R1", None, &set(2)).await.unwrap(),
        2
    );
    assert_eq!(
        s.insert_parameter_set("R9", None, &set(3)).await.unwrap(),
        1
    );
    let latest = s.get_parameter_set("R1", None).await.unwrap().unwrap();
    assert_eq!((latest.version, latest.parameters.session_id()), (2, "n2"));
    let v1 = s.get_parameter_set("R1", Some(1)).await.unwrap().unwrap();
    assert_eq!(v1.job_id.as_deref(), Some(j1.id.as_str()));
    assert!(s.get_parameter_set("R1", Some(3)).await.unwrap().is_none());
    let page = s.list_parameter_sets("R1", 1, None).await.unwrap();
    assert_eq!(page.items[0].version, 2);
    let rest = s
        .list_parameter_sets(
            "R1",
            1,
            page.next_cursor.as_deref().map(|c| c.parse().unwrap()),
        )
        .await
        .unwrap();
    assert_eq!(rest.items[0].version, 1);
    assert_eq!(
        s.get_report("R1", 2).await.unwrap().unwrap(),
        json!({"rms_mm": 0.02})
    );
    assert!(s.get_report("R1", 7).await.unwrap().is_none());

    // Tokens and idempotency keys.
    let t = s.create_token("ci", "hash-1", Scope::Write).await.unwrap();
    assert_eq!(s.find_token("hash-1").await.unwrap().unwrap().id, t.id);
    assert!(s.find_token("hash-2").await.unwrap().is_none());
    assert_eq!(s.list_tokens().await.unwrap().len(), 1);
    assert_eq!(s.count_tokens().await.unwrap(), 1);
    let key = IdempotencyScope {
        principal: "anon".into(),
        method: "POST".into(),
        path: "/v1/x".into(),
        key: "k1".into(),
        holder: "request-1".into(),
    };
    let live = now_unix_ms() + 60_000;
    assert!(matches!(
        s.claim_idempotency(&key, live).await.unwrap(),
        IdempotencyClaim::Fresh
    ));
    assert!(matches!(
        s.claim_idempotency(&key, live).await.unwrap(),
        IdempotencyClaim::InFlight
    ));
    let elsewhere = IdempotencyScope {
        path: "/v1/y".into(),
        ..key.clone()
    };
    assert!(matches!(
        s.claim_idempotency(&elsewhere, live).await.unwrap(),
        IdempotencyClaim::OtherRequest { .. }
    ));
    s.abandon_idempotency(&key).await.unwrap();
    // A holder whose lease lapsed (its process died) frees the key.
    let lapsed = IdempotencyScope {
        holder: "request-2".into(),
        ..key.clone()
    };
    assert!(matches!(
        s.claim_idempotency(&lapsed, now_unix_ms() - 1)
            .await
            .unwrap(),
        IdempotencyClaim::Fresh
    ));
    assert!(matches!(
        s.claim_idempotency(&key, live).await.unwrap(),
        IdempotencyClaim::Fresh
    ));
    // Only the holder completes it.
    s.complete_idempotency(
        &lapsed,
        Some("other"),
        &StoredResponse {
            status: 500,
            headers: vec![],
            body: vec![],
        },
    )
    .await
    .unwrap();
    let response = StoredResponse {
        status: 201,
        headers: vec![("location".into(), "/v1/x/1".into())],
        body: b"{\"id\":1}\x00\xff".to_vec(),
    };
    s.complete_idempotency(&key, Some("fp-1"), &response)
        .await
        .unwrap();
    match s.claim_idempotency(&key, live).await.unwrap() {
        IdempotencyClaim::Done {
            fingerprint,
            response: r,
        } => {
            assert_eq!(fingerprint.as_deref(), Some("fp-1"));
            assert_eq!(
                (r.status, r.headers, r.body),
                (response.status, response.headers, response.body)
            )
        }
        other => panic!("expected a replay, got {other:?}"),
    }
}

#[tokio::test]
async fn replicas_starting_at_once_migrate_once() {
    let dir = tempfile::tempdir().unwrap();
    let db = fresh_database(&dir);
    let stores = replicas(&db, 4).await;
    for s in &stores {
        s.ping().await.unwrap();
    }
    // And again, on the migrated database.
    replicas(&db, 2).await;
}

#[tokio::test]
async fn concurrent_replicas_number_parameter_sets_without_gaps() {
    const WRITERS: usize = 200;
    const SERIALS: usize = 4;
    let dir = tempfile::tempdir().unwrap();
    let db = fresh_database(&dir);
    let stores = replicas(&db, 3).await;
    let results = join_all((0..WRITERS).map(|i| {
        let s = stores[i % stores.len()].clone();
        async move {
            let serial = format!("S{}", i % SERIALS);
            let v = s.insert_parameter_set(&serial, None, &set(i)).await?;
            Ok::<_, StoreError>((serial, v, i))
        }
    }))
    .await;
    let mut by_serial: BTreeMap<String, Vec<i64>> = BTreeMap::new();
    for r in results {
        let (serial, v, i) = r.expect("no write fails");
        let stored = stores[0]
            .get_parameter_set(&serial, Some(v))
            .await
            .unwrap()
            .unwrap();
        assert_eq!(
            stored.parameters.session_id(),
            format!("n{i}"),
            "version {v} of {serial} holds its own write"
        );
        by_serial.entry(serial).or_default().push(v);
    }
    for (serial, mut versions) in by_serial {
        versions.sort();
        let expected: Vec<i64> = (1..=(WRITERS / SERIALS) as i64).collect();
        assert_eq!(versions, expected, "{serial}: 1..n, no gap, no duplicate");
    }
}

#[tokio::test]
async fn concurrent_claimers_take_each_job_exactly_once() {
    const JOBS: usize = 40;
    let dir = tempfile::tempdir().unwrap();
    let db = fresh_database(&dir);
    let stores = replicas(&db, 3).await;
    stores[0].put_robot(&robot("C1")).await.unwrap();
    let session = stores[0]
        .create_session("C1", "camera", &SessionBody::default())
        .await
        .unwrap();
    let enqueued = join_all((0..JOBS).map(|i| {
        let s = stores[i % 3].clone();
        let job = new_job(&session.id, "C1");
        async move { s.enqueue_job(&job, 1000).await.unwrap().id }
    }))
    .await;
    // Six workers over three replicas claim and finish until the queue is empty.
    let claimed = join_all((0..6).map(|w| {
        let s = stores[w % 3].clone();
        async move {
            let worker = format!("w{w}-{}", new_id());
            let mut mine = Vec::new();
            loop {
                let now = now_unix_ms();
                let Some(job) = s.claim_job(&worker, now, now + 60_000).await.unwrap() else {
                    break mine;
                };
                assert_eq!(job.attempt, 1, "a job is claimed once");
                let outcome = JobOutcome::Succeeded {
                    parameter_set: Some(set(0)),
                    summary: Default::default(),
                    detections: vec![],
                    check: None,
                };
                assert_eq!(
                    s.finish_job(&job.id, &worker, &outcome).await.unwrap(),
                    LeaseStatus::Held
                );
                mine.push(job.id);
            }
        }
    }))
    .await;
    let mut all: Vec<String> = claimed.into_iter().flatten().collect();
    all.sort();
    let mut expected = enqueued.clone();
    expected.sort();
    assert_eq!(all, expected, "every job claimed by exactly one worker");
    let page = stores[1]
        .list_parameter_sets("C1", 1000, None)
        .await
        .unwrap();
    let mut versions: Vec<i64> = page.items.iter().map(|p| p.version).collect();
    versions.sort();
    assert_eq!(versions, (1..=JOBS as i64).collect::<Vec<_>>());
}

#[tokio::test]
async fn an_idempotency_key_is_claimed_once_across_replicas() {
    let dir = tempfile::tempdir().unwrap();
    let db = fresh_database(&dir);
    let stores = replicas(&db, 3).await;
    let key = IdempotencyScope {
        principal: "anon".into(),
        method: "POST".into(),
        path: "/v1/robots/X/sessions".into(),
        key: new_id(),
        holder: new_id(),
    };
    let claims = join_all((0..12).map(|i| {
        let s = stores[i % 3].clone();
        let key = key.clone();
        async move {
            s.claim_idempotency(&key, now_unix_ms() + 60_000)
                .await
                .unwrap()
        }
    }))
    .await;
    let fresh = claims
        .iter()
        .filter(|c| matches!(c, IdempotencyClaim::Fresh))
        .count();
    assert_eq!(fresh, 1, "{claims:?}");
}
