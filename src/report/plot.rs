//! A small hand-written plotting kit for the report charts: linear and
//! logarithmic scales with "nice" ticks (1-2-5 steps, decades), axes with
//! ticks, grid and units, and legends (drawn with `svg_writer`). No
//! dependencies.

pub use super::svg_writer::*;

/// Gap between tick marks and their labels.
const TICK_LABEL_GAP: f64 = 3.0;
/// Distance of the rotated y-axis label from the plot's left edge.
const Y_LABEL_OFFSET: f64 = 46.0;
/// Distance of the x-axis label below the plot's bottom edge.
const X_LABEL_OFFSET: f64 = 32.0;

/// The plotting rectangle of a chart, in SVG user units.
#[derive(Debug, Clone, Copy)]
pub struct Area {
    pub x: f64,
    pub y: f64,
    pub w: f64,
    pub h: f64,
}

impl Area {
    pub fn bottom(&self) -> f64 {
        self.y + self.h
    }
    pub fn right(&self) -> f64 {
        self.x + self.w
    }
}

/// A map from data values to one SVG coordinate.
#[derive(Debug, Clone, Copy)]
pub struct Scale {
    pub log: bool,
    pub lo: f64,
    pub hi: f64,
    pub start: f64,
    pub end: f64,
}

/// Errors spanning more than this ratio (max / min) get a log axis, so
/// that 0.05 mm after and 3 mm before are both readable.
pub const LOG_RATIO_THRESHOLD: f64 = 8.0;
/// Most tick intervals on a linear axis.
pub const MAX_TICKS: usize = 6;

impl Scale {
    /// A linear scale over [lo, hi] (extended to nice tick values).
    pub fn linear(lo: f64, hi: f64, start: f64, end: f64) -> Self {
        let (lo, hi) = if hi > lo { (lo, hi) } else { (lo, lo + 1.0) };
        let step = nice_step((hi - lo) / MAX_TICKS as f64);
        let (lo, hi) = ((lo / step).floor() * step, (hi / step).ceil() * step);
        Scale {
            log: false,
            lo,
            hi,
            start,
            end,
        }
    }

    /// A log10 scale over whole decades enclosing [lo, hi] (both > 0).
    pub fn log(lo: f64, hi: f64, start: f64, end: f64) -> Self {
        let lo = 10f64.powf(lo.log10().floor());
        let mut hi = 10f64.powf(hi.log10().ceil());
        if hi <= lo {
            hi = lo * 10.0;
        }
        Scale {
            log: true,
            lo,
            hi,
            start,
            end,
        }
    }

    /// Linear from zero, or log when positive values span more than
    /// [`LOG_RATIO_THRESHOLD`]. Non-finite and non-positive values are ignored.
    pub fn for_magnitudes(values: &[f64], start: f64, end: f64) -> Self {
        let positive: Vec<f64> = values
            .iter()
            .copied()
            .filter(|v| v.is_finite() && *v > 0.0)
            .collect();
        let lo = positive.iter().copied().fold(f64::INFINITY, f64::min);
        let hi = positive.iter().copied().fold(0.0, f64::max);
        if positive.is_empty() {
            Scale::linear(0.0, 1.0, start, end)
        } else if hi / lo > LOG_RATIO_THRESHOLD {
            Scale::log(lo, hi, start, end)
        } else {
            Scale::linear(0.0, hi, start, end)
        }
    }

    fn fraction(&self, value: f64) -> f64 {
        if self.log {
            let v = value.max(self.lo * 1e-3);
            (v.log10() - self.lo.log10()) / (self.hi.log10() - self.lo.log10())
        } else {
            (value - self.lo) / (self.hi - self.lo)
        }
    }

    /// The coordinate of `value`, clamped to the axis ends.
    pub fn map(&self, value: f64) -> f64 {
        let f = if value.is_finite() {
            self.fraction(value).clamp(0.0, 1.0)
        } else {
            0.0
        };
        self.start + f * (self.end - self.start)
    }

    /// A linear scale over exactly [lo, hi] (image coordinates: the axis
    /// must end at the image border, ticks fall inside).
    pub fn exact(lo: f64, hi: f64, start: f64, end: f64) -> Self {
        let hi = if hi > lo { hi } else { lo + 1.0 };
        Scale {
            log: false,
            lo,
            hi,
            start,
            end,
        }
    }

    /// Major ticks (labelled) and minor ticks (unlabelled) of the axis.
    pub fn ticks(&self) -> Vec<Tick> {
        if self.log {
            return log_ticks(self.lo, self.hi);
        }
        let step = nice_step((self.hi - self.lo) / MAX_TICKS as f64);
        let first = (self.lo / step - 1e-9).ceil() as i64;
        let last = (self.hi / step + 1e-9).floor() as i64;
        (first..=last)
            .map(|i| {
                let value = i as f64 * step;
                Tick {
                    value,
                    label: Some(tick_label(value, step)),
                }
            })
            .collect()
    }
}

#[derive(Debug, Clone, PartialEq)]
pub struct Tick {
    pub value: f64,
    /// None for a minor tick.
    pub label: Option<String>,
}

/// The smallest 1, 2 or 5 times a power of ten that is >= `raw`.
pub fn nice_step(raw: f64) -> f64 {
    if !raw.is_finite() || raw <= 0.0 {
        return 1.0;
    }
    let power = 10f64.powf(raw.log10().floor());
    let mantissa = raw / power;
    let nice = [1.0, 2.0, 5.0, 10.0]
        .into_iter()
        .find(|m| *m >= mantissa - 1e-9)
        .unwrap_or(10.0);
    nice * power
}

/// A tick value with just enough decimals for its step (0.05 -> "0.05").
pub fn tick_label(value: f64, step: f64) -> String {
    let decimals = (-step.log10().floor()).max(0.0) as usize;
    let text = format!("{value:.decimals$}");
    if text.starts_with('-') && text.trim_start_matches(['-', '0', '.']).is_empty() {
        text[1..].to_string()
    } else {
        text
    }
}

/// Decades labelled; 2 and 5 labelled too when the axis spans at most
/// two decades; the other integers as minor ticks.
fn log_ticks(lo: f64, hi: f64) -> Vec<Tick> {
    let first = lo.log10().round() as i32;
    let last = hi.log10().round() as i32;
    let label_2_5 = last - first <= 2;
    let mut ticks = Vec::new();
    for decade in first..=last {
        let base = 10f64.powi(decade);
        let multipliers = if decade == last { 1..=1 } else { 1..=9 };
        for m in multipliers {
            let value = base * m as f64;
            let labelled = m == 1 || (label_2_5 && (m == 2 || m == 5));
            let label = labelled.then(|| tick_label(value, base.min(1.0)));
            ticks.push(Tick { value, label });
        }
    }
    ticks
}

/// Left value axis: ticks, labels, horizontal grid lines, rotated label.
pub fn y_axis(svg: &mut Svg, area: Area, scale: &Scale, label: &str) {
    for tick in scale.ticks() {
        let y = scale.map(tick.value);
        let major = tick.label.is_some();
        if major {
            svg.line(area.x, y, area.right(), y, GRID_COLOR, 1.0);
        }
        let len = if major {
            TICK_LENGTH
        } else {
            TICK_LENGTH * 0.6
        };
        svg.line(area.x - len, y, area.x, y, AXIS_COLOR, 1.0);
        if let Some(text) = tick.label {
            let x = area.x - TICK_LENGTH - TICK_LABEL_GAP;
            svg.text(x, y + FONT_SIZE * 0.35, "end", FONT_SIZE, TEXT_COLOR, &text);
        }
    }
    svg.line(area.x, area.y, area.x, area.bottom(), AXIS_COLOR, 1.0);
    let cy = area.y + area.h / 2.0;
    svg.rotated_text(area.x - Y_LABEL_OFFSET, cy, -90.0, "middle", label);
}

/// Bottom value axis: ticks, labels, vertical grid lines, label.
pub fn x_axis(svg: &mut Svg, area: Area, scale: &Scale, label: &str) {
    for tick in scale.ticks() {
        let x = scale.map(tick.value);
        let major = tick.label.is_some();
        if major {
            svg.line(x, area.y, x, area.bottom(), GRID_COLOR, 1.0);
        }
        let len = if major {
            TICK_LENGTH
        } else {
            TICK_LENGTH * 0.6
        };
        svg.line(x, area.bottom(), x, area.bottom() + len, AXIS_COLOR, 1.0);
        if let Some(text) = tick.label {
            let y = area.bottom() + TICK_LENGTH + TICK_LABEL_GAP + FONT_SIZE;
            svg.text(x, y, "middle", FONT_SIZE, TEXT_COLOR, &text);
        }
    }
    svg.line(
        area.x,
        area.bottom(),
        area.right(),
        area.bottom(),
        AXIS_COLOR,
        1.0,
    );
    svg.text(
        area.x + area.w / 2.0,
        area.bottom() + X_LABEL_OFFSET,
        "middle",
        FONT_SIZE,
        TEXT_COLOR,
        label,
    );
}

/// How a legend entry is drawn.
#[derive(Debug, Clone, Copy)]
pub enum Mark<'a> {
    Dot(&'a str),
    Swatch(&'a str),
    Dash(&'a str),
    /// Explanatory text only.
    Text,
}

const LEGEND_SWATCH: f64 = 10.0;
const LEGEND_CHAR_WIDTH: f64 = 6.2;
const LEGEND_GAP: f64 = 18.0;

/// A one-row legend starting at (x, y) (y = text baseline).
pub fn legend(svg: &mut Svg, x: f64, y: f64, entries: &[(Mark, &str)]) {
    let mut cursor = x;
    for (mark, label) in entries {
        let cy = y - FONT_SIZE * 0.35;
        match mark {
            Mark::Dot(color) => svg.circle(cursor + LEGEND_SWATCH / 2.0, cy, 4.0, color),
            Mark::Swatch(color) => {
                let half = LEGEND_SWATCH / 2.0;
                svg.rect(cursor, cy - half, LEGEND_SWATCH, LEGEND_SWATCH, color, 0.75)
            }
            Mark::Dash(color) => {
                svg.dashed_line(cursor - 4.0, cy, cursor + LEGEND_SWATCH + 4.0, cy, color)
            }
            Mark::Text => {}
        }
        let text_x = if matches!(mark, Mark::Text) {
            cursor
        } else {
            cursor + LEGEND_SWATCH + 6.0
        };
        svg.text(text_x, y, "start", FONT_SIZE, TEXT_COLOR, label);
        cursor = text_x + label.chars().count() as f64 * LEGEND_CHAR_WIDTH + LEGEND_GAP;
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn nice_steps_are_1_2_5() {
        assert_eq!(nice_step(0.37), 0.5);
        assert_eq!(nice_step(1.2), 2.0);
        assert_eq!(nice_step(7.0), 10.0);
        assert_eq!(nice_step(0.02), 0.02);
    }

    #[test]
    fn linear_ticks_cover_the_data() {
        let s = Scale::linear(0.0, 2.83, 0.0, 100.0);
        let labels: Vec<String> = s.ticks().into_iter().filter_map(|t| t.label).collect();
        assert_eq!(labels, ["0.0", "0.5", "1.0", "1.5", "2.0", "2.5", "3.0"]);
        assert_eq!(s.map(3.0), 100.0);
    }

    #[test]
    fn wide_spread_gets_log_decades() {
        let s = Scale::for_magnitudes(&[0.05, 0.12, 2.9], 300.0, 0.0);
        assert!(s.log);
        assert_eq!((s.lo, s.hi), (0.01, 10.0));
        let labels: Vec<String> = s.ticks().into_iter().filter_map(|t| t.label).collect();
        assert_eq!(labels, ["0.01", "0.1", "1", "10"]);
        assert!((s.map(0.1) - 200.0).abs() < 1e-9);
    }

    #[test]
    fn narrow_log_axis_labels_2_and_5() {
        let s = Scale::for_magnitudes(&[0.3, 4.0], 0.0, 100.0);
        assert!(s.log);
        let labels: Vec<String> = s.ticks().into_iter().filter_map(|t| t.label).collect();
        assert_eq!(labels, ["0.1", "0.2", "0.5", "1", "2", "5", "10"]);
        assert_eq!(s.ticks().len(), 19);
    }

    #[test]
    fn exact_scale_ends_at_the_image_border() {
        let s = Scale::exact(0.0, 1024.0, 0.0, 512.0);
        assert_eq!(s.map(1024.0), 512.0);
        let last = s.ticks().last().unwrap().value;
        assert_eq!(last, 1000.0);
    }

    #[test]
    fn degenerate_input_does_not_panic() {
        let s = Scale::for_magnitudes(&[f64::NAN, 0.0], 0.0, 10.0);
        assert!(!s.ticks().is_empty());
        assert!(s.map(f64::INFINITY).is_finite());
    }
}
