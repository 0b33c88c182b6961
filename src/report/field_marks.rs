//! The marks of the residual field chart and its key: the arrow of a
//! residual and the shading ramp of a cell's RMS.

use super::plot::Svg;

/// Cells averaging fewer residuals are shaded but get no arrow (too noisy).
pub const MIN_CELL_SAMPLES: usize = 4;
pub const ARROW_COLOR: &str = "#111";
const HEAD_ANGLE_RAD: f64 = 0.45;
const HEAD_LENGTH: f64 = 4.0;
/// Shading ramp for the per-cell RMS: light grey to lavender.
const RAMP_LOW: [f64; 3] = [250.0, 250.0, 250.0];
const RAMP_HIGH: [f64; 3] = [150.0, 140.0, 205.0];

/// The ramp colour at `t` in [0, 1] (light grey to lavender).
pub fn ramp(t: f64) -> String {
    let t = if t.is_finite() {
        t.clamp(0.0, 1.0)
    } else {
        0.0
    };
    let c: Vec<u8> = (0..3)
        .map(|i| (RAMP_LOW[i] + t * (RAMP_HIGH[i] - RAMP_LOW[i])).round() as u8)
        .collect();
    format!("#{:02x}{:02x}{:02x}", c[0], c[1], c[2])
}

pub fn arrow(svg: &mut Svg, x0: f64, y0: f64, x1: f64, y1: f64) {
    let (dx, dy) = (x1 - x0, y1 - y0);
    let len = (dx * dx + dy * dy).sqrt();
    if len < 0.5 {
        svg.circle(x0, y0, 0.8, ARROW_COLOR);
        return;
    }
    let head = HEAD_LENGTH.min(0.4 * len);
    let back = dy.atan2(dx) + std::f64::consts::PI;
    let (ha, hb) = (back + HEAD_ANGLE_RAD, back - HEAD_ANGLE_RAD);
    let d = format!(
        "M{x0:.1} {y0:.1}L{x1:.1} {y1:.1}M{:.1} {:.1}L{x1:.1} {y1:.1}L{:.1} {:.1}",
        x1 + head * ha.cos(),
        y1 + head * ha.sin(),
        x1 + head * hb.cos(),
        y1 + head * hb.sin()
    );
    svg.path(&d, ARROW_COLOR, 1.0, "none");
}
