//! The vector arithmetic of meshes (tubes, leaves, solids), in the
//! files' axes: plain `[f64; 3]`, the same operations in the same order
//! wherever they are used, so the same bits.

pub(super) type V = [f64; 3];

pub(super) fn sub(a: V, b: V) -> V {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}

pub(super) fn cross(a: V, b: V) -> V {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}

pub(super) fn unit(a: V) -> V {
    let n = libm::sqrt(a[0] * a[0] + a[1] * a[1] + a[2] * a[2]);
    [a[0] / n, a[1] / n, a[2] / n]
}

pub(super) fn dot(a: V, b: V) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

pub(super) fn f32s(a: V) -> [f32; 3] {
    // Never -0: the same bytes whichever way a zero was reached.
    a.map(|v| if v == 0.0 { 0.0 } else { v as f32 })
}

/// A tube's frame about its axis `d`: the unit axis `dn`, and `u`, `v`
/// across it, `(u, v, dn)` right-handed (the helper axis is the one least
/// aligned with `d`), so a ring `u cos + v sin` turns counter-clockwise
/// about `dn`.
pub(super) fn frame(d: V) -> (V, V, V) {
    let dn = unit(d);
    let k = (0..3)
        .min_by(|&i, &j| dn[i].abs().total_cmp(&dn[j].abs()))
        .unwrap_or(0);
    let mut e = [0.0; 3];
    e[k] = 1.0;
    let u = unit(cross(dn, e));
    let v = cross(dn, u);
    (dn, u, v)
}
