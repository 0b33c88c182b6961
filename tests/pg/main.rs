//! The PostgreSQL suite: every module of `tests/it` compiled again, a fresh
//! database per test, plus the fleet tests (several real `robocal`
//! processes on one database) and the TLS connection tests.
//!
//! The backend is a parameter of the run (`support::backend()`): PostgreSQL
//! at `ROBOCAL_TEST_PG_URL` (default `postgres://postgres@127.0.0.1:5432/test`)
//! when a server answers there. Without one the modules run on SQLite (said
//! in one line) and the PostgreSQL-only tests (fleet, TLS) say they did not
//! run, so a plain `cargo test` works on a machine without PostgreSQL; set
//! `ROBOCAL_TEST_REQUIRE_PG=1` (CI does) to make a missing server a failure.

#[path = "../it/main.rs"]
mod it;
// The modules name each other `crate::support`, `crate::hostile`...: the same paths here.
use it::*;

mod fleet;
mod pg_tls;

/// Whether this run is on PostgreSQL; a test of PostgreSQL itself (TLS,
/// the fleet's advisory locks and NOTIFY) runs only then, and says so when
/// it does not.
pub fn on_postgres(test: &str) -> bool {
    let on = support::backend() == support::Backend::Postgres;
    if !on {
        eprintln!("{test}: not run, the backend is SQLite");
    }
    on
}
