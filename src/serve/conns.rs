//! The connections served, and who makes room when they are too many.
//!
//! There is no fixed cap that idle connections can fill: when
//! [`MAX_CONNECTIONS`] are open, a new one is still accepted, and the
//! connection that has been idle longest (waiting for a request head, or
//! between requests; never one whose request is being answered) is closed
//! to make room. So slow or idle clients (slowloris: a head sent a byte a
//! second) cannot keep the page from loading, however many they open.

use std::collections::BTreeMap;
use std::sync::{Arc, Mutex};
use std::time::Instant;

use tokio::task::AbortHandle;

/// Connections served at once before the idlest is closed for a new one.
pub const MAX_CONNECTIONS: usize = 256;

struct Conn {
    /// When it last began or finished a request (or was accepted).
    since: Instant,
    /// Requests being answered on it now.
    busy: usize,
    abort: Option<AbortHandle>,
}

/// The open connections.
#[derive(Clone, Default)]
pub struct Conns(Arc<Mutex<Table>>);

#[derive(Default)]
struct Table {
    next: u64,
    open: BTreeMap<u64, Conn>,
}

impl Conns {
    fn table(&self) -> std::sync::MutexGuard<'_, Table> {
        self.0.lock().unwrap_or_else(|p| p.into_inner())
    }

    /// A new connection: makes room first if there are too many.
    pub fn open(&self) -> Ticket {
        let mut t = self.table();
        if t.open.len() >= MAX_CONNECTIONS {
            let idlest = t
                .open
                .iter()
                .filter(|(_, c)| c.busy == 0)
                .min_by_key(|(id, c)| (c.since, **id))
                .map(|(id, _)| *id);
            if let Some(id) = idlest
                && let Some(c) = t.open.remove(&id)
                && let Some(a) = c.abort
            {
                a.abort();
            }
        }
        let id = t.next;
        t.next += 1;
        t.open.insert(
            id,
            Conn {
                since: Instant::now(),
                busy: 0,
                abort: None,
            },
        );
        Ticket {
            conns: self.clone(),
            id,
        }
    }

    /// How many are open.
    #[cfg(test)]
    fn len(&self) -> usize {
        self.table().open.len()
    }
}

/// One connection's place in the table, given up when dropped.
#[derive(Clone)]
pub struct Ticket {
    conns: Conns,
    id: u64,
}

impl Ticket {
    /// How to close the connection's task.
    pub fn set_abort(&self, abort: AbortHandle) {
        if let Some(c) = self.conns.table().open.get_mut(&self.id) {
            c.abort = Some(abort);
        }
    }

    /// A request on it is being answered until the returned guard drops.
    pub fn busy(&self) -> Busy {
        if let Some(c) = self.conns.table().open.get_mut(&self.id) {
            c.busy += 1;
            c.since = Instant::now();
        }
        Busy(self.clone())
    }

    /// The connection closed.
    pub fn close(&self) {
        self.conns.table().open.remove(&self.id);
    }
}

/// A request being answered.
pub struct Busy(Ticket);

impl Drop for Busy {
    fn drop(&mut self) {
        if let Some(c) = self.0.conns.table().open.get_mut(&self.0.id) {
            c.busy = c.busy.saturating_sub(1);
            c.since = Instant::now();
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_idlest_connection_makes_room_and_a_busy_one_never_does() {
        let conns = Conns::default();
        let tickets: Vec<Ticket> = (0..MAX_CONNECTIONS).map(|_| conns.open()).collect();
        // The oldest is busy: the next oldest makes room.
        let _busy = tickets[0].busy();
        let _new = conns.open();
        assert_eq!(conns.len(), MAX_CONNECTIONS);
        let open: Vec<u64> = conns.table().open.keys().copied().collect();
        assert!(open.contains(&0), "a busy connection is never closed");
        assert!(!open.contains(&1), "the idlest one made room");
        tickets[5].close();
        assert_eq!(conns.len(), MAX_CONNECTIONS - 1);
    }
}
