//! Description of a printed ChArUco board (issue 14), as OpenCV's
//! `CharucoBoard(squares, square_length, marker_length, dictionary)` with
//! `setLegacyPattern(legacy_layout)`.

use serde::{Deserialize, Serialize};

use crate::vision::aruco::{predefined, predefined_names, Dictionary};
use crate::vision::error::DetectError;

/// Largest number of squares per side accepted: protects every allocation.
pub const MAX_SQUARES_SIDE: usize = 200;
/// Fewest squares per side: one inner corner needs a 2x2 block.
pub const MIN_SQUARES_SIDE: usize = 2;

/// A chessboard of `squares[0] x squares[1]` (cols x rows) squares with an
/// ArUco marker centred in every white square.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct CharucoSpec {
    /// Squares along x (cols) and along y (rows).
    pub squares: [usize; 2],
    /// Side of a chessboard square.
    pub square_mm: f64,
    /// Side of a marker including its black border.
    pub marker_mm: f64,
    /// OpenCV predefined dictionary name, e.g. `DICT_5X5_100`.
    pub dictionary: String,
    /// Layout of OpenCV < 4.6 (differs only for an even number of rows).
    #[serde(default)]
    pub legacy_layout: bool,
}

impl CharucoSpec {
    /// Squares along x.
    pub fn cols(&self) -> usize {
        self.squares[0]
    }

    /// Squares along y.
    pub fn rows(&self) -> usize {
        self.squares[1]
    }

    /// The marker dictionary; `InvalidTarget` naming the accepted names.
    pub fn dictionary(&self) -> Result<&'static Dictionary, DetectError> {
        predefined(&self.dictionary).ok_or_else(|| {
            DetectError::InvalidTarget(format!(
                "dictionary: unknown '{}'; accepted: {}",
                self.dictionary,
                predefined_names().join(", ")
            ))
        })
    }

    /// Checks that the board can be printed and detected; the message names
    /// the offending field (issue 14 "Bad input").
    pub fn validate(&self) -> Result<(), DetectError> {
        let bad = |why: String| Err(DetectError::InvalidTarget(why));
        for (k, &n) in self.squares.iter().enumerate() {
            if !(MIN_SQUARES_SIDE..=MAX_SQUARES_SIDE).contains(&n) {
                return bad(format!(
                    "squares[{k}]: must be {MIN_SQUARES_SIDE}..={MAX_SQUARES_SIDE}, got {n}"
                ));
            }
        }
        if !(self.square_mm.is_finite() && self.square_mm > 0.0) {
            return bad(format!(
                "square_mm: must be positive, got {}",
                self.square_mm
            ));
        }
        if !(self.marker_mm.is_finite() && self.marker_mm > 0.0) {
            return bad(format!(
                "marker_mm: must be positive, got {}",
                self.marker_mm
            ));
        }
        if self.marker_mm >= self.square_mm {
            return bad(format!(
                "marker_mm: must be smaller than square_mm ({} >= {})",
                self.marker_mm, self.square_mm
            ));
        }
        let dict = self.dictionary()?;
        let needed = self.marker_count();
        if needed > dict.len() {
            return bad(format!(
                "dictionary: {} holds {} markers, the board needs {needed}",
                dict.name,
                dict.len()
            ));
        }
        Ok(())
    }

    /// Whether square `(col, row)` is white and carries a marker. OpenCV
    /// ≥ 4.6 puts the first marker in square (1, 0); the legacy layout on
    /// boards with an even number of rows starts with one in (0, 0).
    pub fn has_marker(&self, col: usize, row: usize) -> bool {
        let parity = if self.legacy_layout && self.rows().is_multiple_of(2) {
            0
        } else {
            1
        };
        (col + row) % 2 == parity
    }

    /// Number of markers on the board.
    pub fn marker_count(&self) -> usize {
        (0..self.rows())
            .map(|r| (0..self.cols()).filter(|&c| self.has_marker(c, r)).count())
            .sum()
    }
}
