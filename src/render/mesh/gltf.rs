//! glTF 2.0: the JSON (`.gltf`, its buffer embedded as a base64 data URI)
//! and the binary container (`.glb`).
//!
//! One scene, one node, one mesh with a primitive per colour (positions,
//! normals, `u32` indices), one material per colour (its sRGB colour
//! turned linear as glTF's `baseColorFactor` is, not metallic, rough).
//! Every number in the JSON has fixed decimals except the positions'
//! `min` and `max`, which glTF requires to equal the `f32` data: those are
//! written as the shortest decimal that reads back as that `f32` (Rust's
//! formatting, the same on every platform).

use std::fmt::Write as _;
use std::io::Write;

use super::{Mesh, le_f32s};
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

/// The JSON and the one buffer's bytes; `uri`: the buffer's data URI
/// (`.gltf`) or none (`.glb`, whose BIN chunk holds it).
fn json_and_buffer(mesh: &Mesh, embed: bool) -> (String, usize) {
    // The buffer is built only to embed it (base64); a .glb streams it
    // from the mesh ([`write_buffer`]), so its bytes are never held twice.
    let mut buffer = Vec::new();
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
        let first = views.len();
        for part in 0..3 {
            let start = len;
            len += match part {
                0 => 12 * p.positions.len(),
                1 => 12 * p.normals.len(),
                _ => 4 * p.indices.len(),
            };
            if embed {
                match part {
                    0 => le_f32s(&p.positions, &mut buffer),
                    1 => le_f32s(&p.normals, &mut buffer),
                    _ => buffer.extend(p.indices.iter().flat_map(|i| i.to_le_bytes())),
                }
            }
            let target = if part == 2 { 34963 } else { 34962 };
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
        accessors.push(format!(
            "{{\"bufferView\": {}, \"componentType\": 5125, \"count\": {}, \"type\": \"SCALAR\"}}",
            first + 2,
            p.indices.len()
        ));
        let c = p.color.unwrap_or(Rgb::BLACK);
        let f = |x: u8| fixed(linear(x), 6, Trim::Keep);
        materials.push(format!(
            "{{\"name\": \"{c}\", \"pbrMetallicRoughness\": {{\"baseColorFactor\": [{}, {}, {}, 1.0], \
             \"metallicFactor\": 0.0, \"roughnessFactor\": 0.9}}}}",
            f(c.r),
            f(c.g),
            f(c.b)
        ));
        prims.push(format!(
            "{{\"attributes\": {{\"POSITION\": {a}, \"NORMAL\": {}}}, \"indices\": {}, \
             \"material\": {}, \"mode\": 4}}",
            a + 1,
            a + 2,
            materials.len() - 1
        ));
    }
    let mut j = String::from("{\"asset\": {\"version\": \"2.0\", \"generator\": \"stlc\"}");
    if prims.is_empty() {
        // Nothing drawn: an empty scene (a mesh needs a primitive).
        j.push_str(", \"scene\": 0, \"scenes\": [{\"nodes\": []}]}");
        return (j, 0);
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
            ", \"buffers\": [{{\"byteLength\": {}, \"uri\": \"data:application/octet-stream;base64,{}\"}}]}}",
            len,
            base64(&buffer)
        );
    } else {
        let _ = write!(j, ", \"buffers\": [{{\"byteLength\": {len}}}]}}");
    }
    (j, len)
}

/// Writes the buffer [`json_and_buffer`] laid out (positions, normals,
/// indices of each primitive that has triangles), a few thousand values
/// at a time.
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
        for part in p.indices.chunks(4096) {
            chunk.clear();
            chunk.extend(part.iter().flat_map(|i| i.to_le_bytes()));
            out.write_all(&chunk)?;
        }
    }
    Ok(())
}

/// Standard base64 with padding.
pub(super) fn base64(bytes: &[u8]) -> String {
    const A: &[u8; 64] = b"ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    let mut s = String::with_capacity(bytes.len().div_ceil(3) * 4);
    for c in bytes.chunks(3) {
        let n = (u32::from(c[0]) << 16)
            | (u32::from(*c.get(1).unwrap_or(&0)) << 8)
            | u32::from(*c.get(2).unwrap_or(&0));
        for k in 0..4 {
            if k <= c.len() {
                s.push(A[(n >> (18 - 6 * k) & 63) as usize] as char);
            } else {
                s.push('=');
            }
        }
    }
    s
}

/// Writes `mesh` as glTF JSON with its buffer embedded.
pub fn write_gltf(mesh: &Mesh, out: &mut dyn Write) -> Result<(), Diagnostics> {
    let (json, _) = json_and_buffer(mesh, true);
    out.write_all(json.as_bytes())
        .and_then(|()| out.write_all(b"\n"))
        .and_then(|()| out.flush())
        .map_err(|e| io_error(&e, "writing the glTF").into())
}

/// Writes `mesh` as binary glTF: a 12-byte header, the JSON chunk (padded
/// with spaces to 4 bytes), the BIN chunk (padded with zeros).
pub fn write_glb(mesh: &Mesh, out: &mut dyn Write) -> Result<(), Diagnostics> {
    let (json, bin) = json_and_buffer(mesh, false);
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
            .with_help("a .glb holds at most 4 GiB: write fewer triangles (--sides, --depth)")
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
