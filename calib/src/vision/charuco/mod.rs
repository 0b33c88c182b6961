//! ChArUco boards (issue 14): the spec, OpenCV's two layouts, and detection
//! (markers → board squares → local homography → inner corners).

pub mod consistency;
pub mod detect;
pub mod drawing;
pub mod layout;
pub mod spec;

pub use detect::{detect_charuco, detect_charuco_with, CornerRefiner};
pub use layout::{corner_mm, inner_corner_grid, marker_cells, squares_around_corner, MarkerCell};
pub use spec::CharucoSpec;
