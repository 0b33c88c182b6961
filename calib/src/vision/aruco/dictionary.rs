//! OpenCV's predefined ArUco / AprilTag dictionaries (issue 14), bit for bit.
//!
//! The bit patterns come from opencv-python through
//! `bench/gen_aruco_dictionaries.py` (format documented there), embedded as
//! `dictionaries.bin`; `bench/aruco_dictionary_check.py` compares every
//! marker of every dictionary with OpenCV's own marker images. A marker's
//! code holds its `size x size` bits row-major, first bit most significant,
//! 1 = white cell, in OpenCV's rotation 0.

use std::sync::OnceLock;

/// The embedded dictionaries, as written by the generator script.
const DICTIONARIES_BIN: &[u8] = include_bytes!("dictionaries.bin");
/// File signature of `dictionaries.bin`.
const MAGIC: &[u8] = b"RCARUCO1";
/// Largest marker side whose bits fit a `u64` code.
pub const MAX_MARKER_BITS_SIDE: usize = 8;

/// One predefined dictionary.
#[derive(Debug, Clone, PartialEq)]
pub struct Dictionary {
    /// OpenCV's constant name, e.g. `DICT_5X5_100`, `DICT_APRILTAG_36h11`.
    pub name: String,
    /// OpenCV's enum value (`cv2.aruco.DICT_...`).
    pub opencv_id: u16,
    /// Bits per marker side (without the black border).
    pub marker_size: usize,
    /// Bit errors OpenCV corrects when identifying a marker.
    pub max_correction_bits: usize,
    /// Codes of markers `0..n`, OpenCV's rotation 0.
    pub codes: Vec<u64>,
}

/// A code matched to a dictionary marker.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Identified {
    pub id: usize,
    /// Clockwise quarter turns applied to the sampled grid to obtain the
    /// marker in its rotation 0.
    pub rotation: usize,
    /// Bits that differed (corrected).
    pub distance: usize,
}

impl Dictionary {
    /// Number of markers.
    pub fn len(&self) -> usize {
        self.codes.len()
    }

    /// Whether the dictionary holds no marker (never for the predefined ones).
    pub fn is_empty(&self) -> bool {
        self.codes.is_empty()
    }

    /// Bit `(row, col)` of marker `id` (true = white).
    pub fn bit(&self, id: usize, row: usize, col: usize) -> bool {
        code_bit(self.codes[id], self.marker_size, row, col)
    }

    /// Matches a sampled code in all four rotations; the closest marker
    /// within `max_correction_bits` wins (ties: lowest id, then rotation).
    pub fn identify(&self, sampled: u64) -> Option<Identified> {
        let mut best: Option<Identified> = None;
        let mut code = sampled;
        for rotation in 0..4 {
            for (id, &m) in self.codes.iter().enumerate() {
                let distance = (m ^ code).count_ones() as usize;
                if distance <= self.max_correction_bits
                    && best.is_none_or(|b| distance < b.distance)
                {
                    best = Some(Identified {
                        id,
                        rotation,
                        distance,
                    });
                }
            }
            code = rotate_cw(code, self.marker_size);
        }
        best
    }
}

/// Bit `(row, col)` of a `size x size` code.
pub fn code_bit(code: u64, size: usize, row: usize, col: usize) -> bool {
    let k = row * size + col;
    (code >> (size * size - 1 - k)) & 1 == 1
}

/// Code of a row-major bit grid (true = white).
pub fn code_from_bits(bits: &[bool], size: usize) -> u64 {
    debug_assert_eq!(bits.len(), size * size);
    bits.iter().fold(0u64, |acc, &b| (acc << 1) | u64::from(b))
}

/// The code of the grid turned a quarter clockwise (as seen with y down):
/// `new(r, c) = old(size - 1 - c, r)`.
pub fn rotate_cw(code: u64, size: usize) -> u64 {
    let mut bits = vec![false; size * size];
    for r in 0..size {
        for c in 0..size {
            bits[r * size + c] = code_bit(code, size, size - 1 - c, r);
        }
    }
    code_from_bits(&bits, size)
}

fn parse(blob: &[u8]) -> Option<Vec<Dictionary>> {
    let mut at = 0usize;
    let mut take = |n: usize| -> Option<&[u8]> {
        let s = blob.get(at..at + n)?;
        at += n;
        Some(s)
    };
    if take(MAGIC.len())? != MAGIC {
        return None;
    }
    let u16_of = |b: &[u8]| u16::from_le_bytes([b[0], b[1]]);
    let count = u16_of(take(2)?) as usize;
    let mut out = Vec::with_capacity(count);
    for _ in 0..count {
        let name_len = take(1)?[0] as usize;
        let name = String::from_utf8(take(name_len)?.to_vec()).ok()?;
        let opencv_id = u16_of(take(2)?);
        let marker_size = take(1)?[0] as usize;
        let max_correction_bits = take(1)?[0] as usize;
        let n = u16_of(take(2)?) as usize;
        if marker_size == 0 || marker_size > MAX_MARKER_BITS_SIDE {
            return None;
        }
        let nbits = marker_size * marker_size;
        let nbytes = nbits.div_ceil(8);
        let mut codes = Vec::with_capacity(n);
        for _ in 0..n {
            let packed = take(nbytes)?;
            let bits: Vec<bool> = (0..nbits)
                .map(|k| (packed[k / 8] >> (7 - k % 8)) & 1 == 1)
                .collect();
            codes.push(code_from_bits(&bits, marker_size));
        }
        out.push(Dictionary {
            name,
            opencv_id,
            marker_size,
            max_correction_bits,
            codes,
        });
    }
    (at == blob.len()).then_some(out)
}

/// Every predefined dictionary, in OpenCV's enum order.
pub fn predefined_all() -> &'static [Dictionary] {
    static ALL: OnceLock<Vec<Dictionary>> = OnceLock::new();
    ALL.get_or_init(|| parse(DICTIONARIES_BIN).unwrap_or_default())
}

/// A predefined dictionary by OpenCV's name, case-insensitive
/// (`DICT_APRILTAG_36H11` and `DICT_APRILTAG_36h11` are the same, as in cv2).
pub fn predefined(name: &str) -> Option<&'static Dictionary> {
    predefined_all()
        .iter()
        .find(|d| d.name.eq_ignore_ascii_case(name))
}

/// The accepted dictionary names, for error messages.
pub fn predefined_names() -> Vec<&'static str> {
    predefined_all().iter().map(|d| d.name.as_str()).collect()
}

#[cfg(test)]
#[path = "dictionary_tests.rs"]
mod tests;
