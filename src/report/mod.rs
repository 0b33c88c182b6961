//! The accuracy report of a parameter set (api.md "Results"): its data
//! model, and its renderings (SVG, self-contained HTML, terminal table).

pub mod model;

pub use model::*;
