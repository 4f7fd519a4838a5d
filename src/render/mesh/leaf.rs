//! Leaves in meshes: each polygon of a `.lsys` (`{ }`, surfaces) a
//! double-sided face (docs/3d.md, *Meshes*): its vertices twice, once
//! with the polygon's normal (Newell's, from the vertices' order) and
//! once with its opposite, each side a fan of triangles from the first
//! vertex, counter-clockwise seen from the side its normal points to; in
//! primitives of their own, one per colour, apart from the stems'.

use super::vector::{V, cross, dot, f32s, sub, unit};
use crate::color::Rgb;
use crate::turtle::turtle3::Point3;

/// A leaf's two faces: positions, normals, texture coordinates, and
/// triangles (indices from 0); kept from leaf to leaf (cleared by
/// [`faces`]), so a mesh of many leaves allocates them once.
#[derive(Debug, Default)]
pub(super) struct Faces {
    pub(super) positions: Vec<[f32; 3]>,
    pub(super) normals: Vec<[f32; 3]>,
    pub(super) texcoords: Vec<[f32; 2]>,
    pub(super) indices: Vec<u32>,
    /// The polygon in its own plane.
    flat: Vec<(f64, f64)>,
}

/// One polygon to mesh: its vertices (canvas units), its colour.
#[derive(Debug, Clone, PartialEq)]
pub struct Leaf {
    /// Its vertices, in order.
    pub points: Vec<Point3>,
    /// Its colour.
    pub color: Rgb,
}

/// The two faces of a polygon whose vertices `pts` are in the files'
/// axes, into `p` (cleared first); false for one with no area (or a
/// coordinate not finite).
pub(super) fn faces(pts: &[V], p: &mut Faces) -> bool {
    p.positions.clear();
    p.normals.clear();
    p.texcoords.clear();
    p.indices.clear();
    p.flat.clear();
    if pts.len() < 3 || !pts.iter().flatten().all(|v| v.is_finite()) {
        return false;
    }
    // Newell's normal: the polygon's area vector.
    let mut n = [0.0; 3];
    for (i, a) in pts.iter().enumerate() {
        let b = pts[(i + 1) % pts.len()];
        n[0] += (a[1] - b[1]) * (a[2] + b[2]);
        n[1] += (a[2] - b[2]) * (a[0] + b[0]);
        n[2] += (a[0] - b[0]) * (a[1] + b[1]);
    }
    if dot(n, n) == 0.0 {
        return false;
    }
    let n = unit(n);
    // Texture coordinates: the polygon in its plane, its first edge along
    // u, scaled into the unit square.
    let e1 = unit(sub(pts[1], pts[0]));
    let e2 = cross(n, e1);
    p.flat.extend(
        pts.iter()
            .map(|&q| (dot(sub(q, pts[0]), e1), dot(sub(q, pts[0]), e2))),
    );
    let lo = p.flat.iter().fold((f64::INFINITY, f64::INFINITY), |m, p| {
        (m.0.min(p.0), m.1.min(p.1))
    });
    let hi = p
        .flat
        .iter()
        .fold((f64::NEG_INFINITY, f64::NEG_INFINITY), |m, p| {
            (m.0.max(p.0), m.1.max(p.1))
        });
    let side = (hi.0 - lo.0).max(hi.1 - lo.1);
    let uv = |f: (f64, f64)| {
        if side > 0.0 && side.is_finite() {
            [((f.0 - lo.0) / side) as f32, ((f.1 - lo.1) / side) as f32]
        } else {
            [0.0, 0.0]
        }
    };
    let k = pts.len() as u32;
    for (normal, front) in [(n, true), (n.map(|x| -x), false)] {
        let base = p.positions.len() as u32;
        for (q, f) in pts.iter().zip(&p.flat) {
            p.positions.push(f32s(*q));
            p.normals.push(f32s(normal));
            p.texcoords.push(uv(*f));
        }
        for j in 1..k - 1 {
            if front {
                p.indices.extend([base, base + j, base + j + 1]);
            } else {
                p.indices.extend([base, base + j + 1, base + j]);
            }
        }
    }
    true
}
