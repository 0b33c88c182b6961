-- Crash-safe idempotency (issue 32): a keyed request's writing transaction
-- sets `wrote` on its key, so a key whose process died after the write
-- committed is not freed for the write to run again.
ALTER TABLE idempotency ADD COLUMN wrote INTEGER NOT NULL DEFAULT 0;
