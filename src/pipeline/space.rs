//! Three dimensions in the pipeline (docs/3d.md): a 3D `.lsys`'s pictures
//! are views (`--view AZ,EL`), any input's mesh (`.glb`, `.gltf`, `.obj`),
//! (`stats` of 3D inputs is `stats3.rs`).

use std::io::Write;

use super::{Rendered, Scene, What, style};
use crate::diag::{Diagnostic, Diagnostics, RenderError};
use crate::interpret::Derivation;
use crate::interpret::lsys::space::draw3;
use crate::interpret::lsys::{Mark3, ReachMemo};
use crate::interpret::stats::stats_with_budget;
use crate::limits::Limits;
use crate::model::lsys::LSystem;
use crate::num::{Trim, fixed};
use crate::progress::{Phase, Progress};
use crate::render::mesh::{self, MeshFormat, MeshOptions, Tube};
use crate::render::view::{Bush, Gathered, MAX_VIEW_SEGMENTS, View, draw_sorted, view_too_large};
use crate::render::{Frame, LOD_PX, RenderOptions, Width, render_framed};
use crate::turtle::space::{Point3, Segment3};
use crate::turtle::{BBox, Segment, Turtle};

/// The 3D `.lsys` of a scene, and its depth, if it is one.
pub(crate) fn space_lsys(scene: &Scene) -> Option<(&LSystem, u32)> {
    match &scene.what {
        What::Lsys { sys, depth } if sys.is_3d() => Some((sys, *depth)),
        _ => None,
    }
}

/// Refuses, before deriving, a deterministic 3D system with more stems
/// than `most` (`over` makes the refusal).
fn check_stems(
    sys: &LSystem,
    depth: u32,
    limits: &Limits,
    most: u64,
    over: impl Fn(String) -> Diagnostics,
) -> Result<(), Diagnostics> {
    if let Some(p) = &sys.parametric {
        // Counted by deriving, stopped as soon as it passes `most`.
        let n = crate::interpret::lsys::param::count_steps(sys, p, depth, limits, most)?;
        if n > most {
            return Err(over(format!("more than {most}")));
        }
        return Ok(());
    }
    if sys.is_stochastic() {
        let fewest = crate::interpret::lsys::Stochastic::new(sys)
            .segment_bounds(depth)
            .0;
        if fewest > most {
            return Err(over(format!("at least {fewest}")));
        }
        return Ok(());
    }
    let stems = stats_with_budget(sys, depth, limits, 0)?.segments;
    if stems > most.into() {
        return Err(over(stems.to_string()));
    }
    Ok(())
}

/// Draws a 3D `.lsys` seen from `view` as the PNG or SVG `opts` asks: its
/// stems projected, drawn far to near, fitted as a 2D drawing is. At a
/// level of detail (the default, `dfs`, a deterministic system the reach
/// memo takes) parts under half a pixel are stand-ins
/// ([`render_view_lod`]); otherwise every stem is drawn.
pub(crate) fn render_view(
    scene: &Scene,
    view: View,
    look: &super::Look,
    opts: &RenderOptions,
    out: &mut dyn Write,
    progress: &mut dyn Progress,
) -> Result<Rendered, Diagnostics> {
    let (sys, depth) = space_lsys(scene).expect("render_view is called for a 3D .lsys");
    if !opts.exact
        && scene.derivation == Derivation::Dfs
        && let Ok(memo) = ReachMemo::new(sys, depth, sys.length)
        && let Some(r) = render_view_lod(scene, &memo, view, look, opts, out, progress)?
    {
        return Ok(r);
    }
    check_stems(sys, depth, &scene.limits, MAX_VIEW_SEGMENTS, view_too_large)?;
    let mut gathered = Gathered::new(view);
    draw3(
        sys,
        depth,
        scene.derivation,
        &scene.limits,
        &mut |s| gathered.push(s),
        &mut Phase::new(progress, "deriving"),
    )?;
    if gathered.over {
        return Err(view_too_large(format!("more than {MAX_VIEW_SEGMENTS}")));
    }
    let stems = gathered.sorted();
    let n = stems.len() as u64;
    draw_view(scene, look, opts, &stems, &[], out, progress)?;
    Ok(Rendered {
        segments: n,
        count: Some(n.to_string()),
        warnings: nothing_drawn(n),
    })
}

/// Most symbols and stand-ins a 3D view's walk visits (about half a second).
pub const VIEW_VISITS: u64 = 10_000_000;

/// Most stems and stand-ins a 3D view at a level of detail holds and sorts
/// (48 bytes each: about 50 MB).
pub const VIEW_MARKS: u64 = 1_000_000;

/// The walk draws a view only when it visits at most this percentage of
/// the word (else the compiled exact path does), 2D's threshold.
const LOD_MAX_VISITS_PERCENT: u128 = 35;

/// Most visits of the first walk, which measures the view.
const MEASURE_VISITS: u64 = 200_000;

/// A 3D view at a level of detail (docs/3d.md): the view's box measured
/// by a coarse walk (every part cut there lies within its reach of its
/// start), the detail half a pixel of the fit from that box, raised by
/// quarter-octaves while the walk would visit more than [`VIEW_VISITS`] or
/// hand out more than [`VIEW_MARKS`] (a warning says so), then the walk
/// gathered and drawn far to near. `None`: at half a pixel the walk fits
/// its budgets but would visit more than 35 % of a word the exact path may
/// draw, which then draws it.
fn render_view_lod(
    scene: &Scene,
    memo: &ReachMemo,
    view: View,
    look: &super::Look,
    opts: &RenderOptions,
    out: &mut dyn Write,
    progress: &mut dyn Progress,
) -> Result<Option<Rendered>, Diagnostics> {
    let (sys, _) = space_lsys(scene).expect("a 3D .lsys");
    let style = style(scene, look);
    let reach = memo.whole().radius;
    // The coarse walk: the smallest detail, halving from the whole, whose
    // walk visits at most MEASURE_VISITS.
    let mut coarse = 4.0 * reach;
    for _ in 0..64 {
        let half = coarse / 2.0;
        if memo.plan(half).visits > MEASURE_VISITS || half == 0.0 {
            break;
        }
        coarse = half;
    }
    let projection = view.projection();
    let mut bbox: Option<BBox> = None;
    let mut add = |p: Point3| {
        let (q, _) = projection.project(p);
        match &mut bbox {
            Some(b) => b.add(q),
            None => bbox = Some(BBox::at(q)),
        }
    };
    let plan = memo.plan(coarse);
    memo.draw_lod(
        sys.heading,
        sys.angle,
        coarse,
        plan.visits,
        &mut |m| match m {
            Mark3::Stem(s) | Mark3::StandIn { seg: s, .. } => {
                add(s.from);
                add(s.to);
            }
        },
        &mut Phase::new(progress, "measuring"),
    );
    let bbox = bbox.map(|b| BBox {
        min_x: b.min_x - coarse,
        min_y: b.min_y - coarse,
        max_x: b.max_x + coarse,
        max_y: b.max_y + coarse,
    });
    let scale = crate::render::Fit::content(bbox, 0, &style.width, opts.size)?.scale;
    let ideal = LOD_PX / scale;
    let mut detail = ideal;
    let mut plan = memo.plan(detail);
    // Little cut at half a pixel, and within the walk's budgets: the
    // compiled exact path costs about what the walk would (as in 2D,
    // docs/rendering.md), and draws the exact picture.
    let whole = memo.whole();
    if plan.visits <= VIEW_VISITS
        && plan.marks <= VIEW_MARKS
        && u128::from(plan.visits) * 100 > u128::from(whole.syms) * LOD_MAX_VISITS_PERCENT
        && whole.syms <= scene.limits.max_symbols
        && whole.stems <= MAX_VIEW_SEGMENTS
    {
        return Ok(None);
    }
    for _ in 0..400 {
        if plan.visits <= VIEW_VISITS && plan.marks <= VIEW_MARKS {
            break;
        }
        detail *= libm::pow(2.0, 0.25);
        plan = memo.plan(detail);
    }
    if plan.visits > VIEW_VISITS || plan.marks > VIEW_MARKS {
        return Err(view_too_large(plan.marks.to_string()));
    }
    let mut gathered = Gathered::new(view);
    memo.draw_lod(
        sys.heading,
        sys.angle,
        detail,
        plan.visits,
        &mut |m| match m {
            Mark3::Stem(s) => gathered.push(s),
            Mark3::StandIn {
                seg,
                spread,
                length,
                runs,
                ..
            } => gathered.push_stand_in(seg, spread, length, runs),
        },
        &mut Phase::new(progress, "deriving"),
    );
    let (stems, bushes) = gathered.sorted_with_bushes();
    let n = stems.len() as u64;
    draw_view(scene, look, opts, &stems, &bushes, out, progress)?;
    let mut warnings = nothing_drawn(n);
    if detail > ideal {
        warnings.push(
            Diagnostic::warning(RenderError::CoarseView {
                px: fixed(detail * scale, 2, Trim::Keep),
            })
            .with_help(format!(
                "a 3D view visits at most {VIEW_VISITS} symbols and holds at most {VIEW_MARKS} stems: \
                 a smaller --depth or --size draws finer"
            )),
        );
    }
    Ok(Some(Rendered {
        segments: n,
        count: Some(n.to_string()),
        warnings,
    }))
}

/// Draws gathered stems (far to near) with the scene's style, fitted.
fn draw_view(
    scene: &Scene,
    look: &super::Look,
    opts: &RenderOptions,
    stems: &[Segment],
    bushes: &[Bush],
    out: &mut dyn Write,
    progress: &mut dyn Progress,
) -> Result<(), Diagnostics> {
    let mut drawing = |t: &mut dyn Turtle, _: &mut dyn Progress| {
        draw_sorted(stems, bushes, t);
        Ok(())
    };
    let exact = RenderOptions {
        exact: true,
        ..*opts
    };
    let style = style(scene, look);
    render_framed(&mut drawing, Frame::Fit, &[], &style, &exact, out, progress)?;
    Ok(())
}

fn nothing_drawn(n: u64) -> Vec<Diagnostic> {
    if n > 0 {
        return Vec::new();
    }
    vec![
        Diagnostic::warning(RenderError::NothingDrawn)
            .with_help("check the axiom or seed and the depth: only `F` draws"),
    ]
}

/// Most stems the editor's 3D view takes: its page holds each in 32 bytes
/// of a WebGL buffer (a 2D answer's SVG has its own limit).
pub const MAX_EDITOR_STEMS: u64 = 1_000_000;

/// A 3D input for an editor that draws it itself (its own WebGL view):
/// [`super::Request::render`] with `trace` and `tree_up_to` gives this in
/// [`super::Drawn::space`] instead of drawing a picture.
#[derive(Debug, Clone, PartialEq)]
pub struct Space {
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
}

/// The scene's stems in 3D for an editor ([`Space`]), with what a picture
/// would have counted; `None` for a flat input. A grown tree's stems are
/// `placed`, its growth's, in growth order with their decisions.
pub(crate) fn editor_space(
    scene: &Scene,
    look: &super::Look,
    placed: &[crate::grow::PlacedStem],
    progress: &mut dyn Progress,
) -> Result<Option<(Space, Rendered)>, Diagnostics> {
    let too_many = |n: String| -> Diagnostics {
        Diagnostic::error(RenderError::ViewTooLarge {
            segments: n,
            limit: MAX_EDITOR_STEMS,
        })
        .with_help("the editor's 3D view holds every stem: use a smaller depth, or `stlc render --view AZ,EL`")
        .into()
    };
    let style = style(scene, look);
    let mut stems = Vec::new();
    let mut over = false;
    let mut keep = |s: Segment3| {
        if stems.len() as u64 >= 8 * MAX_EDITOR_STEMS {
            over = true;
            return;
        }
        let w = match style.width {
            Width::Pixels(w) => w,
            Width::Canvas(lin) => lin.at(s.order).max(0.0),
        };
        let (a, b) = (s.from, s.to);
        stems.extend([a.x, a.y, a.z, b.x, b.y, b.z, w, 0.0]);
    };
    let mut phase = Phase::new(progress, "deriving");
    let (mut volumes, mut axis) = (Vec::new(), None);
    match &scene.what {
        What::Lsys { sys, depth } if sys.is_3d() => {
            check_stems(sys, *depth, &scene.limits, MAX_EDITOR_STEMS, too_many)?;
            let d = scene.derivation;
            draw3(sys, *depth, d, &scene.limits, &mut keep, &mut phase)?;
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
            if placed.is_empty() {
                crate::interpret::bed3::draw3(bed, d, &scene.limits, &mut keep, &mut phase)?;
            }
        }
        _ => return Ok(None),
    }
    if over {
        return Err(too_many(format!("more than {MAX_EDITOR_STEMS}")));
    }
    for p in placed {
        let (a, b) = (p.from, p.to);
        let (w, k) = (p.width, p.decision as f64);
        stems.extend([a.x, a.y, p.z[0], b.x, b.y, p.z[1], w, k]);
    }
    let n = stems.len() as u64 / 8;
    let space = Space {
        stems,
        width_in_pixels: matches!(style.width, Width::Pixels(_)),
        background: style.background,
        volumes,
        axis,
    };
    let rendered = Rendered {
        segments: n,
        count: Some(n.to_string()),
        warnings: nothing_drawn(n),
    };
    Ok(Some((space, rendered)))
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
    let most = opts.max_tubes();
    let mut tubes: Vec<Tube> = Vec::new();
    let mut over = false;
    let mut keep = |s: Segment3| {
        if tubes.len() as u64 >= most {
            over = true;
            return;
        }
        tubes.push(Tube {
            from: s.from,
            to: s.to,
            width: width(s.order),
            color,
        });
    };
    let mut phase = Phase::new(progress, "deriving");
    if let Some((sys, depth)) = space_lsys(scene) {
        check_stems(sys, depth, &scene.limits, most, |_| {
            mesh::mesh_too_large(most, true, opts)
        })?;
        draw3(
            sys,
            depth,
            scene.derivation,
            &scene.limits,
            &mut keep,
            &mut phase,
        )?;
    } else if !super::tree3::draw_tree3(scene, &mut keep, &mut phase)? {
        let mut lift = Lift(&mut keep);
        scene.draw(&mut lift, &mut phase)?;
    }
    mesh::check_tubes(tubes.len() as u64, over, opts)?;
    let m = mesh::build(&tubes, opts);
    match format {
        MeshFormat::Glb => mesh::write_glb(&m, out)?,
        MeshFormat::Gltf => mesh::write_gltf(&m, out)?,
        MeshFormat::Obj => mesh::write_obj(&m, out)?,
    }
    let n = tubes.len() as u64;
    Ok(Meshed {
        stems: n,
        triangles: m.triangles(),
        warnings: nothing_drawn(n),
    })
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
