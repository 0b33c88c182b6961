-- The controller a robot runs on (issue 34): its identity as a JSON
-- document ({"vendor", "serial", "software", "kinematics_hash"}), NULL when
-- none was given. Sessions record it in their spec, parameter sets in
-- their document.
ALTER TABLE robots ADD COLUMN controller TEXT;

-- Every change of a robot's controller identity, oldest first (the
-- robot's history): from what (NULL: none), to what, when. Goes with its
-- robot.
CREATE TABLE robot_controller_changes (
    serial           TEXT COLLATE "C" NOT NULL REFERENCES robots(serial) ON DELETE CASCADE,
    seq              BIGINT NOT NULL,
    from_controller  TEXT,
    to_controller    TEXT,
    changed_at       TEXT NOT NULL,
    PRIMARY KEY (serial, seq)
);
