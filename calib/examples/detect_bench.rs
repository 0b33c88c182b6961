//! Detection benchmark (issue 3): renders random views of the 9x9 board,
//! detects the dots, reports detection rate, centre error against the true
//! centre images, ms per image and MP/s on one core; with `--opencv` also
//! writes the images to a temp dir and runs `bench/opencv_circles.py` on them.
//!
//! `cargo run --release -p robocal-calib --example detect_bench -- [--views N] [--seed S] [--opencv]`

use std::time::Instant;

use image::DynamicImage;
use rand::{rngs::StdRng, SeedableRng};
use robocal_calib::sim::render::RenderOptions;
use robocal_calib::sim::render_circles::render_target;
use robocal_calib::sim::views::{random_view, reference_camera, ViewRanges};
use robocal_calib::vision::{
    decode_image, detect, detect_dynamic, DecodeLimits, GrayImage, TargetSpec,
};

const WIDTH: usize = 1280;
const HEIGHT: usize = 1024;
/// A dot further than this from its true centre means a wrong ordering.
const WRONG_ORDER_PX: f64 = 1.0;

fn arg<T: std::str::FromStr>(name: &str, default: T) -> T {
    let args: Vec<String> = std::env::args().collect();
    args.iter()
        .position(|a| a == name)
        .and_then(|i| args.get(i + 1))
        .and_then(|v| v.parse().ok())
        .unwrap_or(default)
}

/// CPU time of the calling thread, ns (Linux `/proc/thread-self/schedstat`):
/// the machine is shared, so wall time overstates a busy core's cost.
fn thread_cpu_ns() -> Option<u64> {
    let s = std::fs::read_to_string("/proc/thread-self/schedstat").ok()?;
    s.split_whitespace().next()?.parse().ok()
}

/// PNG bytes of an 8-bit grey image.
fn png(img: &image::GrayImage) -> Vec<u8> {
    let mut out = Vec::new();
    DynamicImage::ImageLuma8(img.clone())
        .write_to(&mut std::io::Cursor::new(&mut out), image::ImageFormat::Png)
        .expect("encode png");
    out
}

/// CRC-32 of a PNG chunk (type + data).
fn crc32(bytes: &[u8]) -> u32 {
    let mut c = 0xFFFF_FFFFu32;
    for &b in bytes {
        c ^= b as u32;
        for _ in 0..8 {
            c = if c & 1 != 0 {
                0xEDB8_8320 ^ (c >> 1)
            } else {
                c >> 1
            };
        }
    }
    !c
}

/// Bad inputs: each must give an error, quickly (decode + detect timed).
fn bad_images(target: &TargetSpec) {
    let (w, h) = (WIDTH as u32, HEIGHT as u32);
    let noise = image::GrayImage::from_fn(w, h, |x, y| {
        image::Luma([((x.wrapping_mul(2_654_435_761) ^ y.wrapping_mul(40_503)) >> 7) as u8])
    });
    let good = png(&image::GrayImage::from_pixel(w, h, image::Luma([128])));
    let mut huge = good[..33].to_vec(); // signature + IHDR claiming 30000 x 30000
    huge[16..20].copy_from_slice(&30000u32.to_be_bytes());
    huge[20..24].copy_from_slice(&30000u32.to_be_bytes());
    let crc = crc32(&huge[12..29]);
    huge[29..33].copy_from_slice(&crc.to_be_bytes());
    huge.extend_from_slice(&good[33..]); // the rest of a valid stream
    let cases: Vec<(&str, Vec<u8>)> = vec![
        ("empty", Vec::new()),
        ("1x1", png(&image::GrayImage::new(1, 1))),
        ("all black", png(&image::GrayImage::new(w, h))),
        (
            "all white",
            png(&image::GrayImage::from_pixel(w, h, image::Luma([255]))),
        ),
        ("noise", png(&noise)),
        ("30000x30000 header", huge),
        ("truncated", good[..good.len() / 2].to_vec()),
    ];
    println!("bad images (decode + detect):");
    for (name, bytes) in cases {
        let start = Instant::now();
        let result = decode_image(&bytes, &DecodeLimits::default())
            .and_then(|g: GrayImage| detect(&g, target));
        let ms = start.elapsed().as_secs_f64() * 1e3;
        match result {
            Err(e) => println!("  {name}: {ms:.1} ms, error: {e}"),
            Ok(_) => println!("  {name}: {ms:.1} ms, UNEXPECTED SUCCESS"),
        }
    }
}

fn main() {
    let views: usize = arg("--views", 500);
    let seed: u64 = arg("--seed", 2026);
    let opencv = std::env::args().any(|a| a == "--opencv");
    let camera = reference_camera();
    let target = TargetSpec::robocal_9x9();
    if std::env::args().any(|a| a == "--bad") {
        bad_images(&target);
        return;
    }
    let opts = RenderOptions::default();
    let mut rng = StdRng::seed_from_u64(seed);
    let dir = std::env::temp_dir().join(format!("robocal_detect_bench_{seed}"));
    if opencv {
        std::fs::create_dir_all(&dir).expect("temp dir");
    }
    let mut truth_csv = String::from("image,row,col,x,y\n");
    let (mut found, mut wrong, mut failures) = (0usize, 0usize, Vec::new());
    let (mut sq, mut sq_raw, mut n, mut max, mut max_raw) = (0.0, 0.0, 0usize, 0.0f64, 0.0f64);
    let (mut seconds, mut cpu_ns) = (0.0, 0u64);
    for v in 0..views {
        let pose = random_view(
            &camera,
            &target,
            WIDTH,
            HEIGHT,
            &ViewRanges::default(),
            &mut rng,
        )
        .expect("a view fits");
        let view =
            render_target(&camera, &pose, &target, WIDTH, HEIGHT, &opts, &mut rng).expect("render");
        let img = DynamicImage::ImageLuma8(view.image.to_luma8());
        if opencv {
            let name = format!("view_{v:04}.png");
            img.save(dir.join(&name)).expect("write png");
            for t in &view.truth {
                truth_csv += &format!("{name},{},{},{:.6},{:.6}\n", t.row, t.col, t.x, t.y);
            }
        }
        let (start, cpu0) = (Instant::now(), thread_cpu_ns().unwrap_or(0));
        let result = detect_dynamic(&img, &target);
        cpu_ns += thread_cpu_ns().unwrap_or(0).saturating_sub(cpu0);
        seconds += start.elapsed().as_secs_f64();
        match result {
            Ok(det) => {
                let mut bad = false;
                for (d, t) in det.dots.iter().zip(&view.truth) {
                    let e = ((d.x - t.x).powi(2) + (d.y - t.y).powi(2)).sqrt();
                    let er = ((d.ellipse.cx - t.x).powi(2) + (d.ellipse.cy - t.y).powi(2)).sqrt();
                    bad |= e > WRONG_ORDER_PX || d.row != t.row || d.col != t.col;
                    sq += e * e;
                    sq_raw += er * er;
                    max = max.max(e);
                    max_raw = max_raw.max(er);
                    n += 1;
                }
                if bad {
                    wrong += 1;
                } else {
                    found += 1;
                }
            }
            Err(e) => {
                if let Ok(dump) = std::env::var("DETECT_BENCH_DUMP") {
                    let _ = img.save(format!("{dump}/failed_view_{v:04}.png"));
                }
                failures.push(format!("view {v}: {e}"))
            }
        }
    }
    let mp = (WIDTH * HEIGHT) as f64 * 1e-6;
    println!("robocal detector: {views} views {WIDTH}x{HEIGHT}, 9x9 dots 8 mm / 25 mm pitch, noise {} grey, blur {} px", opts.noise_sigma_grey, opts.blur_sigma_px);
    println!(
        "  detected+ordered: {found}/{views} ({:.1} %), wrong orderings: {wrong}, errors: {}",
        100.0 * found as f64 / views as f64,
        failures.len()
    );
    for f in failures.iter().take(10) {
        println!("    {f}");
    }
    println!(
        "  centre error (bias-corrected): RMS {:.4} px, max {:.4} px over {n} dots",
        (sq / n.max(1) as f64).sqrt(),
        max
    );
    println!(
        "  centre error (raw ellipse centre): RMS {:.4} px, max {:.4} px",
        (sq_raw / n.max(1) as f64).sqrt(),
        max_raw
    );
    let cpu = cpu_ns as f64 * 1e-9;
    println!(
        "  speed: {:.2} ms/image CPU, {:.1} MP/s (one core); wall {:.2} ms/image",
        1e3 * cpu / views as f64,
        mp * views as f64 / cpu,
        1e3 * seconds / views as f64
    );
    if opencv {
        std::fs::write(dir.join("truth.csv"), truth_csv).expect("write truth");
        let script = concat!(env!("CARGO_MANIFEST_DIR"), "/../bench/opencv_circles.py");
        let status = std::process::Command::new("python3")
            .arg(script)
            .arg(&dir)
            .status();
        match status {
            Ok(s) if s.success() => {}
            other => println!("  opencv comparison failed: {other:?}"),
        }
        let _ = std::fs::remove_dir_all(&dir);
    }
}
