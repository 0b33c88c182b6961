//! Monte-Carlo of simulated camera-calibration campaigns (issue 4): refined
//! and paper mode against the truth, figures for BENCHMARKS.md ("Camera").
//!
//! `cargo run --release -p robocal-calib --example camera_campaign -- [seeds] [noise_px]`

use std::time::Instant;

use robocal_calib::camera::{
    calibrate, CalibrationMode, CalibrationOptions, CameraCalibration, ImageSize,
};
use robocal_calib::sim::campaign::CampaignSpec;
use robocal_calib::sim::point_views::{
    simulate_views, SimulatedView, ViewCampaignSpec, ViewLayout, LAYOUT_ROLL_SPREAD_DEG,
};

/// One campaign's errors against the truth.
struct Errors {
    fx_pct: f64,
    fy_pct: f64,
    cx_px: f64,
    cy_px: f64,
    rms_over_noise: f64,
    position_rms_ratio: f64,
    position_worst_ratio: f64,
    corrected_centre_px: f64,
    /// Reported (covariance) standard deviations of cx, cy.
    cx_sd_px: f64,
    cy_sd_px: f64,
    /// Mean board-image bounding box width over image width.
    board_span: f64,
    /// Fraction of a COVERAGE_CELLS^2 grid of the image touched by some dot.
    coverage: f64,
    /// Mean board-centre distance (mm).
    distance_mm: f64,
    seconds: f64,
}

/// Image grid for the coverage figure.
const COVERAGE_CELLS: usize = 10;

/// Design figures of a campaign: mean board span, image coverage, and
/// mean board-centre distance (mm).
fn design(spec: &ViewCampaignSpec, sims: &[SimulatedView]) -> (f64, f64, f64) {
    let b = &spec.board;
    let centre = nalgebra::Point3::new(
        0.5 * (b.cols - 1) as f64 * b.pitch_mm,
        0.5 * (b.rows - 1) as f64 * b.pitch_mm,
        0.0,
    );
    let distance = sims
        .iter()
        .map(|s| (s.camera_to_target * centre).coords.norm())
        .sum::<f64>()
        / sims.len() as f64;
    let (w, h) = (spec.image_size.width as f64, spec.image_size.height as f64);
    let mut hit = [[false; COVERAGE_CELLS]; COVERAGE_CELLS];
    let mut span = 0.0;
    for s in sims {
        let xs = s.observations.dots.iter().map(|d| d.pixel.x);
        let (lo, hi) = xs.fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), x| {
            (a.min(x), b.max(x))
        });
        span += (hi - lo) / w;
        for d in &s.observations.dots {
            let i = ((d.pixel.x / w * COVERAGE_CELLS as f64) as usize).min(COVERAGE_CELLS - 1);
            let j = ((d.pixel.y / h * COVERAGE_CELLS as f64) as usize).min(COVERAGE_CELLS - 1);
            hit[j][i] = true;
        }
    }
    let touched = hit.iter().flatten().filter(|&&b| b).count();
    (
        span / sims.len() as f64,
        touched as f64 / (COVERAGE_CELLS * COVERAGE_CELLS) as f64,
        distance,
    )
}

fn errors(
    spec: &ViewCampaignSpec,
    sims: &[SimulatedView],
    cal: &CameraCalibration,
    seconds: f64,
) -> Errors {
    let (t, c) = (&spec.intrinsics, &cal.intrinsics);
    let (mut pos_sq, mut dist, mut worst, mut centre_sq, mut n) = (0.0, 0.0, 0.0f64, 0.0, 0.0);
    for (s, v) in sims.iter().zip(&cal.views) {
        let truth = s.camera_to_target.inverse().translation.vector;
        let err = (v.pose.target_to_camera.translation.vector - truth).norm();
        pos_sq += err * err;
        dist += truth.norm();
        worst = worst.max(err / truth.norm());
        for (((p, q), o), centroid) in v
            .corrected_pixels
            .iter()
            .zip(&s.true_centre_images)
            .zip(&s.observations.dots)
            .zip(&s.true_centroids)
        {
            centre_sq += (p - (o.pixel - centroid) - q).norm_squared();
            n += 1.0;
        }
    }
    let k = sims.len() as f64;
    let sd = cal.std_dev.unwrap_or_default();
    let (board_span, coverage, distance_mm) = design(spec, sims);
    Errors {
        distance_mm,
        cx_sd_px: sd.cx,
        cy_sd_px: sd.cy,
        board_span,
        coverage,
        fx_pct: 100.0 * (c.fx - t.fx) / t.fx,
        fy_pct: 100.0 * (c.fy - t.fy) / t.fy,
        cx_px: c.cx - t.cx,
        cy_px: c.cy - t.cy,
        rms_over_noise: cal.rms_px / std::f64::consts::SQRT_2 / spec.noise_px,
        position_rms_ratio: (dist / k) / (pos_sq / k).sqrt(),
        position_worst_ratio: 1.0 / worst,
        corrected_centre_px: (centre_sq / n).sqrt(),
        seconds,
    }
}

fn summarise(label: &str, runs: &[Errors]) {
    let n = runs.len() as f64;
    let rms =
        |f: &dyn Fn(&Errors) -> f64| (runs.iter().map(|e| f(e).powi(2)).sum::<f64>() / n).sqrt();
    let max = |f: &dyn Fn(&Errors) -> f64| runs.iter().map(|e| f(e).abs()).fold(0.0, f64::max);
    let frac =
        |f: &dyn Fn(&Errors) -> bool| 100.0 * runs.iter().filter(|e| f(e)).count() as f64 / n;
    println!("{label} ({} campaigns)", runs.len());
    println!(
        "  fx err %  rms {:.5} max {:.5} | fy err % rms {:.5} max {:.5} | within 0.01%: {:.0}%",
        rms(&|e| e.fx_pct),
        max(&|e| e.fx_pct),
        rms(&|e| e.fy_pct),
        max(&|e| e.fy_pct),
        frac(&|e| e.fx_pct.abs() < 0.01 && e.fy_pct.abs() < 0.01)
    );
    println!("  cx err px rms {:.4} max {:.4} | cy err px rms {:.4} max {:.4} | both within 0.1 px: {:.0}%", rms(&|e| e.cx_px), max(&|e| e.cx_px), rms(&|e| e.cy_px), max(&|e| e.cy_px), frac(&|e| e.cx_px.abs() < 0.1 && e.cy_px.abs() < 0.1));
    println!(
        "  reported sd cx {:.4} cy {:.4} px (rms over campaigns) | board span {:.0}% of width, image coverage {:.0}%, mean distance {:.0} mm",
        rms(&|e| e.cx_sd_px),
        rms(&|e| e.cy_sd_px),
        100.0 * runs.iter().map(|e| e.board_span).sum::<f64>() / n,
        100.0 * runs.iter().map(|e| e.coverage).sum::<f64>() / n,
        runs.iter().map(|e| e.distance_mm).sum::<f64>() / n
    );
    println!(
        "  per-axis reprojection rms / noise: mean {:.3} max dev {:.3}",
        runs.iter().map(|e| e.rms_over_noise).sum::<f64>() / n,
        max(&|e| e.rms_over_noise - 1.0)
    );
    println!("  camera position: rms error 1:{:.0} (worst campaign 1:{:.0}), worst single view 1:{:.0} | rms within 1:15000: {:.0}%",
        runs.iter().map(|e| e.position_rms_ratio).sum::<f64>() / n,
        runs.iter().map(|e| e.position_rms_ratio).fold(f64::INFINITY, f64::min),
        runs.iter().map(|e| e.position_worst_ratio).fold(f64::INFINITY, f64::min),
        frac(&|e| e.position_rms_ratio > 15000.0));
    println!(
        "  bias-corrected centres vs true centre images: rms {:.2e} px (max campaign {:.2e})",
        rms(&|e| e.corrected_centre_px),
        max(&|e| e.corrected_centre_px)
    );
    println!(
        "  time per calibration: mean {:.3} s",
        runs.iter().map(|e| e.seconds).sum::<f64>() / n
    );
}

/// Campaign-design overrides from `key=value` arguments (the design study
/// of BENCHMARKS.md "Camera"): `board=ROWSxCOLS`, `pitch=MM`, `dot=MM`,
/// `layout=random|CXxCY` (stratified grid of image cells), `roll=DEG`
/// (after `layout=`: the stratified board's roll spread), `camera=1280|752|2048`
/// (one camera only; 2048 = the rendered campaign's camera, only on request), `paper=0` (skip paper mode).
#[derive(Default)]
struct Overrides {
    board: Option<(usize, usize)>,
    pitch_mm: Option<f64>,
    dot_mm: Option<f64>,
    layout: Option<ViewLayout>,
    camera: Option<String>,
    skip_paper: bool,
}

fn parse_pair<T: std::str::FromStr>(v: &str) -> Option<(T, T)> {
    let (a, b) = v.split_once('x')?;
    Some((a.parse().ok()?, b.parse().ok()?))
}

impl Overrides {
    fn parse(args: &[String]) -> Self {
        let mut o = Self::default();
        for a in args {
            let Some((k, v)) = a.split_once('=') else {
                panic!("expected key=value, got {a}");
            };
            match k {
                "board" => o.board = Some(parse_pair(v).expect("board=ROWSxCOLS")),
                "pitch" => o.pitch_mm = Some(v.parse().expect("pitch=MM")),
                "dot" => o.dot_mm = Some(v.parse().expect("dot=MM")),
                "layout" if v == "random" => o.layout = Some(ViewLayout::Random),
                "layout" => {
                    let (cells_x, cells_y) = parse_pair(v).expect("layout=random|CXxCY");
                    o.layout = Some(ViewLayout::Stratified {
                        cells_x,
                        cells_y,
                        roll_spread_deg: LAYOUT_ROLL_SPREAD_DEG,
                    });
                }
                "roll" => {
                    let spread = v.parse().expect("roll=DEG");
                    if let Some(ViewLayout::Stratified {
                        roll_spread_deg, ..
                    }) = o.layout.as_mut()
                    {
                        *roll_spread_deg = spread;
                    } else {
                        panic!("roll= needs a stratified layout= before it");
                    }
                }
                "camera" => o.camera = Some(v.to_string()),
                "paper" => o.skip_paper = v == "0",
                _ => panic!("unknown option {k}"),
            }
        }
        o
    }

    fn apply(&self, spec: &mut ViewCampaignSpec) {
        if let Some((rows, cols)) = self.board {
            spec.board.rows = rows;
            spec.board.cols = cols;
        }
        if let Some(p) = self.pitch_mm {
            spec.board.pitch_mm = p;
        }
        if let Some(d) = self.dot_mm {
            spec.board.dot_diameter_mm = d;
        }
        if let Some(l) = self.layout {
            spec.layout = l;
        }
    }
}

/// The camera of the rendered end-to-end campaign (`sim::campaign`,
/// `CampaignSpec::standard`: 12 mm lens, 3.45 um pixels, 0.1 px dot noise)
/// in this example's point-view campaign, for board-size comparisons.
fn rendered_campaign_camera(seed: u64) -> ViewCampaignSpec {
    let standard = CampaignSpec::standard("puma560", seed).expect("a preset");
    let size = ImageSize {
        width: standard.image_size.0,
        height: standard.image_size.1,
    };
    ViewCampaignSpec {
        noise_px: standard.pixel_sigma_px,
        ..ViewCampaignSpec::issue_campaign(standard.intrinsics, size, seed)
    }
}

fn main() {
    let args: Vec<String> = std::env::args().collect();
    let seeds: u64 = args.get(1).and_then(|s| s.parse().ok()).unwrap_or(10);
    let noise: Option<f64> = args.get(2).and_then(|s| s.parse().ok());
    let overrides = Overrides::parse(args.get(3..).unwrap_or(&[]));
    for (label, key, make) in [
        (
            "1280x1024, fy/fx = 1",
            "1280",
            ViewCampaignSpec::modern_1280x1024 as fn(u64) -> ViewCampaignSpec,
        ),
        (
            "752x582, fy/fx = 0.9825",
            "752",
            ViewCampaignSpec::paper_752x582,
        ),
        (
            "2048x1536 (rendered end-to-end campaign's camera, 0.1 px)",
            "2048",
            rendered_campaign_camera,
        ),
    ] {
        // The rendered campaign's camera only on request (camera=2048).
        let wanted = overrides
            .camera
            .as_deref()
            .map_or(key != "2048", |c| c == key);
        if !wanted {
            continue;
        }
        let (mut refined, mut paper) = (Vec::new(), Vec::new());
        for seed in 0..seeds {
            let mut spec = make(1000 + seed);
            overrides.apply(&mut spec);
            if let Some(sigma) = noise {
                spec.noise_px = sigma;
            }
            let sims = simulate_views(&spec).expect("simulation");
            let views: Vec<_> = sims.iter().map(|s| s.observations.clone()).collect();
            for (mode, out) in [
                (CalibrationMode::Refined, &mut refined),
                (CalibrationMode::Paper, &mut paper),
            ] {
                if mode == CalibrationMode::Paper && overrides.skip_paper {
                    continue;
                }
                let options = CalibrationOptions {
                    mode,
                    dot_diameter_mm: Some(spec.board.dot_diameter_mm),
                    ..Default::default()
                };
                let start = Instant::now();
                let cal = calibrate(&views, &options).expect("calibration");
                out.push(errors(&spec, &sims, &cal, start.elapsed().as_secs_f64()));
            }
        }
        let mut spec = make(0);
        overrides.apply(&mut spec);
        let b = spec.board;
        println!(
            "== {label}: 60 views, {} px noise, fx {}, board {}x{} dots at {} mm ({} mm dots), {:?}",
            noise.unwrap_or(spec.noise_px),
            spec.intrinsics.fx,
            b.rows,
            b.cols,
            b.pitch_mm,
            b.dot_diameter_mm,
            spec.layout
        );
        summarise("refined", &refined);
        if !paper.is_empty() {
            summarise("paper", &paper);
        }
    }
}
