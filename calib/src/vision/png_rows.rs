//! A PNG decoded row by row straight into grey levels: the decoder holds
//! two rows, never the image in its own sample layout, so a 16-bit RGBA
//! image costs its grey output (4 bytes a pixel) instead of the 14 the
//! whole-image path holds (8 decoded, 2 luma, 4 f32). The levels are
//! exactly those of [`super::DecodedGrey::from_dynamic`] on the `image`
//! crate's decode (same palette and low-depth expansion; each row goes
//! through the crate's own colour conversion). Adam7 files are left to
//! that path.

use std::io::Cursor;

use image::{DynamicImage, ImageBuffer};
use png::{BitDepth, ColorType, Decoder, Reader, Transformations};

use super::error::DetectError;
use super::image::{DecodedGrey, GrayImage};

/// Bytes the PNG decoder may allocate besides its output (row buffers,
/// text and colour-profile chunks); rows are at most 12 000 RGBA16 pixels.
const PNG_DECODER_BYTES: u64 = 16 * 1024 * 1024;

/// A reader past the header, with the `image` crate's transformation
/// (palette to RGB(A), low depths to 8 bits, tRNS to alpha).
pub(crate) fn open(bytes: &[u8]) -> Result<Reader<Cursor<&[u8]>>, DetectError> {
    let mut decoder = Decoder::new_with_limits(
        Cursor::new(bytes),
        png::Limits {
            bytes: PNG_DECODER_BYTES as usize,
        },
    );
    decoder.set_transformations(Transformations::EXPAND);
    decoder
        .read_info()
        .map_err(|e| DetectError::Decode(e.to_string()))
}

/// Whether the output layout decodes to f32 levels: the `image` crate's
/// `Luma16`, `Rgb16` and `Rgba16` (its `LumaA16` becomes 8-bit levels).
pub(crate) fn is_deep(color: ColorType, depth: BitDepth) -> bool {
    depth == BitDepth::Sixteen
        && matches!(
            color,
            ColorType::Grayscale | ColorType::Rgb | ColorType::Rgba
        )
}

/// Decodes a non-interlaced PNG row by row; `Ok(None)` for an Adam7 file
/// (the caller decodes it whole). Each row is converted by the `image`
/// crate itself (a one-row image through [`DecodedGrey::from_dynamic`]),
/// so the levels are those of the whole-image path to the bit.
pub(crate) fn decode(bytes: &[u8]) -> Result<Option<DecodedGrey>, DetectError> {
    let mut reader = open(bytes)?;
    if reader.info().interlaced {
        return Ok(None);
    }
    let (width, height) = (reader.info().width, reader.info().height);
    let (color, depth) = reader.output_color_type();
    let pixels = width as usize * height as usize;
    let deep = is_deep(color, depth);
    let (mut levels, mut floats) = if deep {
        (Vec::new(), Vec::with_capacity(pixels))
    } else {
        (Vec::with_capacity(pixels), Vec::new())
    };
    while let Some(row) = reader
        .next_row()
        .map_err(|e| DetectError::Decode(e.to_string()))?
    {
        match DecodedGrey::from_dynamic(row_image(row.data(), width, color, depth)?) {
            DecodedGrey::Levels8(g) => levels.extend_from_slice(g.as_raw()),
            DecodedGrey::Float(g) => floats.extend_from_slice(&g.data),
        }
    }
    if deep {
        let grey = GrayImage::new(width as usize, height as usize, floats)?;
        return Ok(Some(DecodedGrey::Float(grey)));
    }
    let grey = image::GrayImage::from_raw(width, height, levels)
        .ok_or_else(|| DetectError::Decode("PNG ended before its last row".into()))?;
    Ok(Some(DecodedGrey::Levels8(grey)))
}

/// One decoded row as a one-row image of the `image` crate's layout
/// (16-bit samples from PNG's big-endian order).
fn row_image(
    data: &[u8],
    width: u32,
    color: ColorType,
    depth: BitDepth,
) -> Result<DynamicImage, DetectError> {
    let bad_row = || DetectError::Decode("PNG row of an unexpected length".into());
    let wide = || -> Vec<u16> {
        data.chunks_exact(2)
            .map(|b| u16::from_be_bytes([b[0], b[1]]))
            .collect()
    };
    let image = match (color, depth) {
        (ColorType::Grayscale, BitDepth::Eight) => {
            ImageBuffer::from_raw(width, 1, data.to_vec()).map(DynamicImage::ImageLuma8)
        }
        (ColorType::GrayscaleAlpha, BitDepth::Eight) => {
            ImageBuffer::from_raw(width, 1, data.to_vec()).map(DynamicImage::ImageLumaA8)
        }
        (ColorType::Rgb, BitDepth::Eight) => {
            ImageBuffer::from_raw(width, 1, data.to_vec()).map(DynamicImage::ImageRgb8)
        }
        (ColorType::Rgba, BitDepth::Eight) => {
            ImageBuffer::from_raw(width, 1, data.to_vec()).map(DynamicImage::ImageRgba8)
        }
        (ColorType::Grayscale, BitDepth::Sixteen) => {
            ImageBuffer::from_raw(width, 1, wide()).map(DynamicImage::ImageLuma16)
        }
        (ColorType::GrayscaleAlpha, BitDepth::Sixteen) => {
            ImageBuffer::from_raw(width, 1, wide()).map(DynamicImage::ImageLumaA16)
        }
        (ColorType::Rgb, BitDepth::Sixteen) => {
            ImageBuffer::from_raw(width, 1, wide()).map(DynamicImage::ImageRgb16)
        }
        (ColorType::Rgba, BitDepth::Sixteen) => {
            ImageBuffer::from_raw(width, 1, wide()).map(DynamicImage::ImageRgba16)
        }
        _ => {
            return Err(DetectError::Decode(format!(
                "PNG layout {color:?} at {depth:?} after expansion"
            )))
        }
    };
    image.ok_or_else(bad_row)
}

#[cfg(test)]
mod tests {
    use image::{Luma, LumaA, Rgb, Rgba};

    use super::*;

    fn png(img: &DynamicImage) -> Vec<u8> {
        let mut out = Vec::new();
        img.write_to(&mut Cursor::new(&mut out), image::ImageFormat::Png)
            .unwrap();
        out
    }

    /// A level pattern that uses the whole 16-bit range on every channel.
    fn level(x: u32, y: u32, channel: u32) -> u16 {
        ((x * 7919 + y * 104_729 + channel * 15_485_863) % 65_536) as u16
    }

    fn sources() -> Vec<(&'static str, DynamicImage)> {
        let (w, h) = (37, 11);
        let l16 = ImageBuffer::from_fn(w, h, |x, y| Luma([level(x, y, 0)]));
        let la16 = ImageBuffer::from_fn(w, h, |x, y| LumaA([level(x, y, 0), level(x, y, 1)]));
        let rgb16 = ImageBuffer::from_fn(w, h, |x, y| {
            Rgb([level(x, y, 0), level(x, y, 1), level(x, y, 2)])
        });
        let rgba16 = ImageBuffer::from_fn(w, h, |x, y| {
            Rgba([
                level(x, y, 0),
                level(x, y, 1),
                level(x, y, 2),
                level(x, y, 3),
            ])
        });
        let deep = [
            ("L16", DynamicImage::ImageLuma16(l16)),
            ("LA16", DynamicImage::ImageLumaA16(la16)),
            ("RGB16", DynamicImage::ImageRgb16(rgb16)),
            ("RGBA16", DynamicImage::ImageRgba16(rgba16)),
        ];
        let mut all: Vec<_> = deep.iter().map(|(n, img)| (*n, img.clone())).collect();
        for (name, img) in deep {
            let name8 = match name {
                "L16" => "L8",
                "LA16" => "LA8",
                "RGB16" => "RGB8",
                _ => "RGBA8",
            };
            let eight = match img {
                DynamicImage::ImageLuma16(_) => DynamicImage::ImageLuma8(img.to_luma8()),
                DynamicImage::ImageLumaA16(_) => DynamicImage::ImageLumaA8(img.to_luma_alpha8()),
                DynamicImage::ImageRgb16(_) => DynamicImage::ImageRgb8(img.to_rgb8()),
                _ => DynamicImage::ImageRgba8(img.to_rgba8()),
            };
            all.push((name8, eight));
        }
        all
    }

    #[test]
    fn rows_give_the_whole_image_levels_for_every_layout() {
        for (name, img) in sources() {
            let bytes = png(&img);
            let whole = DecodedGrey::from_dynamic(image::load_from_memory(&bytes).unwrap());
            let rows = decode(&bytes).unwrap().expect("not interlaced");
            assert_eq!(rows, whole, "{name}");
        }
    }

    /// Palette and 1-bit files, which the encoder above never writes.
    #[test]
    fn palette_and_low_depth_files_expand_as_the_image_crate_does() {
        for (color, depth, palette) in [
            (ColorType::Indexed, BitDepth::Four, true),
            (ColorType::Grayscale, BitDepth::One, false),
        ] {
            let (w, h) = (13u32, 5u32);
            let mut out = Vec::new();
            {
                let mut enc = png::Encoder::new(&mut out, w, h);
                enc.set_color(color);
                enc.set_depth(depth);
                if palette {
                    enc.set_palette(
                        (0..16u8)
                            .flat_map(|i| [i * 16, 255 - i * 9, i * 3])
                            .collect::<Vec<_>>(),
                    );
                }
                let mut writer = enc.write_header().unwrap();
                let bits = depth as u32;
                let line = (w * bits).div_ceil(8) as usize;
                let data: Vec<u8> = (0..line * h as usize)
                    .map(|i| (i * 37 % 251) as u8)
                    .collect();
                writer.write_image_data(&data).unwrap();
            }
            let whole = DecodedGrey::from_dynamic(image::load_from_memory(&out).unwrap());
            assert_eq!(decode(&out).unwrap().unwrap(), whole, "{color:?} {depth:?}");
        }
    }

    #[test]
    fn a_truncated_file_is_an_error_not_a_panic() {
        let bytes = png(&sources()[3].1);
        for cut in [bytes.len() / 2, bytes.len() - 20, 40] {
            assert!(decode(&bytes[..cut]).is_err(), "cut at {cut}");
        }
    }
}
