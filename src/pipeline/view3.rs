//! Three dimensions in the pipeline (docs/3d.md): which scenes are drawn
//! in 3D and the view that draws them (a 3D `.lsys` by `lsys3.rs`, a 3D
//! tree by `tree3.rs`), the stems an editor draws in its own 3D view
//! ([`Stems3`]), and any input's mesh (`.glb`, `.gltf`, `.obj`) or solid
//! (`.stl`, `.3mf`, `.glb`).

use std::io::Write;

use super::lsys3::{check_stems, lsys3, nothing_drawn};
use super::tree3::{bed3, draw_tree3};
use super::{Rendered, Scene, What, style};
use crate::diag::{Diagnostic, Diagnostics, RenderError};
use crate::interpret::lsys::lsys3::draw3;
use crate::interpret::lsys::param::Mark;
use crate::progress::{Phase, Progress};
use crate::render::mesh::{self, MeshFormat, MeshOptions, Tube};
use crate::render::view::View;
use crate::render::{RenderOptions, Width};
use crate::turtle::turtle3::{Point3, Segment3};
use crate::turtle::{Segment, Turtle};

/// Whether a scene is drawn in 3D: a 3D `.lsys` or a 3D tree.
pub(crate) fn is_3d(scene: &Scene) -> bool {
    bed3(scene).is_some() || lsys3(scene).is_some()
}

/// Draws a 3D scene seen from `view`: a 3D tree by
/// [`super::tree3::render_view`], a 3D `.lsys` by
/// [`super::lsys3::render_view`].
pub(crate) fn render_view(
    scene: &Scene,
    view: View,
    look: &super::Look,
    opts: &RenderOptions,
    out: &mut dyn Write,
    progress: &mut dyn Progress,
) -> Result<Rendered, Diagnostics> {
    match bed3(scene) {
        Some(bed) => super::tree3::render_view(scene, bed, view, look, opts, out, progress),
        None => super::lsys3::render_view(scene, view, look, opts, out, progress),
    }
}

/// Most stems the editor's 3D view takes: its page holds each in 32 bytes
/// of a WebGL buffer (a 2D answer's SVG has its own limit).
pub const MAX_EDITOR_STEMS: u64 = 1_000_000;

/// A 3D input for an editor that draws it itself (its own WebGL view):
/// [`super::Request::render`] with `trace` and `tree_up_to` gives this in
/// [`super::Drawn::stems3`] instead of drawing a picture.
#[derive(Debug, Clone, PartialEq)]
pub struct Stems3 {
    /// Eight numbers a stem, in drawing order: from x, y, z, to x, y, z,
    /// width, decision (0: a drawing has no decisions).
    pub stems: Vec<f64>,
    /// Whether widths are screen pixels (an `.lsys`'s `width`), not canvas
    /// units (a tree's `B`).
    pub width_in_pixels: bool,
    /// The background, `None` for transparent.
    pub background: Option<crate::color::Rgb>,
    /// A tree's layout volumes, in painting order.
    pub volumes: Vec<crate::model::LayoutSolid>,
    /// A tree's first root's x and z: the axis a `Revolve` turns about.
    pub axis: Option<[f64; 2]>,
    /// The colours of an input that paints (a palette `.lsys`, an `S=`
    /// ramp, leaves), as the meshes and pictures paint it; `[]` when every
    /// stem is in the stroke colour.
    pub colors: Vec<crate::color::Rgb>,
    /// Each stem's index into `colors` (`[]` without colours).
    pub stem_colors: Vec<u32>,
    /// The leaves (polygons, `{ }`, `~X`, `P=`): each its index into
    /// `colors` and its vertices.
    pub leaves: Vec<(u32, Vec<Point3>)>,
}

/// The stems, colours and leaves an editor's 3D view is handed, up to
/// [`MAX_EDITOR_STEMS`] pieces (`over` once one more came).
#[derive(Default)]
struct Pieces {
    stems: Vec<f64>,
    colors: Vec<crate::color::Rgb>,
    stem_colors: Vec<u32>,
    leaves: Vec<(u32, Vec<Point3>)>,
    over: bool,
}

impl Pieces {
    fn full(&mut self) -> bool {
        self.over |= (self.stems.len() / 8 + self.leaves.len()) as u64 >= MAX_EDITOR_STEMS;
        self.over
    }

    fn stem(&mut self, s: Segment3, width: f64, color: Option<u32>) {
        if self.full() {
            return;
        }
        let (a, b) = (s.from, s.to);
        self.stems
            .extend([a.x, a.y, a.z, b.x, b.y, b.z, width, 0.0]);
        self.stem_colors.extend(color);
    }

    /// A painting turtle's marks, `paint` the colour index in force.
    fn mark(
        &mut self,
        m: Mark,
        paint: &mut u32,
        width: impl Fn(u32) -> f64,
        index: impl Fn(usize) -> u32,
    ) {
        match m {
            Mark::Step(s, _) => self.stem(s, width(s.order), Some(*paint)),
            Mark::Paint(i) => *paint = index(i),
            Mark::Polygon(points) => {
                if !self.full() {
                    self.leaves.push((*paint, points.to_vec()));
                }
            }
        }
    }
}

/// The scene's stems in 3D for an editor ([`Stems3`]), with what a picture
/// would have counted; `None` for a flat input. A grown tree's stems are
/// `placed`, its growth's, in growth order with their decisions.
pub(crate) fn editor_stems3(
    scene: &Scene,
    look: &super::Look,
    placed: &[crate::grow::PlacedStem],
    progress: &mut dyn Progress,
) -> Result<Option<(Stems3, Rendered)>, Diagnostics> {
    let too_many = |n: String| -> Diagnostics {
        Diagnostic::error(RenderError::ViewTooLarge {
            segments: n,
            limit: MAX_EDITOR_STEMS,
        })
        .with_help("the editor's 3D view holds every stem: use a smaller depth, or `stlc render --view AZ,EL`")
        .into()
    };
    let style = style(scene, look);
    let width = |order: u32| match style.width {
        Width::Pixels(w) => w,
        Width::Canvas(lin) => lin.at(order).max(0.0),
    };
    let mut got = Pieces::default();
    let mut phase = Phase::new(progress, "deriving");
    let (mut volumes, mut axis) = (Vec::new(), None);
    match &scene.what {
        What::Lsys { sys, depth } if sys.is_3d() => {
            check_stems(sys, *depth, &scene.limits, MAX_EDITOR_STEMS, too_many)?;
            let d = scene.derivation;
            if let Some(p) = sys.parametric.as_deref().filter(|p| p.paints()) {
                // As the mesh paints (docs/lsys.md): the palette, and the
                // stroke past its end (the last colour here).
                got.colors = p.organs.palette.clone();
                got.colors.push(style.stroke);
                let last = got.colors.len() - 1;
                let index = |i: usize| i.min(last) as u32;
                let mut paint = index(if p.organs.palette.is_empty() { last } else { 0 });
                let limits = &scene.limits;
                crate::interpret::lsys::param::draw3_marks(sys, p, *depth, d, limits, &mut |m| {
                    got.mark(m, &mut paint, width, index)
                })?;
            } else {
                let mut keep = |s: Segment3| got.stem(s, width(s.order), None);
                draw3(sys, *depth, d, &scene.limits, &mut keep, &mut phase)?;
            }
        }
        What::Tree { bed, .. } if bed.description().is_3d() => {
            let n = bed.size().stems;
            if n > MAX_EDITOR_STEMS {
                return Err(too_many(n.to_string()));
            }
            let desc = bed.description();
            volumes = desc.layout.iter().flat_map(|l| l.solids.clone()).collect();
            axis = Some([desc.root.0, desc.root_z.unwrap_or(0.0)]);
            let d = scene.derivation;
            if crate::interpret::dress::dresses(desc) {
                dress_placed(
                    &mut got,
                    bed,
                    scene,
                    placed,
                    (style.stroke, width),
                    &mut phase,
                )?;
            } else if placed.is_empty() {
                let mut keep = |s: Segment3| got.stem(s, width(s.order), None);
                crate::interpret::bed3::draw3(bed, d, &scene.limits, &mut keep, &mut phase)?;
            }
        }
        _ => return Ok(None),
    }
    if got.over {
        return Err(too_many(format!("more than {MAX_EDITOR_STEMS}")));
    }
    let Pieces {
        mut stems,
        colors,
        stem_colors,
        leaves,
        ..
    } = got;
    for p in placed {
        let (a, b) = (p.from, p.to);
        let (w, k) = (p.width, p.decision as f64);
        stems.extend([a.x, a.y, p.z[0], b.x, b.y, p.z[1], w, k]);
    }
    let n = stems.len() as u64 / 8;
    let stems3 = Stems3 {
        stems,
        width_in_pixels: matches!(style.width, Width::Pixels(_)),
        background: style.background,
        volumes,
        axis,
        colors,
        stem_colors,
        leaves,
    };
    let rendered = Rendered {
        segments: n,
        count: Some(n.to_string()),
        warnings: nothing_drawn(n),
    };
    Ok(Some((stems3, rendered)))
}

/// A dressed tree's colours and leaves for the editor (section 13): its
/// stems as drawn from the BED when growth placed none, else each placed
/// stem in the colour of the drawn stem at the same place (to the answer's
/// three decimals; the ramp's first colour where none is).
fn dress_placed(
    got: &mut Pieces,
    bed: &crate::bed::Bed,
    scene: &Scene,
    placed: &[crate::grow::PlacedStem],
    (stroke, width): (crate::color::Rgb, impl Fn(u32) -> f64),
    progress: &mut dyn Progress,
) -> Result<(), Diagnostics> {
    use crate::interpret::dress;
    let segs = dress::gather(bed, scene.derivation, &scene.limits, progress)?;
    let dressed = dress::Dress::new(bed.description(), &segs, stroke);
    got.colors = dressed.palette().to_vec();
    let mut paint = 0;
    let mut drawn = Pieces::default();
    dressed.emit(&mut |m| drawn.mark(m, &mut paint, &width, |i| i as u32))?;
    got.over |= drawn.over;
    got.leaves = drawn.leaves;
    if placed.is_empty() {
        got.stems = drawn.stems;
        got.stem_colors = drawn.stem_colors;
        return Ok(());
    }
    let at = |v: &[f64]| -> [i64; 6] { std::array::from_fn(|i| libm::round(v[i] * 1000.0) as i64) };
    let by_place: std::collections::BTreeMap<[i64; 6], u32> = drawn
        .stems
        .chunks_exact(8)
        .zip(&drawn.stem_colors)
        .map(|(s, &c)| (at(s), c))
        .collect();
    got.stem_colors = placed
        .iter()
        .map(|p| {
            let v = [p.from.x, p.from.y, p.z[0], p.to.x, p.to.y, p.z[1]];
            by_place.get(&at(&v)).copied().unwrap_or(0)
        })
        .collect();
    Ok(())
}

/// What [`super::Request::mesh`] wrote.
#[derive(Debug, Clone, PartialEq)]
pub struct Meshed {
    /// Stems meshed.
    pub stems: u64,
    /// Triangles written.
    pub triangles: u64,
    /// Warnings (nothing drawn).
    pub warnings: Vec<Diagnostic>,
}

/// Writes the scene as a mesh: every stem a tube (a 2D input's lifted to
/// z = 0), its diameter the stem's width (an `.lsys`'s `width` is in
/// pixels in a picture; in a mesh it is a tenth of a step per pixel), its
/// colour the stroke's.
pub(crate) fn mesh(
    scene: &Scene,
    look: &super::Look,
    format: MeshFormat,
    opts: &MeshOptions,
    out: &mut dyn Write,
    progress: &mut dyn Progress,
) -> Result<Meshed, Diagnostics> {
    let style = style(scene, look);
    let color = style.stroke;
    let width = move |order: u32| match style.width {
        Width::Canvas(lin) => lin.at(order).max(0.0),
        Width::Pixels(w) => match &scene.what {
            What::Lsys { sys, .. } => w * sys.length / 10.0,
            What::Tree { .. } => w,
        },
    };
    let mut got = Gathered {
        tubes: Vec::new(),
        leaves: Vec::new(),
        over: false,
        most: opts.max_tubes(),
        width,
        paint: color,
    };
    let most = got.most;
    solid_usage(scene, format, opts)?;
    let mut phase = Phase::new(progress, "deriving");
    if let Some((sys, depth)) = lsys3(scene)
        && let Some(p) = sys.parametric.as_deref().filter(|p| p.paints())
    {
        // Colours and polygons (docs/lsys.md, *Colours, widths and
        // organs*): each stem in its palette colour, each polygon a leaf.
        check_stems(sys, depth, &scene.limits, most, |_| {
            mesh::mesh_too_large(most, true, opts)
        })?;
        let palette = &p.organs.palette;
        got.paint = palette.first().copied().unwrap_or(color);
        crate::interpret::lsys::param::draw3_marks(
            sys,
            p,
            depth,
            scene.derivation,
            &scene.limits,
            &mut |m| got.mark(m, |i| palette.get(i).copied().unwrap_or(color)),
        )?;
    } else if let Some((sys, depth)) = lsys3(scene) {
        check_stems(sys, depth, &scene.limits, most, |_| {
            mesh::mesh_too_large(most, true, opts)
        })?;
        draw3(
            sys,
            depth,
            scene.derivation,
            &scene.limits,
            &mut |s| got.step(s, color),
            &mut phase,
        )?;
    } else if let Some(bed) = scene
        .bed()
        .filter(|b| crate::interpret::dress::dresses(b.description()))
    {
        // Colours by order and leaves (section 13): each stem in its
        // colour, each leaf's polygon a double-sided face.
        let segs =
            crate::interpret::dress::gather(bed, scene.derivation, &scene.limits, &mut phase)?;
        let dress = crate::interpret::dress::Dress::new(bed.description(), &segs, color);
        let palette = dress.palette();
        dress.emit(&mut |m| got.mark(m, |i| palette[i]))?;
    } else {
        let mut keep = |s: Segment3| got.step(s, color);
        if !draw_tree3(scene, &mut keep, &mut phase)? {
            let mut lift = Lift(&mut keep);
            scene.draw(&mut lift, &mut phase)?;
        }
    }
    let Gathered {
        tubes,
        leaves,
        over,
        ..
    } = got;
    mesh::check_tubes(tubes.len() as u64, over, opts)?;
    let n = tubes.len() as u64;
    let triangles = if opts.solid {
        let paint = tubes.first().map_or(color, |t| t.color);
        solid(
            &tubes,
            &leaves,
            first_root(scene),
            opts,
            format,
            paint,
            out,
            progress,
        )?
    } else {
        let m = mesh::build_with_leaves(&tubes, &leaves, first_root(scene), opts);
        match format {
            MeshFormat::Glb => mesh::write_glb(&m, out)?,
            MeshFormat::Gltf => mesh::write_gltf(&m, out)?,
            MeshFormat::Obj | MeshFormat::Stl | MeshFormat::ThreeMf => mesh::write_obj(&m, out)?,
        }
        m.triangles()
    };
    Ok(Meshed {
        stems: n,
        triangles,
        warnings: nothing_drawn(n),
    })
}

/// The tubes and leaves of a mesh, gathered up to `most` pieces (`over`
/// once one more came), each stem `width(order)` wide.
struct Gathered<W: Fn(u32) -> f64> {
    tubes: Vec<Tube>,
    leaves: Vec<mesh::Leaf>,
    over: bool,
    most: u64,
    width: W,
    /// The colour in force for marks (a palette's or a ramp's).
    paint: crate::color::Rgb,
}

impl<W: Fn(u32) -> f64> Gathered<W> {
    /// A stem, a tube in `color`.
    fn step(&mut self, s: Segment3, color: crate::color::Rgb) {
        if self.tubes.len() as u64 >= self.most {
            self.over = true;
            return;
        }
        self.tubes.push(Tube {
            from: s.from,
            to: s.to,
            width: (self.width)(s.order),
            color,
        });
    }

    /// A mark of a painting turtle: a stem in the colour in force, a
    /// change of colour (`palette` of its index), a polygon a leaf.
    fn mark(&mut self, m: Mark, palette: impl Fn(usize) -> crate::color::Rgb) {
        match m {
            Mark::Step(s, _) => self.step(s, self.paint),
            Mark::Paint(i) => self.paint = palette(i),
            Mark::Polygon(points) => {
                if (self.tubes.len() + self.leaves.len()) as u64 >= self.most {
                    self.over = true;
                    return;
                }
                self.leaves.push(mesh::Leaf {
                    points: points.to_vec(),
                    color: self.paint,
                });
            }
        }
    }
}

/// Refuses `--solid` of a 2D input or into a format that cannot hold it
/// (a `.gltf`, an `.obj`), and an `.stl` or `.3mf` without `--solid`
/// (usage errors, before any work).
fn solid_usage(scene: &Scene, format: MeshFormat, opts: &MeshOptions) -> Result<(), Diagnostics> {
    let ext = format.extension();
    let message = match (opts.solid, format.takes_solid(), format.solid_only()) {
        (true, false, _) => format!("--solid writes one closed body as .stl, .3mf or .glb, not .{ext}"),
        (false, _, true) => {
            let a = if format == MeshFormat::Stl { "an" } else { "a" };
            format!("{a} .{ext} is written as one closed body: add --solid")
        }
        (true, true, _) if !is_3d(scene) => {
            "--solid needs a 3D input (a 3D .lsys, or an .od or .bed with a 3D layout); this one is 2D".into()
        }
        _ => return Ok(()),
    };
    Err(Diagnostic::error(RenderError::SolidUsage { message })
        .with_help("a solid for 3D printing: stlc render tree3d.od --solid -o tree.stl (or tree.3mf, tree.glb)")
        .into())
}

/// Unites the tubes into one body and writes it as `format` (STL, 3MF,
/// or a `.glb` of one primitive in `paint`); its triangles.
#[cfg(feature = "solid")]
#[allow(clippy::too_many_arguments)]
fn solid(
    tubes: &[Tube],
    leaves: &[mesh::Leaf],
    origin: Point3,
    opts: &MeshOptions,
    format: MeshFormat,
    paint: crate::color::Rgb,
    out: &mut dyn Write,
    progress: &mut dyn Progress,
) -> Result<u64, Diagnostics> {
    let body = mesh::build_solid(tubes, leaves, origin, opts, progress)?;
    match format {
        MeshFormat::ThreeMf => mesh::write_3mf(&body, out),
        MeshFormat::Glb => {
            let m = body.gltf_mesh(paint);
            mesh::write_glb(&m, out)?;
            Ok(m.triangles())
        }
        _ => {
            mesh::write_stl(&body, out)
                .map_err(|e| Diagnostics::from(crate::diag::io_error(&e, "writing the STL")))?;
            Ok(body.triangles.len() as u64)
        }
    }
}

#[cfg(not(feature = "solid"))]
#[allow(clippy::too_many_arguments)]
fn solid(
    _: &[Tube],
    _: &[mesh::Leaf],
    _: Point3,
    _: &MeshOptions,
    _: MeshFormat,
    _: crate::color::Rgb,
    _: &mut dyn Write,
    _: &mut dyn Progress,
) -> Result<u64, Diagnostics> {
    Err(Diagnostic::error(RenderError::SolidUsage {
        message: "this build of stlc has no --solid (the `solid` feature)".into(),
    })
    .into())
}

/// Where a mesh's origin is, in canvas units: a tree's first root (its
/// base stands on the files' origin, section 11), an `.lsys`'s turtle
/// start (the canvas origin).
fn first_root(scene: &Scene) -> Point3 {
    match &scene.what {
        What::Tree { bed, .. } => {
            let d = bed.description();
            Point3::new(d.root.0, d.root.1, d.root_z.unwrap_or(0.0))
        }
        What::Lsys { .. } => Point3::default(),
    }
}

/// A 2D turtle backend that lifts every segment to z = 0.
struct Lift<'a>(&'a mut dyn FnMut(Segment3));

impl Turtle for Lift<'_> {
    fn segment(&mut self, s: Segment) {
        (self.0)(Segment3 {
            from: Point3::new(s.from.x, s.from.y, 0.0),
            to: Point3::new(s.to.x, s.to.y, 0.0),
            order: s.order,
        });
    }
}
