//! A statement and its bound values, independent of the backend. The shared
//! repository code (`repo/`) builds these and runs them on a pool or a
//! transaction, as with `sqlx::query`; each database's [`Driver`] binds the
//! values to its own `sqlx` query. That keeps the shared code free of
//! `sqlx`'s per-database trait bounds.
//!
//! Placeholders are written `$1, $2, ...` for both backends: PostgreSQL reads
//! them natively and `sqlx`'s SQLite driver maps `$n` to the n-th bound value
//! (a placeholder may repeat, as on PostgreSQL). No rewriting is needed.

use std::borrow::Cow;

use futures_util::future::BoxFuture;
use sqlx::{Database, Pool, Transaction};

use super::rows::Columns;

/// One bound value. `None` binds a NULL of the variant's SQL type, which
/// PostgreSQL needs to type the parameter.
#[derive(Debug, Clone, PartialEq)]
pub enum Arg<'a> {
    Text(Option<Cow<'a, str>>),
    Int(Option<i64>),
    Real(f64),
    Bytes(Cow<'a, [u8]>),
}

/// SQL text with its values, in placeholder order (`$1` is the first).
#[derive(Debug, Clone)]
pub struct Statement<'a> {
    pub sql: Cow<'a, str>,
    pub args: Vec<Arg<'a>>,
}

/// Starts a statement; chain [`Statement::bind`] for `$1`, `$2`, ...
pub fn query<'a>(sql: impl Into<Cow<'a, str>>) -> Statement<'a> {
    Statement {
        sql: sql.into(),
        args: Vec::new(),
    }
}

impl<'a> Statement<'a> {
    /// Binds the next placeholder.
    pub fn bind(mut self, value: impl Into<Arg<'a>>) -> Self {
        self.args.push(value.into());
        self
    }

    /// Runs the statement; returns the number of rows it changed.
    pub fn execute<'c, T: Target<'c>>(self, on: T) -> BoxFuture<'c, sqlx::Result<u64>>
    where
        'a: 'c,
    {
        Box::pin(async move {
            match on.target() {
                On::Pool(pool) => T::Db::execute_in(&mut *pool.acquire().await?, self).await,
                On::Tx(conn) => T::Db::execute_in(conn, self).await,
            }
        })
    }

    pub fn fetch_optional<'c, T: Target<'c>>(
        self,
        on: T,
    ) -> BoxFuture<'c, sqlx::Result<Option<DbRow<T::Db>>>>
    where
        'a: 'c,
    {
        Box::pin(async move {
            match on.target() {
                On::Pool(pool) => T::Db::fetch_optional_in(&mut *pool.acquire().await?, self).await,
                On::Tx(conn) => T::Db::fetch_optional_in(conn, self).await,
            }
        })
    }

    pub fn fetch_one<'c, T: Target<'c>>(self, on: T) -> BoxFuture<'c, sqlx::Result<DbRow<T::Db>>>
    where
        'a: 'c,
    {
        let row = self.fetch_optional(on);
        Box::pin(async move { row.await?.ok_or(sqlx::Error::RowNotFound) })
    }

    pub fn fetch_all<'c, T: Target<'c>>(
        self,
        on: T,
    ) -> BoxFuture<'c, sqlx::Result<Vec<DbRow<T::Db>>>>
    where
        'a: 'c,
    {
        Box::pin(async move {
            match on.target() {
                On::Pool(pool) => T::Db::fetch_all_in(&mut *pool.acquire().await?, self).await,
                On::Tx(conn) => T::Db::fetch_all_in(conn, self).await,
            }
        })
    }
}

/// A result row of database `DB`.
pub type DbRow<DB> = <DB as Database>::Row;

/// Where a statement runs: `&Pool` (a connection taken for the statement)
/// or `&mut Transaction`.
pub trait Target<'c>: Send + 'c {
    type Db: Driver;
    fn target(self) -> On<'c, Self::Db>;
}

pub enum On<'c, DB: Database> {
    Pool(&'c Pool<DB>),
    Tx(&'c mut DB::Connection),
}

impl<'c, DB: Driver> Target<'c> for &'c Pool<DB> {
    type Db = DB;
    fn target(self) -> On<'c, DB> {
        On::Pool(self)
    }
}

impl<'c, DB: Driver> Target<'c> for &'c mut Transaction<'static, DB> {
    type Db = DB;
    fn target(self) -> On<'c, DB> {
        On::Tx(&mut **self)
    }
}

impl<'a> From<&'a str> for Arg<'a> {
    fn from(v: &'a str) -> Self {
        Arg::Text(Some(Cow::Borrowed(v)))
    }
}

impl<'a> From<&'a String> for Arg<'a> {
    fn from(v: &'a String) -> Self {
        Arg::Text(Some(Cow::Borrowed(v)))
    }
}

impl From<String> for Arg<'_> {
    fn from(v: String) -> Self {
        Arg::Text(Some(Cow::Owned(v)))
    }
}

impl<'a> From<Option<&'a str>> for Arg<'a> {
    fn from(v: Option<&'a str>) -> Self {
        Arg::Text(v.map(Cow::Borrowed))
    }
}

impl From<Option<String>> for Arg<'_> {
    fn from(v: Option<String>) -> Self {
        Arg::Text(v.map(Cow::Owned))
    }
}

impl From<i64> for Arg<'_> {
    fn from(v: i64) -> Self {
        Arg::Int(Some(v))
    }
}

impl From<Option<i64>> for Arg<'_> {
    fn from(v: Option<i64>) -> Self {
        Arg::Int(v)
    }
}

impl From<f64> for Arg<'_> {
    fn from(v: f64) -> Self {
        Arg::Real(v)
    }
}

impl<'a> From<&'a [u8]> for Arg<'a> {
    fn from(v: &'a [u8]) -> Self {
        Arg::Bytes(Cow::Borrowed(v))
    }
}

impl<'a> From<&'a Vec<u8>> for Arg<'a> {
    fn from(v: &'a Vec<u8>) -> Self {
        Arg::Bytes(Cow::Borrowed(v))
    }
}

/// Binds `args` to a `sqlx` query of either backend, in order, without
/// copying borrowed values. (A macro: a function would need `sqlx`'s
/// per-database bounds, which is what this module avoids.)
macro_rules! bind_args {
    ($query:expr, $args:expr) => {{
        use std::borrow::Cow;
        use $crate::store::statement::Arg;
        let mut q = $query;
        for arg in $args {
            q = match arg {
                Arg::Text(v) => q.bind(v),
                Arg::Int(v) => q.bind(v),
                Arg::Real(v) => q.bind(v),
                Arg::Bytes(Cow::Borrowed(v)) => q.bind(v),
                Arg::Bytes(Cow::Owned(v)) => q.bind(v),
            };
        }
        q
    }};
}
pub(crate) use bind_args;

/// A `sqlx` database whose driver runs a [`Statement`] and whose rows read
/// as [`Columns`]. The three methods read the same for every driver but,
/// written generically, would need each driver's trait bounds:
/// [`run_statements!`] writes them in `impl Driver for <database>`.
pub trait Driver: Database<Row: Columns> {
    /// Runs `stmt`; returns the number of rows it changed.
    fn execute_in<'c>(
        conn: &'c mut Self::Connection,
        stmt: Statement<'c>,
    ) -> BoxFuture<'c, sqlx::Result<u64>>;
    fn fetch_optional_in<'c>(
        conn: &'c mut Self::Connection,
        stmt: Statement<'c>,
    ) -> BoxFuture<'c, sqlx::Result<Option<Self::Row>>>;
    fn fetch_all_in<'c>(
        conn: &'c mut Self::Connection,
        stmt: Statement<'c>,
    ) -> BoxFuture<'c, sqlx::Result<Vec<Self::Row>>>;
}

/// The body of `impl Driver for <database>`.
macro_rules! run_statements {
    () => {
        fn execute_in<'c>(
            conn: &'c mut Self::Connection,
            stmt: $crate::store::statement::Statement<'c>,
        ) -> ::futures_util::future::BoxFuture<'c, ::sqlx::Result<u64>> {
            Box::pin(async move {
                let $crate::store::statement::Statement { sql, args } = stmt;
                let q = $crate::store::statement::bind_args!(::sqlx::query(&sql), args);
                Ok(q.execute(conn).await?.rows_affected())
            })
        }

        fn fetch_optional_in<'c>(
            conn: &'c mut Self::Connection,
            stmt: $crate::store::statement::Statement<'c>,
        ) -> ::futures_util::future::BoxFuture<'c, ::sqlx::Result<Option<Self::Row>>> {
            Box::pin(async move {
                let $crate::store::statement::Statement { sql, args } = stmt;
                let q = $crate::store::statement::bind_args!(::sqlx::query(&sql), args);
                q.fetch_optional(conn).await
            })
        }

        fn fetch_all_in<'c>(
            conn: &'c mut Self::Connection,
            stmt: $crate::store::statement::Statement<'c>,
        ) -> ::futures_util::future::BoxFuture<'c, ::sqlx::Result<Vec<Self::Row>>> {
            Box::pin(async move {
                let $crate::store::statement::Statement { sql, args } = stmt;
                let q = $crate::store::statement::bind_args!(::sqlx::query(&sql), args);
                q.fetch_all(conn).await
            })
        }
    };
}
pub(crate) use run_statements;

#[cfg(test)]
mod tests {
    use super::*;
    use crate::store::rows::Columns;

    #[test]
    fn binds_in_placeholder_order_with_typed_nulls() {
        let s = query("SELECT $1, $2, $3, $4")
            .bind("a")
            .bind(None::<i64>)
            .bind(2.5)
            .bind(None::<String>);
        assert_eq!(
            s.args,
            vec![
                Arg::Text(Some("a".into())),
                Arg::Int(None),
                Arg::Real(2.5),
                Arg::Text(None)
            ]
        );
    }

    /// The shared statements rely on sqlx's SQLite driver reading `$n` as the
    /// n-th bound value, out of order and repeated, as PostgreSQL does.
    #[tokio::test]
    async fn sqlite_reads_numbered_placeholders_like_postgres() {
        let pool = sqlx::SqlitePool::connect("sqlite::memory:").await.unwrap();
        let row = query(
            "SELECT $2 AS second, $1 AS first, $2 || $1 AS both,
               CAST($3 AS BIGINT) IS NULL AS no_version",
        )
        .bind("x")
        .bind("y")
        .bind(None::<i64>)
        .fetch_one(&pool)
        .await
        .unwrap();
        assert_eq!(row.str("first"), "x");
        assert_eq!(row.str("second"), "y");
        assert_eq!(row.str("both"), "yx");
        assert_eq!(row.int("no_version"), 1);
    }
}
