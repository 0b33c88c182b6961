//! ArUco markers (issue 14): OpenCV's predefined dictionaries and marker
//! detection (quads in a thresholded image, bit grid sampled through the
//! quad's homography, matched with rotation and error correction).

pub mod dictionary;
pub mod markers;
pub mod quads;

pub use dictionary::{predefined, predefined_all, predefined_names, Dictionary, Identified};
pub use markers::{detect_markers, MarkerObservation};
