//! The stage's reading of one image of a stage session (issue 18, paper
//! section 4): the sequence (one board placement) and where the stage
//! stood, exactly as its scale reads it. Checked once at upload, stored as
//! the pose column `stage_reading`.

use serde::{Deserialize, Serialize};

use super::{Checker, FieldError, MAX_LENGTH_MM};

/// Largest sequence number: a stage campaign has a few board placements.
pub const MAX_SEQUENCE: u32 = 1000;

#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct StageReading {
    pub sequence: u32,
    /// Stage position (mm, the stage's own axes).
    pub stage_position_mm: [f64; 3],
}

impl StageReading {
    /// Checks the two multipart parts of a stage pose; both are required.
    pub fn check(
        sequence: Option<u32>,
        stage_position_mm: Option<[f64; 3]>,
    ) -> Result<Self, Vec<FieldError>> {
        let mut c = Checker::default();
        match sequence {
            None => c.fail(
                "sequence",
                "required part of a stage pose (an integer 1 to 1000)",
            ),
            Some(s) if !(1..=MAX_SEQUENCE).contains(&s) => {
                c.fail("sequence", format!("must be 1 to {MAX_SEQUENCE}"))
            }
            Some(_) => {}
        }
        match stage_position_mm {
            None => c.fail(
                "stage_position_mm",
                "required part of a stage pose (JSON [x, y, z] in mm)",
            ),
            Some(p) => {
                for (i, v) in p.iter().enumerate() {
                    c.bounded(format!("stage_position_mm[{i}]"), *v, MAX_LENGTH_MM, "mm");
                }
            }
        }
        c.finish()?;
        Ok(Self {
            sequence: sequence.unwrap_or_default(),
            stage_position_mm: stage_position_mm.unwrap_or_default(),
        })
    }
}
