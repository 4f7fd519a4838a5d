//! The spade index (feature `spade-index`): an experiment kept for
//! measuring, see the module documentation of [`super`].

use super::{PointIndex, Seg, conflicts};
use spade::{
    DelaunayTriangulation, FloatTriangulation, HasPosition, HierarchyHintGenerator, Point2,
    Triangulation,
};

fn len(s: &Seg) -> f64 {
    let dx = s.b[0] - s.a[0];
    let dy = s.b[1] - s.a[1];
    (dx * dx + dy * dy).sqrt()
}

/// A vertex of the spade index: an endpoint and its number.
#[derive(Debug, Clone, Copy)]
struct Vertex {
    pos: Point2<f64>,
    id: u32,
}

impl HasPosition for Vertex {
    type Scalar = f64;
    fn position(&self) -> Point2<f64> {
        self.pos
    }
}

type Dt = DelaunayTriangulation<Vertex, (), (), (), HierarchyHintGenerator<f64>>;

/// Endpoints in a Delaunay triangulation; each endpoint lists the segments
/// that end there.
#[derive(Default)]
pub(super) struct SpadeIndex {
    dt: Dt,
    segs: Vec<Seg>,
    /// Segments at each vertex id.
    at: Vec<Vec<u32>>,
    /// Coordinates spade cannot take (beyond its range): scanned linearly.
    odd: Vec<u32>,
    max_len: f64,
    /// Query stamps, to visit each segment once per query.
    seen: std::cell::RefCell<(u32, Vec<u32>)>,
}

impl std::fmt::Debug for SpadeIndex {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("SpadeIndex")
            .field("segments", &self.segs.len())
            .finish()
    }
}

impl SpadeIndex {
    fn vertex_for(&mut self, p: [f64; 2]) -> Option<u32> {
        let pos = spade::mitigate_underflow(Point2::new(p[0], p[1]));
        spade::validate_vertex(&pos).ok()?;
        if let Some(h) = self.dt.locate_vertex(pos) {
            return Some(h.data().id);
        }
        let id = self.at.len() as u32;
        self.dt.insert(Vertex { pos, id }).ok()?;
        self.at.push(Vec::new());
        Some(id)
    }
}

impl PointIndex<Seg> for SpadeIndex {
    fn insert(&mut self, s: Seg) {
        let k = self.segs.len() as u32;
        self.segs.push(s);
        self.max_len = self.max_len.max(len(&s));
        let va = self.vertex_for(s.a);
        let vb = self.vertex_for(s.b);
        match (va, vb) {
            (Some(a), Some(b)) => {
                self.at[a as usize].push(k);
                if b != a {
                    self.at[b as usize].push(k);
                }
            }
            _ => self.odd.push(k),
        }
    }

    fn conflict(&self, t: &Seg, c: f64, widest: f64) -> Option<Seg> {
        if let Some(&k) = self
            .odd
            .iter()
            .find(|&&k| conflicts(t, &self.segs[k as usize], c))
        {
            return Some(self.segs[k as usize]);
        }
        let mid = Point2::new((t.a[0] + t.b[0]) / 2.0, (t.a[1] + t.b[1]) / 2.0);
        // Slightly larger than needed, so rounding never loses a candidate.
        let r = (len(t) / 2.0 + widest + self.max_len / 2.0) * (1.0 + 1e-9) + 1e-9;
        let mut seen = self.seen.borrow_mut();
        let (stamp, marks) = &mut *seen;
        *stamp = stamp.wrapping_add(1);
        if *stamp == 0 {
            marks.iter_mut().for_each(|m| *m = 0);
            *stamp = 1;
        }
        if marks.len() < self.segs.len() {
            marks.resize(self.segs.len(), 0);
        }
        for v in self.dt.get_vertices_in_circle(mid, r * r) {
            for &k in &self.at[v.data().id as usize] {
                if marks[k as usize] != *stamp {
                    marks[k as usize] = *stamp;
                    if conflicts(t, &self.segs[k as usize], c) {
                        return Some(self.segs[k as usize]);
                    }
                }
            }
        }
        None
    }
}
