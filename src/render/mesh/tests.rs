//! The mesh's shape (closed, outward) and its files' structure.

use std::collections::BTreeMap;

use super::vector::cross;
use super::*;

fn p(x: f64, y: f64, z: f64) -> Point3 {
    Point3::new(x, y, z)
}

fn tubes() -> Vec<Tube> {
    let brown = Rgb::new(0x4a, 0x2c, 0x12);
    let green = Rgb::new(0, 0x80, 0);
    vec![
        Tube {
            from: p(0.0, 0.0, 0.0),
            to: p(0.0, -10.0, 0.0),
            width: 2.0,
            color: brown,
        },
        Tube {
            from: p(0.0, -10.0, 0.0),
            to: p(3.0, -14.0, 5.0),
            width: 1.0,
            color: green,
        },
        Tube {
            from: p(1.0, 2.0, 3.0),
            to: p(1.0, 2.0, 3.0),
            width: 1.0,
            color: green,
        },
        Tube {
            from: p(0.0, -10.0, 0.0),
            to: p(-2.5, -13.0, -1.0),
            width: 0.5,
            color: brown,
        },
    ]
}

/// Per tube (4n + 2 vertices each, in order): every undirected edge between
/// welded positions is used by exactly two triangles, once in each
/// direction (closed and consistently wound), and every triangle's
/// normal points away from its tube's centre (a convex solid).
#[test]
fn every_tube_is_closed_and_faces_outward() {
    for sides in [3, 4, 6, 11] {
        let opts = MeshOptions {
            sides,
            ..MeshOptions::default()
        };
        let mesh = build(&tubes(), Point3::default(), &opts);
        assert_eq!(mesh.primitives.len(), 2, "one primitive per colour");
        // The zero-length tube is left out: 3 tubes.
        assert_eq!(mesh.triangles(), 3 * (4 * u64::from(sides) - 4));
        let n = sides as usize;
        for prim in &mesh.primitives {
            assert_eq!(prim.positions.len() % (4 * n + 2), 0);
            assert_eq!(prim.texcoords.len(), prim.positions.len());
            let per = 3 * (4 * n - 4);
            for (t, tris) in prim.indices.chunks(per).enumerate() {
                let key = |i: u32| prim.positions[i as usize].map(f32::to_bits);
                let mut edges: BTreeMap<([u32; 3], [u32; 3]), i32> = BTreeMap::new();
                let verts = &prim.positions[t * (4 * n + 2)..(t + 1) * (4 * n + 2)];
                let mut centre = [0.0f64; 3];
                for v in verts {
                    for k in 0..3 {
                        centre[k] += f64::from(v[k]) / verts.len() as f64;
                    }
                }
                for tri in tris.chunks(3) {
                    for e in 0..3 {
                        let (a, b) = (key(tri[e]), key(tri[(e + 1) % 3]));
                        *edges.entry((a, b)).or_default() += 1;
                    }
                    let q: Vec<[f64; 3]> = tri
                        .iter()
                        .map(|&i| prim.positions[i as usize].map(f64::from))
                        .collect();
                    let nrm = cross(sub(q[1], q[0]), sub(q[2], q[0]));
                    let mid: Vec<f64> = (0..3)
                        .map(|k| (q[0][k] + q[1][k] + q[2][k]) / 3.0 - centre[k])
                        .collect();
                    let dot: f64 = (0..3).map(|k| nrm[k] * mid[k]).sum();
                    assert!(dot > 0.0, "a triangle faces inward (sides {sides})");
                    // Vertex normals agree with the face.
                    for &i in tri {
                        let vn = prim.normals[i as usize].map(f64::from);
                        assert!((0..3).map(|k| vn[k] * nrm[k]).sum::<f64>() > 0.0);
                    }
                }
                for (&(a, b), &c) in &edges {
                    assert_eq!(c, 1, "a directed edge used twice");
                    assert_eq!(edges.get(&(b, a)), Some(&1), "an edge used once");
                }
            }
        }
    }
}

#[test]
fn axes_and_units_are_the_files() {
    // A canvas stem up the screen (-y) from the origin, 100 units, at the
    // default 0.01 m a unit: from y = 0 to y = +1 m (y up in the file).
    let t = [Tube {
        from: p(0.0, 0.0, 0.0),
        to: p(0.0, -100.0, 0.0),
        width: 2.0,
        color: Rgb::BLACK,
    }];
    let mesh = build(&t, Point3::default(), &MeshOptions::default());
    let ys: Vec<f32> = mesh.primitives[0].positions.iter().map(|v| v[1]).collect();
    assert_eq!(ys.iter().copied().fold(f32::MAX, f32::min), 0.0);
    assert_eq!(ys.iter().copied().fold(f32::MIN, f32::max), 1.0);
    // Radius 1 unit = 0.01 m: every side vertex is 0.01 from the axis.
    for v in &mesh.primitives[0].positions {
        assert!((libm::hypot(f64::from(v[0]), f64::from(v[2])) - 0.01).abs() < 1e-7);
    }
    // Away from the viewer (+z on the canvas) is -z in the file.
    assert_eq!(to_file_axes(p(1.0, 2.0, 3.0), 0.5), [0.5, -1.0, -1.5]);
}

#[test]
fn base64_of_known_strings() {
    assert_eq!(gltf::base64(b"Man"), "TWFu");
    assert_eq!(gltf::base64(b"Ma"), "TWE=");
    assert_eq!(gltf::base64(b"M"), "TQ==");
    assert_eq!(gltf::base64(b""), "");
}

fn unbase64(s: &str) -> Vec<u8> {
    let val = |c: u8| match c {
        b'A'..=b'Z' => c - b'A',
        b'a'..=b'z' => c - b'a' + 26,
        b'0'..=b'9' => c - b'0' + 52,
        b'+' => 62,
        _ => 63,
    };
    let mut out = Vec::new();
    for q in s.as_bytes().chunks(4) {
        let n = q
            .iter()
            .take_while(|&&c| c != b'=')
            .fold((0u32, 0), |(n, k), &c| {
                (n | (u32::from(val(c)) << (18 - 6 * k)), k + 1)
            });
        let bytes = [(n.0 >> 16) as u8, (n.0 >> 8) as u8, n.0 as u8];
        out.extend_from_slice(&bytes[..n.1 - 1]);
    }
    out
}

/// The `.gltf`'s JSON read back: counts, offsets and lengths add up,
/// accessors' min and max are the data's, the embedded buffer is the
/// `.glb`'s BIN chunk.
#[test]
fn the_gltf_reads_back_and_agrees_with_its_data() {
    let mesh = build(&tubes(), Point3::default(), &MeshOptions::default());
    let mut text = Vec::new();
    write_gltf(&mesh, &mut text).unwrap();
    let j: serde_json::Value = serde_json::from_slice(&text).unwrap();
    assert_eq!(j["asset"]["version"], "2.0");
    let uri = j["buffers"][0]["uri"].as_str().unwrap();
    let data = unbase64(
        uri.strip_prefix("data:application/octet-stream;base64,")
            .unwrap(),
    );
    assert_eq!(
        j["buffers"][0]["byteLength"].as_u64(),
        Some(data.len() as u64)
    );
    let prims = j["meshes"][0]["primitives"].as_array().unwrap();
    assert_eq!(prims.len(), 2);
    assert_eq!(j["materials"].as_array().unwrap().len(), 2);
    for (prim, ours) in prims.iter().zip(&mesh.primitives) {
        let acc = |i: &serde_json::Value| &j["accessors"][i.as_u64().unwrap() as usize];
        let pos = acc(&prim["attributes"]["POSITION"]);
        let idx = acc(&prim["indices"]);
        assert_eq!(pos["count"].as_u64(), Some(ours.positions.len() as u64));
        assert_eq!(idx["count"].as_u64(), Some(ours.indices.len() as u64));
        assert_eq!(idx["componentType"], 5125);
        let view = &j["bufferViews"][pos["bufferView"].as_u64().unwrap() as usize];
        let off = view["byteOffset"].as_u64().unwrap() as usize;
        assert_eq!(
            view["byteLength"].as_u64(),
            Some(12 * ours.positions.len() as u64)
        );
        // min/max read as f32 equal the data's.
        for k in 0..3 {
            let vals: Vec<f32> = (0..ours.positions.len())
                .map(|v| {
                    let at = off + 12 * v + 4 * k;
                    f32::from_le_bytes(data[at..at + 4].try_into().unwrap())
                })
                .collect();
            let lo = vals.iter().copied().fold(f32::MAX, f32::min);
            let hi = vals.iter().copied().fold(f32::MIN, f32::max);
            assert_eq!(pos["min"][k].as_f64().unwrap() as f32, lo);
            assert_eq!(pos["max"][k].as_f64().unwrap() as f32, hi);
        }
        let iv = &j["bufferViews"][idx["bufferView"].as_u64().unwrap() as usize];
        let ioff = iv["byteOffset"].as_u64().unwrap() as usize;
        for (i, &want) in ours.indices.iter().enumerate() {
            let at = ioff + 4 * i;
            let got = u32::from_le_bytes(data[at..at + 4].try_into().unwrap());
            assert_eq!(got, want);
            assert!((got as usize) < ours.positions.len());
        }
    }
    let mut glb = Vec::new();
    write_glb(&mesh, &mut glb).unwrap();
    assert_eq!(&glb[0..4], b"glTF");
    assert_eq!(
        u32::from_le_bytes(glb[8..12].try_into().unwrap()) as usize,
        glb.len()
    );
    let jl = u32::from_le_bytes(glb[12..16].try_into().unwrap()) as usize;
    assert_eq!(jl % 4, 0);
    let bin_at = 20 + jl;
    let bl = u32::from_le_bytes(glb[bin_at..bin_at + 4].try_into().unwrap()) as usize;
    assert_eq!(&glb[bin_at + 4..bin_at + 8], b"BIN\0");
    assert_eq!(&glb[bin_at + 8..bin_at + 8 + data.len()], &data[..]);
    assert_eq!(bl % 4, 0);
}

#[test]
fn the_obj_has_a_vertex_and_normal_per_vertex_and_a_face_per_triangle() {
    let mesh = build(&tubes(), Point3::default(), &MeshOptions::default());
    let mut out = Vec::new();
    write_obj(&mesh, &mut out).unwrap();
    let text = String::from_utf8(out).unwrap();
    let count = |p: &str| text.lines().filter(|l| l.starts_with(p)).count();
    let verts: usize = mesh.primitives.iter().map(|p| p.positions.len()).sum();
    assert_eq!(count("v "), verts);
    assert_eq!(count("vn "), verts);
    assert_eq!(count("vt "), verts);
    assert_eq!(count("f ") as u64, mesh.triangles());
    assert_eq!(count("g "), 2);
    // Every face's indices are within the vertices written before it.
    let mut seen = 0usize;
    for l in text.lines() {
        if l.starts_with("v ") {
            seen += 1;
            assert_eq!(l.split(' ').count(), 7, "x y z r g b: {l}");
        }
        if let Some(f) = l.strip_prefix("f ") {
            for v in f.split(' ') {
                let k: Vec<usize> = v.split('/').map(|x| x.parse().unwrap()).collect();
                assert_eq!(k.len(), 3, "v/vt/vn: {l}");
                assert!(k.iter().all(|&i| i >= 1 && i <= seen));
            }
        }
    }
}

#[test]
fn the_limit_is_counted_in_triangles() {
    let opts = MeshOptions {
        sides: 6,
        max_triangles: 200,
        ..MeshOptions::default()
    };
    assert_eq!(opts.max_tubes(), 10);
    assert!(check_tubes(10, false, &opts).is_ok());
    let err = check_tubes(11, false, &opts).unwrap_err();
    let msg = err.to_string();
    assert!(msg.contains("220") && msg.contains("200"), "{msg}");
}

/// One vertical stem of a tree rooted at (150, 298, 40), 100 units up at
/// the default 0.01 m a unit, width 2 (radius 0.01 m), six sides: its
/// base ring lies at y = 0 around the origin (the root is the files'
/// origin), its top ring at y = 1; u runs 0, 1/6, ... 1 around (the seam
/// column twice, at u = 0 and u = 1), v is 0 at the base and 1 / (2 pi
/// 0.01) = 15.915494 circumferences at the top; a cap's texture
/// coordinates lie on the unit square's inscribed circle.
#[test]
fn the_first_root_is_the_origin_and_v_counts_circumferences() {
    let root = p(150.0, 298.0, 40.0);
    let t = [Tube {
        from: root,
        to: p(150.0, 198.0, 40.0),
        width: 2.0,
        color: Rgb::BLACK,
    }];
    let mesh = build(&t, root, &MeshOptions::default());
    let prim = &mesh.primitives[0];
    assert_eq!(prim.positions.len(), 4 * 6 + 2);
    let top = (1.0 / (2.0 * std::f64::consts::PI * 0.01)) as f32;
    assert!((top - 15.915_494).abs() < 1e-5);
    for j in 0..=6 {
        let (base, tip) = (2 * j, 2 * j + 1);
        for (i, y, v) in [(base, 0.0, 0.0), (tip, 1.0, top)] {
            let q = prim.positions[i];
            assert_eq!(q[1], y, "vertex {i}");
            assert!((libm::hypot(f64::from(q[0]), f64::from(q[2])) - 0.01).abs() < 1e-7);
            assert_eq!(prim.texcoords[i], [j as f32 / 6.0, v], "vertex {i}");
        }
    }
    // The seam: the last column is the first again.
    assert_eq!(prim.positions[12], prim.positions[0]);
    for i in 14..26 {
        let [u, v] = prim.texcoords[i].map(f64::from);
        assert!(
            (libm::hypot(u - 0.5, v - 0.5) - 0.5).abs() < 1e-6,
            "cap {i}"
        );
    }
    // The ring's centre is the origin: its mean is (0, 0, 0).
    for k in [0, 2] {
        let mean: f64 = (0..6)
            .map(|j| f64::from(prim.positions[2 * j][k]))
            .sum::<f64>()
            / 6.0;
        assert!(mean.abs() < 1e-9, "axis {k}: {mean}");
    }
}
