//! The PostgreSQL suite: every module of `tests/it` compiled again with the
//! PostgreSQL backend (`support::backend()`), a fresh database per test, plus
//! the fleet tests (several real `robocal` processes on one database).
//!
//! Without a server at `ROBOCAL_TEST_PG_URL` (default
//! `postgres://postgres@127.0.0.1:5432/test`) the whole binary says so in one
//! line and passes, so a plain `cargo test` works on a machine without
//! PostgreSQL; set `ROBOCAL_TEST_REQUIRE_PG=1` (CI does) to make that a failure.

#[path = "../it/main.rs"]
mod it;
// The modules name each other `crate::support`, `crate::hostile`...: the same paths here.
use it::*;

mod fleet;
mod pg_tls;

use std::net::{TcpStream, ToSocketAddrs};
use std::time::Duration;

/// How long the one connectivity check waits.
const PROBE_TIMEOUT: Duration = Duration::from_millis(500);

/// Runs before the test harness: decides once whether a server is there.
#[ctor::ctor(unsafe)]
fn skip_without_server() {
    let url = it::test_db::pg_admin_url();
    if server_reachable(&url) {
        return;
    }
    if std::env::var_os("ROBOCAL_TEST_REQUIRE_PG").is_some_and(|v| v != "0") {
        eprintln!("PostgreSQL suite: no server at {url} but ROBOCAL_TEST_REQUIRE_PG is set");
        std::process::exit(1);
    }
    eprintln!("PostgreSQL suite skipped: no server at {url} (set ROBOCAL_TEST_PG_URL to use one)");
    std::process::exit(0);
}

/// A TCP (or Unix socket) connection to the server's address succeeds.
fn server_reachable(url: &str) -> bool {
    let Ok(parsed) = reqwest::Url::parse(url) else {
        return false;
    };
    let host = parsed.host_str().unwrap_or("localhost").to_string();
    let port = parsed.port().unwrap_or(5432);
    if host.starts_with('/') || host.is_empty() {
        return std::os::unix::net::UnixStream::connect(format!("{host}/.s.PGSQL.{port}")).is_ok();
    }
    let Ok(addrs) = (host.as_str(), port).to_socket_addrs() else {
        return false;
    };
    addrs
        .into_iter()
        .any(|a| TcpStream::connect_timeout(&a, PROBE_TIMEOUT).is_ok())
}
