-- Controller flange poses (issue 14): a camera pose may carry, instead of
-- joint angles, the flange in the robot base frame as the controller
-- reported it, `{"translation_mm":[..],"rotation_deg":[..]}` or
-- `{"translation_mm":[..],"matrix":[[..],[..],[..]]}` as uploaded (checked
-- then). NULL for joint poses; such a pose stores `joints_deg` as `[]`.
ALTER TABLE poses ADD COLUMN flange_pose TEXT;
