-- The release gate (issue 17): every parameter set has a status, and
-- `latest` is the newest approved one. Sets stored before the gate were
-- all served as `latest`, so they stay approved. `status_reason` says why
-- a set was held back (or approved), `status_by`/`status_at` who decided
-- and when ("gate" for the automatic decision at the end of the job).
ALTER TABLE parameter_sets ADD COLUMN status TEXT NOT NULL DEFAULT 'approved';
ALTER TABLE parameter_sets ADD COLUMN status_reason TEXT;
ALTER TABLE parameter_sets ADD COLUMN status_by TEXT;
ALTER TABLE parameter_sets ADD COLUMN status_at TEXT;
CREATE INDEX parameter_sets_approved ON parameter_sets(serial, status, version);

-- Every status change, oldest first: who approved or rejected what, when
-- (the history's "who approved what"). Goes with its parameter set.
CREATE TABLE parameter_set_decisions (
    serial      TEXT NOT NULL,
    version     BIGINT NOT NULL,
    seq         INTEGER NOT NULL,
    status      TEXT NOT NULL,
    reason      TEXT,
    decided_by  TEXT NOT NULL,
    decided_at  TEXT NOT NULL,
    PRIMARY KEY (serial, version, seq),
    FOREIGN KEY (serial, version) REFERENCES parameter_sets(serial, version) ON DELETE CASCADE
);
