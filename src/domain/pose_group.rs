//! A pose's configuration group (docs/method.md §7.6 "Held-out groups"):
//! the name a cell engineer gives the arm configuration a photo was shot
//! in. Poses of one group are held out together when the job judges how
//! much of the kinematics the campaign carries; poses without one are
//! grouped by their joints 1–3.

use serde::{Deserialize, Serialize};

/// Longest group name, characters.
pub const MAX_GROUP_CHARS: usize = 32;

/// What a group name may be, as told to clients.
pub const GROUP_RULE: &str = "1 to 32 characters of A-Z, a-z, 0-9, '_' and '-'";

/// A checked group name.
#[derive(Debug, Clone, PartialEq, Eq, Hash, Serialize, Deserialize)]
#[serde(transparent)]
pub struct PoseGroup(String);

impl PoseGroup {
    /// `name` when it follows [`GROUP_RULE`].
    pub fn parse(name: &str) -> Result<PoseGroup, &'static str> {
        let count = name.chars().count();
        let allowed = |c: char| c.is_ascii_alphanumeric() || c == '_' || c == '-';
        if (1..=MAX_GROUP_CHARS).contains(&count) && name.chars().all(allowed) {
            Ok(PoseGroup(name.to_string()))
        } else {
            Err(GROUP_RULE)
        }
    }

    /// A name read back from the store (checked when it was written).
    pub fn stored(name: String) -> PoseGroup {
        PoseGroup(name)
    }

    pub fn as_str(&self) -> &str {
        &self.0
    }

    pub fn into_string(self) -> String {
        self.0
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn names_follow_the_rule() {
        assert_eq!(
            PoseGroup::parse("shoulder_A-1").unwrap().as_str(),
            "shoulder_A-1"
        );
        assert!(PoseGroup::parse(&"g".repeat(MAX_GROUP_CHARS)).is_ok());
        for bad in ["", "a b", "é", "a/b", &"g".repeat(MAX_GROUP_CHARS + 1)] {
            assert_eq!(PoseGroup::parse(bad), Err(GROUP_RULE), "{bad:?}");
        }
    }
}
