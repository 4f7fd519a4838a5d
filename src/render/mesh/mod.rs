//! Meshes: stems as closed tubes, written as glTF 2.0 (`.glb`, `.gltf`)
//! or Wavefront OBJ (`.obj`). docs/3d.md describes the files.
//!
//! A stem is a tube of `sides` sides around its axis, its diameter the
//! stem's width, closed by a flat cap at each end: `4 * sides + 2`
//! vertices (the sides' `sides + 1` columns, the last at the first's place
//! with u = 1, with normals pointing away from the axis; each cap's
//! `sides` with the axis's direction), `4 * sides - 4` triangles,
//! counter-clockwise seen from outside, every edge between welded
//! positions shared by exactly two of its triangles. Texture coordinates
//! (`TEXCOORD_0`): on the sides u runs from 0 to 1 around the tube and v
//! along it in units of its circumference (0 at its start, length / (2 pi
//! r) at its end), so a square bark texture keeps its aspect; a cap maps
//! its disc onto the unit square's inscribed circle. Widths fall with a
//! stem's order (STL's `B`), so a branch tapers stem by stem. Axes: glTF
//! and OBJ are y up, right-handed; a canvas point (x, y, z) (y down, z
//! away from the viewer) is written at (x - x0, y0 - y, z0 - z) times
//! `unit` (metres per canvas unit), where (x0, y0, z0) is the first root
//! (an `.lsys`'s turtle start, the origin): a translation and a rotation,
//! so windings stay outward and the tree stands on the origin. Stems are
//! grouped by colour, one material (glTF) or group (OBJ) per colour, in
//! the order colours first appear.

mod gltf;
mod leaf;
mod obj;
#[cfg(feature = "solid")]
mod solid;
#[cfg(feature = "solid")]
mod threemf;
mod vector;

pub use leaf::Leaf;

pub use gltf::{write_glb, write_gltf};
pub use obj::write_obj;
#[cfg(feature = "solid")]
pub use solid::{MIN_LEAF_MM, Solid, build_solid, slab, tube_mesh, write_stl};
#[cfg(feature = "solid")]
pub use threemf::write_3mf;

use self::vector::{V, f32s, frame, sub};
use crate::color::Rgb;
use crate::diag::{Diagnostic, Diagnostics, Help, Knob, RenderError};
use crate::turtle::turtle3::{Point3, cos_sin};

/// A mesh file format (from the output's extension, or `--mesh`). The
/// variants' doc comments are the help of `--mesh`.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
#[cfg_attr(feature = "cli", derive(clap::ValueEnum))]
pub enum MeshFormat {
    /// Binary glTF.
    Glb,
    /// glTF JSON with its buffer embedded (base64).
    Gltf,
    /// Wavefront OBJ with vertex colours.
    Obj,
    /// Binary STL, one closed body for 3D printing (needs --solid).
    Stl,
    /// 3D Manufacturing Format, one closed body for 3D printing (needs
    /// --solid).
    #[cfg_attr(feature = "cli", value(name = "3mf"))]
    ThreeMf,
}

impl MeshFormat {
    /// The mesh format an output's extension names, if any.
    pub fn from_extension(ext: &str) -> Option<MeshFormat> {
        match ext.to_ascii_lowercase().as_str() {
            "glb" => Some(MeshFormat::Glb),
            "gltf" => Some(MeshFormat::Gltf),
            "obj" => Some(MeshFormat::Obj),
            "stl" => Some(MeshFormat::Stl),
            "3mf" => Some(MeshFormat::ThreeMf),
            _ => None,
        }
    }

    /// The format's extension.
    pub fn extension(self) -> &'static str {
        match self {
            MeshFormat::Glb => "glb",
            MeshFormat::Gltf => "gltf",
            MeshFormat::Obj => "obj",
            MeshFormat::Stl => "stl",
            MeshFormat::ThreeMf => "3mf",
        }
    }

    /// Whether the format holds only a solid (`--solid`): STL and 3MF.
    pub fn solid_only(self) -> bool {
        matches!(self, MeshFormat::Stl | MeshFormat::ThreeMf)
    }

    /// Whether `--solid` can write the format: STL, 3MF and binary glTF.
    pub fn takes_solid(self) -> bool {
        self.solid_only() || self == MeshFormat::Glb
    }
}

/// How meshes are made.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct MeshOptions {
    /// Sides of each tube (`--sides`), [`MIN_SIDES`] to [`MAX_SIDES`].
    pub sides: u32,
    /// Metres per canvas unit (`--unit`).
    pub unit: f64,
    /// Most triangles a mesh may have (`--max-triangles`).
    pub max_triangles: u64,
    /// One closed body (`--solid`: an `.stl`, `.3mf` or `.glb`): the
    /// tubes and joint spheres united (`solid.rs`).
    pub solid: bool,
}

/// Default of [`MeshOptions::sides`].
pub const DEFAULT_SIDES: u32 = 6;
/// Fewest sides a tube may have.
pub const MIN_SIDES: u32 = 3;
/// Most sides a tube may have.
pub const MAX_SIDES: u32 = 64;
/// Default of [`MeshOptions::unit`]: a canvas unit is a centimetre, so a
/// 300-unit tree is 3 m tall.
pub const DEFAULT_UNIT: f64 = 0.01;
/// Default of [`MeshOptions::max_triangles`]: about 54 bytes a triangle in
/// a `.glb` at 6 sides (vertices, normals, texture coordinates, indices)
/// and 61 at the peak in memory (docs/3d.md, *Meshes*).
pub const DEFAULT_MAX_TRIANGLES: u64 = 10_000_000;

impl Default for MeshOptions {
    fn default() -> Self {
        MeshOptions {
            sides: DEFAULT_SIDES,
            unit: DEFAULT_UNIT,
            max_triangles: DEFAULT_MAX_TRIANGLES,
            solid: false,
        }
    }
}

impl MeshOptions {
    /// Triangles of one tube.
    pub fn triangles_per_tube(&self) -> u64 {
        4 * u64::from(self.sides) - 4
    }

    /// Most tubes within [`MeshOptions::max_triangles`].
    pub fn max_tubes(&self) -> u64 {
        self.max_triangles / self.triangles_per_tube()
    }
}

/// The refusal of a mesh of `tubes` stems (or more, `more`) over the
/// triangle limit.
pub fn mesh_too_large(tubes: u64, more: bool, opts: &MeshOptions) -> Diagnostics {
    let tri = tubes.saturating_mul(opts.triangles_per_tube());
    Diagnostic::error(RenderError::MeshTooLarge {
        triangles: if more {
            format!("more than {tri}")
        } else {
            tri.to_string()
        },
        limit: opts.max_triangles,
    })
    .with_help(
        Help::from(format!(
            "each stem is {} triangles at ",
            opts.triangles_per_tube()
        )) + Help::knob(Knob::Sides, &opts.sides.to_string())
            + ": draw less (lower "
            + Help::knob(Knob::Depth, "")
            + "), use fewer "
            + Help::knob(Knob::Sides, "")
            + ", or raise the limit with "
            + Help::knob(Knob::Triangles, "N"),
    )
    .into()
}

/// One stem to mesh: its ends (canvas units), its width, its colour.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Tube {
    /// Start.
    pub from: Point3,
    /// End.
    pub to: Point3,
    /// Diameter, canvas units.
    pub width: f64,
    /// Colour.
    pub color: Rgb,
}

/// The triangles of one colour, in the files' axes and metres.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct Primitive {
    /// Its colour.
    pub color: Option<Rgb>,
    /// Vertex positions.
    pub positions: Vec<[f32; 3]>,
    /// Vertex normals (unit).
    pub normals: Vec<[f32; 3]>,
    /// Vertex texture coordinates (u around, v along; glTF's
    /// `TEXCOORD_0`, v down the image as glTF's is).
    pub texcoords: Vec<[f32; 2]>,
    /// Triangles, three vertex indices each, counter-clockwise from
    /// outside.
    pub indices: Vec<u32>,
    /// Leaves (polygons, both sides), apart from stems of its colour.
    pub leaf: bool,
}

/// A mesh: one [`Primitive`] per colour.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct Mesh {
    /// The primitives, in the order their colours first appear.
    pub primitives: Vec<Primitive>,
}

impl Mesh {
    /// Triangles in all.
    pub fn triangles(&self) -> u64 {
        self.primitives
            .iter()
            .map(|p| p.indices.len() as u64 / 3)
            .sum()
    }
}

/// A canvas point in the files' axes: (x, -y, -z) times `unit`.
pub fn to_file_axes(p: Point3, unit: f64) -> V {
    [p.x * unit, -p.y * unit, -p.z * unit]
}

/// Builds the mesh of `tubes` (zero-length ones are left out), `origin`
/// (canvas units: the first root) at the files' origin. The caller keeps
/// the number of tubes within [`MeshOptions::max_tubes`].
pub fn build(tubes: &[Tube], origin: Point3, opts: &MeshOptions) -> Mesh {
    build_with_leaves(tubes, &[], origin, opts)
}

/// [`build`] with leaves: each polygon a double-sided face, in a
/// primitive per colour of its own (after the stems').
pub fn build_with_leaves(
    tubes: &[Tube],
    leaves: &[Leaf],
    origin: Point3,
    opts: &MeshOptions,
) -> Mesh {
    let moved = |q: Point3| Point3::new(q.x - origin.x, q.y - origin.y, q.z - origin.z);
    let n = opts.sides.clamp(MIN_SIDES, MAX_SIDES) as usize;
    // The ring's directions, exact at multiples of 90 degrees.
    let ring: Vec<(f64, f64)> = (0..n)
        .map(|j| cos_sin(360.0 * j as f64 / n as f64))
        .collect();
    let mut mesh = Mesh::default();
    for t in tubes {
        let a = to_file_axes(moved(t.from), opts.unit);
        let b = to_file_axes(moved(t.to), opts.unit);
        let d = sub(b, a);
        if d == [0.0; 3] || !d.iter().all(|v| v.is_finite()) {
            continue;
        }
        let idx = match mesh
            .primitives
            .iter()
            .position(|p| !p.leaf && p.color == Some(t.color))
        {
            Some(i) => i,
            None => {
                mesh.primitives.push(Primitive {
                    color: Some(t.color),
                    ..Primitive::default()
                });
                mesh.primitives.len() - 1
            }
        };
        tube(
            &mut mesh.primitives[idx],
            a,
            b,
            d,
            t.width * opts.unit / 2.0,
            &ring,
        );
    }
    // Scratch kept from leaf to leaf.
    let (mut pts, mut f): (Vec<V>, leaf::Faces) = Default::default();
    for l in leaves {
        pts.clear();
        pts.extend(l.points.iter().map(|&q| to_file_axes(moved(q), opts.unit)));
        if !leaf::faces(&pts, &mut f) {
            continue;
        }
        let idx = match mesh
            .primitives
            .iter()
            .position(|p| p.leaf && p.color == Some(l.color))
        {
            Some(i) => i,
            None => {
                mesh.primitives.push(Primitive {
                    color: Some(l.color),
                    leaf: true,
                    ..Primitive::default()
                });
                mesh.primitives.len() - 1
            }
        };
        let p = &mut mesh.primitives[idx];
        let base = p.positions.len() as u32;
        p.positions.extend_from_slice(&f.positions);
        p.normals.extend_from_slice(&f.normals);
        p.texcoords.extend_from_slice(&f.texcoords);
        p.indices.extend(f.indices.iter().map(|i| base + i));
    }
    mesh
}

/// Appends one closed tube from `a` to `b` (axis `d = b - a`), radius `r`.
fn tube(p: &mut Primitive, a: V, b: V, d: V, r: f64, ring: &[(f64, f64)]) {
    let n = ring.len() as u32;
    let (dn, u, v) = frame(d);
    let off: Vec<V> = ring
        .iter()
        .map(|&(c, s)| {
            [
                u[0] * c + v[0] * s,
                u[1] * c + v[1] * s,
                u[2] * c + v[2] * s,
            ]
        })
        .collect();
    let at = |base: V, o: V| [base[0] + r * o[0], base[1] + r * o[1], base[2] + r * o[2]];
    // v along the tube in circumferences: its length over 2 pi r.
    let len = libm::sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
    let top = if r > 0.0 {
        len / (2.0 * std::f64::consts::PI * r)
    } else {
        0.0
    };
    let base = p.positions.len() as u32;
    // Sides: bottom and top of each direction, normals outward; the
    // column after the last is the first again, with u = 1 (the seam).
    for j in 0..=n {
        let o = off[(j % n) as usize];
        let s = (f64::from(j) / f64::from(n)) as f32;
        p.positions.push(f32s(at(a, o)));
        p.normals.push(f32s(o));
        p.texcoords.push([s, 0.0]);
        p.positions.push(f32s(at(b, o)));
        p.normals.push(f32s(o));
        p.texcoords.push([s, top as f32]);
    }
    // Caps: the start's facing -d, the end's +d; the disc on the unit
    // square's inscribed circle.
    let back = dn.map(|x| -x);
    let disc = |(c, s): (f64, f64)| [(0.5 + 0.5 * c) as f32, (0.5 + 0.5 * s) as f32];
    for (o, cs) in off.iter().zip(ring) {
        p.positions.push(f32s(at(a, *o)));
        p.normals.push(f32s(back));
        p.texcoords.push(disc(*cs));
    }
    for (o, cs) in off.iter().zip(ring) {
        p.positions.push(f32s(at(b, *o)));
        p.normals.push(f32s(dn));
        p.texcoords.push(disc(*cs));
    }
    for j in 0..n {
        let k = j + 1;
        let (aj, bj, ak, bk) = (
            base + 2 * j,
            base + 2 * j + 1,
            base + 2 * k,
            base + 2 * k + 1,
        );
        p.indices.extend([aj, ak, bk, aj, bk, bj]);
    }
    let start = base + 2 * (n + 1);
    let end = start + n;
    for j in 1..n - 1 {
        p.indices.extend([start, start + j + 1, start + j]);
        p.indices.extend([end, end + j, end + j + 1]);
    }
}

/// Appends `f32` pairs to `buf`, little-endian.
fn le_f32_pairs(v: &[[f32; 2]], buf: &mut Vec<u8>) {
    buf.reserve(8 * v.len());
    for t in v {
        for x in t {
            // Four bytes at a time: a byte-wise `flat_map` was a third of
            // a leafy mesh's time (docs/performance.md).
            buf.extend_from_slice(&x.to_le_bytes());
        }
    }
}

/// Appends `f32` triples to `buf`, little-endian.
fn le_f32s(v: &[[f32; 3]], buf: &mut Vec<u8>) {
    buf.reserve(12 * v.len());
    for t in v {
        for x in t {
            buf.extend_from_slice(&x.to_le_bytes());
        }
    }
}

/// Whether `n` tubes are within the limit; the refusal otherwise.
pub fn check_tubes(n: u64, more: bool, opts: &MeshOptions) -> Result<(), Diagnostics> {
    if more || n > opts.max_tubes() {
        return Err(mesh_too_large(n, more, opts));
    }
    Ok(())
}

#[cfg(test)]
mod tests;
