-- robocal schema, PostgreSQL flavour (the fleet deployment: several replicas
-- on one database). Same tables and columns as migrations/sqlite/0001_init.sql;
-- JSON documents are TEXT (kept byte for byte as written), user-facing
-- timestamps RFC 3339 TEXT, lease deadlines BIGINT unix milliseconds. Keys that
-- page (ids, serials) collate "C": byte order, as in SQLite, whatever the
-- database's locale.

CREATE TABLE robots (
    serial      TEXT COLLATE "C" PRIMARY KEY,
    model       TEXT NOT NULL,
    preset      TEXT,
    kinematics  TEXT NOT NULL,
    created_at  TEXT NOT NULL,
    updated_at  TEXT NOT NULL
);

CREATE TABLE sessions (
    id          TEXT COLLATE "C" PRIMARY KEY,
    serial      TEXT COLLATE "C" NOT NULL REFERENCES robots(serial) ON DELETE CASCADE,
    instrument  TEXT NOT NULL CHECK (instrument IN ('camera', 'tracker')),
    spec        TEXT NOT NULL,
    created_at  TEXT NOT NULL
);
CREATE INDEX sessions_by_serial ON sessions(serial, id);

-- Content-addressed image store: an image is written once, whatever the
-- number of poses (or replicas) naming it.
CREATE TABLE blobs (
    sha256        TEXT PRIMARY KEY,
    size_bytes    BIGINT NOT NULL,
    content_type  TEXT NOT NULL,
    data          BYTEA NOT NULL,
    created_at    TEXT NOT NULL
);

CREATE TABLE poses (
    id            TEXT COLLATE "C" PRIMARY KEY,
    session_id    TEXT COLLATE "C" NOT NULL REFERENCES sessions(id) ON DELETE CASCADE,
    joints_deg    TEXT NOT NULL,
    pose_set      TEXT NOT NULL CHECK (pose_set IN ('cal', 'val')),
    image_sha256  TEXT REFERENCES blobs(sha256),
    image_meta    TEXT,
    points        TEXT NOT NULL,
    measured      TEXT,
    created_at    TEXT NOT NULL
);
CREATE INDEX poses_by_session ON poses(session_id, id);

CREATE TABLE jobs (
    id                TEXT COLLATE "C" PRIMARY KEY,
    kind              TEXT NOT NULL,
    session_id        TEXT COLLATE "C" NOT NULL REFERENCES sessions(id) ON DELETE CASCADE,
    serial            TEXT COLLATE "C" NOT NULL,
    options           TEXT NOT NULL,
    state             TEXT NOT NULL
                      CHECK (state IN ('queued', 'running', 'succeeded', 'failed', 'cancelled')),
    stage             TEXT,
    progress          DOUBLE PRECISION NOT NULL DEFAULT 0,
    attempts          BIGINT NOT NULL DEFAULT 0,
    max_attempts      BIGINT NOT NULL,
    worker_id         TEXT,
    lease_expires_at  BIGINT,
    error             TEXT,
    result            TEXT,
    created_at        TEXT NOT NULL,
    started_at        TEXT,
    finished_at       TEXT
);
CREATE INDEX jobs_by_state ON jobs(state, id);
-- Claims look only at unfinished jobs, oldest first: a small partial index,
-- however many finished jobs the table keeps.
CREATE INDEX jobs_claimable_by_id ON jobs(id) WHERE state IN ('queued', 'running');

-- Prompt pickup across replicas: whenever a job becomes claimable (inserted
-- queued, released, or put back for a retry) every listening replica hears
-- of it on commit. Workers still poll, as the fallback (lease expiry has no
-- event, and a listener may be reconnecting).
CREATE FUNCTION robocal_job_claimable() RETURNS trigger LANGUAGE plpgsql AS $$
BEGIN
    PERFORM pg_notify('robocal_jobs', NEW.id);
    RETURN NULL;
END
$$;
CREATE TRIGGER jobs_claimable AFTER INSERT OR UPDATE OF state ON jobs
    FOR EACH ROW WHEN (NEW.state = 'queued') EXECUTE FUNCTION robocal_job_claimable();

-- Results: one identified parameter set per (serial, version), versions
-- counted per serial from 1. The counter row is bumped in the transaction
-- that inserts the set, so concurrent replicas serialise on it (row lock) and
-- a rolled-back insert leaves no gap.
CREATE TABLE parameter_set_counters (
    serial        TEXT PRIMARY KEY,
    last_version  BIGINT NOT NULL
);

CREATE TABLE parameter_sets (
    serial      TEXT NOT NULL,
    version     BIGINT NOT NULL,
    job_id      TEXT,
    parameters  TEXT NOT NULL,
    created_at  TEXT NOT NULL,
    PRIMARY KEY (serial, version)
);

CREATE TABLE reports (
    serial   TEXT NOT NULL,
    version  BIGINT NOT NULL,
    report   TEXT NOT NULL,
    PRIMARY KEY (serial, version),
    FOREIGN KEY (serial, version) REFERENCES parameter_sets(serial, version) ON DELETE CASCADE
);

-- Bearer tokens: only the SHA-256 of the token is kept.
CREATE TABLE tokens (
    id          TEXT COLLATE "C" PRIMARY KEY,
    name        TEXT NOT NULL,
    token_hash  TEXT NOT NULL UNIQUE,
    scope       TEXT NOT NULL CHECK (scope IN ('read', 'write', 'admin')),
    created_at  TEXT NOT NULL
);

-- Stored responses of writes carrying an Idempotency-Key, per principal,
-- method and path. state 'pending' while the first request runs.
CREATE TABLE idempotency (
    principal    TEXT NOT NULL,
    method       TEXT NOT NULL,
    path         TEXT NOT NULL,
    idem_key     TEXT NOT NULL,
    state        TEXT NOT NULL CHECK (state IN ('pending', 'done')),
    status       BIGINT,
    headers      TEXT,
    body         BYTEA,
    created_ms   BIGINT NOT NULL,
    PRIMARY KEY (principal, method, path, idem_key)
);
