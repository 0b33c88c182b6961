//! ChArUco boards (issue 14): the spec, OpenCV's two layouts, and detection
//! (markers → board squares → local homography → inner corners).

pub mod layout;
pub mod spec;

pub use layout::{corner_mm, inner_corner_grid, marker_cells, MarkerCell};
pub use spec::CharucoSpec;
