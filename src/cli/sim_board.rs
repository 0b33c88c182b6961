//! The board `robocal simulate` draws: the 9x9 dot grid its campaigns are
//! planned for, or a chessboard or ChArUco board in the same target frame
//! (each view re-drawn from the simulator's `target_to_camera`), with the
//! session's `target` document that describes it.

use nalgebra::Isometry3;
use rand::rngs::StdRng;
use robocal_calib::camera::model::Intrinsics;
use robocal_calib::sim::render::RenderOptions;
use robocal_calib::sim::render_charuco::render_charuco;
use robocal_calib::sim::render_chessboard::render_chessboard;
use robocal_calib::sim::render_circles::render_target;
use robocal_calib::vision::charuco::CharucoSpec;
use robocal_calib::vision::chessboard::ChessboardSpec;
use robocal_calib::vision::image::GrayImage;
use robocal_calib::vision::TargetSpec;
use serde_json::{json, Value};

/// Squares of the simulated boards, mm: the dot grid's pitch.
const SQUARE_MM: f64 = 25.0;
/// The chessboard's inner corners (cols, rows): one count even, one odd,
/// so an image fixes its orientation (no half-turn to settle), and the
/// board with its outer squares no larger than the dot grid's sheet.
const CHESSBOARD_INNER_CORNERS: [usize; 2] = [8, 7];
/// The ChArUco board's squares (cols, rows), its markers and dictionary:
/// OpenCV's usual DICT_5X5_100 board at the dot grid's pitch.
const CHARUCO_SQUARES: [usize; 2] = [10, 8];
const CHARUCO_MARKER_MM: f64 = 18.0;
const CHARUCO_DICTIONARY: &str = "DICT_5X5_100";

/// Which board the simulated images show.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum SimBoard {
    #[default]
    Dots,
    Chessboard,
    Charuco,
}

impl SimBoard {
    /// The names `robocal simulate --target` takes.
    pub const NAMES: [&'static str; 3] = ["dots", "chessboard", "charuco"];

    pub fn parse(name: &str) -> Result<SimBoard, String> {
        match name {
            "dots" => Ok(SimBoard::Dots),
            "chessboard" => Ok(SimBoard::Chessboard),
            "charuco" => Ok(SimBoard::Charuco),
            other => Err(format!(
                "{other:?} is not a simulated board ({})",
                Self::NAMES.join(", ")
            )),
        }
    }

    fn chessboard() -> ChessboardSpec {
        ChessboardSpec {
            inner_corners: CHESSBOARD_INNER_CORNERS,
            square_mm: SQUARE_MM,
        }
    }

    fn charuco() -> CharucoSpec {
        CharucoSpec {
            squares: CHARUCO_SQUARES,
            square_mm: SQUARE_MM,
            marker_mm: CHARUCO_MARKER_MM,
            dictionary: CHARUCO_DICTIONARY.into(),
            legacy_layout: false,
        }
    }

    /// The session's `target` document for this board.
    pub fn session_target(self) -> Value {
        match self {
            SimBoard::Dots => {
                let t = simulated_target();
                json!({
                    "rows": t.rows, "cols": t.cols, "pitch_mm": t.pitch_mm,
                    "dot_diameter_mm": t.dot_diameter_mm,
                    "origin_marker_diameter_mm": t.origin_marker_diameter_mm,
                })
            }
            SimBoard::Chessboard => {
                let s = Self::chessboard();
                json!({"kind": "chessboard", "inner_corners": s.inner_corners, "square_mm": s.square_mm})
            }
            SimBoard::Charuco => {
                let s = Self::charuco();
                json!({
                    "kind": "charuco", "squares": s.squares, "square_mm": s.square_mm,
                    "marker_mm": s.marker_mm, "dictionary": s.dictionary,
                })
            }
        }
    }

    /// One view of the board (`p_camera = camera_to_target * p_target`).
    pub fn render(
        self,
        intrinsics: &Intrinsics,
        camera_to_target: &Isometry3<f64>,
        size: (usize, usize),
        options: &RenderOptions,
        rng: &mut StdRng,
    ) -> Result<GrayImage, String> {
        let (w, h) = size;
        let image = match self {
            SimBoard::Dots => render_target(
                intrinsics,
                camera_to_target,
                &simulated_target(),
                w,
                h,
                options,
                rng,
            )
            .map(|v| v.image),
            SimBoard::Chessboard => render_chessboard(
                intrinsics,
                camera_to_target,
                &Self::chessboard(),
                w,
                h,
                options,
                rng,
            )
            .map(|v| v.image),
            SimBoard::Charuco => render_charuco(
                intrinsics,
                camera_to_target,
                &Self::charuco(),
                w,
                h,
                options,
                rng,
            )
            .map(|v| v.image),
        };
        image.map_err(|e| e.to_string())
    }
}

/// The board every simulated campaign uses: 9x9 dots of 8 mm on a 25 mm
/// pitch with a 12 mm origin marker.
pub fn simulated_target() -> TargetSpec {
    TargetSpec::robocal_9x9()
}
