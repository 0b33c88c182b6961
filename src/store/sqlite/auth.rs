use async_trait::async_trait;
use sqlx::Row;

use super::SqliteStore;
use crate::domain::{
    new_id, now_rfc3339, now_unix_ms, IdempotencyClaim, IdempotencyScope, Scope, StoredResponse,
    TokenRecord,
};
use crate::store::rows::token;
use crate::store::{AuthStore, StoreResult};

/// Stored responses are kept this long, then a key may be used afresh.
const IDEMPOTENCY_TTL_MS: i64 = 24 * 3600 * 1000;
/// A pending key older than this belongs to a request that died: reusable.
const PENDING_STALE_MS: i64 = 10 * 60 * 1000;

#[async_trait]
impl AuthStore for SqliteStore {
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
        sqlx::query(
            "INSERT INTO tokens (id, name, token_hash, scope, created_at) VALUES (?, ?, ?, ?, ?)",
        )
        .bind(&record.id)
        .bind(&record.name)
        .bind(token_hash)
        .bind(scope.as_str())
        .bind(&record.created_at)
        .execute(&self.pool)
        .await?;
        Ok(record)
    }

    async fn find_token(&self, token_hash: &str) -> StoreResult<Option<TokenRecord>> {
        let row =
            sqlx::query("SELECT id, name, scope, created_at FROM tokens WHERE token_hash = ?")
                .bind(token_hash)
                .fetch_optional(&self.pool)
                .await?;
        row.as_ref().map(token).transpose()
    }

    async fn list_tokens(&self) -> StoreResult<Vec<TokenRecord>> {
        let rows = sqlx::query("SELECT id, name, scope, created_at FROM tokens ORDER BY id")
            .fetch_all(&self.pool)
            .await?;
        rows.iter().map(token).collect()
    }

    async fn count_tokens(&self) -> StoreResult<i64> {
        Ok(sqlx::query_scalar("SELECT count(*) FROM tokens")
            .fetch_one(&self.pool)
            .await?)
    }

    async fn claim_idempotency(&self, s: &IdempotencyScope) -> StoreResult<IdempotencyClaim> {
        let now = now_unix_ms();
        let mut tx = self.begin_immediate().await?;
        sqlx::query(
            "DELETE FROM idempotency WHERE (state = 'done' AND created_ms < ?)
                OR (state = 'pending' AND created_ms < ?)",
        )
        .bind(now - IDEMPOTENCY_TTL_MS)
        .bind(now - PENDING_STALE_MS)
        .execute(&mut *tx)
        .await?;
        let inserted = sqlx::query(
            "INSERT INTO idempotency (principal, method, path, idem_key, state, created_ms)
             VALUES (?, ?, ?, ?, 'pending', ?) ON CONFLICT DO NOTHING",
        )
        .bind(&s.principal)
        .bind(&s.method)
        .bind(&s.path)
        .bind(&s.key)
        .bind(now)
        .execute(&mut *tx)
        .await?;
        if inserted.rows_affected() > 0 {
            tx.commit().await?;
            return Ok(IdempotencyClaim::Fresh);
        }
        let row = sqlx::query(
            "SELECT state, status, headers, body FROM idempotency
             WHERE principal = ? AND method = ? AND path = ? AND idem_key = ?",
        )
        .bind(&s.principal)
        .bind(&s.method)
        .bind(&s.path)
        .bind(&s.key)
        .fetch_one(&mut *tx)
        .await?;
        tx.commit().await?;
        if row.get::<&str, _>("state") == "pending" {
            return Ok(IdempotencyClaim::InFlight);
        }
        let headers: Vec<(String, String)> =
            serde_json::from_str(row.get::<Option<&str>, _>("headers").unwrap_or("[]"))?;
        Ok(IdempotencyClaim::Replay(StoredResponse {
            status: row.get::<Option<i64>, _>("status").unwrap_or(200) as u16,
            headers,
            body: row.get::<Option<Vec<u8>>, _>("body").unwrap_or_default(),
        }))
    }

    async fn complete_idempotency(
        &self,
        s: &IdempotencyScope,
        response: &StoredResponse,
    ) -> StoreResult<()> {
        sqlx::query(
            "UPDATE idempotency SET state = 'done', status = ?, headers = ?, body = ?
             WHERE principal = ? AND method = ? AND path = ? AND idem_key = ?",
        )
        .bind(response.status as i64)
        .bind(serde_json::to_string(&response.headers)?)
        .bind(&response.body)
        .bind(&s.principal)
        .bind(&s.method)
        .bind(&s.path)
        .bind(&s.key)
        .execute(&self.pool)
        .await?;
        Ok(())
    }

    async fn abandon_idempotency(&self, s: &IdempotencyScope) -> StoreResult<()> {
        sqlx::query(
            "DELETE FROM idempotency WHERE principal = ? AND method = ? AND path = ?
               AND idem_key = ? AND state = 'pending'",
        )
        .bind(&s.principal)
        .bind(&s.method)
        .bind(&s.path)
        .bind(&s.key)
        .execute(&self.pool)
        .await?;
        Ok(())
    }
}
