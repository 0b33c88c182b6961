-- robocal schema, SQLite flavour. JSON documents are TEXT; timestamps shown to
-- users are RFC 3339 TEXT; lease deadlines are INTEGER unix milliseconds so
-- they compare as numbers.

CREATE TABLE robots (
    serial      TEXT PRIMARY KEY,
    model       TEXT NOT NULL,
    preset      TEXT,
    kinematics  TEXT NOT NULL,
    created_at  TEXT NOT NULL,
    updated_at  TEXT NOT NULL
);

CREATE TABLE sessions (
    id          TEXT PRIMARY KEY,
    serial      TEXT NOT NULL REFERENCES robots(serial) ON DELETE CASCADE,
    instrument  TEXT NOT NULL CHECK (instrument IN ('camera', 'tracker')),
    spec        TEXT NOT NULL,
    created_at  TEXT NOT NULL
);
CREATE INDEX sessions_by_serial ON sessions(serial, id);

-- Content-addressed image store: an image is written once, whatever the
-- number of poses naming it.
CREATE TABLE blobs (
    sha256        TEXT PRIMARY KEY,
    size_bytes    INTEGER NOT NULL,
    content_type  TEXT NOT NULL,
    data          BLOB NOT NULL,
    created_at    TEXT NOT NULL
);

CREATE TABLE poses (
    id            TEXT PRIMARY KEY,
    session_id    TEXT NOT NULL REFERENCES sessions(id) ON DELETE CASCADE,
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
    id                TEXT PRIMARY KEY,
    kind              TEXT NOT NULL,
    session_id        TEXT NOT NULL REFERENCES sessions(id) ON DELETE CASCADE,
    serial            TEXT NOT NULL,
    options           TEXT NOT NULL,
    state             TEXT NOT NULL
                      CHECK (state IN ('queued', 'running', 'succeeded', 'failed', 'cancelled')),
    stage             TEXT,
    progress          REAL NOT NULL DEFAULT 0,
    attempts          INTEGER NOT NULL DEFAULT 0,
    max_attempts      INTEGER NOT NULL,
    worker_id         TEXT,
    lease_expires_at  INTEGER,
    error             TEXT,
    result            TEXT,
    created_at        TEXT NOT NULL,
    started_at        TEXT,
    finished_at       TEXT
);
CREATE INDEX jobs_by_state ON jobs(state, id);

-- Results: one identified parameter set per (serial, version), versions
-- counted per serial from 1; the report belonging to it as a JSON document.
CREATE TABLE parameter_sets (
    serial      TEXT NOT NULL,
    version     INTEGER NOT NULL,
    job_id      TEXT,
    parameters  TEXT NOT NULL,
    created_at  TEXT NOT NULL,
    PRIMARY KEY (serial, version)
);

CREATE TABLE reports (
    serial   TEXT NOT NULL,
    version  INTEGER NOT NULL,
    report   TEXT NOT NULL,
    PRIMARY KEY (serial, version),
    FOREIGN KEY (serial, version) REFERENCES parameter_sets(serial, version) ON DELETE CASCADE
);

-- Bearer tokens: only the SHA-256 of the token is kept.
CREATE TABLE tokens (
    id          TEXT PRIMARY KEY,
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
    status       INTEGER,
    headers      TEXT,
    body         BLOB,
    created_ms   INTEGER NOT NULL,
    PRIMARY KEY (principal, method, path, idem_key)
);
