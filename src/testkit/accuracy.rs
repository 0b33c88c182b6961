//! Issue 5's accuracy targets through the service (issue 6): a served
//! parameter set of a simulated campaign judged against the simulator's
//! truth — validation error at the true camera positions, every identified
//! parameter against the truth in units of its reported standard deviation
//! — and the oracle floors of the same campaign (`calib::sim::oracle`).
//! Used by the `pipeline_accuracy` benchmark and the end-to-end tests.

use robocal_calib::kinematics::identify::validate;
use robocal_calib::kinematics::{Instrument, ParamLayout};
use robocal_calib::sim::campaign::{Campaign, CampaignSpec};
use robocal_calib::sim::campaign_io::PoseSet;
use robocal_calib::sim::oracle::{
    equivalent_truth, image_oracle_accuracy, oracle_accuracy, oracle_accuracy_correlated,
    truth_measurements,
};
use robocal_calib::stats::AccuracyStats;

use crate::domain::ParameterSet;
use crate::report::Report;

/// A served parameter set against the truth of its campaign.
#[derive(Debug, Clone)]
pub struct TruthComparison {
    /// Predicted against true camera positions at the validation joints.
    pub validation: AccuracyStats,
    /// Per identified parameter: `(name, (estimate - truth) / std)`.
    pub z: Vec<(String, f64)>,
    /// Layout indices the set identified (not held fixed).
    pub free: Vec<usize>,
}

impl TruthComparison {
    /// The parameter furthest from the truth, in standard deviations.
    pub fn worst(&self) -> Option<&(String, f64)> {
        self.z.iter().max_by(|a, b| a.1.abs().total_cmp(&b.1.abs()))
    }

    /// Root mean square of the z values (1 when the sigmas are right).
    pub fn z_rms(&self) -> f64 {
        let n = self.z.len().max(1) as f64;
        (self.z.iter().map(|(_, z)| z * z).sum::<f64>() / n).sqrt()
    }
}

/// Compares `set` (as served at `.../parameter-sets/{v}`, or a pipeline
/// output's `parameters`) with the truth of `campaign`.
pub fn compare_with_truth(
    set: &ParameterSet,
    campaign: &Campaign,
) -> Result<TruthComparison, String> {
    let model = set.model()?;
    let rows = &set.parameters;
    let layout = ParamLayout::new(&model.robot, Instrument::Camera);
    let mut free = Vec::new();
    let mut std_internal = Vec::new();
    for (i, p) in layout.params.iter().enumerate() {
        let row = rows
            .iter()
            .find(|r| r.name == p.name)
            .ok_or_else(|| format!("parameter {} missing from the set", p.name))?;
        if row.fixed {
            continue;
        }
        free.push(i);
        std_internal.push(if layout.is_angle(i) {
            row.std.to_radians()
        } else {
            row.std
        });
    }
    // Fixed terms sit at their nominal values in the served model, so it is
    // its own reference for the equivalent truth.
    let truth = equivalent_truth(campaign, &model, &free).map_err(|e| e.to_string())?;
    let difference = layout.difference(&model, &truth);
    let z = free
        .iter()
        .zip(&std_internal)
        .map(|(&i, &sd)| (layout.params[i].name.clone(), difference[i] / sd))
        .collect();
    let val = truth_measurements(campaign, PoseSet::Val);
    let validation = validate(&model, &val).map_err(|e| e.to_string())?.0;
    Ok(TruthComparison {
        validation,
        z,
        free,
    })
}

/// Mean 3-D validation error (mm) of the oracle floors of one campaign.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct OracleFloors {
    /// Pose-level, independent draws per pose (optimistic: see
    /// `calib::sim::oracle`).
    pub pose_independent_mm: f64,
    /// Pose-level with the camera step's shared intrinsics error, mean
    /// over draws.
    pub pose_correlated_mm: f64,
    /// Image-level: the efficient estimator on true points plus the dot
    /// noise, mean over draws (the campaign's Cramér–Rao floor).
    pub image_mm: f64,
}

/// The three oracle floors of `campaign` at dot noise `sigma_px` per axis,
/// identifying the layout indices `free`; the correlated and image-level
/// floors are means over `draws` noise draws.
pub fn oracle_floors(
    spec: &CampaignSpec,
    campaign: &Campaign,
    sigma_px: f64,
    free: &[usize],
    draws: u64,
) -> Result<OracleFloors, String> {
    let points = spec.board.points();
    let err = |e: robocal_calib::sim::experiment::ExperimentError| e.to_string();
    let independent = oracle_accuracy(spec, campaign, &points, sigma_px).map_err(err)?;
    let mut correlated = 0.0;
    for draw in 0..draws {
        correlated += oracle_accuracy_correlated(spec, campaign, &points, sigma_px, draw)
            .map_err(err)?
            .norm
            .mean_mm;
    }
    let image = image_oracle_accuracy(spec, campaign, sigma_px, free, draws).map_err(err)?;
    let n = draws.max(1) as f64;
    Ok(OracleFloors {
        pose_independent_mm: independent.norm.mean_mm,
        pose_correlated_mm: correlated / n,
        image_mm: image.iter().map(|s| s.norm.mean_mm).sum::<f64>() / n,
    })
}

/// The dot noise per image axis (px) a served report's camera section
/// measured: its reprojection RMS is per dot (2-D residual length).
pub fn dot_noise_px(report: &Report) -> Result<f64, String> {
    report
        .camera
        .as_ref()
        .map(|c| c.reprojection_rms_px / std::f64::consts::SQRT_2)
        .ok_or_else(|| "report without camera.reprojection_rms_px".to_string())
}
