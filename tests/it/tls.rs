//! HTTPS: the server serves TLS with `--tls-cert`/`--tls-key`, and the
//! client (library and CLI) reaches it with the certificate trusted through
//! `--ca-cert`; an untrusted certificate is a clear error, not a hang.

use std::path::PathBuf;

use robocal::cli::client::{Client, ClientError};
use robocal::server::{start, StartError};

use crate::support::*;

/// A self-signed certificate for `localhost` and its key, as PEM files.
fn self_signed(dir: &tempfile::TempDir) -> (PathBuf, PathBuf) {
    let cert = rcgen::generate_simple_self_signed(vec!["localhost".to_string()]).unwrap();
    let (cert_path, key_path) = (dir.path().join("cert.pem"), dir.path().join("key.pem"));
    std::fs::write(&cert_path, cert.cert.pem()).unwrap();
    std::fs::write(&key_path, cert.key_pair.serialize_pem()).unwrap();
    (cert_path, key_path)
}

// Multi-threaded: the CLI runs as a blocking child process while this
// runtime serves it.
#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn client_and_cli_reach_an_https_server() {
    let certs = tempfile::tempdir().unwrap();
    let (cert, key) = self_signed(&certs);
    let app = spawn_app_with(|c| {
        c.tls_cert = Some(cert.clone());
        c.tls_key = Some(key.clone());
    })
    .await;
    let port = app.base.rsplit(':').next().unwrap().to_string();
    let https = format!("https://localhost:{port}");

    // The library client with the certificate trusted: a real exchange.
    let client = Client::with_ca_cert(&https, None, Some(&cert)).unwrap();
    client.put_robot("TLS-1", &robot_body()).await.unwrap();
    match client.report("TLS-1", None).await {
        Err(ClientError::Problem { status: 404, .. }) => {}
        other => panic!("expected the server's 404, got {other:?}"),
    }

    // Not trusted: a transport error that says why.
    let untrusted = Client::new(&https, None).unwrap();
    match untrusted.put_robot("TLS-2", &robot_body()).await {
        Err(e @ ClientError::Transport(_)) => {
            let message = e.to_string().to_lowercase();
            assert!(message.contains("certificate"), "{message}");
        }
        other => panic!("expected a certificate error, got {other:?}"),
    }
    // Plain HTTP to the TLS port gets no answer.
    assert!(reqwest::get(format!("http://127.0.0.1:{port}/healthz"))
        .await
        .is_err_and(|e| !e.is_status()));

    // The CLI over https, trusting the certificate by flag and by variable.
    let cli = |envs: &[(&str, &str)], extra: &[&str]| {
        let mut cmd = std::process::Command::new(env!("CARGO_BIN_EXE_robocal"));
        cmd.args(["report", "--serial", "TLS-1", "--url", &https])
            .args(extra)
            .env_remove("ROBOCAL_CA_CERT");
        for (k, v) in envs {
            cmd.env(k, v);
        }
        let out = cmd.output().unwrap();
        String::from_utf8_lossy(&out.stderr).to_string()
    };
    let cert_arg = cert.to_str().unwrap();
    for stderr in [
        cli(&[], &["--ca-cert", cert_arg]),
        cli(&[("ROBOCAL_CA_CERT", cert_arg)], &[]),
    ] {
        assert!(stderr.contains("404"), "the server answered: {stderr}");
        assert!(!stderr.contains("cannot reach"), "{stderr}");
    }
    let stderr = cli(&[], &[]);
    assert!(stderr.contains("cannot reach the server"), "{stderr}");
    assert!(stderr.to_lowercase().contains("certificate"), "{stderr}");
}

#[tokio::test]
async fn binary_announces_https_and_bad_key_files_are_refused() {
    let certs = tempfile::tempdir().unwrap();
    let (cert, key) = self_signed(&certs);
    let dir = tempfile::tempdir().unwrap();
    let db = fresh_database(&dir);
    let mut server = spawn_binary(
        &[
            "--bind",
            "127.0.0.1:0",
            "--database-url",
            &db,
            "--workers",
            "1",
            "--tls-cert",
            cert.to_str().unwrap(),
            "--tls-key",
            key.to_str().unwrap(),
        ],
        &[],
    );
    assert!(server.base.starts_with("https://"), "{}", server.base);
    let port = server.base.rsplit(':').next().unwrap();
    let ca = reqwest::Certificate::from_pem(&std::fs::read(&cert).unwrap()).unwrap();
    let c = reqwest::Client::builder()
        .use_rustls_tls()
        .add_root_certificate(ca)
        .build()
        .unwrap();
    let r = c
        .get(format!("https://localhost:{port}/v1/robots"))
        .send()
        .await
        .unwrap();
    assert_eq!(r.status(), 200, "anonymous over https on the loopback");
    server.child.kill().unwrap();
    server.child.wait().unwrap();

    // A key that is not a key, a missing file: refused at start, no panic.
    let not_pem = certs.path().join("junk.pem");
    std::fs::write(&not_pem, "not a key").unwrap();
    for (c, k) in [(&cert, &not_pem), (&certs.path().join("missing.pem"), &key)] {
        let mut config = test_config(&db, &dir);
        config.tls_cert = Some(c.clone());
        config.tls_key = Some(k.clone());
        match start(config).await {
            Err(StartError::Config(message)) => assert!(message.contains("--tls"), "{message}"),
            Err(e) => panic!("wrong error: {e}"),
            Ok(_) => panic!("must refuse to start"),
        }
    }
    let out = run_binary(&["serve", "--tls-cert", cert.to_str().unwrap()]);
    assert!(!out.status.success(), "--tls-cert needs --tls-key");
}
