//! Printable targets: `GET /v1/targets/render` pages are exact-scale, and the
//! board printed on them is found by the detector after rasterising the SVG
//! with an independent renderer (resvg).

use robocal::calib::vision::{detect, GrayImage, TargetSpec};
use serde_json::Value;

use crate::support::*;

/// Raster resolution of the test, pixels per millimetre (about 254 dpi).
const PX_PER_MM: f32 = 10.0;
const PRODUCTION_QUERY: &str =
    "rows=9&cols=9&pitch_mm=25&dot_diameter_mm=8&origin_marker_diameter_mm=12";

pub(crate) fn rasterise(svg: &str) -> GrayImage {
    let tree = resvg::usvg::Tree::from_str(svg, &resvg::usvg::Options::default()).unwrap();
    let size = tree.size();
    // usvg sizes in CSS px (96 per inch); scale them to PX_PER_MM.
    let scale = PX_PER_MM * 25.4 / 96.0;
    let (w, h) = (
        (size.width() * scale).round() as u32,
        (size.height() * scale).round() as u32,
    );
    let mut pixmap = resvg::tiny_skia::Pixmap::new(w, h).unwrap();
    resvg::render(
        &tree,
        resvg::tiny_skia::Transform::from_scale(scale, scale),
        &mut pixmap.as_mut(),
    );
    let data = pixmap
        .pixels()
        .iter()
        .map(|p| {
            let c = p.demultiply();
            (c.red() as f32 + c.green() as f32 + c.blue() as f32) / 3.0
        })
        .collect();
    GrayImage::new(w as usize, h as usize, data).unwrap()
}

#[tokio::test]
async fn printed_dot_board_is_exact_scale_and_detected() {
    let app = spawn_app().await;
    let r = app
        .get(&format!("/v1/targets/render?{PRODUCTION_QUERY}"))
        .await;
    assert_eq!(r.status(), 200);
    assert_eq!(r.headers()["content-type"], "image/svg+xml");
    let svg = r.text().await.unwrap();
    assert!(
        svg.contains(r#"width="297mm" height="420mm""#),
        "A3 portrait"
    );
    assert!(
        svg.contains("\"origin_marker_diameter_mm\": 12"),
        "spec in the margin"
    );
    let img = rasterise(&svg);
    let found = detect(&img, &TargetSpec::robocal_9x9()).unwrap();
    assert_eq!(found.dots.len(), 81);
    assert!(found.ordering_unique);
    // Neighbouring dots 25 mm apart on paper: 250 px at 10 px/mm, to 0.05 px.
    for row in 0..9 {
        for col in 0..8 {
            let a = &found.dots[row * 9 + col];
            let b = &found.dots[row * 9 + col + 1];
            let d = (b.x - a.x).hypot(b.y - a.y);
            assert!((d - 250.0).abs() < 0.05, "({row},{col}) spacing {d} px");
        }
    }
    // The scale bar: five black 10 mm segments of a 100 mm bar.
    assert_eq!(svg.matches(r#"width="10.0000" height="3.0000""#).count(), 5);
    app.shutdown().await;
}

#[tokio::test]
async fn pdf_page_is_a3_with_the_board() {
    let app = spawn_app().await;
    let r = app
        .get(&format!("/v1/targets/render?{PRODUCTION_QUERY}&format=pdf"))
        .await;
    assert_eq!(r.status(), 200);
    assert_eq!(r.headers()["content-type"], "application/pdf");
    let pdf = String::from_utf8(r.bytes().await.unwrap().to_vec()).unwrap();
    assert!(pdf.starts_with("%PDF-1.4"));
    assert!(
        pdf.contains("/MediaBox [0 0 841.8898 1190.5512]"),
        "A3 in points"
    );
    assert_eq!(pdf.matches(" c f\n").count(), 81, "one disc per dot");
    app.shutdown().await;
}

#[tokio::test]
async fn unprintable_specs_are_422_naming_the_field() {
    let app = spawn_app().await;
    for (query, field) in [
        ("rows=9&cols=9&pitch_mm=0&dot_diameter_mm=8", "pitch_mm"),
        (
            "rows=9&cols=9&pitch_mm=25&dot_diameter_mm=25",
            "dot_diameter_mm",
        ),
        ("rows=9&cols=9&pitch_mm=25", "dot_diameter_mm"),
        ("kind=hexagons", "kind"),
        (&format!("{PRODUCTION_QUERY}&format=png"), "format"),
    ] {
        let r = app.get(&format!("/v1/targets/render?{query}")).await;
        assert_eq!(r.status(), 422, "{query}");
        assert_eq!(r.headers()["content-type"], "application/problem+json");
        let body: Value = r.json().await.unwrap();
        assert_eq!(body["errors"][0]["field"], field, "{query}: {body}");
    }
    app.shutdown().await;
}

#[test]
fn cli_writes_the_same_page() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("board.svg");
    let args: Vec<String> = PRODUCTION_QUERY
        .split('&')
        .map(String::from)
        .chain(["--out".into(), out.display().to_string()])
        .collect();
    let args: Vec<&str> = std::iter::once("target")
        .chain(args.iter().map(String::as_str))
        .collect();
    let o = run_binary(&args);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let svg = std::fs::read_to_string(&out).unwrap();
    let found = detect(&rasterise(&svg), &TargetSpec::robocal_9x9()).unwrap();
    assert_eq!(found.dots.len(), 81);
    let bad = run_binary(&[
        "target",
        "rows=9",
        "cols=9",
        "pitch_mm=-3",
        "dot_diameter_mm=8",
    ]);
    assert!(!bad.status.success());
    assert!(String::from_utf8_lossy(&bad.stderr).contains("pitch_mm"));
}

#[tokio::test]
async fn printed_charuco_board_is_detected_with_every_corner() {
    use robocal::calib::vision::charuco::{detect_charuco, CharucoSpec};
    let app = spawn_app().await;
    let r = app
        .get("/v1/targets/render?kind=charuco&squares=10,8&square_mm=20&marker_mm=15&dictionary=DICT_5X5_100")
        .await;
    assert_eq!(r.status(), 200);
    let svg = r.text().await.unwrap();
    assert!(svg.contains("\"kind\": \"charuco\""), "spec in the margin");
    let spec = CharucoSpec {
        squares: [10, 8],
        square_mm: 20.0,
        marker_mm: 15.0,
        dictionary: "DICT_5X5_100".into(),
        legacy_layout: false,
    };
    let found = detect_charuco(&rasterise(&svg), &spec).unwrap();
    assert_eq!(found.points.len(), 9 * 7, "every inner corner");
    // Corners 20 mm apart on paper: 200 px at 10 px/mm.
    let at = |row: usize, col: usize| {
        found
            .points
            .iter()
            .find(|p| p.row == row && p.col == col)
            .map(|p| (p.x_px, p.y_px))
            .unwrap()
    };
    for (row, col) in [(0, 0), (3, 4), (6, 7)] {
        let (a, b) = (at(row, col), at(row, col + 1));
        let d = (b.0 - a.0).hypot(b.1 - a.1);
        assert!((d - 200.0).abs() < 0.1, "({row},{col}) spacing {d} px");
    }
    for (query, field) in [
        (
            "kind=charuco&squares=10,8&square_mm=20&marker_mm=25&dictionary=DICT_5X5_100",
            "marker_mm",
        ),
        (
            "kind=charuco&squares=10,8&square_mm=20&marker_mm=15&dictionary=DICT_5X5_7",
            "dictionary",
        ),
        (
            "kind=charuco&squares=30,30&square_mm=20&marker_mm=15&dictionary=DICT_4X4_50",
            "dictionary",
        ),
        (
            "kind=charuco&squares=10&square_mm=20&marker_mm=15&dictionary=DICT_5X5_100",
            "squares",
        ),
    ] {
        let r = app.get(&format!("/v1/targets/render?{query}")).await;
        assert_eq!(r.status(), 422, "{query}");
        let body: Value = r.json().await.unwrap();
        assert_eq!(body["errors"][0]["field"], field, "{query}: {body}");
    }
    app.shutdown().await;
}

#[tokio::test]
async fn printed_chessboard_is_detected_in_opencv_order() {
    use robocal::calib::vision::chessboard::{detect_chessboard, ChessboardSpec};
    let app = spawn_app().await;
    let r = app
        .get("/v1/targets/render?kind=chessboard&inner_corners=9,6&square_mm=20")
        .await;
    assert_eq!(r.status(), 200);
    let svg = r.text().await.unwrap();
    assert!(
        svg.contains("\"kind\": \"chessboard\""),
        "spec in the margin"
    );
    let spec = ChessboardSpec {
        inner_corners: [9, 6],
        square_mm: 20.0,
    };
    let found = detect_chessboard(&rasterise(&svg), &spec).unwrap();
    assert!(found.ordering_unique, "9x6 is not half-turn symmetric");
    assert_eq!(found.points.len(), 9 * 6, "every inner corner");
    // Corners 20 mm apart on paper: 200 px at 10 px/mm; the page is upright,
    // so OpenCV's order runs along x first, then down.
    let at = |k: usize| (found.points[k].x_px, found.points[k].y_px);
    for k in [0, 13, 40] {
        let (a, b, c) = (at(k), at(k + 1), at(k + 9));
        assert!(
            (b.0 - a.0 - 200.0).abs() < 0.1 && (b.1 - a.1).abs() < 0.1,
            "{k}: {a:?} {b:?}"
        );
        assert!(
            (c.1 - a.1 - 200.0).abs() < 0.1 && (c.0 - a.0).abs() < 0.1,
            "{k}: {a:?} {c:?}"
        );
    }
    for (query, field) in [
        ("kind=chessboard&inner_corners=9,6&square_mm=0", "square_mm"),
        (
            "kind=chessboard&inner_corners=9,6&square_mm=-5",
            "square_mm",
        ),
        (
            "kind=chessboard&inner_corners=1,6&square_mm=20",
            "inner_corners",
        ),
        (
            "kind=chessboard&inner_corners=9&square_mm=20",
            "inner_corners",
        ),
        ("kind=chessboard&square_mm=20", "inner_corners"),
    ] {
        let r = app.get(&format!("/v1/targets/render?{query}")).await;
        assert_eq!(r.status(), 422, "{query}");
        let body: Value = r.json().await.unwrap();
        assert_eq!(body["errors"][0]["field"], field, "{query}: {body}");
    }
    app.shutdown().await;
}

/// `page=a4`: the board scaled to fill the sheet it is printed on (a
/// 10x8 ChArUco board of 25 mm squares would otherwise need A3 and fill
/// half of it); the footer gives the square as drawn. An unknown sheet is
/// a 422 naming `page`.
#[tokio::test]
async fn page_a4_scales_the_board_to_fill_the_sheet() {
    let app = spawn_app().await;
    let query = "kind=charuco&squares=10,8&square_mm=25&marker_mm=18&dictionary=DICT_5X5_100";
    let svg = app
        .get(&format!("/v1/targets/render?{query}"))
        .await
        .text()
        .await
        .unwrap();
    assert!(
        svg.contains(r#"width="297mm" height="420mm""#),
        "A3 as given"
    );
    let r = app
        .get(&format!("/v1/targets/render?{query}&page=a4"))
        .await;
    assert_eq!(r.status(), 200);
    let svg = r.text().await.unwrap();
    assert!(
        svg.contains(r#"width="297mm" height="210mm""#),
        "A4 landscape"
    );
    let square_mm: f64 = svg
        .split("\"square_mm\": ")
        .nth(1)
        .and_then(|rest| rest.split(',').next())
        .and_then(|v| v.trim().parse().ok())
        .expect("the footer states the square");
    // 8 rows of squares and the board's white border in A4's 210 mm less
    // margins and footer (160 mm); `print::fill`'s unit tests show one
    // half-millimetre step more would not fit.
    assert!((16.0..20.0).contains(&square_mm), "{square_mm}");
    let r = app
        .get(&format!("/v1/targets/render?{query}&page=b5"))
        .await;
    assert_eq!(r.status(), 422);
    let p: Value = r.json().await.unwrap();
    assert_eq!(p["errors"][0]["field"], "page", "{p}");
    app.shutdown().await;
}
