-- Stage sessions (issue 18, paper section 4): an image of a camera riding a
-- linear stage carries the stage's reading, `{"sequence": n,
-- "stage_position_mm": [x, y, z]}` as uploaded (checked then). NULL for
-- every other pose; a stage pose stores `joints_deg` as `[]`.
ALTER TABLE poses ADD COLUMN stage_reading TEXT;
