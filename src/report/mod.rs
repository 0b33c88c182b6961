//! The accuracy report of a parameter set (api.md "Results"): its data
//! model, and its renderings (SVG, self-contained HTML, terminal table).

mod field;
pub mod format;
pub mod model;
pub mod plot;
pub mod sample;
pub mod svg;

pub use model::*;
pub use svg::render_svg;
