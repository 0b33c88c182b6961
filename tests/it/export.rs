//! Exports of a parameter set (issue "Deploy the result"): the URDF, read
//! by an independent parser below, reproduces `forward` at random joints to
//! 1e-6 mm (Hayati links included); `dh-json` and CSV carry the identified
//! table with σ and the reasons for held parameters.

use std::collections::HashMap;

use nalgebra::{Isometry3, Translation3, UnitQuaternion, Vector3};
use rand::{rngs::StdRng, Rng, SeedableRng};
use serde_json::{json, Value};

use crate::support::{run_binary, spawn_app_with, upload_and_calibrate, TestApp};

/// `forward` against the URDF's chain, mm and rad.
const MAX_POSITION_MM: f64 = 1e-6;
const MAX_ROTATION_RAD: f64 = 1e-9;
const RANDOM_JOINTS: usize = 20;

/// One `<joint>` of a URDF, as a minimal reader sees it.
#[derive(Debug)]
struct UrdfJoint {
    kind: String,
    parent: String,
    child: String,
    origin: Isometry3<f64>,
    axis: Vector3<f64>,
    limits_rad: Option<(f64, f64)>,
}

fn attr(element: &str, name: &str) -> Option<String> {
    let at = element.find(&format!(" {name}=\""))? + name.len() + 3;
    let end = element[at..].find('"')? + at;
    Some(element[at..end].to_string())
}

fn numbers(text: &str) -> Vec<f64> {
    text.split_whitespace()
        .map(|v| v.parse().unwrap())
        .collect()
}

fn element<'a>(block: &'a str, tag: &str) -> Option<&'a str> {
    let at = block.find(&format!("<{tag} "))?;
    let end = block[at..].find("/>")? + at;
    Some(&block[at..end])
}

/// Joints by child link name, read without any URDF library.
fn read_urdf(text: &str) -> HashMap<String, UrdfJoint> {
    let mut joints = HashMap::new();
    for block in text.split("<joint ").skip(1) {
        let block = &block[..block.find("</joint>").unwrap()];
        let head = format!(" {}", &block[..block.find('>').unwrap()]);
        let origin = element(block, "origin").unwrap();
        let xyz = numbers(&attr(origin, "xyz").unwrap());
        let rpy = numbers(&attr(origin, "rpy").unwrap());
        let rotation = UnitQuaternion::from_euler_angles(rpy[0], rpy[1], rpy[2]);
        let joint = UrdfJoint {
            kind: attr(&head, "type").unwrap(),
            parent: attr(element(block, "parent").unwrap(), "link").unwrap(),
            child: attr(element(block, "child").unwrap(), "link").unwrap(),
            origin: Isometry3::from_parts(
                Translation3::new(xyz[0] * 1e3, xyz[1] * 1e3, xyz[2] * 1e3),
                rotation,
            ),
            axis: element(block, "axis")
                .map(|a| Vector3::from_vec(numbers(&attr(a, "xyz").unwrap())))
                .unwrap_or_else(Vector3::z),
            limits_rad: element(block, "limit").map(|l| {
                (
                    attr(l, "lower").unwrap().parse().unwrap(),
                    attr(l, "upper").unwrap().parse().unwrap(),
                )
            }),
        };
        joints.insert(joint.child.clone(), joint);
    }
    joints
}

/// `base_link`-to-`link` pose (mm) with the revolute joints at `q_rad` in order.
fn chain_pose(joints: &HashMap<String, UrdfJoint>, link: &str, q_rad: &[f64]) -> Isometry3<f64> {
    let mut pose = Isometry3::identity();
    let mut at = link.to_string();
    while let Some(j) = joints.get(&at) {
        let motion = if j.kind == "revolute" {
            let n: usize = j.child.trim_start_matches("link_").parse().unwrap();
            let axis = nalgebra::Unit::new_normalize(j.axis);
            Isometry3::from_parts(
                Translation3::identity(),
                UnitQuaternion::from_axis_angle(&axis, q_rad[n - 1]),
            )
        } else {
            Isometry3::identity()
        };
        pose = j.origin * motion * pose;
        at = j.parent.clone();
    }
    assert_eq!(at, "base_link");
    pose
}

async fn calibrated(app: &TestApp, serial: &str) {
    let dir = tempfile::tempdir().unwrap();
    robocal::cli::campaign::simulate("irb2400", dir.path(), 20, 6, 31).unwrap();
    upload_and_calibrate(app, serial, dir.path()).await;
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn exports_reproduce_forward_and_carry_the_table() {
    let app = spawn_app_with(|c| c.test_validate_only = false).await;
    let serial = "EXP-1";
    calibrated(&app, serial).await;
    let base = format!("/v1/robots/{serial}/parameter-sets/latest");

    let r = app.get(&format!("{base}/export?format=urdf")).await;
    assert_eq!(r.status(), 200);
    assert_eq!(r.headers()["content-type"], "application/xml");
    let text = r.text().await.unwrap();
    // The CLI writes the same document.
    let cli = tokio::task::spawn_blocking({
        let url = app.base.clone();
        move || {
            run_binary(&[
                "export", "--serial", "EXP-1", "--format", "urdf", "--url", &url,
            ])
        }
    })
    .await
    .unwrap();
    assert!(
        cli.status.success(),
        "{}",
        String::from_utf8_lossy(&cli.stderr)
    );
    assert_eq!(String::from_utf8(cli.stdout).unwrap(), text);
    let urdf = read_urdf(&text);
    let limits: Vec<(f64, f64)> = (1..=6)
        .map(|n| urdf[&format!("link_{n}")].limits_rad.unwrap())
        .collect();
    let mut rng = StdRng::seed_from_u64(7);
    let joints_rad: Vec<Vec<f64>> = (0..RANDOM_JOINTS)
        .map(|_| {
            limits
                .iter()
                .map(|&(lo, hi)| rng.random_range(lo..hi))
                .collect()
        })
        .collect();
    let joints_deg: Vec<Vec<f64>> = joints_rad
        .iter()
        .map(|q| q.iter().map(|v| v.to_degrees()).collect())
        .collect();
    let forward: Value = app
        .post_json(
            &format!("{base}/forward"),
            &json!({ "joints_deg": joints_deg }),
        )
        .await
        .json()
        .await
        .unwrap();
    for (row, q) in joints_rad.iter().enumerate() {
        let base_to_camera = chain_pose(&urdf, "camera", q);
        let base_to_target = chain_pose(&urdf, "target", q);
        let urdf_pose = base_to_target.inverse() * base_to_camera;
        let m = &forward["poses"][row]["camera_in_target"]["matrix"];
        let served = robocal_calib::geometry::pose_from_matrix_rows(
            &serde_json::from_value(m.clone()).unwrap(),
        )
        .unwrap();
        let dt = (urdf_pose.translation.vector - served.translation.vector).norm();
        let dr = urdf_pose.rotation.angle_to(&served.rotation);
        assert!(dt < MAX_POSITION_MM, "row {row}: {dt} mm");
        assert!(dr < MAX_ROTATION_RAD, "row {row}: {dr} rad");
    }

    let r = app.get(&format!("{base}/export?format=dh-json")).await;
    assert_eq!(r.status(), 200);
    let table: Value = r.json().await.unwrap();
    let rows = table["joints"].as_array().unwrap();
    assert_eq!(rows.len(), 6);
    assert!(rows.iter().any(|j| j["convention"] == "hayati"), "{table}");
    let params = table["parameters"].as_array().unwrap();
    let free_with_sigma = params
        .iter()
        .filter(|p| p["held"] == false && p["std"].as_f64().unwrap() > 0.0)
        .count();
    assert!(
        free_with_sigma > 20,
        "{free_with_sigma} free parameters with σ"
    );
    for p in params.iter().filter(|p| p["held"] == true) {
        assert!(p["held_because"].as_str().unwrap().len() > 20, "{p}");
    }
    // The full covariance: every identified parameter, its diagonal the
    // rows' σ, symmetric, with correlations.
    let cov = &table["covariance"];
    let names: Vec<&str> = cov["names"]
        .as_array()
        .unwrap()
        .iter()
        .map(|n| n.as_str().unwrap())
        .collect();
    assert_eq!(
        names.len(),
        params.iter().filter(|p| p["held"] == false).count()
    );
    let matrix: Vec<Vec<f64>> = serde_json::from_value(cov["matrix"].clone()).unwrap();
    assert_eq!(matrix.len(), names.len());
    for (i, name) in names.iter().enumerate() {
        let row = params.iter().find(|p| p["name"] == *name).unwrap();
        let sd = row["std"].as_f64().unwrap();
        assert!(
            (matrix[i][i].sqrt() - sd).abs() <= 1e-7 * sd,
            "{name}: sqrt(cov) {} vs std {sd}",
            matrix[i][i].sqrt()
        );
        assert_eq!(cov["units"][i], row["unit"], "{name}");
        for j in 0..names.len() {
            assert!((matrix[i][j] - matrix[j][i]).abs() <= 1e-12 * matrix[i][i].max(matrix[j][j]));
        }
    }
    let correlated = (0..names.len())
        .flat_map(|i| (0..i).map(move |j| (i, j)))
        .filter(|&(i, j)| matrix[i][j].abs() > 0.1 * (matrix[i][i] * matrix[j][j]).sqrt())
        .count();
    assert!(correlated > 0, "no correlation above 0.1");

    let r = app.get(&format!("{base}/export?format=csv")).await;
    assert_eq!(r.status(), 200);
    assert_eq!(r.headers()["content-type"], "text/csv");
    let csv = r.text().await.unwrap();
    let lines: Vec<&str> = csv.lines().collect();
    assert_eq!(lines.len(), 7);
    assert!(lines[0].starts_with("joint,convention,a_mm,a_mm_std,alpha_deg"));
    let a2: f64 = lines[2].split(',').nth(2).unwrap().parse().unwrap();
    assert_eq!(a2, rows[1]["a_mm"].as_f64().unwrap());

    let r = app.get(&format!("{base}/export?format=step")).await;
    assert_eq!(r.status(), 422);
    let problem: Value = r.json().await.unwrap();
    assert_eq!(problem["errors"][0]["field"], "format");
    assert!(problem["detail"]
        .as_str()
        .unwrap()
        .contains("urdf, dh-json, csv"));
    // Without `format`: the same 422 naming it, not a 400 about the query string.
    let r = app.get(&format!("{base}/export")).await;
    assert_eq!(r.status(), 422);
    let problem: Value = r.json().await.unwrap();
    assert_eq!(problem["errors"][0]["field"], "format", "{problem}");
    app.shutdown().await;
}
