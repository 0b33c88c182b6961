//! Conversion between the API's joint table ([`KinematicsDoc`]) and the
//! numerics' robot model, preset expansion, and the convention rule.

use crate::schema::robot::{Convention, KinematicsDoc, Preset, PARALLEL_ALPHA_RAD};

/// The convention the service picks when a joint gives none: a link between
/// two parallel axes (`|alpha| < 1e-6 rad`) gets Hayati's beta instead of d,
/// because d is not identifiable there (method.md, kinematic model).
pub fn auto_convention(alpha_deg: f64) -> Convention {
    if alpha_deg.to_radians().abs() < PARALLEL_ALPHA_RAD {
        Convention::Hayati
    } else {
        Convention::Dh
    }
}

/// The nominal joint table of a preset.
pub fn preset_doc(preset: Preset) -> KinematicsDoc {
    // Filled from robocal_calib::kinematics::presets once the core lands.
    let _ = preset;
    KinematicsDoc { joints: vec![] }
}
