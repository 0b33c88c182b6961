//! Ordering the chosen poses into a short joint-space path: nearest
//! neighbour from the start, then 2-opt. A point-to-point move takes as
//! long as its slowest joint, so the distance is the largest joint change.

/// Largest absolute joint difference (rad).
pub fn joint_distance(a: &[f64], b: &[f64]) -> f64 {
    a.iter()
        .zip(b)
        .map(|(x, y)| (x - y).abs())
        .fold(0.0, f64::max)
}

/// Length of the open path from `start` through `poses` in `order`.
pub fn path_length(start: &[f64], poses: &[Vec<f64>], order: &[usize]) -> f64 {
    let mut at = start;
    let mut total = 0.0;
    for &k in order {
        total += joint_distance(at, &poses[k]);
        at = &poses[k];
    }
    total
}

/// Visiting order of `poses` starting at `start` (an open path).
pub fn order_path(start: &[f64], poses: &[Vec<f64>]) -> Vec<usize> {
    let n = poses.len();
    let mut left: Vec<usize> = (0..n).collect();
    let mut order = Vec::with_capacity(n);
    let mut at = start.to_vec();
    while !left.is_empty() {
        let (slot, _) = left
            .iter()
            .enumerate()
            .map(|(s, &k)| (s, joint_distance(&at, &poses[k])))
            .min_by(|a, b| a.1.total_cmp(&b.1))
            .unwrap_or((0, 0.0));
        let k = left.swap_remove(slot);
        at.clone_from(&poses[k]);
        order.push(k);
    }
    // 2-opt on the open path: reverse order[i..=j] when it shortens.
    let point = |order: &[usize], i: usize| -> Vec<f64> {
        if i == 0 {
            start.to_vec()
        } else {
            poses[order[i - 1]].clone()
        }
    };
    let mut improved = true;
    while improved {
        improved = false;
        for i in 0..n {
            for j in i + 1..n {
                let before = point(&order, i);
                let (a, b) = (&poses[order[i]], &poses[order[j]]);
                let mut old = joint_distance(&before, a);
                let mut new = joint_distance(&before, b);
                if j + 1 < n {
                    let after = &poses[order[j + 1]];
                    old += joint_distance(b, after);
                    new += joint_distance(a, after);
                }
                if new + 1e-12 < old {
                    order[i..=j].reverse();
                    improved = true;
                }
            }
        }
    }
    order
}

#[cfg(test)]
mod tests {
    use super::*;
    use rand::{rngs::StdRng, Rng, SeedableRng};

    #[test]
    fn ordered_path_is_shorter_than_the_given_order_and_a_permutation() {
        let mut rng = StdRng::seed_from_u64(3);
        let poses: Vec<Vec<f64>> = (0..40)
            .map(|_| (0..6).map(|_| rng.random_range(-2.0..2.0)).collect())
            .collect();
        let start = vec![0.0; 6];
        let order = order_path(&start, &poses);
        let mut sorted = order.clone();
        sorted.sort_unstable();
        assert_eq!(sorted, (0..40).collect::<Vec<_>>());
        let given: Vec<usize> = (0..40).collect();
        let (planned, naive) = (
            path_length(&start, &poses, &order),
            path_length(&start, &poses, &given),
        );
        assert!(planned < 0.6 * naive, "{planned} vs {naive}");
    }
}
