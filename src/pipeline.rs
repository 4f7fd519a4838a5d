//! The pipeline as library functions: what every front end calls.
//!
//! The `stlc` command line and the `serve` editor do the same four things
//! with an input, and both call these functions, so the same input and
//! options give the same bytes whichever front end asks:
//!
//! 1. [`load`]: bytes and a kind ([`detect_kind`] tells it from a file name
//!    or the text) into a [`Loaded`] input: a classic L-system, an Outline
//!    Description, or a validated, measured BED ([`Bed`]).
//! 2. [`compile`]: an OD grown into a BED ([`crate::grow`]) and written as
//!    canonical BED text.
//! 3. [`scene`]: what a picture or an expansion shows, everything decided:
//!    an OD is grown first, an L-system gets its depth. Then [`render`] draws
//!    a scene to PNG or SVG with its style defaults and layout view, and
//!    [`expand`] streams its derived word.
//! 4. [`check`] and [`stats`]: summaries without drawing.
//!
//! Front ends map their arguments to the requests here and print what comes
//! back; they hold no pipeline logic of their own. Nothing here prints,
//! exits or touches a file: outputs are `Write`rs the caller opens (the CLI
//! writes atomically), progress goes to a [`Progress`] sink, and every
//! failure is a [`Diagnostics`] value.

use std::fmt::Write as _;
use std::io::Write;
use std::path::Path;

use crate::bed::Bed;
use crate::color::Rgb;
use crate::diag::{Diagnostic, Diagnostics, ErrorKind};
use crate::grow::{GrowOptions, Grown};
use crate::interpret::Derivation;
use crate::limits::Limits;
use crate::model::lsys::{Background, LSystem};
use crate::model::{Description, Format, SeedItem};
use crate::progress::{Phase, Progress};
use crate::render::{RenderOptions, Style, Width};
use crate::syntax::{self, InputKind};
use crate::turtle::{BBox, Fill, Turtle};

/// A parsed input.
#[derive(Debug, Clone, PartialEq)]
pub enum Loaded {
    /// A classic L-system (`.lsys`).
    Lsys(LSystem),
    /// An Outline Description (`.od`): rules, seed and layout, still to grow.
    Od(Description),
    /// A Branch-Expansion Description (`.bed`), validated and measured.
    Bed(Bed),
}

impl Loaded {
    /// The kind of input it was read as.
    pub fn kind(&self) -> InputKind {
        match self {
            Loaded::Lsys(_) => InputKind::Lsys,
            Loaded::Od(_) => InputKind::Od,
            Loaded::Bed(_) => InputKind::Bed,
        }
    }
}

/// The kind of an input: from its file name's extension if it has a known
/// one, else guessed from its text ([`sniff`]). Unnamed input (standard
/// input, text typed in an editor) that cannot be guessed is an OD; a named
/// file that cannot be is an error that says how to name it.
pub fn detect_kind(name: Option<&Path>, bytes: &[u8]) -> Result<InputKind, Diagnostics> {
    match name {
        Some(p) => match InputKind::from_path(p) {
            Some(k) => Ok(k),
            None => sniff(bytes).ok_or_else(|| {
                Diagnostic::error(ErrorKind::UnknownInputKind {
                    name: p.display().to_string(),
                })
                .with_help("name it .od, .bed or .lsys, or say --from od|bed|lsys")
                .into()
            }),
        },
        None => Ok(sniff(bytes).unwrap_or(InputKind::Od)),
    }
}

/// Guesses the kind of unnamed input: `.lsys` if its first word is an
/// `.lsys` key, `.bed` if it has `{` terms, else `.od`. `None` for text
/// that is not UTF-8 or has no word.
pub fn sniff(bytes: &[u8]) -> Option<InputKind> {
    let text = std::str::from_utf8(bytes).ok()?;
    let first = text
        .lines()
        .map(str::trim)
        .find(|l| !l.is_empty() && !l.starts_with('#'))?
        .split_whitespace()
        .next()?;
    if syntax::lsys::KEYS.contains(&first) {
        Some(InputKind::Lsys)
    } else if text.contains('{') {
        Some(InputKind::Bed)
    } else {
        Some(InputKind::Od)
    }
}

/// Parses `bytes` as an input of `kind`, within `limits` (size, nesting,
/// depth, ...). A BED is validated and measured here, once.
pub fn load(bytes: &[u8], kind: InputKind, limits: &Limits) -> Result<Loaded, Diagnostics> {
    let text = syntax::precheck(bytes, limits)?;
    if text.trim().is_empty() {
        let help = match kind {
            InputKind::Lsys => "an .lsys file needs at least `axiom` and `angle` lines",
            InputKind::Od | InputKind::Bed => {
                "a description needs at least a tree name, a root `(x, y)` and `RULE` with a rule"
            }
        };
        return Err(Diagnostic::error(ErrorKind::EmptyInput)
            .with_help(help)
            .into());
    }
    match kind {
        InputKind::Lsys => syntax::lsys::parse(text, limits).map(Loaded::Lsys),
        InputKind::Od => syntax::stl::parse(text, Format::Od, limits).map(Loaded::Od),
        InputKind::Bed => {
            let desc = syntax::stl::parse(text, Format::Bed, limits)?;
            Bed::new(desc, limits).map(Loaded::Bed)
        }
    }
}

/// Refuses an input of the wrong kind for `command`, saying what to do
/// instead.
fn wrong_kind(command: Command, found: InputKind) -> Diagnostics {
    let (message, help): (&str, &str) = match (command, found) {
        (Command::Compile, InputKind::Lsys) => (
            "compile grows Outline Descriptions (.od); this is a classic L-system",
            "draw it with `stlc render`, or print its word with `stlc expand`",
        ),
        (Command::Compile, _) => (
            "compile grows Outline Descriptions (.od); this is already a BED",
            "draw it with `stlc render`; if it is an outline, name it .od or pass --from od",
        ),
        (Command::Stats, _) => (
            "stats counts classic L-system words (.lsys)",
            "for an .od or .bed, `stlc check` prints its rules, terms and stem count",
        ),
    };
    Diagnostic::error(ErrorKind::WrongInputKind {
        message: message.into(),
    })
    .with_help(help)
    .into()
}

/// A command that takes only some kinds of input.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Command {
    Compile,
    Stats,
}

// ------------------------------------------------------------- compile --

/// What [`compile`] produced.
#[derive(Debug, Clone, PartialEq)]
pub struct Compiled {
    /// The grown tree (BED, stems, warnings).
    pub grown: Grown,
    /// The BED as canonical text: what `stlc compile` writes.
    pub text: String,
}

/// Grows an Outline Description into a BED and writes its canonical text.
/// Any other input is refused with a diagnostic that says what to do.
pub fn compile(
    loaded: &Loaded,
    opts: &GrowOptions,
    progress: &mut dyn Progress,
) -> Result<Compiled, Diagnostics> {
    let Loaded::Od(od) = loaded else {
        return Err(wrong_kind(Command::Compile, loaded.kind()));
    };
    let grown = grow(od, opts, progress)?;
    let text = crate::bed::write::write(grown.bed.description());
    Ok(Compiled { grown, text })
}

/// Grows `od`, reporting progress as `growing: ...`.
fn grow(
    od: &Description,
    opts: &GrowOptions,
    progress: &mut dyn Progress,
) -> Result<Grown, Diagnostics> {
    crate::grow::grow(od, opts, &mut Phase::new(progress, "growing"))
}

// --------------------------------------------------------------- scene --

/// What to derive: the options of [`scene`].
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SceneRequest {
    /// How an OD grows (order, clearance, limits).
    pub grow: GrowOptions,
    /// How the word is derived (`--strategy`): the same picture at a
    /// different cost.
    pub derivation: Derivation,
    /// The derivation depth of an L-system (`--depth`); `None`: its
    /// `generations`.
    pub depth: Option<u32>,
    /// The limits in force.
    pub limits: Limits,
}

/// A derivation with everything decided: ready to draw or expand, any
/// number of times.
#[derive(Debug, Clone, PartialEq)]
pub struct Scene {
    what: What,
    derivation: Derivation,
    limits: Limits,
    /// Warnings from getting here (growth cut short, ...).
    pub warnings: Vec<Diagnostic>,
}

#[derive(Debug, Clone, PartialEq)]
enum What {
    Lsys { sys: LSystem, depth: u32 },
    Tree { bed: Box<Bed>, grown: Option<u64> },
}

/// Decides what `loaded` shows: an L-system at its depth, a BED as it is,
/// or an OD grown into a BED.
pub fn scene(
    loaded: Loaded,
    req: &SceneRequest,
    progress: &mut dyn Progress,
) -> Result<Scene, Diagnostics> {
    let (what, warnings) = match loaded {
        Loaded::Lsys(sys) => {
            let depth = lsys_depth(&sys, req.depth, &req.limits)?;
            let warnings = inert_turns(&sys);
            (What::Lsys { sys, depth }, warnings)
        }
        Loaded::Bed(bed) => (
            What::Tree {
                bed: Box::new(bed),
                grown: None,
            },
            Vec::new(),
        ),
        Loaded::Od(od) => {
            let grown = grow(&od, &req.grow, progress)?;
            let what = What::Tree {
                bed: Box::new(grown.bed),
                grown: Some(grown.stems),
            };
            (what, grown.warnings)
        }
    };
    Ok(Scene {
        what,
        derivation: req.derivation,
        limits: req.limits,
        warnings,
    })
}

impl Scene {
    /// The BED drawn, if the scene is a tree (grown or read).
    pub fn bed(&self) -> Option<&Bed> {
        match &self.what {
            What::Tree { bed, .. } => Some(bed),
            What::Lsys { .. } => None,
        }
    }

    /// Stems grown, if the scene was grown from an OD.
    pub fn grown_stems(&self) -> Option<u64> {
        match &self.what {
            What::Tree { grown, .. } => *grown,
            What::Lsys { .. } => None,
        }
    }

    /// Draws the scene's segments into `turtle`.
    pub fn draw(
        &self,
        turtle: &mut dyn Turtle,
        progress: &mut dyn Progress,
    ) -> Result<(), Diagnostics> {
        match &self.what {
            What::Lsys { sys, depth } => crate::interpret::lsys::draw(
                sys,
                *depth,
                self.derivation,
                &self.limits,
                turtle,
                progress,
            ),
            What::Tree { bed, .. } => {
                crate::interpret::bed::draw(bed, self.derivation, &self.limits, turtle, progress)
            }
        }
    }
}

/// Warnings for `L` and `R` in an L-system that has no rule for them: in an
/// `.lsys` they are ordinary symbols (the Hilbert curve's non-terminals),
/// not turns as in STL, so a rule copied from an STL paper
/// (`F -> F[RF]F[LF]F`) would draw a straight line without a word.
pub fn inert_turns(sys: &LSystem) -> Vec<Diagnostic> {
    ['L', 'R']
        .into_iter()
        .filter(|c| !sys.rules.contains_key(c))
        .filter_map(|c| {
            let span = if sys.axiom.contains(&c) {
                Some(sys.axiom_loc.0.clone())
            } else {
                sys.rules
                    .values()
                    .find(|p| p.successor.contains(&c))
                    .map(|p| p.loc.0.clone())
            }?;
            Some(
                Diagnostic::warning(ErrorKind::InertTurn { symbol: c })
                    .with_span(span)
                    .with_label(format!("`{c}` here turns nothing"))
                    .with_help("write `+` for a left turn and `-` for a right turn"),
            )
        })
        .collect()
}

/// The depth to derive an L-system to: `depth` if given, else the file's
/// `generations`, within `limits.max_depth`.
pub fn lsys_depth(sys: &LSystem, depth: Option<u32>, limits: &Limits) -> Result<u32, Diagnostics> {
    let d = depth.or(sys.generations).ok_or_else(|| {
        Diagnostic::error(ErrorKind::NoDepth)
            .with_help("add a line `generations N` to the file, or pass --depth N")
    })?;
    limits.check_depth(d)?;
    Ok(d)
}

// -------------------------------------------------------------- render --

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
    /// Paint the layout's shapes under a tree (`--show-layout`).
    pub show_layout: bool,
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
            width: Width::Pixels(sys.width),
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
pub fn layout_view(scene: &Scene, show: bool) -> (Option<BBox>, Vec<Fill>) {
    let Some(bed) = scene.bed() else {
        return (None, Vec::new());
    };
    let desc = bed.description();
    let Some(layout) = desc.layout.as_ref() else {
        return (None, Vec::new());
    };
    let fills = if show {
        crate::layout::fills(layout)
    } else {
        Vec::new()
    };
    let view = crate::layout::layout_bbox(layout).map(|b| {
        let widest = desc.params.width.base.max(0.0);
        let m = crate::render::MARGIN_FRACTION * b.width().max(b.height()) + widest / 2.0;
        BBox {
            min_x: b.min_x - m,
            min_y: b.min_y - m,
            max_x: b.max_x + m,
            max_y: b.max_y + m,
        }
    });
    (view, fills)
}

/// What [`render`] drew.
#[derive(Debug, Clone, PartialEq)]
pub struct Rendered {
    /// Segments drawn.
    pub segments: u64,
    /// Warnings (nothing drawn, ...).
    pub warnings: Vec<Diagnostic>,
}

/// Draws `scene` as a PNG or SVG into `out`, with its style and layout
/// view (see [`style`] and [`layout_view`]). A picture with no stem in it
/// is written all the same, with a warning.
pub fn render(
    scene: &Scene,
    look: &Look,
    opts: &RenderOptions,
    out: &mut dyn Write,
    progress: &mut dyn Progress,
) -> Result<Rendered, Diagnostics> {
    let style = style(scene, look);
    let (view, underlay) = layout_view(scene, look.show_layout);
    let mut drawing = |t: &mut dyn Turtle, p: &mut dyn Progress| scene.draw(t, p);
    let counted =
        crate::render::render(&mut drawing, view, &underlay, &style, opts, out, progress)?;
    // A tree's stems are known from its measure; an L-system's were counted
    // by the bounding pass (it has no layout view, so one always runs).
    let segments = match &scene.what {
        What::Tree { bed, .. } => bed.size().stems,
        What::Lsys { .. } => counted.unwrap_or(0),
    };
    let mut warnings = Vec::new();
    if segments == 0 {
        warnings.push(Diagnostic::warning(ErrorKind::NothingDrawn).with_help(
            "check the axiom or seed and the depth: only `F` draws (and in an .od, a rule that grows)",
        ));
    }
    Ok(Rendered { segments, warnings })
}

// -------------------------------------------------------------- expand --

/// Writes the scene's derived word to `out`: for an L-system its symbols,
/// for a tree its drawing components (`F f + - [ ] |`), then a newline.
pub fn expand(
    scene: &Scene,
    out: &mut dyn Write,
    progress: &mut dyn Progress,
) -> Result<(), Diagnostics> {
    match &scene.what {
        What::Lsys { sys, depth } => crate::interpret::lsys::expand(
            sys,
            *depth,
            scene.derivation,
            &scene.limits,
            out,
            progress,
        ),
        What::Tree { bed, .. } => {
            crate::interpret::bed::expand(bed, scene.derivation, &scene.limits, out, progress)
        }
    }
}

// --------------------------------------------------------------- stats --

/// Exact word lengths and counts of an L-system (`stlc stats`), as text or
/// JSON. Any other input is refused.
pub fn stats(
    loaded: &Loaded,
    depth: Option<u32>,
    json: bool,
    limits: &Limits,
) -> Result<String, Diagnostics> {
    let Loaded::Lsys(sys) = loaded else {
        return Err(wrong_kind(Command::Stats, loaded.kind()));
    };
    let depth = lsys_depth(sys, depth, limits)?;
    let stats = crate::interpret::stats::stats(sys, depth, limits)?;
    Ok(if json {
        stats.to_json()
    } else {
        stats.to_text()
    })
}

// --------------------------------------------------------------- check --

/// What [`check`] found.
#[derive(Debug, Clone, PartialEq)]
pub struct Checked {
    /// The summary, lines of text.
    pub summary: String,
    /// Warnings (growth cut short, inert symbols, ...).
    pub warnings: Vec<Diagnostic>,
}

/// Answers "would compile and render succeed?" without drawing, and
/// summarises the input (`stlc check`): its rules, seed and layout; an
/// L-system with `generations` is checked against the limits at that depth
/// (its word's length is computed, not derived); an OD is
/// grown with `opts` (every check compile makes: bounded growth, the root
/// inside the layout, a layout with an area, the limits) and its stems
/// counted; a BED's stems come from its measure.
pub fn check(loaded: &Loaded, opts: &GrowOptions) -> Result<Checked, Diagnostics> {
    let limits = &opts.limits;
    Ok(match loaded {
        Loaded::Lsys(sys) => {
            // With its own depth, would it derive within the limits?
            if let Some(depth) = sys.generations {
                crate::interpret::lsys::check(sys, depth, Derivation::Dfs, limits)?;
            }
            Checked {
                summary: lsys_summary(sys),
                warnings: inert_turns(sys),
            }
        }
        Loaded::Od(desc) => {
            let grown = grow(desc, opts, &mut crate::progress::NoProgress)?;
            let mut summary = stl_summary(desc, None, limits)?;
            let order = match opts.growth {
                crate::grow::GrowthOrder::Bfs => "bfs",
                crate::grow::GrowthOrder::Dfs => "dfs",
            };
            let _ = writeln!(summary, "  grows       {} stems ({order})", grown.stems);
            Checked {
                summary,
                warnings: grown.warnings,
            }
        }
        Loaded::Bed(bed) => Checked {
            summary: stl_summary(bed.description(), Some(bed), limits)?,
            warnings: Vec::new(),
        },
    })
}

fn lsys_summary(sys: &LSystem) -> String {
    let mut s = String::new();
    let _ = writeln!(s, "classic L-system: ok");
    let _ = writeln!(s, "  axiom       {}", sys.axiom.iter().collect::<String>());
    for (k, p) in &sys.rules {
        let _ = writeln!(
            s,
            "  rule        {k} -> {}",
            p.successor.iter().collect::<String>()
        );
    }
    let _ = writeln!(s, "  angle       {}", sys.angle);
    match sys.generations {
        Some(g) => {
            let _ = writeln!(s, "  generations {g}");
        }
        None => {
            let _ = writeln!(s, "  generations (none: pass --depth)");
        }
    }
    s
}

fn stl_summary(
    desc: &Description,
    bed: Option<&Bed>,
    limits: &Limits,
) -> Result<String, Diagnostics> {
    use geo::Area;
    let mut s = String::new();
    let what = match desc.format {
        Format::Od => "Outline Description",
        Format::Bed => "Branch-Expansion Description",
    };
    let _ = writeln!(s, "{what} `{}`: ok", desc.name);
    let _ = writeln!(s, "  root        ({}, {})", desc.root.0, desc.root.1);
    for r in &desc.rules {
        let n = r.branch_count();
        let _ = writeln!(
            s,
            "  rule        {} ({} branch{})",
            r.name,
            n,
            if n == 1 { "" } else { "es" }
        );
    }
    let terms = desc.effective_seed().map_or(0, |seed| {
        seed.items
            .iter()
            .filter(|i| matches!(i, SeedItem::Term(_) | SeedItem::Repeat(_)))
            .count()
    });
    let written = if desc.seed.is_some() {
        ""
    } else {
        " (default: F and the first rule)"
    };
    let _ = writeln!(s, "  seed terms  {terms}{written}");
    if let Some(bed) = bed {
        let _ = writeln!(s, "  stems       {}", bed.size().stems);
    }
    match &desc.layout {
        Some(l) => {
            let area = match crate::grow::region::Region::from_layout(l, limits.max_layout_vertices)
            {
                Ok(r) => format!("{:.1} square units", r.area().unsigned_area()),
                Err(e) if e.iter().any(|d| matches!(d.kind, ErrorKind::Limit { .. })) => {
                    return Err(e);
                }
                Err(_) => "empty".to_string(),
            };
            let _ = writeln!(
                s,
                "  layout      {} shape(s), growth area {area}",
                l.shapes.len()
            );
        }
        None => {
            let _ = writeln!(s, "  layout      none");
        }
    }
    Ok(s)
}
