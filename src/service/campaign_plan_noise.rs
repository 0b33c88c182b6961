//! The dot noise a campaign plan predicts with (issue 16: "dot noise from
//! the robot's earlier jobs, or a stated default"). In order: the request's
//! `sigma_px`; else the noise the robot's newest earlier camera job
//! measured on images of the plan's size (its report's reprojection RMS per
//! image axis); else [`DEFAULT_SIGMA_PX`]. The plan says which.

use robocal_calib::plan::request::DEFAULT_SIGMA_PX;

use super::error::ServiceResult;
use super::report_camera::report_camera;
use crate::store::DynStore;

/// Newest parameter sets of the robot searched for a measured dot noise
/// (tracker calibrations and hand–eye sets in between carry none).
pub const NOISE_LOOKBACK_SETS: i64 = 20;
/// [`DotNoise::source`] of a noise the request stated.
pub const SOURCE_REQUEST: &str = "request";
/// [`DotNoise::source`] of the stated default.
pub const SOURCE_DEFAULT: &str = "default";

/// The dot noise (px per axis) and where it came from: [`SOURCE_REQUEST`],
/// [`SOURCE_DEFAULT`], or the parameter set `"{serial}/{version}"` whose
/// job measured it.
#[derive(Debug, Clone, PartialEq)]
pub struct DotNoise {
    pub sigma_px: f64,
    pub source: String,
}

/// The dot noise for a plan of robot `serial` on images of `image_size_px`.
/// A job on another image size (another camera) does not tell this one's
/// noise and is skipped.
pub async fn dot_noise(
    store: &DynStore,
    serial: &str,
    requested_px: Option<f64>,
    image_size_px: (u32, u32),
) -> ServiceResult<DotNoise> {
    if let Some(sigma_px) = requested_px {
        return Ok(DotNoise {
            sigma_px,
            source: SOURCE_REQUEST.to_string(),
        });
    }
    let sets = store
        .list_parameter_sets(serial, NOISE_LOOKBACK_SETS, None)
        .await?;
    for set in sets.items {
        let measured = report_camera(store, serial, set.version)
            .await?
            .filter(|c| c.image_size() == image_size_px)
            .and_then(|c| c.dot_noise_px());
        if let Some(sigma_px) = measured {
            return Ok(DotNoise {
                sigma_px,
                source: format!("{serial}/{}", set.version),
            });
        }
    }
    Ok(DotNoise {
        sigma_px: DEFAULT_SIGMA_PX,
        source: SOURCE_DEFAULT.to_string(),
    })
}
