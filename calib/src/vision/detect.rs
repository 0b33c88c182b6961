//! Public entry of the dot-grid detector (method.md §1): threshold, blobs,
//! sub-pixel ellipses, lattice, orientation, perspective-bias correction.

use image::DynamicImage;
use nalgebra::Vector2;
use serde::{Deserialize, Serialize};

use super::asymmetric::AsymmetricCirclesSpec;
use super::bias::perspective_bias;
use super::circle_board::CircleBoard;
use super::detect_failure::explain_failure;
pub use super::detect_failure::SMALL_DOT_AREA_PX;
use super::dot_candidates::{candidates, grey_range, SIZE_RATIO_SLACK};
pub use super::dot_candidates::{MAX_CANDIDATES, MIN_DOT_AREA_PX};
use super::ellipse::{DotQuality, Ellipse};
use super::error::DetectError;
use super::grid::{grow_lattices, Candidates, MIN_LATTICE_DOTS};
use super::image::GrayImage;
use super::order::{order_lattice, Ordering};
use super::target::TargetSpec;

/// Smallest accepted image side, pixels.
pub const MIN_IMAGE_SIDE_PX: usize = 16;
/// An image whose 1st-99th percentile grey range is below this has no board.
pub const MIN_IMAGE_RANGE_GREY: f32 = 20.0;
/// A partial view must show at least this fraction of the board's dots.
pub const MIN_VIEW_FRACTION: f64 = 0.25;

/// Detector settings.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct DetectOptions {
    /// Local-threshold window radius; `None` picks one from the image size.
    pub threshold_radius_px: Option<usize>,
    /// Subtract the perspective bias predicted by local homographies
    /// (`bias.rs`) from the ellipse centres.
    pub correct_perspective_bias: bool,
}

impl Default for DetectOptions {
    fn default() -> Self {
        Self {
            threshold_radius_px: None,
            correct_perspective_bias: true,
        }
    }
}

/// One dot of the board.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct DotObservation {
    pub row: usize,
    pub col: usize,
    /// Estimated image of the dot's centre, pixels (pixel-centre convention):
    /// the ellipse centre minus `perspective_bias_px` when corrected.
    pub x: f64,
    pub y: f64,
    /// The fitted outline (its centre is the raw, uncorrected centre).
    pub ellipse: Ellipse,
    /// Predicted `ellipse centre - image of centre`, pixels, if computed.
    pub perspective_bias_px: Option<[f64; 2]>,
    pub quality: DotQuality,
}

/// A found board: the dots in view (all `rows * cols` of a full view) in
/// row-major order.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Detection {
    pub rows: usize,
    pub cols: usize,
    pub image_width: usize,
    pub image_height: usize,
    pub dots: Vec<DotObservation>,
    /// False when the board's symmetry leaves the ordering ambiguous (a
    /// marker-less grid, an asymmetric grid with an even number of rows):
    /// the reported reading puts its first dot nearest the image's top-left
    /// corner, and `equivalent_turns` lists the others.
    pub ordering_unique: bool,
    /// Quarter turns (1..=3) of the board that read the image equally well
    /// (`CircleBoard::turned` maps the dots); empty when unique.
    #[serde(default)]
    pub equivalent_turns: Vec<u8>,
    /// Whether `x, y` had the perspective bias removed.
    pub perspective_corrected: bool,
}

/// Detects the board with default options.
pub fn detect(img: &GrayImage, target: &TargetSpec) -> Result<Detection, DetectError> {
    detect_with(img, target, &DetectOptions::default())
}

/// Detects the board in a decoded image of any depth and colour type.
pub fn detect_dynamic(img: &DynamicImage, target: &TargetSpec) -> Result<Detection, DetectError> {
    detect(&GrayImage::from_dynamic(img), target)
}

/// Finds the board described by `target` in a grey image.
pub fn detect_with(
    img: &GrayImage,
    target: &TargetSpec,
    opts: &DetectOptions,
) -> Result<Detection, DetectError> {
    detect_board(img, &CircleBoard::Dots(*target), opts)
}

/// Finds an OpenCV asymmetric circle grid (default options).
pub fn detect_asymmetric(
    img: &GrayImage,
    target: &AsymmetricCirclesSpec,
) -> Result<Detection, DetectError> {
    detect_board(
        img,
        &CircleBoard::Asymmetric(*target),
        &DetectOptions::default(),
    )
}

/// Finds any circle board: the whole board, or the part in view when the
/// view fixes which dots they are (`order.rs`).
pub fn detect_board(
    img: &GrayImage,
    board: &CircleBoard,
    opts: &DetectOptions,
) -> Result<Detection, DetectError> {
    board.validate()?;
    if img.width.checked_mul(img.height) != Some(img.data.len()) {
        return Err(DetectError::BufferSize {
            width: img.width,
            height: img.height,
            len: img.data.len(),
        });
    }
    if img.width < MIN_IMAGE_SIDE_PX || img.height < MIN_IMAGE_SIDE_PX {
        return Err(DetectError::ImageTooSmall {
            width: img.width,
            height: img.height,
            min_side: MIN_IMAGE_SIDE_PX,
        });
    }
    let range = grey_range(img);
    if range < MIN_IMAGE_RANGE_GREY {
        return Err(DetectError::NoContrast { range });
    }
    let set = candidates(img, board, opts.threshold_radius_px);
    let n_dots = board.dot_count();
    if set.dots.len() > MAX_CANDIDATES {
        return Err(DetectError::NoBoard(format!(
            "{} dot-like blobs: clutter or noise",
            set.dots.len()
        )));
    }
    let centres: Vec<Vector2<f64>> = set
        .dots
        .iter()
        .map(|d| Vector2::new(d.ellipse.cx, d.ellipse.cy))
        .collect();
    let areas: Vec<f64> = set.blobs.iter().map(|b| b.area).collect();
    let marker_ratio = board
        .marker_diameter_mm()
        .map_or(1.0, |m| (m / board.dot_diameter_mm()).powi(2));
    let cand = Candidates {
        centres: &centres,
        sizes: &areas,
        max_size_ratio: marker_ratio * SIZE_RATIO_SLACK,
    };
    let lattices = grow_lattices(&cand);
    let min_dots = MIN_LATTICE_DOTS.max((MIN_VIEW_FRACTION * n_dots as f64).ceil() as usize);
    let mut orderings: Vec<(usize, Ordering)> = Vec::new();
    let mut first_error = None;
    for (k, lattice) in lattices.iter().enumerate() {
        if lattice.nodes.len() < min_dots || lattice.nodes.len() > n_dots {
            continue;
        }
        match order_lattice(
            lattice,
            &centres,
            &areas,
            &set.unsharp,
            board,
            (img.width, img.height),
        ) {
            Ok(o) => orderings.push((k, o)),
            Err(e) => {
                first_error.get_or_insert(e);
            }
        }
    }
    let complete = orderings
        .iter()
        .filter(|(_, o)| o.nodes.len() == n_dots)
        .count();
    if complete > 1 {
        return Err(DetectError::AmbiguousBoards(complete));
    }
    // Lattices come largest first: the first readable one is the board.
    let Some((_, ordering)) = orderings.into_iter().next() else {
        return Err(explain_failure(
            &lattices,
            &set,
            &centres,
            img,
            board,
            first_error,
        ));
    };
    let raw: Vec<(usize, usize, Vector2<f64>)> = ordering
        .nodes
        .iter()
        .map(|n| (n.row, n.col, centres[n.index]))
        .collect();
    let bias = if opts.correct_perspective_bias {
        perspective_bias(&raw, board)
    } else {
        vec![None; raw.len()]
    };
    let dots = ordering
        .nodes
        .iter()
        .zip(&bias)
        .map(|(n, b)| {
            let d = &set.dots[n.index];
            let c = centres[n.index] - b.unwrap_or_else(Vector2::zeros);
            DotObservation {
                row: n.row,
                col: n.col,
                x: c.x,
                y: c.y,
                ellipse: d.ellipse,
                perspective_bias_px: b.map(|v| [v.x, v.y]),
                quality: d.quality,
            }
        })
        .collect();
    Ok(Detection {
        rows: board.rows(),
        cols: board.cols(),
        image_width: img.width,
        image_height: img.height,
        dots,
        ordering_unique: ordering.unique(),
        equivalent_turns: ordering.equivalent_turns,
        perspective_corrected: opts.correct_perspective_bias,
    })
}
