-- The image points a calibration job measured on each pose (detected dot
-- centres, and after a successful job their reprojection residuals), as one
-- JSON document per pose: {"job_id","points":[{"row","col","x","y",
-- "residual_px"?}],...}. NULL until a job has run the detect stage. `points`
-- (what was uploaded) is never rewritten; each job replaces every pose's
-- document of its session in one transaction.
ALTER TABLE poses ADD COLUMN detection TEXT;
