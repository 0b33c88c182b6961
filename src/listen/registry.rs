//! The table of open connections, which decides who gets in when a client
//! opens many of them. A connection that is idle (keep-alive, or still
//! reading its request head) costs the attacker nothing and proves nothing,
//! so when the cap (`--max-connections`) is reached a new connection
//! displaces the oldest idle one (past [`DISPLACE_GRACE`]) instead of being
//! refused; only when no connection can be displaced does a new one land in
//! the reserved lane (`--reserved-connections`), which serves `/healthz`,
//! `/readyz` and authenticated requests only. One client address holds at most
//! `--max-connections-per-address` connections. Event streams are counted
//! apart (`--max-event-streams`, `--max-event-streams-per-address`): a
//! connection that turns into a stream leaves the connection count.

use std::collections::{BTreeMap, HashMap};
use std::net::IpAddr;
use std::sync::{Arc, Mutex, MutexGuard};
use std::time::{Duration, Instant};

use tokio::sync::Notify;

/// A connection this young is never displaced: a client that opened it
/// has this long to send its request head before a newer connection may
/// take its place (a flood of new connections cannot cut off each other's
/// first requests).
pub const DISPLACE_GRACE: Duration = Duration::from_millis(500);

/// The limits the table enforces (see the module documentation).
#[derive(Debug, Clone, Copy)]
pub struct ConnLimits {
    pub max_connections: usize,
    pub reserved_connections: usize,
    pub max_per_address: usize,
    pub max_streams: usize,
    pub max_streams_per_address: usize,
}

/// Why a connection or a stream was refused.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Refusal {
    /// The client address holds its maximum.
    PerAddress,
    /// Every place, the reserved lane included, is in a request.
    Full,
}

/// Where an admitted connection was placed.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Lane {
    Ordinary,
    /// Serves only probes and authenticated requests.
    Reserved,
}

#[derive(Debug)]
struct Entry {
    addr: IpAddr,
    /// Requests in flight (their answers included, until fully sent).
    busy: usize,
    /// Turned into an event stream: counted among streams, not connections.
    stream: bool,
    evict: Arc<Notify>,
    opened: Instant,
}

#[derive(Debug, Default)]
struct Table {
    next_id: u64,
    /// By id, so the first entries are the oldest.
    entries: BTreeMap<u64, Entry>,
    per_address: HashMap<IpAddr, usize>,
    streams: usize,
    streams_per_address: HashMap<IpAddr, usize>,
}

impl Table {
    /// Connections counted against the cap (streams are not).
    fn counted(&self) -> usize {
        self.entries.len() - self.streams
    }
}

/// The shared connection table of one listener.
#[derive(Debug)]
pub struct Registry {
    limits: ConnLimits,
    table: Mutex<Table>,
}

/// One admitted connection; leaves the table when dropped.
#[derive(Debug, Clone)]
pub struct ConnRef {
    registry: Arc<Registry>,
    id: u64,
    pub addr: IpAddr,
    pub lane: Lane,
    /// Notified when the connection is displaced by a newer one.
    pub evict: Arc<Notify>,
}

impl Registry {
    pub fn new(limits: ConnLimits) -> Arc<Registry> {
        Arc::new(Registry {
            limits,
            table: Mutex::new(Table::default()),
        })
    }

    pub fn limits(&self) -> ConnLimits {
        self.limits
    }

    fn lock(&self) -> MutexGuard<'_, Table> {
        self.table.lock().unwrap_or_else(|e| e.into_inner())
    }

    /// Admits a connection from `addr`, displacing the oldest idle one when
    /// the cap is reached; the returned reference must be kept (and
    /// [`ConnRef::leave`] called) for the connection's life.
    pub fn admit(self: &Arc<Self>, addr: IpAddr) -> Result<ConnRef, Refusal> {
        let mut table = self.lock();
        if table.per_address.get(&addr).copied().unwrap_or(0) >= self.limits.max_per_address {
            return Err(Refusal::PerAddress);
        }
        let mut lane = Lane::Ordinary;
        let now = Instant::now();
        if table.counted() >= self.limits.max_connections {
            let idle = table
                .entries
                .iter()
                .find(|(_, e)| {
                    e.busy == 0 && !e.stream && now.duration_since(e.opened) >= DISPLACE_GRACE
                })
                .map(|(id, _)| *id);
            match idle {
                Some(id) => {
                    // Out of the table at once: its task ends on the notice.
                    if let Some(gone) = remove(&mut table, id) {
                        gone.evict.notify_one();
                    }
                }
                None if table.counted()
                    < self.limits.max_connections + self.limits.reserved_connections =>
                {
                    lane = Lane::Reserved;
                }
                None => return Err(Refusal::Full),
            }
        }
        let id = table.next_id;
        table.next_id += 1;
        let evict = Arc::new(Notify::new());
        table.entries.insert(
            id,
            Entry {
                addr,
                busy: 0,
                stream: false,
                evict: evict.clone(),
                opened: now,
            },
        );
        *table.per_address.entry(addr).or_default() += 1;
        Ok(ConnRef {
            registry: self.clone(),
            id,
            addr,
            lane,
            evict,
        })
    }

    /// Open connections counted against the cap, and open streams.
    pub fn counts(&self) -> (usize, usize) {
        let table = self.lock();
        (table.counted(), table.streams)
    }
}

/// Takes entry `id` out of the table with its counts.
fn remove(table: &mut Table, id: u64) -> Option<Entry> {
    let entry = table.entries.remove(&id)?;
    decrement(&mut table.per_address, entry.addr);
    if entry.stream {
        table.streams -= 1;
        decrement(&mut table.streams_per_address, entry.addr);
    }
    Some(entry)
}

fn decrement(counts: &mut HashMap<IpAddr, usize>, addr: IpAddr) {
    if let Some(n) = counts.get_mut(&addr) {
        *n -= 1;
        if *n == 0 {
            counts.remove(&addr);
        }
    }
}

impl ConnRef {
    /// The connection closed: it leaves the table (if not displaced already).
    pub fn leave(&self) {
        let mut table = self.registry.lock();
        remove(&mut table, self.id);
    }

    /// A request starts on this connection; it counts as busy until the
    /// guard is dropped (after its answer is sent).
    pub fn begin_request(&self) -> BusyGuard {
        let mut table = self.registry.lock();
        if let Some(e) = table.entries.get_mut(&self.id) {
            e.busy += 1;
        }
        BusyGuard { conn: self.clone() }
    }

    /// No request is in flight (the connection may be closed outright).
    pub fn is_idle(&self) -> bool {
        let table = self.registry.lock();
        table.entries.get(&self.id).is_none_or(|e| e.busy == 0)
    }

    /// Turns this connection into an event stream: it leaves the connection
    /// count and takes a stream place until the guard is dropped.
    pub fn open_stream(&self) -> Result<StreamGuard, Refusal> {
        let limits = self.registry.limits;
        let mut table = self.registry.lock();
        let Some(entry) = table.entries.get(&self.id) else {
            return Err(Refusal::Full);
        };
        if entry.stream {
            return Ok(StreamGuard { conn: self.clone() });
        }
        let on_address = table
            .streams_per_address
            .get(&self.addr)
            .copied()
            .unwrap_or(0);
        if on_address >= limits.max_streams_per_address {
            return Err(Refusal::PerAddress);
        }
        if table.streams >= limits.max_streams {
            return Err(Refusal::Full);
        }
        if let Some(e) = table.entries.get_mut(&self.id) {
            e.stream = true;
        }
        table.streams += 1;
        *table.streams_per_address.entry(self.addr).or_default() += 1;
        Ok(StreamGuard { conn: self.clone() })
    }
}

/// A request in flight on a connection.
#[derive(Debug)]
pub struct BusyGuard {
    conn: ConnRef,
}

impl Drop for BusyGuard {
    fn drop(&mut self) {
        let mut table = self.conn.registry.lock();
        if let Some(e) = table.entries.get_mut(&self.conn.id) {
            e.busy = e.busy.saturating_sub(1);
        }
    }
}

/// A connection serving an event stream.
#[derive(Debug)]
pub struct StreamGuard {
    conn: ConnRef,
}

impl Drop for StreamGuard {
    fn drop(&mut self) {
        let mut table = self.conn.registry.lock();
        let addr = self.conn.addr;
        if let Some(e) = table.entries.get_mut(&self.conn.id) {
            if e.stream {
                e.stream = false;
                table.streams -= 1;
                decrement(&mut table.streams_per_address, addr);
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn limits() -> ConnLimits {
        ConnLimits {
            max_connections: 2,
            reserved_connections: 1,
            max_per_address: 3,
            max_streams: 2,
            max_streams_per_address: 1,
        }
    }

    fn ip(last: u8) -> IpAddr {
        IpAddr::from([127, 0, 0, last])
    }

    #[test]
    fn idle_connections_are_displaced_oldest_first_busy_ones_never() {
        let r = Registry::new(limits());
        let a = r.admit(ip(1)).unwrap();
        let b = r.admit(ip(2)).unwrap();
        let _busy = b.begin_request();
        // Full, and `a` still has its first request to send: reserved lane.
        let young = r.admit(ip(3)).unwrap();
        assert_eq!(young.lane, Lane::Reserved);
        young.leave();
        std::thread::sleep(DISPLACE_GRACE);
        // The idle `a` makes room.
        let c = r.admit(ip(3)).unwrap();
        assert_eq!(c.lane, Lane::Ordinary);
        assert_eq!(r.counts(), (2, 0));
        a.leave();
        assert_eq!(r.counts(), (2, 0), "a displaced entry leaves once");
        let _busy_c = c.begin_request();
        // Every place busy: the reserved lane, then refusal.
        let d = r.admit(ip(4)).unwrap();
        assert_eq!(d.lane, Lane::Reserved);
        let _busy_d = d.begin_request();
        assert_eq!(r.admit(ip(5)).unwrap_err(), Refusal::Full);
    }

    #[test]
    fn one_address_holds_its_maximum_and_streams_count_apart() {
        let r = Registry::new(ConnLimits {
            max_connections: 10,
            ..limits()
        });
        let held: Vec<ConnRef> = (0..3).map(|_| r.admit(ip(1)).unwrap()).collect();
        assert_eq!(r.admit(ip(1)).unwrap_err(), Refusal::PerAddress);
        assert!(r.admit(ip(2)).is_ok());
        let stream = held[0].open_stream().unwrap();
        assert_eq!(r.counts(), (3, 1));
        assert_eq!(held[1].open_stream().unwrap_err(), Refusal::PerAddress);
        drop(stream);
        assert_eq!(r.counts(), (4, 0));
        assert!(held[1].open_stream().is_ok());
    }
}
