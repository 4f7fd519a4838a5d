//! One request type for every front end: [`Request`] holds the input and
//! every option a run can take; its methods run the pipeline and return
//! everything a front end shows.
//!
//! A front end builds a `Request` once from its own inputs (the CLI from its
//! flags, `stlc serve` from a JSON body) and calls one method:
//!
//! | method | what | CLI | serve |
//! | --- | --- | --- | --- |
//! | [`Request::render`] | the picture (PNG or SVG) into a writer, and with [`Request::trace`] the BED text and the stems in growth order | `render` | `/api/render`, `/api/export` |
//! | [`Request::compile`] | an OD grown into BED text | `compile` | |
//! | [`Request::expand`] | the derived word into a writer | `expand` | |
//! | [`Request::check`], [`Request::stats`] | summaries | `check`, `stats` | |
//!
//! Options a front end was not given are `None`; an option given for an
//! input it does nothing for is a warning ([`super::ignored_flags`]), named
//! by its command-line flag (docs/cli.md states the rule).

use std::io::Write;
use std::path::PathBuf;

use super::{
    Compiled, Given, Loaded, Look, SceneRequest, ShowLayout, TraceTree, detect_kind, ignored_flags,
    load,
};
use crate::color::Rgb;
use crate::diag::{Diagnostic, Diagnostics, ErrorKind};
use crate::grow::{GrowOptions, GrowthOrder};
use crate::interpret::Derivation;
use crate::limits::{Bound, Limits};
use crate::model::{Description, Design};
use crate::progress::Progress;
use crate::render::mesh::{MeshFormat, MeshOptions};
use crate::render::view::View;
use crate::render::{ImageFormat, RenderOptions};
use crate::syntax::InputKind;
use crate::turtle::BBox;

/// Everything one run of the pipeline takes: the input and its options.
#[derive(Debug, Clone, PartialEq)]
pub struct Request {
    /// The input's bytes.
    pub input: Vec<u8>,
    /// The input's file name, if it has one: its extension tells its kind.
    pub name: Option<PathBuf>,
    /// The input's kind (`--from`); `None`: from [`Request::name`], else
    /// guessed from the text ([`super::detect_kind`]).
    pub kind: Option<InputKind>,
    /// How the word is derived (`--derivation`): the same picture at a
    /// different cost; `None`: depth-first.
    pub derivation: Option<Derivation>,
    /// Growth order of an OD (`--growth`); `None`: breadth-first.
    pub growth: Option<GrowthOrder>,
    /// Derivation depth of an L-system (`--depth`); `None`: its
    /// `generations`.
    pub depth: Option<u32>,
    /// Seed of stochastic rules (`--seed`); `None`: an L-system's `seed`
    /// key, an OD's 0.
    pub seed: Option<u64>,
    /// Clearance between stems (`--clearance`); `None`: the OD's `C=`.
    pub clearance: Option<f64>,
    /// Stems one growth may add (`--max-stems`), at most
    /// `limits.max_stems`; `None`: that limit, as a safety net (growth
    /// with no other bound is then refused).
    pub max_stems: Option<u64>,
    /// The limits in force (`--max-*`).
    pub limits: Limits,
    /// Colours and the layout underlay.
    pub look: Look,
    /// Image format, size, SVG segment limit, level of detail.
    pub image: RenderOptions,
    /// [`Request::render`] also returns the grown tree's BED text and its
    /// stems in the order growth placed them (an editor's replay).
    pub trace: bool,
    /// With [`Request::trace`]: a grown tree of more stems than this is
    /// left out of [`Request::render`]'s picture (its background and
    /// layout underlay are drawn; [`Drawn::tree_left_out`]), for an editor
    /// that draws the traced stems itself; `None`: always drawn.
    pub tree_up_to: Option<u64>,
    /// The view of a 3D input (`--view AZ,EL`); `None`:
    /// [`View::DEFAULT`]. A 2D input has only its front view: given for
    /// one, a warning.
    pub view: Option<View>,
    /// How [`Request::mesh`] makes tubes (`--sides`, `--unit`,
    /// `--max-triangles`).
    pub mesh: MeshOptions,
}

impl Default for Request {
    /// No input, every option at its default: a PNG at the default size.
    fn default() -> Self {
        Request {
            input: Vec::new(),
            name: None,
            kind: None,
            derivation: None,
            growth: None,
            depth: None,
            seed: None,
            clearance: None,
            max_stems: None,
            limits: Limits::DEFAULT,
            look: Look::default(),
            image: RenderOptions::new(ImageFormat::Png, None),
            trace: false,
            tree_up_to: None,
            view: None,
            mesh: MeshOptions::default(),
        }
    }
}

/// What [`Request::render`] drew.
#[derive(Debug, Clone, PartialEq)]
pub struct Drawn {
    /// Segments drawn (a tree's stems; an L-system's segments),
    /// saturating at `u64::MAX`.
    pub segments: u64,
    /// The same in decimal digits, exact at any depth; `None` where no
    /// exact count is known (see [`super::Rendered::count`]).
    pub count: Option<String>,
    /// Stems grown, if an OD was grown.
    pub grown: Option<u64>,
    /// The OD as read, if the input was one (its root and layout, with
    /// their spans, for an editor to draw and edit).
    pub od: Option<Description>,
    /// With [`Request::trace`], for an OD: the grown BED's text and its
    /// stems in growth order.
    pub trace: Option<TraceTree>,
    /// The canvas area the layout defines, if the input has one.
    pub view: Option<BBox>,
    /// Warnings, in the order the work met them.
    pub warnings: Vec<Diagnostic>,
    /// The colour the tree's stems are (or would be) drawn in.
    pub stroke: Rgb,
    /// Whether the tree was left out of the picture for its size
    /// ([`Request::tree_up_to`]): the trace has its stems.
    pub tree_left_out: bool,
    /// With [`Request::trace`] and [`Request::tree_up_to`], a 3D input's
    /// stems for an editor that draws them itself: then no picture is
    /// drawn.
    pub stems3: Option<super::Stems3>,
}

impl Request {
    /// A request for `input` with every option at its default.
    pub fn new(input: Vec<u8>) -> Self {
        Request {
            input,
            ..Request::default()
        }
    }

    /// The input's kind: [`Request::kind`], else from its name or text.
    pub fn input_kind(&self) -> Result<InputKind, Diagnostics> {
        match self.kind {
            Some(k) => Ok(k),
            None => detect_kind(self.name.as_deref(), &self.input),
        }
    }

    /// The limits and growth options of this request for an input whose
    /// file keeps `design` (an OD's `O=`, `V=`, `M=`): the request's own
    /// options override the file's for this run; `max_stems`, if given,
    /// within `limits.max_stems`, and the file's `M=` within both.
    fn options(&self, design: &Design) -> Result<(Limits, GrowOptions), Diagnostics> {
        let mut limits = self.limits;
        if let Some(n) = self.max_stems {
            if n > limits.max_stems {
                return Err(Bound::Stems
                    .exceeded_by("max stems asked for", n, limits.max_stems)
                    .with_help(crate::diag::Help::from("ask for fewer, or ") + Bound::Stems)
                    .into());
            }
            limits.max_stems = n;
        }
        if let Some(m) = design.max_stems {
            limits.max_stems = limits.max_stems.min(m);
        }
        let grow = GrowOptions {
            growth: self.growth.or(design.order).unwrap_or_default(),
            clearance: self.clearance,
            limits,
            max_stems_explicit: self.max_stems.is_some() || design.max_stems.is_some(),
            seed: self.seed.or(design.seed).unwrap_or(0),
        };
        Ok((limits, grow))
    }

    /// Which options were given, for the warnings about those that do
    /// nothing for the input.
    fn given(&self) -> Given {
        Given {
            growth: self.growth.is_some(),
            derivation: self.derivation.is_some(),
            clearance: self.clearance.is_some(),
            max_stems: self.max_stems.is_some(),
            depth: self.depth.is_some(),
            seed: self.seed.is_some(),
        }
    }

    /// Loads the input within the limits, with the seed in place, and the
    /// warnings for options that do nothing for it.
    pub fn open(&self) -> Result<(Loaded, Vec<Diagnostic>), Diagnostics> {
        let (limits, _) = self.options(&Design::default())?;
        let loaded = load(&self.input, self.input_kind()?, &limits)?.seeded(self.seed);
        let mut warnings = ignored_flags(&loaded, &self.given());
        if self.view.is_some() && !loaded.is_3d() {
            warnings.push(Diagnostic::warning(ErrorKind::IgnoredFlag {
                flag: "--view".into(),
                reason: "this input is flat: its picture is its front view (`dimensions 3` makes an .lsys 3D, a root `(x, y, z)` an .od or .bed)".into(),
            }));
        }
        if self.look.show_layout == ShowLayout::Yes && !has_layout(&loaded) {
            warnings.push(Diagnostic::warning(ErrorKind::IgnoredFlag {
                flag: "--show-layout".into(),
                reason: "this input has no LAYOUT to show".into(),
            }));
        }
        Ok((loaded, warnings))
    }

    /// The scene's request: how to grow and derive.
    fn scene_request(&self, loaded: &Loaded) -> Result<SceneRequest, Diagnostics> {
        let (limits, grow) = self.options(&design(loaded))?;
        Ok(SceneRequest {
            grow,
            derivation: self.derivation.unwrap_or_default(),
            depth: self.depth,
            limits,
        })
    }

    /// Draws the input as [`Request::image`] asks into `out`: an OD grown
    /// first (traced with [`Request::trace`]), an L-system at its depth, a
    /// BED as it is.
    pub fn render(
        &self,
        out: &mut dyn Write,
        progress: &mut dyn Progress,
    ) -> Result<Drawn, Diagnostics> {
        let (loaded, mut warnings) = self.open()?;
        let req = self.scene_request(&loaded)?;
        let (scene, od, trace) = super::traced_scene(loaded, &req, self.trace, progress)?;
        let grown = scene.grown_stems();
        let tree_left_out = trace.is_some()
            && matches!((self.tree_up_to, grown), (Some(most), Some(n)) if n > most);
        let stems3 = match self.tree_up_to {
            Some(_) if self.trace => {
                let placed = trace.as_ref().map_or(&[][..], |t| &t.placed[..]);
                super::view3::editor_stems3(&scene, &self.look, placed, progress)?
            }
            _ => None,
        };
        let (stems3, rendered) = match stems3 {
            Some((stems3, rendered)) => (Some(stems3), Some(rendered)),
            None => (None, None),
        };
        let rendered = if let Some(r) = rendered {
            r
        } else if super::view3::is_3d(&scene) {
            let view = self.view.unwrap_or(View::DEFAULT);
            super::view3::render_view(&scene, view, &self.look, &self.image, out, progress)?
        } else {
            super::render_tree(
                &scene,
                &self.look,
                &self.image,
                !tree_left_out,
                out,
                progress,
            )?
        };
        let stroke = super::style(&scene, &self.look).stroke;
        let view = super::layout_view(&scene, false).0;
        warnings.extend(scene.warnings);
        warnings.extend(rendered.warnings);
        Ok(Drawn {
            segments: rendered.segments,
            count: rendered.count,
            grown,
            od,
            trace,
            view,
            warnings,
            stroke,
            tree_left_out,
            stems3,
        })
    }

    /// Writes the input as a mesh in `format` (docs/3d.md): an OD grown
    /// first, an L-system at its depth (a 2D one, and any tree, lifted to
    /// z = 0); returns what was written with the warnings.
    pub fn mesh(
        &self,
        format: MeshFormat,
        out: &mut dyn Write,
        progress: &mut dyn Progress,
    ) -> Result<super::Meshed, Diagnostics> {
        let (loaded, mut warnings) = self.open()?;
        let req = self.scene_request(&loaded)?;
        let scene = super::scene(loaded, &req, progress)?;
        let mut meshed = super::view3::mesh(&scene, &self.look, format, &self.mesh, out, progress)?;
        warnings.extend(scene.warnings);
        warnings.append(&mut meshed.warnings);
        meshed.warnings = warnings;
        Ok(meshed)
    }

    /// Grows an OD into a BED and writes its canonical text. Any other
    /// input is refused with a diagnostic that says what to do.
    /// Returns it with the warnings: options that do nothing, then the
    /// growth's own.
    pub fn compile(
        &self,
        progress: &mut dyn Progress,
    ) -> Result<(Compiled, Vec<Diagnostic>), Diagnostics> {
        let (loaded, mut warnings) = self.open()?;
        let (_, grow) = self.options(&design(&loaded))?;
        let compiled = super::compile(&loaded, &grow, progress)?;
        warnings.extend(compiled.grown.warnings.iter().cloned());
        Ok((compiled, warnings))
    }

    /// Writes the derived word to `out` (see [`super::expand`]); returns
    /// the warnings.
    pub fn expand(
        &self,
        out: &mut dyn Write,
        progress: &mut dyn Progress,
    ) -> Result<Vec<Diagnostic>, Diagnostics> {
        let (loaded, mut warnings) = self.open()?;
        let req = self.scene_request(&loaded)?;
        let scene = super::scene(loaded, &req, progress)?;
        super::expand(&scene, out, progress)?;
        warnings.extend(scene.warnings);
        Ok(warnings)
    }

    /// `stlc check`'s summary and warnings (see [`super::check`]).
    pub fn check(&self) -> Result<super::Checked, Diagnostics> {
        let (loaded, mut warnings) = self.open()?;
        let (_, grow) = self.options(&design(&loaded))?;
        let checked = super::check(&loaded, &grow)?;
        warnings.extend(checked.warnings);
        Ok(super::Checked {
            summary: checked.summary,
            warnings,
        })
    }

    /// `stlc stats`'s text (or JSON) and warnings (see [`super::stats`]).
    pub fn stats(&self, json: bool) -> Result<(String, Vec<Diagnostic>), Diagnostics> {
        let (loaded, warnings) = self.open()?;
        let (limits, _) = self.options(&Design::default())?;
        let text = super::stats(&loaded, self.depth, json, &limits)?;
        Ok((text, warnings))
    }
}

/// What an OD's file keeps of its growth (`O=`, `V=`, `M=`); nothing for
/// other inputs.
fn design(loaded: &Loaded) -> Design {
    match loaded {
        Loaded::Od(d) => d.params.design,
        _ => Design::default(),
    }
}

/// Whether the input is a tree with a LAYOUT.
fn has_layout(loaded: &Loaded) -> bool {
    match loaded {
        Loaded::Od(d) => d.layout.is_some(),
        Loaded::Bed(b) => b.description().layout.is_some(),
        Loaded::Lsys(_) => false,
    }
}
