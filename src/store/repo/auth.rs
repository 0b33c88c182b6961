use async_trait::async_trait;

use crate::domain::{
    new_id, now_rfc3339, now_unix_ms, IdempotencyClaim, IdempotencyScope, Scope, StoredResponse,
    TokenRecord,
};
use crate::store::backend::Backend;
use crate::store::rows::{token, Columns};
use crate::store::statement::query;
use crate::store::{AuthStore, StoreResult};

/// Stored responses are kept this long, then a key may be used afresh.
const IDEMPOTENCY_TTL_MS: i64 = 24 * 3600 * 1000;
/// A pending key older than this belongs to a request that died: reusable.
const PENDING_STALE_MS: i64 = 10 * 60 * 1000;
/// A stored response without a status (never written so) replays as 200.
const DEFAULT_STATUS: i64 = 200;

#[async_trait]
impl<B: Backend> AuthStore for B {
    async fn create_token(
        &self,
        name: &str,
        token_hash: &str,
        scope: Scope,
    ) -> StoreResult<TokenRecord> {
        let record = TokenRecord {
            id: new_id(),
            name: name.to_string(),
            scope,
            created_at: now_rfc3339(),
        };
        self.execute(
            query(
                "INSERT INTO tokens (id, name, token_hash, scope, created_at)
                 VALUES ($1, $2, $3, $4, $5)",
            )
            .bind(&record.id)
            .bind(&record.name)
            .bind(token_hash)
            .bind(scope.as_str())
            .bind(&record.created_at),
        )
        .await?;
        Ok(record)
    }

    async fn find_token(&self, token_hash: &str) -> StoreResult<Option<TokenRecord>> {
        let row = self
            .fetch_optional(
                query("SELECT id, name, scope, created_at FROM tokens WHERE token_hash = $1")
                    .bind(token_hash),
            )
            .await?;
        row.as_ref().map(token).transpose()
    }

    async fn list_tokens(&self) -> StoreResult<Vec<TokenRecord>> {
        let rows = self
            .fetch_all(query(
                "SELECT id, name, scope, created_at FROM tokens ORDER BY id",
            ))
            .await?;
        rows.iter().map(token).collect()
    }

    async fn count_tokens(&self) -> StoreResult<i64> {
        let row = self
            .fetch_one(query("SELECT count(*) AS n FROM tokens"))
            .await?;
        Ok(row.int("n"))
    }

    async fn claim_idempotency(&self, s: &IdempotencyScope) -> StoreResult<IdempotencyClaim> {
        let now = now_unix_ms();
        // Housekeeping of other keys, outside the claim: two replicas sweeping
        // the same rows could deadlock, and a failed sweep changes nothing
        // for this request.
        if let Err(e) = self
            .execute(
                query(
                    "DELETE FROM idempotency WHERE (state = 'done' AND created_ms < $1)
                        OR (state = 'pending' AND created_ms < $2)",
                )
                .bind(now - IDEMPOTENCY_TTL_MS)
                .bind(now - PENDING_STALE_MS),
            )
            .await
        {
            tracing::debug!(error = %e, "idempotency sweep skipped");
        }
        let mut tx = self.begin_write().await?;
        // This key, if expired (or abandoned by a dead request), is free again.
        B::execute_in(
            &mut tx,
            query(
                "DELETE FROM idempotency
                 WHERE principal = $1 AND method = $2 AND path = $3 AND idem_key = $4
                   AND ((state = 'done' AND created_ms < $5)
                        OR (state = 'pending' AND created_ms < $6))",
            )
            .bind(&s.principal)
            .bind(&s.method)
            .bind(&s.path)
            .bind(&s.key)
            .bind(now - IDEMPOTENCY_TTL_MS)
            .bind(now - PENDING_STALE_MS),
        )
        .await?;
        // The primary key decides: of writers inserting the same key at once,
        // one inserts and the others wait for its commit, then insert nothing.
        let inserted = B::execute_in(
            &mut tx,
            query(
                "INSERT INTO idempotency (principal, method, path, idem_key, state, created_ms)
                 VALUES ($1, $2, $3, $4, 'pending', $5) ON CONFLICT DO NOTHING",
            )
            .bind(&s.principal)
            .bind(&s.method)
            .bind(&s.path)
            .bind(&s.key)
            .bind(now),
        )
        .await?;
        if inserted > 0 {
            tx.commit().await?;
            return Ok(IdempotencyClaim::Fresh);
        }
        let row = B::fetch_optional_in(
            &mut tx,
            query(
                "SELECT state, status, headers, body FROM idempotency
                 WHERE principal = $1 AND method = $2 AND path = $3 AND idem_key = $4",
            )
            .bind(&s.principal)
            .bind(&s.method)
            .bind(&s.path)
            .bind(&s.key),
        )
        .await?;
        tx.commit().await?;
        // Gone between the insert and the select (abandoned meanwhile): the
        // client may retry, as with any request still in flight.
        let Some(row) = row else {
            return Ok(IdempotencyClaim::InFlight);
        };
        if row.str("state") == "pending" {
            return Ok(IdempotencyClaim::InFlight);
        }
        let headers: Vec<(String, String)> =
            serde_json::from_str(row.opt_str("headers").unwrap_or("[]"))?;
        Ok(IdempotencyClaim::Replay(StoredResponse {
            status: row.opt_int("status").unwrap_or(DEFAULT_STATUS) as u16,
            headers,
            body: row.opt_bytes("body").unwrap_or_default(),
        }))
    }

    async fn complete_idempotency(
        &self,
        s: &IdempotencyScope,
        response: &StoredResponse,
    ) -> StoreResult<()> {
        self.execute(
            query(
                "UPDATE idempotency SET state = 'done', status = $1, headers = $2, body = $3
                 WHERE principal = $4 AND method = $5 AND path = $6 AND idem_key = $7",
            )
            .bind(response.status as i64)
            .bind(serde_json::to_string(&response.headers)?)
            .bind(&response.body)
            .bind(&s.principal)
            .bind(&s.method)
            .bind(&s.path)
            .bind(&s.key),
        )
        .await?;
        Ok(())
    }

    async fn abandon_idempotency(&self, s: &IdempotencyScope) -> StoreResult<()> {
        self.execute(
            query(
                "DELETE FROM idempotency WHERE principal = $1 AND method = $2 AND path = $3
                   AND idem_key = $4 AND state = 'pending'",
            )
            .bind(&s.principal)
            .bind(&s.method)
            .bind(&s.path)
            .bind(&s.key),
        )
        .await?;
        Ok(())
    }
}
