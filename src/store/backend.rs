//! What the shared repository code (`repo/`) needs from a database backend:
//! a pool, a way to open a writing transaction, statement execution, and the
//! few places where the SQLite and PostgreSQL dialects (or their concurrency
//! models) differ. Each repository operation is written once, in `repo/`,
//! over this trait; `sqlite/` and `postgres/` only implement it.
//!
//! Why the dialect differences are this small: statements use `$n`
//! placeholders, which both drivers read (see `statement.rs`), and only
//! portable SQL (`RETURNING`, `ON CONFLICT`, `CAST`, `CASE`). What remains is
//! row locking (PostgreSQL replicas lock rows; SQLite's `BEGIN IMMEDIATE`
//! already excludes every other writer) and two operations whose
//! race-freedom needs backend-specific SQL.

use async_trait::async_trait;
use futures_util::future::BoxFuture;
use sqlx::{Database, Pool, Transaction};

use super::rows::Columns;
use super::statement::Statement;
use super::StoreResult;
use crate::domain::RobotRecord;

/// A connection of the backend's database: `&mut *tx` of a transaction or
/// `&mut *conn` of a pooled connection.
pub type Conn<B> = <<B as Backend>::Db as Database>::Connection;
/// A result row of the backend's database.
pub type DbRow<B> = <<B as Backend>::Db as Database>::Row;

#[async_trait]
pub trait Backend: Send + Sync + 'static {
    type Db: Database<Row: Columns>;

    /// Row-lock clause for a row this transaction will update.
    const FOR_UPDATE: &'static str;
    /// Row-lock clause that skips rows another transaction holds (a claim
    /// never waits for, nor takes, a job another replica is claiming).
    const FOR_UPDATE_SKIP_LOCKED: &'static str;
    /// Row-lock clause that keeps a parent row from being deleted meanwhile.
    const FOR_KEY_SHARE: &'static str;
    /// Takes the serial's next parameter-set version (`$1` = serial) inside
    /// the writing transaction; returns it as column `version`.
    const NEXT_VERSION: &'static str;

    fn pool(&self) -> &Pool<Self::Db>;

    /// Opens a transaction that is going to write.
    async fn begin_write(&self) -> StoreResult<Transaction<'static, Self::Db>>;

    /// Runs `stmt`; returns the number of rows it changed. (This and the two
    /// below are the same for every driver: [`run_statements!`] writes them.)
    fn execute_in<'c>(
        conn: &'c mut Conn<Self>,
        stmt: Statement<'c>,
    ) -> BoxFuture<'c, sqlx::Result<u64>>;
    fn fetch_optional_in<'c>(
        conn: &'c mut Conn<Self>,
        stmt: Statement<'c>,
    ) -> BoxFuture<'c, sqlx::Result<Option<DbRow<Self>>>>;
    fn fetch_all_in<'c>(
        conn: &'c mut Conn<Self>,
        stmt: Statement<'c>,
    ) -> BoxFuture<'c, sqlx::Result<Vec<DbRow<Self>>>>;

    /// Serialises enqueues (the `--max-queued` bound is a count, then an
    /// insert) inside the enqueue's transaction. Nothing to do where the
    /// writing transaction excludes other writers already.
    async fn serialise_enqueue(_tx: &mut Conn<Self>) -> StoreResult<()> {
        Ok(())
    }

    /// Creates or replaces the robot; `true` when it was created, answered
    /// once even when two processes create the same serial at once.
    async fn upsert_robot(&self, robot: &RobotRecord) -> StoreResult<bool>;

    async fn fetch_one_in(conn: &mut Conn<Self>, stmt: Statement<'_>) -> sqlx::Result<DbRow<Self>> {
        Self::fetch_optional_in(conn, stmt)
            .await?
            .ok_or(sqlx::Error::RowNotFound)
    }

    /// [`Backend::execute_in`] on a connection from the pool.
    async fn execute(&self, stmt: Statement<'_>) -> sqlx::Result<u64> {
        Self::execute_in(&mut *self.pool().acquire().await?, stmt).await
    }

    async fn fetch_optional(&self, stmt: Statement<'_>) -> sqlx::Result<Option<DbRow<Self>>> {
        Self::fetch_optional_in(&mut *self.pool().acquire().await?, stmt).await
    }

    async fn fetch_one(&self, stmt: Statement<'_>) -> sqlx::Result<DbRow<Self>> {
        Self::fetch_one_in(&mut *self.pool().acquire().await?, stmt).await
    }

    async fn fetch_all(&self, stmt: Statement<'_>) -> sqlx::Result<Vec<DbRow<Self>>> {
        Self::fetch_all_in(&mut *self.pool().acquire().await?, stmt).await
    }
}

/// True when `e` is a foreign-key violation (a parent row deleted
/// concurrently, or never there).
pub fn is_foreign_key_violation(e: &sqlx::Error) -> bool {
    e.as_database_error()
        .is_some_and(|d| d.is_foreign_key_violation())
}

/// The statement-running methods of a [`Backend`] impl, in the impl block.
/// They read the same for every `sqlx` driver but, written generically, would
/// need each driver's trait bounds; a macro writes them per concrete driver.
macro_rules! run_statements {
    () => {
        fn execute_in<'c>(
            conn: &'c mut $crate::store::backend::Conn<Self>,
            stmt: $crate::store::statement::Statement<'c>,
        ) -> ::futures_util::future::BoxFuture<'c, ::sqlx::Result<u64>> {
            Box::pin(async move {
                let $crate::store::statement::Statement { sql, args } = stmt;
                let q = $crate::store::statement::bind_args!(::sqlx::query(&sql), args);
                Ok(q.execute(conn).await?.rows_affected())
            })
        }

        fn fetch_optional_in<'c>(
            conn: &'c mut $crate::store::backend::Conn<Self>,
            stmt: $crate::store::statement::Statement<'c>,
        ) -> ::futures_util::future::BoxFuture<
            'c,
            ::sqlx::Result<Option<$crate::store::backend::DbRow<Self>>>,
        > {
            Box::pin(async move {
                let $crate::store::statement::Statement { sql, args } = stmt;
                $crate::store::statement::bind_args!(::sqlx::query(&sql), args)
                    .fetch_optional(conn)
                    .await
            })
        }

        fn fetch_all_in<'c>(
            conn: &'c mut $crate::store::backend::Conn<Self>,
            stmt: $crate::store::statement::Statement<'c>,
        ) -> ::futures_util::future::BoxFuture<
            'c,
            ::sqlx::Result<Vec<$crate::store::backend::DbRow<Self>>>,
        > {
            Box::pin(async move {
                let $crate::store::statement::Statement { sql, args } = stmt;
                $crate::store::statement::bind_args!(::sqlx::query(&sql), args)
                    .fetch_all(conn)
                    .await
            })
        }
    };
}
pub(crate) use run_statements;
