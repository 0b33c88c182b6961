use async_trait::async_trait;

use crate::domain::{
    new_id, now_rfc3339, now_unix_ms, IdempotencyClaim, IdempotencyScope, Scope, StoredResponse,
    TokenRecord,
};
use crate::store::backend::Backend;
use crate::store::rows::{token, Columns};
use crate::store::statement::{query, Statement};
use crate::store::{AuthStore, StoreError, StoreResult};

/// Stored responses are kept this long, then a key may be used afresh.
const IDEMPOTENCY_TTL_MS: i64 = 24 * 3600 * 1000;
/// The columns [`token`] reads.
const TOKEN_COLUMNS: &str = "id, name, scope, created_at, expires_ms, revoked_ms, last_used_ms";
/// A stored response without a status (never written so) replays as 200.
const DEFAULT_STATUS: i64 = 200;

#[async_trait]
impl<B: Backend> AuthStore for B {
    async fn create_token_expiring(
        &self,
        name: &str,
        token_hash: &str,
        scope: Scope,
        expires_ms: Option<i64>,
    ) -> StoreResult<TokenRecord> {
        let record = TokenRecord {
            id: new_id(),
            name: name.to_string(),
            scope,
            created_at: now_rfc3339(),
            expires_ms,
            revoked_ms: None,
            last_used_ms: None,
        };
        query(
            "INSERT INTO tokens (id, name, token_hash, scope, created_at, expires_ms)
             VALUES ($1, $2, $3, $4, $5, $6)",
        )
        .bind(&record.id)
        .bind(&record.name)
        .bind(token_hash)
        .bind(scope.as_str())
        .bind(&record.created_at)
        .bind(expires_ms)
        .execute(self.pool())
        .await?;
        Ok(record)
    }

    async fn find_token(&self, token_hash: &str) -> StoreResult<Option<TokenRecord>> {
        let row = query(format!(
            "SELECT {TOKEN_COLUMNS} FROM tokens WHERE token_hash = $1"
        ))
        .bind(token_hash)
        .fetch_optional(self.pool())
        .await?;
        row.as_ref().map(token).transpose()
    }

    async fn list_tokens(&self) -> StoreResult<Vec<TokenRecord>> {
        let rows = query(format!("SELECT {TOKEN_COLUMNS} FROM tokens ORDER BY id"))
            .fetch_all(self.pool())
            .await?;
        rows.iter().map(token).collect()
    }

    async fn count_tokens(&self) -> StoreResult<i64> {
        let row = query("SELECT count(*) AS n FROM tokens")
            .fetch_one(self.pool())
            .await?;
        Ok(row.int("n"))
    }

    async fn revoke_token(&self, id: &str) -> StoreResult<Option<TokenRecord>> {
        query("UPDATE tokens SET revoked_ms = $2 WHERE id = $1 AND revoked_ms IS NULL")
            .bind(id)
            .bind(now_unix_ms())
            .execute(self.pool())
            .await?;
        let row = query(format!("SELECT {TOKEN_COLUMNS} FROM tokens WHERE id = $1"))
            .bind(id)
            .fetch_optional(self.pool())
            .await?;
        row.as_ref().map(token).transpose()
    }

    async fn revoke_token_keeping_an_admin(&self, id: &str) -> StoreResult<Option<TokenRecord>> {
        let now = now_unix_ms();
        let mut tx = self.begin_write().await?;
        // The usable admin tokens, locked: two revocations at once cannot
        // each count the other as the one that remains.
        let admins = query(format!(
            "SELECT id FROM tokens WHERE scope = $1 AND revoked_ms IS NULL
               AND (expires_ms IS NULL OR expires_ms > $2) ORDER BY id{}",
            B::FOR_UPDATE
        ))
        .bind(Scope::Admin.as_str())
        .bind(now)
        .fetch_all(&mut tx)
        .await?;
        let others = admins.iter().filter(|r| r.str("id") != id).count();
        if others == 0 && admins.len() == 1 {
            return Err(StoreError::Conflict(format!(
                "token {id} is the last usable admin token: create another admin token \
                 before revoking it"
            )));
        }
        query("UPDATE tokens SET revoked_ms = $2 WHERE id = $1 AND revoked_ms IS NULL")
            .bind(id)
            .bind(now)
            .execute(&mut tx)
            .await?;
        let row = query(format!("SELECT {TOKEN_COLUMNS} FROM tokens WHERE id = $1"))
            .bind(id)
            .fetch_optional(&mut tx)
            .await?;
        tx.commit().await?;
        row.as_ref().map(token).transpose()
    }

    async fn touch_token(&self, id: &str, now_ms: i64, min_interval_ms: i64) -> StoreResult<()> {
        query(
            "UPDATE tokens SET last_used_ms = $2
             WHERE id = $1 AND (last_used_ms IS NULL OR last_used_ms <= $3)",
        )
        .bind(id)
        .bind(now_ms)
        .bind(now_ms - min_interval_ms)
        .execute(self.pool())
        .await?;
        Ok(())
    }

    async fn server_secret(&self, name: &str, fresh: &str) -> StoreResult<String> {
        let select = "SELECT value FROM server_secrets WHERE name = $1";
        if let Some(row) = query(select).bind(name).fetch_optional(self.pool()).await? {
            return Ok(row.string("value"));
        }
        query(
            "INSERT INTO server_secrets (name, value, created_at) VALUES ($1, $2, $3)
             ON CONFLICT DO NOTHING",
        )
        .bind(name)
        .bind(fresh)
        .bind(now_rfc3339())
        .execute(self.pool())
        .await?;
        let row = query(select).bind(name).fetch_one(self.pool()).await?;
        Ok(row.string("value"))
    }

    async fn claim_idempotency(
        &self,
        s: &IdempotencyScope,
        lease_until_ms: i64,
    ) -> StoreResult<IdempotencyClaim> {
        let now = now_unix_ms();
        // Housekeeping of other keys, outside the claim: two replicas sweeping
        // the same rows could deadlock, and a failed sweep changes nothing
        // for this request.
        if let Err(e) = query(
            "DELETE FROM idempotency WHERE ((state = 'done' OR wrote = 1) AND created_ms < $1)
                OR (state = 'pending' AND wrote = 0 AND lease_until_ms < $2)",
        )
        .bind(now - IDEMPOTENCY_TTL_MS)
        .bind(now)
        .execute(self.pool())
        .await
        {
            tracing::debug!(error = %e, "idempotency sweep skipped");
        }
        let mut tx = self.begin_write().await?;
        // This key, if expired (or held by a request whose lease lapsed: its
        // process died), is free again, unless that request wrote.
        bind_key(
            query(
                "DELETE FROM idempotency WHERE principal = $1 AND idem_key = $2
                   AND (((state = 'done' OR wrote = 1) AND created_ms < $3)
                        OR (state = 'pending' AND wrote = 0 AND lease_until_ms < $4))",
            ),
            s,
        )
        .bind(now - IDEMPOTENCY_TTL_MS)
        .bind(now)
        .execute(&mut tx)
        .await?;
        // The primary key decides: of writers inserting the same key at once,
        // one inserts and the others wait for its commit, then insert nothing.
        let inserted = bind_key(
            query(
                "INSERT INTO idempotency (principal, idem_key, method, path, state, holder,
                   lease_until_ms, created_ms)
                 VALUES ($1, $2, $3, $4, 'pending', $5, $6, $7) ON CONFLICT DO NOTHING",
            ),
            s,
        )
        .bind(&s.method)
        .bind(&s.path)
        .bind(&s.holder)
        .bind(lease_until_ms)
        .bind(now)
        .execute(&mut tx)
        .await?;
        if inserted > 0 {
            tx.commit().await?;
            return Ok(IdempotencyClaim::Fresh);
        }
        let row = bind_key(
            query(
                "SELECT method, path, state, wrote, lease_until_ms, fingerprint, status, headers, body
                 FROM idempotency
                 WHERE principal = $1 AND idem_key = $2",
            ),
            s,
        )
        .fetch_optional(&mut tx)
        .await?;
        tx.commit().await?;
        // Gone between the insert and the select (abandoned meanwhile): the
        // client may retry, as with any request still in flight.
        let Some(row) = row else {
            return Ok(IdempotencyClaim::InFlight);
        };
        if row.str("method") != s.method || row.str("path") != s.path {
            return Ok(IdempotencyClaim::OtherRequest {
                method: row.str("method").to_string(),
                path: row.str("path").to_string(),
            });
        }
        if row.str("state") == "pending" {
            let lapsed = row.int("lease_until_ms") < now;
            if row.int("wrote") != 0 && lapsed {
                return Ok(IdempotencyClaim::Lost);
            }
            return Ok(IdempotencyClaim::InFlight);
        }
        let headers: Vec<(String, String)> =
            serde_json::from_str(row.opt_str("headers").unwrap_or("[]"))?;
        Ok(IdempotencyClaim::Done {
            fingerprint: row.opt_str("fingerprint").map(str::to_string),
            response: StoredResponse {
                status: row.opt_int("status").unwrap_or(DEFAULT_STATUS) as u16,
                headers,
                body: row.opt_bytes("body").unwrap_or_default(),
            },
        })
    }

    async fn renew_idempotency(
        &self,
        s: &IdempotencyScope,
        lease_until_ms: i64,
    ) -> StoreResult<()> {
        bind_key(
            query(
                "UPDATE idempotency SET lease_until_ms = $3
                 WHERE principal = $1 AND idem_key = $2 AND state = 'pending' AND holder = $4",
            ),
            s,
        )
        .bind(lease_until_ms)
        .bind(&s.holder)
        .execute(self.pool())
        .await?;
        Ok(())
    }

    async fn complete_idempotency(
        &self,
        s: &IdempotencyScope,
        fingerprint: Option<&str>,
        response: &StoredResponse,
    ) -> StoreResult<()> {
        bind_key(
            query(
                "UPDATE idempotency SET state = 'done', holder = NULL, fingerprint = $3,
                   status = $4, headers = $5, body = $6
                 WHERE principal = $1 AND idem_key = $2 AND state = 'pending' AND holder = $7",
            ),
            s,
        )
        .bind(fingerprint)
        .bind(response.status as i64)
        .bind(serde_json::to_string(&response.headers)?)
        .bind(&response.body)
        .bind(&s.holder)
        .execute(self.pool())
        .await?;
        Ok(())
    }

    async fn abandon_idempotency(&self, s: &IdempotencyScope) -> StoreResult<()> {
        bind_key(
            query(
                "DELETE FROM idempotency WHERE principal = $1 AND idem_key = $2
                   AND state = 'pending' AND holder = $3 AND wrote = 0",
            ),
            s,
        )
        .bind(&s.holder)
        .execute(self.pool())
        .await?;
        // A request that wrote keeps its key: lapsed now, a retry is told
        // it was carried out rather than running again.
        bind_key(
            query(
                "UPDATE idempotency SET lease_until_ms = 0, holder = NULL
                 WHERE principal = $1 AND idem_key = $2 AND state = 'pending' AND holder = $3",
            ),
            s,
        )
        .bind(&s.holder)
        .execute(self.pool())
        .await?;
        Ok(())
    }
}

/// Binds an idempotency key's columns to `$1`, `$2` (principal, key), in
/// which order every statement on the table names them.
fn bind_key<'a>(stmt: Statement<'a>, s: &'a IdempotencyScope) -> Statement<'a> {
    stmt.bind(&s.principal).bind(&s.key)
}
