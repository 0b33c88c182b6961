//! Arm configurations of a campaign (method.md §7.6 "Held-out groups"): poses
//! that share the shoulder and elbow (joints 1–3) within a few degrees see
//! the same link geometry; only the wrist differs. A model is judged by how
//! it predicts configurations it was not fitted to, so poses are grouped by
//! configuration and whole groups are held out together.

use std::collections::HashMap;

/// Poses whose joints 1–3 all agree within this (deg) share a configuration
/// (single linkage: a chain of such neighbours is one group).
pub const GROUP_TOLERANCE_DEG: f64 = 3.0;
/// The joints that set a configuration: shoulder and elbow.
pub const CONFIGURATION_JOINTS: usize = 3;

/// The configuration group of every pose, numbered 0.. in order of first
/// appearance. Poses with an explicit label share the group of that label;
/// the others are clustered on joints 1–3 (`joints_rad`) within
/// [`GROUP_TOLERANCE_DEG`], never joining a labelled group.
pub fn configuration_groups(joints_rad: &[Vec<f64>], labels: &[Option<String>]) -> Vec<usize> {
    let n = joints_rad.len();
    let tolerance = GROUP_TOLERANCE_DEG.to_radians();
    let label = |i: usize| labels.get(i).and_then(|l| l.as_deref());
    let close = |a: &[f64], b: &[f64]| {
        a.iter()
            .zip(b)
            .take(CONFIGURATION_JOINTS)
            .all(|(x, y)| (x - y).abs() <= tolerance)
    };
    // Union–find over the unlabelled poses' neighbourhoods.
    let mut parent: Vec<usize> = (0..n).collect();
    fn root(parent: &mut [usize], mut i: usize) -> usize {
        while parent[i] != i {
            parent[i] = parent[parent[i]];
            i = parent[i];
        }
        i
    }
    let mut by_label: HashMap<&str, usize> = HashMap::new();
    for i in 0..n {
        if let Some(l) = label(i) {
            let first = *by_label.entry(l).or_insert(i);
            let (a, b) = (root(&mut parent, i), root(&mut parent, first));
            parent[a] = b;
        }
    }
    for i in 0..n {
        for j in (i + 1)..n {
            if label(i).is_none() && label(j).is_none() && close(&joints_rad[i], &joints_rad[j]) {
                let (a, b) = (root(&mut parent, i), root(&mut parent, j));
                parent[a] = b;
            }
        }
    }
    let mut number: HashMap<usize, usize> = HashMap::new();
    (0..n)
        .map(|i| {
            let r = root(&mut parent, i);
            let next = number.len();
            *number.entry(r).or_insert(next)
        })
        .collect()
}

/// Number of distinct groups in `groups`.
pub fn group_count(groups: &[usize]) -> usize {
    groups.iter().max().map_or(0, |m| m + 1)
}

/// Whether any pose in `val` shares a group with a pose in `cal` (indices
/// into `groups`): then the validation poses repeat the calibration's
/// configurations and say nothing about unseen ones.
pub fn shares_configurations(groups: &[usize], cal: &[usize], val: &[usize]) -> bool {
    val.iter()
        .any(|&v| cal.iter().any(|&c| groups.get(c) == groups.get(v)))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn deg(v: [f64; 6]) -> Vec<f64> {
        v.iter().map(|d| d.to_radians()).collect()
    }

    #[test]
    fn wrist_moves_share_a_group_and_shoulder_moves_do_not() {
        let joints = vec![
            deg([0.0, -30.0, 60.0, 0.0, 40.0, 0.0]),
            deg([0.5, -30.2, 60.1, 50.0, -20.0, 90.0]),
            deg([20.0, -30.0, 60.0, 0.0, 40.0, 0.0]),
            // Chained through the second pose (single linkage).
            deg([2.9, -30.0, 60.0, 0.0, 0.0, 0.0]),
            deg([20.0, -10.0, 60.0, 0.0, 40.0, 0.0]),
        ];
        let groups = configuration_groups(&joints, &[]);
        assert_eq!(groups, vec![0, 0, 1, 0, 2]);
        assert_eq!(group_count(&groups), 3);
        assert!(shares_configurations(&groups, &[0, 2], &[1]));
        assert!(!shares_configurations(&groups, &[0, 1], &[2, 4]));
    }

    #[test]
    fn labels_override_the_clustering() {
        let same = deg([0.0, -30.0, 60.0, 0.0, 40.0, 0.0]);
        let joints = vec![same.clone(), same.clone(), same.clone()];
        let labels = vec![Some("a".to_string()), Some("b".to_string()), None];
        assert_eq!(configuration_groups(&joints, &labels), vec![0, 1, 2]);
        let labels = vec![Some("a".to_string()), None, Some("a".to_string())];
        let far = deg([90.0, 0.0, 0.0, 0.0, 0.0, 0.0]);
        assert_eq!(
            configuration_groups(&[same.clone(), same, far], &labels),
            vec![0, 1, 0]
        );
        assert!(configuration_groups(&[], &[]).is_empty());
    }
}
