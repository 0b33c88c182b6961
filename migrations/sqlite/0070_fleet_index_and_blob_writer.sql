-- A robot's jobs newest first (ids are UUIDv7): the fleet page reads each
-- robot's newest job and newest re-check inside one statement, an index
-- lookup per robot instead of a scan of every job.
CREATE INDEX jobs_by_serial ON jobs(serial, id);

-- The process that stored an image (host, boot, process id and start
-- time): an image no pose names whose writer is known to be gone (a
-- killed upload) is collected at once, not after the grace period.
ALTER TABLE blobs ADD COLUMN stored_by TEXT;
