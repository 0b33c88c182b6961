//! Why a detection failed: every failure is a clear error value, never a
//! wrong ordering (issue 3).

use thiserror::Error;

/// Errors of decoding an image and of finding the dot grid in it.
#[derive(Debug, Clone, PartialEq, Error)]
pub enum DetectError {
    /// The target description is not physically meaningful.
    #[error("invalid target description: {0}")]
    InvalidTarget(String),
    /// The bytes are not a decodable PNG/JPEG (empty, truncated, unknown format).
    #[error("cannot decode image: {0}")]
    Decode(String),
    /// The image header claims dimensions beyond the configured limits.
    #[error("image {width}x{height} exceeds the limit of {max_width}x{max_height} pixels")]
    ImageTooLarge {
        width: u32,
        height: u32,
        max_width: u32,
        max_height: u32,
    },
    /// The image is too small to hold a dot grid.
    #[error("image {width}x{height} is too small (minimum {min_side} px per side)")]
    ImageTooSmall {
        width: usize,
        height: usize,
        min_side: usize,
    },
    /// The grey-level buffer does not match its stated dimensions.
    #[error("pixel buffer holds {len} values, expected {width}x{height}")]
    BufferSize {
        width: usize,
        height: usize,
        len: usize,
    },
    /// The image has (almost) no contrast: empty, all black or all white.
    #[error("image has no usable contrast (grey-level range {range:.1})")]
    NoContrast { range: f32 },
    /// No lattice of dots resembling the board was found.
    #[error("no board found: {0}")]
    NoBoard(String),
    /// A lattice was found but part of it lies outside the image.
    #[error(
        "board partly outside the image: found {found_rows}x{found_cols} of {rows}x{cols} dots"
    )]
    BoardPartlyOutside {
        found_rows: usize,
        found_cols: usize,
        rows: usize,
        cols: usize,
    },
    /// A lattice was found but it does not match the target description.
    #[error("dot lattice does not match the target: {0}")]
    GridMismatch(String),
    /// More than one complete board is visible.
    #[error("ambiguous: {0} complete boards are visible")]
    AmbiguousBoards(usize),
    /// The target has an origin marker but no corner dot is larger.
    #[error("origin marker not found: {0}")]
    MarkerNotFound(String),
    /// More than one dot looks like the origin marker.
    #[error("origin marker ambiguous: {0}")]
    MarkerAmbiguous(String),
    /// More than one placement of the dots on the board fits the image, and
    /// the placements are not related by the board's own symmetry.
    #[error("ordering ambiguous: {0}")]
    OrderingAmbiguous(String),
    /// The dots are too small in the image for a sub-pixel centre.
    #[error("dots too small: median area {median_area_px:.1} px, minimum {min_area_px:.1} px")]
    DotsTooSmall {
        median_area_px: f64,
        min_area_px: f64,
    },
    /// The dot edges are too blurred (or too low in contrast) for a sub-pixel centre.
    #[error("dots too blurred: {0}")]
    DotsTooBlurred(String),
}

impl DetectError {
    /// A stable short name of the failure, so that callers can tell when
    /// many images fail for one reason although their messages differ in
    /// the figures they quote.
    pub fn kind(&self) -> &'static str {
        match self {
            DetectError::InvalidTarget(_) => "invalid_target",
            DetectError::Decode(_) => "decode",
            DetectError::ImageTooLarge { .. } => "image_too_large",
            DetectError::ImageTooSmall { .. } => "image_too_small",
            DetectError::BufferSize { .. } => "buffer_size",
            DetectError::NoContrast { .. } => "no_contrast",
            DetectError::NoBoard(_) => "no_board",
            DetectError::BoardPartlyOutside { .. } => "board_partly_outside",
            DetectError::GridMismatch(_) => "grid_mismatch",
            DetectError::AmbiguousBoards(_) => "ambiguous_boards",
            DetectError::MarkerNotFound(_) => "marker_not_found",
            DetectError::MarkerAmbiguous(_) => "marker_ambiguous",
            DetectError::OrderingAmbiguous(_) => "ordering_ambiguous",
            DetectError::DotsTooSmall { .. } => "dots_too_small",
            DetectError::DotsTooBlurred(_) => "dots_too_blurred",
        }
    }

    /// Whether the failure means the image does not show the target as
    /// described (another board, or none), rather than a poor image of it.
    pub fn is_target_missing(&self) -> bool {
        matches!(
            self,
            DetectError::NoBoard(_)
                | DetectError::GridMismatch(_)
                | DetectError::BoardPartlyOutside { .. }
                | DetectError::AmbiguousBoards(_)
                | DetectError::MarkerNotFound(_)
        )
    }
}
