//! Page layout: the board at 1:1 in millimetres, a scale bar to check the
//! printer did not scale, and the spec text so a sheet found in a drawer says
//! what it is.

use robocal_calib::vision::{BoardDrawing, Mark};
use serde::Deserialize;

/// White margin kept clear on every side of the page (printers do not print
/// to the edge), mm.
pub const PAGE_MARGIN_MM: f64 = 10.0;
/// Height of the band below the board with the scale bar and the spec, mm.
pub const FOOTER_MM: f64 = 30.0;
/// Length of the scale bar, mm, when the page is wide enough.
pub const SCALE_BAR_MM: f64 = 100.0;
/// Length of one alternating segment of the scale bar, mm.
pub const SCALE_STEP_MM: f64 = 10.0;
/// Thickness of the scale bar, mm.
pub const SCALE_BAR_HEIGHT_MM: f64 = 3.0;
/// Text height, mm (about 10 pt).
pub const TEXT_MM: f64 = 3.5;
/// ISO 216 sheets tried in order, portrait (width, height), mm.
pub const SHEETS_MM: [(&str, f64, f64); 5] = [
    ("A4", 210.0, 297.0),
    ("A3", 297.0, 420.0),
    ("A2", 420.0, 594.0),
    ("A1", 594.0, 841.0),
    ("A0", 841.0, 1189.0),
];

/// The two page formats.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Deserialize, Default)]
#[serde(rename_all = "lowercase")]
pub enum PageFormat {
    #[default]
    Svg,
    Pdf,
}

impl PageFormat {
    pub fn content_type(self) -> &'static str {
        match self {
            PageFormat::Svg => "image/svg+xml",
            PageFormat::Pdf => "application/pdf",
        }
    }
}

/// Everything to draw on one sheet, page coordinates in mm (origin top-left,
/// y down).
#[derive(Debug, Clone, PartialEq)]
pub struct Page {
    /// e.g. "A4 landscape", or "custom" when no ISO sheet holds the board.
    pub sheet: String,
    pub size_mm: [f64; 2],
    /// The board's marks, already moved to page coordinates.
    pub marks: Vec<Mark>,
    /// Where the board's white area sits on the page.
    pub board_min_mm: [f64; 2],
    pub board_size_mm: [f64; 2],
    /// Dark segments of the scale bar and its total length.
    pub scale_bar: Vec<Mark>,
    pub scale_bar_mm: f64,
    /// Text lines of the footer with their baseline positions.
    pub text: Vec<([f64; 2], String)>,
}

impl Page {
    /// Lays `board` out on the smallest ISO sheet (either orientation) that
    /// holds it with the margins and the footer; a custom sheet otherwise.
    /// `spec_lines` are printed under the scale bar.
    pub fn layout(board: &BoardDrawing, spec_lines: &[String]) -> Page {
        let (sheet, size_mm) = sheet_for(Self::need_mm(board));
        Self::layout_on(board, spec_lines, sheet, size_mm)
    }

    /// The page size `board` needs with the margins and the footer, mm.
    pub fn need_mm(board: &BoardDrawing) -> [f64; 2] {
        [
            board.size_mm[0] + 2.0 * PAGE_MARGIN_MM,
            board.size_mm[1] + 2.0 * PAGE_MARGIN_MM + FOOTER_MM,
        ]
    }

    /// [`Self::layout`] on a given sheet (`sheet` names it).
    pub fn layout_on(
        board: &BoardDrawing,
        spec_lines: &[String],
        sheet: String,
        size_mm: [f64; 2],
    ) -> Page {
        // Board centred horizontally, at the top margin.
        let board_min_mm = [(size_mm[0] - board.size_mm[0]) / 2.0, PAGE_MARGIN_MM];
        let shift = [
            board_min_mm[0] - board.min_mm[0],
            board_min_mm[1] - board.min_mm[1],
        ];
        let marks = board.marks.iter().map(|m| moved(m, shift)).collect();
        let bar_y = board_min_mm[1] + board.size_mm[1] + TEXT_MM;
        let scale_bar_mm = scale_bar_length(size_mm[0] - 2.0 * PAGE_MARGIN_MM);
        let steps = (scale_bar_mm / SCALE_STEP_MM).round() as usize;
        let scale_bar = (0..steps)
            .step_by(2)
            .map(|k| Mark::Rect {
                x_mm: PAGE_MARGIN_MM + k as f64 * SCALE_STEP_MM,
                y_mm: bar_y,
                width_mm: SCALE_STEP_MM,
                height_mm: SCALE_BAR_HEIGHT_MM,
            })
            .collect();
        let mut text = vec![(
            [PAGE_MARGIN_MM, bar_y + SCALE_BAR_HEIGHT_MM + 1.5 * TEXT_MM],
            format!(
                "scale bar {scale_bar_mm:.0} mm in {SCALE_STEP_MM:.0} mm steps: print at 100 %, measure before use"
            ),
        )];
        for (i, line) in spec_lines.iter().enumerate() {
            let y = bar_y + SCALE_BAR_HEIGHT_MM + (2.8 + 1.3 * i as f64) * TEXT_MM;
            text.push(([PAGE_MARGIN_MM, y], line.clone()));
        }
        Page {
            sheet,
            size_mm,
            marks,
            board_min_mm,
            board_size_mm: board.size_mm,
            scale_bar,
            scale_bar_mm,
            text,
        }
    }
}

/// The longest whole number of steps up to [`SCALE_BAR_MM`] that fits `room_mm`.
fn scale_bar_length(room_mm: f64) -> f64 {
    let steps = (room_mm.min(SCALE_BAR_MM) / SCALE_STEP_MM).floor().max(1.0);
    steps * SCALE_STEP_MM
}

fn sheet_for(need: [f64; 2]) -> (String, [f64; 2]) {
    for (name, w, h) in SHEETS_MM {
        if need[0] <= w && need[1] <= h {
            return (format!("{name} portrait"), [w, h]);
        }
        if need[0] <= h && need[1] <= w {
            return (format!("{name} landscape"), [h, w]);
        }
    }
    ("custom".into(), need)
}

fn moved(m: &Mark, d: [f64; 2]) -> Mark {
    match *m {
        Mark::Rect {
            x_mm,
            y_mm,
            width_mm,
            height_mm,
        } => Mark::Rect {
            x_mm: x_mm + d[0],
            y_mm: y_mm + d[1],
            width_mm,
            height_mm,
        },
        Mark::Disc {
            cx_mm,
            cy_mm,
            diameter_mm,
        } => Mark::Disc {
            cx_mm: cx_mm + d[0],
            cy_mm: cy_mm + d[1],
            diameter_mm,
        },
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use robocal_calib::vision::TargetSpec;

    #[test]
    fn production_board_fits_a3_portrait_at_exact_scale() {
        let d = TargetSpec::robocal_9x9().drawing();
        let page = Page::layout(&d, &["kind dots".into()]);
        assert_eq!(page.sheet, "A3 portrait");
        // Same spacing as on the board: dot 1 is 25 mm right of dot 0.
        let x = |m: &Mark| m.extent_mm().0[0] + m.extent_mm().1[0];
        assert!(((x(&page.marks[1]) - x(&page.marks[0])) / 2.0 - 25.0).abs() < 1e-9);
        assert_eq!(page.scale_bar_mm, 100.0);
        assert_eq!(page.scale_bar.len(), 5);
    }

    #[test]
    fn a_huge_board_gets_a_custom_sheet() {
        let mut t = TargetSpec::robocal_9x9();
        t.rows = 60;
        t.cols = 60;
        let page = Page::layout(&t.drawing(), &[]);
        assert_eq!(page.sheet, "custom");
        assert!(page.size_mm[0] > 1500.0);
    }
}
