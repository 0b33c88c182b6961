//! Markers read from OpenCV's own board drawings (`generateImage`).

use super::*;
use crate::vision::charuco::{marker_cells, CharucoSpec};
use crate::vision::image::{decode_image, GrayImage};
use crate::vision::DecodeLimits;

const FIXTURE_DIR: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/tests/data/charuco");
/// Hull corners sit on pixel centres: within a pixel of the true outline.
const CORNER_TOL_PX: f64 = 1.0;

/// Pads an image with white so that border squares are not cut.
fn padded(img: &GrayImage, pad: usize) -> GrayImage {
    let (w, h) = (img.width + 2 * pad, img.height + 2 * pad);
    let mut data = vec![255.0f32; w * h];
    for y in 0..img.height {
        for x in 0..img.width {
            data[(y + pad) * w + x + pad] = img.at(x, y);
        }
    }
    GrayImage::new(w, h, data).unwrap()
}

#[test]
fn every_marker_of_opencv_boards_is_found_with_its_id_and_corners() {
    let pad = 20;
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
    ];
    for (file, cols, rows, dict, sq, mk, legacy) in cases {
        let bytes = std::fs::read(format!("{FIXTURE_DIR}/{file}")).unwrap();
        let img = padded(
            &decode_image(&bytes, &DecodeLimits::default()).unwrap(),
            pad,
        );
        let spec = CharucoSpec {
            squares: [cols, rows],
            square_mm: sq as f64,
            marker_mm: mk as f64,
            dictionary: dict.into(),
            legacy_layout: legacy,
        };
        let d = spec.dictionary().unwrap();
        let cells = marker_cells(&spec);
        let found = detect_markers(&img, d);
        assert_eq!(found.len(), cells.len(), "{file}: {found:?}");
        for (m, cell) in found.iter().zip(&cells) {
            assert_eq!(m.id, cell.id);
            assert_eq!(m.corrected_bits, 0);
            for (p, q) in m.corners_px.iter().zip(&cell.corners_mm) {
                // 1 mm = 1 px here; pixel (0,0)'s centre is 0.5 px into the image.
                let (ex, ey) = (q[0] + pad as f64 - 0.5, q[1] + pad as f64 - 0.5);
                let err = (p[0] - ex).hypot(p[1] - ey);
                assert!(
                    err < CORNER_TOL_PX,
                    "{file} id {}: {p:?} vs ({ex}, {ey})",
                    m.id
                );
            }
        }
        // Rotated a quarter turn, the same markers come back, corners rotated.
        let rot = GrayImage::new(
            img.height,
            img.width,
            (0..img.width * img.height)
                .map(|k| {
                    let (x, y) = (k % img.height, k / img.height);
                    img.at(y, img.height - 1 - x)
                })
                .collect(),
        )
        .unwrap();
        let again = detect_markers(&rot, d);
        assert_eq!(again.len(), cells.len(), "{file} rotated");
        for (a, b) in again.iter().zip(&found) {
            let [x, y] = b.corners_px[0];
            let expect = [img.height as f64 - 1.0 - y, x];
            let err = (a.corners_px[0][0] - expect[0]).hypot(a.corners_px[0][1] - expect[1]);
            assert!(
                err < 1e-9,
                "{file} rotated id {}: {:?} vs {expect:?}",
                a.id,
                a.corners_px[0]
            );
        }
    }
}
