-- PostgreSQL flavour of sqlite/0006_token_lifecycle.sql. Token lifecycle:
-- optional expiry, revocation and last use, as Unix milliseconds (NULL:
-- never expires / not revoked / never used). A revoked token keeps its row,
-- so `robocal tokens list` shows what was revoked and the service never
-- falls back to anonymous access once a token existed. last_used_ms is
-- written at most once a minute per token.
ALTER TABLE tokens ADD COLUMN expires_ms BIGINT;
ALTER TABLE tokens ADD COLUMN revoked_ms BIGINT;
ALTER TABLE tokens ADD COLUMN last_used_ms BIGINT;

-- Server-wide secrets shared by every replica, created on first use
-- (`report-links`: the HMAC key that signs read-only report links).
CREATE TABLE server_secrets (
    name        TEXT COLLATE "C" PRIMARY KEY,
    value       TEXT NOT NULL,
    created_at  TEXT NOT NULL
);
