//! Predicted uncertainty (issue "Deploy the result"): after calibrations
//! of simulated campaigns through the service, `forward`'s predicted σ are
//! honest against the simulator's truth. The true error is the served
//! camera pose against the true robot's (compliance included) at the same
//! recorded joints: what the model gets wrong, not the encoders'
//! repeatability. The `uncertainty-map` answers the same σ at the same
//! joints, solves a box by IK and names unreachable points.
//!
//! What is checked, and why (docs/decisions/0015-predicted-sigma.md): the
//! validation poses of one campaign share ONE draw of the parameter
//! error, so the per-pose RMS(error/σ) of one campaign spreads
//! from about 0.2 to 2 even with an exact σ (over 20 rendered campaigns
//! per preset, `examples/sigma_pipeline.rs`, the pooled ratio is 0.92-1.10).
//! Two campaigns cannot pin that ratio. The served covariance can be
//! pinned by the same errors: the Mahalanobis form `e^T C^+ e` of all the
//! validation poses' 6-D errors stacked, `C = J Σ J^T` with the set's
//! stored covariance `Σ`, is χ² with rank(C) (30 per campaign here)
//! degrees of freedom when `Σ` is right. Over the two campaigns (60) its
//! mean per degree of freedom lies in [0.50, 1.71] with probability 0.999;
//! a σ off by a factor of 2 either way gives about 0.25 or 4. `forward`'s
//! σ is then checked to be `sqrt(trace)` of `C`'s blocks, so what it
//! serves is what was tested. The per-pose ratio is printed: with these
//! two campaigns 0.41 (position) and 0.30 (rotation), while
//! `e^T C^+ e / rank` is 0.81 and 1.53.

use nalgebra::{DMatrix, DVector, Vector6};
use robocal::domain::ParameterSet;
use robocal_calib::geometry::{pose_error, pose_from_matrix_rows, Pose};
use robocal_calib::kinematics::jacobian::tool_pose_jacobian;
use robocal_calib::kinematics::{CalibratedModel, Instrument, ParamLayout};
use robocal_calib::sim::campaign::compliance;
use robocal_calib::sim::campaign_io::{PoseEntry, PoseSet, Truth};
use serde_json::{json, Value};

use crate::support::{spawn_app_with, upload_and_calibrate, TestApp};

/// `e^T C^+ e / rank(C)` pooled over the campaigns (see the module doc).
const HONEST_PER_DOF: std::ops::RangeInclusive<f64> = 0.5..=2.0;
/// Eigenvalues of `C` below this fraction of the largest are directions
/// the calibration does not move (rounding), left out of `C^+`.
const RANK_TOLERANCE: f64 = 1e-10;
/// Rotation rows are scaled by this lever (mm per rad) so that `C`'s
/// eigenvalues in mm² and rad² share one scale; the form is unchanged.
const LEVER_MM: f64 = 1000.0;
/// Campaigns: (preset, calibration poses, validation poses, seed).
const CAMPAIGNS: [(&str, usize, usize, u64); 2] = [("irb2400", 24, 16, 5), ("puma560", 24, 16, 6)];

fn matrix_pose(v: &Value) -> Pose {
    pose_from_matrix_rows(&serde_json::from_value(v["matrix"].clone()).unwrap()).unwrap()
}

/// One campaign's validation poses: the issue's `(position, rotation)`
/// ratios squared and summed, the count, and `e^T C^+ e` with rank(C).
struct Honesty {
    position: f64,
    rotation: f64,
    poses: usize,
    mahalanobis: f64,
    rank: usize,
}

/// The served set's model and stored covariance (internal units), read
/// back through the API.
async fn served_set(app: &TestApp, base: &str) -> (CalibratedModel, DMatrix<f64>) {
    let mut served: Value = app.get(base).await.json().await.unwrap();
    for outer in ["serial", "version", "job_id", "created_at"] {
        served.as_object_mut().unwrap().remove(outer);
    }
    let set: ParameterSet = serde_json::from_value(served).unwrap();
    (
        set.model().unwrap(),
        set.covariance_matrix().unwrap().unwrap(),
    )
}

/// `e^T C^+ e` and rank(C) of the stacked 6-D errors `errors` at joints
/// `joints_rad`, `C = J Σ J^T`; checks on the way that `forward`'s σ of each
/// row are `sqrt(trace)` of its blocks.
fn mahalanobis(
    model: &CalibratedModel,
    covariance: &DMatrix<f64>,
    joints_rad: &[Vec<f64>],
    errors: &[Vector6<f64>],
    served_std: &[(f64, f64)],
) -> (f64, usize) {
    let layout = ParamLayout::new(&model.robot, Instrument::Camera);
    let m = joints_rad.len();
    let mut jac = DMatrix::zeros(6 * m, layout.len());
    let mut e = DVector::zeros(6 * m);
    for (k, q) in joints_rad.iter().enumerate() {
        let (_, j) = tool_pose_jacobian(&layout, model, q).unwrap();
        jac.view_mut((6 * k, 0), (6, layout.len())).copy_from(&j);
        e.rows_mut(6 * k, 6).copy_from(&errors[k]);
        let block = &j * covariance * j.transpose();
        let (p, r) = (
            block.view((0, 0), (3, 3)).trace().sqrt(),
            block.view((3, 3), (3, 3)).trace().sqrt().to_degrees(),
        );
        let (sp, sr) = served_std[k];
        assert!(
            (p - sp).abs() <= 1e-9 * sp,
            "row {k}: σ {sp} mm served, {p} from C"
        );
        assert!(
            (r - sr).abs() <= 1e-9 * sr,
            "row {k}: σ {sr} deg served, {r} from C"
        );
    }
    for k in 0..m {
        jac.view_mut((6 * k + 3, 0), (3, layout.len()))
            .scale_mut(LEVER_MM);
        e.rows_mut(6 * k + 3, 3).scale_mut(LEVER_MM);
    }
    let c = &jac * covariance * jac.transpose();
    let eigen = c.symmetric_eigen();
    let largest = eigen.eigenvalues.max();
    let (mut form, mut rank) = (0.0, 0);
    for (i, &l) in eigen.eigenvalues.iter().enumerate() {
        if l > RANK_TOLERANCE * largest {
            form += eigen.eigenvectors.column(i).dot(&e).powi(2) / l;
            rank += 1;
        }
    }
    (form, rank)
}

/// One campaign through the service; checks the map on the way.
async fn one_campaign(app: &TestApp, preset: &str, cal: usize, val: usize, seed: u64) -> Honesty {
    let dir = tempfile::tempdir().unwrap();
    robocal::cli::campaign::simulate(preset, dir.path(), cal, val, seed).unwrap();
    let serial = format!("SIGMA-{preset}");
    upload_and_calibrate(app, &serial, dir.path()).await;
    let read = |name: &str| std::fs::read_to_string(dir.path().join(name)).unwrap();
    let truth: Truth = serde_json::from_str(&read("truth.json")).unwrap();
    let entries: Vec<PoseEntry> = serde_json::from_str(&read("poses.json")).unwrap();
    let true_model = truth.model().unwrap();
    let joints_deg: Vec<Vec<f64>> = entries
        .iter()
        .filter(|e| e.set == PoseSet::Val)
        .map(|e| e.joints_deg.clone())
        .collect();
    assert_eq!(joints_deg.len(), val);
    let base = format!("/v1/robots/{serial}/parameter-sets/latest");
    let r = app
        .post_json(
            &format!("{base}/forward"),
            &json!({ "joints_deg": joints_deg }),
        )
        .await;
    assert_eq!(r.status(), 200);
    let forward: Value = r.json().await.unwrap();
    let (mut pos, mut rot) = (0.0, 0.0);
    let (mut joints_rad, mut pose_errors, mut served_std) = (Vec::new(), Vec::new(), Vec::new());
    for (row, deg) in joints_deg.iter().enumerate() {
        let served = &forward["poses"][row];
        let q: Vec<f64> = deg.iter().map(|d| d.to_radians()).collect();
        let bent = compliance(&true_model.robot, &q, truth.compliance_rad_per_m);
        let truth_pose = true_model.world_to_tool(&bent).unwrap();
        let e = pose_error(&truth_pose, &matrix_pose(&served["camera_in_target"]));
        let sigma_mm = served["position_std_mm"].as_f64().unwrap();
        let sigma_rad = served["rotation_std_deg"].as_f64().unwrap().to_radians();
        assert!(sigma_mm > 0.0 && sigma_rad > 0.0, "{served}");
        assert!(served["flange_position_std_mm"].as_f64().unwrap() > 0.0);
        joints_rad.push(q);
        pose_errors.push(e);
        served_std.push((sigma_mm, served["rotation_std_deg"].as_f64().unwrap()));
        pos += (e.rows(0, 3).norm() / sigma_mm).powi(2);
        rot += (e.rows(3, 3).norm() / sigma_rad).powi(2);
        eprintln!(
            "{preset} val {row}: error {:.4} mm, σ {sigma_mm:.4} mm; {:.2e} rad, σ {sigma_rad:.2e}",
            e.rows(0, 3).norm(),
            e.rows(3, 3).norm()
        );
    }

    // The map at the same joints answers the same σ.
    let r = app
        .post_json(
            &format!("{base}/uncertainty-map"),
            &json!({ "joints_deg": joints_deg }),
        )
        .await;
    assert_eq!(r.status(), 200);
    let map: Value = r.json().await.unwrap();
    for row in 0..joints_deg.len() {
        let (a, b) = (
            map["points"][row]["position_std_mm"].as_f64().unwrap(),
            forward["poses"][row]["position_std_mm"].as_f64().unwrap(),
        );
        assert!((a - b).abs() <= 1e-12 * b, "row {row}: {a} vs {b}");
    }
    // A box around the first validation flange, and a point far out.
    let flange = matrix_pose(&forward["poses"][0]["flange_in_base"]);
    let p = flange.translation.vector;
    let rotation = robocal_calib::geometry::PoseXyzRpy::from_pose(&flange).rotation_deg;
    let step = 20.0;
    let body = json!({
        "box": {"min_mm": [p.x - step, p.y - step, p.z], "max_mm": [p.x + step, p.y + step, p.z],
                "step_mm": step},
        "rotation_deg": rotation,
        "seed_joints_deg": joints_deg[0],
    });
    let r = app
        .post_json(&format!("{base}/uncertainty-map"), &body)
        .await;
    assert_eq!(r.status(), 200);
    let map: Value = r.json().await.unwrap();
    assert_eq!(map["points"].as_array().unwrap().len(), 9, "{map}");
    // A corner of the box may need joints past the limits: that point is a
    // per-point error naming its index, never a failed request.
    let errors = map["errors"].as_array().unwrap();
    assert!(errors.len() <= 4, "{map}");
    for e in errors {
        let i = e["index"].as_u64().unwrap() as usize;
        assert_ne!(i, 4, "the centre is reachable: {map}");
        assert!(map["points"][i].is_null(), "{map}");
        assert!(e["message"].as_str().unwrap().contains("limits"), "{map}");
    }
    let centre = &map["points"][4];
    let reached: Vec<f64> = serde_json::from_value(centre["flange_position_mm"].clone()).unwrap();
    assert!(
        (reached[0] - p.x).abs() < 1e-3 && (reached[2] - p.z).abs() < 1e-3,
        "{centre}"
    );
    let far = json!({
        "box": {"min_mm": [p.x, p.y, p.z], "max_mm": [p.x + 9000.0, p.y, p.z], "step_mm": 9000.0},
        "rotation_deg": rotation,
    });
    let map: Value = app
        .post_json(&format!("{base}/uncertainty-map"), &far)
        .await
        .json()
        .await
        .unwrap();
    assert_eq!(map["errors"][0]["index"], 1, "{map}");
    assert!(map["points"][1].is_null());
    let (model, covariance) = served_set(app, &base).await;
    let (mahalanobis, rank) =
        mahalanobis(&model, &covariance, &joints_rad, &pose_errors, &served_std);
    Honesty {
        position: pos,
        rotation: rot,
        poses: joints_deg.len(),
        mahalanobis,
        rank,
    }
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn predicted_sigma_is_honest_on_simulated_campaigns() {
    let app = spawn_app_with(|c| c.test_validate_only = false).await;
    let (mut pos, mut rot, mut n, mut form, mut dof) = (0.0, 0.0, 0, 0.0, 0);
    for (preset, cal, val, seed) in CAMPAIGNS {
        let h = one_campaign(&app, preset, cal, val, seed).await;
        eprintln!(
            "{preset}: RMS(error/σ) position {:.3}, rotation {:.3}; e^T C^+ e / rank {:.3} (rank {})",
            (h.position / h.poses as f64).sqrt(),
            (h.rotation / h.poses as f64).sqrt(),
            h.mahalanobis / h.rank as f64,
            h.rank
        );
        pos += h.position;
        rot += h.rotation;
        n += h.poses;
        form += h.mahalanobis;
        dof += h.rank;
    }
    let (pos, rot) = ((pos / n as f64).sqrt(), (rot / n as f64).sqrt());
    let per_dof = form / dof as f64;
    eprintln!(
        "all: RMS(error/σ) position {pos:.3}, rotation {rot:.3} over {n} poses; \
         e^T C^+ e / rank {per_dof:.3} over {dof} degrees of freedom"
    );
    // Each campaign moves the tool in every identified direction.
    assert!(dof >= 40, "rank {dof}");
    assert!(
        HONEST_PER_DOF.contains(&per_dof),
        "e^T C^+ e / rank {per_dof}"
    );
    app.shutdown().await;
}
