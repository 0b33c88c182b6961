//! The SVG element writer of the report charts and their shared look
//! (font, colours). All text content is escaped on the way in.

use super::format::escape_xml;
use std::fmt::Write;

/// Font used by every chart; generic fallbacks only, nothing is fetched.
pub const FONT_FAMILY: &str = "'DejaVu Sans', 'Helvetica Neue', Arial, sans-serif";
pub const FONT_SIZE: f64 = 11.0;
pub const TITLE_SIZE: f64 = 14.0;
pub const TEXT_COLOR: &str = "#222";
pub const AXIS_COLOR: &str = "#444";
pub const GRID_COLOR: &str = "#e3e3e3";
pub const MUTED_COLOR: &str = "#666";
/// Before calibration: orange; after: blue (distinct for colour-blind
/// readers and still distinct as greys when printed in black and white).
pub const BEFORE_COLOR: &str = "#d9730d";
pub const AFTER_COLOR: &str = "#1f5fa8";
pub const TICK_LENGTH: f64 = 5.0;
/// Left edge of chart titles and legends (aligned with the page text).
pub const TITLE_X: f64 = 4.0;
/// Collects SVG elements; all text content is escaped on the way in.
#[derive(Default)]
pub struct Svg {
    pub body: String,
}

impl Svg {
    pub fn line(&mut self, x1: f64, y1: f64, x2: f64, y2: f64, stroke: &str, width: f64) {
        let _ = writeln!(
            self.body,
            r#"<line x1="{x1:.1}" y1="{y1:.1}" x2="{x2:.1}" y2="{y2:.1}" stroke="{stroke}" stroke-width="{width}"/>"#
        );
    }

    pub fn dashed_line(&mut self, x1: f64, y1: f64, x2: f64, y2: f64, stroke: &str) {
        let _ = writeln!(
            self.body,
            r#"<line x1="{x1:.1}" y1="{y1:.1}" x2="{x2:.1}" y2="{y2:.1}" stroke="{stroke}" stroke-width="1" stroke-dasharray="5 3"/>"#
        );
    }

    /// A filled rectangle; `opacity` 1 for solid.
    pub fn rect(&mut self, x: f64, y: f64, w: f64, h: f64, fill: &str, opacity: f64) {
        let _ = writeln!(
            self.body,
            r#"<rect x="{x:.1}" y="{y:.1}" width="{:.1}" height="{:.1}" fill="{fill}" fill-opacity="{opacity}"/>"#,
            w.max(0.0),
            h.max(0.0)
        );
    }

    pub fn outline(&mut self, x: f64, y: f64, w: f64, h: f64, stroke: &str) {
        let _ = writeln!(
            self.body,
            r#"<rect x="{x:.1}" y="{y:.1}" width="{w:.1}" height="{h:.1}" fill="none" stroke="{stroke}" stroke-width="1"/>"#
        );
    }

    pub fn circle(&mut self, cx: f64, cy: f64, r: f64, fill: &str) {
        let _ = writeln!(
            self.body,
            r#"<circle cx="{cx:.1}" cy="{cy:.1}" r="{r:.1}" fill="{fill}"/>"#
        );
    }

    /// Raw path data (numbers only; callers never pass text here).
    pub fn path(&mut self, d: &str, stroke: &str, width: f64, fill: &str) {
        let _ = writeln!(
            self.body,
            r#"<path d="{d}" stroke="{stroke}" stroke-width="{width}" fill="{fill}"/>"#
        );
    }

    /// Text at (x, y); `anchor` is start, middle or end.
    pub fn text(&mut self, x: f64, y: f64, anchor: &str, size: f64, fill: &str, text: &str) {
        let _ = writeln!(
            self.body,
            r#"<text x="{x:.1}" y="{y:.1}" text-anchor="{anchor}" font-size="{size}" fill="{fill}">{}</text>"#,
            escape_xml(text)
        );
    }

    pub fn bold_text(&mut self, x: f64, y: f64, anchor: &str, size: f64, text: &str) {
        let _ = writeln!(
            self.body,
            r#"<text x="{x:.1}" y="{y:.1}" text-anchor="{anchor}" font-size="{size}" font-weight="bold" fill="{TEXT_COLOR}">{}</text>"#,
            escape_xml(text)
        );
    }

    /// Text rotated by `angle_deg` about its anchor point.
    pub fn rotated_text(&mut self, x: f64, y: f64, angle_deg: f64, anchor: &str, text: &str) {
        let _ = writeln!(
            self.body,
            r#"<text x="{x:.1}" y="{y:.1}" text-anchor="{anchor}" font-size="{FONT_SIZE}" fill="{TEXT_COLOR}" transform="rotate({angle_deg} {x:.1} {y:.1})">{}</text>"#,
            escape_xml(text)
        );
    }

    /// A chart title at the top left of a chart.
    pub fn title(&mut self, x: f64, y: f64, text: &str) {
        self.bold_text(x, y, "start", TITLE_SIZE, text);
    }
}

/// Wraps chart content into a standalone `<svg>` document element.
/// `title` (escaped here) names the image for screen readers and tooltips.
pub fn standalone(width: f64, height: f64, title: &str, body: &str) -> String {
    format!(
        "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"{width}\" height=\"{height}\" \
         viewBox=\"0 0 {width} {height}\" font-family=\"{FONT_FAMILY}\" role=\"img\">\n\
         <title>{}</title>\n<rect width=\"{width}\" height=\"{height}\" fill=\"white\"/>\n{body}</svg>\n",
        escape_xml(title)
    )
}
