//! The page as a one-page PDF 1.4 written by hand: vector rectangles, discs
//! as four cubic Béziers, and Helvetica (a base-14 font, nothing embedded).
//! Drawing happens in millimetres under a y-down transform, so the numbers
//! are the same as the SVG's.

use std::fmt::Write;

use robocal_calib::vision::Mark;

use super::page::{Page, TEXT_MM};

/// PostScript points per millimetre.
const PT_PER_MM: f64 = 72.0 / 25.4;
/// Control-point distance of a quarter-circle cubic Bézier, in radii.
const KAPPA: f64 = 0.552_284_749_830_793_4;

/// The page as PDF bytes.
pub fn write_pdf(page: &Page) -> Vec<u8> {
    let [w_mm, h_mm] = page.size_mm;
    let (w_pt, h_pt) = (w_mm * PT_PER_MM, h_mm * PT_PER_MM);
    let mut c = String::new();
    // y-down millimetres: x_pt = k x, y_pt = H - k y.
    let _ = writeln!(c, "{PT_PER_MM:.6} 0 0 {:.6} 0 {h_pt:.4} cm", -PT_PER_MM);
    let _ = writeln!(c, "0 g");
    for m in page.marks.iter().chain(&page.scale_bar) {
        mark(&mut c, m);
    }
    if let Some(first) = page.scale_bar.first() {
        let (a, b) = first.extent_mm();
        let _ = writeln!(
            c,
            "0.2 w {:.4} {:.4} {:.4} {:.4} re S",
            a[0],
            a[1],
            page.scale_bar_mm,
            b[1] - a[1]
        );
    }
    for ([x, y], line) in &page.text {
        // The text matrix flips y back so glyphs stand upright.
        let _ = writeln!(
            c,
            "BT /F1 {TEXT_MM} Tf 1 0 0 -1 {x:.3} {y:.3} Tm ({}) Tj ET",
            escape(line)
        );
    }
    let objects = [
        "<< /Type /Catalog /Pages 2 0 R >>".to_string(),
        "<< /Type /Pages /Kids [3 0 R] /Count 1 >>".to_string(),
        format!(
            "<< /Type /Page /Parent 2 0 R /MediaBox [0 0 {w_pt:.4} {h_pt:.4}] \
             /Resources << /Font << /F1 4 0 R >> >> /Contents 5 0 R >>"
        ),
        "<< /Type /Font /Subtype /Type1 /BaseFont /Helvetica /Encoding /WinAnsiEncoding >>"
            .to_string(),
        format!("<< /Length {} >>\nstream\n{c}endstream", c.len()),
    ];
    let mut out = String::from("%PDF-1.4\n");
    let mut offsets = Vec::with_capacity(objects.len());
    for (i, body) in objects.iter().enumerate() {
        offsets.push(out.len());
        let _ = write!(out, "{} 0 obj\n{body}\nendobj\n", i + 1);
    }
    let xref = out.len();
    let _ = write!(out, "xref\n0 {}\n0000000000 65535 f \n", objects.len() + 1);
    for o in offsets {
        let _ = writeln!(out, "{o:010} 00000 n ");
    }
    let _ = write!(
        out,
        "trailer\n<< /Size {} /Root 1 0 R >>\nstartxref\n{xref}\n%%EOF\n",
        objects.len() + 1
    );
    out.into_bytes()
}

fn mark(c: &mut String, m: &Mark) {
    match *m {
        Mark::Rect {
            x_mm,
            y_mm,
            width_mm,
            height_mm,
        } => {
            let _ = writeln!(c, "{x_mm:.4} {y_mm:.4} {width_mm:.4} {height_mm:.4} re f");
        }
        Mark::Disc {
            cx_mm: x,
            cy_mm: y,
            diameter_mm,
        } => {
            let r = diameter_mm / 2.0;
            let k = KAPPA * r;
            let _ = writeln!(
                c,
                "{:.4} {y:.4} m \
                 {:.4} {:.4} {:.4} {:.4} {x:.4} {:.4} c \
                 {:.4} {:.4} {:.4} {:.4} {:.4} {y:.4} c \
                 {:.4} {:.4} {:.4} {:.4} {x:.4} {:.4} c \
                 {:.4} {:.4} {:.4} {:.4} {:.4} {y:.4} c f",
                x + r,
                x + r,
                y + k,
                x + k,
                y + r,
                y + r,
                x - k,
                y + r,
                x - r,
                y + k,
                x - r,
                x - r,
                y - k,
                x - k,
                y - r,
                y - r,
                x + k,
                y - r,
                x + r,
                y - k,
                x + r,
            );
        }
    }
}

/// A PDF literal string's body: ASCII only, with `\`, `(` and `)` escaped.
fn escape(text: &str) -> String {
    text.chars()
        .map(|ch| {
            if ch.is_ascii() && !ch.is_ascii_control() {
                ch
            } else {
                '?'
            }
        })
        .flat_map(|ch| match ch {
            '\\' | '(' | ')' => vec!['\\', ch],
            _ => vec![ch],
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use robocal_calib::vision::TargetSpec;

    #[test]
    fn xref_offsets_point_at_their_objects() {
        let page = Page::layout(&TargetSpec::robocal_9x9().drawing(), &["a (b) \\ c".into()]);
        let pdf = String::from_utf8(write_pdf(&page)).unwrap();
        let xref_at: usize = pdf
            .rsplit("startxref\n")
            .next()
            .and_then(|t| t.lines().next())
            .and_then(|n| n.parse().ok())
            .unwrap();
        assert!(pdf[xref_at..].starts_with("xref"));
        let entries: Vec<usize> = pdf[xref_at..]
            .lines()
            .skip(3)
            .take(5)
            .map(|l| l[..10].parse().unwrap())
            .collect();
        for (i, off) in entries.iter().enumerate() {
            assert!(pdf[*off..].starts_with(&format!("{} 0 obj", i + 1)));
        }
        assert!(pdf.contains("(a \\(b\\) \\\\ c) Tj"));
        // 81 dots, each one closed Bézier path.
        assert_eq!(pdf.matches(" c f\n").count(), 81);
    }
}
