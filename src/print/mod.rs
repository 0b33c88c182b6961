//! Printable targets (issue "Targets people own"): a board drawn at exact
//! scale on a page with a scale bar and the board's spec in the margin, as
//! SVG or PDF, for `GET /v1/targets/render` and `robocal target`.
//!
//! The board itself comes from `calib` ([`robocal_calib::vision::BoardDrawing`]),
//! the same geometry the detectors use; this module only lays out the page
//! and writes the two formats.

pub mod fill;
pub mod page;
pub mod pdf;
pub mod query;
pub mod svg;
pub mod target;

pub use page::{Page, PageFormat};
pub use query::{parse_pairs, PrintError, PrintRequest};
pub use target::PrintableTarget;

/// `robocal target KEY=VALUE…`: the page's bytes. Errors name the key, as
/// the HTTP route's 422 does.
pub fn render_args(args: &[String]) -> Result<Vec<u8>, String> {
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
    Ok(render(&request))
}

/// The page of a parsed request in its format: on the smallest ISO sheet
/// that holds the board, or with `page` the board scaled to fill that
/// sheet (`fill.rs`; parsing checked that it fits).
pub fn render(request: &PrintRequest) -> Vec<u8> {
    let filled = request
        .page
        .and_then(|(name, size)| fill::fill(&request.target, name, size));
    let page = match filled {
        Some((_, page)) => page,
        None => Page::layout(&request.target.drawing(), &request.target.spec_lines()),
    };
    match request.format {
        PageFormat::Svg => svg::write_svg(&page).into_bytes(),
        PageFormat::Pdf => pdf::write_pdf(&page),
    }
}
