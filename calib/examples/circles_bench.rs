//! Circle-grid benchmark (issue 14): renders views of OpenCV's asymmetric
//! circle grid (11 rows of 4, 20 mm pitch, 14 mm dots) and of a marker-less
//! symmetric grid (7 rows of 9, 25 mm pitch, 10 mm dots) in five kinds
//! (fronto, steep, partial, blurred, uneven light), writes them as PNGs with
//! `truth.csv` per board, detects them and prints, per board and kind: views
//! read with true identities (a marker-less grid: the reported reading or
//! one of its reported turns), dots found / visible, centre RMS and worst
//! error against the true centre projections, and CPU ms per image.
//! `bench/circles_opencv.py DIR` runs OpenCV's `findCirclesGrid` on the same
//! PNGs with the same truth.
//!
//! cargo run --release -p robocal-calib --example circles_bench -- [--views N] [--seed S] [--out DIR]

use std::fmt::Write as _;

use nalgebra::{Isometry3, Translation3, UnitQuaternion, Vector3};
use rand::{rngs::StdRng, Rng, SeedableRng};
use robocal_calib::sim::render::{RenderOptions, RenderedView};
use robocal_calib::sim::render_circles::render_circle_board;
use robocal_calib::sim::views::reference_camera;
use robocal_calib::vision::{
    detect_board, AsymmetricCirclesSpec, CircleBoard, DetectOptions, TargetSpec,
};

const WIDTH: usize = 1280;
const HEIGHT: usize = 1024;
/// A dot further than this from its truth has a wrong identity.
const WRONG_ID_PX: f64 = 1.0;
const KINDS: [&str; 5] = ["fronto", "steep", "partial", "blurred", "uneven"];
/// A partial view shows between these fractions of the dots.
const PARTIAL_FRACTION: (f64, f64) = (0.4, 0.95);
/// Attempts to draw a view of the wanted kind.
const MAX_ATTEMPTS: usize = 500;

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

fn boards() -> [(&'static str, CircleBoard); 2] {
    [
        (
            "asymmetric_4x11",
            CircleBoard::Asymmetric(AsymmetricCirclesSpec::opencv_4x11()),
        ),
        (
            "symmetric_9x7",
            CircleBoard::Dots(TargetSpec {
                rows: 7,
                cols: 9,
                pitch_mm: 25.0,
                dot_diameter_mm: 10.0,
                origin_marker_diameter_mm: None,
            }),
        ),
    ]
}

/// Board centre, mm.
fn centre_mm(board: &CircleBoard) -> (f64, f64) {
    let (mut x, mut y) = (0.0f64, 0.0f64);
    for r in 0..board.rows() {
        for c in 0..board.cols() {
            let m = board.dot_centre_mm(r, c);
            x = x.max(m[0]);
            y = y.max(m[1]);
        }
    }
    (0.5 * x, 0.5 * y)
}

/// A random view of the given kind: render and check the visible share.
fn view(kind: &str, board: &CircleBoard, rng: &mut StdRng) -> RenderedView {
    let base = RenderOptions {
        supersampling: 8,
        ..RenderOptions::default()
    };
    for _ in 0..MAX_ATTEMPTS {
        let (dist, tilt, shift, opts): (f64, f64, f64, RenderOptions) = match kind {
            "fronto" => (
                rng.random_range(550.0..800.0),
                rng.random_range(0.0..15.0),
                20.0,
                base,
            ),
            "steep" => (
                rng.random_range(550.0..750.0),
                rng.random_range(50.0..62.0),
                20.0,
                base,
            ),
            "partial" => (
                rng.random_range(400.0..600.0),
                rng.random_range(10.0..35.0),
                150.0,
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
        let (cx, cy) = centre_mm(board);
        let centre = Vector3::new(
            cx + rng.random_range(-shift..=shift),
            cy + rng.random_range(-shift..=shift),
            0.0,
        );
        let rot = UnitQuaternion::from_axis_angle(
            &Vector3::z_axis(),
            rng.random_range(0.0..360f64).to_radians(),
        ) * UnitQuaternion::from_axis_angle(&Vector3::x_axis(), tilt.to_radians());
        let iso = Isometry3::from_parts(Translation3::new(0.0, 0.0, dist), rot)
            * Translation3::from(-centre);
        let v = render_circle_board(&reference_camera(), &iso, board, WIDTH, HEIGHT, &opts, rng)
            .expect("render");
        let share = v.truth.iter().filter(|t| t.visible).count() as f64 / v.truth.len() as f64;
        let wanted = if kind == "partial" {
            (PARTIAL_FRACTION.0..=PARTIAL_FRACTION.1).contains(&share)
        } else {
            share == 1.0
        };
        if wanted {
            return v;
        }
    }
    panic!("no {kind} view after {MAX_ATTEMPTS} attempts");
}

fn main() {
    let views: usize = arg("--views", 10);
    let seed: u64 = arg("--seed", 14);
    let out: String = arg("--out", "/tmp/circles_bench".to_string());
    println!("robocal circle grids, {WIDTH}x{HEIGHT}, {views} views per kind, seed {seed}");
    for (name, board) in boards() {
        let dir = format!("{out}/{name}");
        std::fs::create_dir_all(&dir).expect("output dir");
        let mut rng = StdRng::seed_from_u64(seed);
        let mut csv = String::from("image,row,col,x,y,visible\n");
        println!("{name}");
        for kind in KINDS {
            let (mut read, mut wrong, mut found, mut visible) = (0, 0, 0, 0);
            let (mut sum2, mut worst, mut cpu_ns) = (0.0, 0.0f64, 0u64);
            for k in 0..views {
                let v = view(kind, &board, &mut rng);
                let file = format!("{kind}_{k:03}.png");
                v.image
                    .to_luma8()
                    .save(format!("{dir}/{file}"))
                    .expect("write png");
                for t in &v.truth {
                    let _ = writeln!(
                        csv,
                        "{file},{},{},{:.6},{:.6},{}",
                        t.row,
                        t.col,
                        t.x,
                        t.y,
                        u8::from(t.visible)
                    );
                }
                visible += v.truth.iter().filter(|t| t.visible).count();
                let t0 = thread_cpu_ns();
                let det = detect_board(&v.image, &board, &DetectOptions::default());
                cpu_ns += thread_cpu_ns() - t0;
                let Ok(det) = det else { continue };
                // The reported reading or one of its reported turns.
                let best = std::iter::once(0)
                    .chain(det.equivalent_turns.iter().copied())
                    .map(|turn| {
                        det.dots
                            .iter()
                            .map(|d| {
                                let (r, c) = if turn == 0 {
                                    (d.row, d.col)
                                } else {
                                    board.turned(turn, d.row, d.col).expect("a board symmetry")
                                };
                                let t = v.truth[r * board.cols() + c];
                                (d.x - t.x).hypot(d.y - t.y)
                            })
                            .collect::<Vec<f64>>()
                    })
                    .min_by(|a, b| {
                        let m = |e: &Vec<f64>| e.iter().copied().fold(0.0, f64::max);
                        m(a).total_cmp(&m(b))
                    })
                    .expect("one reading");
                if best.iter().any(|&e| e > WRONG_ID_PX) {
                    wrong += 1;
                    continue;
                }
                read += 1;
                found += best.len();
                sum2 += best.iter().map(|e| e * e).sum::<f64>();
                worst = best.iter().copied().fold(worst, f64::max);
            }
            println!(
                "  {kind:8} views {read}/{views}, wrong {wrong}, dots {found}/{visible}, RMS {:.4} px, worst {:.4} px, {:.1} ms/image (CPU)",
                (sum2 / found.max(1) as f64).sqrt(),
                worst,
                cpu_ns as f64 / 1e6 / views as f64
            );
        }
        std::fs::write(format!("{dir}/truth.csv"), csv).expect("write truth");
    }
    println!("images + truth.csv in {out}/<board>; OpenCV: python3 bench/circles_opencv.py {out}");
}
