//! The commands: map arguments to library requests ([`stlc::pipeline`]),
//! read the input, write the output, report. No pipeline logic lives here.

use std::io::Write;
use std::process::ExitCode;

use stlc::color::Rgb;
use stlc::diag::{Diagnostic, Diagnostics, ErrorKind, io_error};
use stlc::grow::{GrowOptions, GrowthOrder};
use stlc::interpret::Derivation;
use stlc::limits::Limits;
use stlc::pipeline::{self, Loaded, Look, SceneRequest};
use stlc::progress::Progress as _;
use stlc::render::{ImageFormat, RenderOptions};
use stlc::syntax::InputKind;
use stlc::{Severity, syntax};

use super::args::{
    CheckArgs, Cli, Command, CompileArgs, ExpandArgs, FormatArg, FromKind, GrowArgs, InputArgs,
    RenderArgs, StatsArgs, StrategyArg,
};
use super::io::{Input, Output, sibling};
use super::progress::Bar;
use super::report::{self, SourceText};

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
    let mut source = Source::default();
    let outcome = match &cli.command {
        Command::Render(a) => render(a, cli.quiet, &mut source),
        Command::Compile(a) => compile(a, cli.quiet, &mut source),
        Command::Expand(a) => expand(a, cli.quiet, &mut source),
        Command::Stats(a) => stats(a, &mut source),
        Command::Check(a) => check(a, &mut source),
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
            ExitCode::FAILURE
        }
    }
}

/// Reads the input named by `args` and loads it with the library.
fn load(args: &InputArgs, limits: &Limits, source: &mut Source) -> Result<Loaded, Diagnostics> {
    let input = Input::parse(&args.input);
    source.name = input.display_name();
    let bytes = input.read(limits.max_input_bytes)?;
    let kind = match args.from {
        Some(FromKind::Od) => InputKind::Od,
        Some(FromKind::Bed) => InputKind::Bed,
        Some(FromKind::Lsys) => InputKind::Lsys,
        None => match &input {
            Input::Path(p) => pipeline::detect_kind(Some(p), &bytes)?,
            Input::Stdin => pipeline::detect_kind(None, &bytes)?,
        },
    };
    // Keep the text for diagnostics (if it is text: precheck says why not).
    if let Ok(text) = syntax::precheck(&bytes, limits) {
        source.text = text.to_string();
    }
    pipeline::load(&bytes, kind, limits)
}

/// The growth options the growth flags ask for.
fn grow_options(order: GrowthOrder, g: &GrowArgs, limits: &Limits) -> GrowOptions {
    GrowOptions {
        growth: order,
        clearance: g.clearance,
        limits: *limits,
        max_stems_explicit: g.max_stems.is_some(),
    }
}

fn growth_order(s: StrategyArg) -> GrowthOrder {
    match s {
        StrategyArg::Dfs => GrowthOrder::Dfs,
        StrategyArg::Bfs => GrowthOrder::Bfs,
    }
}

fn render(a: &RenderArgs, quiet: bool, source: &mut Source) -> Outcome {
    let limits = a.limits.limits(a.grow.max_stems);
    let loaded = load(&a.input, &limits, source)?;
    let input = Input::parse(&a.input.input);
    let format = match a.format {
        Some(FormatArg::Png) => ImageFormat::Png,
        Some(FormatArg::Svg) => ImageFormat::Svg,
        None => pipeline::format_for(a.output.as_deref()),
    };
    let ext = match format {
        ImageFormat::Png => "png",
        ImageFormat::Svg => "svg",
    };
    let output = match &a.output {
        Some(o) => Output::parse(o),
        None => sibling(&input, ext).ok_or_else(|| {
            Diagnostic::error(ErrorKind::NoOutput)
                .with_help("reading standard input, say where the picture goes: -o tree.png, or -o - for standard output")
        })?,
    };
    if format == ImageFormat::Png && output.is_terminal() {
        return Err(Diagnostic::error(ErrorKind::PngToTerminal)
            .with_help("redirect standard output to a file, or use -o tree.png")
            .into());
    }
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
    };
    // On `render`, --strategy is the growth order of an OD (whose BED is
    // then streamed depth-first) and the derivation of a BED or an L-system.
    let derivation = match loaded {
        Loaded::Od(_) => Derivation::Dfs,
        Loaded::Lsys(_) | Loaded::Bed(_) => a.strategy.into(),
    };
    let req = SceneRequest {
        grow: grow_options(growth_order(a.strategy), &a.grow, &limits),
        derivation,
        depth: a.depth,
        limits,
    };
    let mut bar = Bar::new(quiet);
    let scene = pipeline::scene(loaded, &req, &mut bar)?;
    bar.finish();
    output.write_with(|out| pipeline::render(&scene, &look, &opts, out, &mut bar))?;
    bar.finish();
    Ok(scene.warnings)
}

/// A colour given on the command line.
fn colour(text: &str, flag: &str) -> Result<Rgb, Diagnostics> {
    Rgb::parse(text).ok_or_else(|| {
        let d = Diagnostic::error(ErrorKind::UnknownColourFlag {
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
    let limits = a.limits.limits(a.grow.max_stems);
    let loaded = load(&a.input, &limits, source)?;
    let opts = grow_options(growth_order(a.strategy), &a.grow, &limits);
    let mut bar = Bar::new(quiet);
    let compiled = pipeline::compile(&loaded, &opts, &mut bar)?;
    bar.finish();
    let input = Input::parse(&a.input.input);
    let output = match &a.output {
        Some(o) => Output::parse(o),
        None => sibling(&input, "bed").unwrap_or(Output::Stdout),
    };
    output.write_with(|out| {
        out.write_all(compiled.text.as_bytes())
            .map_err(|e| io_error(&e, "cannot write the BED").into())
    })?;
    Ok(compiled.grown.warnings)
}

fn expand(a: &ExpandArgs, quiet: bool, source: &mut Source) -> Outcome {
    let limits = a.limits.limits(a.grow.max_stems);
    let loaded = load(&a.input, &limits, source)?;
    let output = Output::parse(&a.output);
    // On `expand`, --strategy is the derivation; an OD grows breadth-first.
    let req = SceneRequest {
        grow: grow_options(GrowthOrder::Bfs, &a.grow, &limits),
        derivation: a.strategy.into(),
        depth: a.depth,
        limits,
    };
    let mut bar = Bar::new(quiet);
    let scene = pipeline::scene(loaded, &req, &mut bar)?;
    bar.finish();
    output.write_with(|out| pipeline::expand(&scene, out, &mut bar))?;
    bar.finish();
    Ok(scene.warnings)
}

fn stats(a: &StatsArgs, source: &mut Source) -> Outcome {
    let limits = a.limits.limits(None);
    let loaded = load(&a.input, &limits, source)?;
    print_out(&pipeline::stats(&loaded, a.depth, a.json, &limits)?)?;
    Ok(Vec::new())
}

fn check(a: &CheckArgs, source: &mut Source) -> Outcome {
    let limits = a.limits.limits(None);
    let loaded = load(&a.input, &limits, source)?;
    print_out(&pipeline::check(&loaded, &limits)?)?;
    Ok(Vec::new())
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
