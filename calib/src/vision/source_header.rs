//! What an image's header says before a pixel is decoded: its format,
//! size and sample layout, and from them what decoding it will hold in
//! memory at most. A service refuses an image over its budget from this
//! alone, so an image that inflates 2 MB into gigabytes costs nothing.

use std::io::Cursor;

use image::codecs::jpeg::JpegDecoder;
use image::ImageDecoder;

use super::error::DetectError;

/// Bytes of one f32 grey level.
const F32_BYTES: u64 = 4;
/// A JPEG decode holds per component one output sample and, for
/// progressive files, one i16 coefficient: three bytes a pixel.
const JPEG_BYTES_PER_COMPONENT: u64 = 3;
/// The whole-image path's 16-bit luma intermediate, bytes a pixel.
const LUMA16_BYTES: u64 = 2;

/// The accepted containers.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum SourceFormat {
    Png,
    Jpeg,
}

/// An image's header, read without decoding pixels.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct SourceHeader {
    pub format: SourceFormat,
    pub width: u32,
    pub height: u32,
    /// Samples a pixel after palette expansion (1 grey … 4 RGBA).
    pub channels: u8,
    /// Bits a sample after palette and low-depth expansion (8 or 16).
    pub bits_per_sample: u8,
    /// Whether the decode keeps f32 levels (16-bit grey or colour, see
    /// [`super::DecodedGrey`]) instead of 8-bit ones.
    pub deep: bool,
    /// PNG Adam7: decoded whole, not row by row.
    pub interlaced: bool,
}

impl SourceHeader {
    pub fn pixels(&self) -> u64 {
        u64::from(self.width) * u64::from(self.height)
    }

    /// Most bytes a pixel of this image costs at once while it is decoded
    /// and read by a detector: the grey output, what the decoder holds
    /// beside it, and the f32 copy circle detectors read of 8-bit levels.
    pub fn bytes_per_pixel(&self) -> u64 {
        let float_copy = if self.deep { 0 } else { F32_BYTES };
        let output = if self.deep { F32_BYTES } else { 1 };
        let decoder = match (self.format, self.interlaced) {
            // Row by row: the decoder holds two rows, not an image.
            (SourceFormat::Png, false) => 0,
            // Whole image, then its luma (16-bit at most) before the grey output.
            (SourceFormat::Png, true) => {
                u64::from(self.channels) * u64::from(self.bits_per_sample / 8) + LUMA16_BYTES
            }
            (SourceFormat::Jpeg, _) => u64::from(self.channels) * JPEG_BYTES_PER_COMPONENT,
        };
        output + decoder + float_copy
    }

    /// [`Self::bytes_per_pixel`] for the whole image.
    pub fn decode_bytes(&self) -> u64 {
        self.pixels().saturating_mul(self.bytes_per_pixel())
    }

    /// A short description for messages: `4000x3000 16-bit RGBA PNG`.
    pub fn describe(&self) -> String {
        let layout = match self.channels {
            1 => "grey",
            2 => "grey+alpha",
            3 => "RGB",
            _ => "RGBA",
        };
        let format = match self.format {
            SourceFormat::Png => "PNG",
            SourceFormat::Jpeg => "JPEG",
        };
        format!(
            "{}x{} {}-bit {layout} {format}",
            self.width, self.height, self.bits_per_sample
        )
    }
}

/// Reads the header of PNG or JPEG bytes; anything else is an error.
pub fn read_header(bytes: &[u8]) -> Result<SourceHeader, DetectError> {
    match image::guess_format(bytes) {
        Ok(image::ImageFormat::Png) => png_header(bytes),
        Ok(image::ImageFormat::Jpeg) => jpeg_header(bytes),
        _ => Err(DetectError::Decode("not a PNG or JPEG image".into())),
    }
}

fn png_header(bytes: &[u8]) -> Result<SourceHeader, DetectError> {
    let reader = super::png_rows::open(bytes)?;
    let info = reader.info();
    let (color, depth) = reader.output_color_type();
    Ok(SourceHeader {
        format: SourceFormat::Png,
        width: info.width,
        height: info.height,
        channels: color.samples() as u8,
        bits_per_sample: depth as u8,
        deep: super::png_rows::is_deep(color, depth),
        interlaced: info.interlaced,
    })
}

fn jpeg_header(bytes: &[u8]) -> Result<SourceHeader, DetectError> {
    let decoder =
        JpegDecoder::new(Cursor::new(bytes)).map_err(|e| DetectError::Decode(e.to_string()))?;
    let (width, height) = decoder.dimensions();
    let color = decoder.color_type();
    Ok(SourceHeader {
        format: SourceFormat::Jpeg,
        width,
        height,
        channels: color.channel_count(),
        bits_per_sample: 8,
        deep: false,
        interlaced: false,
    })
}
