//! `--solid`: a tree as one closed manifold body for 3D printing
//! (docs/3d.md, *Solids*). Every stem a closed tube (a ring of `sides`
//! vertices at each end, each end capped by a fan), a sphere of the
//! stem's radius at the end of every stem (its joint with the stems that
//! start there, or its rounded tip), and the union of them all computed
//! by `manifold-rust`, a port of the Manifold library (docs/dependencies.md).
//! The result's vertices are shared (welded) by construction; it has no
//! normals or texture coordinates (an STL's facet normal is its
//! triangle's).
//!
//! Axes and units are the printing ones: millimetres (the unit every
//! slicer assumes in an STL), z up; a canvas point is placed as in a mesh
//! (first root at the origin, `--unit` metres per canvas unit) and then
//! turned from y up to z up, (x, y, z) to (x, -z, y), a rotation, so
//! windings stay outward.

use std::collections::BTreeMap;

use manifold_rust::csg_tree::CsgNode;
use manifold_rust::linalg::{Mat3x4, Vec2, Vec3};
use manifold_rust::manifold::Manifold;
use manifold_rust::types::{Error, MeshGL64, OpType};

use super::leaf::Leaf;
use super::vector::{V, cross, f32s, frame, sub, unit};
use super::{MAX_SIDES, MIN_SIDES, Mesh, MeshOptions, Primitive, Tube, to_file_axes};
use crate::color::Rgb;
use crate::diag::{Diagnostic, Diagnostics, RenderError};
use crate::progress::Progress;
use crate::turtle::turtle3::{Point3, cos_sin};

/// Millimetres per metre: a solid is written in millimetres.
const MM: f64 = 1000.0;

/// Edges shorter than this (millimetres) are collapsed after the union:
/// a micrometre, far under any printer's resolution and far over an
/// `f32`'s step at a tree's size, so that no two corners of the body
/// round to one point in the STL.
const TOLERANCE: f64 = 1e-3;

/// Parts (tubes and spheres) united at a time before the groups are
/// united: the progress bar advances once a group.
const GROUP: usize = 512;

/// A closed body: shared vertices (millimetres, z up, as written) and triangles
/// counter-clockwise from outside.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct Solid {
    /// Vertex positions, each distinct.
    pub positions: Vec<[f32; 3]>,
    /// Triangles, three indices into `positions` each.
    pub triangles: Vec<[u32; 3]>,
}

/// A point placed in the solid's axes: the first root at the origin,
/// millimetres, z up.
fn placed(p: Point3, origin: Point3, unit_m: f64) -> V {
    let moved = Point3::new(p.x - origin.x, p.y - origin.y, p.z - origin.z);
    let [x, y, z] = to_file_axes(moved, unit_m * MM);
    [x, -z, y]
}

/// One closed tube from `a` to `b`, radius `r`, `ring` its directions: a
/// ring at each end and a fan over each end's ring, counter-clockwise
/// from outside. `None` when it has no length or radius.
pub fn tube_mesh(a: V, b: V, r: f64, ring: &[(f64, f64)]) -> Option<MeshGL64> {
    let d = sub(b, a);
    if d == [0.0; 3] || r <= 0.0 || !d.iter().chain(&a).all(|v| v.is_finite()) {
        return None;
    }
    let (_, u, v) = frame(d);
    let mut pos = Vec::with_capacity(6 * ring.len());
    for c in [a, b] {
        for &(co, si) in ring {
            for i in 0..3 {
                pos.push(c[i] + r * (u[i] * co + v[i] * si));
            }
        }
    }
    let n = ring.len() as u64;
    let mut tri = Vec::with_capacity(12 * ring.len());
    for j in 0..n {
        let k = (j + 1) % n;
        // (u, v, dn) is right-handed, so the ring turns counter-clockwise
        // about dn: these face outward.
        tri.extend([j, k, n + k, j, n + k, n + j]);
    }
    for j in 1..n - 1 {
        tri.extend([0, j + 1, j]);
        tri.extend([n, n + j, n + j + 1]);
    }
    Some(MeshGL64 {
        num_prop: 3,
        vert_properties: pos,
        tri_verts: tri,
        ..MeshGL64::default()
    })
}

/// The solid of `tubes` and `leaves` (canvas units), `origin` the first
/// root: each leaf a slab [`MIN_LEAF_MM`] thick ([`slab`]), its first
/// corner its tip, where the stem's joint ball overlaps it. Fails when the
/// union's library reports an error.
pub fn build_solid(
    tubes: &[Tube],
    leaves: &[Leaf],
    origin: Point3,
    opts: &MeshOptions,
    progress: &mut dyn Progress,
) -> Result<Solid, Diagnostics> {
    let n = opts.sides.clamp(MIN_SIDES, MAX_SIDES);
    let ring: Vec<(f64, f64)> = (0..n)
        .map(|j| cos_sin(360.0 * f64::from(j) / f64::from(n)))
        .collect();
    let mut parts: Vec<Manifold> = Vec::with_capacity(2 * tubes.len());
    // The joints by position's bits (a BTreeMap: the same order each
    // run): the largest radius there, and how many stems end and start.
    let mut joints: BTreeMap<[u64; 3], Joint> = BTreeMap::new();
    // A stem drawn twice (an L-system may retrace one) is meshed once:
    // two coincident tubes would leave coincident faces in the union.
    let mut seen: std::collections::BTreeSet<[u64; 7]> = std::collections::BTreeSet::new();
    for t in tubes {
        let a = placed(t.from, origin, opts.unit);
        let b = placed(t.to, origin, opts.unit);
        let r = t.width * opts.unit * MM / 2.0;
        let (p, q) = if a.map(f64::to_bits) <= b.map(f64::to_bits) {
            (a, b)
        } else {
            (b, a)
        };
        let key = [p[0], p[1], p[2], q[0], q[1], q[2], r].map(f64::to_bits);
        if !seen.insert(key) {
            continue;
        }
        if let Some(m) = tube_mesh(a, b, r, &ring) {
            parts.push(checked(Manifold::from_mesh_gl64(&m))?);
            for (c, end) in [(a, false), (b, true)] {
                let j = joints.entry(c.map(f64::to_bits)).or_insert(Joint {
                    at: c,
                    radius: r,
                    ends: 0,
                    starts: 0,
                });
                j.radius = j.radius.max(r);
                if end {
                    j.ends += 1;
                } else {
                    j.starts += 1;
                }
            }
        }
    }
    let (ball, grow) = joint_ball(n);
    for j in joints.values() {
        // A root's base (one stem starts there, none ends) stays flat.
        if j.ends == 0 && j.starts < 2 {
            continue;
        }
        let r = j.radius * grow;
        parts.push(
            ball.scale(Vec3::new(r, r, r))
                .translate(Vec3::new(j.at[0], j.at[1], j.at[2])),
        );
    }
    for l in leaves {
        let corners: Vec<V> = l
            .points
            .iter()
            .map(|p| placed(*p, origin, opts.unit))
            .collect();
        if let Some(m) = slab(&corners, MIN_LEAF_MM) {
            parts.push(m);
        }
    }
    let body = union(parts, progress)?;
    let body = checked(body.simplify(TOLERANCE))?;
    let gl = body.get_mesh_gl64(-1);
    let stride = gl.num_prop as usize;
    let corners: Vec<[f32; 3]> = gl
        .vert_properties
        .chunks_exact(stride)
        .map(|p| [p[0], p[1], p[2]].map(|x| if x == 0.0 { 0.0 } else { x as f32 }))
        .collect();
    let triangles: Vec<[u32; 3]> = gl
        .tri_verts
        .chunks_exact(3)
        .map(|t| [t[0] as u32, t[1] as u32, t[2] as u32])
        .collect();
    Ok(rounded(&corners, &triangles))
}

/// The body with its corners rounded to `f32` (an STL's numbers) and
/// welded by their bits ([`weld`]).
fn rounded(corners: &[[f32; 3]], triangles: &[[u32; 3]]) -> Solid {
    let keys: Vec<[u32; 3]> = corners.iter().map(|c| c.map(f32::to_bits)).collect();
    let (first, triangles) = weld(&keys, triangles);
    Solid {
        positions: first.iter().map(|&i| corners[i]).collect(),
        triangles,
    }
}

/// Welds corners with equal `keys` (one a corner) into one vertex: where
/// two corners become one (a sliver thinner than the written numbers'
/// step), the triangles that become degenerate are dropped, and so is
/// each pair of triangles on the same three corners facing opposite ways
/// (a fin of no volume), so every edge stays shared by two triangles.
/// Gives each vertex's first corner and the kept triangles, in order.
pub(super) fn weld<K: Ord + Copy>(
    keys: &[K],
    triangles: &[[u32; 3]],
) -> (Vec<usize>, Vec<[u32; 3]>) {
    let mut index: BTreeMap<K, u32> = BTreeMap::new();
    let mut first: Vec<usize> = Vec::with_capacity(keys.len());
    let welded: Vec<u32> = keys
        .iter()
        .enumerate()
        .map(|(i, k)| {
            *index.entry(*k).or_insert_with(|| {
                first.push(i);
                first.len() as u32 - 1
            })
        })
        .collect();
    let mut kept: Vec<Option<[u32; 3]>> = triangles
        .iter()
        .map(|t| t.map(|i| welded[i as usize]))
        .filter(|[a, b, c]| a != b && b != c && c != a)
        .map(Some)
        .collect();
    // Triangles by their corners in a turn-free order (the smallest first)
    // and by orientation.
    let mut by_corners: BTreeMap<[u32; 3], (Vec<usize>, Vec<usize>)> = BTreeMap::new();
    for (i, t) in kept.iter().enumerate() {
        let [a, b, c] = t.unwrap_or_default();
        let turned = if a < b && a < c {
            [a, b, c]
        } else if b < c {
            [b, c, a]
        } else {
            [c, a, b]
        };
        let (key, forward) = if turned[1] < turned[2] {
            (turned, true)
        } else {
            ([turned[0], turned[2], turned[1]], false)
        };
        let e = by_corners.entry(key).or_default();
        if forward { e.0.push(i) } else { e.1.push(i) }
    }
    for (f, b) in by_corners.values() {
        for (&i, &j) in f.iter().zip(b) {
            kept[i] = None;
            kept[j] = None;
        }
    }
    (first, kept.into_iter().flatten().collect())
}

impl Solid {
    /// The body as a glTF mesh (`--solid -o x.glb`): glTF's axes and
    /// metres (y up; the solid's (x, y, z) millimetres, z up, turned back
    /// to (x, z, -y) / 1000, a rotation, so windings stay outward),
    /// welded again by the `f32` bits there (as the STL is), one primitive of
    /// `color`, a normal per vertex (the sum of its triangles' area
    /// normals, made unit), no texture coordinates.
    pub fn gltf_mesh(&self, color: Rgb) -> Mesh {
        let corners: Vec<[f32; 3]> = self
            .positions
            .iter()
            .map(|p| {
                let [x, y, z] = p.map(f64::from);
                f32s([x / MM, z / MM, -y / MM])
            })
            .collect();
        let keys: Vec<[u32; 3]> = corners.iter().map(|c| c.map(f32::to_bits)).collect();
        let (first, triangles) = weld(&keys, &self.triangles);
        let positions: Vec<[f32; 3]> = first.iter().map(|&i| corners[i]).collect();
        let mut sums = vec![[0.0f64; 3]; positions.len()];
        for t in &triangles {
            let [a, b, c] = t.map(|i| positions[i as usize].map(f64::from));
            let n = cross(sub(b, a), sub(c, a));
            for &i in t {
                let s = &mut sums[i as usize];
                for k in 0..3 {
                    s[k] += n[k];
                }
            }
        }
        let normals = sums
            .into_iter()
            .map(|s| {
                if s.iter().all(|x| x.is_finite()) && s != [0.0; 3] {
                    f32s(unit(s))
                } else {
                    [0.0, 1.0, 0.0]
                }
            })
            .collect();
        Mesh {
            primitives: vec![Primitive {
                color: Some(color),
                positions,
                normals,
                texcoords: Vec::new(),
                indices: triangles.into_iter().flatten().collect(),
                leaf: false,
            }],
        }
    }
}

/// The leaf thickness a solid gives a flat polygon at least (docs/3d.md,
/// *Solids*): half a millimetre.
pub const MIN_LEAF_MM: f64 = 0.5;

/// A flat polygon (a leaf, `corners` in the solid's axes, millimetres,
/// in order around it, convex or not) thickened into a closed slab for
/// the union: the polygon offset `thickness / 2` each way along its
/// normal (Newell's, so the corners' turning decides which side is
/// which), closed at its rim. `None` for fewer than three corners, no
/// area, a thickness under [`MIN_LEAF_MM`] or a failed triangulation.
pub fn slab(corners: &[V], thickness: f64) -> Option<Manifold> {
    if corners.len() < 3 || thickness < MIN_LEAF_MM || !thickness.is_finite() {
        return None;
    }
    let mut nrm = [0.0; 3];
    for (i, a) in corners.iter().enumerate() {
        let b = corners[(i + 1) % corners.len()];
        nrm[0] += (a[1] - b[1]) * (a[2] + b[2]);
        nrm[1] += (a[2] - b[2]) * (a[0] + b[0]);
        nrm[2] += (a[0] - b[0]) * (a[1] + b[1]);
    }
    if nrm == [0.0; 3] || !nrm.iter().all(|v| v.is_finite()) {
        return None;
    }
    let n = unit(nrm);
    let o = corners[0];
    let k = (0..3)
        .min_by(|&i, &j| n[i].abs().total_cmp(&n[j].abs()))
        .unwrap_or(0);
    let mut e = [0.0; 3];
    e[k] = 1.0;
    let x = unit(cross(e, n));
    let y = cross(n, x);
    let dot = |a: V, b: V| a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
    // In the plane's (x, y), counter-clockwise about n.
    let flat: Vec<Vec2> = corners
        .iter()
        .map(|c| {
            let d = sub(*c, o);
            Vec2::new(dot(d, x), dot(d, y))
        })
        .collect();
    let slab = Manifold::extrude(&vec![flat], thickness, 0, 0.0, Vec2::new(1.0, 1.0));
    if slab.status() != Error::NoError || slab.is_empty() {
        return None;
    }
    let v = |a: V| Vec3::new(a[0], a[1], a[2]);
    let place = Mat3x4 {
        x: v(x),
        y: v(y),
        z: v(n),
        w: v([
            o[0] - n[0] * thickness / 2.0,
            o[1] - n[1] * thickness / 2.0,
            o[2] - n[2] * thickness / 2.0,
        ]),
    };
    Some(slab.transform(&place))
}

/// A point where stems meet.
struct Joint {
    /// Where.
    at: V,
    /// The largest radius of the stems there.
    radius: f64,
    /// Stems that end there.
    ends: u32,
    /// Stems that start there.
    starts: u32,
}

/// The unit sphere a joint's ball is scaled from (twice the tubes' sides
/// around, at least 8), and the factor its radius is grown by so that
/// every face lies outside the stems' radius: every tube's end ring then
/// lies strictly inside the ball, and no tube touches it at a vertex or
/// along a face (a touching the union would keep as a pinch).
fn joint_ball(sides: u32) -> (Manifold, f64) {
    let ball = Manifold::sphere(1.0, (2 * sides).max(8) as i32);
    let gl = ball.get_mesh_gl64(-1);
    let p = |i: u64| {
        let k = 3 * i as usize;
        [
            gl.vert_properties[k],
            gl.vert_properties[k + 1],
            gl.vert_properties[k + 2],
        ]
    };
    // The nearest face plane to the centre.
    let inner = gl
        .tri_verts
        .chunks_exact(3)
        .map(|t| {
            let (a, b, c) = (p(t[0]), p(t[1]), p(t[2]));
            let nrm = unit(cross(sub(b, a), sub(c, a)));
            (nrm[0] * a[0] + nrm[1] * a[1] + nrm[2] * a[2]).abs()
        })
        .fold(1.0, f64::min);
    (ball, 1.01 / inner)
}

/// The union of `parts`: groups of [`GROUP`] in order (stems come in
/// drawing order, so a group is a connected piece), then the groups.
fn union(parts: Vec<Manifold>, progress: &mut dyn Progress) -> Result<Manifold, Diagnostics> {
    let groups = parts.len().div_ceil(GROUP) as u64;
    progress.start("uniting", groups + 1);
    let mut united = Vec::with_capacity(groups as usize);
    for (i, g) in parts.chunks(GROUP).enumerate() {
        united.push(unite(g)?);
        progress.update(i as u64 + 1);
    }
    let body = unite(&united)?;
    progress.update(groups + 1);
    progress.finish();
    Ok(body)
}

/// One batch union through the library's CSG tree.
fn unite(parts: &[Manifold]) -> Result<Manifold, Diagnostics> {
    let leaves = parts
        .iter()
        .map(|m| CsgNode::leaf(m.as_impl().clone()))
        .collect();
    checked(Manifold::from_impl(
        CsgNode::op_n(OpType::Add, leaves).evaluate(),
    ))
}

fn checked(m: Manifold) -> Result<Manifold, Diagnostics> {
    match m.status() {
        Error::NoError => Ok(m),
        s => Err(Diagnostic::error(RenderError::SolidUnion {
            status: format!("{s:?}"),
        })
        .into()),
    }
}

/// Writes `solid` as binary STL: an 80-byte header, the triangle count,
/// then per triangle its unit normal, its three corners (`f32`,
/// little-endian) and a zero attribute word.
pub fn write_stl(solid: &Solid, out: &mut dyn std::io::Write) -> std::io::Result<()> {
    let mut head = [0u8; 80];
    let title = b"stlc solid, millimetres, z up";
    head[..title.len()].copy_from_slice(title);
    out.write_all(&head)?;
    out.write_all(&(solid.triangles.len() as u32).to_le_bytes())?;
    let mut buf = Vec::with_capacity(50 * 1024);
    for t in &solid.triangles {
        let [a, b, c] = t.map(|i| solid.positions[i as usize].map(f64::from));
        let nrm = cross(sub(b, a), sub(c, a));
        let len = libm::sqrt(nrm[0] * nrm[0] + nrm[1] * nrm[1] + nrm[2] * nrm[2]);
        let nrm = if len > 0.0 {
            nrm.map(|x| x / len)
        } else {
            [0.0; 3]
        };
        for p in [nrm, a, b, c] {
            for x in p {
                let x = if x == 0.0 { 0.0f32 } else { x as f32 };
                buf.extend(x.to_le_bytes());
            }
        }
        buf.extend([0, 0]);
        if buf.len() >= 50 * 1000 {
            out.write_all(&buf)?;
            buf.clear();
        }
    }
    out.write_all(&buf)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// An L-shaped leaf (not convex), 3 x 3 mm with a 2 x 2 notch, tilted
    /// out of every axis plane: thickened by 0.5 mm it is one closed
    /// body of genus 0 whose volume is its area (5 mm^2) times 0.5.
    #[test]
    fn a_leaf_polygon_thickens_into_a_closed_slab() {
        // In the plane spanned by p and q, from the point o.
        let (o, p, q) = (
            [1.0, 2.0, 3.0],
            unit([1.0, 1.0, 0.0]),
            unit([-1.0, 1.0, 1.0]),
        );
        let q = unit(sub(
            q,
            p.map(|c| c * (p[0] * q[0] + p[1] * q[1] + p[2] * q[2])),
        ));
        let at = |s: f64, t: f64| [0, 1, 2].map(|i| o[i] + s * p[i] + t * q[i]);
        let l = [
            at(0.0, 0.0),
            at(3.0, 0.0),
            at(3.0, 1.0),
            at(1.0, 1.0),
            at(1.0, 3.0),
            at(0.0, 3.0),
        ];
        let body = slab(&l, 0.5).unwrap();
        assert_eq!(body.status(), Error::NoError);
        assert_eq!(body.genus(), 0);
        assert_eq!(body.decompose().len(), 1);
        assert!((body.volume() - 2.5).abs() < 1e-9, "{}", body.volume());
        // Its two faces lie 0.25 mm each side of the polygon's plane.
        let n = unit(cross(p, q));
        let gl = body.get_mesh_gl64(-1);
        for c in gl.vert_properties.chunks_exact(gl.num_prop as usize) {
            let d = sub([c[0], c[1], c[2]], o);
            let h = n[0] * d[0] + n[1] * d[1] + n[2] * d[2];
            assert!((h.abs() - 0.25).abs() < 1e-9, "{h}");
        }
        // Reversed corners give the same slab (the normal turns with them).
        let back: Vec<V> = l.iter().rev().copied().collect();
        assert!((slab(&back, 0.5).unwrap().volume() - 2.5).abs() < 1e-9);
        // Too thin, or no area: refused.
        assert!(slab(&l, 0.4).is_none());
        assert!(slab(&[at(0.0, 0.0), at(1.0, 0.0), at(2.0, 0.0)], 1.0).is_none());
    }

    /// The welding after rounding: a degenerate triangle and a fin (two
    /// triangles on the same corners facing opposite ways) are dropped, the
    /// rest kept with welded indices.
    #[test]
    fn rounding_drops_degenerate_triangles_and_fins() {
        let corners = [
            [0.0, 0.0, 0.0],
            [1.0, 0.0, 0.0],
            [0.0, 1.0, 0.0],
            // Rounds onto corner 1's bits.
            [1.0, 0.0, 0.0],
            [0.0, 0.0, 1.0],
        ];
        let tris = [[0, 1, 2], [1, 3, 4], [0, 2, 4], [4, 2, 0], [2, 3, 0]];
        let s = rounded(&corners, &tris);
        assert_eq!(s.positions.len(), 4);
        // [1, 3, 4] is degenerate; [0, 2, 4] and [4, 2, 0] are a fin;
        // [2, 3, 0] is [2, 1, 0] welded, the reverse of [0, 1, 2]: a fin too.
        assert_eq!(s.triangles, Vec::<[u32; 3]>::new());
        let s = rounded(&corners, &tris[..1]);
        assert_eq!(s.triangles, vec![[0, 1, 2]]);
    }
}
