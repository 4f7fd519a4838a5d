//! `--solid` (issue 33, item 4): one closed body for 3D printing, written
//! as binary STL. Every file here is read back by a reader written in this
//! test (not the library's code): corners welded by their exact bits,
//! then every edge must be shared by exactly two triangles running it in
//! opposite directions (watertight and consistently oriented), the
//! triangles must form one connected body, its signed volume must be
//! positive (outward windings), and its Euler characteristic V - E + F
//! must be 2 - 2g for the genus g the shape has (0 for a tree, 1 for a
//! ring). Expected values are worked by hand from the inputs.

use std::collections::BTreeMap;
use std::path::Path;

use stlc::color::Rgb;
use stlc::pipeline::NoProgress;
use stlc::render::mesh::{MeshOptions, Tube, build_solid, write_stl};
use stlc::turtle::turtle3::Point3;

use crate::support::{manifest_path, stlc, stlc_line};

/// What the reader found.
#[derive(Debug)]
pub(crate) struct Body {
    pub(crate) triangles: usize,
    vertices: usize,
    edges: usize,
    /// Every edge in exactly two triangles, once each way.
    pub(crate) closed: bool,
    pub(crate) components: usize,
    pub(crate) volume: f64,
    /// The lowest and highest corner, in the file's unit.
    pub(crate) min: [f64; 3],
    pub(crate) max: [f64; 3],
}

impl Body {
    fn euler(&self) -> i64 {
        self.vertices as i64 - self.edges as i64 + self.triangles as i64
    }
}

/// Reads a binary STL: corners welded by their bits, each triangle's
/// written normal against its winding, then [`analyse`].
fn read(bytes: &[u8]) -> Body {
    assert!(bytes.len() >= 84, "shorter than an STL's header");
    let n = u32::from_le_bytes(bytes[80..84].try_into().unwrap()) as usize;
    assert_eq!(bytes.len(), 84 + 50 * n, "size against the triangle count");
    let f = |at: usize| f32::from_le_bytes(bytes[at..at + 4].try_into().unwrap());
    let mut ids: BTreeMap<[u32; 3], usize> = BTreeMap::new();
    let mut points: Vec<[f64; 3]> = Vec::new();
    let mut tris = Vec::with_capacity(n);
    for t in 0..n {
        let at = 84 + 50 * t;
        let normal = [f(at), f(at + 4), f(at + 8)];
        let mut c = [0usize; 3];
        for (k, slot) in c.iter_mut().enumerate() {
            let p = [0, 4, 8].map(|o| f(at + 12 + 12 * k + o));
            *slot = *ids.entry(p.map(f32::to_bits)).or_insert_with(|| {
                points.push(p.map(f64::from));
                points.len() - 1
            });
        }
        // The written normal agrees with the winding.
        let [a, b, cc] = c.map(|i| points[i]);
        let w = crate::organs::winding_normal(a, b, cc);
        let dot: f64 = (0..3).map(|i| w[i] * f64::from(normal[i])).sum();
        assert!(dot >= 0.0, "triangle {t}'s normal against its winding");
        tris.push(c);
    }
    analyse(&points, &tris)
}

/// Checks triangles over shared vertices as the module says: edges,
/// components, signed volume, bounds.
pub(crate) fn analyse(points: &[[f64; 3]], tris: &[[usize; 3]]) -> Body {
    let mut directed: BTreeMap<(usize, usize), u32> = BTreeMap::new();
    for &[a, b, c] in tris {
        for e in [(a, b), (b, c), (c, a)] {
            *directed.entry(e).or_default() += 1;
        }
    }
    let closed = directed
        .iter()
        .all(|(&(a, b), &k)| k == 1 && directed.get(&(b, a)) == Some(&1));
    // Components by union-find over the triangles' corners.
    let mut parent: Vec<usize> = (0..points.len()).collect();
    fn root(p: &mut [usize], mut x: usize) -> usize {
        while p[x] != x {
            p[x] = p[p[x]];
            x = p[x];
        }
        x
    }
    for &[a, b, c] in tris {
        let ra = root(&mut parent, a);
        for x in [b, c] {
            let rx = root(&mut parent, x);
            parent[rx] = ra;
        }
    }
    let mut roots: Vec<usize> = (0..points.len()).map(|i| root(&mut parent, i)).collect();
    roots.sort_unstable();
    roots.dedup();
    let volume = tris
        .iter()
        .map(|t| {
            let [a, b, c] = t.map(|i| points[i]);
            (a[0] * (b[1] * c[2] - b[2] * c[1]) - a[1] * (b[0] * c[2] - b[2] * c[0])
                + a[2] * (b[0] * c[1] - b[1] * c[0]))
                / 6.0
        })
        .sum();
    let axis = |i: usize| points.iter().map(move |p| p[i]);
    let min = [0, 1, 2].map(|i| axis(i).fold(f64::INFINITY, f64::min));
    let max = [0, 1, 2].map(|i| axis(i).fold(f64::NEG_INFINITY, f64::max));
    Body {
        triangles: tris.len(),
        vertices: points.len(),
        edges: directed.len() / 2,
        closed,
        components: roots.len(),
        volume,
        min,
        max,
    }
}

/// A body that can be printed: closed, one piece, outward, of genus `g`.
pub(crate) fn printable(body: &Body, genus: i64) {
    let ok = body.closed;
    assert!(ok, "not watertight or not consistently oriented: {body:?}");
    assert_eq!(body.components, 1, "{body:?}");
    assert!(body.volume > 0.0, "{body:?}");
    assert_eq!(body.euler(), 2 - 2 * genus, "{body:?}");
}

/// A canvas point, (x, y, z).
type Xyz = (f64, f64, f64);

/// The STL of hand-made stems: `(from, to)` in canvas units (y down), each
/// 2 units wide, at the default unit (0.01 m: 10 mm a canvas unit).
fn stems(ends: &[(Xyz, Xyz)]) -> Vec<u8> {
    let p = |(x, y, z): Xyz| Point3::new(x, y, z);
    let tubes: Vec<Tube> = ends
        .iter()
        .map(|&(a, b)| Tube {
            from: p(a),
            to: p(b),
            width: 2.0,
            color: Rgb::BLACK,
        })
        .collect();
    let opts = MeshOptions {
        solid: true,
        ..MeshOptions::default()
    };
    let body = build_solid(&tubes, &[], p(ends[0].0), &opts, &mut NoProgress).unwrap();
    let mut out = Vec::new();
    write_stl(&body, &mut out).unwrap();
    out
}

/// A Y: a stem 10 units up and two branches from its top, 5 across and 5
/// up. One body of genus 0, standing on the origin, z up, millimetres.
#[test]
fn a_y_joint_is_one_closed_body() {
    let y = [
        ((0.0, 0.0, 0.0), (0.0, -10.0, 0.0)),
        ((0.0, -10.0, 0.0), (5.0, -15.0, 0.0)),
        ((0.0, -10.0, 0.0), (-5.0, -15.0, 0.0)),
    ];
    let bytes = stems(&y);
    let body = read(&bytes);
    printable(&body, 0);
    // The stem's base is flat on z = 0 (a root's start gets no ball), its
    // radius 10 mm.
    assert_eq!(body.min[2], 0.0);
    // The tips are at 150 mm up and 50 mm aside; each tip's ball (a little
    // over the 10 mm radius) reaches past them, not by more than 13 mm.
    let top = body.max[2];
    assert!(top > 150.0 + 9.0 && top < 150.0 + 13.0, "top {top}");
    let side = body.max[0];
    assert!(side > 50.0 + 9.0 && side < 50.0 + 13.0, "side {side}");
    assert!(body.min[0] < -59.0, "symmetric");
    // The same stems give the same bytes.
    assert_eq!(bytes, stems(&y));
}

/// Two tubes crossing through each other's middle, no shared end: the
/// union is one body of genus 0 (a plus sign's skin).
#[test]
fn two_crossing_tubes_unite() {
    let plus = [
        ((0.0, 0.0, 0.0), (0.0, -10.0, 0.0)),
        ((-5.0, -5.0, 0.0), (5.0, -5.0, 0.0)),
    ];
    printable(&read(&stems(&plus)), 0);
    // Apart, they are two bodies: the reader sees it.
    let apart = [
        ((0.0, 0.0, 0.0), (0.0, -10.0, 0.0)),
        ((10.0, 0.0, 0.0), (10.0, -10.0, 0.0)),
    ];
    assert_eq!(read(&stems(&apart)).components, 2);
}

/// A square ring of four stems closes on itself: one body of genus 1
/// (Euler characteristic 0).
#[test]
fn a_ring_has_genus_one() {
    let ring = [
        ((0.0, 0.0, 0.0), (0.0, -10.0, 0.0)),
        ((0.0, -10.0, 0.0), (10.0, -10.0, 0.0)),
        ((10.0, -10.0, 0.0), (10.0, 0.0, 0.0)),
        ((10.0, 0.0, 0.0), (0.0, 0.0, 0.0)),
    ];
    printable(&read(&stems(&ring)), 1);
}

/// The oak, written by the command line as `--solid`: one watertight body
/// standing on the origin. (Its genus is what its crossing branches make
/// it; the Euler characteristic must still be even and match a closed
/// surface's 2 - 2g with g >= 0.)
#[test]
fn the_oak_is_one_watertight_body() {
    let dir = tempfile::tempdir().unwrap();
    let oak = manifest_path("examples/oak3d.od");
    let body = read(&solid_written(&oak, &dir.path().join("oak.stl")));
    assert!(body.closed, "{body:?}");
    assert_eq!(body.components, 1, "{body:?}");
    assert!(body.volume > 0.0);
    assert!(body.euler() <= 2 && body.euler() % 2 == 0, "{body:?}");
    assert_eq!(body.min[2], 0.0, "the oak stands on z = 0");
}

/// `--solid` of a 2D input, `--solid` into a picture, an OBJ or a `.gltf`,
/// and an `.stl` or `.3mf` without `--solid` are usage errors (status 2),
/// nothing written.
#[test]
fn solid_usage_errors() {
    let dir = tempfile::tempdir().unwrap();
    let flat = manifest_path("examples/paper-worked.bed");
    let oak = manifest_path("examples/oak3d.od");
    for (input, out, solid, says) in [
        (&flat, "a.stl", true, "needs a 3D input"),
        (&oak, "a.png", true, "not a picture"),
        (&oak, "a.obj", true, "not .obj"),
        (&oak, "a.gltf", true, "not .gltf"),
        (&oak, "a.stl", false, "an .stl {closed}"),
        (&oak, "a.3mf", false, "a .3mf {closed}"),
    ] {
        let says = says.replace("{closed}", "is written as one closed body: add --solid");
        let path = dir.path().join(out);
        let mut cmd = stlc();
        cmd.args(["render", "-q", "-o"]).arg(&path).arg(input);
        if solid {
            cmd.arg("--solid");
        }
        cmd.assert().code(2).stderr(predicates::str::contains(says));
        assert!(!path.exists(), "{out} written");
    }
}

/// `stlc render -q --solid -o out input`, which must succeed: the bytes
/// written.
pub(crate) fn solid_written(input: &Path, out: &Path) -> Vec<u8> {
    let line = format!("render -q --solid -o {} {}", out.display(), input.display());
    stlc_line(&line).assert().success();
    std::fs::read(out).unwrap()
}

/// A trunk and two branches at right angles, `leaf` (` P=L`, or nothing)
/// at each tip, `L` a square of side 10 units (100 mm).
pub(crate) fn leafy_y(leaf: &str) -> String {
    format!(
        "T\n(0, 0, 0)\nL=10(0) B=1(0) A=90{leaf}\nRULE\nR1: [+F][-F]\nSEED\nF R1{{,}}\nENDSEED\n\
         SURFACES\nsurface L {{ {{.f.+f.+f.}} }}\nENDSURFACES\n"
    )
}

/// Leaves join the solid (issue 33): a trunk and two branches with a
/// square leaf of side L at each tip is still one closed body, of genus 0
/// (each leaf's slab overlaps its tip's joint ball), and holds more than
/// the bare stems.
#[test]
fn leaves_are_slabs_united_with_their_stems() {
    let dir = tempfile::tempdir().unwrap();
    let mut volumes = Vec::new();
    for (name, leaf) in [("bare", ""), ("leafy", " P=L")] {
        let input = dir.path().join(format!("{name}.bed"));
        std::fs::write(&input, leafy_y(leaf)).unwrap();
        let out = dir.path().join(format!("{name}.stl"));
        let body = read(&solid_written(&input, &out));
        printable(&body, 0);
        volumes.push(body.volume);
    }
    // Two slabs of 100 mm x 100 mm (L = 10 units of 10 mm) and at least
    // 0.5 mm thick, less what they share with the stems and balls.
    let ok = volumes[1] > volumes[0] + 2.0 * 100.0 * 100.0 * 0.4;
    assert!(ok, "{volumes:?}");
}
