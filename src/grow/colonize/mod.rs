//! Space-first growth (`O=space`, `stl-language.md` section 14): the order
//! in which growth points are decided, driven by attraction points
//! scattered over the region, after Runions, Lane and Prusinkiewicz's
//! space colonization (2007).
//!
//! - **Points** ([`sample`]): `N=` of them, uniform over the region (the
//!   plane: by area over the triangles of spade's constrained Delaunay
//!   triangulation of the outline and its holes; space: by volume, drawn
//!   in the region's box and kept where the region holds them), from the
//!   seed `V=`. Without a region there are none, and space-first growth
//!   decides in `bfs` order.
//! - **Ownership.** A living point belongs to the nearest waiting growth
//!   point within that growth point's reach (ties: the one made first): `Q=`
//!   if written, else four stem lengths at the order its stems would be
//!   drawn, so deep tips of a length decrement reach less, as their stems
//!   kill less; a growth point's *score* is the number of points that
//!   belong to it.
//! - **Order.** The waiting growth point with the highest score is decided
//!   first; ties, and the growth points that score nothing, in `bfs` order
//!   (the order they were made). So growth reaches into empty parts of the
//!   outline before it thickens what is full.
//! - **Killing.** A point dies once a placed stem passes within the kill
//!   distance of it: the stem's own length (the segment length at its
//!   order).
//!
//! `Colonizer` keeps the points and the waiting growth points in a
//! uniform grid of cells as wide as the reach (`grid.rs`; two R*-trees
//! did the same 4.5 times slower than bfs at 10^6 stems, and a
//! triangulation cannot delete cheaply: `docs/dependencies.md`) and the
//! scores in a heap whose stale entries are skipped. Every answer is a function of the points and
//! the growth points alone (never of a tree's shape or an iteration
//! order), so the order is the same on every machine.

mod grid;
pub mod sample;

use std::cmp::Reverse;
use std::collections::{BinaryHeap, VecDeque};

use super::occupancy::{Cap, point_seg_dist2};
use grid::{Fixed, Grid};

/// The default reach `Q=`, in stem lengths at the order a growth point's
/// stems would be drawn (`L` itself without a length decrement).
pub const DEFAULT_REACH_IN_L: f64 = 4.0;

/// No owner.
const NONE: u32 = u32::MAX;

/// A waiting growth point.
#[derive(Debug)]
struct Slot<const N: usize, G> {
    gp: Option<G>,
    pos: [f64; N],
    /// When it was made: `bfs` order.
    seq: u64,
    /// The points that belong to it.
    score: u32,
    /// Its squared reach.
    reach2: f64,
    /// Its score changed since its last heap entry.
    dirty: bool,
    /// The previous and next slot listed in its cell ([`NONE`]: none).
    prev: u32,
    next: u32,
}

/// The attraction points and the growth points waiting for their decision,
/// in space-first order (the module documentation).
pub(super) struct Colonizer<const N: usize, G> {
    reach: f64,
    reach2: f64,
    pts: Vec<[f64; N]>,
    grid: Grid<N>,
    /// The points, by cell.
    cells: Fixed,
    /// By point: alive.
    alive: Vec<bool>,
    living: usize,
    /// By point: the slot it belongs to, and its squared distance there.
    owner: Vec<(u32, f64)>,
    slots: Vec<Slot<N, G>>,
    free: Vec<u32>,
    /// The waiting growth points (slots) listed by cell: the first of a
    /// doubly linked list through the slots (no allocation a cell).
    waiting: Vec<u32>,
    /// (score, earliest first, slot) of the growth points in slots. A
    /// slot's highest entry is at least its score: a score that rises
    /// gets a new entry, one that falls keeps its entry, corrected when it
    /// comes to the top. An entry is stale unless the slot still holds
    /// that growth point (`seq`).
    heap: BinaryHeap<(u32, Reverse<u64>, u32)>,
    /// The growth points made with no living point within reach, which
    /// score nothing for good (points only die), with their `seq`: in the
    /// order made, so the earliest is first. They need no slot, and
    /// orphaned points need not look for them.
    idle: VecDeque<(u64, G)>,
    dirty: Vec<u32>,
    next_seq: u64,
    live: usize,
    /// Scratch: the points a query found.
    found: Vec<u32>,
}

impl<const N: usize, G> Colonizer<N, G> {
    /// The colonizer of `points`, with reach `reach`.
    pub(super) fn new(points: Vec<[f64; N]>, reach: f64) -> Self {
        let grid = Grid::new(&points, reach);
        // Numbered by cell (stably), a cell's points are neighbours in
        // memory; which point is which changes no answer.
        let (cells, points) = Fixed::sort(&grid, &points);
        let waiting = if points.is_empty() {
            Vec::new()
        } else {
            vec![NONE; grid.cells()]
        };
        Colonizer {
            reach,
            reach2: reach * reach,
            owner: vec![(NONE, f64::INFINITY); points.len()],
            alive: vec![true; points.len()],
            living: points.len(),
            pts: points,
            grid,
            cells,
            slots: Vec::new(),
            free: Vec::new(),
            waiting,
            heap: BinaryHeap::new(),
            idle: VecDeque::new(),
            dirty: Vec::new(),
            next_seq: 0,
            live: 0,
            found: Vec::new(),
        }
    }

    /// A growth point at `pos` waits for its decision; it scores the
    /// points within `reach` (at most the colonizer's).
    pub(super) fn push(&mut self, pos: [f64; N], reach: f64, gp: G) {
        let reach2 = (reach * reach).min(self.reach2);
        let seq = self.next_seq;
        self.next_seq += 1;
        let mut found = std::mem::take(&mut self.found);
        found.clear();
        if !self.pts.is_empty() {
            self.living_near(pos, self.reach, &mut found);
            found.retain(|&p| dist2(self.pts[p as usize], pos) <= reach2);
        }
        if found.is_empty() {
            // No point within reach: none can ever belong to it (points
            // only die), so it waits in the order made, with no slot.
            self.found = found;
            self.idle.push_back((seq, gp));
            return;
        }
        let cell = self.grid.cell_of(pos);
        let head = self.waiting[cell];
        let slot = Slot {
            gp: Some(gp),
            pos,
            seq,
            score: 0,
            reach2,
            dirty: false,
            prev: NONE,
            next: head,
        };
        let s = match self.free.pop() {
            Some(s) => {
                self.slots[s as usize] = slot;
                s
            }
            None => {
                self.slots.push(slot);
                (self.slots.len() - 1) as u32
            }
        };
        if head != NONE {
            self.slots[head as usize].prev = s;
        }
        self.waiting[cell] = s;
        self.live += 1;
        for &p in &found {
            let d2 = dist2(self.pts[p as usize], pos);
            let (old, od2) = self.owner[p as usize];
            // The growth point made first keeps a tie.
            if d2 < od2 {
                if old != NONE {
                    self.change(old, -1);
                }
                self.owner[p as usize] = (s, d2);
                self.slots[s as usize].score += 1;
            }
        }
        self.found = found;
        self.heap
            .push((self.slots[s as usize].score, Reverse(seq), s));
        self.flush();
    }

    /// The growth point to decide next, and its score (the points that
    /// belonged to it). Its points go to the nearest other waiting growth
    /// points within reach.
    pub(super) fn pop(&mut self) -> Option<(G, u32)> {
        if self.heap.len() > 4 * self.live + 1024 {
            self.compact();
        }
        // The heap's best true entry, if any.
        let best = loop {
            let Some(&(score, Reverse(seq), s)) = self.heap.peek() else {
                break None;
            };
            let slot = &self.slots[s as usize];
            if slot.gp.is_none() || slot.seq != seq || slot.score > score {
                self.heap.pop();
            } else if slot.score < score {
                // It fell since: its true entry goes in.
                let fell = (slot.score, Reverse(seq), s);
                self.heap.pop();
                self.heap.push(fell);
            } else {
                break Some((score, Reverse(seq), s));
            }
        };
        let idle_first = match (best, self.idle.front()) {
            (_, None) => false,
            (None, Some(_)) => true,
            (Some((score, Reverse(b), _)), Some(&(i, _))) => score == 0 && i < b,
        };
        if idle_first {
            return self.idle.pop_front().map(|(_, gp)| (gp, 0));
        }
        let (score, _, s) = best?;
        self.heap.pop();
        let slot = &mut self.slots[s as usize];
        let gp = slot.gp.take().expect("waiting");
        let pos = slot.pos;
        slot.score = 0;
        self.live -= 1;
        self.free.push(s);
        self.unlist(s, pos);
        self.orphan(s, pos);
        Some((gp, score))
    }

    /// Takes the slot `s` at `pos` out of its cell's list.
    fn unlist(&mut self, s: u32, pos: [f64; N]) {
        let (prev, next) = {
            let slot = &self.slots[s as usize];
            (slot.prev, slot.next)
        };
        if prev == NONE {
            self.waiting[self.grid.cell_of(pos)] = next;
        } else {
            self.slots[prev as usize].next = next;
        }
        if next != NONE {
            self.slots[next as usize].prev = prev;
        }
    }

    /// Gives the points of the slot `s` (at `pos`, no longer waiting) to
    /// the nearest waiting growth points within reach.
    fn orphan(&mut self, s: u32, pos: [f64; N]) {
        let mut found = std::mem::take(&mut self.found);
        self.living_near(pos, self.reach, &mut found);
        found.retain(|&p| self.owner[p as usize].0 == s);
        for &p in &found {
            let at = self.pts[p as usize];
            let mut best = (NONE, f64::INFINITY, u64::MAX);
            let (waiting, slots) = (&self.waiting, &self.slots);
            self.grid.near(at, self.reach, |c| {
                let mut w = waiting[c];
                while w != NONE {
                    let slot = &slots[w as usize];
                    let d2 = dist2(at, slot.pos);
                    if d2 <= slot.reach2 && (d2, slot.seq) < (best.1, best.2) {
                        best = (w, d2, slot.seq);
                    }
                    w = slot.next;
                }
            });
            self.owner[p as usize] = (best.0, best.1);
            if best.0 != NONE {
                self.change(best.0, 1);
            }
        }
        self.found = found;
        self.flush();
    }

    /// Kills the living points within `dist` of the centre line of `stem`;
    /// returns how many died.
    pub(super) fn kill(&mut self, stem: &Cap<N>, dist: f64) -> u64 {
        if self.living == 0 {
            return 0;
        }
        let lo = std::array::from_fn(|i| stem.a[i].min(stem.b[i]) - dist);
        let hi = std::array::from_fn(|i| stem.a[i].max(stem.b[i]) + dist);
        let d2 = dist * dist;
        let mut found = std::mem::take(&mut self.found);
        found.clear();
        let (cells, alive, pts) = (&self.cells, &self.alive, &self.pts);
        self.grid.each_cell(lo, hi, |c| {
            found.extend(
                cells
                    .in_cell(c)
                    .filter(|&p| alive[p as usize] && point_seg_dist2(pts[p as usize], stem) <= d2),
            );
        });
        for &p in &found {
            self.alive[p as usize] = false;
            self.living -= 1;
            let (o, _) = self.owner[p as usize];
            if o != NONE {
                self.change(o, -1);
            }
            self.owner[p as usize] = (NONE, f64::INFINITY);
        }
        let n = found.len() as u64;
        self.found = found;
        self.flush();
        n
    }

    /// Into `found`: the living points in the cells within `r` of `pos`
    /// (a superset of those within `r`).
    fn living_near(&self, pos: [f64; N], r: f64, found: &mut Vec<u32>) {
        found.clear();
        self.grid.near(pos, r, |c| {
            found.extend(self.cells.in_cell(c).filter(|&p| self.alive[p as usize]));
        });
    }

    /// Changes the score of slot `s` by `by`, if it still waits. Only a
    /// rise needs a new heap entry (the heap's invariant).
    fn change(&mut self, s: u32, by: i32) {
        let slot = &mut self.slots[s as usize];
        if slot.gp.is_none() {
            return;
        }
        slot.score = slot.score.saturating_add_signed(by);
        if by > 0 && !slot.dirty {
            slot.dirty = true;
            self.dirty.push(s);
        }
    }

    /// Gives every slot whose score changed its heap entry.
    fn flush(&mut self) {
        for s in self.dirty.drain(..) {
            let slot = &mut self.slots[s as usize];
            slot.dirty = false;
            if slot.gp.is_some() {
                self.heap.push((slot.score, Reverse(slot.seq), s));
            }
        }
    }

    /// Rebuilds the heap from the waiting growth points (its stale entries
    /// outgrew it).
    fn compact(&mut self) {
        let entries: Vec<_> = self
            .slots
            .iter()
            .enumerate()
            .filter(|(_, s)| s.gp.is_some())
            .map(|(i, s)| (s.score, Reverse(s.seq), i as u32))
            .collect();
        self.heap = BinaryHeap::from(entries);
    }
}

/// The squared distance of two points.
fn dist2<const N: usize>(a: [f64; N], b: [f64; N]) -> f64 {
    (0..N).map(|i| (a[i] - b[i]) * (a[i] - b[i])).sum()
}
