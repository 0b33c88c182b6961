//! The layout against OpenCV's own boards: object points exported by
//! `bench/charuco_layout_fixture.py` and boards drawn by `generateImage`.

use super::*;
use crate::vision::image::decode_image;
use crate::vision::DecodeLimits;

const FIXTURE_DIR: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/tests/data/charuco");
/// OpenCV stores object points as f32 (30 mm prints as 30.0000019).
const TOL_MM: f64 = 1e-4;

fn spec_of(b: &serde_json::Value) -> CharucoSpec {
    serde_json::from_value(serde_json::json!({
        "squares": b["squares"], "square_mm": b["square_mm"], "marker_mm": b["marker_mm"],
        "dictionary": b["dictionary"], "legacy_layout": b["legacy_layout"],
    }))
    .unwrap()
}

fn close(a: &[f64], b: &serde_json::Value) -> bool {
    a.iter()
        .zip(b.as_array().unwrap())
        .all(|(x, y)| (x - y.as_f64().unwrap()).abs() < TOL_MM)
}

#[test]
fn layouts_equal_opencvs_object_points_in_both_layouts() {
    let text = std::fs::read_to_string(format!("{FIXTURE_DIR}/layouts.json")).unwrap();
    let fixture: serde_json::Value = serde_json::from_str(&text).unwrap();
    let boards = fixture["boards"].as_array().unwrap();
    assert_eq!(boards.len(), 10);
    let mut legacy_differs = 0;
    for b in boards {
        let spec = spec_of(b);
        spec.validate().unwrap();
        let cells = marker_cells(&spec);
        let ids = b["marker_ids"].as_array().unwrap();
        assert_eq!(cells.len(), ids.len(), "{spec:?}");
        for (k, cell) in cells.iter().enumerate() {
            assert_eq!(cell.id as u64, ids[k].as_u64().unwrap());
            let want = &b["marker_corners_mm"][k];
            for (i, corner) in cell.corners_mm.iter().enumerate() {
                assert!(close(corner, &want[i]), "{spec:?} marker {k} corner {i}");
            }
        }
        let (nx, ny) = inner_corner_grid(&spec);
        let want = b["chessboard_corners_mm"].as_array().unwrap();
        assert_eq!(want.len(), nx * ny);
        for row in 0..ny {
            for col in 0..nx {
                let c = corner_mm(&spec, row, col);
                assert!(
                    close(&c[..2], &want[row * nx + col]),
                    "{spec:?} corner {row},{col}"
                );
            }
        }
        let mut other = spec.clone();
        other.legacy_layout = !spec.legacy_layout;
        legacy_differs += usize::from(marker_cells(&other) != cells);
    }
    // Both layouts of the even-row boards (5x4, 7x6, 3x8) differ.
    assert_eq!(legacy_differs, 6);
}

/// OpenCV's drawing of a board: every white square's marker bits and every
/// black square, sampled at the centres of the bit cells.
#[test]
fn opencv_renderings_match_layout_and_dictionary_bits() {
    // (file, cols, rows, dictionary, square px, marker px, legacy)
    let cases = [
        (
            "board_5x4_DICT_4X4_50_current.png",
            5,
            4,
            "DICT_4X4_50",
            64,
            48,
            false,
        ),
        (
            "board_5x4_DICT_4X4_50_legacy.png",
            5,
            4,
            "DICT_4X4_50",
            64,
            48,
            true,
        ),
        (
            "board_6x5_DICT_5X5_100_current.png",
            6,
            5,
            "DICT_5X5_100",
            70,
            49,
            false,
        ),
        (
            "board_6x5_DICT_5X5_100_legacy.png",
            6,
            5,
            "DICT_5X5_100",
            70,
            49,
            true,
        ),
    ];
    for (file, cols, rows, dict, sq, mk, legacy) in cases {
        let bytes = std::fs::read(format!("{FIXTURE_DIR}/{file}")).unwrap();
        let img = decode_image(&bytes, &DecodeLimits::default()).unwrap();
        let spec = CharucoSpec {
            squares: [cols, rows],
            square_mm: sq as f64,
            marker_mm: mk as f64,
            dictionary: dict.into(),
            legacy_layout: legacy,
        };
        let d = spec.dictionary().unwrap();
        let white = |x: f64, y: f64| img.at(x as usize, y as usize) > 127.0;
        let cells = marker_cells(&spec);
        for row in 0..rows {
            for col in 0..cols {
                let centre = (
                    (col as f64 + 0.5) * sq as f64,
                    (row as f64 + 0.5) * sq as f64,
                );
                let Some(cell) = cells.iter().find(|c| (c.col, c.row) == (col, row)) else {
                    assert!(!white(centre.0, centre.1), "{file}: ({col},{row}) black");
                    continue;
                };
                let bit_px = mk as f64 / (d.marker_size + 2) as f64;
                let [x0, y0] = cell.corners_mm[0];
                for r in 0..d.marker_size {
                    for c in 0..d.marker_size {
                        let x = x0 + (c as f64 + 1.5) * bit_px;
                        let y = y0 + (r as f64 + 1.5) * bit_px;
                        assert_eq!(
                            white(x, y),
                            d.bit(cell.id, r, c),
                            "{file} id {} ({r},{c})",
                            cell.id
                        );
                    }
                }
            }
        }
    }
}

#[test]
fn invalid_specs_name_the_field() {
    let good = CharucoSpec {
        squares: [7, 5],
        square_mm: 30.0,
        marker_mm: 22.0,
        dictionary: "DICT_5X5_100".into(),
        legacy_layout: false,
    };
    good.validate().unwrap();
    let check = |edit: &dyn Fn(&mut CharucoSpec), field: &str| {
        let mut s = good.clone();
        edit(&mut s);
        match s.validate() {
            Err(crate::vision::DetectError::InvalidTarget(m)) => {
                assert!(m.starts_with(field), "{m} should name {field}")
            }
            other => panic!("{s:?}: {other:?}"),
        }
    };
    check(&|s| s.squares = [1, 5], "squares[0]");
    check(&|s| s.square_mm = 0.0, "square_mm");
    check(&|s| s.square_mm = -3.0, "square_mm");
    check(&|s| s.marker_mm = f64::NAN, "marker_mm");
    check(&|s| s.marker_mm = 30.0, "marker_mm");
    check(&|s| s.dictionary = "DICT_9X9_5".into(), "dictionary");
    // 20 x 12 squares need 120 markers; DICT_5X5_100 holds 100.
    check(&|s| s.squares = [20, 12], "dictionary");
    let mut s = good.clone();
    s.dictionary = "DICT_9X9_5".into();
    let msg = s.validate().unwrap_err().to_string();
    assert!(
        msg.contains("DICT_APRILTAG_36h11") && msg.contains("DICT_4X4_50"),
        "{msg}"
    );
}
