//! A counting semaphore around image decodes. One gate per process, sized
//! to the job workers and shared by upload detection and jobs: each decode
//! holds a grey image of the camera's size (and the decoder's buffers), so
//! the gate, not the number of clients, bounds that memory.

use std::sync::{Condvar, Mutex};

#[derive(Debug)]
pub struct DecodeGate {
    free: Mutex<usize>,
    released: Condvar,
    size: usize,
}

/// One decode's slot; released on drop.
#[derive(Debug)]
pub struct DecodePermit<'a> {
    gate: &'a DecodeGate,
}

impl DecodeGate {
    /// A gate letting `size` decodes run at once (at least one).
    pub fn new(size: usize) -> DecodeGate {
        let size = size.max(1);
        DecodeGate {
            free: Mutex::new(size),
            released: Condvar::new(),
            size,
        }
    }

    pub fn size(&self) -> usize {
        self.size
    }

    /// Waits for a slot. Blocking: call it on a blocking thread, never on
    /// the async runtime.
    pub fn acquire(&self) -> DecodePermit<'_> {
        let mut free = self.free.lock().unwrap_or_else(|e| e.into_inner());
        while *free == 0 {
            free = self.released.wait(free).unwrap_or_else(|e| e.into_inner());
        }
        *free -= 1;
        DecodePermit { gate: self }
    }
}

impl Drop for DecodePermit<'_> {
    fn drop(&mut self) {
        let mut free = self.gate.free.lock().unwrap_or_else(|e| e.into_inner());
        *free += 1;
        self.gate.released.notify_one();
    }
}

#[cfg(test)]
mod tests {
    use std::sync::atomic::{AtomicUsize, Ordering};

    use super::DecodeGate;

    #[test]
    fn never_more_holders_than_slots() {
        let gate = DecodeGate::new(2);
        let (inside, most) = (AtomicUsize::new(0), AtomicUsize::new(0));
        std::thread::scope(|s| {
            for _ in 0..8 {
                s.spawn(|| {
                    for _ in 0..50 {
                        let _permit = gate.acquire();
                        let now = inside.fetch_add(1, Ordering::SeqCst) + 1;
                        most.fetch_max(now, Ordering::SeqCst);
                        std::thread::yield_now();
                        inside.fetch_sub(1, Ordering::SeqCst);
                    }
                });
            }
        });
        assert_eq!(most.load(Ordering::SeqCst), 2);
    }
}
