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

mod draw;
mod lsys3;
mod request;
mod stats3;
mod summary;
mod tree3;
mod view3;

pub(crate) use draw::{Given, ignored_flags, layout_view, render_tree};
pub use draw::{Look, Rendered, ShowLayout, TREE_BROWN, image_format, render, style};
pub use request::{Drawn, Request};
pub use summary::{Checked, check, stats};
pub use view3::{MAX_EDITOR_STEMS, Meshed, Stems3};

// What front ends name, reached through the pipeline: the enums their
// options take, the limits, colours, progress sinks and what comes back.
pub use crate::color::Rgb;
pub use crate::grow::{GrowthOrder, PlacedStem};
pub use crate::interpret::Derivation;
pub use crate::limits::{Bound, Limits};
pub use crate::progress::{NoProgress, Progress};
pub use crate::render::mesh::{
    DEFAULT_MAX_TRIANGLES, DEFAULT_SIDES, DEFAULT_UNIT, MeshFormat, MeshOptions,
};
pub use crate::render::view::View;
pub use crate::render::{DEFAULT_MAX_SVG_SEGMENTS, ImageFormat, RenderOptions};
pub use crate::syntax::InputKind;
pub use crate::turtle::BBox;

use std::io::Write;
use std::path::Path;

use crate::bed::Bed;
use crate::diag::{Diagnostic, Diagnostics, Help, InputError, Knob, LsysError};
use crate::grow::{GrowOptions, Grown};
use crate::model::lsys::LSystem;
use crate::model::{Description, Format};
use crate::progress::Phase;
use crate::syntax;
use crate::turtle::Turtle;

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

    /// Whether the input is 3D: an `.lsys` with `dimensions 3`, an OD or
    /// BED whose roots have three coordinates.
    pub fn is_3d(&self) -> bool {
        match self {
            Loaded::Lsys(sys) => sys.is_3d(),
            Loaded::Od(d) => d.is_3d(),
            Loaded::Bed(b) => b.description().is_3d(),
        }
    }

    /// The input with `seed` (`--seed`), if given, in place of an
    /// L-system's `seed` key. An OD takes its seed with its growth options
    /// ([`GrowOptions::seed`]); a BED has every choice written out and
    /// needs none, so for both this changes nothing.
    pub fn seeded(self, seed: Option<u64>) -> Loaded {
        match (self, seed) {
            (Loaded::Lsys(mut sys), Some(s)) => {
                sys.seed = s;
                Loaded::Lsys(sys)
            }
            (other, _) => other,
        }
    }
}

/// The kind of an input: from its file name's extension if it has a known
/// one, else guessed from its text (its first word, or `{` terms). Unnamed input (standard
/// input, text typed in an editor) that cannot be guessed is an OD; a named
/// file that cannot be is an error that says how to name it.
pub fn detect_kind(name: Option<&Path>, bytes: &[u8]) -> Result<InputKind, Diagnostics> {
    match name {
        Some(p) => match InputKind::from_path(p) {
            Some(k) => Ok(k),
            None => sniff(bytes).ok_or_else(|| {
                Diagnostic::error(InputError::UnknownInputKind {
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
/// `.lsys` key (a parametric file's `define`, `ignore`, `tropism` and
/// `elasticity` among them), `.bed` if it has `{` terms, else `.od`. `None` for text
/// that is not UTF-8 or has no word.
pub(crate) fn sniff(bytes: &[u8]) -> Option<InputKind> {
    let text = std::str::from_utf8(bytes).ok()?;
    let first = text
        .lines()
        .map(str::trim)
        .find(|l| !l.is_empty() && !l.starts_with('#'))?
        .split_whitespace()
        .next()?;
    if syntax::lsys::KEYS.contains(&first) || syntax::lsys::PARAM_KEYS.contains(&first) {
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
        return Err(Diagnostic::error(InputError::EmptyInput)
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
            "stats counts classic L-system words (.lsys) and measures 3D BEDs",
            "for an .od or a 2D .bed, `stlc check` prints its rules, terms and stem count; \
             `stlc compile` makes a 3D .od's BED",
        ),
    };
    Diagnostic::error(InputError::WrongInputKind {
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

/// A grown tree as an editor replays it: the BED's text (the same as
/// [`compile`]'s) and its stems in the order growth placed them
/// ([`crate::grow::grow_traced`]).
#[derive(Debug, Clone, PartialEq)]
pub struct TraceTree {
    /// The BED as canonical text.
    pub text: String,
    /// The stems in growth order, each with its decision.
    pub placed: Vec<PlacedStem>,
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

/// [`scene`], and for an OD the description as read and, if `trace`,
/// the grown tree as an editor replays it ([`TraceTree`]): one growth
/// for both.
fn traced_scene(
    loaded: Loaded,
    req: &SceneRequest,
    trace: bool,
    progress: &mut dyn Progress,
) -> Result<(Scene, Option<Description>, Option<TraceTree>), Diagnostics> {
    let Loaded::Od(od) = loaded else {
        return Ok((scene(loaded, req, progress)?, None, None));
    };
    let (grown, traced) = if trace {
        let (grown, placed) =
            crate::grow::grow_traced(&od, &req.grow, &mut Phase::new(progress, "growing"))?;
        let text = crate::bed::write::write(grown.bed.description());
        (grown, Some(TraceTree { text, placed }))
    } else {
        (grow(&od, &req.grow, progress)?, None)
    };
    let scene = Scene {
        what: What::Tree {
            bed: Box::new(grown.bed),
            grown: Some(grown.stems),
        },
        derivation: req.derivation,
        limits: req.limits,
        warnings: grown.warnings,
    };
    Ok((scene, Some(od), traced))
}

impl Scene {
    /// The BED drawn, if the scene is a tree (grown or read).
    pub fn bed(&self) -> Option<&Bed> {
        match &self.what {
            What::Tree { bed, .. } => Some(bed),
            What::Lsys { .. } => None,
        }
    }

    /// Whether the scene is a tree with a LAYOUT (something `show_layout`
    /// can paint).
    pub fn has_layout(&self) -> bool {
        self.bed().is_some_and(|b| b.description().layout.is_some())
    }

    /// Stems grown, if the scene was grown from an OD.
    pub fn grown_stems(&self) -> Option<u64> {
        match &self.what {
            What::Tree { grown, .. } => *grown,
            What::Lsys { .. } => None,
        }
    }

    /// Draws the scene's segments into `turtle` (a 3D tree's front view:
    /// its stems' x and y).
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
            // A dressed tree (section 13: an `S=` ramp, `P=` leaves).
            What::Tree { bed, .. } if crate::interpret::dress::dresses(bed.description()) => {
                crate::interpret::dress::draw2(bed, self.derivation, &self.limits, turtle, progress)
            }
            // A 3D tree drawn flat is its front view: its stems' x and y.
            What::Tree { bed, .. } if bed.description().is_3d() => {
                let mut flat = |s: crate::turtle::turtle3::Segment3| {
                    turtle.segment(crate::turtle::Segment {
                        from: crate::turtle::Point::new(s.from.x, s.from.y),
                        to: crate::turtle::Point::new(s.to.x, s.to.y),
                        order: s.order,
                    })
                };
                let limits = &self.limits;
                crate::interpret::bed3::draw3(bed, self.derivation, limits, &mut flat, progress)
                    .map(|_| ())
            }
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
pub(crate) fn inert_turns(sys: &LSystem) -> Vec<Diagnostic> {
    ['L', 'R']
        .into_iter()
        .filter(|c| !sys.rules.contains_key(c))
        .filter_map(|c| {
            let span = if sys.axiom.contains(&c) {
                Some(sys.axiom_loc.0.clone())
            } else {
                sys.rules
                    .values()
                    .flatten()
                    .find(|p| p.successor.contains(&c))
                    .map(|p| p.loc.0.clone())
            }?;
            Some(
                Diagnostic::warning(LsysError::InertTurn { symbol: c })
                    .with_span(span)
                    .with_label(format!("`{c}` here turns nothing"))
                    .with_help("write `+` for a left turn and `-` for a right turn"),
            )
        })
        .collect()
}

/// The depth to derive an L-system to: `depth` if given, else the file's
/// `generations`, within `limits.max_depth`.
pub(crate) fn lsys_depth(
    sys: &LSystem,
    depth: Option<u32>,
    limits: &Limits,
) -> Result<u32, Diagnostics> {
    let d = depth.or(sys.generations).ok_or_else(|| {
        Diagnostic::error(LsysError::NoDepth).with_help(
            Help::from("add a line `generations N` to the file, or set ")
                + Help::knob(Knob::Depth, "N"),
        )
    })?;
    limits.check_depth(d)?;
    Ok(d)
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
        What::Tree { bed, .. } if bed.description().is_3d() => {
            crate::interpret::bed3::expand3(bed, scene.derivation, &scene.limits, out, progress)
        }
        What::Tree { bed, .. } => {
            crate::interpret::bed::expand(bed, scene.derivation, &scene.limits, out, progress)
        }
    }
}
