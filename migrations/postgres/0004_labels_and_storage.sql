-- PostgreSQL flavour of sqlite/0004_labels_and_storage.sql.
-- Pose labels: the uploaded image's file name (multipart filename, or the
-- image's path inside a dataset archive), or the `label` a JSON pose sent;
-- NULL when none was given (reports then number the pose, `#12`).
ALTER TABLE poses ADD COLUMN label TEXT;

-- Blob collection: unix ms of the last upload that stored (or re-stored)
-- the image, so the periodic collection leaves alone images an upload
-- stored a moment ago and has not yet attached to its pose; and an index
-- to find the blobs no pose references.
ALTER TABLE blobs ADD COLUMN touched_ms BIGINT NOT NULL DEFAULT 0;
CREATE INDEX poses_by_image ON poses(image_sha256);

-- Deleting a robot now deletes its parameter sets (and version counter);
-- the sets of robots deleted before this migration would otherwise
-- reappear as `latest` of a robot re-created under the same serial.
DELETE FROM parameter_sets WHERE serial NOT IN (SELECT serial FROM robots);
DELETE FROM parameter_set_counters WHERE serial NOT IN (SELECT serial FROM robots);
