//! The cameras the simulator renders each preset's campaign with
//! (`robocal simulate`), shared by the CLI and the calib examples that
//! reproduce its campaigns.

use crate::camera::model::Intrinsics;

/// A simulated camera per preset: the IRB-2400 campaign uses a modern
/// 1280x1024 sensor (`fy/fx` = 1), the PUMA-560 one a camera like the
/// paper's, 752x582 with `fy/fx` = 0.9825 (issue 6).
/// Returns the intrinsics, the image size (px) and the pixel size (um).
pub fn rendered_camera(preset: &str) -> (Intrinsics, (u32, u32), f64) {
    match preset {
        "puma560" => (
            Intrinsics {
                fx: 1100.0,
                fy: 1100.0 * 0.9825,
                cx: 377.5,
                cy: 289.0,
                k1: -0.12,
                k2: 0.08,
                p1: 3e-4,
                p2: -2e-4,
                k3: 0.0,
            },
            (752, 582),
            8.6,
        ),
        _ => (
            Intrinsics {
                fx: 2100.0,
                fy: 2100.0,
                cx: 641.0,
                cy: 511.0,
                k1: -0.09,
                k2: 0.07,
                p1: 2e-4,
                p2: -1e-4,
                k3: 0.0,
            },
            (1280, 1024),
            5.3,
        ),
    }
}
