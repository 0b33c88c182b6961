//! Public entry of the dot-grid detector (method.md §1): threshold, blobs,
//! sub-pixel ellipses, lattice, orientation, perspective-bias correction.

use image::DynamicImage;
use nalgebra::Vector2;
use serde::{Deserialize, Serialize};

use super::asymmetric::AsymmetricCirclesSpec;
use super::bias::perspective_bias;
use super::blobs::{find_blobs, Blob};
use super::circle_board::CircleBoard;
use super::ellipse::{refine_dot, DotQuality, Ellipse, Rejection};
use super::error::DetectError;
use super::grid::{grow_lattices, Candidates, Lattice, MIN_LATTICE_DOTS};
use super::image::GrayImage;
use super::order::{order_lattice, Ordering};
use super::target::TargetSpec;
use super::threshold::{auto_window_radius, local_threshold};

/// Smallest accepted image side, pixels.
pub const MIN_IMAGE_SIDE_PX: usize = 16;
/// An image whose 1st-99th percentile grey range is below this has no board.
pub const MIN_IMAGE_RANGE_GREY: f32 = 20.0;
/// Blobs below this area are noise.
const MIN_BLOB_AREA_PX: f64 = 3.0;
/// Dots below this area are too small for a sub-pixel centre.
pub const MIN_DOT_AREA_PX: f64 = 12.0;
/// An incomplete lattice of dots below this area is reported as too small.
pub const SMALL_DOT_AREA_PX: f64 = 30.0;
/// Accepted thresholded-area / moment-ellipse-area range (convexity proxy).
const MIN_FILL_RATIO: f64 = 0.8;
const MAX_FILL_RATIO: f64 = 1.25;
/// Smallest accepted minor/major axis ratio (60 degree tilt gives ~0.5).
const MIN_AXIS_RATIO: f64 = 0.15;
/// More dot-like blobs than this is clutter or noise, not a board.
pub const MAX_CANDIDATES: usize = 5000;
/// Pixel step of the grey-range sampling.
const RANGE_SAMPLE_STEP: usize = 7;
/// Fraction of a lattice step beyond the next dot that must still be inside
/// the image for that dot to count as visible.
const EDGE_FIT_FRACTION: f64 = 0.5;
/// A partial view must show at least this fraction of the board's dots.
pub const MIN_VIEW_FRACTION: f64 = 0.25;
/// Area ratio slack between lattice neighbours beyond the marker's own ratio.
const SIZE_RATIO_SLACK: f64 = 2.0;

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

/// Grey range between the 1st and 99th percentile of a pixel sample.
fn grey_range(img: &GrayImage) -> f32 {
    let mut hist = [0usize; 256];
    let mut n = 0usize;
    for v in img.data.iter().step_by(RANGE_SAMPLE_STEP) {
        hist[v.clamp(0.0, 255.0) as usize] += 1;
        n += 1;
    }
    let pct = |f: f64| {
        let goal = (f * n as f64) as usize;
        let mut acc = 0usize;
        hist.iter()
            .position(|&h| {
                acc += h;
                acc > goal
            })
            .unwrap_or(255) as f32
    };
    pct(0.99) - pct(0.01)
}

/// Dot-like blobs and why others were dropped.
struct CandidateSet {
    blobs: Vec<Blob>,
    dots: Vec<super::ellipse::RefinedDot>,
    /// Centres and areas of dot-like blobs too small to refine.
    too_small: Vec<(Vector2<f64>, f64)>,
    /// Centres and areas of dot-like blobs rejected for contrast or edges.
    unsharp: Vec<(Vector2<f64>, f64)>,
}

fn candidates(img: &GrayImage, board: &CircleBoard, opts: &DetectOptions) -> CandidateSet {
    let radius = opts
        .threshold_radius_px
        .unwrap_or_else(|| auto_window_radius(img.width, img.height));
    let thr = local_threshold(img, radius);
    let max_area = (img.width * img.height) as f64 / board.dot_count() as f64;
    let mut set = CandidateSet {
        blobs: Vec::new(),
        dots: Vec::new(),
        too_small: Vec::new(),
        unsharp: Vec::new(),
    };
    for b in find_blobs(img, &thr, MIN_BLOB_AREA_PX) {
        if b.area > max_area || b.touches_border(img.width, img.height) {
            continue;
        }
        let fill = b.area / b.moment_ellipse_area().max(f64::MIN_POSITIVE);
        let (major, minor) = b.moment_semi_axes();
        if !(MIN_FILL_RATIO..=MAX_FILL_RATIO).contains(&fill) || minor < MIN_AXIS_RATIO * major {
            continue;
        }
        if b.area < MIN_DOT_AREA_PX {
            set.too_small.push((Vector2::new(b.cx, b.cy), b.area));
            continue;
        }
        match refine_dot(img, &b) {
            Ok(d) => {
                set.blobs.push(b);
                set.dots.push(d);
            }
            Err(Rejection::NotAnEllipse) => {}
            Err(_) => set.unsharp.push((Vector2::new(b.cx, b.cy), b.area)),
        }
    }
    set
}

/// Whether the lattice continues past its border outside the image.
fn runs_off_image(lat: &Lattice, c: &[Vector2<f64>], w: usize, h: usize) -> bool {
    let inside = |p: Vector2<f64>| p.x >= 0.0 && p.y >= 0.0 && p.x < w as f64 && p.y < h as f64;
    lat.nodes.iter().any(|(&(i, j), &k)| {
        [(1, 0), (-1, 0), (0, 1), (0, -1)].iter().any(|&(di, dj)| {
            let beyond = (i + di, j + dj);
            let back = (i - di, j - dj);
            match (lat.nodes.get(&beyond), lat.nodes.get(&back)) {
                (None, Some(&kb)) => {
                    let step = c[k] - c[kb];
                    // The next dot would not fit with its half-pitch surround.
                    !inside(c[k] + step * (1.0 + EDGE_FIT_FRACTION))
                }
                _ => false,
            }
        })
    })
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
    let set = candidates(img, board, opts);
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

/// Median area of a lattice of at least half the board's dots among
/// rejected blobs, if there is one (the board is there but unusable).
fn rejected_lattice(rejected: &[(Vector2<f64>, f64)], n_dots: usize) -> Option<f64> {
    if rejected.len() < n_dots / 2 || rejected.len() > MAX_CANDIDATES {
        return None;
    }
    let centres: Vec<Vector2<f64>> = rejected.iter().map(|r| r.0).collect();
    let areas: Vec<f64> = rejected.iter().map(|r| r.1).collect();
    let cand = Candidates {
        centres: &centres,
        sizes: &areas,
        max_size_ratio: SIZE_RATIO_SLACK * 2.0,
    };
    let best = grow_lattices(&cand).into_iter().next()?;
    if best.nodes.len() < n_dots / 2 {
        return None;
    }
    let mut a: Vec<f64> = best.nodes.values().map(|&k| areas[k]).collect();
    a.sort_by(f64::total_cmp);
    Some(a[a.len() / 2])
}

/// The clearest error when no board was read: the first lattice's
/// ordering error if there was one, else what the candidates show.
fn explain_failure(
    lattices: &[Lattice],
    set: &CandidateSet,
    centres: &[Vector2<f64>],
    img: &GrayImage,
    board: &CircleBoard,
    ordering_error: Option<DetectError>,
) -> DetectError {
    let n_dots = board.dot_count();
    let Some(best) = lattices.first() else {
        if let Some(median_area_px) = rejected_lattice(&set.too_small, n_dots) {
            return DetectError::DotsTooSmall {
                median_area_px,
                min_area_px: MIN_DOT_AREA_PX,
            };
        }
        if let Some(area) = rejected_lattice(&set.unsharp, n_dots) {
            return DetectError::DotsTooBlurred(format!(
                "a lattice of dots (median area {area:.0} px) has too little contrast or ragged edges"
            ));
        }
        return DetectError::NoBoard(format!("no lattice among {} dot candidates", centres.len()));
    };
    let (ni, nj) = best.shape();
    let (rows, cols) = (board.rows(), board.cols());
    if best.nodes.len() > n_dots {
        return DetectError::GridMismatch(format!(
            "found a lattice of {} dots ({ni}x{nj}), more than the {rows}x{cols} target (clutter in line with the board?)",
            best.nodes.len()
        ));
    }
    let mut areas: Vec<f64> = best.nodes.values().map(|&k| set.blobs[k].area).collect();
    areas.sort_by(f64::total_cmp);
    let median_area_px = areas[areas.len() / 2];
    if median_area_px < SMALL_DOT_AREA_PX && best.nodes.len() < n_dots {
        return DetectError::DotsTooSmall {
            median_area_px,
            min_area_px: SMALL_DOT_AREA_PX,
        };
    }
    if let Some(e) = ordering_error {
        return e;
    }
    if runs_off_image(best, centres, img.width, img.height) {
        return DetectError::BoardPartlyOutside {
            found_rows: ni.min(nj),
            found_cols: ni.max(nj),
            rows,
            cols,
        };
    }
    DetectError::NoBoard(format!(
        "best lattice has {} dots in a {ni}x{nj} box, target is {rows}x{cols} (dots occluded or unreadable?)",
        best.nodes.len(),
    ))
}
