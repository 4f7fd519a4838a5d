//! The commands: map arguments to library requests ([`stlc::pipeline`]),
//! read the input, write the output, report. No pipeline logic lives here.

use std::io::Write;
use std::process::ExitCode;

use stlc::diag::{Diagnostic, Diagnostics, ErrorKind, RenderError, Severity, io_error};
use stlc::pipeline::{
    self, GrowthOrder, ImageFormat, Limits, Look, MeshFormat, MeshOptions, Progress as _,
    RenderOptions, Request, Rgb, ShowLayout,
};

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
        return crate::serve::run(&a.config(), color);
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

/// Reads the input named by `args` into a request with the input options
/// and `limits`: every command starts here.
fn request(args: &InputArgs, limits: Limits, source: &mut Source) -> Result<Request, Diagnostics> {
    let input = Input::parse(&args.input);
    source.name = input.display_name();
    let bytes = input.read(limits.max_input_bytes)?;
    // Keep the text for diagnostics, whatever the library then says of it
    // (a nesting error points into it); text that is not UTF-8 has none.
    if let Ok(text) = std::str::from_utf8(&bytes) {
        source.text = text.to_string();
    }
    Ok(Request {
        name: match input {
            Input::Path(p) => Some(p),
            Input::Stdin => None,
        },
        kind: args.from,
        seed: args.seed,
        limits,
        ..Request::new(bytes)
    })
}

/// The request with the growth flags (`order`: `--growth` or an alias of
/// it).
fn with_growth(req: Request, order: Option<GrowthOrder>, g: &GrowArgs) -> Request {
    Request {
        growth: order,
        clearance: g.clearance,
        max_stems: g.max_stems,
        ..req
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
    let named = a
        .output
        .as_deref()
        .and_then(|o| std::path::Path::new(o).extension())
        .and_then(|e| MeshFormat::from_extension(&e.to_string_lossy()));
    if a.solid && a.mesh.is_none() && named.is_none() {
        if a.output.is_none() && a.format.is_none() {
            return render_mesh(a, MeshFormat::Stl, limits, quiet, source);
        }
        return Err(Diagnostic::error(RenderError::SolidUsage {
            message: "--solid writes one closed body as .stl, .3mf or .glb, not a picture".into(),
        })
        .with_help("name the output tree.stl, tree.3mf or tree.glb (or give --mesh stl with -o -)")
        .into());
    }
    match (a.mesh, named) {
        (Some(m), Some(n)) if m != n => {
            return Err(Diagnostic::error(RenderError::FormatMismatch {
                format: m.extension().into(),
                path: a.output.clone().unwrap_or_default(),
            })
            .with_help("leave out --mesh (the extension decides), or name the output to match")
            .into());
        }
        (Some(format), _) | (None, Some(format)) if a.format.is_none() => {
            return render_mesh(a, format, limits, quiet, source);
        }
        _ => {}
    }
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
        show_layout: if a.show_layout {
            ShowLayout::Yes
        } else {
            ShowLayout::No
        },
    };
    let req = Request {
        derivation: a.derivation,
        depth: a.depth,
        look,
        image: RenderOptions {
            format,
            size: a.size,
            max_svg_segments: a.max_svg_segments,
            exact: a.exact,
            threads: a.threads.map_or_else(
                || std::thread::available_parallelism().map_or(1, |n| n.get()),
                usize::from,
            ),
        },
        view: a.view,
        ..with_growth(request(&a.input, limits, source)?, a.grow.growth, &a.grow)
    };
    let mut bar = Bar::new(quiet);
    let mut drawn = None;
    output.write_with(|out| {
        drawn = Some(req.render(out, &mut bar)?);
        Ok(())
    })?;
    bar.finish();
    Ok(drawn.map(|d| d.warnings).unwrap_or_default())
}

/// `render -o x.glb|x.gltf|x.obj` (or `--solid -o x.stl|x.3mf|x.glb`):
/// the input as a mesh (docs/3d.md).
fn render_mesh(
    a: &RenderArgs,
    format: MeshFormat,
    limits: Limits,
    quiet: bool,
    source: &mut Source,
) -> Outcome {
    let input = Input::parse(&a.input.input);
    let output = match &a.output {
        Some(o) => Output::parse(o),
        None => sibling(&input, format.extension()).ok_or_else(|| {
            Diagnostic::error(FrontEndError::NoOutput).with_help(
                "reading standard input, say where the mesh goes: -o tree.glb, or -o - for standard output",
            )
        })?,
    };
    let binary = match format {
        MeshFormat::Glb => Some("glTF"),
        MeshFormat::Stl => Some("STL"),
        MeshFormat::ThreeMf => Some("3MF"),
        MeshFormat::Gltf | MeshFormat::Obj => None,
    };
    if let Some(name) = binary
        && output.is_terminal()
    {
        let ext = format.extension();
        return Err(
            Diagnostic::error(FrontEndError::BinaryToTerminal { format: name })
                .with_help(format!(
                    "a .{ext} is binary: redirect standard output to a file, or use -o tree.{ext}"
                ))
                .into(),
        );
    }
    not_the_input(&input, &output)?;
    let req = Request {
        derivation: a.derivation,
        depth: a.depth,
        look: Look {
            stroke: a
                .stroke
                .as_deref()
                .map(|c| colour(c, "--stroke"))
                .transpose()?,
            ..Look::default()
        },
        view: a.view,
        mesh: MeshOptions {
            sides: a.sides,
            unit: a.unit,
            max_triangles: a.max_triangles,
            solid: a.solid,
        },
        ..with_growth(request(&a.input, limits, source)?, a.grow.growth, &a.grow)
    };
    let mut bar = Bar::new(quiet);
    let mut warnings = Vec::new();
    output.write_with(|out| {
        warnings = req.mesh(format, out, &mut bar)?.warnings;
        Ok(())
    })?;
    bar.finish();
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
    let req = with_growth(
        request(&a.input, limits, source)?,
        a.strategy.or(a.grow.growth),
        &a.grow,
    );
    let mut bar = Bar::new(quiet);
    let (compiled, warnings) = req.compile(&mut bar)?;
    bar.finish();
    output.write_with(|out| {
        out.write_all(compiled.text.as_bytes())
            .map_err(|e| io_error(&e, "cannot write the BED").into())
    })?;
    let mut all = Vec::new();
    if let Some(order) = a.strategy {
        all.push(
            Diagnostic::warning(FrontEndError::StrategyMeansGrowth)
                .with_help(format!("write --growth {order}: on render and expand, --strategy is the derivation order, which cannot change a tree")),
        );
    }
    all.extend(warnings);
    Ok(all)
}

fn expand(a: &ExpandArgs, quiet: bool, source: &mut Source) -> Outcome {
    let limits = a.derive_limits.limits(&a.limits, a.grow.max_stems);
    let input = Input::parse(&a.input.input);
    let output = Output::parse(&a.output);
    not_the_input(&input, &output)?;
    let req = Request {
        derivation: a.derivation,
        depth: a.depth,
        ..with_growth(request(&a.input, limits, source)?, a.grow.growth, &a.grow)
    };
    let mut bar = Bar::new(quiet);
    let mut warnings = Vec::new();
    output.write_with(|out| {
        warnings = req.expand(out, &mut bar)?;
        Ok(())
    })?;
    bar.finish();
    Ok(warnings)
}

fn stats(a: &StatsArgs, source: &mut Source) -> Outcome {
    let limits = a.limits.limits(Some(&a.symbol_limits), None, None, None);
    let req = Request {
        depth: a.depth,
        ..request(&a.input, limits, source)?
    };
    let (text, warnings) = req.stats(a.json)?;
    print_out(&text)?;
    Ok(warnings)
}

fn check(a: &CheckArgs, source: &mut Source) -> Outcome {
    let limits = a.limits.limits(
        Some(&a.symbol_limits),
        None,
        Some(&a.layout_limits),
        a.grow.max_stems,
    );
    let req = with_growth(request(&a.input, limits, source)?, a.grow.growth, &a.grow);
    let checked = req.check()?;
    print_out(&checked.summary)?;
    Ok(checked.warnings)
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
