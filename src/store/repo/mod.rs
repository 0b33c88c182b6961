//! The repository traits of `store/mod.rs`, implemented once for every
//! [`Backend`](super::backend::Backend): each operation's logic (statements,
//! transactions, lease checks, error mapping) lives here, and the backends
//! supply only their dialect (`backend.rs`).

mod auth;
mod jobs;
mod results;
mod robots;
mod sessions;

pub use robots::UPSERT_ROBOT;

/// The cursor of a full page is its last key; a short page is the last one.
fn page_cursor<T>(items: &[T], limit: i64, key: impl Fn(&T) -> String) -> Option<String> {
    if items.len() as i64 == limit {
        items.last().map(key)
    } else {
        None
    }
}
