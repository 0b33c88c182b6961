//! A statement and its bound values, independent of the backend. The shared
//! repository code (`repo/`) builds these; each backend binds the values to
//! its own `sqlx` query (`Backend::fetch_all` and friends). That keeps the
//! shared code free of `sqlx`'s per-database trait bounds.
//!
//! Placeholders are written `$1, $2, ...` for both backends: PostgreSQL reads
//! them natively and `sqlx`'s SQLite driver maps `$n` to the n-th bound value
//! (a placeholder may repeat, as on PostgreSQL). No rewriting is needed.

use std::borrow::Cow;

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

#[cfg(test)]
mod tests {
    use super::*;

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
}
