//! glTF 2.0: the JSON (`.gltf`, its buffer embedded as a base64 data URI)
//! and the binary container (`.glb`).
//!
//! One scene, one node, one mesh with a primitive per colour (positions,
//! normals, texture coordinates `TEXCOORD_0` (none in a solid's), `u32`
//! indices), one
//! material per colour (its sRGB colour
//! turned linear as glTF's `baseColorFactor` is, not metallic, rough).
//! Every number in the JSON has fixed decimals except the positions'
//! `min` and `max`, which glTF requires to equal the `f32` data: those are
//! written as the shortest decimal that reads back as that `f32` (Rust's
//! formatting, the same on every platform).

use std::fmt::Write as _;
use std::io::Write;

use super::{Mesh, le_f32_pairs, le_f32s};
use crate::color::Rgb;
use crate::diag::{Diagnostics, io_error};
use crate::num::{Trim, fixed};

/// `x` as the shortest decimal that reads back as the same `f32`, never
/// `-0`.
fn exact_f32(x: f32) -> String {
    if x == 0.0 { "0".into() } else { format!("{x}") }
}

/// An sRGB channel as glTF's linear colour factor.
fn linear(c: u8) -> f64 {
    let s = f64::from(c) / 255.0;
    if s <= 0.04045 {
        s / 12.92
    } else {
        libm::pow((s + 0.055) / 1.055, 2.4)
    }
}

/// The JSON around the one buffer, and the buffer's length. With
/// `embed` (`.gltf`) the JSON is cut where the buffer's base64 goes (the
/// second part follows it); else (`.glb`, whose BIN chunk holds the
/// buffer) the second part is empty. Either way the buffer is streamed
/// from the mesh ([`write_buffer`]), never held.
fn json_and_buffer(mesh: &Mesh, embed: bool) -> (String, String, usize) {
    let mut len = 0usize;
    let mut views = Vec::new();
    let mut accessors = Vec::new();
    let mut prims = Vec::new();
    let mut materials = Vec::new();
    for p in &mesh.primitives {
        if p.indices.is_empty() {
            continue;
        }
        let mut lo = [f32::INFINITY; 3];
        let mut hi = [f32::NEG_INFINITY; 3];
        for v in &p.positions {
            for k in 0..3 {
                lo[k] = lo[k].min(v[k]);
                hi[k] = hi[k].max(v[k]);
            }
        }
        // A primitive without texture coordinates (a solid's) has no
        // view or accessor for them.
        let uv = !p.texcoords.is_empty();
        let first = views.len();
        for part in (0..4).filter(|&k| uv || k != 2) {
            let start = len;
            len += match part {
                0 => 12 * p.positions.len(),
                1 => 12 * p.normals.len(),
                2 => 8 * p.texcoords.len(),
                _ => 4 * p.indices.len(),
            };
            let target = if part == 3 { 34963 } else { 34962 };
            views.push(format!(
                "{{\"buffer\": 0, \"byteOffset\": {start}, \"byteLength\": {}, \"target\": {target}}}",
                len - start
            ));
        }
        let three = |a: [f32; 3]| {
            format!(
                "[{}, {}, {}]",
                exact_f32(a[0]),
                exact_f32(a[1]),
                exact_f32(a[2])
            )
        };
        let count = p.positions.len();
        let a = accessors.len();
        accessors.push(format!(
            "{{\"bufferView\": {first}, \"componentType\": 5126, \"count\": {count}, \
             \"type\": \"VEC3\", \"min\": {}, \"max\": {}}}",
            three(lo),
            three(hi)
        ));
        accessors.push(format!(
            "{{\"bufferView\": {}, \"componentType\": 5126, \"count\": {count}, \"type\": \"VEC3\"}}",
            first + 1
        ));
        let mut attributes = format!("\"POSITION\": {a}, \"NORMAL\": {}", a + 1);
        if uv {
            accessors.push(format!(
                "{{\"bufferView\": {}, \"componentType\": 5126, \"count\": {count}, \"type\": \"VEC2\"}}",
                first + 2
            ));
            let _ = write!(attributes, ", \"TEXCOORD_0\": {}", a + 2);
        }
        let indices = accessors.len();
        accessors.push(format!(
            "{{\"bufferView\": {}, \"componentType\": 5125, \"count\": {}, \"type\": \"SCALAR\"}}",
            views.len() - 1,
            p.indices.len()
        ));
        let c = p.color.unwrap_or(Rgb::BLACK);
        let f = |x: u8| fixed(linear(x), 6, Trim::Keep);
        let name = if p.leaf {
            format!("leaf {c}")
        } else {
            c.to_string()
        };
        materials.push(format!(
            "{{\"name\": \"{name}\", \"pbrMetallicRoughness\": {{\"baseColorFactor\": [{}, {}, {}, 1.0], \
             \"metallicFactor\": 0.0, \"roughnessFactor\": 0.9}}}}",
            f(c.r),
            f(c.g),
            f(c.b)
        ));
        prims.push(format!(
            "{{\"attributes\": {{{attributes}}}, \"indices\": {indices}, \"material\": {}, \"mode\": 4}}",
            materials.len() - 1
        ));
    }
    let mut j = String::from("{\"asset\": {\"version\": \"2.0\", \"generator\": \"stlc\"}");
    if prims.is_empty() {
        // Nothing drawn: an empty scene (a mesh needs a primitive).
        j.push_str(", \"scene\": 0, \"scenes\": [{\"nodes\": []}]}");
        return (j, String::new(), 0);
    }
    j.push_str(", \"scene\": 0, \"scenes\": [{\"nodes\": [0]}]");
    j.push_str(", \"nodes\": [{\"mesh\": 0, \"name\": \"tree\"}]");
    let _ = write!(
        j,
        ", \"meshes\": [{{\"name\": \"tree\", \"primitives\": [{}]}}]",
        prims.join(", ")
    );
    let _ = write!(j, ", \"materials\": [{}]", materials.join(", "));
    let _ = write!(j, ", \"accessors\": [{}]", accessors.join(", "));
    let _ = write!(j, ", \"bufferViews\": [{}]", views.join(", "));
    if embed {
        let _ = write!(
            j,
            ", \"buffers\": [{{\"byteLength\": {len}, \"uri\": \"data:application/octet-stream;base64,"
        );
        (j, "\"}]}".to_string(), len)
    } else {
        let _ = write!(j, ", \"buffers\": [{{\"byteLength\": {len}}}]}}");
        (j, String::new(), len)
    }
}

/// Writes the buffer [`json_and_buffer`] laid out (positions, normals,
/// texture coordinates, indices of each primitive that has triangles), a
/// few thousand values at a time.
fn write_buffer(mesh: &Mesh, out: &mut dyn Write) -> std::io::Result<()> {
    let mut chunk: Vec<u8> = Vec::with_capacity(1 << 16);
    for p in mesh.primitives.iter().filter(|p| !p.indices.is_empty()) {
        for v in [&p.positions, &p.normals] {
            for part in v.chunks(4096) {
                chunk.clear();
                le_f32s(part, &mut chunk);
                out.write_all(&chunk)?;
            }
        }
        for part in p.texcoords.chunks(4096) {
            chunk.clear();
            le_f32_pairs(part, &mut chunk);
            out.write_all(&chunk)?;
        }
        for part in p.indices.chunks(4096) {
            chunk.clear();
            for i in part {
                chunk.extend_from_slice(&i.to_le_bytes());
            }
            out.write_all(&chunk)?;
        }
    }
    Ok(())
}

/// Standard base64 with padding.
#[cfg(test)]
pub(super) fn base64(bytes: &[u8]) -> String {
    let mut out = Vec::new();
    let mut w = Base64::new(&mut out);
    // Into a Vec: cannot fail.
    let _ = w.write_all(bytes);
    let _ = w.finish();
    String::from_utf8(out).unwrap_or_default()
}

/// Writes what it is given as base64 (RFC 4648, padded) to `out`, a few
/// kilobytes at a time.
struct Base64<'a> {
    out: &'a mut dyn Write,
    /// Bytes not yet encoded (fewer than three).
    rest: [u8; 3],
    n: usize,
    text: Vec<u8>,
}

impl<'a> Base64<'a> {
    fn new(out: &'a mut dyn Write) -> Base64<'a> {
        Base64 {
            out,
            rest: [0; 3],
            n: 0,
            text: Vec::with_capacity(1 << 13),
        }
    }

    /// Encodes `rest[..n]` (with padding when fewer than three).
    fn encode(&mut self) {
        const A: &[u8; 64] = b"ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
        let [a, b, c] = self.rest;
        let v = (u32::from(a) << 16) | (u32::from(b) << 8) | u32::from(c);
        for k in 0..4 {
            self.text.push(if k <= self.n {
                A[(v >> (18 - 6 * k) & 63) as usize]
            } else {
                b'='
            });
        }
        self.rest = [0; 3];
        self.n = 0;
    }

    /// Encodes what is left, padded, and writes everything out.
    fn finish(mut self) -> std::io::Result<()> {
        if self.n > 0 {
            self.encode();
        }
        self.out.write_all(&self.text)
    }
}

impl Write for Base64<'_> {
    fn write(&mut self, buf: &[u8]) -> std::io::Result<usize> {
        for &byte in buf {
            self.rest[self.n] = byte;
            self.n += 1;
            if self.n == 3 {
                self.encode();
                if self.text.len() >= 1 << 13 {
                    self.out.write_all(&self.text)?;
                    self.text.clear();
                }
            }
        }
        Ok(buf.len())
    }

    fn flush(&mut self) -> std::io::Result<()> {
        self.out.flush()
    }
}

/// Writes `mesh` as glTF JSON with its buffer embedded.
pub fn write_gltf(mesh: &Mesh, out: &mut dyn Write) -> Result<(), Diagnostics> {
    let (head, tail, len) = json_and_buffer(mesh, true);
    let res = (|| {
        out.write_all(head.as_bytes())?;
        if len > 0 {
            let mut b64 = Base64::new(out);
            write_buffer(mesh, &mut b64)?;
            b64.finish()?;
        }
        out.write_all(tail.as_bytes())?;
        out.write_all(b"\n")?;
        out.flush()
    })();
    res.map_err(|e| io_error(&e, "writing the glTF").into())
}

/// Writes `mesh` as binary glTF: a 12-byte header, the JSON chunk (padded
/// with spaces to 4 bytes), the BIN chunk (padded with zeros).
pub fn write_glb(mesh: &Mesh, out: &mut dyn Write) -> Result<(), Diagnostics> {
    let (json, _, bin) = json_and_buffer(mesh, false);
    let mut json = json.into_bytes();
    while json.len() % 4 != 0 {
        json.push(b' ');
    }
    let pad = (4 - bin % 4) % 4;
    let padded = bin + pad;
    let bin_chunk = if bin == 0 { 0 } else { 8 + padded };
    let total = 12 + 8 + json.len() + bin_chunk;
    if u32::try_from(total).is_err() {
        return Err(
            crate::diag::Diagnostic::error(crate::diag::RenderError::MeshTooLarge {
                triangles: mesh.triangles().to_string(),
                limit: mesh.triangles(),
            })
            .with_help(
                crate::diag::Help::from("a .glb holds at most 4 GiB: write fewer triangles (")
                    + crate::diag::Help::knob(crate::diag::Knob::Sides, "")
                    + ", "
                    + crate::diag::Help::knob(crate::diag::Knob::Depth, "")
                    + ")",
            )
            .into(),
        );
    }
    let res = (|| {
        out.write_all(b"glTF")?;
        out.write_all(&2u32.to_le_bytes())?;
        out.write_all(&(total as u32).to_le_bytes())?;
        out.write_all(&(json.len() as u32).to_le_bytes())?;
        out.write_all(b"JSON")?;
        out.write_all(&json)?;
        if bin > 0 {
            out.write_all(&(padded as u32).to_le_bytes())?;
            out.write_all(b"BIN\0")?;
            write_buffer(mesh, out)?;
            out.write_all(&[0u8; 3][..pad])?;
        }
        out.flush()
    })();
    res.map_err(|e| io_error(&e, "writing the glTF").into())
}
