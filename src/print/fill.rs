//! `page=a4` (… `a0`): the board scaled to fill the sheet it will be
//! printed on, at exact scale. Every length of the board grows or shrinks
//! by one factor; its main length (the dot pitch, the square) is a whole
//! number of [`STEP_MM`], the largest whose page fits the sheet in either
//! orientation. The footer states the board as drawn, so the session is
//! configured from the sheet itself.

use super::page::{Page, SHEETS_MM};
use super::target::PrintableTarget;

/// The main length is a multiple of this, mm: a figure a person can read
/// off the sheet and type into a session.
pub const STEP_MM: f64 = 0.5;
/// Other lengths are rounded to this, mm (far below any printer's dot).
const ROUND_MM: f64 = 0.01;
/// Steps tried beyond the first estimate either way (the drawing's quiet
/// zone does not scale with the board, so the estimate can be off by a few).
const MAX_STEPS: usize = 400;

/// An ISO sheet by its name (`a4`, case-insensitive): name, portrait size.
pub fn sheet(name: &str) -> Option<(&'static str, [f64; 2])> {
    SHEETS_MM
        .iter()
        .find(|(n, _, _)| n.eq_ignore_ascii_case(name.trim()))
        .map(|&(n, w, h)| (n, [w, h]))
}

/// The orientation of `portrait` that holds `need`, if either does.
fn orient(need: [f64; 2], portrait: [f64; 2]) -> Option<(&'static str, [f64; 2])> {
    let [w, h] = portrait;
    if need[0] <= w && need[1] <= h {
        Some(("portrait", [w, h]))
    } else if need[0] <= h && need[1] <= w {
        Some(("landscape", [h, w]))
    } else {
        None
    }
}

/// `target` scaled so its page fills the sheet `(name, portrait size)`,
/// and that page. `None` when not even one step fits.
pub fn fill(
    target: &PrintableTarget,
    name: &str,
    portrait: [f64; 2],
) -> Option<(PrintableTarget, Page)> {
    let main = target.main_length_mm();
    let at = |length: f64| {
        let scaled = target.scaled(length / main, ROUND_MM);
        let need = Page::need_mm(&scaled.drawing());
        orient(need, portrait).map(|o| (scaled, o))
    };
    // First estimate from the board as given, then step to the largest fit.
    let need = Page::need_mm(&target.drawing());
    let [w, h] = portrait;
    let grow = ((w / need[0]).min(h / need[1])).max((h / need[0]).min(w / need[1]));
    let mut steps = ((main * grow) / STEP_MM).floor().max(1.0) as usize;
    while steps > 1 && at(steps as f64 * STEP_MM).is_none() {
        steps -= 1;
    }
    for _ in 0..MAX_STEPS {
        if at((steps + 1) as f64 * STEP_MM).is_none() {
            break;
        }
        steps += 1;
    }
    let (scaled, (orientation, size_mm)) = at(steps as f64 * STEP_MM)?;
    let page = Page::layout_on(
        &scaled.drawing(),
        &scaled.spec_lines(),
        format!("{name} {orientation}, board scaled to fill it"),
        size_mm,
    );
    Some((scaled, page))
}

#[cfg(test)]
mod tests {
    use super::*;
    use robocal_calib::vision::charuco::CharucoSpec;
    use robocal_calib::vision::TargetSpec;

    fn charuco() -> PrintableTarget {
        PrintableTarget::Charuco(CharucoSpec {
            squares: [10, 8],
            square_mm: 25.0,
            marker_mm: 18.0,
            dictionary: "DICT_5X5_100".into(),
            legacy_layout: false,
        })
    }

    /// `scaled` fits `portrait` in some orientation, and one step more
    /// of its main length would not.
    fn assert_fills(scaled: &PrintableTarget, portrait: [f64; 2]) {
        let fits = |t: &PrintableTarget| orient(Page::need_mm(&t.drawing()), portrait).is_some();
        assert!(fits(scaled), "{scaled:?}");
        let main = scaled.main_length_mm();
        assert!(
            !fits(&scaled.scaled((main + STEP_MM) / main, ROUND_MM)),
            "{scaled:?}"
        );
    }

    #[test]
    fn a_charuco_board_fills_an_a4_sheet_keeping_its_proportions() {
        let (name, a4) = sheet("a4").unwrap();
        let (scaled, page) = fill(&charuco(), name, a4).unwrap();
        let PrintableTarget::Charuco(s) = &scaled else {
            panic!("{scaled:?}")
        };
        assert_eq!(page.sheet, "A4 landscape, board scaled to fill it");
        assert_eq!(page.size_mm, [297.0, 210.0]);
        assert_eq!((s.square_mm / STEP_MM).fract(), 0.0, "{}", s.square_mm);
        assert!(
            (s.marker_mm / s.square_mm - 18.0 / 25.0).abs() < 1e-3,
            "{s:?}"
        );
        assert_fills(&scaled, a4);
        // The sheet says the board as drawn.
        assert!(
            page.text
                .iter()
                .any(|(_, t)| t.contains(&format!("\"square_mm\": {}", s.square_mm))),
            "{:?}",
            page.text
        );
    }

    #[test]
    fn a_small_dot_grid_grows_to_fill_an_a3_sheet() {
        let dots = PrintableTarget::Dots(TargetSpec {
            rows: 9,
            cols: 9,
            pitch_mm: 10.0,
            dot_diameter_mm: 3.2,
            origin_marker_diameter_mm: Some(4.8),
        });
        let (name, a3) = sheet("A3").unwrap();
        let (scaled, page) = fill(&dots, name, a3).unwrap();
        assert_fills(&scaled, a3);
        let PrintableTarget::Dots(t) = scaled else {
            panic!()
        };
        assert!(t.pitch_mm > 25.0, "{t:?}");
        assert!(page.sheet.starts_with("A3 "), "{}", page.sheet);
        assert!(
            (t.dot_diameter_mm / t.pitch_mm - 0.32).abs() < 1e-3,
            "{t:?}"
        );
    }
}
