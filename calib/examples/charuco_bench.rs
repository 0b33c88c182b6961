//! ChArUco benchmark (issue 14): renders views of a 9x7 DICT_5X5_100 board
//! (30 mm squares, 22 mm markers) in five kinds (fronto, steep, partial,
//! blurred, uneven light), writes them as PNGs with `truth.csv`, detects the
//! inner corners and prints, per kind, corners found / visible, RMS and
//! worst error against the true corner projections, and CPU ms per image.
//! `bench/charuco_opencv.py DIR` runs OpenCV's CharucoDetector on the same
//! PNGs with the same truth.
//!
//! The detector reads the 8-bit image as written (what OpenCV is given);
//! `--from DIR` decodes an earlier run's PNGs and truth instead of rendering,
//! `--kind K` keeps one kind (with `--from`: `bench/charuco_interleaved.sh`).
//!
//! cargo run --release -p robocal-calib --example charuco_bench -- [--views N] [--seed S] [--out DIR] [--from DIR] [--kind K]

#[path = "support/bench_pngs.rs"]
mod bench_pngs;

use bench_pngs::{read_truth, Views, TRUTH_HEADER};
use nalgebra::{Isometry3, Translation3, UnitQuaternion, Vector3};
use rand::{rngs::StdRng, Rng, SeedableRng};
use robocal_calib::sim::render::RenderOptions;
use robocal_calib::sim::render_charuco::render_charuco;
use robocal_calib::sim::views::reference_camera;
use robocal_calib::vision::charuco::{detect_charuco, CharucoSpec};

const WIDTH: usize = 1280;
const HEIGHT: usize = 1024;
/// A corner further than this from its truth has a wrong identity.
const WRONG_ID_PX: f64 = 3.0;
const KINDS: [&str; 5] = ["fronto", "steep", "partial", "blurred", "uneven"];

fn arg<T: std::str::FromStr>(name: &str, default: T) -> T {
    let args: Vec<String> = std::env::args().collect();
    args.iter()
        .position(|a| a == name)
        .and_then(|i| args.get(i + 1))
        .and_then(|v| v.parse().ok())
        .unwrap_or(default)
}

/// CPU time of the calling thread, ns (the machine is shared).
fn thread_cpu_ns() -> u64 {
    std::fs::read_to_string("/proc/thread-self/schedstat")
        .ok()
        .and_then(|s| s.split_whitespace().next()?.parse().ok())
        .unwrap_or(0)
}

fn board() -> CharucoSpec {
    CharucoSpec {
        squares: [9, 7],
        square_mm: 30.0,
        marker_mm: 22.0,
        dictionary: "DICT_5X5_100".into(),
        legacy_layout: false,
    }
}

/// A random pose of the given kind and its render options.
fn view(kind: &str, rng: &mut StdRng) -> (Isometry3<f64>, RenderOptions) {
    let spec = board();
    let base = RenderOptions {
        supersampling: 8,
        board_margin_mm: 15.0,
        ..RenderOptions::default()
    };
    let (dist, tilt, shift, opts): (f64, f64, f64, RenderOptions) = match kind {
        "fronto" => (
            rng.random_range(550.0..750.0),
            rng.random_range(0.0..15.0),
            20.0,
            base,
        ),
        "steep" => (
            rng.random_range(550.0..700.0),
            rng.random_range(50.0..62.0),
            20.0,
            base,
        ),
        "partial" => (
            rng.random_range(450.0..600.0),
            rng.random_range(10.0..35.0),
            120.0,
            base,
        ),
        "blurred" => (
            rng.random_range(600.0..800.0),
            rng.random_range(20.0..45.0),
            20.0,
            RenderOptions {
                blur_sigma_px: 2.0,
                noise_sigma_grey: 3.0,
                ..base
            },
        ),
        _ => (
            rng.random_range(600.0..800.0),
            rng.random_range(20.0..45.0),
            20.0,
            RenderOptions {
                vignetting: 0.65,
                ..base
            },
        ),
    };
    let centre = Vector3::new(
        0.5 * spec.cols() as f64 * spec.square_mm + rng.random_range(-shift..=shift),
        0.5 * spec.rows() as f64 * spec.square_mm + rng.random_range(-shift..=shift),
        0.0,
    );
    let rot = UnitQuaternion::from_axis_angle(
        &Vector3::z_axis(),
        rng.random_range(0.0..360f64).to_radians(),
    ) * UnitQuaternion::from_axis_angle(&Vector3::x_axis(), tilt.to_radians());
    let iso =
        Isometry3::from_parts(Translation3::new(0.0, 0.0, dist), rot) * Translation3::from(-centre);
    (iso, opts)
}

fn main() {
    let views: usize = arg("--views", 8);
    let seed: u64 = arg("--seed", 14);
    let out: String = arg("--out", "/tmp/charuco_bench".to_string());
    let from = Some(arg("--from", String::new())).filter(|d| !d.is_empty());
    let only: String = arg("--kind", String::new());
    let truth_of = from.as_deref().map(read_truth);
    let mut csv = String::from(TRUTH_HEADER);
    let mut source = match (&from, &truth_of) {
        (Some(dir), Some(truth)) => Views::Read { dir, truth },
        _ => Views::Render {
            out: &out,
            csv: &mut csv,
        },
    };
    if from.is_none() {
        std::fs::create_dir_all(&out).expect("output dir");
    }
    let spec = board();
    let mut rng = StdRng::seed_from_u64(seed);
    println!(
        "robocal ChArUco 9x7 DICT_5X5_100, {WIDTH}x{HEIGHT}, {views} views per kind, seed {seed}"
    );
    for kind in KINDS.into_iter().filter(|k| only.is_empty() || *k == only) {
        let (mut found, mut visible, mut wrong, mut sum2, mut worst, mut cpu_ns) =
            (0, 0, 0, 0.0, 0.0f64, 0u64);
        for k in 0..views {
            let name = format!("{kind}_{k:03}.png");
            let (image, truth) = source.get(&name, || {
                let (iso, opts) = view(kind, &mut rng);
                let v = render_charuco(
                    &reference_camera(),
                    &iso,
                    &spec,
                    WIDTH,
                    HEIGHT,
                    &opts,
                    &mut rng,
                )
                .expect("render");
                (v.image, v.truth)
            });
            visible += truth.iter().filter(|t| t.visible).count();
            let t0 = thread_cpu_ns();
            let det = detect_charuco(&image, &spec);
            cpu_ns += thread_cpu_ns() - t0;
            let Ok(det) = det else { continue };
            for p in &det.points {
                let t = truth[p.row * (spec.cols() - 1) + p.col];
                let e = (p.x_px - t.x).hypot(p.y_px - t.y);
                if e > WRONG_ID_PX {
                    wrong += 1;
                    continue;
                }
                found += 1;
                sum2 += e * e;
                worst = worst.max(e);
            }
        }
        println!(
            "{kind:8} corners {found}/{visible} ({:.1} %), wrong {wrong}, RMS {:.3} px, worst {:.3} px, {:.1} ms/image (CPU)",
            100.0 * found as f64 / visible.max(1) as f64,
            (sum2 / found.max(1) as f64).sqrt(),
            worst,
            cpu_ns as f64 / 1e6 / views as f64
        );
    }
    if from.is_some() {
        return;
    }
    std::fs::write(format!("{out}/truth.csv"), csv).expect("write truth");
    println!("images + truth.csv in {out}; OpenCV: python3 bench/charuco_opencv.py {out}");
}
