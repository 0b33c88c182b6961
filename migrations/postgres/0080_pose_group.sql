-- A pose's configuration group as the client named it (docs/method.md
-- §7.6): poses of one group are held out together when a job chooses its
-- model; NULL: the job groups the pose by its joints 1-3.
ALTER TABLE poses ADD COLUMN pose_group TEXT;
