//! Images an upload stored before its poses. Blobs are written one by one
//! (an archive's images are never all in memory) and the poses naming them
//! in one transaction at the end; when the upload fails in between (a bad
//! image, a limit, the client going away), the images it stored are
//! discarded, so a refused archive leaves nothing behind. Images that
//! other poses name stay (`discard_blobs` checks).

use crate::store::DynStore;

pub struct StagedImages {
    store: DynStore,
    sha256s: Vec<String>,
}

impl StagedImages {
    pub fn new(store: DynStore) -> StagedImages {
        StagedImages {
            store,
            sha256s: Vec::new(),
        }
    }

    /// Remembers an image just stored with `put_blob`.
    pub fn stored(&mut self, sha256: &str) {
        self.sha256s.push(sha256.to_string());
    }

    /// The poses naming the images are committed: keep them.
    pub fn keep(mut self) {
        self.sha256s.clear();
    }

    /// The upload failed: discards its images now (before the error is answered).
    pub async fn discard(mut self) {
        let sha256s = std::mem::take(&mut self.sha256s);
        discard(&self.store, &sha256s).await;
    }
}

/// A handler cancelled midway (the client hung up) drops its staged images
/// without [`StagedImages::discard`]: they are discarded in the background.
impl Drop for StagedImages {
    fn drop(&mut self) {
        if self.sha256s.is_empty() {
            return;
        }
        let (store, sha256s) = (self.store.clone(), std::mem::take(&mut self.sha256s));
        if let Ok(runtime) = tokio::runtime::Handle::try_current() {
            runtime.spawn(async move { discard(&store, &sha256s).await });
        }
    }
}

async fn discard(store: &DynStore, sha256s: &[String]) {
    if sha256s.is_empty() {
        return;
    }
    match store.discard_blobs(sha256s).await {
        Ok(n) => tracing::info!(discarded = n, "images of a refused upload discarded"),
        // The periodic collection takes them later.
        Err(e) => tracing::warn!(error = %e, "images of a refused upload left for collection"),
    }
}
