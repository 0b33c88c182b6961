//! Printable targets (issue "Targets people own"): a board drawn at exact
//! scale on a page with a scale bar and the board's spec in the margin, as
//! SVG or PDF, for `GET /v1/targets/render` and `robocal target`.
//!
//! The board itself comes from `calib` ([`robocal_calib::vision::BoardDrawing`]),
//! the same geometry the detectors use; this module only lays out the page
//! and writes the two formats.

pub mod page;
pub mod pdf;
pub mod query;
pub mod svg;

pub use page::{Page, PageFormat};
pub use query::{parse_pairs, PrintError};

/// `robocal target KEY=VALUE… [--out FILE]`: the page written to `out`, or
/// to standard output. Errors name the key, as the HTTP route's 422 does.
pub fn render_to(args: &[String], out: Option<&std::path::Path>) -> Result<(), String> {
    let pairs = args
        .iter()
        .map(|a| {
            a.split_once('=')
                .map(|(k, v)| (k.to_string(), v.to_string()))
                .ok_or_else(|| format!("{a:?}: expected KEY=VALUE"))
        })
        .collect::<Result<Vec<_>, _>>()?;
    let request = parse_pairs(&pairs).map_err(|errors| {
        errors
            .iter()
            .map(|e| format!("{}: {}", e.field, e.message))
            .collect::<Vec<_>>()
            .join("; ")
    })?;
    let page = Page::layout(&request.target.drawing(), &request.target.spec_lines());
    let bytes = match request.format {
        PageFormat::Svg => svg::write_svg(&page).into_bytes(),
        PageFormat::Pdf => pdf::write_pdf(&page),
    };
    match out {
        Some(path) => std::fs::write(path, bytes).map_err(|e| format!("{}: {e}", path.display())),
        None => {
            use std::io::Write;
            std::io::stdout()
                .write_all(&bytes)
                .map_err(|e| e.to_string())
        }
    }
}
