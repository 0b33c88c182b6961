//! Campaign plans (issue 16): which poses to shoot and how good the result
//! will be. The request is typed into the numerics' plan request
//! (`campaign_plan_inputs`, with the dot noise of `campaign_plan_noise`),
//! the plan is computed on a blocking thread and stored
//! (`campaign_plan_doc`); the stored plan is served as JSON or as a cell
//! program. A plan may extend a session's campaign
//! (`campaign_plan_extension`, issue 30).

use robocal_calib::kinematics::{CalibratedModel, Instrument, ParamLayout};
use robocal_calib::plan::plan_campaign;

use super::campaign_plan_doc::{plan_doc, plan_error};
use super::campaign_plan_extension::{existing_joints_rad, fill_from_session, session_to_extend};
use super::campaign_plan_inputs::{camera_of, plan_request, planning_robot};
use super::campaign_plan_noise::dot_noise;
use super::error::{ServiceError, ServiceResult};
use super::evaluate::pose_of;
use super::export::Exported;
use crate::export::campaign_program::{
    write_csv, write_krl, write_rapid, write_urscript, ProgramFormat, KRL_PROGRAM,
};
use crate::schema::campaign_plan::{CampaignPlanBody, CampaignPlanOut};
use crate::schema::Checker;
use crate::store::{CampaignPlanRecord, DynStore};

/// `POST /v1/robots/{serial}/campaign-plans`: plan, store, return the plan.
pub async fn create_plan(
    store: &DynStore,
    serial: &str,
    mut body: CampaignPlanBody,
) -> ServiceResult<CampaignPlanOut> {
    let (robot, model_name) = planning_robot(store, serial).await?;
    let extended = match &body.extend_session {
        Some(id) => Some(session_to_extend(store, serial, id).await?),
        None => None,
    };
    if let Some(session) = &extended {
        fill_from_session(&mut body, session);
    }
    body.check()?;
    let existing = match &extended {
        Some(session) => existing_joints_rad(store, session).await?,
        None => Vec::new(),
    };
    let mut c = Checker::default();
    let target_to_base = pose_of(&body.target_to_base_guess, "target_to_base_guess", &mut c);
    let flange_to_camera = pose_of(
        &body.flange_to_camera_guess,
        "flange_to_camera_guess",
        &mut c,
    );
    c.finish()?;
    let (Some(world_to_base), Some(flange_to_tool)) = (target_to_base, flange_to_camera) else {
        return Err(ServiceError::invalid("target_to_base_guess", "not a pose"));
    };
    let (intrinsics, size, hold) = camera_of(store, &body).await?;
    let noise = dot_noise(store, serial, body.sigma_px, size).await?;
    let model = CalibratedModel {
        robot,
        world_to_base,
        flange_to_tool,
    };
    let mut request = plan_request(&body, model, intrinsics, size, hold, noise.sigma_px)?;
    request.existing_joints_rad = existing;
    let layout = ParamLayout::new(&request.model.robot, Instrument::Camera);
    let plan = tokio::task::spawn_blocking(move || plan_campaign(&request))
        .await
        .map_err(ServiceError::internal)?
        .map_err(plan_error)?;
    let is_angle = |name: &str| layout.index_of(name).is_some_and(|i| layout.is_angle(i));
    let id = uuid::Uuid::now_v7().to_string();
    let mut out = plan_doc(id, serial, model_name, &plan, &noise, &is_angle);
    out.extend_session = body.extend_session.clone();
    let record = CampaignPlanRecord {
        id: out.id.clone(),
        serial: serial.to_string(),
        request: serde_json::to_value(&body).map_err(ServiceError::internal)?,
        plan: serde_json::to_value(&out).map_err(ServiceError::internal)?,
        created_at: out.created_at.clone(),
    };
    store.insert_campaign_plan(&record).await?;
    Ok(out)
}

/// `GET /v1/robots/{serial}/campaign-plans/{id}?format=`.
pub async fn get_plan(
    store: &DynStore,
    serial: &str,
    id: &str,
    format: Option<&str>,
) -> ServiceResult<Exported> {
    let format = match format {
        None => ProgramFormat::Json,
        Some(name) => ProgramFormat::parse(name).ok_or_else(|| {
            ServiceError::invalid(
                "format",
                format!("must be one of {}", ProgramFormat::NAMES.join(", ")),
            )
        })?,
    };
    let record = store
        .get_campaign_plan(serial, id)
        .await?
        .ok_or_else(|| ServiceError::not_found("campaign plan", id))?;
    let plan: CampaignPlanOut =
        serde_json::from_value(record.plan).map_err(ServiceError::internal)?;
    let joints = plan.poses.first().map_or(0, |p| p.joints_deg.len());
    if let Some(max) = format.max_joints().filter(|&m| joints > m) {
        return Err(ServiceError::invalid(
            "format",
            format!(
                "a {} program carries at most {max} axes; this robot has {joints}",
                ProgramFormat::NAMES[format as usize]
            ),
        ));
    }
    let body = match format {
        ProgramFormat::Json => serde_json::to_vec_pretty(&plan).map_err(ServiceError::internal)?,
        ProgramFormat::Csv => write_csv(&plan).into_bytes(),
        ProgramFormat::Urscript => write_urscript(&plan).into_bytes(),
        ProgramFormat::Rapid => write_rapid(&plan).into_bytes(),
        ProgramFormat::Krl => write_krl(&plan).into_bytes(),
    };
    Ok(Exported {
        content_type: format.content_type(),
        // KRL wants the file named as its DEF.
        file_name: match format {
            ProgramFormat::Krl => format!("{KRL_PROGRAM}.src"),
            _ => format!("{serial}-plan-{id}.{}", format.extension()),
        },
        body,
    })
}
