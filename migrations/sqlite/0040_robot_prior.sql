-- The prior on a robot's kinematic deviations from nominal (docs/method.md
-- §6.7) as a JSON document ({"joint_offset_deg", "length_mm",
-- "twist_deg"}); NULL: manufacturing tolerances.
ALTER TABLE robots ADD COLUMN prior TEXT;
