//! Cost of `forward` with predicted σ (issue "Deploy the result"): 10,000
//! joint rows through `service::uncertainty::forward` and the JSON
//! serialisation of the answer, for an IRB 2400 camera set with a dense
//! covariance (its size and sparsity do not matter to the cost: every
//! layout entry is propagated). Prints rows per wall second and per CPU
//! second of the thread (`/proc/thread-self/schedstat`).
//!
//! ```text
//! cargo run --example forward_bench -- [ROWS]
//! ```

use nalgebra::DMatrix;
use robocal::service::evaluate::ForwardRequest;
use robocal::service::uncertainty::{forward, Uncertainty};
use robocal_calib::geometry::pose_from_xyz_rpy_deg;
use robocal_calib::kinematics::{presets, CalibratedModel, Instrument, ParamLayout};

/// CPU time of this thread (s); `None` off Linux.
fn thread_cpu_s() -> Option<f64> {
    let text = std::fs::read_to_string("/proc/thread-self/schedstat").ok()?;
    let ns: f64 = text.split_whitespace().next()?.parse().ok()?;
    Some(ns * 1e-9)
}

fn main() -> Result<(), String> {
    let rows: usize = std::env::args()
        .nth(1)
        .map_or(Ok(10_000), |a| a.parse())
        .map_err(|e| format!("ROWS: {e}"))?;
    let model = CalibratedModel {
        robot: presets::irb2400(),
        world_to_base: pose_from_xyz_rpy_deg([1500.0, 100.0, -300.0], [180.0, 0.0, 10.0])
            .map_err(|e| e.to_string())?,
        flange_to_tool: pose_from_xyz_rpy_deg([0.0, 60.0, 80.0], [0.0, 0.0, 90.0])
            .map_err(|e| e.to_string())?,
    };
    let layout = ParamLayout::new(&model.robot, Instrument::Camera);
    let n = layout.len();
    // A dense, well-conditioned covariance: A A^T / n + 1e-6 I.
    let a = DMatrix::from_fn(n, n, |i, j| ((i * 7 + j * 13) % 17) as f64 * 1e-3 - 8e-3);
    let covariance = &a * a.transpose() / n as f64 + DMatrix::identity(n, n) * 1e-6;
    let u = Uncertainty::from_covariance(layout, covariance)?;
    let joints_deg: Vec<Vec<f64>> = (0..rows)
        .map(|i| {
            let t = i as f64 / rows as f64;
            vec![
                20.0 * t,
                10.0 + 5.0 * t,
                -10.0 * t,
                30.0 * t,
                45.0 - 20.0 * t,
                90.0 * t,
            ]
        })
        .collect();
    let req = ForwardRequest {
        joints_deg,
        tool: None,
        session_id: None,
    };
    let model = robocal_calib::kinematics::term_model::TermModel::geometric(model);
    let (wall, cpu) = (std::time::Instant::now(), thread_cpu_s());
    let answer = forward(&model, Some(&u), &req).map_err(|e| format!("{e:?}"))?;
    let (t_fwd, c_fwd) = (wall.elapsed().as_secs_f64(), thread_cpu_s());
    let bytes = serde_json::to_vec(&answer).map_err(|e| e.to_string())?;
    let (t_all, c_all) = (wall.elapsed().as_secs_f64(), thread_cpu_s());
    let per_cpu = |c: Option<f64>| match (cpu, c) {
        (Some(a), Some(b)) if b > a => format!("{:.0} rows per CPU s", rows as f64 / (b - a)),
        _ => "CPU time unavailable".into(),
    };
    println!(
        "forward with σ, {rows} rows: {t_fwd:.3} s wall ({:.0} rows/s, {}); with the JSON answer ({:.1} MB): {t_all:.3} s ({})",
        rows as f64 / t_fwd,
        per_cpu(c_fwd),
        bytes.len() as f64 / 1e6,
        per_cpu(c_all),
    );
    Ok(())
}
