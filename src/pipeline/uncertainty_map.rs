//! The report's map of predicted uncertainty over the workspace (issue
//! "Deploy the result"): the identified covariance propagated to the tool
//! position (`calib::kinematics::uncertainty`) over a horizontal grid of
//! flange positions around the calibration poses, each solved by the
//! calibrated inverse kinematics. It shows where the calibration holds
//! (inside the posed volume) and how fast it degrades outside it. With
//! kept non-geometric terms (issue 19) the flanges, the inverse kinematics
//! and the σ go through them (`TermModel`), as `forward`'s σ does: the
//! covariance at the deflected joints plus the terms' own σ.

use robocal_calib::geometry::{pose_from_xyz_rpy_deg, Pose, PoseXyzRpy};
use robocal_calib::kinematics::term_model::TermModel;
use robocal_calib::kinematics::term_uncertainty::TermCovarianceFactor;
use robocal_calib::kinematics::uncertainty::{pose_std, PoseFrame};
use robocal_calib::kinematics::CalibratedModel;

use super::identify_stage::Identified;
use super::PoseInput;
use crate::report::{UncertaintyCell, UncertaintyMapReport};

/// Grid points along the longer side of the slice.
const GRID_POINTS: usize = 13;
/// The slice extends this fraction of the poses' span beyond them on each
/// side (the map's point is to show the outside too).
const MARGIN_FRACTION: f64 = 0.35;
/// Smallest span of the slice (mm): a campaign posed in one spot still
/// gets a readable map.
const MIN_SPAN_MM: f64 = 200.0;

/// The map over the calibration poses of `id`; `None` when no grid point
/// is reachable or the model cannot be evaluated.
pub fn workspace_map(id: &Identified, poses: &[PoseInput]) -> Option<UncertaintyMapReport> {
    let evaluated = id.term_model().ok()?;
    let model = &evaluated.model;
    let flange_model = TermModel {
        model: CalibratedModel {
            robot: model.robot.clone(),
            world_to_base: Pose::identity(),
            flange_to_tool: Pose::identity(),
        },
        ..evaluated.clone()
    };
    // The terms' joint covariance with the geometry, factored once for
    // every cell.
    let joint = match &evaluated.covariance {
        Some(c) => {
            Some(TermCovarianceFactor::new(&id.identification.layout, &id.covariance, c).ok()?)
        }
        None => None,
    };
    let joints: Vec<Vec<f64>> = id
        .cal
        .iter()
        .map(|&i| poses[i].joints_deg.to_radians())
        .collect();
    let flanges: Vec<Pose> = joints
        .iter()
        .map(|q| evaluated.base_to_flange(q).ok())
        .collect::<Option<_>>()?;
    // The pose at the median height sets the slice's height, orientation
    // and the IK seed.
    let mut by_height: Vec<usize> = (0..flanges.len()).collect();
    by_height.sort_by(|&a, &b| {
        flanges[a]
            .translation
            .vector
            .z
            .total_cmp(&flanges[b].translation.vector.z)
    });
    let middle = *by_height.get(by_height.len() / 2)?;
    let z_mm = flanges[middle].translation.vector.z;
    let rotation_deg = PoseXyzRpy::from_pose(&flanges[middle]).rotation_deg;
    let seed = &joints[middle];
    let (lo, hi) = flanges.iter().fold(
        ([f64::INFINITY; 2], [f64::NEG_INFINITY; 2]),
        |(lo, hi), f| {
            let p = f.translation.vector;
            (
                [lo[0].min(p.x), lo[1].min(p.y)],
                [hi[0].max(p.x), hi[1].max(p.y)],
            )
        },
    );
    let span = (hi[0] - lo[0]).max(hi[1] - lo[1]).max(MIN_SPAN_MM) * (1.0 + 2.0 * MARGIN_FRACTION);
    let step_mm = span / (GRID_POINTS - 1) as f64;
    let centre = [(lo[0] + hi[0]) / 2.0, (lo[1] + hi[1]) / 2.0];
    let mut cells = Vec::new();
    for iy in 0..GRID_POINTS {
        for ix in 0..GRID_POINTS {
            let x = centre[0] - span / 2.0 + ix as f64 * step_mm;
            let y = centre[1] - span / 2.0 + iy as f64 * step_mm;
            let Ok(target) = pose_from_xyz_rpy_deg([x, y, z_mm], rotation_deg) else {
                continue;
            };
            let Ok(solution) = flange_model.nearest_within_limits(&target, seed) else {
                continue;
            };
            if let Some(position_std_mm) =
                position_std_mm(&evaluated, id, joint.as_ref(), &solution.joints_rad)
            {
                cells.push(UncertaintyCell {
                    x_mm: x,
                    y_mm: y,
                    position_std_mm,
                });
            }
        }
    }
    if cells.is_empty() {
        return None;
    }
    Some(UncertaintyMapReport {
        z_mm,
        rotation_deg,
        step_mm,
        cells,
        poses_xy_mm: flanges
            .iter()
            .map(|f| [f.translation.vector.x, f.translation.vector.y])
            .collect(),
    })
}

/// The tool's position σ at commanded joints `q_rad`: the identified
/// covariance at the deflected joints plus the kept terms' σ, through their
/// `joint` covariance when the fit gave it (as `forward`'s σ), else taken
/// as independent.
fn position_std_mm(
    evaluated: &TermModel,
    id: &Identified,
    joint: Option<&TermCovarianceFactor>,
    q_rad: &[f64],
) -> Option<f64> {
    let layout = &id.identification.layout;
    let frame = PoseFrame::ToolInWorld;
    if let Some(joint) = joint {
        return Some(joint.pose_std(evaluated, q_rad, frame).ok()?.position_mm);
    }
    let bent = evaluated.deflected(q_rad).ok()?;
    let std = pose_std(layout, &evaluated.model, &id.covariance, &bent, frame).ok()?;
    let terms = evaluated.term_variance(&evaluated.model, q_rad).ok()?;
    Some((std.position_mm.powi(2) + terms.position_mm2).sqrt())
}
