//! Wavefront OBJ: positions with vertex colours (`v x y z r g b`, the
//! extension Blender, MeshLab and others read), texture coordinates
//! (`vt u v`, OBJ's v up the image: 1 - glTF's), normals, and one group
//! per colour (`g stem_rrggbb`), faces `f v/vt/vn`. Colours travel with
//! the vertices, so one file is the whole mesh (no `.mtl` beside it) and
//! `-o -` writes all of it. Positions have 6 decimals (micrometres at the
//! default unit), texture coordinates, normals and colours 4.

use std::fmt::Write as _;
use std::io::Write;

use super::Mesh;
use crate::color::Rgb;
use crate::diag::{Diagnostics, io_error};
/// Appends `x` with `decimals` digits after the point: `x * 10^decimals`
/// rounded half away from zero, as integers (fast: an OBJ writes tens of
/// millions of numbers); never `-0`.
fn push_fixed(buf: &mut String, x: f64, decimals: u32) {
    use std::fmt::Write as _;
    let scale = 10i64.pow(decimals);
    let n = (x * scale as f64).round() as i64;
    if n < 0 {
        buf.push('-');
    }
    let a = n.unsigned_abs();
    let s = scale as u64;
    let _ = write!(buf, "{}.{:0w$}", a / s, a % s, w = decimals as usize);
}

/// Writes `mesh` as OBJ text.
pub fn write_obj(mesh: &Mesh, out: &mut dyn Write) -> Result<(), Diagnostics> {
    let mut w = std::io::BufWriter::with_capacity(1 << 16, out);
    let mut line = String::with_capacity(128);
    let put = |w: &mut std::io::BufWriter<&mut dyn Write>, line: &mut String| {
        line.push('\n');
        let r = w.write_all(line.as_bytes());
        line.clear();
        r
    };
    let fail = |e: std::io::Error| -> Diagnostics { io_error(&e, "writing the OBJ").into() };
    line.push_str("# stlc mesh: y up, right-handed, metres; vertex colours (v x y z r g b)");
    put(&mut w, &mut line).map_err(fail)?;
    let mut base = 1u64;
    for p in &mesh.primitives {
        let c = p.color.unwrap_or(Rgb::BLACK);
        let group = if p.leaf { "leaf" } else { "stem" };
        let _ = write!(line, "g {group}_{:02x}{:02x}{:02x}", c.r, c.g, c.b);
        put(&mut w, &mut line).map_err(fail)?;
        let rgb = [c.r, c.g, c.b].map(|x| f64::from(x) / 255.0);
        for v in &p.positions {
            line.push('v');
            for x in v {
                line.push(' ');
                push_fixed(&mut line, f64::from(*x), 6);
            }
            for x in rgb {
                line.push(' ');
                push_fixed(&mut line, x, 4);
            }
            put(&mut w, &mut line).map_err(fail)?;
        }
        for t in &p.texcoords {
            line.push_str("vt ");
            push_fixed(&mut line, f64::from(t[0]), 4);
            line.push(' ');
            push_fixed(&mut line, 1.0 - f64::from(t[1]), 4);
            put(&mut w, &mut line).map_err(fail)?;
        }
        for n in &p.normals {
            line.push_str("vn");
            for x in n {
                line.push(' ');
                push_fixed(&mut line, f64::from(*x), 4);
            }
            put(&mut w, &mut line).map_err(fail)?;
        }
        for t in p.indices.chunks(3) {
            line.push('f');
            for &i in t {
                let k = base + u64::from(i);
                let _ = write!(line, " {k}/{k}/{k}");
            }
            put(&mut w, &mut line).map_err(fail)?;
        }
        base += p.positions.len() as u64;
    }
    w.flush().map_err(fail)
}

#[cfg(test)]
mod tests {
    #[test]
    fn fixed_decimals_round_half_away_and_never_write_minus_zero() {
        let f = |x: f64, d: u32| {
            let mut s = String::new();
            super::push_fixed(&mut s, x, d);
            s
        };
        assert_eq!(f(1.5, 6), "1.500000");
        assert_eq!(f(-0.0000004, 6), "0.000000");
        assert_eq!(f(-0.0000006, 6), "-0.000001");
        assert_eq!(f(-12.34567, 4), "-12.3457");
        assert_eq!(f(0.00005, 4), "0.0001");
        assert_eq!(f(3.0, 4), "3.0000");
    }
}
