//! Peak memory and time of decoding one 16-bit RGBA PNG, whole (the
//! `image` crate's decode, then luma, then f32: what the service did) or
//! row by row (what it does), and whether the service's header check
//! refuses it first. One decode per process, so the peak (`VmHWM`) is
//! that decode's.
//!
//! ```text
//! cargo run --release --example decode_peak -- gen 18000 18000 /tmp/huge.png
//! cargo run --release --example decode_peak -- whole /tmp/huge.png
//! cargo run --release --example decode_peak -- rows /tmp/huge.png
//! cargo run --release --example decode_peak -- check /tmp/huge.png
//! ```

use std::io::{BufWriter, Write};
use std::time::Instant;

use robocal::imaging::{self, DecodeBudget};
use robocal_calib::vision::{decode_grey, DecodeLimits, DecodedGrey};

/// The server's defaults (`--max-camera-pixels`, `--max-decode-bytes`).
const DEFAULT_BUDGET: DecodeBudget = DecodeBudget {
    max_pixels: 50_000_000,
    max_bytes: 512 * 1024 * 1024,
};

fn peak_rss_mb() -> f64 {
    std::fs::read_to_string("/proc/self/status")
        .unwrap()
        .lines()
        .find_map(|l| l.strip_prefix("VmHWM:"))
        .and_then(|v| v.trim().trim_end_matches("kB").trim().parse::<f64>().ok())
        .unwrap_or(f64::NAN)
        / 1024.0
}

/// A 16-bit RGBA PNG written row by row: a soft gradient, so it
/// compresses to a few MB however large it is.
fn generate(width: u32, height: u32, path: &str) {
    let file = BufWriter::new(std::fs::File::create(path).unwrap());
    let mut encoder = png::Encoder::new(file, width, height);
    encoder.set_color(png::ColorType::Rgba);
    encoder.set_depth(png::BitDepth::Sixteen);
    encoder.set_compression(png::Compression::High);
    let mut writer = encoder.write_header().unwrap();
    let mut stream = writer.stream_writer().unwrap();
    let mut row = vec![0u8; width as usize * 8];
    for y in 0..height {
        let level = ((u64::from(y) * 65_535) / u64::from(height.max(1))) as u16;
        for px in row.chunks_exact_mut(8) {
            for c in 0..4 {
                px[2 * c..2 * c + 2].copy_from_slice(&level.to_be_bytes());
            }
        }
        stream.write_all(&row).unwrap();
    }
    stream.finish().unwrap();
    let size = std::fs::metadata(path).unwrap().len();
    println!("wrote {width}x{height} 16-bit RGBA PNG, {size} bytes, to {path}");
}

fn main() {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let arg = |i: usize| args.get(i).cloned().unwrap_or_default();
    if arg(0) == "gen" {
        generate(arg(1).parse().unwrap(), arg(2).parse().unwrap(), &arg(3));
        return;
    }
    let bytes = std::fs::read(arg(1)).expect("usage: decode_peak gen|whole|rows|check FILE");
    let start = Instant::now();
    let size = match arg(0).as_str() {
        "whole" => {
            let img = image::load_from_memory(&bytes).unwrap();
            DecodedGrey::from_dynamic(img).size()
        }
        "rows" => {
            let limits = DecodeLimits {
                max_width: u32::MAX,
                max_height: u32::MAX,
                max_alloc_bytes: u64::MAX,
            };
            decode_grey(&bytes, &limits).unwrap().size()
        }
        "check" => match imaging::check_header(&bytes, None, DEFAULT_BUDGET) {
            Ok(head) => (head.width as usize, head.height as usize),
            Err(refused) => {
                println!("refused: {refused}");
                (0, 0)
            }
        },
        other => panic!("unknown mode {other}"),
    };
    println!(
        "{}: {}x{} grey in {:.2} s, peak RSS {:.0} MB (file {} bytes)",
        arg(0),
        size.0,
        size.1,
        start.elapsed().as_secs_f64(),
        peak_rss_mb(),
        bytes.len()
    );
}
