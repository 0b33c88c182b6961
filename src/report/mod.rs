//! The accuracy report of a parameter set (api.md "Results"): its data
//! model, and its renderings: one SVG sheet of charts ([`render_svg`]), a
//! printable self-contained HTML page ([`render_html`]) and a plain-text
//! terminal table ([`render_table`]).

mod chart_frame;
mod distribution;
mod field;
mod field_key;
mod field_marks;
pub mod format;
mod gate_section;
pub mod hand_eye;
mod hand_eye_section;
mod html;
mod html_sections;
pub mod measurement_accuracy;
pub mod model;
pub mod model_selection;
mod plot;
mod pose_chart;
pub mod regions;
mod regions_chart;
mod regions_section;
mod regions_table;
pub mod sample;
pub mod sample_regions;
pub mod sample_stage;
pub use crate::domain::numerics_schema as schema;
mod stage_chart;
mod stage_section;
pub mod svg;
mod svg_writer;
mod table;
pub mod terms;
mod text_table;
mod uncertainty_chart;
#[cfg(test)]
mod xml_check;

pub use hand_eye::{BoardScaleReport, FrameReport, HandEyeReport};
pub use html::render_html;
pub use measurement_accuracy::{
    MeasurementAccuracyReport, SequenceAccuracyReport, TravelErrorReport,
};
pub use model::*;
pub use svg::render_svg;
pub use table::render_table;
pub use terms::{TermLine, TermsReport};
