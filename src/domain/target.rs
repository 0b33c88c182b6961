//! The board a camera session uses, typed once from the session's `target`
//! (issue 14): robocal's dot grid (with or without its origin marker), a
//! ChArUco board, a chessboard or OpenCV's asymmetric circle grid. Everything downstream
//! (detection at upload, the camera stage) asks this type where a feature
//! sits on the board and how to find it, never the JSON.

use robocal_calib::vision::charuco::{self, CharucoSpec};
use robocal_calib::vision::chessboard::{self, ChessboardSpec};
use robocal_calib::vision::{
    self, AsymmetricCirclesSpec, CircleBoard, DecodedGrey, DetectError, DetectOptions, TargetSpec,
};

use super::{Checker, FieldError, MAX_LENGTH_MM};
use super::{TargetDoc, TargetKind, MAX_GRID_SIDE};

/// One identified board feature in an image: its board indices and its
/// raw image position (px).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct FoundPoint {
    pub row: u32,
    pub col: u32,
    pub x: f64,
    pub y: f64,
}

#[derive(Debug, Clone, PartialEq)]
pub enum Target {
    Dots(TargetSpec),
    Charuco(CharucoSpec),
    Chessboard(ChessboardSpec),
    AsymmetricCircles(AsymmetricCirclesSpec),
}

/// Fields that belong to one kind only, for the "not a field of this kind" check.
const DOT_FIELDS: [&str; 5] = [
    "rows",
    "cols",
    "pitch_mm",
    "dot_diameter_mm",
    "origin_marker_diameter_mm",
];
const CHARUCO_FIELDS: [&str; 5] = [
    "squares",
    "square_mm",
    "marker_mm",
    "dictionary",
    "legacy_layout",
];
const CHESSBOARD_FIELDS: [&str; 2] = ["inner_corners", "square_mm"];
/// An asymmetric grid's fields; every other field is refused.
const ASYMMETRIC_FIELDS: [&str; 4] = ["rows", "cols", "pitch_mm", "dot_diameter_mm"];
/// Fields a kind may omit.
const OPTIONAL_FIELDS: [&str; 2] = ["legacy_layout", "origin_marker_diameter_mm"];

impl Target {
    /// The typed board, or every problem named as `target.<field>`.
    pub fn from_doc(doc: &TargetDoc) -> Result<Target, Vec<FieldError>> {
        let mut c = Checker::default();
        let given = |name: &str| match name {
            "rows" => doc.rows.is_some(),
            "cols" => doc.cols.is_some(),
            "pitch_mm" => doc.pitch_mm.is_some(),
            "dot_diameter_mm" => doc.dot_diameter_mm.is_some(),
            "origin_marker_diameter_mm" => doc.origin_marker_diameter_mm.is_some(),
            "squares" => doc.squares.is_some(),
            "square_mm" => doc.square_mm.is_some(),
            "marker_mm" => doc.marker_mm.is_some(),
            "dictionary" => doc.dictionary.is_some(),
            "inner_corners" => doc.inner_corners.is_some(),
            _ => doc.legacy_layout.is_some(),
        };
        let (own, kind): (&[&str], _) = match doc.kind {
            TargetKind::Dots => (&DOT_FIELDS[..], "dots"),
            TargetKind::Charuco => (&CHARUCO_FIELDS[..], "charuco"),
            TargetKind::Chessboard => (&CHESSBOARD_FIELDS[..], "chessboard"),
            TargetKind::AsymmetricCircles => (&ASYMMETRIC_FIELDS[..], "asymmetric_circles"),
        };
        let every = DOT_FIELDS
            .iter()
            .chain(&CHARUCO_FIELDS)
            .chain(&CHESSBOARD_FIELDS);
        let mut other: Vec<&str> = Vec::new();
        for name in every.copied().filter(|n| !own.contains(n)) {
            if !other.contains(&name) {
                other.push(name);
            }
        }
        for name in other.iter().filter(|n| given(n)) {
            c.fail(
                format!("target.{name}"),
                format!("not a field of a {kind} target"),
            );
        }
        for name in own
            .iter()
            .filter(|n| !given(n) && !OPTIONAL_FIELDS.contains(n))
        {
            c.fail(
                format!("target.{name}"),
                format!("required for a {kind} target"),
            );
        }
        c.finish()?;
        match doc.kind {
            TargetKind::Dots => dots(doc),
            TargetKind::Charuco => charuco(doc),
            TargetKind::Chessboard => chessboard_spec(doc),
            TargetKind::AsymmetricCircles => asymmetric(doc),
        }
    }

    /// Where feature `(row, col)` sits on the board, target frame, mm.
    pub fn point_mm(&self, row: u32, col: u32) -> [f64; 3] {
        match self {
            Target::Dots(t) => t.dot_centre_mm(row as usize, col as usize),
            Target::Charuco(t) => charuco::corner_mm(t, row as usize, col as usize),
            Target::Chessboard(t) => t.corner_mm(row as usize, col as usize),
            Target::AsymmetricCircles(t) => t.dot_centre_mm(row as usize, col as usize),
        }
    }

    /// Features the camera model leaves out: the dot board's larger origin
    /// marker, whose centroid bias differs from the ordinary dots' (the bias
    /// correction models one diameter).
    pub fn left_out(&self, row: u32, col: u32) -> bool {
        match self {
            Target::Dots(t) => {
                row == 0
                    && col == 0
                    && t.origin_marker_diameter_mm
                        .is_some_and(|m| m > t.dot_diameter_mm)
            }
            Target::Charuco(_) | Target::Chessboard(_) | Target::AsymmetricCircles(_) => false,
        }
    }

    /// The diameter whose ellipse-centre bias the camera stage corrects
    /// (method.md §4); `None` for corners, which have no such bias.
    pub fn dot_diameter_mm(&self) -> Option<f64> {
        match self {
            Target::Dots(t) => Some(t.dot_diameter_mm),
            Target::AsymmetricCircles(t) => Some(t.dot_diameter_mm),
            Target::Charuco(_) | Target::Chessboard(_) => None,
        }
    }

    /// Every feature found in `image` (raw positions: for dots the ellipse
    /// centres, whose perspective bias the camera stage corrects from the
    /// calibrated model). A circle grid whose symmetry leaves the dot
    /// identities open in this image beyond the board's own symmetry (which
    /// the job settles from the robot data, [`Target::symmetry`]) is refused
    /// with `OrderingAmbiguous`: identities that might differ from image to
    /// image would bend the fit.
    ///
    /// The saddle detectors (chessboard, ChArUco) read an 8-bit image as
    /// decoded; the circle detectors read f32 levels.
    pub fn detect(&self, image: &DecodedGrey) -> Result<Vec<FoundPoint>, DetectError> {
        let board = match (self, image) {
            (Target::Dots(t), _) => CircleBoard::Dots(*t),
            (Target::AsymmetricCircles(t), _) => CircleBoard::Asymmetric(*t),
            (Target::Charuco(t), DecodedGrey::Levels8(g)) => {
                return Ok(found_points(&charuco::detect_charuco(g, t)?))
            }
            (Target::Charuco(t), DecodedGrey::Float(g)) => {
                return Ok(found_points(&charuco::detect_charuco(g, t)?))
            }
            (Target::Chessboard(t), DecodedGrey::Levels8(g)) => {
                return Ok(found_points(&chessboard::detect_chessboard(g, t)?))
            }
            (Target::Chessboard(t), DecodedGrey::Float(g)) => {
                return Ok(found_points(&chessboard::detect_chessboard(g, t)?))
            }
        };
        let image = image.to_float();
        let options = DetectOptions {
            correct_perspective_bias: false,
            ..DetectOptions::default()
        };
        let found = vision::detect_board(&image, &board, &options)?;
        let settled_later = self
            .symmetry()
            .is_some_and(|s| found.equivalent_turns.iter().all(|k| s.turns.contains(k)));
        if !found.ordering_unique && !settled_later {
            let turns: Vec<String> = found
                .equivalent_turns
                .iter()
                .map(|k| format!("{} deg", 90 * u32::from(*k)))
                .collect();
            return Err(DetectError::OrderingAmbiguous(format!(
                "the board reads the same turned by {}: its dots cannot be told apart (use a board with an origin marker, or an asymmetric grid with an odd number of rows)",
                turns.join(" or ")
            )));
        }
        Ok(found
            .dots
            .iter()
            .map(|d| FoundPoint {
                row: d.row as u32,
                col: d.col as u32,
                x: d.ellipse.cx,
                y: d.ellipse.cy,
            })
            .collect())
    }

    /// Whether every image's features get the same identities (an origin
    /// marker, ChArUco's marker ids, a chessboard's colours when one side is
    /// odd and the other even).
    pub fn ordering_unique(&self) -> bool {
        match self {
            Target::Dots(t) => t.origin_marker_diameter_mm.is_some(),
            Target::AsymmetricCircles(t) => t.rows % 2 == 1,
            Target::Charuco(_) => true,
            Target::Chessboard(t) => !t.ambiguous_180(),
        }
    }

    /// How reports name the board: `7x9` (dots, rows x cols) or
    /// `ChArUco 9x7` (squares, cols x rows).
    pub fn board_name(&self) -> String {
        match self {
            Target::Dots(t) => format!("{}x{}", t.rows, t.cols),
            Target::Charuco(t) => format!("ChArUco {}x{}", t.cols(), t.rows()),
            Target::Chessboard(t) => format!("chessboard {}x{}", t.cols(), t.rows()),
            Target::AsymmetricCircles(t) => {
                format!("asymmetric circles {}x{}", t.cols, t.rows)
            }
        }
    }

    /// The fields to check when many images miss the board.
    pub fn fields_hint(&self) -> &'static str {
        match self {
            Target::Dots(_) => "rows, cols, pitch_mm, dot diameters",
            Target::Charuco(_) => "squares, square_mm, marker_mm, dictionary, legacy_layout",
            Target::Chessboard(_) => "inner_corners (cols, rows of inner corners), square_mm",
            Target::AsymmetricCircles(_) => "rows, cols (dots per row), pitch_mm, dot_diameter_mm",
        }
    }
}

fn dots(doc: &TargetDoc) -> Result<Target, Vec<FieldError>> {
    let mut c = Checker::default();
    let rows = doc.rows.unwrap_or_default();
    let cols = doc.cols.unwrap_or_default();
    for (name, v) in [("target.rows", rows), ("target.cols", cols)] {
        if !(2..=MAX_GRID_SIDE).contains(&v) {
            c.fail(name, format!("must be 2 to {MAX_GRID_SIDE}"));
        }
    }
    let pitch = doc.pitch_mm.unwrap_or_default();
    let dot = doc.dot_diameter_mm.unwrap_or_default();
    c.positive("target.pitch_mm", pitch, MAX_LENGTH_MM, "mm");
    c.positive("target.dot_diameter_mm", dot, pitch.abs(), "mm");
    if let Some(marker) = doc.origin_marker_diameter_mm {
        c.positive(
            "target.origin_marker_diameter_mm",
            marker,
            MAX_LENGTH_MM,
            "mm",
        );
    }
    c.finish()?;
    Ok(Target::Dots(TargetSpec {
        rows: rows as usize,
        cols: cols as usize,
        pitch_mm: pitch,
        dot_diameter_mm: dot,
        origin_marker_diameter_mm: doc.origin_marker_diameter_mm,
    }))
}

fn found_points(found: &vision::BoardDetection) -> Vec<FoundPoint> {
    found
        .points
        .iter()
        .map(|p| FoundPoint {
            row: p.row as u32,
            col: p.col as u32,
            x: p.x_px,
            y: p.y_px,
        })
        .collect()
}

fn asymmetric(doc: &TargetDoc) -> Result<Target, Vec<FieldError>> {
    let mut c = Checker::default();
    for (name, v) in [("target.rows", doc.rows), ("target.cols", doc.cols)] {
        if !(2..=MAX_GRID_SIDE).contains(&v.unwrap_or_default()) {
            c.fail(name, format!("must be 2 to {MAX_GRID_SIDE}"));
        }
    }
    let pitch = doc.pitch_mm.unwrap_or_default();
    c.positive("target.pitch_mm", pitch, MAX_LENGTH_MM, "mm");
    c.finish()?;
    let spec = AsymmetricCirclesSpec {
        rows: doc.rows.unwrap_or_default() as usize,
        cols: doc.cols.unwrap_or_default() as usize,
        pitch_mm: pitch,
        dot_diameter_mm: doc.dot_diameter_mm.unwrap_or_default(),
    };
    spec.validate().map_err(field_errors)?;
    Ok(Target::AsymmetricCircles(spec))
}

/// calib names the offending field first ("<field>: why"): the same field
/// under `target.`.
fn field_errors(e: DetectError) -> Vec<FieldError> {
    let text = match e {
        DetectError::InvalidTarget(text) => text,
        other => other.to_string(),
    };
    match text.split_once(": ") {
        Some((field, why)) => vec![FieldError::new(format!("target.{field}"), why)],
        None => vec![FieldError::new("target", text)],
    }
}

fn chessboard_spec(doc: &TargetDoc) -> Result<Target, Vec<FieldError>> {
    let [cols, rows] = doc.inner_corners.unwrap_or_default();
    let spec = ChessboardSpec {
        inner_corners: [cols as usize, rows as usize],
        square_mm: doc.square_mm.unwrap_or_default(),
    };
    spec.validate().map_err(field_errors)?;
    Ok(Target::Chessboard(spec))
}

fn charuco(doc: &TargetDoc) -> Result<Target, Vec<FieldError>> {
    let squares = doc.squares.unwrap_or_default();
    let spec = CharucoSpec {
        squares: [squares[0] as usize, squares[1] as usize],
        square_mm: doc.square_mm.unwrap_or_default(),
        marker_mm: doc.marker_mm.unwrap_or_default(),
        dictionary: doc.dictionary.clone().unwrap_or_default(),
        legacy_layout: doc.legacy_layout.unwrap_or(false),
    };
    // calib names the offending field first: "<field>: why".
    spec.validate().map_err(|e| {
        let text = match e {
            DetectError::InvalidTarget(text) => text,
            other => other.to_string(),
        };
        match text.split_once(": ") {
            Some((field, why)) => vec![FieldError::new(format!("target.{field}"), why)],
            None => vec![FieldError::new("target", text)],
        }
    })?;
    Ok(Target::Charuco(spec))
}
