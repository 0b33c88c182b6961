-- PostgreSQL flavour of sqlite/0003_image_detection.sql. What the dot
-- detector found on a pose's image, measured once: at upload (or, for poses
-- stored before detection ran at upload, by the first job that decoded the
-- image). {"points":[{"row","col","x","y"}]} with the raw ellipse centres, or
-- {"points":[],"error","error_kind"} when no board was found. Jobs reuse it
-- instead of decoding the image again; NULL when detection never ran (JSON
-- poses, older image poses).
ALTER TABLE poses ADD COLUMN image_detection TEXT;
