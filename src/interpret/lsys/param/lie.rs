//! How a piece's ink lies in space (memo3.rs): symmetric matrices of
//! its strokes' directions and its polygons' normals, turned with the
//! piece, and a polygon's vector area.

use crate::interpret::lsys::reach::{M, V, apply};
use crate::turtle::turtle3::Point3;

pub(super) fn dot(a: V, b: V) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

pub(super) fn norm(v: V) -> f64 {
    libm::sqrt(dot(v, v))
}

pub(super) fn axpy(a: V, b: V, k: f64) -> V {
    [a[0] + b[0] * k, a[1] + b[1] * k, a[2] + b[2] * k]
}

/// A symmetric 3 x 3 matrix: `xx, xy, xz, yy, yz, zz`.
pub(super) type Sym = [f64; 6];

/// `k a a^T`.
pub(super) fn outer(a: V, k: f64) -> Sym {
    [
        k * a[0] * a[0],
        k * a[0] * a[1],
        k * a[0] * a[2],
        k * a[1] * a[1],
        k * a[1] * a[2],
        k * a[2] * a[2],
    ]
}

pub(super) fn add_sym(a: &mut Sym, b: &Sym) {
    for (x, y) in a.iter_mut().zip(b) {
        *x += y;
    }
}

/// `u^T t u`.
pub(super) fn quad(t: &Sym, u: V) -> f64 {
    t[0] * u[0] * u[0]
        + t[3] * u[1] * u[1]
        + t[5] * u[2] * u[2]
        + 2.0 * (t[1] * u[0] * u[1] + t[2] * u[0] * u[2] + t[4] * u[1] * u[2])
}

/// `F t F^T`: `t` given in the frame `f` (its columns), in `f`'s
/// coordinates.
pub(super) fn turned(f: &M, t: &Sym) -> Sym {
    let full = [[t[0], t[1], t[2]], [t[1], t[3], t[4]], [t[2], t[4], t[5]]];
    // G = F T: column j of G is F applied to column j of T.
    let g: [V; 3] = [apply(f, full[0]), apply(f, full[1]), apply(f, full[2])];
    // (G F^T)_{ab} = sum_j G_{aj} F_{bj}.
    let at = |a: usize, b: usize| (0..3).map(|j| g[j][a] * f[j][b]).sum::<f64>();
    [at(0, 0), at(0, 1), at(0, 2), at(1, 1), at(1, 2), at(2, 2)]
}

/// The vector area of a closed polygon in space (its normal times its
/// area).
pub(super) fn vector_area(points: &[Point3]) -> V {
    let mut s = [0.0; 3];
    for (i, a) in points.iter().enumerate() {
        let b = points[(i + 1) % points.len()];
        s = axpy(
            s,
            [
                a.y * b.z - a.z * b.y,
                a.z * b.x - a.x * b.z,
                a.x * b.y - a.y * b.x,
            ],
            1.0,
        );
    }
    s.map(|v| v / 2.0)
}
