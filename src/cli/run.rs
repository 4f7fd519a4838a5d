//! The commands: map arguments to library requests ([`stlc::pipeline`]),
//! read the input, write the output, report. No pipeline logic lives here.

use std::io::Write;
use std::process::ExitCode;

use stlc::Severity;
use stlc::color::Rgb;
use stlc::diag::{Diagnostic, Diagnostics, ErrorKind, io_error};
use stlc::grow::{GrowOptions, GrowthOrder};
use stlc::interpret::Derivation;
use stlc::limits::Limits;
use stlc::pipeline::{self, Given, Loaded, Look, Scene, SceneRequest};
use stlc::progress::Progress as _;
use stlc::render::{ImageFormat, RenderOptions};

use super::args::{
    CheckArgs, Cli, Command, CompileArgs, ExpandArgs, GrowArgs, InputArgs, RenderArgs, StatsArgs,
};
use super::progress::Bar;
use crate::frontend::error::FrontEndError;
use crate::frontend::io::{Input, Output, same_file, sibling};
use crate::frontend::report::{self, SourceText};

/// The input as read: its name and text, kept for diagnostics.
#[derive(Default)]
struct Source {
    name: String,
    text: String,
}

/// What a command produced besides its output: warnings to show.
type Outcome = Result<Vec<Diagnostic>, Diagnostics>;

/// Runs one command and reports; returns the exit code.
pub fn run(cli: &Cli, color: bool) -> ExitCode {
    if let Command::Serve(a) = &cli.command {
        return crate::serve::run(a, cli.quiet, color);
    }
    let mut source = Source::default();
    let input = match &cli.command {
        Command::Render(a) => &a.input.input,
        Command::Compile(a) => &a.input.input,
        Command::Expand(a) => &a.input.input,
        Command::Stats(a) => &a.input.input,
        Command::Check(a) => &a.input.input,
        Command::Serve(_) => unreachable!("served above"),
    };
    // Named before any work, so every diagnostic says which input it is about.
    source.name = Input::parse(input).display_name();
    let outcome = match &cli.command {
        Command::Render(a) => render(a, cli.quiet, &mut source),
        Command::Compile(a) => compile(a, cli.quiet, &mut source),
        Command::Expand(a) => expand(a, cli.quiet, &mut source),
        Command::Stats(a) => stats(a, &mut source),
        Command::Check(a) => check(a, &mut source),
        Command::Serve(_) => unreachable!("served above"),
    };
    let src = SourceText {
        name: &source.name,
        text: &source.text,
    };
    let mut stderr = std::io::stderr().lock();
    match outcome {
        Ok(warnings) => {
            if !cli.quiet {
                for w in &warnings {
                    report::write(&mut stderr, w, Some(&src), color);
                }
            }
            ExitCode::SUCCESS
        }
        Err(diags) => {
            if diags
                .iter()
                .any(|d| matches!(d.kind, ErrorKind::BrokenPipe))
            {
                // The reader went away (`stlc expand ... | head`): not an error.
                return ExitCode::SUCCESS;
            }
            for d in diags.iter() {
                if d.severity == Severity::Warning && cli.quiet {
                    continue;
                }
                report::write(&mut stderr, d, Some(&src), color);
            }
            if diags.iter().any(|d| d.is_error() && d.kind.is_usage()) {
                // A contradictory command line, like clap's own errors.
                ExitCode::from(2)
            } else {
                ExitCode::FAILURE
            }
        }
    }
}

/// Reads the input named by `args` and loads it with the library.
fn load(args: &InputArgs, limits: &Limits, source: &mut Source) -> Result<Loaded, Diagnostics> {
    let input = Input::parse(&args.input);
    source.name = input.display_name();
    let bytes = input.read(limits.max_input_bytes)?;
    let kind = match (args.from, &input) {
        (Some(kind), _) => kind,
        (None, Input::Path(p)) => pipeline::detect_kind(Some(p), &bytes)?,
        (None, Input::Stdin) => pipeline::detect_kind(None, &bytes)?,
    };
    // Keep the text for diagnostics, whatever the library then says of it
    // (a nesting error points into it); text that is not UTF-8 has none.
    if let Ok(text) = std::str::from_utf8(&bytes) {
        source.text = text.to_string();
    }
    Ok(pipeline::load(&bytes, kind, limits)?.seeded(args.seed))
}

/// The growth options the growth flags ask for (`order`: `--growth` or an
/// alias of it; default bfs).
fn grow_options(
    order: Option<GrowthOrder>,
    g: &GrowArgs,
    seed: Option<u64>,
    limits: &Limits,
) -> GrowOptions {
    GrowOptions {
        seed: seed.unwrap_or(0),
        growth: order.unwrap_or_default(),
        clearance: g.clearance,
        limits: *limits,
        max_stems_explicit: g.max_stems.is_some(),
    }
}

/// Loads the input and decides its scene (growing an OD), with warnings for
/// the flags that do nothing for it: what `render` and `expand` share.
fn scene(
    input: &InputArgs,
    grow: &GrowArgs,
    strategy: Derivation,
    depth: Option<u32>,
    limits: &Limits,
    quiet: bool,
    source: &mut Source,
) -> Result<(Scene, Vec<Diagnostic>), Diagnostics> {
    let loaded = load(input, limits, source)?;
    let warnings = pipeline::ignored_flags(&loaded, &given(grow, depth, input.seed));
    let req = SceneRequest {
        grow: grow_options(grow.growth, grow, input.seed, limits),
        derivation: strategy,
        depth,
        limits: *limits,
    };
    let mut bar = Bar::new(quiet);
    let scene = pipeline::scene(loaded, &req, &mut bar)?;
    bar.finish();
    Ok((scene, warnings))
}

/// The growth, depth and seed flags given explicitly.
fn given(g: &GrowArgs, depth: Option<u32>, seed: Option<u64>) -> Given {
    Given {
        growth: g.growth.is_some(),
        clearance: g.clearance.is_some(),
        max_stems: g.max_stems.is_some(),
        depth: depth.is_some(),
        seed: seed.is_some(),
    }
}

/// Refuses an output that is the input file, before any work.
fn not_the_input(input: &Input, output: &Output) -> Result<(), Diagnostics> {
    if !same_file(input, output) {
        return Ok(());
    }
    let name = |o: &Output| match o {
        Output::Path(p) => p.display().to_string(),
        Output::Stdout => "-".into(),
    };
    Err(Diagnostic::error(FrontEndError::OutputIsInput {
        input: input.display_name(),
        output: name(output),
    })
    .with_help("name another output file with -o")
    .into())
}

fn render(a: &RenderArgs, quiet: bool, source: &mut Source) -> Outcome {
    let limits = a.derive_limits.limits(&a.limits, a.grow.max_stems);
    let input = Input::parse(&a.input.input);
    let format = pipeline::image_format(a.format, a.output.as_deref().filter(|o| *o != "-"))?;
    let ext = match format {
        ImageFormat::Png => "png",
        ImageFormat::Svg => "svg",
    };
    let output = match &a.output {
        Some(o) => Output::parse(o),
        None => sibling(&input, ext).ok_or_else(|| {
            Diagnostic::error(FrontEndError::NoOutput)
                .with_help("reading standard input, say where the picture goes: -o tree.png, or -o - for standard output")
        })?,
    };
    if format == ImageFormat::Png && output.is_terminal() {
        return Err(Diagnostic::error(FrontEndError::PngToTerminal)
            .with_help("redirect standard output to a file, or use -o tree.png")
            .into());
    }
    not_the_input(&input, &output)?;
    let look = Look {
        stroke: a
            .stroke
            .as_deref()
            .map(|c| colour(c, "--stroke"))
            .transpose()?,
        background: match a.background.as_deref() {
            None => None,
            Some("none") => Some(None),
            Some(c) => Some(Some(colour(c, "--background")?)),
        },
        show_layout: a.show_layout,
    };
    let opts = RenderOptions {
        format,
        size: a.size,
        max_svg_segments: a.max_svg_segments,
        exact: a.exact,
    };
    let (scene, mut warnings) = scene(
        &a.input, &a.grow, a.strategy, a.depth, &limits, quiet, source,
    )?;
    let mut bar = Bar::new(quiet);
    if a.show_layout && !scene.has_layout() {
        warnings.push(Diagnostic::warning(ErrorKind::IgnoredFlag {
            flag: "--show-layout".into(),
            reason: "this input has no LAYOUT to show".into(),
        }));
    }
    let mut rendered = None;
    output.write_with(|out| {
        rendered = Some(pipeline::render(&scene, &look, &opts, out, &mut bar)?);
        Ok(())
    })?;
    bar.finish();
    warnings.extend(scene.warnings);
    warnings.extend(rendered.map(|r| r.warnings).unwrap_or_default());
    Ok(warnings)
}

/// A colour given on the command line.
fn colour(text: &str, flag: &str) -> Result<Rgb, Diagnostics> {
    Rgb::parse(text).ok_or_else(|| {
        let d = Diagnostic::error(FrontEndError::UnknownColourFlag {
            flag: flag.into(),
            text: text.into(),
        });
        match Rgb::suggest(text) {
            Some(s) => d.with_help(format!(
                "did you mean `{s}`? Colours are #rrggbb or Delphi names"
            )),
            None => d.with_help("colours are #rrggbb or Delphi names such as clGreen"),
        }
        .into()
    })
}

fn compile(a: &CompileArgs, quiet: bool, source: &mut Source) -> Outcome {
    let limits = a
        .limits
        .limits(None, None, Some(&a.layout_limits), a.grow.max_stems);
    let input = Input::parse(&a.input.input);
    let output = match &a.output {
        Some(o) => Output::parse(o),
        None => sibling(&input, "bed").unwrap_or(Output::Stdout),
    };
    not_the_input(&input, &output)?;
    let loaded = load(&a.input, &limits, source)?;
    let opts = grow_options(a.strategy.or(a.grow.growth), &a.grow, a.input.seed, &limits);
    let mut bar = Bar::new(quiet);
    let compiled = pipeline::compile(&loaded, &opts, &mut bar)?;
    bar.finish();
    output.write_with(|out| {
        out.write_all(compiled.text.as_bytes())
            .map_err(|e| io_error(&e, "cannot write the BED").into())
    })?;
    let mut warnings = pipeline::ignored_flags(&loaded, &given(&a.grow, None, a.input.seed));
    warnings.extend(compiled.grown.warnings);
    Ok(warnings)
}

fn expand(a: &ExpandArgs, quiet: bool, source: &mut Source) -> Outcome {
    let limits = a.derive_limits.limits(&a.limits, a.grow.max_stems);
    let input = Input::parse(&a.input.input);
    let output = Output::parse(&a.output);
    not_the_input(&input, &output)?;
    let (scene, mut warnings) = scene(
        &a.input, &a.grow, a.strategy, a.depth, &limits, quiet, source,
    )?;
    let mut bar = Bar::new(quiet);
    output.write_with(|out| pipeline::expand(&scene, out, &mut bar))?;
    bar.finish();
    warnings.extend(scene.warnings);
    Ok(warnings)
}

fn stats(a: &StatsArgs, source: &mut Source) -> Outcome {
    let limits = a.limits.limits(Some(&a.symbol_limits), None, None, None);
    let loaded = load(&a.input, &limits, source)?;
    print_out(&pipeline::stats(&loaded, a.depth, a.json, &limits)?)?;
    let seed = Given {
        seed: a.input.seed.is_some(),
        ..Given::default()
    };
    Ok(pipeline::ignored_flags(&loaded, &seed))
}

fn check(a: &CheckArgs, source: &mut Source) -> Outcome {
    let limits = a.limits.limits(
        Some(&a.symbol_limits),
        None,
        Some(&a.layout_limits),
        a.grow.max_stems,
    );
    let loaded = load(&a.input, &limits, source)?;
    let mut warnings = pipeline::ignored_flags(&loaded, &given(&a.grow, None, a.input.seed));
    let checked = pipeline::check(
        &loaded,
        &grow_options(a.grow.growth, &a.grow, a.input.seed, &limits),
    )?;
    print_out(&checked.summary)?;
    warnings.extend(checked.warnings);
    Ok(warnings)
}

fn print_out(text: &str) -> Result<(), Diagnostics> {
    let mut out = std::io::stdout().lock();
    out.write_all(text.as_bytes())
        .and_then(|_| {
            if text.ends_with('\n') {
                Ok(())
            } else {
                out.write_all(b"\n")
            }
        })
        .and_then(|_| out.flush())
        .map_err(|e| io_error(&e, "cannot write to standard output").into())
}
