//! Dot-grid target detection (method.md §1): threshold, blobs, ellipses, grid;
//! robocal's symmetric grid (with or without origin marker) and OpenCV's
//! asymmetric circle grid (issue 14), plus ChArUco boards.
//!
//! Entry points: [`decode_image`] for untrusted bytes, [`detect`] /
//! [`detect_with`] for a grey image and a [`TargetSpec`].

pub mod aruco;
pub mod asymmetric;
pub mod bias;
pub mod blobs;
pub mod board_point;
pub mod charuco;
pub mod chessboard;
pub mod circle_board;
pub mod detect;
mod detect_failure;
mod dot_candidates;
pub mod drawing;
pub mod ellipse;
pub mod error;
pub mod grid;
pub mod homography;
pub mod image;
pub mod order;
mod order_reading;
mod png_rows;
pub mod saddle;
pub mod site_prediction;
pub mod source_header;
pub mod target;
pub mod threshold;

pub use asymmetric::AsymmetricCirclesSpec;
pub use board_point::{BoardDetection, BoardPoint};
pub use circle_board::CircleBoard;
pub use detect::{
    detect, detect_asymmetric, detect_board, detect_dynamic, detect_with, DetectOptions, Detection,
    DotObservation,
};
pub use drawing::{BoardDrawing, Mark};
pub use ellipse::{DotQuality, Ellipse};
pub use error::DetectError;
pub use image::{decode_grey, decode_image, DecodeLimits, DecodedGrey, GrayImage, GreyLevels};
pub use source_header::{read_header, SourceFormat, SourceHeader};
pub use target::TargetSpec;

#[cfg(test)]
mod circle_tests;
#[cfg(test)]
mod detect_tests;
#[cfg(test)]
mod real_data_tests;
