//! The gate around image decodes. One gate per process, sized to the job
//! workers and shared by upload detection and jobs: each decode holds a
//! grey image of the camera's size, so the gate, not the number of
//! clients, bounds that memory.
//!
//! Slots go to waiters by fair share, not by arrival: a free slot goes to
//! the waiting key (a session, or the jobs) that holds the fewest slots,
//! the longest waiting first among equals. A session that queues thirty
//! images therefore delays another session's one image by at most the
//! decode already running, not by its thirty (see
//! docs/decisions/0322-decode-budget-and-fair-gate.md).

use std::collections::{HashMap, VecDeque};
use std::sync::{Condvar, Mutex};

/// The key job decodes share: the worker pool already bounds them.
pub const JOBS_KEY: &str = "jobs";

/// What one decode may cost, checked on the header before decoding.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct DecodeBudget {
    /// Most pixels (width × height) of an image without a session camera
    /// to compare with; the server's camera ceiling.
    pub max_pixels: u64,
    /// Most bytes one decode and its detection may hold at once.
    pub max_bytes: u64,
}

impl DecodeBudget {
    /// No limit beyond the per-side one (tools that decode their own files).
    pub const UNBOUNDED: DecodeBudget = DecodeBudget {
        max_pixels: u64::MAX,
        max_bytes: u64::MAX,
    };
}

#[derive(Debug, Default)]
struct Slots {
    free: usize,
    /// Slots held, by key (keys holding none are removed).
    held: HashMap<String, usize>,
    /// Waiting tickets in arrival order, with their keys.
    waiting: VecDeque<(u64, String)>,
    /// Tickets given a slot and not yet woken.
    granted: Vec<u64>,
    next_ticket: u64,
}

impl Slots {
    /// Hands free slots to waiters, fewest held first, then oldest.
    fn dispatch(&mut self) {
        while self.free > 0 && !self.waiting.is_empty() {
            let held = |key: &str| self.held.get(key).copied().unwrap_or(0);
            let (index, _) = self
                .waiting
                .iter()
                .enumerate()
                .min_by_key(|(i, (_, key))| (held(key), *i))
                .expect("not empty");
            let (ticket, key) = self.waiting.remove(index).expect("index in range");
            *self.held.entry(key).or_default() += 1;
            self.free -= 1;
            self.granted.push(ticket);
        }
    }
}

#[derive(Debug)]
pub struct DecodeGate {
    slots: Mutex<Slots>,
    changed: Condvar,
    size: usize,
    budget: DecodeBudget,
}

/// One decode's slot; released on drop.
#[derive(Debug)]
pub struct DecodePermit<'a> {
    gate: &'a DecodeGate,
    key: String,
}

impl DecodeGate {
    /// A gate letting `size` decodes run at once (at least one), with no
    /// budget beyond the per-side limit.
    pub fn new(size: usize) -> DecodeGate {
        DecodeGate::with_budget(size, DecodeBudget::UNBOUNDED)
    }

    /// A gate of `size` slots whose decodes must fit `budget`.
    pub fn with_budget(size: usize, budget: DecodeBudget) -> DecodeGate {
        let size = size.max(1);
        DecodeGate {
            slots: Mutex::new(Slots {
                free: size,
                ..Slots::default()
            }),
            changed: Condvar::new(),
            size,
            budget,
        }
    }

    pub fn size(&self) -> usize {
        self.size
    }

    pub fn budget(&self) -> DecodeBudget {
        self.budget
    }

    /// Waits for a slot for `key`'s fair share. Blocking: call it on a
    /// blocking thread, never on the async runtime.
    pub fn acquire(&self, key: &str) -> DecodePermit<'_> {
        let mut slots = self.slots.lock().unwrap_or_else(|e| e.into_inner());
        let ticket = slots.next_ticket;
        slots.next_ticket += 1;
        slots.waiting.push_back((ticket, key.to_string()));
        slots.dispatch();
        loop {
            if let Some(i) = slots.granted.iter().position(|t| *t == ticket) {
                slots.granted.swap_remove(i);
                return DecodePermit {
                    gate: self,
                    key: key.to_string(),
                };
            }
            slots = self.changed.wait(slots).unwrap_or_else(|e| e.into_inner());
        }
    }
}

impl DecodePermit<'_> {
    /// The budget of the gate this slot belongs to.
    pub fn budget(&self) -> DecodeBudget {
        self.gate.budget
    }
}

impl Drop for DecodePermit<'_> {
    fn drop(&mut self) {
        let mut slots = self.gate.slots.lock().unwrap_or_else(|e| e.into_inner());
        if let Some(n) = slots.held.get_mut(&self.key) {
            *n -= 1;
            if *n == 0 {
                slots.held.remove(&self.key);
            }
        }
        slots.free += 1;
        slots.dispatch();
        self.gate.changed.notify_all();
    }
}

#[cfg(test)]
mod tests {
    use std::sync::atomic::{AtomicUsize, Ordering};
    use std::sync::{Arc, Mutex};
    use std::time::Duration;

    use super::DecodeGate;

    #[test]
    fn never_more_holders_than_slots() {
        let gate = DecodeGate::new(2);
        let (inside, most) = (AtomicUsize::new(0), AtomicUsize::new(0));
        std::thread::scope(|s| {
            for t in 0..8 {
                let (gate, inside, most) = (&gate, &inside, &most);
                s.spawn(move || {
                    for _ in 0..50 {
                        let _permit = gate.acquire(&format!("s{}", t % 3));
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

    /// Session "a" holds both slots and has six more images waiting when
    /// session "b" asks for one: "b" gets the first slot freed.
    #[test]
    fn a_session_queued_behind_another_s_batch_goes_next() {
        let gate = Arc::new(DecodeGate::new(2));
        let order = Arc::new(Mutex::new(Vec::new()));
        let held: Vec<_> = (0..2).map(|_| gate.acquire("a")).collect();
        let waiting = |key: &'static str| {
            let (gate, order) = (gate.clone(), order.clone());
            std::thread::spawn(move || {
                let _permit = gate.acquire(key);
                order.lock().unwrap().push(key);
                std::thread::sleep(Duration::from_millis(5));
            })
        };
        let mut threads: Vec<_> = (0..6).map(|_| waiting("a")).collect();
        std::thread::sleep(Duration::from_millis(100));
        threads.push(waiting("b"));
        std::thread::sleep(Duration::from_millis(100));
        drop(held);
        for t in threads {
            t.join().unwrap();
        }
        let order = order.lock().unwrap();
        let b_at = order.iter().position(|k| *k == "b").unwrap();
        assert!(b_at <= 1, "b decoded {}th of {:?}", b_at + 1, *order);
    }
}
