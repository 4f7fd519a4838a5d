//! Drawing a scene: its style (the input's own colours and widths, or the
//! front end's), its layout view, PNG or SVG; and the rules front ends
//! share about image formats and options that do not apply.

use std::io::Write;
use std::path::Path;

use super::{Loaded, Scene, What};
use crate::color::Rgb;
use crate::diag::{Diagnostic, Diagnostics, ErrorKind, RenderError};
use crate::interpret::lsys;
use crate::model::lsys::Background;
use crate::progress::Phase;
use crate::progress::Progress;
use crate::render::{Fit, LOD_PX};
use crate::render::{Frame, ImageFormat, RenderOptions, Style, Width};
use crate::turtle::{BBox, Bounds, Fill, Turtle};

/// How a picture looks: the options of [`render`] beyond size and format.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct Look {
    /// Stroke colour; `None`: the input's own (an L-system's `color`, a
    /// description's `S=`), else [`TREE_BROWN`] for trees and black for
    /// L-systems.
    pub stroke: Option<Rgb>,
    /// Canvas colour; `None`: the input's own (an L-system's
    /// `background`, a description's `G=`), else white. `Some(None)` is
    /// transparent.
    pub background: Option<Option<Rgb>>,
    /// Whether to paint the layout's shapes under a tree.
    pub show_layout: ShowLayout,
}

/// Whether a picture shows the layout's shapes under the tree.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum ShowLayout {
    /// The tree alone (the default).
    #[default]
    No,
    /// Asked for (`--show-layout`): an input with no LAYOUT to show gets
    /// a warning.
    Yes,
    /// Wherever there is one, without a word where there is none (an
    /// editor, which shows every input's layout).
    IfAny,
}

/// The default stroke of STL trees: a dark bark brown.
pub const TREE_BROWN: Rgb = Rgb::new(0x4a, 0x2c, 0x12);

/// The style a scene is drawn with: the input's own colours and widths,
/// overridden by `look`.
pub fn style(scene: &Scene, look: &Look) -> Style {
    match &scene.what {
        What::Lsys { sys, .. } => Style {
            stroke: look.stroke.or(sys.color).unwrap_or(Rgb::BLACK),
            background: look.background.unwrap_or(match sys.background {
                Background::White => Some(Rgb::WHITE),
                Background::None => None,
                Background::Color(c) => Some(c),
            }),
            // A parametric system's `!(w)`: each segment's width in
            // canvas units, carried by its order (docs/lsys.md).
            width: match &sys.parametric {
                Some(p) if p.sets_width() => Width::Canvas(crate::num::Linear::new(
                    0.0,
                    -crate::model::param::WIDTH_QUANTUM,
                )),
                _ => Width::Pixels(sys.width),
            },
        },
        What::Tree { bed, .. } => {
            let p = &bed.description().params;
            Style {
                stroke: look
                    .stroke
                    .or(p.stroke.as_ref().and_then(|c| c.rgb))
                    .unwrap_or(TREE_BROWN),
                background: look
                    .background
                    .unwrap_or(p.background.as_ref().map_or(Some(Rgb::WHITE), |c| c.rgb)),
                width: Width::Canvas(p.width),
            }
        }
    }
}

/// The canvas area a tree's layout defines, and its shapes as fills if
/// `show`. The area is the shapes' bounds with a margin around them: half
/// the widest stem (so a stem at the layout's edge is not cut by the
/// image's edge) plus [`crate::render::MARGIN_FRACTION`] of the longest
/// side, the margin a fitted picture gets. An L-system or a tree without a
/// layout is fitted to its drawing instead.
pub(crate) fn layout_view(scene: &Scene, show: bool) -> (Option<BBox>, Vec<Fill>) {
    let Some(bed) = scene.bed() else {
        return (None, Vec::new());
    };
    let desc = bed.description();
    let Some(layout) = desc.layout.as_ref() else {
        return (None, Vec::new());
    };
    let fills = if show {
        crate::rings::fills(layout)
    } else {
        Vec::new()
    };
    let view = crate::rings::layout_bbox(layout)
        .map(|b| crate::render::layout_frame(b, desc.params.width.base));
    (view, fills)
}

/// What [`render`] drew.
#[derive(Debug, Clone, PartialEq)]
pub struct Rendered {
    /// Segments drawn, saturating at `u64::MAX` (see [`Rendered::count`]).
    pub segments: u64,
    /// Segments drawn, in decimal digits: exact at any depth (an
    /// L-system's count past `u64` comes from its exact statistics).
    /// `None` only where no exact count is known (a BED whose measure
    /// saturated): at least `u64::MAX` then, never to be shown as a count.
    pub count: Option<String>,
    /// Warnings (nothing drawn, ...).
    pub warnings: Vec<Diagnostic>,
}

/// Draws `scene` as a PNG or SVG into `out`, with its style and layout
/// view (see [`style`]; the view is the layout's bounds with a margin); a
/// 3D `.lsys` from the default view (docs/3d.md). A picture with no stem in it
/// is written all the same, with a warning.
pub fn render(
    scene: &Scene,
    look: &Look,
    opts: &RenderOptions,
    out: &mut dyn Write,
    progress: &mut dyn Progress,
) -> Result<Rendered, Diagnostics> {
    // A 3D .lsys is drawn as a view ([`Request`]'s `view`; here the
    // default one).
    if super::view3::is_3d(scene) {
        let view = crate::render::view::View::DEFAULT;
        return super::view3::render_view(scene, view, look, opts, out, progress);
    }
    render_tree(scene, look, opts, true, out, progress)
}

/// [`render`], with a tree's stems left out of the picture unless `tree`
/// (its background and layout underlay are drawn, and counted as ever):
/// for an editor that draws a big traced tree itself.
pub(crate) fn render_tree(
    scene: &Scene,
    look: &Look,
    opts: &RenderOptions,
    tree: bool,
    out: &mut dyn Write,
    progress: &mut dyn Progress,
) -> Result<Rendered, Diagnostics> {
    let style = style(scene, look);
    let (view, underlay) = layout_view(scene, look.show_layout != ShowLayout::No);
    // At a level of detail, an L-system's memoized geometry (when it
    // applies) is built once and serves the whole render: fitting (no
    // bounding pass), an SVG's count and the drawing; a stochastic one's
    // expected geometry likewise (its fit: see `chance_frame`).
    let lod = match &scene.what {
        What::Lsys { sys, depth }
            if !opts.exact && scene.derivation == crate::interpret::Derivation::Dfs =>
        {
            scene.limits.check_depth(*depth)?;
            if let Some(p) = lsys::param::of(sys) {
                lsys::param::ParamMemo::new(sys, p, *depth)?.map(Lod::Param)
            } else if sys.is_stochastic() {
                lsys::Chance::new(sys, *depth).ok().map(Lod::Chance)
            } else {
                lsys::Memo::new(sys, *depth).ok().map(Lod::Memo)
            }
            .map(|m| (m, sys, *depth))
        }
        _ => None,
    };
    // A stochastic system's `--exact` SVG (a command a segment) that even
    // its fewest segments would overflow is refused before any derivation
    // (its count is otherwise known only by deriving the word). Without
    // --exact the SVG is merged, and its commands are counted as written.
    if let What::Lsys { sys, depth } = &scene.what
        && sys.is_stochastic()
        && opts.format == ImageFormat::Svg
        && opts.exact
        && lsys::Stochastic::new(sys).segment_bounds(*depth).0 > opts.max_svg_segments
    {
        return Err(crate::render::svg_too_large(None, opts.max_svg_segments));
    }
    let (frame, fixed) = match (view, &lod) {
        (Some(view), _) => {
            let segments = scene.bed().map(|bed| bed.size().stems);
            (Frame::View { view, segments }, None)
        }
        (None, Some((Lod::Memo(m), _, _))) => {
            let m = m.measured();
            let known = Frame::Known {
                bbox: m.bbox,
                segments: m.segments,
            };
            (known, None)
        }
        (None, Some((Lod::Chance(c), _, _))) => chance_frame(scene, c, &style, opts, progress)?,
        (None, Some((Lod::Param(m), sys, _))) => {
            param_frame(scene, m, sys, &style, opts, progress)?
        }
        (None, None) => (Frame::Fit, None),
    };
    let mut drawing = |t: &mut dyn Turtle, p: &mut dyn Progress| match &lod {
        Some((Lod::Memo(m), sys, depth)) => lsys::draw_with(m, sys, *depth, &scene.limits, t, p),
        Some((Lod::Chance(c), _, _)) => match fixed.or(t.detail()) {
            Some(detail) => lsys::draw_chance(c, detail, &scene.limits, t, p).map(|_| ()),
            None => scene.draw(t, p),
        },
        Some((Lod::Param(m), sys, _)) => match (fixed.or(t.detail()), lsys::param::of(sys)) {
            (Some(detail), Some(par)) if fixed.is_some() || m.walk_pays(detail) => {
                m.draw(sys, par, detail, &scene.limits, t, p).map(|_| ())
            }
            _ => scene.draw(t, p),
        },
        None if !tree => Ok(()),
        None => scene.draw(t, p),
    };
    // A deterministic L-system at a level of detail is painted on one
    // thread: its walk then skips subtrees whose reach is already full
    // ink (docs/rendering.md, *Full ink*), which the band threads' raster
    // would hide from it. Its pixels are the same either way.
    let mut opts = *opts;
    if matches!(lod, Some((Lod::Memo(_), _, _))) {
        opts.threads = 1;
    }
    let counted =
        crate::render::render_framed(&mut drawing, frame, &underlay, &style, &opts, out, progress)?;
    // A tree's stems are known from its measure; an L-system's were counted
    // by the bounding pass (it has no layout view, so one always runs).
    let segments = match &scene.what {
        What::Tree { bed, .. } => bed.size().stems,
        What::Lsys { .. } => counted.unwrap_or(0),
    };
    let count = match &scene.what {
        _ if segments < u64::MAX => Some(segments.to_string()),
        // Saturated: an L-system's exact count is its statistics' (big
        // integers, memoized per symbol and depth); a stochastic one's word
        // was walked, so its count never saturates.
        What::Lsys { sys, depth } if !sys.is_stochastic() => {
            crate::interpret::stats::stats(sys, *depth, &scene.limits)
                .ok()
                .map(|s| s.segments.to_string())
        }
        _ => None,
    };
    let mut warnings = Vec::new();
    // Polygons and surfaces draw without a segment (not counted).
    let organs = match &scene.what {
        What::Lsys { sys, .. } => sys.parametric.as_ref().is_some_and(|p| p.paints()),
        What::Tree { .. } => false,
    };
    if segments == 0 && !organs {
        warnings.push(Diagnostic::warning(RenderError::NothingDrawn).with_help(
            "check the axiom or seed and the depth: only `F` draws (and in an .od, a rule that grows)",
        ));
    }
    Ok(Rendered {
        segments,
        count,
        warnings,
    })
}

/// The memo an L-system is drawn with at a level of detail.
enum Lod {
    /// A deterministic system's memoized geometry.
    Memo(lsys::Memo),
    /// A stochastic system's expected geometry.
    Chance(lsys::Chance),
    /// A parametric system's repeated pieces.
    Param(lsys::param::ParamMemo),
}

/// The frame of a parametric system at a level of detail, as a
/// stochastic one's ([`fitted_frame`]): the first fit is to the ball that
/// holds the drawing.
fn param_frame(
    scene: &Scene,
    memo: &lsys::param::ParamMemo,
    sys: &crate::model::lsys::LSystem,
    style: &Style,
    opts: &RenderOptions,
    progress: &mut dyn Progress,
) -> Result<(Frame, Option<f64>), Diagnostics> {
    let segments = memo.stems();
    let Some(par) = lsys::param::of(sys) else {
        return Ok((Frame::Fit, None));
    };
    let r = memo.radius();
    let ball = BBox {
        min_x: -r,
        min_y: -r,
        max_x: r,
        max_y: r,
    };
    let near = segments as f64 <= lsys::FIT_SYMBOLS;
    fitted_frame(
        scene,
        style,
        opts,
        progress,
        near,
        Some(ball),
        segments,
        |detail, bounds, phase| {
            memo.draw(sys, par, detail, &scene.limits, bounds, phase)
                .map(|_| ())
        },
    )
}

/// The frame of a stochastic system at a level of detail, as
/// [`fitted_frame`]'s: the first fit is to the expected box, the count the
/// expected one.
fn chance_frame(
    scene: &Scene,
    chance: &lsys::Chance,
    style: &Style,
    opts: &RenderOptions,
    progress: &mut dyn Progress,
) -> Result<(Frame, Option<f64>), Diagnostics> {
    let near = chance.expected_symbols() <= lsys::FIT_SYMBOLS;
    let segments = libm::round(chance.expected_segments()).min(u64::MAX as f64) as u64;
    fitted_frame(
        scene,
        style,
        opts,
        progress,
        near,
        chance.expected_box(),
        segments,
        |detail, bounds, phase| {
            lsys::draw_chance(chance, detail, &scene.limits, bounds, phase).map(|_| ())
        },
    )
}

/// The frame of a system drawn at a level of detail whose box is not
/// known exactly (stochastic, parametric), and the detail (canvas units)
/// to draw at when it must be the one the frame was measured at. `near`
/// (a word within [`lsys::FIT_SYMBOLS`]): the exact bounding pass (the
/// box and count `--exact` uses). Else `walk`, a bounding walk at a
/// detail, runs at the detail of a first fit to `first_box`, then again at
/// the detail of that fit, whose box and detail the drawing then uses,
/// with `segments` as its count.
#[allow(clippy::too_many_arguments)]
fn fitted_frame(
    scene: &Scene,
    style: &Style,
    opts: &RenderOptions,
    progress: &mut dyn Progress,
    near: bool,
    first_box: Option<BBox>,
    segments: u64,
    walk: impl Fn(f64, &mut Bounds, &mut dyn Progress) -> Result<(), Diagnostics>,
) -> Result<(Frame, Option<f64>), Diagnostics> {
    if near {
        let mut bounds = Bounds::default();
        scene.draw(&mut bounds, &mut Phase::new(progress, "measuring"))?;
        let known = Frame::Known {
            bbox: bounds.bbox(),
            segments: bounds.count,
        };
        return Ok((known, None));
    }
    let detail_of = |bbox: Option<BBox>| -> Result<f64, Diagnostics> {
        Ok(LOD_PX / Fit::content(bbox, 0, &style.width, opts.size)?.scale)
    };
    let bounded = |detail: f64, progress: &mut dyn Progress| {
        let mut bounds = Bounds::default();
        let mut phase = Phase::new(progress, "measuring");
        walk(detail, &mut bounds, &mut phase).map(|_| bounds.bbox())
    };
    let first = bounded(detail_of(first_box)?, progress)?;
    let detail = detail_of(first)?;
    let known = Frame::Known {
        bbox: bounded(detail, progress)?,
        segments,
    };
    Ok((known, Some(detail)))
}

/// The image format: `asked` (`-f`) if given, else the output name's
/// extension (`.svg`; `.png` or no extension: PNG). An extension that is
/// neither, or that contradicts `asked`, is a usage error.
pub fn image_format(
    asked: Option<ImageFormat>,
    output: Option<&str>,
) -> Result<ImageFormat, Diagnostics> {
    let name = |f: ImageFormat| match f {
        ImageFormat::Png => "png",
        ImageFormat::Svg => "svg",
    };
    let ext = output
        .and_then(|p| Path::new(p).extension())
        .map(|e| e.to_string_lossy().to_ascii_lowercase());
    let named = match ext.as_deref() {
        None => None,
        Some("png") => Some(ImageFormat::Png),
        Some("svg") => Some(ImageFormat::Svg),
        Some(other) => {
            return Err(Diagnostic::error(RenderError::UnknownOutputExtension {
                path: output.unwrap_or_default().into(),
                extension: other.into(),
            })
            .with_help("name the output .png or .svg")
            .into());
        }
    };
    match (asked, named) {
        (Some(a), Some(n)) if a != n => Err(Diagnostic::error(RenderError::FormatMismatch {
            format: name(a).into(),
            path: output.unwrap_or_default().into(),
        })
        .with_help("leave out -f (the extension decides), or name the output to match")
        .into()),
        (Some(a), _) => Ok(a),
        (None, n) => Ok(n.unwrap_or(ImageFormat::Png)),
    }
}

/// Which options a front end was given explicitly (not left at their
/// defaults), for [`ignored_flags`].
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub(crate) struct Given {
    /// A growth order (`--growth`).
    pub growth: bool,
    /// A derivation order (`--derivation`, or its old name `--strategy`).
    pub derivation: bool,
    /// A clearance (`--clearance`).
    pub clearance: bool,
    /// A stem limit (`--max-stems`).
    pub max_stems: bool,
    /// A derivation depth (`--depth`).
    pub depth: bool,
    /// A seed (`--seed`).
    pub seed: bool,
}

/// Warnings for options that do nothing for this input: growth options on
/// an input that does not grow, a depth on one that has none, a seed on
/// one that chooses nothing. Scripts pass
/// one set of options to many files, so these are warnings, not errors
/// (docs/cli.md states the rule).
pub(crate) fn ignored_flags(loaded: &Loaded, given: &Given) -> Vec<Diagnostic> {
    let mut w = Vec::new();
    let mut ignored = |flag: &str, reason: &str| {
        w.push(Diagnostic::warning(ErrorKind::IgnoredFlag {
            flag: flag.into(),
            reason: reason.into(),
        }));
    };
    if !matches!(loaded, Loaded::Od(_)) {
        let why = "only an .od grows; this input's tree is already decided";
        for (on, flag) in [
            (given.growth, "--growth"),
            (given.clearance, "--clearance"),
            (given.max_stems, "--max-stems"),
        ] {
            if on {
                ignored(flag, why);
            }
        }
    }
    if given.depth && !matches!(loaded, Loaded::Lsys(_)) {
        ignored(
            "--depth",
            "only an .lsys has a derivation depth; an .od or .bed draws its whole tree",
        );
    }
    if given.seed {
        match loaded {
            Loaded::Bed(_) => ignored(
                "--seed",
                "a .bed has its choices written out; it draws the same tree whatever the seed",
            ),
            Loaded::Lsys(sys) if !sys.is_stochastic() => ignored(
                "--seed",
                "this L-system has no stochastic rules (`rule F (0.5) -> ...`); every seed draws the same",
            ),
            Loaded::Od(desc) if !desc.chooses() => ignored(
                "--seed",
                "this description has no alternatives (`R1 (0.5): ...`); every seed grows the same tree",
            ),
            _ => {}
        }
    }
    if given.derivation && !given.growth && matches!(loaded, Loaded::Od(_)) {
        w.push(
            Diagnostic::warning(ErrorKind::IgnoredFlag {
                flag: "--derivation".into(),
                reason: "it is the derivation order (--strategy is its old name), which draws the same tree at another cost".into(),
            })
            .with_help("to grow the tree depth-first, write --growth dfs"),
        );
    }
    w
}
