//! Storage that would otherwise only grow: spool files of archive uploads
//! that a killed process left behind, and images no pose names any more
//! (refused uploads, deleted robots, uploads cut off between storing an
//! image and its pose). Run once at start and then periodically.
//!
//! Both sweeps leave alone what an upload in progress may still need: the
//! spool dir defaults to the shared temp dir (other robocal processes may
//! be spooling there) and an image is stored before its pose.

use std::path::Path;
use std::time::{Duration, SystemTime};

use tokio::sync::watch;
use tokio::task::JoinHandle;

use crate::domain::now_unix_ms;
use crate::store::DynStore;

/// Name prefix of robocal's spool files: only these are ever removed.
pub const SPOOL_PREFIX: &str = "robocal-upload-";
/// A spool file untouched this long belongs to no running upload (an
/// upload writes its file as the body arrives and reads it right after).
pub const SPOOL_STALE: Duration = Duration::from_secs(60 * 60);
/// An unreferenced image stored this recently may belong to an upload in
/// progress (stored, its pose not yet committed): it is kept.
pub const BLOB_GRACE: Duration = Duration::from_secs(60 * 60);
/// Time between sweeps after the one at start.
pub const SWEEP_INTERVAL: Duration = Duration::from_secs(60 * 60);

/// Removes robocal's spool files in `dir` not modified for `stale`;
/// returns how many. Other files, and directories, are never touched.
pub fn clean_spool(dir: &Path, stale: Duration) -> std::io::Result<usize> {
    let now = SystemTime::now();
    let mut removed = 0;
    for entry in std::fs::read_dir(dir)? {
        let entry = entry?;
        let own = entry
            .file_name()
            .to_str()
            .is_some_and(|n| n.starts_with(SPOOL_PREFIX));
        let Ok(meta) = entry.metadata() else { continue };
        if !own || !meta.is_file() {
            continue;
        }
        let age = meta
            .modified()
            .ok()
            .and_then(|m| now.duration_since(m).ok())
            .unwrap_or_default();
        if age >= stale && std::fs::remove_file(entry.path()).is_ok() {
            removed += 1;
        }
    }
    Ok(removed)
}

/// One sweep: stale spool files and unreferenced images past their grace.
pub async fn sweep(store: &DynStore, spool_dir: &Path) {
    match clean_spool(spool_dir, SPOOL_STALE) {
        Ok(0) => {}
        Ok(n) => {
            tracing::info!(removed = n, dir = %spool_dir.display(), "stale upload spool files removed")
        }
        Err(e) => {
            tracing::warn!(error = %e, dir = %spool_dir.display(), "cannot clean the upload spool dir")
        }
    }
    let cutoff = now_unix_ms() - BLOB_GRACE.as_millis() as i64;
    match store.collect_blobs(cutoff).await {
        Ok(0) => {}
        Ok(n) => tracing::info!(collected = n, "images no pose names were deleted"),
        Err(e) => tracing::warn!(error = %e, "image collection failed; retried at the next sweep"),
    }
}

/// Sweeps now, then every [`SWEEP_INTERVAL`] until `shutdown`.
pub fn spawn(
    store: DynStore,
    spool_dir: std::path::PathBuf,
    mut shutdown: watch::Receiver<bool>,
) -> JoinHandle<()> {
    tokio::spawn(async move {
        loop {
            sweep(&store, &spool_dir).await;
            tokio::select! {
                _ = tokio::time::sleep(SWEEP_INTERVAL) => {}
                _ = shutdown.wait_for(|stop| *stop) => return,
            }
        }
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn only_stale_spool_files_of_robocal_go() {
        let dir = tempfile::tempdir().unwrap();
        let old = SystemTime::now() - 2 * SPOOL_STALE;
        let write = |name: &str, modified: SystemTime| {
            let path = dir.path().join(name);
            std::fs::write(&path, b"zip").unwrap();
            let file = std::fs::File::options().write(true).open(&path).unwrap();
            file.set_modified(modified).unwrap();
        };
        write("robocal-upload-killed", old);
        write("robocal-upload-running", SystemTime::now());
        write("someone-elses.tmp", old);
        std::fs::create_dir(dir.path().join("robocal-upload-dir")).unwrap();
        assert_eq!(clean_spool(dir.path(), SPOOL_STALE).unwrap(), 1);
        let mut left: Vec<String> = std::fs::read_dir(dir.path())
            .unwrap()
            .map(|e| e.unwrap().file_name().into_string().unwrap())
            .collect();
        left.sort();
        assert_eq!(
            left,
            [
                "robocal-upload-dir",
                "robocal-upload-running",
                "someone-elses.tmp"
            ]
        );
    }
}
