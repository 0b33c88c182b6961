//! Untrusted images, bounded: the header is read and compared with the
//! session camera before a single pixel is decoded, the decoder's
//! allocation is capped to what the header's size needs, and decodes run
//! under a [`DecodeGate`] shared by uploads and jobs so that concurrent
//! uploads cannot multiply the memory of one decode; the header's bit
//! depth and channels price a decode in bytes before it starts.

mod found;
mod gate;

use robocal_calib::vision::{self, DecodeLimits, DecodedGrey, SourceHeader};

pub use found::detect;
pub use gate::{DecodeBudget, DecodeGate, DecodePermit, JOBS_KEY};

use crate::domain::{ImageDetection, Target};
use crate::schema::session::MAX_IMAGE_SIDE;

/// Most bytes per pixel any accepted PNG/JPEG decodes to (16-bit RGBA).
const MAX_BYTES_PER_PIXEL: u64 = 8;
/// Decoder working memory beyond the pixel buffer (rows, tables), bytes.
const DECODE_SLACK_BYTES: u64 = 16 * 1024 * 1024;

/// The header alone (PNG or JPEG only): format, size, sample layout.
pub fn header(bytes: &[u8]) -> Result<SourceHeader, String> {
    vision::read_header(bytes).map_err(|e| match e {
        vision::DetectError::Decode(m) if m.starts_with("not a PNG") => {
            "not a PNG or JPEG image; send PNG or JPEG".to_string()
        }
        e => format!("cannot read the image header: {e}"),
    })
}

/// Checks the header against the per-side limit, the session camera's
/// `expected` size and the decode `budget` (pixels, and the bytes the
/// decode would hold given its bit depth and channels), without decoding.
pub fn check_header(
    bytes: &[u8],
    expected: Option<(u32, u32)>,
    budget: DecodeBudget,
) -> Result<SourceHeader, String> {
    let head = header(bytes)?;
    let (w, h) = (head.width, head.height);
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
    if head.pixels() > budget.max_pixels {
        return Err(format!(
            "image is {w}x{h} = {} pixels; this server decodes at most {} \
             (server option --max-camera-pixels)",
            head.pixels(),
            budget.max_pixels
        ));
    }
    if head.decode_bytes() > budget.max_bytes {
        return Err(format!(
            "a {} decodes into {} bytes ({} a pixel); this server decodes at most {} \
             (server option --max-decode-bytes): send 8-bit grey or a smaller image",
            head.describe(),
            head.decode_bytes(),
            head.bytes_per_pixel(),
            budget.max_bytes
        ));
    }
    Ok(head)
}

/// Decodes to grey after [`check_header`] against the gate's budget, the
/// decoder allowed no more memory than the header's size needs (a lying
/// header fails, it does not allocate). 8-bit sources stay 8-bit
/// ([`DecodedGrey`]); PNGs are decoded row by row. The caller holds a
/// [`DecodePermit`].
pub fn decode_checked(
    bytes: &[u8],
    expected: Option<(u32, u32)>,
    permit: &DecodePermit<'_>,
) -> Result<DecodedGrey, String> {
    let head = check_header(bytes, expected, permit.budget())?;
    let (w, h) = (head.width, head.height);
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

/// Checks (header first), decodes once under `gate` in `key`'s share
/// and detects `target`. `Err` only for images that cannot be accepted
/// (not PNG/JPEG, wrong size, over budget, undecodable); a board not
/// found is an `Ok` with the reason inside.
pub fn inspect(
    bytes: &[u8],
    expected: Option<(u32, u32)>,
    target: Option<&Target>,
    gate: &DecodeGate,
    key: &str,
) -> Result<Inspected, String> {
    let head = check_header(bytes, expected, gate.budget())?;
    let (width, height) = (head.width, head.height);
    let permit = gate.acquire(key);
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
