//! Grey-level image buffer the detector works on, and safe decoding of
//! untrusted bytes (limits are checked before any pixel allocation).

use std::borrow::Cow;
use std::io::Cursor;

use image::{DynamicImage, ImageReader, Limits};

use super::error::DetectError;

/// Default largest accepted image side, pixels.
pub const DEFAULT_MAX_SIDE_PX: u32 = 12_000;
/// Default largest decoder allocation, bytes (a 12k x 12k 16-bit RGB image is
/// ~860 MB; keep a service worker well below that).
pub const DEFAULT_MAX_ALLOC_BYTES: u64 = 512 * 1024 * 1024;
/// Grey levels are expressed on the 8-bit scale whatever the source depth.
pub const WHITE_LEVEL: f32 = 255.0;
/// 16-bit to 8-bit grey-level scale.
const U16_TO_U8_SCALE: f32 = 1.0 / 257.0;

/// Decoding limits for untrusted image bytes.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct DecodeLimits {
    pub max_width: u32,
    pub max_height: u32,
    pub max_alloc_bytes: u64,
}

impl Default for DecodeLimits {
    fn default() -> Self {
        Self {
            max_width: DEFAULT_MAX_SIDE_PX,
            max_height: DEFAULT_MAX_SIDE_PX,
            max_alloc_bytes: DEFAULT_MAX_ALLOC_BYTES,
        }
    }
}

/// Row-major grey levels on the 8-bit scale (0 black .. 255 white), any
/// source depth; the pixel in column `j`, row `i` has centre `(j, i)`
/// (method.md §1).
#[derive(Debug, Clone, PartialEq)]
pub struct GrayImage {
    pub width: usize,
    pub height: usize,
    pub data: Vec<f32>,
}

impl GrayImage {
    /// Wraps a buffer, checking its length.
    pub fn new(width: usize, height: usize, data: Vec<f32>) -> Result<Self, DetectError> {
        if width.checked_mul(height) != Some(data.len()) {
            return Err(DetectError::BufferSize {
                width,
                height,
                len: data.len(),
            });
        }
        Ok(Self {
            width,
            height,
            data,
        })
    }

    /// Converts any decoded image to grey (luma of colour, 16-bit scaled to 8-bit).
    pub fn from_dynamic(img: &DynamicImage) -> Self {
        let (width, height) = (img.width() as usize, img.height() as usize);
        let data = match img {
            DynamicImage::ImageLuma8(g) => g.as_raw().iter().map(|&v| v as f32).collect(),
            DynamicImage::ImageLuma16(g) => g
                .as_raw()
                .iter()
                .map(|&v| v as f32 * U16_TO_U8_SCALE)
                .collect(),
            other if other.color().has_color() && other.color().bytes_per_pixel() > 4 => other
                .to_luma16()
                .as_raw()
                .iter()
                .map(|&v| v as f32 * U16_TO_U8_SCALE)
                .collect(),
            other => other
                .to_luma8()
                .as_raw()
                .iter()
                .map(|&v| v as f32)
                .collect(),
        };
        Self {
            width,
            height,
            data,
        }
    }

    /// Grey level at column `x`, row `y` (no bounds check beyond the slice's).
    #[inline]
    pub fn at(&self, x: usize, y: usize) -> f32 {
        self.data[y * self.width + x]
    }

    /// Rounds to an 8-bit image (for writing PNGs).
    pub fn to_luma8(&self) -> image::GrayImage {
        let raw = self
            .data
            .iter()
            .map(|&v| v.round().clamp(0.0, WHITE_LEVEL) as u8)
            .collect();
        image::GrayImage::from_raw(self.width as u32, self.height as u32, raw)
            .expect("length checked at construction")
    }
}

/// Read access to grey levels on the 8-bit scale whatever the buffer's
/// element type. The chessboard detector reads the decoder's 8-bit image
/// through it directly: an f32 copy is four times the memory its
/// decimation and refinement read (issue 14's time per image).
pub trait GreyLevels {
    fn width(&self) -> usize;
    fn height(&self) -> usize;
    /// Grey level of the pixel at row-major index `i`.
    fn level(&self, i: usize) -> f32;
    /// Adds the first `acc.len()` levels of row `y` into `acc`.
    fn add_row(&self, y: usize, acc: &mut [f32]);
}

impl GreyLevels for GrayImage {
    fn width(&self) -> usize {
        self.width
    }
    fn height(&self) -> usize {
        self.height
    }
    #[inline]
    fn level(&self, i: usize) -> f32 {
        self.data[i]
    }
    fn add_row(&self, y: usize, acc: &mut [f32]) {
        let line = &self.data[y * self.width..][..acc.len()];
        for (a, x) in acc.iter_mut().zip(line) {
            *a += x;
        }
    }
}

/// The decoder's 8-bit grey image (levels as they are).
impl GreyLevels for image::GrayImage {
    fn width(&self) -> usize {
        self.width() as usize
    }
    fn height(&self) -> usize {
        self.height() as usize
    }
    #[inline]
    fn level(&self, i: usize) -> f32 {
        f32::from(self.as_raw()[i])
    }
    fn add_row(&self, y: usize, acc: &mut [f32]) {
        let w = self.width() as usize;
        let line = &self.as_raw()[y * w..][..acc.len()];
        for (a, &x) in acc.iter_mut().zip(line) {
            *a += f32::from(x);
        }
    }
}

fn reader(bytes: &[u8]) -> Result<ImageReader<Cursor<&[u8]>>, DetectError> {
    let r = ImageReader::new(Cursor::new(bytes))
        .with_guessed_format()
        .map_err(|e| DetectError::Decode(e.to_string()))?;
    if r.format().is_none() {
        return Err(DetectError::Decode("unrecognised image format".into()));
    }
    Ok(r)
}

/// A decoded image as the detectors read it. Sources of 8 bits or fewer
/// per channel keep their 8-bit grey levels: the chessboard and ChArUco
/// detectors read them through [`GreyLevels`] with no f32 copy (a quarter
/// of the memory; issue 14's time per image). Deeper sources are scaled to
/// f32 on the 8-bit scale, keeping their precision. The levels are those
/// of [`GrayImage::from_dynamic`] either way.
#[derive(Debug, Clone, PartialEq)]
pub enum DecodedGrey {
    Levels8(image::GrayImage),
    Float(GrayImage),
}

impl DecodedGrey {
    /// Grey levels of any decoded image, 8-bit where the source is.
    pub fn from_dynamic(img: DynamicImage) -> Self {
        let deep = match &img {
            DynamicImage::ImageLuma16(_) => true,
            other => other.color().has_color() && other.color().bytes_per_pixel() > 4,
        };
        match img {
            _ if deep => Self::Float(GrayImage::from_dynamic(&img)),
            DynamicImage::ImageLuma8(g) => Self::Levels8(g),
            other => Self::Levels8(other.to_luma8()),
        }
    }

    /// The f32 image the circle detectors read (a copy for 8-bit levels).
    pub fn to_float(&self) -> Cow<'_, GrayImage> {
        match self {
            Self::Levels8(g) => Cow::Owned(GrayImage {
                width: g.width() as usize,
                height: g.height() as usize,
                data: g.as_raw().iter().map(|&v| f32::from(v)).collect(),
            }),
            Self::Float(g) => Cow::Borrowed(g),
        }
    }

    /// `(width, height)`, pixels.
    pub fn size(&self) -> (usize, usize) {
        match self {
            Self::Levels8(g) => (g.width() as usize, g.height() as usize),
            Self::Float(g) => (g.width, g.height),
        }
    }
}

impl From<GrayImage> for DecodedGrey {
    fn from(img: GrayImage) -> Self {
        Self::Float(img)
    }
}

/// Decodes untrusted PNG/JPEG bytes to grey, rejecting oversized headers
/// before allocating pixels and truncated or unknown data with an error.
pub fn decode_image(bytes: &[u8], limits: &DecodeLimits) -> Result<GrayImage, DetectError> {
    Ok(decode_grey(bytes, limits)?.to_float().into_owned())
}

/// [`decode_image`] keeping 8-bit sources 8-bit ([`DecodedGrey`]). A
/// non-interlaced PNG is decoded row by row (`png_rows`); what the
/// decode holds is [`super::SourceHeader::bytes_per_pixel`].
pub fn decode_grey(bytes: &[u8], limits: &DecodeLimits) -> Result<DecodedGrey, DetectError> {
    if bytes.is_empty() {
        return Err(DetectError::Decode("empty input".into()));
    }
    let (width, height) = reader(bytes)?
        .into_dimensions()
        .map_err(|e| DetectError::Decode(e.to_string()))?;
    if width > limits.max_width || height > limits.max_height {
        return Err(DetectError::ImageTooLarge {
            width,
            height,
            max_width: limits.max_width,
            max_height: limits.max_height,
        });
    }
    if image::guess_format(bytes).ok() == Some(image::ImageFormat::Png) {
        // Row by row, so the decoder never holds the image's own layout.
        if let Some(grey) = super::png_rows::decode(bytes)? {
            return Ok(grey);
        }
    }
    let mut r = reader(bytes)?;
    let mut lim = Limits::default();
    lim.max_image_width = Some(limits.max_width);
    lim.max_image_height = Some(limits.max_height);
    lim.max_alloc = Some(limits.max_alloc_bytes);
    r.limits(lim);
    let img = r.decode().map_err(|e| DetectError::Decode(e.to_string()))?;
    Ok(DecodedGrey::from_dynamic(img))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn png(img: DynamicImage) -> Vec<u8> {
        let mut out = Vec::new();
        img.write_to(&mut Cursor::new(&mut out), image::ImageFormat::Png)
            .unwrap();
        out
    }

    /// 8-bit grey and colour sources stay 8-bit with the levels the f32
    /// decode gives; 16-bit sources keep their precision in f32.
    #[test]
    fn eight_bit_sources_stay_eight_bit_and_deeper_ones_become_float() {
        let limits = DecodeLimits::default();
        let grey = image::GrayImage::from_fn(5, 3, |x, y| image::Luma([(40 * x + 7 * y) as u8]));
        let decoded = decode_grey(&png(DynamicImage::ImageLuma8(grey.clone())), &limits).unwrap();
        assert_eq!(decoded, DecodedGrey::Levels8(grey.clone()));
        assert_eq!(decoded.size(), (5, 3));
        let float = decode_image(&png(DynamicImage::ImageLuma8(grey.clone())), &limits).unwrap();
        assert_eq!(*decoded.to_float(), float);
        assert_eq!(float.at(3, 2), 134.0);

        let rgb = image::RgbImage::from_fn(4, 2, |x, _| image::Rgb([60 * x as u8, 10, 200]));
        let dynamic = DynamicImage::ImageRgb8(rgb);
        let decoded = decode_grey(&png(dynamic.clone()), &limits).unwrap();
        assert_eq!(decoded, DecodedGrey::Levels8(dynamic.to_luma8()));

        let deep = image::ImageBuffer::<image::Luma<u16>, _>::from_fn(3, 2, |x, _| {
            image::Luma([1000 + 257 * x as u16])
        });
        match decode_grey(&png(DynamicImage::ImageLuma16(deep)), &limits).unwrap() {
            DecodedGrey::Float(g) => {
                assert!((g.at(0, 0) - 1000.0 / 257.0).abs() < 1e-4, "{}", g.at(0, 0));
                assert!((g.at(2, 1) - (1000.0 / 257.0 + 2.0)).abs() < 1e-4);
            }
            other => panic!("16-bit decoded as {other:?}"),
        }
    }
}
