//! Untrusted images, bounded: the header is read and compared with the
//! session camera before a single pixel is decoded, the decoder's
//! allocation is capped to what the header's size needs, and decodes run
//! under a [`DecodeGate`] shared by uploads and jobs so that concurrent
//! uploads cannot multiply the memory of one decode (issue 12).

mod found;
mod gate;

use std::io::Cursor;

use image::{ImageFormat, ImageReader};
use robocal_calib::vision::{self, DecodeLimits, DecodedGrey};

pub use found::detect;
pub use gate::{DecodeGate, DecodePermit};

use crate::domain::{ImageDetection, Target};
use crate::schema::session::MAX_IMAGE_SIDE;

/// Most bytes per pixel any accepted PNG/JPEG decodes to (16-bit RGBA).
const MAX_BYTES_PER_PIXEL: u64 = 8;
/// Decoder working memory beyond the pixel buffer (rows, tables), bytes.
const DECODE_SLACK_BYTES: u64 = 16 * 1024 * 1024;

/// Format and `(width, height)` from the header alone (PNG or JPEG only).
pub fn header(bytes: &[u8]) -> Result<(ImageFormat, u32, u32), String> {
    let format = image::guess_format(bytes).map_err(|_| "not a PNG or JPEG image".to_string())?;
    if !matches!(format, ImageFormat::Png | ImageFormat::Jpeg) {
        return Err(format!(
            "{format:?} images are not accepted; send PNG or JPEG"
        ));
    }
    let (width, height) = ImageReader::with_format(Cursor::new(bytes), format)
        .into_dimensions()
        .map_err(|e| format!("cannot read the image header: {e}"))?;
    Ok((format, width, height))
}

/// Checks the header's size against the limits and the session camera's
/// `expected` size, without decoding. Returns `(width, height)`.
pub fn check_header(bytes: &[u8], expected: Option<(u32, u32)>) -> Result<(u32, u32), String> {
    let (_, w, h) = header(bytes)?;
    if let Some((ew, eh)) = expected {
        if (w, h) != (ew, eh) {
            return Err(format!("image is {w}x{h}, the session camera is {ew}x{eh}"));
        }
    }
    if w > MAX_IMAGE_SIDE || h > MAX_IMAGE_SIDE {
        return Err(format!(
            "image is {w}x{h}; at most {MAX_IMAGE_SIDE} pixels per side"
        ));
    }
    Ok((w, h))
}

/// Decodes to grey after [`check_header`], the decoder allowed no more
/// memory than the header's size needs (a lying header fails, it does not
/// allocate). 8-bit sources stay 8-bit ([`DecodedGrey`]): the chessboard
/// and ChArUco detectors read them as they are. The caller holds a
/// [`DecodePermit`].
pub fn decode_checked(
    bytes: &[u8],
    expected: Option<(u32, u32)>,
    _permit: &DecodePermit<'_>,
) -> Result<DecodedGrey, String> {
    let (w, h) = check_header(bytes, expected)?;
    let limits = DecodeLimits {
        max_width: w,
        max_height: h,
        max_alloc_bytes: w as u64 * h as u64 * MAX_BYTES_PER_PIXEL + DECODE_SLACK_BYTES,
    };
    vision::decode_grey(bytes, &limits).map_err(|e| e.to_string())
}

/// What an upload learns from an image: its size, and when the session has
/// a target, what the detector finds on it.
#[derive(Debug, Clone)]
pub struct Inspected {
    pub width: u32,
    pub height: u32,
    pub detection: Option<ImageDetection>,
}

/// Checks (header first), decodes once under `gate` and detects `target`.
/// `Err` only for images that cannot be accepted (not PNG/JPEG, wrong size,
/// undecodable); a board not found is an `Ok` with the reason inside.
pub fn inspect(
    bytes: &[u8],
    expected: Option<(u32, u32)>,
    target: Option<&Target>,
    gate: &DecodeGate,
) -> Result<Inspected, String> {
    let (width, height) = check_header(bytes, expected)?;
    let permit = gate.acquire();
    let gray = decode_checked(bytes, expected, &permit)?;
    let detection = target.map(|t| detect(&gray, t));
    drop(gray);
    drop(permit);
    Ok(Inspected {
        width,
        height,
        detection,
    })
}
