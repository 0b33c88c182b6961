//! A printable target: the board kinds robocal prints, each validated when
//! its request was parsed (`query.rs`), with its drawing and the margin
//! text that tells how to configure a session for it.

use robocal_calib::vision::charuco::CharucoSpec;
use robocal_calib::vision::chessboard::ChessboardSpec;
use robocal_calib::vision::{AsymmetricCirclesSpec, BoardDrawing, TargetSpec};

/// The target kinds robocal prints.
#[derive(Debug, Clone, PartialEq)]
pub enum PrintableTarget {
    /// robocal's dot grid (with or without the origin marker).
    Dots(TargetSpec),
    /// An OpenCV ChArUco board (validated: it can be drawn).
    Charuco(CharucoSpec),
    /// A chessboard (validated), OpenCV's corner order.
    Chessboard(ChessboardSpec),
    /// OpenCV's asymmetric circle grid (validated).
    AsymmetricCircles(AsymmetricCirclesSpec),
}

impl PrintableTarget {
    pub fn drawing(&self) -> BoardDrawing {
        match self {
            PrintableTarget::Dots(t) => t.drawing(),
            PrintableTarget::Charuco(t) => {
                t.drawing().expect("validated when the request was parsed")
            }
            PrintableTarget::Chessboard(t) => {
                t.drawing().expect("validated when the request was parsed")
            }
            PrintableTarget::AsymmetricCircles(t) => t.drawing(),
        }
    }

    /// The length that sets the board's size: the dot pitch, the square.
    pub fn main_length_mm(&self) -> f64 {
        match self {
            PrintableTarget::Dots(t) => t.pitch_mm,
            PrintableTarget::Charuco(t) => t.square_mm,
            PrintableTarget::Chessboard(t) => t.square_mm,
            PrintableTarget::AsymmetricCircles(t) => t.pitch_mm,
        }
    }

    /// Every length times `k`; the main length exactly, the others rounded
    /// to `round_mm` (the sizes a person types into a session).
    pub fn scaled(&self, k: f64, round_mm: f64) -> PrintableTarget {
        let r = |v: f64| (v * k / round_mm).round() * round_mm;
        let main = self.main_length_mm() * k;
        match self {
            PrintableTarget::Dots(t) => PrintableTarget::Dots(TargetSpec {
                pitch_mm: main,
                dot_diameter_mm: r(t.dot_diameter_mm),
                origin_marker_diameter_mm: t.origin_marker_diameter_mm.map(r),
                ..*t
            }),
            PrintableTarget::Charuco(t) => PrintableTarget::Charuco(CharucoSpec {
                square_mm: main,
                marker_mm: r(t.marker_mm),
                ..t.clone()
            }),
            PrintableTarget::Chessboard(t) => PrintableTarget::Chessboard(ChessboardSpec {
                square_mm: main,
                ..t.clone()
            }),
            PrintableTarget::AsymmetricCircles(t) => {
                PrintableTarget::AsymmetricCircles(AsymmetricCirclesSpec {
                    pitch_mm: main,
                    dot_diameter_mm: r(t.dot_diameter_mm),
                    ..*t
                })
            }
        }
    }

    /// The margin text: the spec as a session's `target` JSON, so the sheet
    /// says how to configure a session for it.
    pub fn spec_lines(&self) -> Vec<String> {
        match self {
            PrintableTarget::Dots(t) => {
                let marker = t
                    .origin_marker_diameter_mm
                    .map(|m| format!(", \"origin_marker_diameter_mm\": {m}"))
                    .unwrap_or_default();
                vec![
                    format!(
                        "robocal dot grid {} x {}, pitch {} mm, dots {} mm",
                        t.rows, t.cols, t.pitch_mm, t.dot_diameter_mm
                    ),
                    format!(
                        "session target: {{\"kind\": \"dots\", \"rows\": {}, \"cols\": {}, \"pitch_mm\": {}, \"dot_diameter_mm\": {}{marker}}}",
                        t.rows, t.cols, t.pitch_mm, t.dot_diameter_mm
                    ),
                ]
            }
            PrintableTarget::Charuco(t) => vec![
                format!(
                    "ChArUco {} x {} squares of {} mm, markers {} mm, {}{}",
                    t.cols(),
                    t.rows(),
                    t.square_mm,
                    t.marker_mm,
                    t.dictionary,
                    if t.legacy_layout { ", legacy layout (OpenCV < 4.6)" } else { "" }
                ),
                format!(
                    "session target: {{\"kind\": \"charuco\", \"squares\": [{}, {}], \"square_mm\": {}, \"marker_mm\": {}, \"dictionary\": \"{}\", \"legacy_layout\": {}}}",
                    t.cols(),
                    t.rows(),
                    t.square_mm,
                    t.marker_mm,
                    t.dictionary,
                    t.legacy_layout
                ),
            ],
            PrintableTarget::Chessboard(t) => vec![
                format!(
                    "chessboard {} x {} inner corners, squares of {} mm",
                    t.cols(),
                    t.rows(),
                    t.square_mm
                ),
                format!(
                    "session target: {{\"kind\": \"chessboard\", \"inner_corners\": [{}, {}], \"square_mm\": {}}}",
                    t.cols(),
                    t.rows(),
                    t.square_mm
                ),
            ],
            PrintableTarget::AsymmetricCircles(t) => vec![
                format!(
                    "asymmetric circle grid: {} rows of {} dots {} mm, rows {} mm apart, dots in a row {} mm apart (OpenCV findCirclesGrid patternSize ({}, {}))",
                    t.rows,
                    t.cols,
                    t.dot_diameter_mm,
                    t.pitch_mm,
                    2.0 * t.pitch_mm,
                    t.cols,
                    t.rows
                ),
                format!(
                    "session target: {{\"kind\": \"asymmetric_circles\", \"rows\": {}, \"cols\": {}, \"pitch_mm\": {}, \"dot_diameter_mm\": {}}}",
                    t.rows, t.cols, t.pitch_mm, t.dot_diameter_mm
                ),
            ],
        }
    }
}
