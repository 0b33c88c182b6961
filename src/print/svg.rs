//! The page as SVG: `width`/`height` in millimetres and a viewBox in the same
//! units, so any viewer or printer that honours SVG units prints 1:1.

use std::fmt::Write;

use robocal_calib::vision::Mark;

use super::page::{Page, TEXT_MM};

/// Decimal places written for coordinates (0.1 µm: far below any printer).
const DECIMALS: usize = 4;

/// The page as a standalone SVG document.
pub fn write_svg(page: &Page) -> String {
    let [w, h] = page.size_mm;
    let mut s = String::new();
    let _ = writeln!(s, r#"<?xml version="1.0" encoding="UTF-8"?>"#);
    let _ = writeln!(
        s,
        r#"<svg xmlns="http://www.w3.org/2000/svg" width="{w}mm" height="{h}mm" viewBox="0 0 {w} {h}">"#
    );
    let _ = writeln!(
        s,
        r#"<rect x="0" y="0" width="{w}" height="{h}" fill="white"/>"#
    );
    let _ = writeln!(s, r#"<g fill="black" stroke="none">"#);
    for m in page.marks.iter().chain(&page.scale_bar) {
        mark(&mut s, m);
    }
    // The scale bar's outline, so its white segments show too.
    if let (Some(first), Some(_)) = (page.scale_bar.first(), page.scale_bar.last()) {
        let (a, b) = first.extent_mm();
        let _ = writeln!(
            s,
            r#"<rect x="{:.d$}" y="{:.d$}" width="{:.d$}" height="{:.d$}" fill="none" stroke="black" stroke-width="0.2"/>"#,
            a[0],
            a[1],
            page.scale_bar_mm,
            b[1] - a[1],
            d = DECIMALS
        );
    }
    let _ = writeln!(s, "</g>");
    let _ = writeln!(
        s,
        r#"<g font-family="Helvetica, Arial, sans-serif" font-size="{TEXT_MM}" fill="black">"#
    );
    for ([x, y], line) in &page.text {
        let _ = writeln!(s, r#"<text x="{x:.2}" y="{y:.2}">{}</text>"#, escape(line));
    }
    let _ = writeln!(s, "</g>\n</svg>");
    s
}

fn mark(s: &mut String, m: &Mark) {
    let d = DECIMALS;
    match *m {
        Mark::Rect {
            x_mm,
            y_mm,
            width_mm,
            height_mm,
        } => {
            let _ = writeln!(
                s,
                r#"<rect x="{x_mm:.d$}" y="{y_mm:.d$}" width="{width_mm:.d$}" height="{height_mm:.d$}"/>"#
            );
        }
        Mark::Disc {
            cx_mm,
            cy_mm,
            diameter_mm,
        } => {
            let r = diameter_mm / 2.0;
            let _ = writeln!(
                s,
                r#"<circle cx="{cx_mm:.d$}" cy="{cy_mm:.d$}" r="{r:.d$}"/>"#
            );
        }
    }
}

/// XML text-content escaping (quotes stay: the spec line is JSON).
fn escape(text: &str) -> String {
    text.replace('&', "&amp;")
        .replace('<', "&lt;")
        .replace('>', "&gt;")
}
