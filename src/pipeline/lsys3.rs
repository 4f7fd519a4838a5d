//! A 3D `.lsys` in the pipeline (docs/3d.md): its pictures are views
//! (`--view AZ,EL`), exact or at a level of detail. A 3D tree's are in
//! `tree3.rs`; which of the two a scene is, the editor's 3D stems and any
//! input's mesh, in `view3.rs`; `stats` of 3D inputs in `stats3.rs`.

use std::io::Write;

use super::{Rendered, Scene, What, style};
use crate::diag::{Diagnostic, Diagnostics, Help, Knob, RenderError};
use crate::interpret::Derivation;
use crate::interpret::lsys::lsys3::draw3;
use crate::interpret::lsys::param::ViewMemo;
use crate::interpret::lsys::{Mark3, ReachMemo, ViewLod};
use crate::interpret::stats::stats_with_budget;
use crate::limits::Limits;
use crate::model::lsys::LSystem;
use crate::num::{Trim, fixed};
use crate::progress::{Phase, Progress};
use crate::render::view::{
    Bush, Gathered, MAX_VIEW_SEGMENTS, Sorted, View, draw_sorted, view_too_large,
};
use crate::render::{Frame, LOD_PX, RenderOptions, render_framed};
use crate::turtle::turtle3::Point3;
use crate::turtle::{BBox, Segment, Turtle};

/// The 3D `.lsys` of a scene, and its depth, if it is one.
pub(crate) fn lsys3(scene: &Scene) -> Option<(&LSystem, u32)> {
    match &scene.what {
        What::Lsys { sys, depth } if sys.is_3d() => Some((sys, *depth)),
        _ => None,
    }
}

/// Refuses, before deriving, a deterministic 3D system with more stems
/// than `most` (`over` makes the refusal).
pub(super) fn check_stems(
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
    let (sys, depth) = lsys3(scene).expect("render_view is called for a 3D .lsys");
    if !opts.exact && scene.derivation == Derivation::Dfs {
        let memo: Option<Box<dyn ViewLod>> = match sys.parametric.as_deref() {
            None => ReachMemo::new(sys, depth, sys.length)
                .ok()
                .map(|m| Box::new(m) as Box<dyn ViewLod>),
            Some(p) => ViewMemo::new(sys, p, depth)?
                .filter(|m| !p.paints() || m.size().0 > PAINTED_EXACT_SYMBOLS)
                .map(|m| Box::new(m) as Box<dyn ViewLod>),
        };
        let palette = sys
            .parametric
            .as_deref()
            .filter(|p| p.paints())
            .map(|p| p.organs.palette.clone());
        if let Some(memo) = memo
            && let Some(r) =
                render_view_lod(scene, &*memo, palette, view, look, opts, out, progress)?
        {
            return Ok(r);
        }
    }
    check_stems(sys, depth, &scene.limits, MAX_VIEW_SEGMENTS, view_too_large)?;
    if let Some(p) = sys.parametric.as_deref().filter(|p| p.paints()) {
        return render_view_organs(scene, sys, p, view, look, opts, out, progress);
    }
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

/// [`render_view`] of a system with colours or organs: every stem and
/// polygon in its colour, sorted far to near.
#[allow(clippy::too_many_arguments)]
fn render_view_organs(
    scene: &Scene,
    sys: &LSystem,
    p: &crate::model::param::Parametric,
    view: View,
    look: &super::Look,
    opts: &RenderOptions,
    out: &mut dyn Write,
    progress: &mut dyn Progress,
) -> Result<Rendered, Diagnostics> {
    use crate::interpret::lsys::param::{Mark, draw3_marks};
    let mut gathered = Gathered::with_organs(view, p.organs.palette.clone());
    let depth = match &scene.what {
        What::Lsys { depth, .. } => *depth,
        What::Tree { .. } => 0,
    };
    progress.start("modules", 0);
    draw3_marks(
        sys,
        p,
        depth,
        scene.derivation,
        &scene.limits,
        &mut |m| match m {
            Mark::Step(s, _) => gathered.push(s),
            Mark::Paint(i) => gathered.paint(i),
            Mark::Polygon(points) => gathered.push_polygon(points),
        },
    )?;
    progress.finish();
    if gathered.over {
        return Err(view_too_large(format!("more than {MAX_VIEW_SEGMENTS}")));
    }
    let sorted = gathered.sorted_organs();
    let n = sorted.stems();
    draw_organs(scene, look, opts, &sorted, out, progress)?;
    Ok(Rendered {
        segments: n,
        count: Some(n.to_string()),
        warnings: Vec::new(),
    })
}

/// A system that paints is drawn exactly while its word has at most this
/// many modules (about 7 s), with stand-ins past that: a stand-in's
/// colour is its ink's mean, where the exact drawing shows the nearest of
/// the strokes piled up in a pixel (docs/3d.md, *Level of detail*).
pub const PAINTED_EXACT_SYMBOLS: u64 = 4 * VIEW_VISITS;

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
#[allow(clippy::too_many_arguments)]
fn render_view_lod(
    scene: &Scene,
    memo: &dyn ViewLod,
    palette: Option<Vec<crate::color::Rgb>>,
    view: View,
    look: &super::Look,
    opts: &RenderOptions,
    out: &mut dyn Write,
    progress: &mut dyn Progress,
) -> Result<Option<Rendered>, Diagnostics> {
    let (sys, _) = lsys3(scene).expect("a 3D .lsys");
    let style = style(scene, look);
    let reach = memo.radius();
    if !reach.is_finite() {
        // Lengths past f64's range (`S -> SFS` at depth 1024): no fit.
        return Err(Diagnostic::error(RenderError::DrawingNotFinite)
            .with_help("the drawing's size overflows at this depth: use a smaller depth")
            .into());
    }
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
    if plan.visits > VIEW_VISITS {
        return Err(view_too_large(format!("more than {MAX_VIEW_SEGMENTS}")));
    }
    memo.walk(
        sys,
        coarse,
        plan.visits,
        (0.0, 1.0),
        projection.forward(),
        &mut |m| match m {
            Mark3::Stem(s) | Mark3::StandIn { seg: s, .. } => {
                add(s.from);
                add(s.to);
            }
            Mark3::Polygon(points) => points.iter().for_each(|&p| add(p)),
            Mark3::Paint(_) => {}
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
    let (syms, stems) = memo.size();
    if plan.visits <= VIEW_VISITS
        && plan.marks <= VIEW_MARKS
        && u128::from(plan.visits) * 100 > u128::from(syms) * LOD_MAX_VISITS_PERCENT
        && syms <= scene.limits.max_symbols
        && stems <= MAX_VIEW_SEGMENTS
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
    let painted = palette.is_some();
    let mut gathered = match palette {
        Some(p) => Gathered::with_organs(view, p),
        None => Gathered::new(view),
    };
    let stroke = crate::render::stroke_px(&style.width, scale, 0) / scale;
    memo.walk(
        sys,
        detail,
        plan.visits,
        (stroke, scale),
        projection.forward(),
        &mut |m| match m {
            Mark3::Stem(s) => gathered.push(s),
            Mark3::StandIn {
                seg,
                spread,
                length,
                runs,
                color,
                order,
                ..
            } => gathered.push_stand_in(
                seg,
                Bush {
                    spread,
                    length,
                    runs,
                    color,
                    order,
                },
            ),
            Mark3::Paint(i) => gathered.paint(i),
            Mark3::Polygon(points) => gathered.push_polygon(points),
        },
        &mut Phase::new(progress, "deriving"),
    );
    let n = if painted {
        let sorted = gathered.sorted_organs();
        let n = sorted.stems();
        draw_organs(scene, look, opts, &sorted, out, progress)?;
        n
    } else {
        let (stems, bushes) = gathered.sorted_with_bushes();
        let n = stems.len() as u64;
        draw_view(scene, look, opts, &stems, &bushes, out, progress)?;
        n
    };
    let mut warnings = nothing_drawn(n);
    if detail > ideal {
        warnings.push(
            Diagnostic::warning(RenderError::CoarseView {
                px: fixed(detail * scale, 2, Trim::Keep),
            })
            .with_help(
                Help::from(format!(
                    "a 3D view visits at most {VIEW_VISITS} symbols and holds at most \
                     {VIEW_MARKS} stems: a lower "
                )) + Help::knob(Knob::Depth, "")
                    + " or "
                    + Help::knob(Knob::Size, "")
                    + " draws finer",
            ),
        );
    }
    Ok(Some(Rendered {
        segments: n,
        count: Some(n.to_string()),
        warnings,
    }))
}

/// Draws gathered stems and polygons (far to near), each in its colour,
/// with the scene's style, fitted.
fn draw_organs(
    scene: &Scene,
    look: &super::Look,
    opts: &RenderOptions,
    sorted: &Sorted,
    out: &mut dyn Write,
    progress: &mut dyn Progress,
) -> Result<(), Diagnostics> {
    draw_fitted(scene, look, opts, &mut |t| sorted.draw(t), out, progress)
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
    draw_fitted(
        scene,
        look,
        opts,
        &mut |t| draw_sorted(stems, bushes, t),
        out,
        progress,
    )
}

/// What `draw` draws, as it comes (the view sorted it), with the scene's
/// style, fitted.
fn draw_fitted(
    scene: &Scene,
    look: &super::Look,
    opts: &RenderOptions,
    draw: &mut dyn FnMut(&mut dyn Turtle),
    out: &mut dyn Write,
    progress: &mut dyn Progress,
) -> Result<(), Diagnostics> {
    let mut drawing = |t: &mut dyn Turtle, _: &mut dyn Progress| {
        draw(t);
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

pub(super) fn nothing_drawn(n: u64) -> Vec<Diagnostic> {
    if n > 0 {
        return Vec::new();
    }
    vec![
        Diagnostic::warning(RenderError::NothingDrawn)
            .with_help("check the axiom or seed and the depth: only `F` draws"),
    ]
}
