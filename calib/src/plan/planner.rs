//! The planner end to end (module doc of [`super`]): check the request,
//! generate candidates, select, order, predict.

use rand::{rngs::StdRng, seq::SliceRandom, SeedableRng};

use super::candidates::{anchor_joints, binding_constraint, generate, limited_model};
use super::error::{FilterCount, PlanError};
use super::extension::{existing_factors, predict_existing, ExistingCampaign};
use super::information::{pose_factor, Columns};
use super::path::{order_path, path_length};
use super::predict::{position_weight, predict, Prediction};
use super::request::{
    PlanCriterion, PlanPurpose, PlanRequest, QUICK_CHECK_MAX_POSES, QUICK_CHECK_MIN_POSES,
};
use super::select::{select_after, Criterion};

/// Random feasible poses the validation error is predicted over.
pub const PREDICTION_POSES: usize = 200;
/// Further random feasible poses the I criterion weighs (not the
/// prediction's: a plan fitted to its own test poses would flatter itself).
pub const WEIGHT_POSES: usize = 200;
/// Seeds the validation and prediction draws apart from the candidates.
const VALIDATION_SEED: u64 = 0x7a_11d;
/// Largest view angle (deg): beyond it the board is seen edge-on.
const MAX_VIEW_ANGLE_DEG: f64 = 80.0;

/// Which set a planned pose belongs to (the session's `set`).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum PlannedSet {
    Cal,
    Val,
}

#[derive(Debug, Clone, PartialEq)]
pub struct PlannedPose {
    pub joints_rad: Vec<f64>,
    pub set: PlannedSet,
}

#[derive(Debug, Clone, PartialEq)]
pub struct CampaignPlan {
    /// In path order.
    pub poses: Vec<PlannedPose>,
    /// Of the campaign shot as planned: with an extension, the existing
    /// poses and the planned ones together.
    pub prediction: Prediction,
    /// An extension's existing campaign alone (`None` for a plan from
    /// scratch): the gain of the planned poses is the difference.
    pub existing: Option<ExistingCampaign>,
    /// Existing poses whose information seeded the plan (those that see
    /// the board by the planning model).
    pub existing_poses: usize,
    /// Survivors of every candidate filter.
    pub filters: Vec<FilterCount>,
    /// Where the path starts (the request's start, or the anchor pose).
    pub start_joints_rad: Vec<f64>,
    /// Sum of the largest joint change of every move (rad).
    pub path_length_rad: f64,
    pub purpose: PlanPurpose,
}

fn invalid(field: &'static str, message: impl Into<String>) -> PlanError {
    PlanError::Invalid {
        field,
        message: message.into(),
    }
}

fn check(request: &PlanRequest) -> Result<(), PlanError> {
    let (d0, d1) = request.distance_mm;
    if !(d0.is_finite() && d1.is_finite() && 0.0 < d0 && d0 <= d1) {
        return Err(invalid("distance_mm", "needs 0 < min <= max"));
    }
    let (a0, a1) = request.view_angle_deg;
    if !(a0.is_finite() && a1.is_finite() && 0.0 <= a0 && a0 <= a1 && a1 <= MAX_VIEW_ANGLE_DEG) {
        return Err(invalid(
            "view_angle_deg",
            format!("needs 0 <= min <= max <= {MAX_VIEW_ANGLE_DEG}"),
        ));
    }
    if request.board_points.is_empty() {
        return Err(invalid("target", "the board has no points"));
    }
    if request.image_width_px == 0 || request.image_height_px == 0 {
        return Err(invalid("camera", "image size must be positive"));
    }
    if !(request.sigma_px.is_finite() && request.sigma_px > 0.0) {
        return Err(invalid("sigma_px", "must be positive"));
    }
    match request.purpose {
        PlanPurpose::QuickCheck
            if !(QUICK_CHECK_MIN_POSES..=QUICK_CHECK_MAX_POSES).contains(&request.poses) =>
        {
            Err(invalid(
                "poses",
                format!(
                    "a quick check has {QUICK_CHECK_MIN_POSES}..={QUICK_CHECK_MAX_POSES} poses"
                ),
            ))
        }
        // An extension adds to poses that determine most parameters already.
        PlanPurpose::Calibration
            if request.existing_joints_rad.is_empty() && request.poses < QUICK_CHECK_MIN_POSES =>
        {
            Err(invalid(
                "poses",
                format!("at least {QUICK_CHECK_MIN_POSES} poses"),
            ))
        }
        _ if request.poses == 0 => Err(invalid("poses", "at least 1 pose")),
        _ => Ok(()),
    }
}

/// Plan the campaign `request` asks for (an extension of the existing
/// poses when it names some: [`super::extension`]).
pub fn plan_campaign(request: &PlanRequest) -> Result<CampaignPlan, PlanError> {
    check(request)?;
    let model = limited_model(request)?;
    let set = generate(request)?;
    let wanted = request.poses + request.validation_poses;
    let columns = Columns::of(request, &model)?;
    let existing = existing_factors(request, &model, &columns)?;
    let mut feasible = Vec::new();
    let mut factors = Vec::new();
    for c in &set.candidates {
        if let Some(g) = pose_factor(request, &model, &columns, &c.joints_rad) {
            feasible.push(c.joints_rad.clone());
            factors.push(g);
        }
    }
    if feasible.len() < wanted {
        return Err(PlanError::Infeasible {
            constraint: binding_constraint(&set.filters),
            feasible: feasible.len(),
            wanted,
            filters: set.filters,
        });
    }
    let mut rng = StdRng::seed_from_u64(request.seed ^ VALIDATION_SEED);
    let mut shuffled: Vec<usize> = (0..feasible.len()).collect();
    shuffled.shuffle(&mut rng);
    let probe: Vec<Vec<f64>> = shuffled
        .iter()
        .take(PREDICTION_POSES)
        .map(|&k| feasible[k].clone())
        .collect();
    let criterion = request
        .criterion
        .unwrap_or(PlanCriterion::for_purpose(request.purpose));
    let chosen = match criterion {
        PlanCriterion::D => select_after(
            &existing,
            &factors,
            columns.len(),
            request.poses,
            Criterion::D,
        ),
        PlanCriterion::I => {
            let weighed: Vec<Vec<f64>> = shuffled
                .iter()
                .skip(PREDICTION_POSES)
                .take(WEIGHT_POSES)
                .map(|&k| feasible[k].clone())
                .collect();
            let weighed = if weighed.is_empty() { &probe } else { &weighed };
            let weight = position_weight(&model, &columns, weighed)?;
            select_after(
                &existing,
                &factors,
                columns.len(),
                request.poses,
                Criterion::I(&weight),
            )
        }
    };
    let validation: Vec<usize> = shuffled
        .iter()
        .rev()
        .filter(|k| !chosen.contains(*k))
        .take(request.validation_poses)
        .copied()
        .collect();
    let campaign_factors: Vec<_> = existing
        .iter()
        .chain(chosen.iter().map(|&k| &factors[k]))
        .collect();
    let prediction = predict(&model, &columns, &campaign_factors, &probe)?;
    let existing_poses = existing.len();
    let existing = if existing.is_empty() {
        None
    } else {
        Some(predict_existing(&model, &columns, &existing, &probe)?)
    };
    let start = anchor_joints(request, &model)?;
    let planned: Vec<(usize, PlannedSet)> = chosen
        .iter()
        .map(|&k| (k, PlannedSet::Cal))
        .chain(validation.iter().map(|&k| (k, PlannedSet::Val)))
        .collect();
    let joints: Vec<Vec<f64>> = planned.iter().map(|(k, _)| feasible[*k].clone()).collect();
    let order = order_path(&start, &joints);
    let path_length_rad = path_length(&start, &joints, &order);
    Ok(CampaignPlan {
        poses: order
            .iter()
            .map(|&i| PlannedPose {
                joints_rad: joints[i].clone(),
                set: planned[i].1,
            })
            .collect(),
        prediction,
        existing,
        existing_poses,
        filters: set.filters,
        start_joints_rad: start,
        path_length_rad,
        purpose: request.purpose,
    })
}
