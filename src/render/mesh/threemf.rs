//! `--solid -o x.3mf`: the solid as a 3D Manufacturing Format package
//! (docs/3d.md, *Solids*). A 3MF is a zip (an OPC package) of three
//! parts: `[Content_Types].xml`, `_rels/.rels` (which names the model)
//! and `3D/3dmodel.model`, the XML model: one `<object type="model">`
//! whose mesh lists each vertex once and each triangle by three vertex
//! indices, counter-clockwise from outside, in millimetres (the solid's
//! axes: z up), and one build item placing it as it is.
//!
//! The bytes are the same on every run: coordinates have six decimals
//! (a nanometre), written from integers; the zip's entries
//! carry a fixed date (1980-01-01 00:00, the earliest a zip can say) and
//! are deflated by `flate2` (a dependency already compiled in for PNG
//! encoding, docs/dependencies.md). The container is written here: its
//! local headers, central directory and end record (PKWARE's APPNOTE,
//! no ZIP64: a package over 4 GiB is refused).

use std::fmt::Write as _;
use std::io::Write;

use flate2::write::DeflateEncoder;
use flate2::{Compression, Crc};

use super::solid::{Solid, weld};
use crate::diag::{Diagnostic, Diagnostics, RenderError, io_error};

/// Steps of a millimetre in the model's coordinates: six decimals, a
/// nanometre, finer than an `f32`'s step at 16 mm and over, so the corners
/// of the STL's body stay apart (the oak's 3MF has the STL's vertices and
/// triangles, docs/3d.md).
const STEPS: f64 = 1_000_000.0;

const CONTENT_TYPES: &str = "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n\
<Types xmlns=\"http://schemas.openxmlformats.org/package/2006/content-types\">\
<Default Extension=\"rels\" ContentType=\"application/vnd.openxmlformats-package.relationships+xml\"/>\
<Default Extension=\"model\" ContentType=\"application/vnd.ms-package.3dmanufacturing-3dmodel+xml\"/>\
</Types>\n";

const RELS: &str = "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n\
<Relationships xmlns=\"http://schemas.openxmlformats.org/package/2006/relationships\">\
<Relationship Target=\"/3D/3dmodel.model\" Id=\"rel0\" \
Type=\"http://schemas.microsoft.com/3dmanufacturing/2013/01/3dmodel\"/>\
</Relationships>\n";

/// One deflated part of the package.
struct Entry {
    name: &'static str,
    crc: u32,
    /// Bytes before deflating.
    size: u64,
    deflated: Vec<u8>,
}

/// Deflates a part as it is written, counting its bytes and their CRC.
struct Part {
    crc: Crc,
    deflate: DeflateEncoder<Vec<u8>>,
}

impl Part {
    fn new() -> Part {
        Part {
            crc: Crc::new(),
            deflate: DeflateEncoder::new(Vec::new(), Compression::fast()),
        }
    }

    fn push(&mut self, text: &str) -> std::io::Result<()> {
        self.crc.update(text.as_bytes());
        self.deflate.write_all(text.as_bytes())
    }

    fn finish(self, name: &'static str) -> std::io::Result<Entry> {
        Ok(Entry {
            name,
            crc: self.crc.sum(),
            size: u64::from(self.crc.amount()),
            deflated: self.deflate.finish()?,
        })
    }
}

/// A coordinate in steps of [`STEPS`] per millimetre, rounded to the
/// nearest (half away from zero).
fn steps(x: f32) -> i64 {
    libm::round(f64::from(x) * STEPS) as i64
}

/// `k` steps as a decimal with six places.
fn push_steps(buf: &mut String, k: i64) {
    let sign = if k < 0 { "-" } else { "" };
    let a = k.unsigned_abs();
    let _ = write!(buf, "{sign}{}.{:06}", a / 1_000_000, a % 1_000_000);
}

/// The model part: the solid's corners on the six-decimal grid, welded
/// there ([`weld`]: two corners within a step of each other are one
/// vertex, and a triangle that loses its area goes), streamed into its
/// deflater. Gives the part and the triangles written.
fn model(solid: &Solid) -> std::io::Result<(Entry, u64)> {
    let keys: Vec<[i64; 3]> = solid.positions.iter().map(|p| p.map(steps)).collect();
    let (first, triangles) = weld(&keys, &solid.triangles);
    let mut part = Part::new();
    let mut buf = String::with_capacity(1 << 16);
    buf.push_str(
        "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n\
         <model unit=\"millimeter\" xml:lang=\"en-US\" \
         xmlns=\"http://schemas.microsoft.com/3dmanufacturing/core/2015/02\">\n\
         <metadata name=\"Application\">stlc</metadata>\n\
         <resources>\n<object id=\"1\" type=\"model\" name=\"tree\">\n<mesh>\n<vertices>\n",
    );
    for &i in &first {
        let [x, y, z] = keys[i];
        buf.push_str("<vertex x=\"");
        push_steps(&mut buf, x);
        buf.push_str("\" y=\"");
        push_steps(&mut buf, y);
        buf.push_str("\" z=\"");
        push_steps(&mut buf, z);
        buf.push_str("\"/>\n");
        if buf.len() >= 1 << 16 {
            part.push(&buf)?;
            buf.clear();
        }
    }
    buf.push_str("</vertices>\n<triangles>\n");
    for [a, b, c] in &triangles {
        let _ = writeln!(buf, "<triangle v1=\"{a}\" v2=\"{b}\" v3=\"{c}\"/>");
        if buf.len() >= 1 << 16 {
            part.push(&buf)?;
            buf.clear();
        }
    }
    buf.push_str(
        "</triangles>\n</mesh>\n</object>\n</resources>\n\
         <build>\n<item objectid=\"1\"/>\n</build>\n</model>\n",
    );
    part.push(&buf)?;
    Ok((part.finish("3D/3dmodel.model")?, triangles.len() as u64))
}

/// Writes `solid` as a 3MF package; the triangles written.
pub fn write_3mf(solid: &Solid, out: &mut dyn Write) -> Result<u64, Diagnostics> {
    let err = |e: std::io::Error| Diagnostics::from(io_error(&e, "writing the 3MF"));
    let small = |name, text: &str| {
        let mut p = Part::new();
        p.push(text)?;
        p.finish(name)
    };
    let (model, triangles) = model(solid).map_err(err)?;
    let entries = [
        small("[Content_Types].xml", CONTENT_TYPES).map_err(err)?,
        small("_rels/.rels", RELS).map_err(err)?,
        model,
    ];
    let total: u64 = entries
        .iter()
        .map(|e| e.size.max(e.deflated.len() as u64) + 200)
        .sum();
    if u32::try_from(total).is_err() {
        return Err(Diagnostic::error(RenderError::MeshTooLarge {
            triangles: triangles.to_string(),
            limit: triangles,
        })
        .with_help("a .3mf here holds at most 4 GiB: write the solid as .stl, or unite fewer stems")
        .into());
    }
    write_zip(&entries, out).map_err(err)?;
    Ok(triangles)
}

/// The zip's fixed modification time and date (MS-DOS format):
/// 1980-01-01 00:00:00.
const DOS_TIME: u16 = 0;
const DOS_DATE: u16 = (1 << 5) | 1;

/// Writes `entries` as a zip: each a local header and its deflated bytes,
/// then the central directory and its end record. The caller has checked
/// that every size and offset fits in 32 bits.
fn write_zip(entries: &[Entry], out: &mut dyn Write) -> std::io::Result<()> {
    // The fields a local header and a central directory record share,
    // from "version needed" to the name's length.
    let common = |e: &Entry| {
        let mut b = Vec::with_capacity(26);
        b.extend(20u16.to_le_bytes()); // version needed: 2.0 (deflate)
        b.extend(0u16.to_le_bytes()); // flags
        b.extend(8u16.to_le_bytes()); // method: deflate
        b.extend(DOS_TIME.to_le_bytes());
        b.extend(DOS_DATE.to_le_bytes());
        b.extend(e.crc.to_le_bytes());
        b.extend((e.deflated.len() as u32).to_le_bytes());
        b.extend((e.size as u32).to_le_bytes());
        b.extend((e.name.len() as u16).to_le_bytes());
        b
    };
    let mut offsets = Vec::with_capacity(entries.len());
    let mut at = 0u64;
    for e in entries {
        offsets.push(at as u32);
        let mut head = 0x0403_4b50u32.to_le_bytes().to_vec();
        head.extend(common(e));
        head.extend(0u16.to_le_bytes()); // extra field's length
        head.extend(e.name.as_bytes());
        out.write_all(&head)?;
        out.write_all(&e.deflated)?;
        at += (head.len() + e.deflated.len()) as u64;
    }
    let mut dir = Vec::new();
    for (e, offset) in entries.iter().zip(&offsets) {
        dir.extend(0x0201_4b50u32.to_le_bytes());
        dir.extend(20u16.to_le_bytes()); // made by: MS-DOS, 2.0
        dir.extend(common(e));
        dir.extend(0u16.to_le_bytes()); // extra field's length
        dir.extend(0u16.to_le_bytes()); // comment's length
        dir.extend(0u16.to_le_bytes()); // disk
        dir.extend(0u16.to_le_bytes()); // internal attributes
        dir.extend(0u32.to_le_bytes()); // external attributes
        dir.extend(offset.to_le_bytes());
        dir.extend(e.name.as_bytes());
    }
    let n = entries.len() as u16;
    let mut end = 0x0605_4b50u32.to_le_bytes().to_vec();
    end.extend(0u16.to_le_bytes()); // this disk
    end.extend(0u16.to_le_bytes()); // the directory's disk
    end.extend(n.to_le_bytes());
    end.extend(n.to_le_bytes());
    end.extend((dir.len() as u32).to_le_bytes());
    end.extend((at as u32).to_le_bytes());
    end.extend(0u16.to_le_bytes()); // comment's length
    out.write_all(&dir)?;
    out.write_all(&end)?;
    out.flush()
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Coordinates are written from whole steps: six places, a sign only
    /// below zero, half a step rounded away from zero.
    #[test]
    fn coordinates_have_six_decimals() {
        let text = |x: f32| {
            let mut s = String::new();
            push_steps(&mut s, steps(x));
            s
        };
        assert_eq!(text(0.0), "0.000000");
        assert_eq!(text(-0.0), "0.000000");
        assert_eq!(text(12.5), "12.500000");
        assert_eq!(text(-0.25), "-0.250000");
        assert_eq!(text(2300.0), "2300.000000");
        // The f32 nearest -1.0000004 is -1.00000035762...; nearest 6e-7,
        // 6.0000002e-7.
        assert_eq!(text(-1.000_000_4), "-1.000000");
        assert_eq!(text(0.000_000_6), "0.000001");
    }
}
