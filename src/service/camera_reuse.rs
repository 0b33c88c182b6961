//! A session's `camera_calibration_id` (api.md "Measurement sessions"): it
//! names an earlier calibration, a parameter set `"{serial}/{version}"`
//! (`"{serial}/latest"` is resolved when the session is created), whose
//! camera intrinsics the session's jobs reuse and hold fixed. The paper
//! tunes `fx` and `k` once for a camera and keeps them (method.md §4); a
//! camera moved to another robot keeps its intrinsics too, so the serial
//! may be any robot's.

use robocal_calib::camera::Intrinsics;

use super::error::{ServiceError, ServiceResult};
use super::report_camera::report_camera;
use crate::pipeline::FixedCamera;
use crate::schema::session::{CameraDoc, Instrument, SessionBody};
use crate::store::{DynStore, StoreError};

/// The session field this module resolves (named in every error).
pub const FIELD: &str = "camera_calibration_id";

#[derive(Debug, thiserror::Error)]
pub enum ReuseError {
    /// Not of the form `"{serial}/{version}"`.
    #[error("{0}")]
    Malformed(String),
    /// No such parameter set.
    #[error("{0}")]
    NotFound(String),
    /// The parameter set cannot provide intrinsics for this session.
    #[error("{0}")]
    Unusable(String),
    #[error(transparent)]
    Store(#[from] StoreError),
}

/// `"{serial}/{version}"` split; `version` `None` is `latest`.
fn parse(id: &str) -> Result<(&str, Option<i64>), ReuseError> {
    let malformed = || {
        ReuseError::Malformed(format!(
            "{id:?} is not \"{{serial}}/{{version}}\" of a parameter set (e.g. \"IRB-001/3\" or \"IRB-001/latest\")"
        ))
    };
    let (serial, version) = id.split_once('/').ok_or_else(malformed)?;
    if crate::schema::robot::check_serial(serial).is_err() {
        return Err(malformed());
    }
    match version {
        "latest" => Ok((serial, None)),
        v => match v.parse::<i64>() {
            Ok(v) if v >= 1 => Ok((serial, Some(v))),
            _ => Err(malformed()),
        },
    }
}

/// Checks a new session's `camera_calibration_id` names a camera
/// calibration the session can reuse; returns it with `latest` resolved, so
/// the session's jobs all use one calibration.
pub async fn resolve_for_session(
    store: &DynStore,
    body: &SessionBody,
    id: &str,
) -> ServiceResult<String> {
    if body.instrument != Instrument::Camera {
        return Err(ServiceError::invalid(
            FIELD,
            "only a camera session reuses camera intrinsics",
        ));
    }
    match resolve(store, id, body.camera.as_ref()).await {
        Ok(fixed) => Ok(fixed.calibration_id),
        Err(ReuseError::NotFound(message)) => Err(ServiceError::NotFoundField {
            field: FIELD,
            message,
        }),
        Err(ReuseError::Malformed(message) | ReuseError::Unusable(message)) => {
            Err(ServiceError::invalid(FIELD, message))
        }
        Err(ReuseError::Store(e)) => Err(e.into()),
    }
}

/// Looks the calibration up and checks it fits a session whose camera is
/// `camera`: it has intrinsics, measured on images of the same size.
pub async fn resolve(
    store: &DynStore,
    id: &str,
    camera: Option<&CameraDoc>,
) -> Result<FixedCamera, ReuseError> {
    let (serial, version) = parse(id)?;
    let set = store
        .get_parameter_set(serial, version)
        .await?
        .ok_or_else(|| ReuseError::NotFound(format!("no parameter set {id:?}")))?;
    let resolved = format!("{serial}/{}", set.version);
    let intrinsics: Intrinsics = set.parameters.camera().copied().ok_or_else(|| {
        ReuseError::Unusable(format!(
            "parameter set {resolved} has no camera intrinsics (not a camera calibration)"
        ))
    })?;
    if let Some(camera) = camera {
        let calibrated = report_camera(store, serial, set.version).await?;
        if let Some((w, h)) = calibrated.map(|c| c.image_size()) {
            if (w, h) != (camera.width, camera.height) {
                return Err(ReuseError::Unusable(format!(
                    "parameter set {resolved} calibrated {w}x{h} images, the session camera is {}x{}",
                    camera.width, camera.height
                )));
            }
        }
    }
    Ok(FixedCamera {
        calibration_id: resolved,
        intrinsics,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn ids_parse_as_serial_and_version() {
        assert_eq!(parse("IRB-001/3").unwrap(), ("IRB-001", Some(3)));
        assert_eq!(parse("IRB-001/latest").unwrap(), ("IRB-001", None));
        for bad in [
            "IRB-001",
            "IRB-001/0",
            "IRB-001/x",
            "/3",
            "a b/1",
            "IRB/1/2",
        ] {
            assert!(matches!(parse(bad), Err(ReuseError::Malformed(_))), "{bad}");
        }
    }
}
