//! Storage that would otherwise only grow: spool files of archive uploads
//! that a killed process left behind (at start-up at once: a spool file
//! names its process), and images no pose names any more
//! (refused uploads, deleted robots, uploads cut off between storing an
//! image and its pose). Run once at start and then periodically.
//!
//! Both sweeps leave alone what an upload in progress may still need: the
//! spool dir defaults to the shared temp dir (other robocal processes may
//! be spooling there) and an image is stored before its pose. An image
//! whose writer process is known to be gone (`store::writer`: same host,
//! its process no longer running) goes at once, like a spool file.

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

/// The spool file prefix of this process: [`SPOOL_PREFIX`], its process
/// id, `-`; so a sweep knows a file of a process that is gone at once.
pub fn spool_prefix() -> String {
    format!("{SPOOL_PREFIX}{}-", std::process::id())
}

/// Whether the process that spooled file `name` may still be running:
/// false only when its id is known and no such process exists (`/proc`).
fn spooler_may_run(name: &str) -> bool {
    let pid = name
        .strip_prefix(SPOOL_PREFIX)
        .and_then(|rest| rest.split('-').next())
        .and_then(|pid| pid.parse::<u32>().ok());
    let proc_dir = Path::new("/proc");
    match pid {
        Some(pid) if proc_dir.join("self").exists() => proc_dir.join(pid.to_string()).exists(),
        _ => true,
    }
}

/// Removes robocal's spool files in `dir` whose process is gone, or not
/// modified for `stale`; returns how many. Other files, and directories,
/// are never touched.
pub fn clean_spool(dir: &Path, stale: Duration) -> std::io::Result<usize> {
    let now = SystemTime::now();
    let mut removed = 0;
    for entry in std::fs::read_dir(dir)? {
        let entry = entry?;
        let name = entry.file_name();
        let Some(name) = name.to_str().filter(|n| n.starts_with(SPOOL_PREFIX)) else {
            continue;
        };
        let Ok(meta) = entry.metadata() else { continue };
        if !meta.is_file() {
            continue;
        }
        let age = meta
            .modified()
            .ok()
            .and_then(|m| now.duration_since(m).ok())
            .unwrap_or_default();
        let orphan = !spooler_may_run(name);
        if (orphan || age >= stale) && std::fs::remove_file(entry.path()).is_ok() {
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
    match store.collect_orphan_blobs().await {
        Ok(0) => {}
        Ok(n) => tracing::info!(
            collected = n,
            "images of uploads cut off by a crash were deleted"
        ),
        Err(e) => {
            tracing::warn!(error = %e, "orphan image collection failed; retried at the next sweep")
        }
    }
    let cutoff = now_unix_ms() - BLOB_GRACE.as_millis() as i64;
    match store.collect_blobs(cutoff).await {
        Ok(0) => {}
        Ok(n) => tracing::info!(collected = n, "images no pose names were deleted"),
        Err(e) => tracing::warn!(error = %e, "image collection failed; retried at the next sweep"),
    }
    if let Err(e) = store.reclaim_space().await {
        tracing::warn!(error = %e, "freed database space not returned; retried at the next sweep");
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
        // A fresh file of a process that is gone (killed mid-upload) goes at
        // once; one of a live process stays.
        write("robocal-upload-4294967295-gone", SystemTime::now());
        let own = format!("{}x", spool_prefix());
        write(&own, SystemTime::now());
        write("someone-elses.tmp", old);
        std::fs::create_dir(dir.path().join("robocal-upload-dir")).unwrap();
        assert_eq!(clean_spool(dir.path(), SPOOL_STALE).unwrap(), 2);
        let mut left: Vec<String> = std::fs::read_dir(dir.path())
            .unwrap()
            .map(|e| e.unwrap().file_name().into_string().unwrap())
            .collect();
        left.sort();
        let mut expected = vec![
            "robocal-upload-dir".to_string(),
            "robocal-upload-running".to_string(),
            "someone-elses.tmp".to_string(),
            own,
        ];
        expected.sort();
        assert_eq!(left, expected);
    }
}
