//! Meshes an artist can use (issue 33, item 3, first half): a mesh places
//! its first root's base at the origin, y up (stl-language.md section
//! 11), and its tubes carry texture coordinates (`TEXCOORD_0`: u from 0 to
//! 1 around, v along the tube in units of its circumference). Read back
//! from the `.glb` bytes; expected values worked by hand.

use stlc::pipeline::{MeshFormat, NoProgress, Request};

use crate::support::manifest_path;

/// The `.glb` of `text` (named `name`, so its kind is known).
fn glb(name: &str, text: &[u8]) -> Vec<u8> {
    let (mut req, mut out) = (Request::new(text.to_vec()), Vec::new());
    req.name = Some(name.into());
    req.mesh(MeshFormat::Glb, &mut out, &mut NoProgress)
        .unwrap();
    out
}

/// A `.glb` read back: its JSON and its BIN chunk.
pub struct Glb {
    pub json: serde_json::Value,
    bin: Vec<u8>,
}

impl Glb {
    pub fn read(bytes: &[u8]) -> Glb {
        assert_eq!(&bytes[..4], b"glTF");
        let word = |at: usize| u32::from_le_bytes(bytes[at..at + 4].try_into().unwrap()) as usize;
        let jl = word(12);
        assert_eq!(&bytes[16..20], b"JSON");
        let json = serde_json::from_slice(&bytes[20..20 + jl]).unwrap();
        let bl = word(20 + jl);
        assert_eq!(&bytes[24 + jl..28 + jl], b"BIN\0");
        let bin = bytes[28 + jl..28 + jl + bl].to_vec();
        Glb { json, bin }
    }

    /// The 4-byte words of the first primitive's accessor `which` (an
    /// attribute, or `indices`), checked to be glTF's `component` type,
    /// tightly packed, in rows of `width`.
    fn words(&self, which: &str, component: u32, width: usize) -> Vec<Vec<[u8; 4]>> {
        let prim = &self.json["meshes"][0]["primitives"][0];
        let index = prim.get(which).unwrap_or(&prim["attributes"][which]);
        let a = &self.json["accessors"][index.as_u64().unwrap() as usize];
        assert_eq!(a["componentType"], component);
        let view = &self.json["bufferViews"][a["bufferView"].as_u64().unwrap() as usize];
        let off = view["byteOffset"].as_u64().unwrap() as usize;
        let count = a["count"].as_u64().unwrap() as usize;
        let length = view["byteLength"].as_u64().unwrap() as usize;
        assert_eq!(length, 4 * width * count);
        let word = |at: usize| self.bin[at..at + 4].try_into().unwrap();
        let words: Vec<[u8; 4]> = (0..width * count).map(|j| word(off + 4 * j)).collect();
        words.chunks(width).map(<[_]>::to_vec).collect()
    }

    /// The attribute `attribute` of the first primitive, as `width`-float
    /// vectors.
    pub fn floats(&self, attribute: &str, width: usize) -> Vec<Vec<f32>> {
        let float = |r: Vec<[u8; 4]>| r.into_iter().map(f32::from_le_bytes).collect();
        self.words(attribute, 5126, width)
            .into_iter()
            .map(float)
            .collect()
    }

    /// The first primitive's indices (unsigned 32-bit).
    pub fn indices(&self) -> Vec<usize> {
        let rows = self.words("indices", 5125, 1).into_iter();
        rows.map(|r| u32::from_le_bytes(r[0]) as usize).collect()
    }
}

/// The base ring of the mesh's first tube (its side vertices at the
/// start: every other one of the first 2 x (sides + 1), the seam's last
/// one left out), and its texture coordinates' v at the tube's end.
fn first_tube(g: &Glb, sides: usize) -> (Vec<Vec<f32>>, f32) {
    let pos = g.floats("POSITION", 3);
    let uv = g.floats("TEXCOORD_0", 2);
    let ring = (0..sides).map(|j| pos[2 * j].clone()).collect();
    for j in 0..=sides {
        assert_eq!(uv[2 * j], vec![j as f32 / sides as f32, 0.0], "u around");
    }
    (ring, uv[1][1])
}

/// The ring lies at y = 0 around the origin, `r` from it.
fn on_the_ground_at_the_origin(ring: &[Vec<f32>], r: f64) {
    let n = ring.len() as f64;
    for k in [0, 2] {
        let mean: f64 = ring.iter().map(|v| f64::from(v[k])).sum::<f64>() / n;
        let holds = mean.abs() < 1e-7;
        assert!(holds, "the ring's centre is off the origin: {mean}");
    }
    for v in ring {
        assert_eq!(v[1], 0.0, "{v:?}");
        let d = libm::hypot(f64::from(v[0]), f64::from(v[2]));
        assert!((d - r).abs() < 1e-7, "{d}");
    }
}

/// One vertical stem of a BED rooted at (100, 200): 10 units of `L` at
/// 0.01 m a unit (0.1 m), `B=2` (radius 1 unit, 0.01 m), six sides. Its
/// base ring is at y = 0 around the origin, not at (1, -2) m where the
/// canvas puts its root, its top at y = 0.1, and v at its top is
/// 0.1 / (2 pi 0.01) = 1.5915494 circumferences.
#[test]
fn a_single_vertical_stem_stands_on_the_origin_with_v_in_circumferences() {
    let one = b"T (100, 200) L=10(0) B=2(0) A=30\nRULE\nR1: [F]\nSEED\nF\nENDSEED\n";
    let g = Glb::read(&glb("one.bed", one));
    let pos = g.floats("POSITION", 3);
    assert_eq!(pos.len(), 4 * 6 + 2);
    let (ring, v) = first_tube(&g, 6);
    on_the_ground_at_the_origin(&ring, 0.01);
    let top: Vec<f32> = (0..6).map(|j| pos[2 * j + 1][1]).collect();
    let holds = top.iter().all(|&y| (f64::from(y) - 0.1).abs() < 1e-7);
    assert!(holds, "{top:?}");
    assert!((f64::from(v) - 1.591_549_4).abs() < 1e-6, "{v}");
}

/// The oak (examples/oak3d.od, root (100, 290, 0), `L=12`, `B=3`) lands
/// on the origin: its trunk's base ring at y = 0 around it, radius
/// 1.5 units (0.015 m), nothing below the ground; the trunk's first stem
/// is 0.12 m long, so v at its top is 0.12 / (2 pi 0.015) = 1.2732395.
#[test]
fn the_oak_stands_on_the_origin() {
    let oak = std::fs::read(manifest_path("examples/oak3d.od")).unwrap();
    let g = Glb::read(&glb("oak3d.od", &oak));
    let (ring, v) = first_tube(&g, 6);
    on_the_ground_at_the_origin(&ring, 0.015);
    assert!((f64::from(v) - 1.273_239_5).abs() < 1e-6, "{v}");
    let prim = &g.json["meshes"][0]["primitives"][0];
    let pos = &g.json["accessors"][prim["attributes"]["POSITION"].as_u64().unwrap() as usize];
    assert_eq!(pos["min"][1], 0.0, "nothing below the root's base");
}
