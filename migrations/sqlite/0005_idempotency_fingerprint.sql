-- Idempotency keys become unique per principal (not per method and path), so
-- a key reused for a different request is recognised and refused. Each done
-- key keeps the fingerprint of its request (method, path, body digest); a
-- pending key is held by one request (`holder`) under a lease it renews, so
-- a request that died with its process frees the key once the lease lapses.
-- Done keys carry over without a fingerprint (they replay as before until
-- they expire); pending ones belonged to the stopped process and are dropped.
ALTER TABLE idempotency RENAME TO idempotency_0001;
CREATE TABLE idempotency (
    principal      TEXT NOT NULL,
    idem_key       TEXT NOT NULL,
    method         TEXT NOT NULL,
    path           TEXT NOT NULL,
    state          TEXT NOT NULL CHECK (state IN ('pending', 'done')),
    holder         TEXT,
    lease_until_ms INTEGER NOT NULL DEFAULT 0,
    fingerprint    TEXT,
    status         INTEGER,
    headers        TEXT,
    body           BLOB,
    created_ms     INTEGER NOT NULL,
    PRIMARY KEY (principal, idem_key)
);
INSERT OR IGNORE INTO idempotency
    (principal, idem_key, method, path, state, status, headers, body, created_ms)
SELECT principal, idem_key, method, path, state, status, headers, body, created_ms
FROM idempotency_0001 WHERE state = 'done' ORDER BY created_ms;
DROP TABLE idempotency_0001;
