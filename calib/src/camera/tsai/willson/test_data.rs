//! Willson's sample data and published camera files
//! (`calib/tests/data/tsai/willson_v3.0b3/`), shared by the Tsai tests.

use super::model::{parse_points, TsaiModel, TsaiPoint};

const DATA: &str = concat!(
    env!("CARGO_MANIFEST_DIR"),
    "/tests/data/tsai/willson_v3.0b3/"
);
/// Willson's initial image-centre guess for the Photometrics Star I (px).
pub(crate) const INITIAL_CENTRE: (f64, f64) = (258.0, 204.0);

/// Points of a `*_cd.dat` file.
pub(crate) fn load(name: &str) -> Vec<TsaiPoint> {
    parse_points(&std::fs::read_to_string(format!("{DATA}{name}")).unwrap()).unwrap()
}

/// The 19-number camera file (`Ncx .. p2`), 11 significant digits.
pub(crate) fn published(file: &str) -> TsaiModel {
    let v: Vec<f64> = std::fs::read_to_string(format!("{DATA}{file}"))
        .unwrap()
        .split_whitespace()
        .map(|t| t.parse().unwrap())
        .collect();
    TsaiModel {
        cx: v[6],
        cy: v[7],
        sx: v[8],
        f_mm: v[9],
        kappa1: v[10],
        tx: v[11],
        ty: v[12],
        tz: v[13],
        rx: v[14],
        ry: v[15],
        rz: v[16],
    }
}
