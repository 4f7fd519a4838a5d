//! Stems as capsules, in the plane and in space, and the clearance rule
//! between two of them (the module documentation of [`super`] states it).
//!
//! One type serves both: [`Cap<N>`] with `N = 2` ([`Seg`]) or `N = 3`
//! ([`Seg3`]). Everything but the distance between two centre lines is
//! written once for both; that distance is the plane's orientation test
//! in 2D, and the closest points of two lines (Ericson, *Real-Time
//! Collision Detection* 5.1.9) in 3D, except for two stems in one plane
//! z = const, which take the 2D computation so that a planar 3D tree makes
//! the 2D tree's decisions bit for bit.

use rstar::{AABB, RTreeObject};

/// One straight stem from `a` to `b` (the turtle's direction), drawn
/// `2 r` wide, canvas units, in `N` dimensions.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Cap<const N: usize> {
    /// Start (where the turtle was).
    pub a: [f64; N],
    /// End (where the turtle went).
    pub b: [f64; N],
    /// Half the stroke width: the radius of the capsule it is drawn as.
    pub r: f64,
}

/// A stem in the plane.
pub type Seg = Cap<2>;

/// A stem in space.
pub type Seg3 = Cap<3>;

impl<const N: usize> Cap<N> {
    /// A hairline segment (radius 0) from two points.
    pub fn new(a: [f64; N], b: [f64; N]) -> Self {
        Cap { a, b, r: 0.0 }
    }

    /// A segment drawn `2 r` wide (a negative radius counts as 0).
    pub fn capsule(a: [f64; N], b: [f64; N], r: f64) -> Self {
        Cap {
            a,
            b,
            r: r.max(0.0),
        }
    }

    /// The box of the points within `c` of the segment's bounding box:
    /// every segment that can come within `c` of it has its box meet it.
    pub fn reach(&self, c: f64) -> AABB<[f64; N]> {
        let lo = std::array::from_fn(|i| self.a[i].min(self.b[i]) - c);
        let hi = std::array::from_fn(|i| self.a[i].max(self.b[i]) + c);
        AABB::from_corners(lo, hi)
    }

    /// The box a placed stem has in the occupancy tree: any box holding
    /// its centre line will do (queries find candidates by it and test
    /// them exactly). In the plane its bounding box. In space grown by the
    /// radius, and where it is flat, to a thousandth of the stem's length:
    /// a planar tree's boxes would otherwise all be flat in z, and the
    /// R*-tree, which chooses where to insert by volumes, builds a poor
    /// tree of boxes that have none (growth in a prism took 3.2 times the
    /// 2D time; with an eighth of the length, growth in a cube 1.6 times
    /// as long as with none, from the looser boxes).
    pub fn placed_box(&self) -> AABB<[f64; N]> {
        if N == 2 {
            return self.envelope();
        }
        let d = sub(self.b, self.a);
        let thin = dot(d, d).sqrt() / 1024.0;
        let lo = std::array::from_fn(|i| self.a[i].min(self.b[i]) - self.r.max(thin - d[i].abs()));
        let hi = std::array::from_fn(|i| self.a[i].max(self.b[i]) + self.r.max(thin - d[i].abs()));
        AABB::from_corners(lo, hi)
    }

    /// The bits of the stem, for telling a copy of it.
    pub(super) fn bits(&self) -> ([u64; N], [u64; N], u64) {
        (
            self.a.map(f64::to_bits),
            self.b.map(f64::to_bits),
            self.r.to_bits(),
        )
    }
}

impl<const N: usize> RTreeObject for Cap<N> {
    type Envelope = AABB<[f64; N]>;
    fn envelope(&self) -> Self::Envelope {
        AABB::from_corners(self.a, self.b)
    }
}

/// The squared distance between two segments' centre lines (0 if they
/// cross): the part of the clearance rule that depends on the dimension.
pub trait SegDist {
    /// Squared distance between `t` and `s`.
    fn seg_seg_dist2(t: &Self, s: &Self) -> f64;
}

impl SegDist for Seg {
    fn seg_seg_dist2(t: &Self, s: &Self) -> f64 {
        seg_seg_dist2(t, s)
    }
}

impl SegDist for Seg3 {
    fn seg_seg_dist2(t: &Self, s: &Self) -> f64 {
        let z = t.a[2];
        if t.b[2] == z && s.a[2] == z && s.b[2] == z {
            let flat = |c: &Seg3| Seg::new([c.a[0], c.a[1]], [c.b[0], c.b[1]]);
            return seg_seg_dist2(&flat(t), &flat(s));
        }
        space_seg_seg_dist2(t, s)
    }
}

fn sub<const N: usize>(p: [f64; N], q: [f64; N]) -> [f64; N] {
    std::array::from_fn(|i| p[i] - q[i])
}

fn dot<const N: usize>(p: [f64; N], q: [f64; N]) -> f64 {
    let mut s = p[0] * q[0];
    for i in 1..N {
        s += p[i] * q[i];
    }
    s
}

/// Squared distance between two segments in space: the closest points of
/// the two lines, clamped to the segments.
fn space_seg_seg_dist2(t: &Seg3, s: &Seg3) -> f64 {
    let (d1, d2, r) = (sub(t.b, t.a), sub(s.b, s.a), sub(t.a, s.a));
    let (a, e, f) = (dot(d1, d1), dot(d2, d2), dot(d2, r));
    let (u, v) = if a == 0.0 && e == 0.0 {
        (0.0, 0.0)
    } else if a == 0.0 {
        (0.0, (f / e).clamp(0.0, 1.0))
    } else {
        let c = dot(d1, r);
        if e == 0.0 {
            ((-c / a).clamp(0.0, 1.0), 0.0)
        } else {
            let b = dot(d1, d2);
            let denom = a * e - b * b;
            let u = if denom > 0.0 {
                ((b * f - c * e) / denom).clamp(0.0, 1.0)
            } else {
                0.0
            };
            let v = (b * u + f) / e;
            if v < 0.0 {
                ((-c / a).clamp(0.0, 1.0), 0.0)
            } else if v > 1.0 {
                (((b - c) / a).clamp(0.0, 1.0), 1.0)
            } else {
                (u, v)
            }
        }
    };
    let gap: [f64; 3] = std::array::from_fn(|i| (t.a[i] + d1[i] * u) - (s.a[i] + d2[i] * v));
    dot(gap, gap)
}

/// The joint, and `s`'s far end, if `t` starts on an end of `s`.
fn joint<const N: usize>(t: &Cap<N>, s: &Cap<N>) -> Option<([f64; N], [f64; N])> {
    if t.a == s.a {
        Some((s.a, s.b))
    } else if t.a == s.b {
        Some((s.b, s.a))
    } else {
        None
    }
}

/// Whether a new segment `t` conflicts with a placed segment `s` under
/// clearance `c` (the rule in the module documentation of [`super`]).
pub fn conflicts<const N: usize>(t: &Cap<N>, s: &Cap<N>, c: f64) -> bool
where
    Cap<N>: SegDist,
{
    let threshold = c + t.r + s.r;
    if threshold <= 0.0 {
        return false;
    }
    let c2 = threshold * threshold;
    match joint(t, s) {
        Some((j, far_s)) => {
            let near = |p: [f64; N], seg: &Cap<N>| {
                let (d2, at) = point_seg_nearest(p, seg);
                d2 < c2 && at != j
            };
            near(t.b, s) || near(far_s, t)
        }
        None => Cap::<N>::seg_seg_dist2(t, s) < c2,
    }
}

/// The distance between the centre lines of `t` and `s` that the clearance
/// test of [`conflicts`] measures: with a joint (`t` starts on an end of
/// `s`), the smaller of the distances from `t`'s far end to `s` and from
/// `s`'s far end to `t` that are not reached at the joint (infinite if
/// both are); otherwise the distance between the segments. `t` conflicts
/// with `s` exactly when it is below `c + t.r + s.r` (and that is above 0).
pub fn clearance_distance<const N: usize>(t: &Cap<N>, s: &Cap<N>) -> f64
where
    Cap<N>: SegDist,
{
    match joint(t, s) {
        Some((j, far_s)) => {
            let away = |p: [f64; N], seg: &Cap<N>| {
                let (d2, at) = point_seg_nearest(p, seg);
                if at != j { d2 } else { f64::INFINITY }
            };
            away(t.b, s).min(away(far_s, t)).sqrt()
        }
        None => Cap::<N>::seg_seg_dist2(t, s).sqrt(),
    }
}

/// Squared distance from point `p` to segment `s`, and the point of `s`
/// nearest to `p` (exactly an endpoint of `s` when that is the nearest).
/// In the plane z = const, a 3D point and stem give the 2D answer bit for
/// bit (the z terms are 0 and add nothing).
fn point_seg_nearest<const N: usize>(p: [f64; N], s: &Cap<N>) -> (f64, [f64; N]) {
    let d = sub(s.b, s.a);
    let q = sub(p, s.a);
    let len2 = dot(d, d);
    let t = if len2 > 0.0 {
        (dot(q, d) / len2).clamp(0.0, 1.0)
    } else {
        0.0
    };
    let at = if t <= 0.0 {
        s.a
    } else if t >= 1.0 {
        s.b
    } else {
        std::array::from_fn(|i| s.a[i] + t * d[i])
    };
    let e: [f64; N] = std::array::from_fn(|i| q[i] - t * d[i]);
    (dot(e, e), at)
}

/// Squared distance from point `p` to segment `s`.
pub fn point_seg_dist2<const N: usize>(p: [f64; N], s: &Cap<N>) -> f64 {
    point_seg_nearest(p, s).0
}

fn orient(a: [f64; 2], b: [f64; 2], c: [f64; 2]) -> f64 {
    (b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0])
}

/// Squared distance between two segments in the plane (0 if they cross).
pub fn seg_seg_dist2(t: &Seg, s: &Seg) -> f64 {
    let d1 = orient(s.a, s.b, t.a);
    let d2 = orient(s.a, s.b, t.b);
    let d3 = orient(t.a, t.b, s.a);
    let d4 = orient(t.a, t.b, s.b);
    if ((d1 > 0.0 && d2 < 0.0) || (d1 < 0.0 && d2 > 0.0))
        && ((d3 > 0.0 && d4 < 0.0) || (d3 < 0.0 && d4 > 0.0))
    {
        return 0.0;
    }
    // Not properly crossing: the distance is reached at an endpoint (touching
    // cases give 0 here too).
    point_seg_dist2(t.a, s)
        .min(point_seg_dist2(t.b, s))
        .min(point_seg_dist2(s.a, t))
        .min(point_seg_dist2(s.b, t))
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Distance between two segments in space by dense sampling of both
    /// (an independent computation): an upper bound within the sampling
    /// step of the true distance.
    fn sampled(t: &Seg3, s: &Seg3) -> f64 {
        let n = 400;
        let at = |c: &Seg3, k: usize| -> [f64; 3] {
            let u = k as f64 / n as f64;
            std::array::from_fn(|i| c.a[i] + (c.b[i] - c.a[i]) * u)
        };
        let mut best = f64::INFINITY;
        for i in 0..=n {
            let p = at(t, i);
            for j in 0..=n {
                let q = at(s, j);
                let d =
                    ((p[0] - q[0]).powi(2) + (p[1] - q[1]).powi(2) + (p[2] - q[2]).powi(2)).sqrt();
                best = best.min(d);
            }
        }
        best
    }

    #[test]
    fn space_distance_matches_sampling_and_hand_values() {
        // Skew lines one apart: x axis at z = 0 and y axis at z = 1.
        let t = Seg3::new([-5.0, 0.0, 0.0], [5.0, 0.0, 0.0]);
        let s = Seg3::new([0.0, -5.0, 1.0], [0.0, 5.0, 1.0]);
        assert_eq!(Seg3::seg_seg_dist2(&t, &s), 1.0);
        // Parallel, offset along their line: end to end 3 apart along x
        // and 4 in z: 5.
        let p = Seg3::new([0.0, 0.0, 0.0], [1.0, 0.0, 0.0]);
        let q = Seg3::new([4.0, 0.0, 4.0], [6.0, 0.0, 4.0]);
        assert!((Seg3::seg_seg_dist2(&p, &q) - 25.0).abs() < 1e-12);
        // A point (zero-length) against a stem.
        let o = Seg3::new([0.0, 3.0, 4.0], [0.0, 3.0, 4.0]);
        assert!((Seg3::seg_seg_dist2(&o, &t) - 25.0).abs() < 1e-12);
        let mut x: u64 = 0x2545_f491_4f6c_dd1d;
        let mut next = || {
            x ^= x << 13;
            x ^= x >> 7;
            x ^= x << 17;
            (x >> 11) as f64 / (1u64 << 53) as f64 * 10.0 - 5.0
        };
        for _ in 0..60 {
            let t = Seg3::new([next(), next(), next()], [next(), next(), next()]);
            let s = Seg3::new([next(), next(), next()], [next(), next(), next()]);
            let exact = Seg3::seg_seg_dist2(&t, &s).sqrt();
            let approx = sampled(&t, &s);
            // Sampling finds a distance no smaller, and within its step.
            assert!(exact <= approx + 1e-12, "{exact} {approx}");
            assert!(approx - exact < 0.05, "{exact} {approx}");
        }
    }

    #[test]
    fn a_flat_3d_pair_measures_as_the_2d_pair() {
        let t = Seg::new([0.1, 0.3], [7.7, -2.9]);
        let s = Seg::new([3.3, 1.9], [-1.0, 0.7]);
        let lift = |c: &Seg| Seg3::new([c.a[0], c.a[1], 2.5], [c.b[0], c.b[1], 2.5]);
        assert_eq!(
            Seg3::seg_seg_dist2(&lift(&t), &lift(&s)),
            seg_seg_dist2(&t, &s)
        );
        for c in [0.5, 1.0, 3.0] {
            assert_eq!(conflicts(&lift(&t), &lift(&s), c), conflicts(&t, &s, c));
        }
    }
}
