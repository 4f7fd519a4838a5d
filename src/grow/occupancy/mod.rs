//! The occupancy index: grown segments, and the clearance test.
//!
//! # The clearance rule
//!
//! A stem occupies the space it is drawn with: a capsule of radius `r`
//! (half its stroke width) around its centre line. A new segment `t` (from
//! `t.a` to `t.b`, the turtle's direction) conflicts with a segment `s`
//! already placed when their drawn edges come closer than the clearance `C`,
//! that is when their centre lines come closer than `C + t.r + s.r` (the
//! *threshold*; canvas units):
//!
//! - **Joint exception.** If `t` starts where `s` starts or ends (`t.a` equal,
//!   bit for bit, to `s.a` or `s.b`: a stem and the branches at its tip, two
//!   branches at one tip, consecutive stems of one branch), their strokes
//!   meet at that joint by construction, so the joint is left out: they
//!   conflict only if `t`'s far end `t.b` comes within the threshold of `s`
//!   at a point other than the joint, or `s`'s far end (the endpoint other
//!   than the joint) comes within it of `t` at a point other than the
//!   joint. So only stems that fold onto each other at a joint conflict (a
//!   branch folding back onto its stem, two branches at an angle too small
//!   for their length and width); a straight continuation never does,
//!   however short and thick its stems.
//! - **Otherwise** they conflict if the distance between the two centre
//!   lines is below the threshold (0 if they touch or cross).
//!
//! Only the new segment's *start* can be a joint: a segment that *ends* on an
//! existing stem touches it (distance 0) and conflicts, so a tree never
//! closes a loop. A threshold of 0 (`C = 0` and hairline stems) switches
//! the test off: stems may then touch and cross, and only the region bounds
//! growth.
//!
//! # The indexes
//!
//! [`Occupancy`] keeps the placed segments in an R*-tree (`rstar` 0.12, the
//! one geo uses) and asks for those whose bounding box meets the new
//! segment's box grown by `C`, then applies the exact rule above.
//! [`LocalIndex`] keeps the segments of the application being drawn, which
//! must keep the clearance from each other too: a list scanned linearly,
//! and an R*-tree once an application passes [`LOCAL_LINEAR`] segments.
//! With the region's tree of boundary edges ([`super::region`]), these are
//! the only places growth names the spatial index.
//!
//! # spade: measured, and not used here
//!
//! A Delaunay triangulation of the stems' endpoints (`spade`) answered the
//! same clearance query 3.7 to 12 times slower than the R*-tree
//! (`docs/growth.md`, *The spatial index*); it was kept behind a feature
//! for measuring until space-first growth (issue 34) put spade to work
//! where a triangulation is what is wanted, and then removed
//! (`docs/dependencies.md`).

mod capsule;

pub use capsule::{
    Cap, Seg, Seg3, SegDist, clearance_distance, conflicts, point_seg_dist2, seg_seg_dist2,
};
use rstar::{AABB, RStarInsertionStrategy, RTree, RTreeObject, RTreeParams};

/// The occupancy tree's node sizes: rstar's 3 to 6 entries, but no forced
/// reinsertion. Growth inserts a stem for every query it answers, so
/// insertion dominates; without reinsertion it costs a third less, and the
/// queries' answers (sets) are the same whatever the tree's shape, so the
/// trees grown are too. Nodes of up to 8 cost less to insert into but make
/// a larger tree that depth-first growth, which inserts all over it, pays
/// for in cache misses. Measured in docs/performance.md (rstar's default is
/// 3, 6 and 2).
pub struct OccupancyParams;

impl RTreeParams for OccupancyParams {
    const MIN_SIZE: usize = 3;
    const MAX_SIZE: usize = 6;
    const REINSERTION_COUNT: usize = 0;
    type DefaultInsertionStrategy = RStarInsertionStrategy;
}

/// A placed stem in the occupancy tree: its box, computed once (the R*-tree
/// asks an entry for its box at every comparison while it inserts and
/// splits; computing it from the ends each time was a third of growth's
/// instructions), and the stem's index in [`Occupancy::segs`], where the
/// exact test finds it. A small entry keeps the tree small: 64 bytes a
/// node entry against 80 with the stem inside (docs/performance.md).
#[derive(Debug, Clone, Copy)]
struct Placed<const N: usize> {
    env: AABB<[f64; N]>,
    index: usize,
}

impl<const N: usize> RTreeObject for Placed<N> {
    type Envelope = AABB<[f64; N]>;
    fn envelope(&self) -> Self::Envelope {
        self.env
    }
}

/// Which spatial index answers the clearance query.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Backend {
    /// R*-tree over the segments (the one index: see `docs/growth.md`).
    #[default]
    Rstar,
}

/// What the indexes need of a dimension: the distance of two stems.
pub trait Dim: SegDist + Copy + PartialEq + std::fmt::Debug {}

impl Dim for Seg {}

impl Dim for Seg3 {}

/// The grown segments and the clearance query, in the plane (`N = 2`, the
/// default) or in space (`N = 3`).
#[derive(Debug)]
pub struct Occupancy<const N: usize = 2>
where
    Cap<N>: Dim,
{
    clearance: f64,
    len: usize,
    /// The largest radius placed (the query's reach grows by it).
    max_r: f64,
    /// The placed stems, by [`Placed::index`].
    segs: Vec<Cap<N>>,
    /// The seed's stems placed, by their bits ([`Occupancy::insert_drawn`]).
    /// Membership only: never iterated.
    drawn: std::collections::HashSet<([u64; N], [u64; N], u64)>,
    inner: Inner<N>,
}

#[derive(Debug)]
enum Inner<const N: usize> {
    Rstar(RTree<Placed<N>, OccupancyParams>),
}

impl<const N: usize> Occupancy<N>
where
    Cap<N>: Dim,
{
    /// An empty index keeping clearance `clearance` (>= 0).
    pub fn new(backend: Backend, clearance: f64) -> Self {
        let inner = match backend {
            Backend::Rstar => Inner::Rstar(RTree::new_with_params()),
        };
        Occupancy {
            clearance,
            len: 0,
            max_r: 0.0,
            segs: Vec::new(),
            drawn: std::collections::HashSet::new(),
            inner,
        }
    }

    /// The clearance kept.
    pub fn clearance(&self) -> f64 {
        self.clearance
    }

    /// Number of segments placed.
    pub fn len(&self) -> usize {
        self.len
    }

    /// True if nothing is placed.
    pub fn is_empty(&self) -> bool {
        self.len == 0
    }

    /// Whether `t` conflicts with any placed segment.
    pub fn conflicts(&self, t: &Cap<N>) -> bool {
        self.conflict(t).is_some()
    }

    /// A placed segment `t` conflicts with, if any (the first the index
    /// finds).
    pub fn conflict(&self, t: &Cap<N>) -> Option<Cap<N>> {
        let c = self.clearance;
        // No placed segment's threshold with `t` is above this.
        let widest = c + t.r + self.max_r;
        if widest <= 0.0 || self.len == 0 {
            return None;
        }
        match &self.inner {
            Inner::Rstar(tree) => {
                // `any` with the hit kept aside is `find`; the release build
                // happened to make much faster code of this shape with the
                // default codegen units (docs/performance.md).
                let mut hit = None;
                tree.locate_in_envelope_intersecting(&t.reach(widest))
                    .any(|p| {
                        let s = &self.segs[p.index];
                        let near = conflicts(t, s, c);
                        if near {
                            hit = Some(*s);
                        }
                        near
                    });
                hit
            }
        }
    }

    /// Places `s`, a stem the seed draws untested. A copy of a seed stem
    /// placed changes no [`Occupancy::conflict`] answer, so it is kept but
    /// not indexed again: the trees of a forest on one point draw the same
    /// seed, and 10^5 of them grow in linear time, not quadratic. (A grown
    /// stem equal to a placed one conflicts with it: never placed.)
    pub fn insert_drawn(&mut self, s: Cap<N>) {
        if !self.drawn.insert(s.bits()) {
            self.len += 1;
            self.segs.push(s);
            return;
        }
        self.insert(s);
    }

    /// Places `s`.
    pub fn insert(&mut self, s: Cap<N>) {
        self.len += 1;
        self.max_r = self.max_r.max(s.r);
        match &mut self.inner {
            Inner::Rstar(tree) => {
                tree.insert(Placed {
                    env: s.placed_box(),
                    index: self.segs.len(),
                });
                self.segs.push(s);
            }
        }
    }
}

/// The segments of one rule application checked linearly up to this many;
/// beyond, through an R*-tree.
pub const LOCAL_LINEAR: usize = 64;

/// The segments of the rule application being drawn, in drawing order, and
/// the clearance query among them (a new segment must keep the clearance
/// from the application's own earlier segments too). Most applications
/// draw a few segments, which a scan tests fastest; one that passes
/// [`LOCAL_LINEAR`] (a large fixed figure) gets an R*-tree.
#[derive(Debug)]
pub struct LocalIndex<const N: usize = 2> {
    clearance: f64,
    segs: Vec<Cap<N>>,
    tree: Option<RTree<Cap<N>>>,
    /// The largest radius held.
    max_r: f64,
}

impl<const N: usize> LocalIndex<N>
where
    Cap<N>: Dim,
{
    /// An empty index keeping clearance `clearance` (>= 0).
    pub fn new(clearance: f64) -> Self {
        LocalIndex {
            clearance,
            segs: Vec::new(),
            tree: None,
            max_r: 0.0,
        }
    }

    /// Forgets every segment (a new application starts).
    pub fn clear(&mut self) {
        self.segs.clear();
        self.tree = None;
        self.max_r = 0.0;
    }

    /// Number of segments held.
    pub fn len(&self) -> usize {
        self.segs.len()
    }

    /// True if no segment is held.
    pub fn is_empty(&self) -> bool {
        self.segs.is_empty()
    }

    /// Whether `t` conflicts with any segment held.
    pub fn conflicts(&self, t: &Cap<N>) -> bool {
        self.conflict(t).is_some()
    }

    /// A segment held that `t` conflicts with, if any (the first found).
    pub fn conflict(&self, t: &Cap<N>) -> Option<Cap<N>> {
        let c = self.clearance;
        let widest = c + t.r + self.max_r;
        if widest <= 0.0 {
            return None;
        }
        match &self.tree {
            Some(tree) => tree
                .locate_in_envelope_intersecting(&t.reach(widest))
                .find(|s| conflicts(t, s, c))
                .copied(),
            None => self.segs.iter().find(|s| conflicts(t, s, c)).copied(),
        }
    }

    /// Where `s` is in drawing order (0 for the first segment held), if it
    /// is held: linear, for explaining a failure, not for growth.
    pub fn position(&self, s: &Cap<N>) -> Option<usize> {
        self.segs.iter().position(|x| x == s)
    }

    /// Adds `s`.
    pub fn insert(&mut self, s: Cap<N>) {
        self.segs.push(s);
        self.max_r = self.max_r.max(s.r);
        match &mut self.tree {
            Some(tree) => tree.insert(s),
            // With no clearance and hairlines nothing is ever queried.
            None if self.clearance + self.max_r > 0.0 && self.segs.len() == LOCAL_LINEAR => {
                self.tree = Some(RTree::bulk_load(self.segs.clone()));
            }
            None => {}
        }
    }

    /// Hands the segments over in drawing order, leaving the index empty.
    pub fn drain(&mut self) -> impl Iterator<Item = Cap<N>> + '_ {
        self.tree = None;
        self.max_r = 0.0;
        self.segs.drain(..)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn seg(ax: f64, ay: f64, bx: f64, by: f64) -> Seg {
        Seg::new([ax, ay], [bx, by])
    }

    /// A seed stem drawn again (the trees of a forest on one point) is
    /// kept and counted but indexed once, and every answer is the same as
    /// with one copy; a different stem is indexed.
    #[test]
    fn a_seed_stem_drawn_again_is_indexed_once() {
        let mut occ = Occupancy::new(Backend::Rstar, 1.0);
        let trunk = seg(0.0, 0.0, 0.0, -10.0);
        for _ in 0..1000 {
            occ.insert_drawn(trunk);
        }
        occ.insert_drawn(seg(50.0, 0.0, 50.0, -10.0));
        // The one variant.
        #[allow(irrefutable_let_patterns)]
        let Inner::Rstar(tree) = &occ.inner else {
            unreachable!()
        };
        assert_eq!(tree.size(), 2);
        assert_eq!(occ.segs.len(), 1001);
        let mut one = Occupancy::new(Backend::Rstar, 1.0);
        one.insert(trunk);
        one.insert(seg(50.0, 0.0, 50.0, -10.0));
        for t in [
            seg(0.0, -10.0, -5.0, -18.66),
            seg(0.0, -10.0, 0.0, -20.0),
            seg(0.5, 0.0, 0.5, -10.0),
            seg(30.0, 0.0, 30.0, -10.0),
        ] {
            assert_eq!(occ.conflicts(&t), one.conflicts(&t), "{t:?}");
        }
    }

    #[test]
    fn branches_at_a_joint_do_not_conflict_but_folding_back_does() {
        let stem = seg(0.0, 0.0, 0.0, -10.0);
        // A branch 30 degrees off the stem's line, from its tip.
        let br = seg(0.0, -10.0, -5.0, -10.0 - 8.660_254_037_844_386);
        assert!(!conflicts(&br, &stem, 1.0));
        // Folding back along the stem: its far end lies on the stem.
        let back = seg(0.0, -10.0, 0.5, -1.0);
        assert!(conflicts(&back, &stem, 1.0));
        // Sibling branches 60 degrees apart, length 10: far ends 8.66 off.
        let left = seg(0.0, -10.0, 5.0, -18.66);
        assert!(!conflicts(&left, &br, 1.0));
        assert!(conflicts(&left, &br, 9.0));
    }

    /// The distance the clearance test measured: with a joint, the far
    /// ends' (not the joint itself); without, the segments'. A segment
    /// conflicts exactly when it is below the threshold.
    #[test]
    fn clearance_distance_is_what_the_test_compares() {
        let stem = seg(0.0, 0.0, 0.0, -10.0);
        // Siblings 60 degrees apart, length 10: far ends 10 sin 60 off.
        let br = seg(0.0, -10.0, -5.0, -10.0 - 8.660_254_037_844_386);
        let left = seg(0.0, -10.0, 5.0, -10.0 - 8.660_254_037_844_386);
        assert!((clearance_distance(&left, &br) - 8.660_254_037_844_386).abs() < 1e-12);
        // A straight continuation: only the joint is near, never a conflict.
        let on = seg(0.0, -10.0, 0.0, -20.0);
        assert_eq!(clearance_distance(&on, &stem), f64::INFINITY);
        // Folding back: the far end lies on the stem.
        let back = seg(0.0, -10.0, 0.5, -1.0);
        assert!((clearance_distance(&back, &stem) - 0.5).abs() < 1e-12);
        // No joint: parallel stems 3 apart.
        let far = seg(3.0, 0.0, 3.0, -10.0);
        assert_eq!(clearance_distance(&far, &stem), 3.0);
        for (t, s) in [(left, br), (on, stem), (back, stem), (far, stem)] {
            for c in [0.4, 0.6, 3.5, 9.0] {
                assert_eq!(conflicts(&t, &s, c), clearance_distance(&t, &s) < c);
            }
        }
    }

    /// Stems as drawn: the threshold is C plus both half widths.
    #[test]
    fn wide_stems_keep_the_clearance_between_their_edges() {
        // Two parallel stems 3 apart: hairlines with C=1 are fine; 2 wide
        // each (r=1) with C=1 need 3, which is just met; r=1.1 is not.
        let a = Seg::capsule([0.0, 0.0], [0.0, 10.0], 1.0);
        let b = Seg::capsule([3.0, 0.0], [3.0, 10.0], 1.0);
        assert!(!conflicts(&b, &a, 1.0));
        let b_wide = Seg::capsule([3.0, 0.0], [3.0, 10.0], 1.1);
        assert!(conflicts(&b_wide, &a, 1.0));
        // C=0 with wide stems still keeps the strokes apart.
        assert!(conflicts(
            &Seg::capsule([1.5, 0.0], [1.5, 9.0], 1.0),
            &a,
            0.0
        ));
        // A straight continuation never conflicts, however short and thick.
        let stem = Seg::capsule([0.0, 0.0], [0.0, -1.0], 2.0);
        let next = Seg::capsule([0.0, -1.0], [0.0, -2.0], 2.0);
        assert!(!conflicts(&next, &stem, 1.0));
        // Nor does a branch whose far end's nearest point on the stem is
        // the joint itself (it turns away by more than 90 degrees).
        let away = Seg::capsule([0.0, -1.0], [1.0, -1.5], 2.0);
        assert!(!conflicts(&away, &stem, 1.0));
        // Branches at a joint, 60 degrees apart and 10 long: far ends 8.66
        // from the other; 4 wide each plus C=1 needs 5: fine; 8 wide each
        // plus C=1 needs 9: they fold onto each other.
        let br = seg(0.0, -10.0, -5.0, -10.0 - 8.660_254_037_844_386);
        let left = seg(0.0, -10.0, 5.0, -18.66);
        let wide = |s: Seg, r: f64| Seg { r, ..s };
        assert!(!conflicts(&wide(left, 2.0), &wide(br, 2.0), 1.0));
        assert!(conflicts(&wide(left, 4.0), &wide(br, 4.0), 1.0));
    }

    #[test]
    fn ending_on_a_stem_conflicts() {
        let s = seg(0.0, 0.0, 10.0, 0.0);
        assert!(conflicts(&seg(5.0, 5.0, 5.0, 0.0), &s, 0.5));
        assert!(conflicts(&seg(5.0, 5.0, 5.0, -5.0), &s, 0.5)); // crossing
        assert!(!conflicts(&seg(5.0, 5.0, 5.0, 1.0), &s, 0.5));
        assert!(conflicts(&seg(5.0, 5.0, 5.0, 1.0), &s, 1.5));
        // A segment ending exactly at s's endpoint is not a joint for it.
        assert!(conflicts(&seg(10.0, 5.0, 10.0, 0.0), &s, 0.5));
        assert!(!conflicts(&seg(10.0, 5.0, 10.0, 0.0), &s, 0.0));
    }

    #[test]
    fn backends_agree_with_brute_force() {
        // A pseudo-random field of short segments.
        let mut x: u64 = 0x9e37_79b9_7f4a_7c15;
        let mut next = || {
            x ^= x << 13;
            x ^= x >> 7;
            x ^= x << 17;
            (x >> 11) as f64 / (1u64 << 53) as f64
        };
        let mut all = Vec::new();
        for _ in 0..400 {
            let (ax, ay) = (next() * 100.0, next() * 100.0);
            let (dx, dy) = (next() * 6.0 - 3.0, next() * 6.0 - 3.0);
            // Widths from hairline to 2 (radius 0 to 1): the index's reach
            // must grow with the widest stem placed.
            let r = next();
            all.push(Seg::capsule([ax, ay], [ax + dx, ay + dy], r));
        }
        let backends = [Backend::Rstar];
        for backend in backends {
            let mut occ = Occupancy::new(backend, 1.5);
            let mut placed: Vec<Seg> = Vec::new();
            for s in &all {
                let brute = placed.iter().any(|p| conflicts(s, p, 1.5));
                assert_eq!(occ.conflicts(s), brute, "{backend:?}");
                if !brute {
                    occ.insert(*s);
                    placed.push(*s);
                }
            }
            assert!(placed.len() > 20 && placed.len() < 400);
            assert_eq!(occ.len(), placed.len());
        }
    }
}
