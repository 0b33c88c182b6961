//! Reading a dataset archive (a zip holding `poses.json` and the images it
//! names) from a file on disk, defensively: entry names must be plain
//! relative paths (no `..`, no absolute paths: zip-slip), entry count and the
//! manifest size are bounded, and every entry is measured *while it is
//! decompressed* against the per-image and total limits, so a zip bomb is
//! stopped after at most the limit, whatever its headers claim.

use std::fs::File;
use std::io::Read;
use std::path::Path;

use zip::ZipArchive;

use crate::schema::pose_body::DatasetPoseDoc;
use crate::schema::FieldError;

pub const MANIFEST: &str = "poses.json";
/// Most entries an archive may hold.
pub const MAX_ENTRIES: usize = 100_000;
/// Largest `poses.json`, bytes.
pub const MAX_MANIFEST_BYTES: u64 = 32 * 1024 * 1024;

#[derive(Debug, Clone, Copy)]
pub struct DatasetLimits {
    pub max_image_bytes: u64,
    /// Total of all decompressed entries.
    pub max_total_bytes: u64,
    /// Test hook: a pause after each stored image (zero: none), so a test
    /// can kill the process with images stored and no pose yet.
    pub test_pause_per_image: std::time::Duration,
}

#[derive(Debug, thiserror::Error)]
pub enum DatasetError {
    /// Not a readable zip / manifest: 400.
    #[error("{field}: {message}")]
    Malformed { field: String, message: String },
    /// Readable but wrong: 422.
    #[error("invalid archive")]
    Invalid(Vec<FieldError>),
    /// A size limit was exceeded: 413.
    #[error("{limit} exceeded")]
    TooLarge { limit: &'static str, bytes: u64 },
}

fn malformed(field: &str, message: impl std::fmt::Display) -> DatasetError {
    DatasetError::Malformed {
        field: field.to_string(),
        message: message.to_string(),
    }
}

pub struct DatasetReader {
    archive: ZipArchive<File>,
    pub manifest: Vec<DatasetPoseDoc>,
    limits: DatasetLimits,
    total: u64,
}

/// A name is safe when it is relative and never climbs out of the archive.
pub fn is_safe_name(name: &str) -> bool {
    !name.is_empty()
        && !name.starts_with('/')
        && !name.starts_with('\\')
        && !name.contains('\0')
        && !name.contains(':')
        && name.split(['/', '\\']).all(|part| part != "..")
}

impl DatasetReader {
    pub fn open(path: &Path, limits: DatasetLimits) -> Result<DatasetReader, DatasetError> {
        let mut file = File::open(path).map_err(|e| malformed("archive", e))?;
        // The zip reader keeps one entry per name: a second one is refused
        // here, before it could stand in for the first.
        match super::zip_names::first_duplicate(&mut file) {
            Ok(None) => {}
            Ok(Some(name)) => {
                return Err(DatasetError::Invalid(vec![FieldError::new(
                    format!("archive/{name}"),
                    "duplicate entry: the archive holds this name more than once",
                )]))
            }
            Err(e) => return Err(malformed("archive", e)),
        }
        let archive = ZipArchive::new(file)
            .map_err(|e| malformed("archive", format!("not a zip archive: {e}")))?;
        if archive.len() > MAX_ENTRIES {
            return Err(DatasetError::Invalid(vec![FieldError::new(
                "archive",
                format!("{} entries; at most {MAX_ENTRIES}", archive.len()),
            )]));
        }
        let unsafe_names: Vec<FieldError> = archive
            .file_names()
            .filter(|n| !is_safe_name(n))
            .take(10)
            .map(|n| FieldError::new(format!("archive/{n}"), "unsafe entry path (absolute or ..)"))
            .collect();
        if !unsafe_names.is_empty() {
            return Err(DatasetError::Invalid(unsafe_names));
        }
        let mut reader = DatasetReader {
            archive,
            manifest: vec![],
            limits,
            total: 0,
        };
        let bytes = reader.read_entry(MANIFEST, MAX_MANIFEST_BYTES, "max_json_bytes")?;
        if let Some(field) = crate::schema::nul::json_nul_field(&bytes) {
            return Err(DatasetError::Invalid(vec![FieldError::new(
                if field.starts_with('[') {
                    format!("{MANIFEST}{field}")
                } else {
                    format!("{MANIFEST}.{field}")
                },
                crate::schema::nul::NUL_MESSAGE,
            )]));
        }
        let de = &mut serde_json::Deserializer::from_slice(&bytes);
        reader.manifest = serde_path_to_error::deserialize(de).map_err(|e| {
            let path = e.path().to_string();
            let inner = e.into_inner();
            if inner.classify() == serde_json::error::Category::Data {
                DatasetError::Invalid(vec![FieldError::new(
                    format!("{MANIFEST}{path}"),
                    inner.to_string(),
                )])
            } else {
                malformed(MANIFEST, format!("malformed JSON: {inner}"))
            }
        })?;
        let bad: Vec<FieldError> = reader
            .manifest
            .iter()
            .enumerate()
            .filter(|(_, p)| !is_safe_name(&p.image))
            .map(|(i, _)| FieldError::new(format!("{MANIFEST}[{i}].image"), "unsafe path"))
            .collect();
        if !bad.is_empty() {
            return Err(DatasetError::Invalid(bad));
        }
        Ok(reader)
    }

    /// Reads one image entry, enforcing the per-image and total limits while decompressing.
    pub fn read_image(&mut self, name: &str) -> Result<Vec<u8>, DatasetError> {
        self.read_entry(name, self.limits.max_image_bytes, "max_image_bytes")
    }

    fn read_entry(
        &mut self,
        name: &str,
        limit: u64,
        limit_name: &'static str,
    ) -> Result<Vec<u8>, DatasetError> {
        let entry = match self.archive.by_name(name) {
            Ok(e) => e,
            Err(zip::result::ZipError::FileNotFound) => {
                return Err(DatasetError::Invalid(vec![FieldError::new(
                    format!("archive/{name}"),
                    "named in poses.json but not in the archive",
                )]))
            }
            Err(e) => return Err(malformed(&format!("archive/{name}"), e)),
        };
        let remaining_total = self.limits.max_total_bytes.saturating_sub(self.total);
        let cap = limit.min(remaining_total);
        let mut buf = Vec::new();
        entry
            .take(cap + 1)
            .read_to_end(&mut buf)
            .map_err(|e| malformed(&format!("archive/{name}"), format!("corrupt entry: {e}")))?;
        if buf.len() as u64 > cap {
            return Err(if cap == limit {
                DatasetError::TooLarge {
                    limit: limit_name,
                    bytes: limit,
                }
            } else {
                DatasetError::TooLarge {
                    limit: "max_archive_bytes",
                    bytes: self.limits.max_total_bytes,
                }
            });
        }
        self.total += buf.len() as u64;
        Ok(buf)
    }
}

#[cfg(test)]
mod tests {
    use super::is_safe_name;

    #[test]
    fn unsafe_names_are_recognised() {
        for bad in [
            "../x.png",
            "a/../../x",
            "/etc/passwd",
            "\\win",
            "C:/x",
            "a\\..\\b",
            "",
        ] {
            assert!(!is_safe_name(bad), "{bad:?}");
        }
        for good in ["poses.json", "img/0001.png", "a..b.png", "dir/.hidden.png"] {
            assert!(is_safe_name(good), "{good:?}");
        }
    }
}
