-- Campaign plans (issue 16): the request and the plan served back, both as
-- JSON documents. A plan belongs to its robot and goes with it.
CREATE TABLE campaign_plans (
    id          TEXT PRIMARY KEY,
    serial      TEXT NOT NULL REFERENCES robots(serial) ON DELETE CASCADE,
    request     TEXT NOT NULL,
    plan        TEXT NOT NULL,
    created_at  TEXT NOT NULL
);
CREATE INDEX campaign_plans_by_serial ON campaign_plans(serial, id);
