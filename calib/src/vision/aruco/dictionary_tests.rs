//! Known marker bit patterns, printed by opencv-python 5.0
//! (`generateImageMarker(dict, id, size + 2)`, inner cells, 1 = white).

use super::*;

/// (dictionary, id, rows of bits) as OpenCV draws them.
const KNOWN: &[(&str, usize, &[&str])] = &[
    ("DICT_4X4_50", 0, &["1011", "0101", "0011", "0010"]),
    ("DICT_4X4_50", 1, &["0000", "1111", "1001", "1010"]),
    ("DICT_4X4_50", 49, &["0101", "0000", "0001", "0011"]),
    (
        "DICT_5X5_100",
        0,
        &["10100", "01011", "01100", "10101", "11100"],
    ),
    (
        "DICT_5X5_100",
        99,
        &["00100", "01001", "00011", "10111", "11101"],
    ),
    (
        "DICT_6X6_250",
        7,
        &["100010", "001010", "010100", "001111", "001010", "011010"],
    ),
    (
        "DICT_7X7_1000",
        999,
        &[
            "1110011", "1111001", "1010010", "1101110", "0010000", "0011010", "0111111",
        ],
    ),
    ("DICT_ARUCO_ORIGINAL", 1023, &["01110"; 5]),
    (
        "DICT_APRILTAG_36h11",
        586,
        &["110011", "101101", "001001", "111101", "110000", "010111"],
    ),
    (
        "DICT_ARUCO_MIP_36h12",
        249,
        &["010011", "010101", "100011", "011011", "111010", "100000"],
    ),
];

#[test]
fn known_markers_have_opencvs_bits() {
    for (name, id, rows) in KNOWN {
        let d = predefined(name).unwrap_or_else(|| panic!("{name} missing"));
        for (r, row) in rows.iter().enumerate() {
            for (c, ch) in row.chars().enumerate() {
                assert_eq!(d.bit(*id, r, c), ch == '1', "{name} id {id} bit ({r},{c})");
            }
        }
    }
}

#[test]
fn every_opencv_dictionary_is_present_with_its_size_and_correction() {
    // (name, enum, bits per side, maxCorrectionBits, markers) from cv2 5.0.
    let expect: &[(&str, u16, usize, usize, usize)] = &[
        ("DICT_4X4_50", 0, 4, 1, 50),
        ("DICT_4X4_1000", 3, 4, 0, 1000),
        ("DICT_5X5_100", 5, 5, 3, 100),
        ("DICT_6X6_1000", 11, 6, 4, 1000),
        ("DICT_7X7_50", 12, 7, 9, 50),
        ("DICT_7X7_1000", 15, 7, 6, 1000),
        ("DICT_ARUCO_ORIGINAL", 16, 5, 1, 1024),
        ("DICT_APRILTAG_16h5", 17, 4, 2, 30),
        ("DICT_APRILTAG_25h9", 18, 5, 4, 35),
        ("DICT_APRILTAG_36h10", 19, 6, 4, 2320),
        ("DICT_APRILTAG_36h11", 20, 6, 5, 587),
        ("DICT_ARUCO_MIP_36h12", 21, 6, 5, 250),
    ];
    assert_eq!(predefined_all().len(), 22);
    for &(name, enum_value, size, corr, n) in expect {
        let d = predefined(name).unwrap();
        assert_eq!(
            (d.opencv_id, d.marker_size, d.max_correction_bits, d.len()),
            (enum_value, size, corr, n),
            "{name}"
        );
    }
    assert_eq!(
        predefined("dict_apriltag_36H11").map(|d| d.opencv_id),
        Some(20)
    );
    assert!(predefined("DICT_8X8_50").is_none());
}

#[test]
fn identify_finds_rotated_and_corrupted_markers_and_refuses_noise() {
    let d = predefined("DICT_5X5_100").unwrap();
    let size = d.marker_size;
    // Seen turned k quarters counter-clockwise: k clockwise turns undo it.
    let mut seen = d.codes[42];
    for k in 0..4 {
        let hit = d.identify(seen).unwrap();
        assert_eq!((hit.id, hit.rotation, hit.distance), (42, k, 0));
        seen = rotate_cw(rotate_cw(rotate_cw(seen, size), size), size);
    }
    // Up to maxCorrectionBits flipped bits are corrected ...
    let flipped = d.codes[7] ^ 0b1_0000_0001_0000_0000_0001;
    assert_eq!(
        d.identify(flipped).map(|h| (h.id, h.distance)),
        Some((7, 3))
    );
    // ... a code farther than that from every marker (in any rotation) is none.
    let far = (0u64..1 << 25)
        .step_by(9973)
        .find(|&c| {
            (0..4).all(|k| {
                let mut r = c;
                (0..k).for_each(|_| r = rotate_cw(r, size));
                d.codes
                    .iter()
                    .all(|m| (m ^ r).count_ones() as usize > d.max_correction_bits)
            })
        })
        .unwrap();
    assert!(d.identify(far).is_none());
    // Four quarter turns are the identity.
    let c = d.codes[3];
    assert_eq!(rotate_cw(rotate_cw(rotate_cw(rotate_cw(c, 5), 5), 5), 5), c);
    assert_ne!(rotate_cw(c, 5), c);
}
