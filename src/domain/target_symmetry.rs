//! Boards whose images fix the feature order only up to a turn (issue 14):
//! a chessboard with both sides even or both odd (a half turn), a dot grid
//! without its origin marker (a half turn; also quarter turns when square),
//! an asymmetric circle grid with an even number of rows (a half turn). The
//! detector reads such a board one way; the job settles each image's turn
//! from the robot data (`pipeline::board_turn`). This file says which turns
//! map the board onto itself and how a turn relabels its features.

use std::collections::HashMap;

use nalgebra::{Isometry3, Point3, Translation3, UnitQuaternion, Vector3};

use super::target::Target;

/// Board coordinates are compared after rounding to this many mm (far
/// below any feature spacing, far above floating-point error).
const COORDINATE_QUANTUM_MM: f64 = 1e-3;

/// The turns of a board that look the same in an image.
#[derive(Debug, Clone)]
pub struct BoardSymmetry {
    /// Quarter turns (1..=3) about the board's centre (+x towards +y) that
    /// map the board onto itself: `[2]`, or `[1, 2, 3]` for a square grid.
    pub turns: Vec<u8>,
    /// Centre of the features' bounding box, target frame, mm.
    centre_mm: [f64; 2],
    /// Every feature by its rounded position.
    labels: HashMap<(i64, i64), (u32, u32)>,
    /// Inner corners `[cols, rows]` or dots per row and rows.
    size: (u32, u32),
    /// What the board is: "chessboard", "dot grid without an origin marker".
    kind: &'static str,
    /// The session field the refusal names.
    pub field: &'static str,
    /// What to use instead, for the refusal.
    pub advice: &'static str,
}

fn key(x: f64, y: f64) -> (i64, i64) {
    (
        (x / COORDINATE_QUANTUM_MM).round() as i64,
        (y / COORDINATE_QUANTUM_MM).round() as i64,
    )
}

impl BoardSymmetry {
    /// `p_old = turn(k) * p_new`: the board-frame motion of a turn by `k`
    /// quarter turns about the board's centre.
    pub fn turn(&self, quarter_turns: u8) -> Isometry3<f64> {
        let c = Vector3::new(self.centre_mm[0], self.centre_mm[1], 0.0);
        let angle = f64::from(quarter_turns % 4) * std::f64::consts::FRAC_PI_2;
        Translation3::from(c)
            * UnitQuaternion::from_axis_angle(&Vector3::z_axis(), angle)
            * Translation3::from(-c)
    }

    /// After a view is turned by `quarter_turns` (its board frame moved by
    /// [`Self::turn`]), the label and position of the feature the view had
    /// at `p`; `None` if the turn does not map `p` onto a feature.
    pub fn relabel(&self, quarter_turns: u8, p: &Point3<f64>) -> Option<((u32, u32), Point3<f64>)> {
        let q = self.turn(quarter_turns) * p;
        let label = *self.labels.get(&key(q.x, q.y))?;
        Some((label, q))
    }

    /// Whether every feature is a key (the position of each feature is
    /// needed by `relabel`).
    fn maps_onto_itself(&self, quarter_turns: u8) -> bool {
        self.labels.keys().all(|&(x, y)| {
            let p = Point3::new(
                x as f64 * COORDINATE_QUANTUM_MM,
                y as f64 * COORDINATE_QUANTUM_MM,
                0.0,
            );
            self.relabel(quarter_turns, &p).is_some()
        })
    }

    /// What the refusal and the report call the turn: "a half turn" or
    /// "a quarter or half turn".
    pub fn turn_words(&self) -> &'static str {
        if self.turns == [2] {
            "a half turn"
        } else {
            "a quarter or half turn"
        }
    }

    /// The board as the refusal names it: "8 x 6 chessboard" (`cols x rows`).
    pub fn board_words(&self) -> String {
        format!("{} x {} {}", self.size.0, self.size.1, self.kind)
    }
}

impl Target {
    /// The turns an image cannot tell apart on this board, `None` when its
    /// order is unique (an origin marker, ChArUco's ids, a chessboard with
    /// one odd and one even side, an asymmetric grid with odd rows).
    pub fn symmetry(&self) -> Option<BoardSymmetry> {
        let (cols, rows, kind, field, advice, candidates): (usize, usize, _, _, _, &[u8]) =
            match self {
                Target::Chessboard(t) if t.ambiguous_180() => (
                    t.cols(),
                    t.rows(),
                    "chessboard",
                    "target.inner_corners",
                    "use a board with one odd and one even side",
                    &[2],
                ),
                Target::Dots(t) if t.origin_marker_diameter_mm.is_none() => (
                    t.cols,
                    t.rows,
                    "dot grid without an origin marker",
                    "target.origin_marker_diameter_mm",
                    "use a board with an origin marker",
                    &[1, 2, 3],
                ),
                Target::AsymmetricCircles(t) if t.rows % 2 == 0 => (
                    t.cols,
                    t.rows,
                    "asymmetric circle grid",
                    "target.rows",
                    "use an asymmetric grid with an odd number of rows",
                    &[2],
                ),
                _ => return None,
            };
        let mut labels = HashMap::with_capacity(cols * rows);
        let (mut lo, mut hi) = ([f64::INFINITY; 2], [f64::NEG_INFINITY; 2]);
        for row in 0..rows as u32 {
            for col in 0..cols as u32 {
                let [x, y, _] = self.point_mm(row, col);
                labels.insert(key(x, y), (row, col));
                lo = [lo[0].min(x), lo[1].min(y)];
                hi = [hi[0].max(x), hi[1].max(y)];
            }
        }
        let mut symmetry = BoardSymmetry {
            turns: Vec::new(),
            centre_mm: [(lo[0] + hi[0]) / 2.0, (lo[1] + hi[1]) / 2.0],
            labels,
            size: (cols as u32, rows as u32),
            kind,
            field,
            advice,
        };
        symmetry.turns = candidates
            .iter()
            .copied()
            .filter(|&k| symmetry.maps_onto_itself(k))
            .collect();
        (!symmetry.turns.is_empty()).then_some(symmetry)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use robocal_calib::vision::chessboard::ChessboardSpec;
    use robocal_calib::vision::{AsymmetricCirclesSpec, TargetSpec};

    fn dots(rows: usize, cols: usize, marker: Option<f64>) -> Target {
        Target::Dots(TargetSpec {
            rows,
            cols,
            pitch_mm: 20.0,
            dot_diameter_mm: 8.0,
            origin_marker_diameter_mm: marker,
        })
    }

    #[test]
    fn turns_are_the_ones_that_map_the_board_onto_itself() {
        let chess = |cols, rows| {
            Target::Chessboard(ChessboardSpec {
                inner_corners: [cols, rows],
                square_mm: 25.0,
            })
        };
        let asym = |rows| {
            Target::AsymmetricCircles(AsymmetricCirclesSpec {
                rows,
                cols: 4,
                pitch_mm: 20.0,
                dot_diameter_mm: 8.0,
            })
        };
        let turns = |t: Target| t.symmetry().map(|s| s.turns);
        assert_eq!(turns(chess(8, 6)), Some(vec![2]));
        assert_eq!(turns(chess(7, 5)), Some(vec![2]));
        assert_eq!(turns(chess(9, 6)), None);
        assert_eq!(turns(dots(7, 9, None)), Some(vec![2]));
        assert_eq!(turns(dots(10, 10, None)), Some(vec![1, 2, 3]));
        assert_eq!(turns(dots(7, 9, Some(12.0))), None);
        assert_eq!(turns(asym(10)), Some(vec![2]));
        assert_eq!(turns(asym(11)), None);
    }

    #[test]
    fn a_turn_relabels_each_feature_to_the_one_now_in_its_place() {
        let t = dots(7, 9, None);
        let s = t.symmetry().unwrap();
        let p = |row, col| {
            let [x, y, z] = t.point_mm(row, col);
            Point3::new(x, y, z)
        };
        // Half turn: (row, col) -> (rows-1-row, cols-1-col).
        assert_eq!(s.relabel(2, &p(1, 2)).unwrap().0, (5, 6));
        assert_eq!(s.relabel(2, &p(0, 0)).unwrap().0, (6, 8));
        let square = dots(5, 5, None);
        let s = square.symmetry().unwrap();
        let [x, y, z] = square.point_mm(0, 0);
        let (label, q) = s.relabel(1, &Point3::new(x, y, z)).unwrap();
        // +x towards +y about the centre (40, 40): (0, 0) -> (80, 0).
        assert_eq!(label, (0, 4));
        assert!((q - Point3::new(80.0, 0.0, 0.0)).norm() < 1e-9);
        // Four quarter turns are none.
        let mut q = Point3::new(x, y, z);
        for _ in 0..4 {
            q = s.relabel(1, &q).unwrap().1;
        }
        assert!((q - Point3::new(x, y, z)).norm() < 1e-9);
    }

    /// A marker-less grid's image is read (one of its two readings) and its
    /// turn left to the job, not refused at upload as ambiguous.
    #[test]
    fn a_marker_less_grid_is_read_for_the_job_to_settle_its_turn() {
        use nalgebra::{Isometry3, Translation3, UnitQuaternion};
        use rand::SeedableRng;
        use robocal_calib::sim::render::RenderOptions;
        use robocal_calib::sim::render_circles::render_target;
        use robocal_calib::sim::views::reference_camera;

        let Target::Dots(spec) = dots(7, 9, None) else {
            unreachable!()
        };
        let centre = Vector3::new(4.0 * spec.pitch_mm, 3.0 * spec.pitch_mm, 0.0);
        let camera_to_target = Isometry3::from_parts(
            Translation3::new(0.0, 0.0, 900.0),
            UnitQuaternion::from_axis_angle(&Vector3::x_axis(), 0.3),
        ) * Translation3::from(-centre);
        let mut rng = rand::rngs::StdRng::seed_from_u64(7);
        let view = render_target(
            &reference_camera(),
            &camera_to_target,
            &spec,
            1280,
            1024,
            &RenderOptions::default(),
            &mut rng,
        )
        .unwrap();
        let found = Target::Dots(spec).detect(&view.image.into()).unwrap();
        assert_eq!(found.len(), 63);
    }
}
