-- Token lifecycle: optional expiry, revocation and last use, as Unix
-- milliseconds (NULL: never expires / not revoked / never used). A revoked
-- token keeps its row, so `robocal tokens list` shows what was revoked and
-- the service never falls back to anonymous access once a token existed.
-- last_used_ms is written at most once a minute per token.
ALTER TABLE tokens ADD COLUMN expires_ms INTEGER;
ALTER TABLE tokens ADD COLUMN revoked_ms INTEGER;
ALTER TABLE tokens ADD COLUMN last_used_ms INTEGER;

-- Server-wide secrets shared by every replica, created on first use
-- (`report-links`: the HMAC key that signs read-only report links).
CREATE TABLE server_secrets (
    name        TEXT PRIMARY KEY,
    value       TEXT NOT NULL,
    created_at  TEXT NOT NULL
);
