//! A robot's serial number, validated once. Serials are path segments
//! (`/v1/robots/{serial}`) and parts of parameter-set ids
//! (`"{serial}/{version}"`), so they must survive URL handling unchanged:
//! `.` and `..` are dot-segments every client normalises away (a robot
//! stored under them could never be fetched or deleted again), and `/`,
//! `%` or spaces would change the path.

use std::fmt;
use std::ops::Deref;

use serde::{Deserialize, Serialize};

/// Longest serial number, bytes (all characters are ASCII).
pub const MAX_SERIAL_LEN: usize = 64;

/// What a serial may be, as told to clients.
pub const SERIAL_RULE: &str = "1 to 64 characters of A-Z a-z 0-9 - _ . (not \".\" or \"..\")";

/// A valid serial: 1 to [`MAX_SERIAL_LEN`] characters of `A-Z a-z 0-9 - _ .`,
/// and not a dot-segment (`.`, `..`).
#[derive(Debug, Clone, PartialEq, Eq, PartialOrd, Ord, Hash, Serialize, Deserialize)]
#[serde(try_from = "String", into = "String")]
pub struct Serial(String);

/// Why a text is not a serial; the message is [`SERIAL_RULE`].
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
#[error("{SERIAL_RULE}")]
pub struct InvalidSerial;

impl Serial {
    pub fn parse(text: &str) -> Result<Serial, InvalidSerial> {
        let allowed = |c: char| c.is_ascii_alphanumeric() || matches!(c, '-' | '_' | '.');
        let ok = !text.is_empty()
            && text.len() <= MAX_SERIAL_LEN
            && text.chars().all(allowed)
            && text != "."
            && text != "..";
        if ok {
            Ok(Serial(text.to_string()))
        } else {
            Err(InvalidSerial)
        }
    }

    pub fn as_str(&self) -> &str {
        &self.0
    }
}

impl Deref for Serial {
    type Target = str;
    fn deref(&self) -> &str {
        &self.0
    }
}

impl fmt::Display for Serial {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(&self.0)
    }
}

impl TryFrom<String> for Serial {
    type Error = InvalidSerial;
    fn try_from(text: String) -> Result<Serial, InvalidSerial> {
        Serial::parse(&text)
    }
}

impl From<Serial> for String {
    fn from(s: Serial) -> String {
        s.0
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn dot_segments_and_foreign_characters_are_refused() {
        let too_long = "A".repeat(MAX_SERIAL_LEN + 1);
        for bad in [
            "",
            ".",
            "..",
            "a/b",
            "a b",
            "%2e",
            "ü",
            "a\0",
            too_long.as_str(),
        ] {
            assert_eq!(Serial::parse(bad), Err(InvalidSerial), "{bad:?}");
        }
        let longest = "A".repeat(MAX_SERIAL_LEN);
        for good in ["IRB-001", "a.b", "...", ".hidden", "x_1", longest.as_str()] {
            assert_eq!(Serial::parse(good).unwrap().as_str(), good);
        }
    }

    #[test]
    fn deserialising_validates() {
        assert!(serde_json::from_str::<Serial>("\"..\"").is_err());
        let s: Serial = serde_json::from_str("\"IRB-1\"").unwrap();
        assert_eq!(&*s, "IRB-1");
    }
}
