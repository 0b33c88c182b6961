//! What a dataset upload warns of although it stored every pose: images on
//! which the detector did not find the session's target. A campaign whose
//! images show another board (a 9x9 grid for a 7x9 session) would
//! otherwise look uploaded and fail only when its job runs.

use std::collections::BTreeMap;

use crate::store::PoseRecord;

/// The warning for `stored` poses, when fewer than half of their images
/// show the target: how many do, and the most frequent reason of the rest.
pub fn detection_warning(stored: &[PoseRecord]) -> Option<String> {
    let images: Vec<_> = stored
        .iter()
        .filter_map(|p| p.image_detection.as_ref())
        .collect();
    let found = images.iter().filter(|d| !d.points.is_empty()).count();
    if images.is_empty() || 2 * found >= images.len() {
        return None;
    }
    let mut reasons: BTreeMap<&str, usize> = BTreeMap::new();
    for d in images.iter().filter(|d| d.points.is_empty()) {
        *reasons
            .entry(d.error.as_deref().unwrap_or("no reason given"))
            .or_default() += 1;
    }
    let (reason, count) = reasons
        .into_iter()
        .max_by_key(|(_, n)| *n)
        .unwrap_or(("no reason given", 0));
    Some(format!(
        "{found} of {} images show the session's target; {count} say: {reason}",
        images.len()
    ))
}
