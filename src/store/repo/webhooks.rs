//! Webhooks and the durable outbox their events are delivered from.
//!
//! Recording an event fans it out, in one `INSERT … SELECT`, to one outbox
//! row per webhook subscribed to it, inside the caller's transaction
//! ([`record_event_tx`]), so the event commits with the state change it
//! reports. The delivery loop (`src/outbox/`) claims due rows under a
//! lease (any replica; a crashed one's claims expire), and marks a row
//! delivered only after its receiver answered 2xx: at least once.

use async_trait::async_trait;
use serde::Serialize;
use sqlx::Transaction;

use crate::domain::{new_id, now_rfc3339, DomainEvent};
use crate::store::backend::Backend;
use crate::store::rows::Columns;
use crate::store::statement::query;
use crate::store::{OutboxDelivery, StoreResult, WebhookRecord, WebhookStore};

const COLUMNS: &str = "id, url, events, secret, created_at";

/// The stored form of a subscription's event names: between commas, so
/// one `LIKE` finds a name (`,job.finished,set.approved,`).
fn events_column(events: &[String]) -> String {
    format!(",{},", events.join(","))
}

fn webhook(row: &impl Columns) -> WebhookRecord {
    WebhookRecord {
        id: row.string("id"),
        url: row.string("url"),
        events: row
            .str("events")
            .split(',')
            .filter(|e| !e.is_empty())
            .map(str::to_string)
            .collect(),
        secret: row.string("secret"),
        created_at: row.string("created_at"),
    }
}

/// The document a receiver gets: the event's `type` and `data`, with the
/// event's id (the same in every retry: receivers drop duplicates by it).
#[derive(Serialize)]
struct Envelope<'a> {
    id: &'a str,
    created_at: &'a str,
    #[serde(flatten)]
    event: &'a DomainEvent,
}

/// Writes `event` to the outbox of every webhook subscribed to it, inside
/// `tx` (it commits, or is lost, with the change it reports).
pub async fn record_event_tx<B: Backend>(
    tx: &mut Transaction<'static, B::Db>,
    event: &DomainEvent,
    now_ms: i64,
) -> StoreResult<()> {
    let id = new_id();
    let created_at = now_rfc3339();
    let body = serde_json::to_string(&Envelope {
        id: &id,
        created_at: &created_at,
        event,
    })?;
    query(
        "INSERT INTO webhook_outbox (id, event_id, webhook_id, event, body, next_attempt_ms,
           created_at)
         SELECT $1 || '/' || id, $1, id, $2, $3, $4, $5 FROM webhooks
         WHERE events LIKE '%,' || $2 || ',%'",
    )
    .bind(id.clone())
    .bind(event.name())
    .bind(body)
    .bind(now_ms)
    .bind(created_at)
    .execute(&mut *tx)
    .await?;
    Ok(())
}

#[async_trait]
impl<B: Backend> WebhookStore for B {
    async fn create_webhook(&self, w: &WebhookRecord) -> StoreResult<()> {
        query(format!(
            "INSERT INTO webhooks ({COLUMNS}) VALUES ($1, $2, $3, $4, $5)"
        ))
        .bind(w.id.clone())
        .bind(w.url.clone())
        .bind(events_column(&w.events))
        .bind(w.secret.clone())
        .bind(w.created_at.clone())
        .execute(self.pool())
        .await?;
        Ok(())
    }

    async fn list_webhooks(&self) -> StoreResult<Vec<WebhookRecord>> {
        let rows = query(format!("SELECT {COLUMNS} FROM webhooks ORDER BY id"))
            .fetch_all(self.pool())
            .await?;
        Ok(rows.iter().map(webhook).collect())
    }

    async fn get_webhook(&self, id: &str) -> StoreResult<Option<WebhookRecord>> {
        let row = query(format!("SELECT {COLUMNS} FROM webhooks WHERE id = $1"))
            .bind(id)
            .fetch_optional(self.pool())
            .await?;
        Ok(row.as_ref().map(webhook))
    }

    async fn delete_webhook(&self, id: &str) -> StoreResult<bool> {
        let deleted = query("DELETE FROM webhooks WHERE id = $1")
            .bind(id)
            .execute(self.pool())
            .await?;
        Ok(deleted > 0)
    }

    async fn record_event(&self, event: &DomainEvent, now_ms: i64) -> StoreResult<()> {
        let mut tx = self.begin_write().await?;
        record_event_tx::<B>(&mut tx, event, now_ms).await?;
        tx.commit().await?;
        Ok(())
    }

    async fn claim_deliveries(
        &self,
        now_ms: i64,
        lease_until_ms: i64,
        limit: i64,
    ) -> StoreResult<Vec<OutboxDelivery>> {
        // Polled by every process: look before taking the write lock
        // (SQLite has one for the whole database).
        let due = query(
            "SELECT id FROM webhook_outbox
             WHERE state = 'pending' AND next_attempt_ms <= $1
               AND (lease_until_ms IS NULL OR lease_until_ms < $1) LIMIT 1",
        )
        .bind(now_ms)
        .fetch_optional(self.pool())
        .await?;
        if due.is_none() {
            return Ok(Vec::new());
        }
        let mut tx = self.begin_write().await?;
        let rows = query(format!(
            "UPDATE webhook_outbox SET lease_until_ms = $1
             WHERE id IN (SELECT id FROM webhook_outbox
                          WHERE state = 'pending' AND next_attempt_ms <= $2
                            AND (lease_until_ms IS NULL OR lease_until_ms < $2)
                          ORDER BY next_attempt_ms, id LIMIT $3{})
             RETURNING id, event_id, webhook_id, event, body, attempts",
            B::FOR_UPDATE_SKIP_LOCKED
        ))
        .bind(lease_until_ms)
        .bind(now_ms)
        .bind(limit)
        .fetch_all(&mut tx)
        .await?;
        let mut claimed = Vec::with_capacity(rows.len());
        for row in &rows {
            let Some(hook) = query("SELECT url, secret FROM webhooks WHERE id = $1")
                .bind(row.string("webhook_id"))
                .fetch_optional(&mut tx)
                .await?
            else {
                continue; // deleted meanwhile: its rows go with it
            };
            claimed.push(OutboxDelivery {
                id: row.string("id"),
                event_id: row.string("event_id"),
                event: row.string("event"),
                body: row.string("body"),
                attempts: row.int("attempts"),
                url: hook.string("url"),
                secret: hook.string("secret"),
            });
        }
        tx.commit().await?;
        Ok(claimed)
    }

    async fn mark_delivered(&self, id: &str) -> StoreResult<()> {
        query(
            "UPDATE webhook_outbox SET state = 'delivered', attempts = attempts + 1,
               delivered_at = $1, lease_until_ms = NULL, last_error = NULL
             WHERE id = $2",
        )
        .bind(now_rfc3339())
        .bind(id)
        .execute(self.pool())
        .await?;
        Ok(())
    }

    async fn mark_attempt_failed(
        &self,
        id: &str,
        error: &str,
        retry_at_ms: Option<i64>,
    ) -> StoreResult<()> {
        let state = if retry_at_ms.is_some() {
            "pending"
        } else {
            "failed"
        };
        query(
            "UPDATE webhook_outbox SET state = $1, attempts = attempts + 1,
               next_attempt_ms = COALESCE($2, next_attempt_ms), lease_until_ms = NULL,
               last_error = $3
             WHERE id = $4",
        )
        .bind(state)
        .bind(retry_at_ms)
        .bind(error)
        .bind(id)
        .execute(self.pool())
        .await?;
        Ok(())
    }

    async fn outbox_counts(&self, webhook_id: &str) -> StoreResult<Vec<(String, i64)>> {
        let rows = query(
            "SELECT state, count(*) AS n FROM webhook_outbox WHERE webhook_id = $1
             GROUP BY state ORDER BY state",
        )
        .bind(webhook_id)
        .fetch_all(self.pool())
        .await?;
        Ok(rows
            .iter()
            .map(|r| (r.string("state"), r.int("n")))
            .collect())
    }
}
