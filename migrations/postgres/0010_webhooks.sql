-- PostgreSQL flavour of sqlite/0010_webhooks.sql. Webhooks (issue 17):
-- subscriptions, and the durable outbox their events
-- are delivered from. An event is fanned out to one outbox row per
-- subscribed webhook in the same transaction as the state change it
-- reports (a job's end), so a kill -9 after the commit loses nothing: the
-- delivery loop of any replica sends it later (at least once) and marks it
-- delivered only after a 2xx.
CREATE TABLE webhooks (
    id          TEXT COLLATE "C" PRIMARY KEY,
    url         TEXT NOT NULL,
    -- Subscribed event names between commas: ",job.finished,set.approved,".
    events      TEXT NOT NULL,
    -- The HMAC-SHA256 key of the signature header (shown once at creation).
    secret      TEXT NOT NULL,
    created_at  TEXT NOT NULL
);

CREATE TABLE webhook_outbox (
    -- event id '/' webhook id
    id               TEXT COLLATE "C" PRIMARY KEY,
    event_id         TEXT NOT NULL,
    webhook_id       TEXT NOT NULL REFERENCES webhooks(id) ON DELETE CASCADE,
    event            TEXT NOT NULL,
    -- The JSON document sent, byte for byte (what the signature covers).
    body             TEXT NOT NULL,
    state            TEXT NOT NULL DEFAULT 'pending'
                     CHECK (state IN ('pending', 'delivered', 'failed')),
    attempts         BIGINT NOT NULL DEFAULT 0,
    -- Unix ms: not before (backoff), and the claim of a delivery in flight.
    next_attempt_ms  BIGINT NOT NULL,
    lease_until_ms   BIGINT,
    last_error       TEXT,
    created_at       TEXT NOT NULL,
    delivered_at     TEXT
);
CREATE INDEX webhook_outbox_due ON webhook_outbox(state, next_attempt_ms);
CREATE INDEX webhook_outbox_by_webhook ON webhook_outbox(webhook_id);
