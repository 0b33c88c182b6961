//! Per-test databases. SQLite: a file in the test's temporary directory.
//! PostgreSQL: a fresh database on the server named by `ROBOCAL_TEST_PG_URL`
//! (default [`DEFAULT_PG_URL`]), created for one test and dropped when its
//! [`TestDb`] guard goes (also when the test panics). Databases left behind
//! by a test process that was itself killed are dropped by the next run.

use std::fmt;
use std::future::Future;
use std::net::{TcpStream, ToSocketAddrs};
use std::ops::Deref;
use std::sync::atomic::{AtomicU64, Ordering};
use std::sync::Once;
use std::time::Duration;

use sqlx::{Connection, PgConnection};

/// The CI server: trust auth, database `test`.
pub const DEFAULT_PG_URL: &str = "postgres://postgres@127.0.0.1:5432/test";
/// Name prefix of the databases the tests create (`robocal_t_<pid>_<n>`).
const PREFIX: &str = "robocal_t_";

/// How long the one connectivity check waits.
const PROBE_TIMEOUT: Duration = Duration::from_millis(500);

pub fn pg_admin_url() -> String {
    std::env::var("ROBOCAL_TEST_PG_URL").unwrap_or_else(|_| DEFAULT_PG_URL.to_string())
}

/// A TCP (or Unix socket) connection to the server's address succeeds.
pub fn server_reachable(url: &str) -> bool {
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

/// A database URL that lives as long as the guard. Derefs to the URL.
pub struct TestDb {
    url: String,
    pg_name: Option<String>,
}

impl TestDb {
    pub fn sqlite(dir: &tempfile::TempDir) -> TestDb {
        TestDb {
            url: format!("sqlite://{}/robocal.db", dir.path().display()),
            pg_name: None,
        }
    }

    /// Creates an empty PostgreSQL database (the server's migrations run when
    /// robocal connects to it).
    pub fn postgres() -> TestDb {
        static SWEEP: Once = Once::new();
        static NEXT: AtomicU64 = AtomicU64::new(0);
        let admin = pg_admin_url();
        SWEEP.call_once(|| block_on(sweep_orphans(&admin)));
        let name = format!(
            "{PREFIX}{}_{}",
            std::process::id(),
            NEXT.fetch_add(1, Ordering::SeqCst)
        );
        block_on(async {
            let mut conn = PgConnection::connect(&admin).await.unwrap_or_else(|e| {
                panic!("no PostgreSQL test server at {admin} ({e}): start one, or run on SQLite")
            });
            sqlx::query(&format!("CREATE DATABASE \"{name}\""))
                .execute(&mut conn)
                .await
                .expect("create test database");
        });
        let mut url = reqwest::Url::parse(&admin).expect("ROBOCAL_TEST_PG_URL is a URL");
        url.set_path(&name);
        TestDb {
            url: url.to_string(),
            pg_name: Some(name),
        }
    }
}

impl Deref for TestDb {
    type Target = str;
    fn deref(&self) -> &str {
        &self.url
    }
}

impl fmt::Display for TestDb {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(&self.url)
    }
}

impl Drop for TestDb {
    fn drop(&mut self) {
        if let Some(name) = self.pg_name.take() {
            let admin = pg_admin_url();
            block_on(async move {
                if let Err(e) = drop_database(&admin, &name).await {
                    eprintln!("could not drop test database {name}: {e}");
                }
            });
        }
    }
}

/// `WITH (FORCE)` ends connections a killed or still running server left.
async fn drop_database(admin: &str, name: &str) -> Result<(), sqlx::Error> {
    let mut conn = PgConnection::connect(admin).await?;
    sqlx::query(&format!("DROP DATABASE IF EXISTS \"{name}\" WITH (FORCE)"))
        .execute(&mut conn)
        .await?;
    Ok(())
}

/// Drops test databases whose creating process no longer exists.
async fn sweep_orphans(admin: &str) {
    let Ok(mut conn) = PgConnection::connect(admin).await else {
        return;
    };
    let names: Vec<String> =
        sqlx::query_scalar("SELECT datname FROM pg_database WHERE datname LIKE 'robocal\\_t\\_%'")
            .fetch_all(&mut conn)
            .await
            .unwrap_or_default();
    for name in names {
        let pid = name[PREFIX.len()..].split('_').next().unwrap_or("");
        let alive = std::path::Path::new(&format!("/proc/{pid}")).exists();
        if cfg!(target_os = "linux") && !alive {
            let _ = drop_database(admin, &name).await;
        }
    }
}

/// Runs a future to completion from sync code, also from inside a test's
/// runtime (on a scoped thread with its own runtime).
fn block_on<F: Future + Send>(f: F) -> F::Output
where
    F::Output: Send,
{
    std::thread::scope(|s| {
        s.spawn(|| {
            tokio::runtime::Builder::new_current_thread()
                .enable_all()
                .build()
                .unwrap()
                .block_on(f)
        })
        .join()
        .unwrap()
    })
}
