//! What services read of a stored report's camera section: the size of the
//! images the camera was calibrated on (a reused calibration must match the
//! new camera) and the dots' reprojection RMS the job measured (a campaign
//! plan predicts with it). Typed here once, so no service reads the stored
//! report as untyped JSON.

use serde::Deserialize;

use crate::store::{DynStore, StoreError, StoreResult};

/// The part of a stored report read here.
#[derive(Deserialize)]
struct StoredReport {
    camera: Option<ReportCamera>,
}

/// A report's camera section, as far as it is read here.
#[derive(Debug, Clone, Copy, PartialEq, Deserialize)]
pub struct ReportCamera {
    pub image_width: u32,
    pub image_height: u32,
    /// `sqrt(mean |r|^2)` over the dots (2-D residual length, px); absent
    /// in reports that carry no camera fit.
    #[serde(default)]
    pub reprojection_rms_px: Option<f64>,
}

impl ReportCamera {
    pub fn image_size(&self) -> (u32, u32) {
        (self.image_width, self.image_height)
    }

    /// The dot noise per image axis (px) the job measured: the RMS is of
    /// the 2-D residual, so per axis it is `rms / sqrt 2`. `None` when not
    /// recorded or not a positive number.
    pub fn dot_noise_px(&self) -> Option<f64> {
        self.reprojection_rms_px
            .filter(|r| r.is_finite() && *r > 0.0)
            .map(|r| r / std::f64::consts::SQRT_2)
    }
}

/// The camera section of parameter set `version`'s report; `None` when the
/// set has no report or the report no camera section.
pub async fn report_camera(
    store: &DynStore,
    serial: &str,
    version: i64,
) -> StoreResult<Option<ReportCamera>> {
    let Some(report) = store.get_report(serial, version).await? else {
        return Ok(None);
    };
    let read: StoredReport = serde_json::from_value(report).map_err(|e| {
        StoreError::Backend(format!(
            "camera section of stored report {serial}/{version}: {e}"
        ))
    })?;
    Ok(read.camera)
}
