//! A printable target from flat `key=value` pairs: the query string of
//! `GET /v1/targets/render` and the arguments of `robocal target`. The keys
//! are a session target's fields (api.md "sessions"), plus `format`.

use std::collections::BTreeMap;

use robocal_calib::vision::charuco::CharucoSpec;
use robocal_calib::vision::chessboard::ChessboardSpec;
use robocal_calib::vision::target::MAX_GRID_SIDE;
use robocal_calib::vision::{AsymmetricCirclesSpec, DetectError, TargetSpec};

use super::page::PageFormat;
use super::target::PrintableTarget;
use crate::schema::{Checker, FieldError};

/// Largest board side printed, mm (an A0 sheet's long side is 1189 mm; a
/// custom sheet may be a little larger, a wall is not).
pub const MAX_PRINT_MM: f64 = 2000.0;

/// Keys a dot board takes.
const DOT_KEYS: [&str; 5] = [
    "rows",
    "cols",
    "pitch_mm",
    "dot_diameter_mm",
    "origin_marker_diameter_mm",
];

/// Keys a ChArUco board takes (`squares` as `cols,rows`).
const CHARUCO_KEYS: [&str; 5] = [
    "squares",
    "square_mm",
    "marker_mm",
    "dictionary",
    "legacy_layout",
];

/// Keys a chessboard takes (`inner_corners` as `cols,rows`).
const CHESSBOARD_KEYS: [&str; 2] = ["inner_corners", "square_mm"];

/// Why pairs could not be turned into a printable target.
pub type PrintError = Vec<FieldError>;

/// A target that can be printed, with the page format asked for.
#[derive(Debug, Clone, PartialEq)]
pub struct PrintRequest {
    pub target: PrintableTarget,
    pub format: PageFormat,
    /// `page=a4` … `a0`: the board scaled to fill that sheet (name,
    /// portrait size mm); `None`: drawn as given on the smallest sheet.
    pub page: Option<(&'static str, [f64; 2])>,
}

/// Parses the pairs; every problem is reported with the key it concerns.
pub fn parse_pairs(pairs: &[(String, String)]) -> Result<PrintRequest, PrintError> {
    let mut c = Checker::default();
    let mut map: BTreeMap<&str, &str> = BTreeMap::new();
    for (k, v) in pairs {
        if map.insert(k.as_str(), v.as_str()).is_some() {
            c.fail(k.clone(), "given more than once");
        }
    }
    let format = match map.remove("format") {
        None | Some("svg") => PageFormat::Svg,
        Some("pdf") => PageFormat::Pdf,
        Some(_) => {
            c.fail("format", "must be svg or pdf");
            PageFormat::Svg
        }
    };
    let page = match map.remove("page") {
        None => None,
        Some(name) => {
            let found = super::fill::sheet(name);
            if found.is_none() {
                c.fail("page", "must be an ISO sheet: a4, a3, a2, a1 or a0");
            }
            found
        }
    };
    let target = match map.remove("kind").unwrap_or("dots") {
        "dots" => dots(&mut c, &mut map),
        "charuco" => charuco(&mut c, &mut map),
        "chessboard" => chessboard(&mut c, &mut map),
        "asymmetric_circles" => asymmetric(&mut c, &mut map),
        other => {
            c.fail(
                "kind",
                format!("{other:?} is not a printable target kind (dots, charuco, chessboard, asymmetric_circles)"),
            );
            None
        }
    };
    for k in map.keys() {
        c.fail(*k, "unknown parameter for this kind");
    }
    if let (Some(t), Some((name, size))) = (&target, page) {
        if super::fill::fill(t, name, size).is_none() {
            c.fail(
                "page",
                format!(
                    "the board does not fit a {name} sheet at a {} mm step",
                    super::fill::STEP_MM
                ),
            );
        }
    }
    c.finish()?;
    target
        .map(|target| PrintRequest {
            target,
            format,
            page,
        })
        .ok_or_else(|| vec![FieldError::new("kind", "incomplete target")])
}

fn dots(c: &mut Checker, map: &mut BTreeMap<&str, &str>) -> Option<PrintableTarget> {
    let got = take_keys(map, &DOT_KEYS);
    let side = |c: &mut Checker, key: &str| -> Option<usize> {
        let v = number(c, &got, key)?;
        if v.fract() != 0.0 || !(2.0..=MAX_GRID_SIDE as f64).contains(&v) {
            c.fail(key, format!("must be a whole number 2 to {MAX_GRID_SIDE}"));
            return None;
        }
        Some(v as usize)
    };
    let rows = side(c, "rows");
    let cols = side(c, "cols");
    let pitch_mm = number(c, &got, "pitch_mm");
    let dot_diameter_mm = number(c, &got, "dot_diameter_mm");
    let origin_marker_diameter_mm = match got.get("origin_marker_diameter_mm") {
        None => None,
        Some(_) => Some(number(c, &got, "origin_marker_diameter_mm")?),
    };
    let (rows, cols, pitch_mm, dot_diameter_mm) = (rows?, cols?, pitch_mm?, dot_diameter_mm?);
    c.positive("pitch_mm", pitch_mm, MAX_PRINT_MM, "mm");
    c.positive("dot_diameter_mm", dot_diameter_mm, MAX_PRINT_MM, "mm");
    if pitch_mm > 0.0 && dot_diameter_mm > 0.0 && dot_diameter_mm >= pitch_mm {
        c.fail(
            "dot_diameter_mm",
            "must be below pitch_mm (dots would touch)",
        );
    }
    if let Some(m) = origin_marker_diameter_mm {
        if !(m > dot_diameter_mm && m < 2.0 * pitch_mm - dot_diameter_mm) {
            c.fail(
                "origin_marker_diameter_mm",
                "must exceed dot_diameter_mm and stay clear of the neighbouring dots",
            );
        }
    }
    let spec = TargetSpec {
        rows,
        cols,
        pitch_mm,
        dot_diameter_mm,
        origin_marker_diameter_mm,
    };
    if (rows.max(cols) + 1) as f64 * pitch_mm > MAX_PRINT_MM {
        c.fail(
            "pitch_mm",
            format!("the board would exceed {MAX_PRINT_MM} mm"),
        );
    }
    Some(PrintableTarget::Dots(spec))
}

fn charuco(c: &mut Checker, map: &mut BTreeMap<&str, &str>) -> Option<PrintableTarget> {
    let got = take_keys(map, &CHARUCO_KEYS);
    let squares = cols_rows(c, &got, "squares")?;
    let square_mm = number(c, &got, "square_mm");
    let marker_mm = number(c, &got, "marker_mm");
    let legacy_layout = match got.get("legacy_layout").copied() {
        None | Some("false") => false,
        Some("true") => true,
        Some(_) => {
            c.fail("legacy_layout", "true or false");
            false
        }
    };
    let Some(dictionary) = got.get("dictionary") else {
        c.fail("dictionary", "required");
        return None;
    };
    let spec = CharucoSpec {
        squares,
        square_mm: square_mm?,
        marker_mm: marker_mm?,
        dictionary: dictionary.to_string(),
        legacy_layout,
    };
    if let Err(e) = spec.validate() {
        let text = match e {
            DetectError::InvalidTarget(text) => text,
            other => other.to_string(),
        };
        match text.split_once(": ") {
            Some((field, why)) => c.fail(field.split('[').next().unwrap_or(field), why),
            None => c.fail("kind", text),
        }
        return None;
    }
    let side_mm = squares[0].max(squares[1]) as f64 * spec.square_mm;
    if side_mm > MAX_PRINT_MM {
        c.fail(
            "square_mm",
            format!("the board would exceed {MAX_PRINT_MM} mm"),
        );
        return None;
    }
    Some(PrintableTarget::Charuco(spec))
}

fn chessboard(c: &mut Checker, map: &mut BTreeMap<&str, &str>) -> Option<PrintableTarget> {
    let got = take_keys(map, &CHESSBOARD_KEYS);
    let inner_corners = cols_rows(c, &got, "inner_corners")?;
    let spec = ChessboardSpec {
        inner_corners,
        square_mm: number(c, &got, "square_mm")?,
    };
    if let Err(e) = spec.validate() {
        let text = match e {
            DetectError::InvalidTarget(text) => text,
            other => other.to_string(),
        };
        match text.split_once(": ") {
            Some((field, why)) => c.fail(field, why),
            None => c.fail("kind", text),
        }
        return None;
    }
    let side_mm = (inner_corners[0].max(inner_corners[1]) + 3) as f64 * spec.square_mm;
    if side_mm > MAX_PRINT_MM {
        c.fail(
            "square_mm",
            format!("the board would exceed {MAX_PRINT_MM} mm"),
        );
        return None;
    }
    Some(PrintableTarget::Chessboard(spec))
}

fn asymmetric(c: &mut Checker, map: &mut BTreeMap<&str, &str>) -> Option<PrintableTarget> {
    let got = take_keys(map, &["rows", "cols", "pitch_mm", "dot_diameter_mm"]);
    let side = |c: &mut Checker, key: &str| -> Option<usize> {
        let v = number(c, &got, key)?;
        if v.fract() != 0.0 || !(2.0..=MAX_GRID_SIDE as f64).contains(&v) {
            c.fail(key, format!("must be a whole number 2 to {MAX_GRID_SIDE}"));
            return None;
        }
        Some(v as usize)
    };
    let rows = side(c, "rows");
    let cols = side(c, "cols");
    let pitch_mm = number(c, &got, "pitch_mm");
    let dot_diameter_mm = number(c, &got, "dot_diameter_mm");
    let spec = AsymmetricCirclesSpec {
        rows: rows?,
        cols: cols?,
        pitch_mm: pitch_mm?,
        dot_diameter_mm: dot_diameter_mm?,
    };
    if let Err(e) = spec.validate() {
        let text = e.to_string();
        let text = text
            .strip_prefix("invalid target description: ")
            .unwrap_or(&text);
        match text.split_once(": ") {
            Some((field, why)) => c.fail(field, why),
            None => c.fail("kind", text),
        }
        return None;
    }
    let [w, h] = spec.drawing().size_mm;
    if w.max(h) > MAX_PRINT_MM {
        c.fail(
            "pitch_mm",
            format!("the board would exceed {MAX_PRINT_MM} mm"),
        );
        return None;
    }
    Some(PrintableTarget::AsymmetricCircles(spec))
}

/// The query pairs of `keys`, taken out of `map` (what is left over is
/// reported as unknown by the caller).
fn take_keys<'v>(
    map: &mut BTreeMap<&str, &'v str>,
    keys: &[&'static str],
) -> BTreeMap<&'static str, &'v str> {
    keys.iter()
        .filter_map(|&key| map.remove(key).map(|v| (key, v)))
        .collect()
}

/// A required `cols,rows` pair of whole numbers.
fn cols_rows(c: &mut Checker, got: &BTreeMap<&str, &str>, key: &str) -> Option<[usize; 2]> {
    let parsed: Option<Vec<usize>> = got.get(key).map(|v| {
        v.split(',')
            .map(|n| n.trim().parse::<usize>().unwrap_or(0))
            .collect()
    });
    match parsed.as_deref() {
        Some(&[cols, rows]) => Some([cols, rows]),
        Some(_) => {
            c.fail(key, "two whole numbers: cols,rows");
            None
        }
        None => {
            c.fail(key, "required");
            None
        }
    }
}

/// A required finite number.
fn number(c: &mut Checker, got: &BTreeMap<&str, &str>, key: &str) -> Option<f64> {
    match got.get(key).map(|v| v.trim().parse::<f64>()) {
        None => {
            c.fail(key, "required");
            None
        }
        Some(Ok(v)) if v.is_finite() => Some(v),
        Some(_) => {
            c.fail(key, "must be a finite number");
            None
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn pairs(s: &str) -> Vec<(String, String)> {
        s.split('&')
            .filter(|p| !p.is_empty())
            .map(|p| {
                let (k, v) = p.split_once('=').unwrap_or((p, ""));
                (k.to_string(), v.to_string())
            })
            .collect()
    }

    #[test]
    fn the_production_board_parses_with_kind_omitted() {
        let r = parse_pairs(&pairs(
            "rows=9&cols=9&pitch_mm=25&dot_diameter_mm=8&origin_marker_diameter_mm=12&format=pdf",
        ))
        .unwrap();
        assert_eq!(r.target, PrintableTarget::Dots(TargetSpec::robocal_9x9()));
        assert_eq!(r.format, PageFormat::Pdf);
    }

    #[test]
    fn each_bad_field_is_named() {
        let fields = |q: &str| -> Vec<String> {
            parse_pairs(&pairs(q))
                .unwrap_err()
                .into_iter()
                .map(|e| e.field)
                .collect()
        };
        assert_eq!(
            fields("rows=9&cols=9&pitch_mm=-1&dot_diameter_mm=8"),
            ["pitch_mm"]
        );
        assert_eq!(
            fields("rows=1&cols=9&pitch_mm=25&dot_diameter_mm=8"),
            ["rows"]
        );
        assert_eq!(
            fields("rows=9&cols=9&pitch_mm=25&dot_diameter_mm=30"),
            ["dot_diameter_mm"]
        );
        assert_eq!(
            fields("rows=9&cols=9&pitch_mm=25&dot_diameter_mm=8&format=png"),
            ["format"]
        );
        assert_eq!(fields("kind=hexagons"), ["kind"]);
        assert_eq!(
            fields("rows=9&cols=9&pitch_mm=25&dot_diameter_mm=8&colour=red"),
            ["colour"]
        );
        assert_eq!(
            fields("rows=9&cols=9&pitch_mm=NaN&dot_diameter_mm=8"),
            ["pitch_mm"]
        );
        assert_eq!(
            fields("rows=9&rows=8&cols=9&pitch_mm=25&dot_diameter_mm=8"),
            ["rows"]
        );
        assert_eq!(
            fields("rows=200&cols=200&pitch_mm=25&dot_diameter_mm=8"),
            ["pitch_mm"]
        );
    }
}
