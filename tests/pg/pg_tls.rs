//! PostgreSQL over TLS (sqlx with rustls and `ring`): `sslmode` in the
//! database URL. `disable` and `prefer` connect; `require` encrypts when the
//! server offers TLS and fails with a clear error when it does not;
//! `verify-full` refuses a certificate no trusted root signed.

use sqlx::{Connection, PgConnection};
use tokio::io::{AsyncReadExt, AsyncWriteExt};

use robocal::store;

use crate::it::test_db::TestDb;
use crate::on_postgres;

/// Bytes of the SSLRequest a client sends first (length + code).
const SSL_REQUEST_LEN: usize = 8;

fn with_sslmode(url: &str, mode: &str) -> String {
    let mut url = reqwest::Url::parse(url).unwrap();
    url.query_pairs_mut().append_pair("sslmode", mode);
    url.to_string()
}

async fn server_has_ssl(url: &str) -> bool {
    let mut conn = PgConnection::connect(url).await.unwrap();
    let ssl: String = sqlx::query_scalar("SHOW ssl")
        .fetch_one(&mut conn)
        .await
        .unwrap();
    ssl == "on"
}

#[tokio::test]
async fn sslmode_disable_and_prefer_connect() {
    if !on_postgres("sslmode_disable_and_prefer_connect") {
        return;
    }
    let db = TestDb::postgres();
    for mode in ["disable", "prefer"] {
        let url = with_sslmode(&db, mode);
        let s = store::connect(&url)
            .await
            .unwrap_or_else(|e| panic!("{mode}: {e}"));
        s.ping().await.unwrap();
    }
}

#[tokio::test]
async fn sslmode_require_encrypts_when_the_server_offers_tls() {
    if !on_postgres("sslmode_require_encrypts_when_the_server_offers_tls") {
        return;
    }
    let db = TestDb::postgres();
    let url = with_sslmode(&db, "require");
    if !server_has_ssl(&db).await {
        let e = store::connect(&url).await.err().expect("TLS required");
        assert!(e.to_string().contains("TLS"), "{e}");
        return;
    }
    store::connect(&url).await.unwrap().ping().await.unwrap();
    let mut conn = PgConnection::connect(&url).await.unwrap();
    let encrypted: bool =
        sqlx::query_scalar("SELECT ssl FROM pg_stat_ssl WHERE pid = pg_backend_pid()")
            .fetch_one(&mut conn)
            .await
            .unwrap();
    assert!(encrypted, "sslmode=require runs over TLS");
    // A certificate no public root signed (a local server's) is refused under verify-full.
    let e = store::connect(&with_sslmode(&db, "verify-full"))
        .await
        .err()
        .expect("an untrusted certificate is refused");
    assert!(e.to_string().to_lowercase().contains("certificate"), "{e}");
}

#[tokio::test]
async fn sslmode_require_against_a_server_without_tls_is_a_clear_error() {
    if !on_postgres("sslmode_require_against_a_server_without_tls_is_a_clear_error") {
        return;
    }
    // A stand-in that answers the SSLRequest as PostgreSQL with ssl=off does.
    let listener = tokio::net::TcpListener::bind("127.0.0.1:0").await.unwrap();
    let port = listener.local_addr().unwrap().port();
    let server = tokio::spawn(async move {
        let (mut socket, _) = listener.accept().await.unwrap();
        let mut request = [0u8; SSL_REQUEST_LEN];
        socket.read_exact(&mut request).await.unwrap();
        socket.write_all(b"N").await.unwrap();
        let mut rest = Vec::new();
        let _ = socket.read_to_end(&mut rest).await;
    });
    let url = format!("postgres://postgres@127.0.0.1:{port}/test?sslmode=require");
    let started = std::time::Instant::now();
    let e = store::connect(&url).await.err().expect("must fail");
    assert!(e.to_string().contains("TLS"), "{e}");
    assert!(started.elapsed().as_secs() < 5, "fails at once");
    server.abort();
}
