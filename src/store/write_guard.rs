//! Crash-safe `Idempotency-Key`s: the idempotency layer runs a keyed request
//! inside [`guarded`], and every writing transaction the request opens
//! ([`Backend::begin_write`](super::backend::Backend::begin_write)) marks
//! the key as written in that same transaction. If the process dies after
//! the write commits but before the answer is stored, the key stays taken
//! when its lease lapses, so a retry is told the request was carried out
//! instead of running the write a second time.

use std::future::Future;

use sqlx::Transaction;

use super::statement::{query, Driver};
use super::StoreResult;
use crate::domain::IdempotencyScope;

tokio::task_local! {
    static GUARDED: IdempotencyScope;
}

/// Runs `work` (a request's handler) with its writes guarded by `scope`.
pub async fn guarded<F: Future>(scope: IdempotencyScope, work: F) -> F::Output {
    GUARDED.scope(scope, work).await
}

/// Marks the key of the request running this task (if any) as written, in
/// the writing transaction `tx`: the mark commits with the write, or not at all.
pub async fn mark<DB: Driver>(tx: &mut Transaction<'static, DB>) -> StoreResult<()> {
    let Ok(scope) = GUARDED.try_with(Clone::clone) else {
        return Ok(());
    };
    query(
        "UPDATE idempotency SET wrote = 1
         WHERE principal = $1 AND idem_key = $2 AND state = 'pending' AND holder = $3",
    )
    .bind(&scope.principal)
    .bind(&scope.key)
    .bind(&scope.holder)
    .execute(tx)
    .await?;
    Ok(())
}
