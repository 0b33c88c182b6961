//! Session 12 (issue 19): the UR10 of Landgraf 2021 calibrated on Series B
//! with the T-Mac's orientation (full pose, `Instrument::Camera` layout: 6
//! rows per pose, a 6-DoF `flange_to_tool`) against position only
//! (`Instrument::Tracker`, 3 rows), each with and without the selected
//! non-geometric terms; validated on Series C and D with `world_to_base`
//! re-fitted on each (a different tracker station), and the σ of the wrist
//! parameters. Also checks the T-Mac's Euler convention against the
//! nominal kinematics (docs/decisions/0030-tmac-euler-convention.md).
//!
//! `cargo run --release -p robocal-calib --example ur10_pose_bench [every]`
//! (`every`: fit on every n-th pose of Series B; default 1, all 1495).

#[path = "support/tmac_convention.rs"]
mod tmac_convention;

use nalgebra::{DVector, UnitQuaternion, Vector3};
use robocal_calib::geometry::{pose_error, Pose};
use robocal_calib::kinematics::identify::{
    fit_parameters, frame_indices, identify, Identification, IdentifyMode, Measurement, Observed,
};
use robocal_calib::kinematics::initial::initial_world_to_base;
use robocal_calib::kinematics::nongeometric::{CandidateOptions, NonGeometric};
use robocal_calib::kinematics::term_selection::{identify_with_terms, Verdict};
use robocal_calib::kinematics::term_validate::refit_base_with_terms;
use robocal_calib::kinematics::tracker_csv::{landgraf2021_rows, TrackerRow};
use robocal_calib::kinematics::{presets, CalibratedModel, Instrument, ParamLayout};

const DATA: &str = concat!(
    env!("CARGO_MANIFEST_DIR"),
    "/tests/data/kinematic/ur10_landgraf2021"
);
/// Probe origin in the flange frame, the start of the existing
/// position-only test (`Trafo_TM_F_init.txt`: 109 mm along z).
const TOOL_GUESS_MM: [f64; 3] = [0.0, 0.0, 109.0];
/// Probe rotation in the flange frame: `Trafo_TM_F_init.txt`'s rotation
/// block as is, `Rz(-90°)` (the data give -90.01° within 0.16°).
const TOOL_GUESS_RZ_DEG: f64 = -90.0;
/// Wrist joints (0-based) whose σ are compared.
const WRIST: [usize; 3] = [3, 4, 5];
const PARAM_NAMES: [&str; 4] = ["dtheta", "a", "d", "alpha"];
const VALIDATION: [(&str, &str); 2] = [
    ("Series_C", "measurements_random_poses.csv"),
    ("Series_D", "measurements_iso_cubes.csv"),
];

fn rows(series: &str, file: &str) -> Vec<TrackerRow> {
    let text = std::fs::read_to_string(format!("{DATA}/{series}/{file}")).expect("data file");
    landgraf2021_rows(&text).expect("parses")
}

fn positions(rows: &[TrackerRow]) -> Vec<Measurement> {
    rows.iter().map(TrackerRow::measurement).collect()
}

/// Positions weighted like the full poses' position block: the file's
/// standard deviations with the tracker floor (separates the effect of
/// the per-row weights from that of the orientation).
fn weighted_positions(rows: &[TrackerRow]) -> Vec<Measurement> {
    poses(rows)
        .into_iter()
        .map(|m| match m.observed {
            Observed::Pose {
                world_to_tool,
                covariance: Some(c),
            } => Measurement {
                observed: Observed::Position {
                    position_mm: world_to_tool.translation.vector,
                    covariance: Some(c.fixed_view::<3, 3>(0, 0).into_owned()),
                },
                ..m
            },
            _ => unreachable!("T-Mac poses carry a covariance"),
        })
        .collect()
}

fn poses(rows: &[TrackerRow]) -> Vec<Measurement> {
    rows.iter()
        .map(|r| r.pose_measurement().expect("T-Mac rows have orientation"))
        .collect()
}

/// A calibrated model, its terms and the geometric σ.
#[derive(Clone)]
struct Fitted {
    label: String,
    /// Nominal kinematics, base and tool fitted (the identification's
    /// first stage).
    before: CalibratedModel,
    instrument: Instrument,
    model: CalibratedModel,
    terms: Option<NonGeometric>,
    layout: ParamLayout,
    std_devs: DVector<f64>,
    fixed: Vec<String>,
}

fn fit(
    label: &str,
    start: &CalibratedModel,
    instrument: Instrument,
    data: &[Measurement],
    terms: bool,
) -> Fitted {
    let t0 = std::time::Instant::now();
    let (model, kept, std_devs, id): (_, _, _, Identification) = if terms {
        let t = identify_with_terms(
            start,
            instrument,
            data,
            IdentifyMode::Weighted.into(),
            &CandidateOptions::for_robot(&start.robot),
        )
        .expect("identifies");
        for l in &t.report {
            if matches!(l.verdict, Verdict::Kept | Verdict::DoesNotGeneralise) {
                println!(
                    "  {label}: {:?} {} {:+.2e} ± {:.1e} {}: {}",
                    l.verdict, l.name, l.value, l.std_dev, l.unit, l.why
                );
            }
        }
        println!("  {label}: {} term(s) kept", t.terms.terms.len());
        let std = match &t.geometric_covariance {
            Some(c) => c.diagonal().map(|v| v.max(0.0).sqrt()),
            None => t.geometric.std_devs.clone(),
        };
        let kept = (!t.terms.terms.is_empty()).then_some(t.terms);
        (t.model, kept, std, t.geometric)
    } else {
        let id =
            identify(start, instrument, data, IdentifyMode::Weighted.into()).expect("identifies");
        (id.model.clone(), None, id.std_devs.clone(), id)
    };
    println!(
        "  {label}: {} poses, residual rms {:.3} (whitened), cond {:.0}, {} iterations, {:.1} s, fixed {:?}",
        data.len(), id.residual_rms, id.identifiability.condition_number, id.iterations,
        t0.elapsed().as_secs_f64(), id.identifiability.fixed
    );
    let tool = model.flange_to_tool;
    println!(
        "  {label}: flange_to_tool {:.3?} mm, rotation {:.3?} deg",
        tool.translation.vector.as_slice(),
        tool.rotation.scaled_axis().map(f64::to_degrees).as_slice()
    );
    Fitted {
        label: label.into(),
        before: id.before.clone(),
        instrument,
        model,
        terms: kept,
        layout: id.layout,
        std_devs,
        fixed: id.identifiability.fixed,
    }
}

fn predict(f: &Fitted, model: &CalibratedModel, q: &[f64]) -> Pose {
    match &f.terms {
        Some(t) => t.world_to_tool(model, q).unwrap(),
        None => model.world_to_tool(q).unwrap(),
    }
}

/// `world_to_base` re-fitted on `data` (positions: `Instrument::Tracker`;
/// poses: `Instrument::Camera`), everything else held.
fn refit_base(f: &Fitted, instrument: Instrument, data: &[Measurement]) -> CalibratedModel {
    let options = IdentifyMode::Weighted.into();
    match &f.terms {
        Some(t) => refit_base_with_terms(&f.model, t, instrument, data, options).unwrap(),
        None => {
            let base = frame_indices(&ParamLayout::new(&f.model.robot, instrument), false);
            fit_parameters(&f.model, instrument, data, &base, options)
                .unwrap()
                .0
        }
    }
}

/// (mean, rms, max) of a list.
fn summary(e: &[f64]) -> (f64, f64, f64) {
    let n = e.len() as f64;
    let mean = e.iter().sum::<f64>() / n;
    let rms = (e.iter().map(|x| x * x).sum::<f64>() / n).sqrt();
    (mean, rms, e.iter().cloned().fold(0.0, f64::max))
}

/// 3-D position error (mm) and, for a model with a tool rotation, the
/// orientation error (deg) at `val` poses.
fn errors(f: &Fitted, model: &CalibratedModel, val: &[Measurement], rotation: bool) -> String {
    let (mut p, mut r) = (Vec::new(), Vec::new());
    for m in val {
        let pred = predict(f, model, &m.joints_rad);
        let Observed::Pose { world_to_tool, .. } = &m.observed else {
            unreachable!()
        };
        let e = pose_error(world_to_tool, &pred);
        p.push(Vector3::new(e[0], e[1], e[2]).norm());
        r.push(Vector3::new(e[3], e[4], e[5]).norm().to_degrees());
    }
    let (pm, pr, px) = summary(&p);
    let mut s = format!("position {pm:.4} / {pr:.4} / {px:.3} mm");
    if rotation {
        let (rm, rr, rx) = summary(&r);
        s += &format!("; orientation {rm:.4} / {rr:.4} / {rx:.3} deg");
    }
    s
}

fn validate_all(f: &Fitted, rotation: bool, val: &[(String, Vec<Measurement>, Vec<Measurement>)]) {
    for (name, pos, pose) in val {
        let m = refit_base(f, Instrument::Tracker, pos);
        println!(
            "  {} -> {name} ({} poses), base re-fitted on positions: {} (mean / rms / max)",
            f.label,
            pos.len(),
            errors(f, &m, pose, rotation)
        );
        if rotation && f.instrument == Instrument::Camera {
            let m = refit_base(f, Instrument::Camera, pose);
            println!(
                "  {} -> {name}, base re-fitted on full poses: {}",
                f.label,
                errors(f, &m, pose, true)
            );
        }
    }
}

fn wrist_sigmas(f: &Fitted) -> String {
    let mut s = String::new();
    for j in WRIST {
        for (k, p) in PARAM_NAMES.iter().enumerate() {
            let name = format!("{p}_{}", j + 1);
            let i = f.layout.index_of(&name).expect("DH joint");
            let v = if f.fixed.contains(&name) {
                "fixed".to_string()
            } else if f.layout.is_angle(i) {
                format!("{:.2e} rad", f.std_devs[i])
            } else {
                format!("{:.2e} mm", f.std_devs[i])
            };
            s += &format!("{name} {v}{}", if k == 3 { "\n    " } else { ", " });
        }
    }
    s
}

/// Scale each pose's position and orientation covariance blocks so that
/// the whitened residual of `f` at `data` has unit rms per block (one
/// round of a two-component variance estimate): the weights the data's
/// own scatter supports. Returns the data and the two factors.
fn reweighted(f: &Fitted, data: &[Measurement]) -> (Vec<Measurement>, f64, f64) {
    let (mut sp, mut sr) = (0.0, 0.0);
    for m in data {
        let Observed::Pose {
            world_to_tool,
            covariance: Some(c),
        } = &m.observed
        else {
            unreachable!()
        };
        let e = pose_error(world_to_tool, &predict(f, &f.model, &m.joints_rad));
        let block = |o: usize| {
            let l = c.fixed_view::<3, 3>(o, o).into_owned().cholesky().unwrap();
            l.l()
                .solve_lower_triangular(&Vector3::new(e[o], e[o + 1], e[o + 2]))
                .unwrap()
                .norm_squared()
        };
        sp += block(0);
        sr += block(3);
    }
    let n = 3.0 * data.len() as f64;
    let (sp, sr) = ((sp / n).sqrt(), (sr / n).sqrt());
    let mut out = data.to_vec();
    for m in &mut out {
        if let Observed::Pose {
            covariance: Some(c),
            ..
        } = &mut m.observed
        {
            for a in 0..6 {
                for b in 0..6 {
                    c[(a, b)] *= if a < 3 { sp } else { sr } * if b < 3 { sp } else { sr };
                }
            }
        }
    }
    (out, sp, sr)
}

fn main() {
    let every: usize = std::env::args()
        .nth(1)
        .and_then(|s| s.parse().ok())
        .unwrap_or(1);
    let b_rows: Vec<TrackerRow> = rows("Series_B", "measurements_joint_configurations.csv")
        .into_iter()
        .step_by(every)
        .collect();
    let (b_pos, b_pose) = (positions(&b_rows), poses(&b_rows));
    let val: Vec<(String, Vec<Measurement>, Vec<Measurement>)> = VALIDATION
        .iter()
        .map(|(s, f)| {
            let r = rows(s, f);
            (s.to_string(), positions(&r), poses(&r))
        })
        .collect();
    let mut start_pos = CalibratedModel {
        robot: presets::ur10(),
        world_to_base: Pose::identity(),
        flange_to_tool: Pose::translation(TOOL_GUESS_MM[0], TOOL_GUESS_MM[1], TOOL_GUESS_MM[2]),
    };
    start_pos.world_to_base = initial_world_to_base(&start_pos, &b_pos).unwrap();
    // Convention cross-check: nominal kinematics, base fitted on positions.
    let (frames, _) = fit_parameters(
        &start_pos,
        Instrument::Tracker,
        &b_pos,
        &frame_indices(
            &ParamLayout::new(&start_pos.robot, Instrument::Tracker),
            true,
        ),
        IdentifyMode::Weighted.into(),
    )
    .unwrap();
    println!("T-Mac convention against the nominal UR10, Series B (every {every}): rotation mismatch rms / max");
    for (name, rot) in &tmac_convention::candidates() {
        let (rms, max) = tmac_convention::mismatch_deg(&frames, &b_rows, rot);
        println!("  {name:58} {rms:.4} / {max:.4} deg");
    }
    let mut start_pose = start_pos.clone();
    start_pose.flange_to_tool.rotation =
        UnitQuaternion::from_axis_angle(&Vector3::z_axis(), TOOL_GUESS_RZ_DEG.to_radians());
    for terms in [false, true] {
        let tag = if terms { " + terms" } else { "" };
        println!(
            "\n== {} ==",
            if terms {
                "with the selected non-geometric terms"
            } else {
                "geometric"
            }
        );
        let a = fit(
            &format!("(a) position{tag}"),
            &start_pos,
            Instrument::Tracker,
            &b_pos,
            terms,
        );
        let b = fit(
            &format!("(b) full pose{tag}"),
            &start_pose,
            Instrument::Camera,
            &b_pose,
            terms,
        );
        let (b_rew, sp, sr) = reweighted(&b, &b_pose);
        println!("  (b) block scale (whitened rms at B): position {sp:.2}, orientation {sr:.2}");
        let b2 = fit(
            &format!("(b') full pose, re-weighted{tag}"),
            &start_pose,
            Instrument::Camera,
            &b_rew,
            terms,
        );
        let (_, sp2, sr2) = reweighted(&b2, &b_rew);
        println!("  (b') block scale after: position {sp2:.2}, orientation {sr2:.2}");
        // (a)'s kinematics with a tool rotation fitted on B afterwards:
        // how well position-only kinematics predict the orientation.
        let a_rot = (a.terms.is_none()).then(|| {
            let mut m = a.model.clone();
            m.flange_to_tool.rotation = start_pose.flange_to_tool.rotation;
            let layout = ParamLayout::new(&m.robot, Instrument::Camera);
            let rot: Vec<usize> = (layout.tool_start() + 3..layout.tool_start() + 6).collect();
            let (m, _) = fit_parameters(
                &m,
                Instrument::Camera,
                &b_pose,
                &rot,
                IdentifyMode::Weighted.into(),
            )
            .unwrap();
            Fitted {
                label: format!("(a) + tool rotation fitted on B{tag}"),
                before: a.before.clone(),
                instrument: Instrument::Tracker,
                model: m,
                terms: None,
                layout: a.layout.clone(),
                std_devs: a.std_devs.clone(),
                fixed: a.fixed.clone(),
            }
        });
        if !terms {
            let nominal = Fitted {
                label: "nominal kinematics, frames fitted on B poses".into(),
                model: b.before.clone(),
                terms: None,
                ..b.clone()
            };
            validate_all(&nominal, true, &val);
        }
        validate_all(&a, false, &val);
        if !terms {
            let a_w = fit(
                "(a') position, per-row weights",
                &start_pos,
                Instrument::Tracker,
                &weighted_positions(&b_rows),
                false,
            );
            validate_all(&a_w, false, &val);
            println!("  σ wrist, {}:\n    {}", a_w.label, wrist_sigmas(&a_w));
        }
        if let Some(ar) = &a_rot {
            validate_all(ar, true, &val);
        }
        validate_all(&b, true, &val);
        validate_all(&b2, true, &val);
        for f in [&a, &b, &b2] {
            println!("  σ wrist, {}:\n    {}", f.label, wrist_sigmas(f));
        }
    }
}
