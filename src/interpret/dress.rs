//! A grown tree dressed (`stl-language.md` section 13): its stems
//! coloured by an `S=` ramp from the seed's order to the deepest order
//! grown in that tree, and the surface `P=` names placed at every tip that
//! grew no further (a leaf).
//!
//! A tree's stems come from the one interpretation of its BED (2D or 3D),
//! gathered; a tip is a stem's end where no stem starts (bit for bit, as
//! the turtle puts a branch's first stem where its parent ended). Each
//! leaf is drawn by the parametric turtle in the tip's frame: H along the
//! tip's stem, L levelled horizontal as ABOP's `$` does in 3D (in 2D, L in
//! the canvas plane), its steps the stem length `L` at the tip's order.
//! Stems keep their drawing order; the leaves follow, in their tips'.

use crate::color::Rgb;
use crate::diag::{Diagnostic, Diagnostics};
use crate::interpret::lsys::param::{Mark, Turtle3P};
use crate::model::Description;
use crate::model::param::MAX_POLYGON_VERTICES;
use crate::turtle::turtle3::{Point3, Segment3};

/// The fill of leaves when `S=` is no ramp (with a ramp: its end).
pub const LEAF_GREEN: Rgb = Rgb::new(0x3b, 0x7d, 0x23);

/// Whether a description is dressed: an `S=` ramp or `P=` leaves.
pub fn dresses(desc: &Description) -> bool {
    desc.params.stroke_end.is_some() || desc.params.leaf.is_some()
}

/// A tree's stems with their colours and leaves, ready to hand on.
pub struct Dress<'a> {
    desc: &'a Description,
    segs: &'a [Segment3],
    /// Each stem's colour index.
    paint: Vec<usize>,
    /// The colours, the leaves' last.
    palette: Vec<Rgb>,
    /// Whether the stems are painted by order (else they keep the stroke).
    ramp: bool,
}

/// A point's bits, for exact comparisons.
fn key(p: Point3) -> [u64; 3] {
    [p.x.to_bits(), p.y.to_bits(), p.z.to_bits()]
}

/// The colour `t` of the way from `a` to `b`, each channel rounded.
fn mix(a: Rgb, b: Rgb, t: f64) -> Rgb {
    let m = |x: u8, y: u8| {
        let v = f64::from(x) + (f64::from(y) - f64::from(x)) * t;
        libm::round(v).clamp(0.0, 255.0) as u8
    };
    Rgb::new(m(a.r, b.r), m(a.g, b.g), m(a.b, b.b))
}

impl<'a> Dress<'a> {
    /// Dresses `segs`, the stems of `desc`'s trees in drawing order;
    /// `stroke` is the colour of one-coloured stems (`S=`, `--stroke` or
    /// the default: colour index 0, which [`Dress::emit`] never paints, so
    /// the backend's own stroke stands). A ramp is drawn as written.
    pub fn new(desc: &'a Description, segs: &'a [Segment3], stroke: Rgb) -> Self {
        let end = desc.params.stroke_end;
        let start = desc.params.stroke.as_ref().and_then(|c| c.rgb);
        let (stroke, end) = match (start, end) {
            (Some(a), Some(b)) => (a, Some(b)),
            _ => (stroke, None),
        };
        let ramp = end.is_some();
        let roots: Vec<[u64; 3]> = std::iter::once((desc.root, desc.root_z))
            .chain(desc.forest.iter().map(|t| (t.root, t.root_z)))
            .map(|((x, y), z)| key(Point3::new(x, y, z.unwrap_or(0.0))))
            .collect();
        // Which tree each stem is of: a tree's stems follow its root's
        // first stem (trees are drawn in root order).
        let mut tree = vec![0usize; segs.len()];
        let mut deepest = vec![0u32; roots.len()];
        let mut cur = 0usize;
        for (i, s) in segs.iter().enumerate() {
            if s.order == 0 && cur + 1 < roots.len() {
                let k = key(s.from);
                if let Some(j) = roots[cur + 1..].iter().position(|r| *r == k) {
                    cur += 1 + j;
                }
            }
            tree[i] = cur;
            deepest[cur] = deepest[cur].max(s.order);
        }
        let mut palette: Vec<Rgb> = Vec::new();
        let index = |c: Rgb, palette: &mut Vec<Rgb>| match palette.iter().position(|&p| p == c) {
            Some(i) => i,
            None => {
                palette.push(c);
                palette.len() - 1
            }
        };
        // Each tree's colour index by order.
        let by_order: Vec<Vec<usize>> = deepest
            .iter()
            .map(|&m| match end {
                Some(b) => (0..=m)
                    .map(|k| {
                        let t = if m == 0 {
                            0.0
                        } else {
                            f64::from(k) / f64::from(m)
                        };
                        index(mix(stroke, b, t), &mut palette)
                    })
                    .collect(),
                None => vec![index(stroke, &mut palette)],
            })
            .collect();
        let paint = segs
            .iter()
            .zip(&tree)
            .map(|(s, &t)| {
                let row = &by_order[t];
                row[(s.order as usize).min(row.len() - 1)]
            })
            .collect();
        palette.push(end.unwrap_or(LEAF_GREEN));
        Dress {
            desc,
            segs,
            paint,
            palette,
            ramp,
        }
    }

    /// The colours the marks' `Paint` indices name.
    pub fn palette(&self) -> &[Rgb] {
        &self.palette
    }

    /// Hands on every stem (each after its colour, when it changes) and
    /// then every leaf; an error if a leaf's polygon records more than
    /// [`MAX_POLYGON_VERTICES`] vertices.
    pub fn emit(&self, sink: &mut dyn FnMut(Mark<'_>)) -> Result<(), Diagnostics> {
        let p = &self.desc.params;
        let mut shown = None;
        for (s, &i) in self.segs.iter().zip(&self.paint) {
            if self.ramp && shown != Some(i) {
                sink(Mark::Paint(i));
                shown = Some(i);
            }
            sink(Mark::Step(*s, p.width.at(s.order)));
        }
        let (Some(&(name, _)), Some(block)) = (p.leaf.as_ref(), self.desc.surfaces.as_ref()) else {
            return Ok(());
        };
        sink(Mark::Paint(self.palette.len() - 1));
        let three = self.desc.is_3d();
        let mut turtle = Turtle3P::for_surfaces(&block.surfaces, p.angle(), three);
        let mut starts: Vec<[u64; 3]> = self.segs.iter().map(|s| key(s.from)).collect();
        starts.sort_unstable();
        starts.dedup();
        let mut each = |m: Mark<'_>| sink(m);
        for s in self.segs {
            if starts.binary_search(&key(s.to)).is_ok() {
                continue;
            }
            let Some(frame) = frame(s, three) else {
                continue;
            };
            let len = p.length.at(s.order).max(0.0);
            turtle.place_at(name, s.to, frame, len, &mut each);
        }
        if turtle.overfull {
            let loc = block.surfaces.iter().find(|s| s.name == name);
            let span = loc.map_or(0..0, |s| s.loc.0.clone());
            let mut d: Diagnostic = *crate::syntax::lsys::too_many(span);
            d.label = Some(format!(
                "surface `{name}` records more than {MAX_POLYGON_VERTICES} vertices in one polygon"
            ));
            return Err(d.into());
        }
        Ok(())
    }
}

type V = [f64; 3];

/// A tip's frame: H along its stem; in 3D L levelled horizontal
/// (`$`: L = V x H / |V x H|, V up the canvas), in 2D L in the plane;
/// U = H x L. `None` for a stem of no length.
fn frame(s: &Segment3, three: bool) -> Option<[V; 3]> {
    let d = [s.to.x - s.from.x, s.to.y - s.from.y, s.to.z - s.from.z];
    let n = libm::sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
    if n == 0.0 || !n.is_finite() {
        return None;
    }
    let h = [d[0] / n, d[1] / n, d[2] / n];
    let cross = |a: V, b: V| -> V {
        [
            a[1] * b[2] - a[2] * b[1],
            a[2] * b[0] - a[0] * b[2],
            a[0] * b[1] - a[1] * b[0],
        ]
    };
    let flat = [h[1], -h[0], 0.0];
    let l = if three {
        let l = cross([0.0, -1.0, 0.0], h);
        let m = libm::sqrt(l[0] * l[0] + l[1] * l[1] + l[2] * l[2]);
        if m > 1e-9 {
            [l[0] / m, l[1] / m, l[2] / m]
        } else {
            [-1.0, 0.0, 0.0]
        }
    } else {
        let m = libm::sqrt(flat[0] * flat[0] + flat[1] * flat[1]);
        [flat[0] / m, flat[1] / m, 0.0]
    };
    Some([h, l, cross(h, l)])
}

/// Every stem of a BED's trees, in drawing order, in 3D (a 2D tree's at
/// z = 0).
pub fn gather(
    bed: &crate::bed::Bed,
    strategy: crate::interpret::Derivation,
    limits: &crate::limits::Limits,
    progress: &mut dyn crate::progress::Progress,
) -> Result<Vec<Segment3>, Diagnostics> {
    let mut segs = Vec::new();
    if bed.description().is_3d() {
        super::bed3::draw3(bed, strategy, limits, &mut |s| segs.push(s), progress)?;
    } else {
        struct Lift<'v>(&'v mut Vec<Segment3>);
        impl crate::turtle::Turtle for Lift<'_> {
            fn segment(&mut self, s: crate::turtle::Segment) {
                self.0.push(Segment3 {
                    from: Point3::new(s.from.x, s.from.y, 0.0),
                    to: Point3::new(s.to.x, s.to.y, 0.0),
                    order: s.order,
                });
            }
        }
        super::bed::draw(bed, strategy, limits, &mut Lift(&mut segs), progress)?;
    }
    Ok(segs)
}

/// Draws a dressed BED flat into a 2D backend (a 3D tree's front view:
/// x and y): colours through [`crate::turtle::Turtle::paint`], leaves
/// through [`crate::turtle::Turtle::polygon`].
pub fn draw2(
    bed: &crate::bed::Bed,
    strategy: crate::interpret::Derivation,
    limits: &crate::limits::Limits,
    turtle: &mut dyn crate::turtle::Turtle,
    progress: &mut dyn crate::progress::Progress,
) -> Result<(), Diagnostics> {
    use crate::turtle::{Point, Segment};
    let segs = gather(bed, strategy, limits, progress)?;
    // One-coloured stems are never painted: the backend's stroke stands.
    let dress = Dress::new(bed.description(), &segs, Rgb::BLACK);
    let palette = dress.palette();
    let mut flat: Vec<Point> = Vec::new();
    dress.emit(&mut |m| match m {
        Mark::Step(s, _) => turtle.segment(Segment {
            from: Point::new(s.from.x, s.from.y),
            to: Point::new(s.to.x, s.to.y),
            order: s.order,
        }),
        Mark::Paint(i) => turtle.paint(palette[i]),
        Mark::Polygon(points) => {
            flat.clear();
            flat.extend(points.iter().map(|q| Point::new(q.x, q.y)));
            turtle.polygon(&flat);
        }
    })
}
