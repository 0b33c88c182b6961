//! Chessboards (issue 14): the spec as OpenCV's `findChessboardCorners`
//! takes it, and detection (saddle candidates → lattice → OpenCV order →
//! sub-pixel saddle fit).

pub mod candidates;
pub mod detect;
pub mod drawing;
pub mod lattice;
pub mod orient;
mod seed;
pub mod spec;

pub use detect::detect_chessboard;
pub use spec::ChessboardSpec;
