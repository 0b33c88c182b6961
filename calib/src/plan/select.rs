//! D-optimal selection: greedy, then exchange (Fedorov's), on the low-rank
//! pose factors of [`super::information`].
//!
//! With `P = M^-1` the inverse information so far, adding a pose with
//! factor `G` multiplies `det M` by `det(I + G P G^T)` and changes `P` by
//! Woodbury's identity, `P - W^T S^-1 W` with `W = G P`, `S = I + W G^T`:
//! one candidate costs `O(m p^2)` for `m <= 14` rows and `p` parameters,
//! never a `p x p` factorisation. Removing a pose is the same with the sign
//! of its information flipped.
//!
//! [`i_optimal_exchange`] minimises instead the predicted variance of the
//! camera position at validation poses (`tr(W P)`, `W = sum A_v^T A_v`; a
//! swap changes it by `-+ tr(S^-1 W_g W W_g^T)`). The planner does not use
//! it: on the simulator it chose poses at the edge of the image (a board
//! point left the image on the true robot) and did worse than D-optimal
//! (see docs/notes/session6-plan.md).
#![allow(clippy::needless_range_loop)] // the exchange writes back into `chosen[slot]`

use nalgebra::DMatrix;

/// Exchange passes at most (each tries every chosen pose once).
pub const EXCHANGE_PASSES: usize = 2;
/// A swap must raise `ln det M` by this much to be taken.
const EXCHANGE_MIN_GAIN: f64 = 1e-6;

/// `ln det(I + sign G P G^T)` and `W = G P`; `None` if not positive definite.
fn gain(
    p: &DMatrix<f64>,
    g: &DMatrix<f64>,
    sign: f64,
) -> Option<(f64, DMatrix<f64>, DMatrix<f64>)> {
    let w = g * p;
    let s = DMatrix::identity(g.nrows(), g.nrows()) + (&w * g.transpose()) * sign;
    let chol = s.clone().cholesky()?;
    let logdet = 2.0 * chol.l().diagonal().iter().map(|d| d.ln()).sum::<f64>();
    Some((logdet, w, s))
}

/// `P` after adding (`sign = 1`) or removing (`-1`) a pose with factor `g`.
fn update(p: &DMatrix<f64>, w: &DMatrix<f64>, s: &DMatrix<f64>, sign: f64) -> Option<DMatrix<f64>> {
    let s_inv_w = s.clone().cholesky()?.solve(w);
    Some(p - (w.transpose() * s_inv_w) * sign)
}

/// The best candidate (not in `taken`) to add to `p`, with its gain.
fn best_addition(
    p: &DMatrix<f64>,
    factors: &[DMatrix<f64>],
    taken: &[bool],
) -> Option<(usize, f64)> {
    factors
        .iter()
        .enumerate()
        .filter(|(k, _)| !taken[*k])
        .filter_map(|(k, g)| gain(p, g, 1.0).map(|(v, _, _)| (k, v)))
        .max_by(|a, b| a.1.total_cmp(&b.1))
}

/// Choose `count` of the candidates' factors maximising `ln det(prior +
/// sum G^T G)` (`prior = I` in the scaled units); returns their indices in
/// the order chosen. Fewer than `count` only if fewer candidates exist.
pub fn d_optimal(factors: &[DMatrix<f64>], parameters: usize, count: usize) -> Vec<usize> {
    let mut p = DMatrix::<f64>::identity(parameters, parameters);
    let mut taken = vec![false; factors.len()];
    let mut chosen = Vec::with_capacity(count);
    while chosen.len() < count {
        let Some((k, _)) = best_addition(&p, factors, &taken) else {
            break;
        };
        let Some((_, w, s)) = gain(&p, &factors[k], 1.0) else {
            break;
        };
        let Some(next) = update(&p, &w, &s, 1.0) else {
            break;
        };
        p = next;
        taken[k] = true;
        chosen.push(k);
    }
    for _ in 0..EXCHANGE_PASSES {
        let mut swapped = false;
        for slot in 0..chosen.len() {
            let out = chosen[slot];
            // P without the pose in this slot.
            let Some((loss, w, s)) = gain(&p, &factors[out], -1.0) else {
                continue;
            };
            let Some(without) = update(&p, &w, &s, -1.0) else {
                continue;
            };
            taken[out] = false;
            let back = -loss;
            let best = best_addition(&without, factors, &taken);
            let k = match best {
                Some((k, v)) if v > back + EXCHANGE_MIN_GAIN => k,
                _ => out,
            };
            let Some((_, w, s)) = gain(&without, &factors[k], 1.0) else {
                taken[out] = true;
                continue;
            };
            let Some(next) = update(&without, &w, &s, 1.0) else {
                taken[out] = true;
                continue;
            };
            swapped |= k != out;
            p = next;
            taken[k] = true;
            chosen[slot] = k;
        }
        if !swapped {
            break;
        }
    }
    chosen
}

/// `tr(S^-1 Wg W Wg^T)`: how much adding (`sign = 1`) or removing (`-1`)
/// the pose with factor `g` changes `tr(W P)` (in magnitude), with `Wg = G P`.
fn variance_change(
    p: &DMatrix<f64>,
    g: &DMatrix<f64>,
    weight: &DMatrix<f64>,
    sign: f64,
) -> Option<(f64, DMatrix<f64>, DMatrix<f64>)> {
    let w = g * p;
    let s = DMatrix::identity(g.nrows(), g.nrows()) + (&w * g.transpose()) * sign;
    let ww = &w * weight;
    let m = &ww * w.transpose();
    let chol = s.clone().cholesky()?;
    let change = chol.solve(&m).trace();
    Some((change, w, s))
}

/// The candidate (not in `taken`) whose addition to `p` lowers `tr(W P)` most.
fn best_for_variance(
    p: &DMatrix<f64>,
    factors: &[DMatrix<f64>],
    taken: &[bool],
    weight: &DMatrix<f64>,
) -> Option<(usize, f64)> {
    factors
        .iter()
        .enumerate()
        .filter(|(k, _)| !taken[*k])
        .filter_map(|(k, g)| variance_change(p, g, weight, 1.0).map(|(v, _, _)| (k, v)))
        .max_by(|a, b| a.1.total_cmp(&b.1))
}

/// Exchange passes on `chosen` minimising `tr(weight (prior + sum G^T
/// G)^-1)` (see the module doc); `chosen` keeps its length.
pub fn i_optimal_exchange(
    factors: &[DMatrix<f64>],
    parameters: usize,
    mut chosen: Vec<usize>,
    weight: &DMatrix<f64>,
) -> Vec<usize> {
    let mut m = DMatrix::<f64>::identity(parameters, parameters);
    for &k in &chosen {
        m += factors[k].transpose() * &factors[k];
    }
    let Some(mut p) = m.cholesky().map(|c| c.inverse()) else {
        return chosen;
    };
    let mut taken = vec![false; factors.len()];
    for &k in &chosen {
        taken[k] = true;
    }
    for _ in 0..EXCHANGE_PASSES {
        let mut swapped = false;
        for slot in 0..chosen.len() {
            let out = chosen[slot];
            let Some((loss, w, s)) = variance_change(&p, &factors[out], weight, -1.0) else {
                continue;
            };
            let Some(without) = update(&p, &w, &s, -1.0) else {
                continue;
            };
            taken[out] = false;
            // Putting it back lowers the variance by exactly what removing it raised.
            let k = match best_for_variance(&without, factors, &taken, weight) {
                Some((k, v)) if v > loss * (1.0 + EXCHANGE_MIN_GAIN) => k,
                _ => out,
            };
            let Some((_, w, s)) = gain(&without, &factors[k], 1.0) else {
                taken[out] = true;
                continue;
            };
            let Some(next) = update(&without, &w, &s, 1.0) else {
                taken[out] = true;
                continue;
            };
            swapped |= k != out;
            p = next;
            taken[k] = true;
            chosen[slot] = k;
        }
        if !swapped {
            break;
        }
    }
    chosen
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

    /// The rank-one updates agree with the direct determinant, and the
    /// selection beats every one of many random subsets.
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

    /// The exchange never raises the weighted variance it minimises.
    #[test]
    fn exchange_lowers_the_weighted_variance() {
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
        let better = i_optimal_exchange(&factors, p, start.clone(), &weight);
        assert_eq!(better.len(), 5);
        assert!(variance(&better) <= variance(&start) * (1.0 + 1e-12));
    }
}
