//! Selection on the low-rank pose factors of [`super::information`]:
//! greedy D-optimal (lazy, [`lazy_greedy`]), then exchange (Fedorov's)
//! passes, for either of two
//! criteria ([`Criterion`]): D (the determinant of the information) or I
//! (the predicted camera-position variance at validation poses, what a
//! job's validation error measures).
//!
//! With `P = M^-1` the inverse information so far, adding a pose with
//! factor `G` multiplies `det M` by `det(I + G P G^T)` and changes `P` by
//! Woodbury's identity, `P - W^T S^-1 W` with `W = G P`, `S = I + W G^T`:
//! one candidate costs `O(m p^2)` for `m <= 14` rows and `p` parameters,
//! never a `p x p` factorisation. Removing a pose is the same with the sign
//! of its information flipped, so one [`Woodbury`] step serves the greedy
//! additions and both halves of every exchange, for both criteria: the
//! I criterion's change is `tr(S^-1 W V W^T)` for the weight `V`.

use std::cmp::Reverse;
use std::collections::BinaryHeap;

use nalgebra::{Cholesky, DMatrix, Dyn};

/// Exchange passes at most (each tries every chosen pose once).
pub const EXCHANGE_PASSES: usize = 2;
/// A swap must improve the criterion by this fraction (at least this much
/// in absolute terms) to be taken.
const EXCHANGE_MIN_GAIN: f64 = 1e-6;

/// What a selection maximises.
#[derive(Debug, Clone, Copy)]
pub enum Criterion<'a> {
    /// `ln det M`: every parameter at once.
    D,
    /// `-tr(V P)`: the summed predicted variance of what `V = sum A^T A`
    /// weighs (the camera position at validation poses,
    /// [`super::predict::position_weight`]).
    I(&'a DMatrix<f64>),
}

/// Adding or removing one pose's information `G^T G`.
#[derive(Debug, Clone, Copy, PartialEq)]
enum Sign {
    Add,
    Remove,
}

impl Sign {
    fn value(self) -> f64 {
        match self {
            Sign::Add => 1.0,
            Sign::Remove => -1.0,
        }
    }
}

/// One Woodbury step, with how much it raises the criterion.
struct Woodbury {
    /// Change of the criterion (`ln det M`, or `-tr(V P)`).
    gain: f64,
    w: DMatrix<f64>,
    s: Cholesky<f64, Dyn>,
    sign: Sign,
}

impl Woodbury {
    /// `None` if `I + sign G P G^T` is not positive definite (removing a
    /// pose the information cannot lose, or a non-finite factor).
    fn new(p: &DMatrix<f64>, g: &DMatrix<f64>, sign: Sign, criterion: Criterion) -> Option<Self> {
        let w = g * p;
        let s = DMatrix::identity(g.nrows(), g.nrows()) + (&w * g.transpose()) * sign.value();
        let s = s.cholesky()?;
        let gain = match criterion {
            Criterion::D => 2.0 * s.l().diagonal().iter().map(|d| d.ln()).sum::<f64>(),
            // tr(V P) changes by -sign tr(S^-1 W V W^T).
            Criterion::I(v) => sign.value() * s.solve(&(&w * v * w.transpose())).trace(),
        };
        gain.is_finite().then_some(Self { gain, w, s, sign })
    }

    /// `P` after the step: `P - sign W^T S^-1 W`.
    fn apply(&self, p: &DMatrix<f64>) -> DMatrix<f64> {
        p - (self.w.transpose() * self.s.solve(&self.w)) * self.sign.value()
    }
}

/// The best candidate (not in `taken`) to add to `p`, with its gain.
fn best_addition(
    p: &DMatrix<f64>,
    factors: &[DMatrix<f64>],
    taken: &[bool],
    criterion: Criterion,
) -> Option<(usize, f64)> {
    factors
        .iter()
        .enumerate()
        .filter(|(k, _)| !taken[*k])
        .filter_map(|(k, g)| Woodbury::new(p, g, Sign::Add, criterion).map(|step| (k, step.gain)))
        .max_by(|a, b| a.1.total_cmp(&b.1))
}

/// One exchange of the pose in `chosen[slot]`: remove it, add back the best
/// candidate if it beats the removed pose by [`EXCHANGE_MIN_GAIN`], else the
/// removed pose. Returns whether the slot changed; `p`, `taken` and
/// `chosen` are left consistent either way.
fn exchange_slot(
    p: &mut DMatrix<f64>,
    factors: &[DMatrix<f64>],
    taken: &mut [bool],
    chosen: &mut [usize],
    slot: usize,
    criterion: Criterion,
) -> bool {
    let out = chosen[slot];
    let Some(removal) = Woodbury::new(p, &factors[out], Sign::Remove, criterion) else {
        return false;
    };
    let without = removal.apply(p);
    taken[out] = false;
    // Adding `out` back gains exactly what removing it lost.
    let back = -removal.gain;
    let k = match best_addition(&without, factors, taken, criterion) {
        Some((k, gain)) if gain > back + EXCHANGE_MIN_GAIN * back.abs().max(1.0) => k,
        _ => out,
    };
    let Some(addition) = Woodbury::new(&without, &factors[k], Sign::Add, criterion) else {
        taken[out] = true;
        return false;
    };
    *p = addition.apply(&without);
    taken[k] = true;
    chosen[slot] = k;
    k != out
}

/// Up to [`EXCHANGE_PASSES`] exchange passes on `chosen` (inverse
/// information `p`) for `criterion`; stops early when a pass swaps nothing.
fn exchange(
    p: &mut DMatrix<f64>,
    factors: &[DMatrix<f64>],
    taken: &mut [bool],
    chosen: &mut [usize],
    criterion: Criterion,
) {
    for _ in 0..EXCHANGE_PASSES {
        let mut swapped = false;
        for slot in 0..chosen.len() {
            swapped |= exchange_slot(p, factors, taken, chosen, slot, criterion);
        }
        if !swapped {
            break;
        }
    }
}

/// Choose `count` of the candidates' factors maximising `ln det(prior +
/// sum G^T G)` (`prior = I` in the scaled units) greedily, then exchange
/// for `criterion`; returns their indices. Fewer than `count` only if
/// fewer candidates exist.
pub fn select(
    factors: &[DMatrix<f64>],
    parameters: usize,
    count: usize,
    criterion: Criterion,
) -> Vec<usize> {
    select_after(&[], factors, parameters, count, criterion)
}

/// [`select`] after the poses a campaign already has (factors
/// `existing`): their information is in `P` from the start, so the
/// choice favours what they leave undetermined, and the exchange only
/// swaps the new poses (the existing ones are shot already).
pub fn select_after(
    existing: &[DMatrix<f64>],
    factors: &[DMatrix<f64>],
    parameters: usize,
    count: usize,
    criterion: Criterion,
) -> Vec<usize> {
    let mut p = DMatrix::<f64>::identity(parameters, parameters);
    for g in existing {
        if let Some(step) = Woodbury::new(&p, g, Sign::Add, Criterion::D) {
            p = step.apply(&p);
        }
    }
    let mut taken = vec![false; factors.len()];
    let mut chosen = lazy_greedy(&mut p, factors, &mut taken, count);
    // The exchange for the plan's own criterion only: an I plan starts its
    // exchange from the greedy D plan (a D exchange first would cost as
    // much again for little).
    exchange(&mut p, factors, &mut taken, &mut chosen, criterion);
    chosen
}

/// Greedy D-optimal additions, lazily: `ln det` is submodular (a pose's
/// gain only shrinks as others are added), so a gain computed earlier is
/// an upper bound, and a candidate whose fresh gain beats every other
/// bound is the greedy choice without re-evaluating the rest. Gains of
/// additions are `>= 0`, so their bit patterns order like the values.
fn lazy_greedy(
    p: &mut DMatrix<f64>,
    factors: &[DMatrix<f64>],
    taken: &mut [bool],
    count: usize,
) -> Vec<usize> {
    let mut bounds: BinaryHeap<(u64, Reverse<usize>)> = factors
        .iter()
        .enumerate()
        .filter(|(k, _)| !taken[*k])
        .filter_map(|(k, g)| {
            Woodbury::new(p, g, Sign::Add, Criterion::D)
                .map(|step| (step.gain.max(0.0).to_bits(), Reverse(k)))
        })
        .collect();
    let mut chosen = Vec::with_capacity(count);
    while chosen.len() < count {
        let Some((_, Reverse(k))) = bounds.pop() else {
            break;
        };
        let Some(step) = Woodbury::new(p, &factors[k], Sign::Add, Criterion::D) else {
            continue;
        };
        let fresh = step.gain.max(0.0).to_bits();
        if bounds.peek().is_none_or(|&(bound, _)| fresh >= bound) {
            *p = step.apply(p);
            taken[k] = true;
            chosen.push(k);
        } else {
            bounds.push((fresh, Reverse(k)));
        }
    }
    chosen
}

/// [`select`] for the D criterion.
pub fn d_optimal(factors: &[DMatrix<f64>], parameters: usize, count: usize) -> Vec<usize> {
    select(factors, parameters, count, Criterion::D)
}

#[cfg(test)]
mod tests {
    use super::*;
    use rand::{rngs::StdRng, Rng, SeedableRng};

    fn logdet(factors: &[DMatrix<f64>], chosen: &[usize], p: usize) -> f64 {
        let mut m = DMatrix::<f64>::identity(p, p);
        for &k in chosen {
            m += factors[k].transpose() * &factors[k];
        }
        m.cholesky()
            .unwrap()
            .l()
            .diagonal()
            .iter()
            .map(|d| 2.0 * d.ln())
            .sum()
    }

    /// One Woodbury step agrees with the direct inverse and determinant,
    /// and removing the pose again restores `P`.
    #[test]
    fn woodbury_step_matches_direct_inverse() {
        let mut rng = StdRng::seed_from_u64(3);
        let p = 7;
        let g = DMatrix::from_fn(3, p, |_, _| rng.random_range(-1.0..1.0));
        let start = DMatrix::<f64>::identity(p, p) * 0.5;
        let add = Woodbury::new(&start, &g, Sign::Add, Criterion::D).unwrap();
        let added = add.apply(&start);
        let direct = (start.clone().try_inverse().unwrap() + g.transpose() * &g)
            .try_inverse()
            .unwrap();
        assert!((&added - &direct).amax() < 1e-12);
        let det_ratio = direct.determinant().recip() * start.determinant();
        assert!((add.gain - det_ratio.ln()).abs() < 1e-10);
        let removed = Woodbury::new(&added, &g, Sign::Remove, Criterion::D)
            .unwrap()
            .apply(&added);
        assert!((&removed - &start).amax() < 1e-12);
    }

    /// The selection beats every one of many random subsets.
    #[test]
    fn selection_beats_random_subsets() {
        let mut rng = StdRng::seed_from_u64(7);
        let p = 8;
        let factors: Vec<DMatrix<f64>> = (0..60)
            .map(|_| DMatrix::from_fn(2, p, |_, _| rng.random_range(-1.0..1.0)))
            .collect();
        let chosen = d_optimal(&factors, p, 6);
        assert_eq!(chosen.len(), 6);
        let best = logdet(&factors, &chosen, p);
        for _ in 0..200 {
            let mut idx: Vec<usize> = (0..60).collect();
            for i in 0..6 {
                let j = rng.random_range(i..60);
                idx.swap(i, j);
            }
            assert!(logdet(&factors, &idx[..6], p) <= best + 1e-9);
        }
    }

    /// Seeded by existing poses, the greedy choice is the greedy choice
    /// on the existing information: the first pick maximises `ln det(I +
    /// E + G^T G)`, which differs from the unseeded pick here (the existing
    /// poses already carry the directions it favoured).
    #[test]
    fn existing_poses_seed_the_selection() {
        let mut rng = StdRng::seed_from_u64(11);
        let p = 6;
        let factors: Vec<DMatrix<f64>> = (0..40)
            .map(|_| DMatrix::from_fn(2, p, |_, _| rng.random_range(-1.0..1.0)))
            .collect();
        let plain = d_optimal(&factors, p, 1)[0];
        // Existing poses that carry exactly the plain pick's directions, strongly.
        let existing = vec![&factors[plain] * 30.0];
        let seeded = select_after(&existing, &factors, p, 1, Criterion::D)[0];
        assert_ne!(seeded, plain);
        let with = |k: usize| {
            let mut m = DMatrix::<f64>::identity(p, p);
            m += existing[0].transpose() * &existing[0];
            m += factors[k].transpose() * &factors[k];
            m.determinant().ln()
        };
        let best = (0..factors.len()).map(with).fold(f64::MIN, f64::max);
        assert!((with(seeded) - best).abs() < 1e-9);
    }

    /// The I exchange never raises the weighted variance it minimises, and
    /// its step's gain is the exact change of `tr(V P)`.
    #[test]
    fn i_exchange_lowers_the_weighted_variance() {
        let mut rng = StdRng::seed_from_u64(9);
        let p = 6;
        let factors: Vec<DMatrix<f64>> = (0..50)
            .map(|_| DMatrix::from_fn(2, p, |_, _| rng.random_range(-1.0..1.0)))
            .collect();
        let a = DMatrix::from_fn(3, p, |r, c| {
            if c < 4 {
                (r + c) as f64 * 0.3 - 0.5
            } else {
                0.0
            }
        });
        let weight = a.transpose() * a;
        let variance = |chosen: &[usize]| {
            let mut m = DMatrix::<f64>::identity(p, p);
            for &k in chosen {
                m += factors[k].transpose() * &factors[k];
            }
            (&weight * m.try_inverse().unwrap()).trace()
        };
        let start = d_optimal(&factors, p, 5);
        let better = select(&factors, p, 5, Criterion::I(&weight));
        assert_eq!(better.len(), 5);
        assert!(variance(&better) <= variance(&start) * (1.0 + 1e-12));
        let id = DMatrix::<f64>::identity(p, p);
        let step = Woodbury::new(&id, &factors[0], Sign::Add, Criterion::I(&weight)).unwrap();
        let direct = variance(&[]) - variance(&[0]);
        assert!((step.gain - direct).abs() < 1e-12 * direct.abs().max(1.0));
    }
}
