//! The commands: read the input, call the library, write the output, report.

use std::io::Write;
use std::process::ExitCode;

use stlc::bed::Bed;
use stlc::color::Rgb;
use stlc::diag::{Diagnostic, Diagnostics, ErrorKind, io_error};
use stlc::grow::{GrowOptions, GrowthOrder};
use stlc::interpret::Derivation;
use stlc::model::lsys::{Background, LSystem};
use stlc::model::{Description, Format};
use stlc::progress::{Phase, Progress};
use stlc::render::{self, ImageFormat, RenderOptions, Style, Width};
use stlc::syntax::{self, InputKind};
use stlc::turtle::{BBox, Fill, Turtle};
use stlc::{Limits, Severity};

use super::args::{
    CheckArgs, Cli, Command, CompileArgs, ExpandArgs, FormatArg, FromKind, GrowArgs, InputArgs,
    RenderArgs, StatsArgs,
};
use super::io::{Input, Output, sibling};
use super::progress::Bar;
use super::report::{self, SourceText};

/// The input as read: its name and text, kept for diagnostics.
struct Source {
    name: String,
    text: String,
}

/// What a command produced besides its output: warnings to show.
type Outcome = Result<Vec<Diagnostic>, Diagnostics>;

/// Runs one command and reports; returns the exit code.
pub fn run(cli: &Cli, color: bool) -> ExitCode {
    let mut source = Source {
        name: String::new(),
        text: String::new(),
    };
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

/// A parsed input.
enum Loaded {
    Lsys(LSystem),
    Stl(Description),
    Bed(Bed),
}

/// Reads and parses the input named by `args`.
fn load(args: &InputArgs, limits: &Limits, source: &mut Source) -> Result<Loaded, Diagnostics> {
    let input = Input::parse(&args.input);
    source.name = input.display_name();
    let bytes = input.read(limits.max_input_bytes)?;
    let kind = match args.from {
        Some(FromKind::Od) => InputKind::Od,
        Some(FromKind::Bed) => InputKind::Bed,
        Some(FromKind::Lsys) => InputKind::Lsys,
        None => match &input {
            Input::Path(p) => match InputKind::from_path(p) {
                Some(k) => k,
                None => sniff(&bytes).ok_or_else(|| {
                    Diagnostic::error(ErrorKind::Io(format!(
                        "cannot tell what kind of file `{}` is",
                        p.display()
                    )))
                    .with_help("name it .od, .bed or .lsys, or say --from od|bed|lsys")
                })?,
            },
            Input::Stdin => sniff(&bytes).unwrap_or(InputKind::Od),
        },
    };
    let text = syntax::precheck(&bytes, limits)?;
    source.text = text.to_string();
    match kind {
        InputKind::Lsys => syntax::lsys::parse(text, limits).map(Loaded::Lsys),
        InputKind::Od => syntax::stl::parse(text, Format::Od, limits).map(Loaded::Stl),
        InputKind::Bed => {
            let desc = syntax::stl::parse(text, Format::Bed, limits)?;
            Ok(Loaded::Bed(Bed::new(desc, limits)?))
        }
    }
}

/// Guesses the kind of unnamed input: `.lsys` if its first word is an
/// `.lsys` key, `.bed` if it has `{` terms, else `.od`.
fn sniff(bytes: &[u8]) -> Option<InputKind> {
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

/// The depth to derive an L-system to.
fn depth_of(sys: &LSystem, depth: Option<u32>, limits: &Limits) -> Result<u32, Diagnostics> {
    let d = depth.or(sys.generations).ok_or_else(|| {
        Diagnostic::error(ErrorKind::Lsys("no derivation depth".into()))
            .with_help("add a line `generations N` to the file, or pass --depth N")
    })?;
    limits.check_depth(d)?;
    Ok(d)
}

/// Grows an OD into a BED, returning it with growth warnings.
fn grow(
    od: &Description,
    growth: GrowthOrder,
    g: &GrowArgs,
    limits: &Limits,
    quiet: bool,
) -> Result<(Bed, Vec<Diagnostic>), Diagnostics> {
    let opts = GrowOptions {
        growth,
        clearance: g.clearance,
        limits: *limits,
        max_stems_explicit: g.max_stems.is_some(),
    };
    let mut bar = Bar::new(quiet);
    let grown = stlc::grow::grow(od, &opts, &mut Phase::new(&mut bar, "growing"))?;
    bar.finish();
    Ok((grown.bed, grown.warnings))
}

fn render(a: &RenderArgs, quiet: bool, source: &mut Source) -> Outcome {
    let limits = a.limits.limits(a.grow.max_stems);
    let loaded = load(&a.input, &limits, source)?;
    let input = Input::parse(&a.input.input);
    let format = match (a.format, &a.output) {
        (Some(FormatArg::Png), _) => ImageFormat::Png,
        (Some(FormatArg::Svg), _) => ImageFormat::Svg,
        (None, Some(o)) => match Output::parse(o).extension().as_deref() {
            Some("svg") => ImageFormat::Svg,
            _ => ImageFormat::Png,
        },
        (None, None) => ImageFormat::Png,
    };
    let ext = match format {
        ImageFormat::Png => "png",
        ImageFormat::Svg => "svg",
    };
    let output = match &a.output {
        Some(o) => Output::parse(o),
        None => sibling(&input, ext).ok_or_else(|| {
            Diagnostic::error(ErrorKind::Io("no output named".into()))
                .with_help("reading standard input, say where the picture goes: -o tree.png, or -o - for standard output")
        })?,
    };
    if format == ImageFormat::Png && output.is_terminal() {
        return Err(Diagnostic::error(ErrorKind::Io(
            "refusing to write a PNG to a terminal".into(),
        ))
        .with_help("redirect standard output to a file, or use -o tree.png")
        .into());
    }
    let stroke = a
        .stroke
        .as_deref()
        .map(|c| colour(c, "--stroke"))
        .transpose()?;
    let background = match a.background.as_deref() {
        None => None,
        Some("none") => Some(None),
        Some(c) => Some(Some(colour(c, "--background")?)),
    };
    let opts = RenderOptions {
        format,
        size: a.size,
        max_svg_segments: a.max_svg_segments,
    };
    let strategy: Derivation = a.strategy.into();
    let mut bar = Bar::new(quiet);
    let mut warnings = Vec::new();
    match loaded {
        Loaded::Lsys(sys) => {
            let depth = depth_of(&sys, a.depth, &limits)?;
            let style = Style {
                stroke: stroke.or(sys.color).unwrap_or(Rgb::BLACK),
                background: background.unwrap_or(match sys.background {
                    Background::White => Some(Rgb::WHITE),
                    Background::None => None,
                    Background::Color(c) => Some(c),
                }),
                width: Width::Pixels(sys.width),
            };
            let mut drawing = |t: &mut dyn Turtle, p: &mut dyn Progress| {
                stlc::interpret::lsys::draw(&sys, depth, strategy, &limits, t, p)
            };
            output.write_with(|out| {
                render::render(&mut drawing, None, &[], &style, &opts, out, &mut bar)
            })?;
        }
        Loaded::Stl(_) | Loaded::Bed(_) => {
            // An OD grows first (the strategy is the growth strategy), then
            // its BED is streamed depth-first.
            let (bed, interp) = match loaded {
                Loaded::Stl(desc) => {
                    let growth = match strategy {
                        Derivation::Dfs => GrowthOrder::Dfs,
                        Derivation::Bfs => GrowthOrder::Bfs,
                    };
                    let (bed, w) = grow(&desc, growth, &a.grow, &limits, quiet)?;
                    warnings.extend(w);
                    (bed, Derivation::Dfs)
                }
                Loaded::Bed(bed) => (bed, strategy),
                Loaded::Lsys(_) => unreachable!("matched above"),
            };
            let style = Style {
                stroke: stroke.unwrap_or(TREE_BROWN),
                background: background.unwrap_or(Some(Rgb::WHITE)),
                width: Width::Canvas(bed.description().params.width),
            };
            let (view, underlay) = layout_view(bed.description(), a.show_layout);
            let mut drawing = |t: &mut dyn Turtle, p: &mut dyn Progress| {
                stlc::interpret::bed::draw(&bed, interp, &limits, t, p)
            };
            output.write_with(|out| {
                render::render(&mut drawing, view, &underlay, &style, &opts, out, &mut bar)
            })?;
        }
    }
    bar.finish();
    Ok(warnings)
}

/// The default stroke of STL trees: a dark bark brown.
const TREE_BROWN: Rgb = Rgb::new(0x4a, 0x2c, 0x12);

/// The canvas area of a layout (its shapes' bounds) and, if asked, its
/// shapes as fills.
fn layout_view(desc: &Description, show: bool) -> (Option<BBox>, Vec<Fill>) {
    let Some(layout) = &desc.layout else {
        return (None, Vec::new());
    };
    let bbox = stlc::layout::layout_bbox(layout);
    let fills = if show {
        stlc::layout::fills(layout)
    } else {
        Vec::new()
    };
    (bbox, fills)
}

fn colour(text: &str, flag: &str) -> Result<Rgb, Diagnostics> {
    Rgb::parse(text).ok_or_else(|| {
        let mut d = Diagnostic::error(ErrorKind::Io(format!("{flag}: unknown colour `{text}`")));
        d = match Rgb::suggest(text) {
            Some(s) => d.with_help(format!(
                "did you mean `{s}`? Colours are #rrggbb or Delphi names"
            )),
            None => d.with_help("colours are #rrggbb or Delphi names such as clGreen"),
        };
        d.into()
    })
}

fn compile(a: &CompileArgs, quiet: bool, source: &mut Source) -> Outcome {
    let limits = a.limits.limits(a.grow.max_stems);
    let loaded = load(&a.input, &limits, source)?;
    let desc =
        match loaded {
            Loaded::Stl(desc) => desc,
            Loaded::Lsys(_) => {
                return Err(Diagnostic::error(ErrorKind::Io(
                    "compile grows Outline Descriptions (.od); this is a classic L-system".into(),
                ))
                .with_help("draw it with `stlc render`, or print its word with `stlc expand`")
                .into());
            }
            Loaded::Bed(_) => return Err(Diagnostic::error(ErrorKind::Io(
                "compile grows Outline Descriptions (.od); this is already a BED".into(),
            ))
            .with_help(
                "draw it with `stlc render`; if it is an outline, name it .od or pass --from od",
            )
            .into()),
        };
    let growth = match a.strategy {
        super::args::StrategyArg::Dfs => GrowthOrder::Dfs,
        super::args::StrategyArg::Bfs => GrowthOrder::Bfs,
    };
    let (bed, warnings) = grow(&desc, growth, &a.grow, &limits, quiet)?;
    let text = stlc::bed::write::write(bed.description());
    let input = Input::parse(&a.input.input);
    let output = match &a.output {
        Some(o) => Output::parse(o),
        None => sibling(&input, "bed").unwrap_or(Output::Stdout),
    };
    output.write_with(|out| {
        out.write_all(text.as_bytes())
            .map_err(|e| io_error(&e, "cannot write the BED").into())
    })?;
    Ok(warnings)
}

fn expand(a: &ExpandArgs, quiet: bool, source: &mut Source) -> Outcome {
    let limits = a.limits.limits(a.grow.max_stems);
    let loaded = load(&a.input, &limits, source)?;
    let output = Output::parse(&a.output);
    let strategy: Derivation = a.strategy.into();
    let mut bar = Bar::new(quiet);
    let mut warnings = Vec::new();
    match loaded {
        Loaded::Lsys(sys) => {
            let depth = depth_of(&sys, a.depth, &limits)?;
            output.write_with(|out| {
                stlc::interpret::lsys::expand(&sys, depth, strategy, &limits, out, &mut bar)
            })?;
        }
        Loaded::Stl(_) | Loaded::Bed(_) => {
            let bed = match loaded {
                Loaded::Stl(desc) => {
                    let (bed, w) = grow(&desc, GrowthOrder::Bfs, &a.grow, &limits, quiet)?;
                    warnings.extend(w);
                    bed
                }
                Loaded::Bed(bed) => bed,
                Loaded::Lsys(_) => unreachable!("matched above"),
            };
            output.write_with(|out| {
                stlc::interpret::bed::expand(&bed, strategy, &limits, out, &mut bar)
            })?;
        }
    }
    bar.finish();
    Ok(warnings)
}

fn stats(a: &StatsArgs, source: &mut Source) -> Outcome {
    let limits = a.limits.limits(None);
    let loaded = load(&a.input, &limits, source)?;
    let Loaded::Lsys(sys) = loaded else {
        return Err(Diagnostic::error(ErrorKind::Io(
            "stats counts classic L-system words (.lsys)".into(),
        ))
        .with_help("for an .od or .bed, `stlc check` prints its rules, terms and stem count")
        .into());
    };
    let depth = depth_of(&sys, a.depth, &limits)?;
    let stats = stlc::interpret::stats::stats(&sys, depth, &limits)?;
    let text = if a.json {
        stats.to_json()
    } else {
        stats.to_text()
    };
    print_out(&text)?;
    Ok(Vec::new())
}

fn check(a: &CheckArgs, source: &mut Source) -> Outcome {
    let limits = a.limits.limits(None);
    let loaded = load(&a.input, &limits, source)?;
    let text = match &loaded {
        Loaded::Lsys(sys) => summary::lsys(sys),
        Loaded::Stl(desc) => summary::stl(desc, None, &limits)?,
        Loaded::Bed(bed) => summary::stl(bed.description(), Some(bed), &limits)?,
    };
    print_out(&text)?;
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

/// `stlc check` summaries.
mod summary {
    use std::fmt::Write as _;

    use geo::Area;

    use stlc::Limits;
    use stlc::diag::Diagnostics;
    use stlc::interpret::Derivation;
    use stlc::model::lsys::LSystem;
    use stlc::model::{Description, Format, SeedItem};
    use stlc::progress::NoProgress;
    use stlc::turtle::Counter;

    pub fn lsys(sys: &LSystem) -> String {
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

    pub fn stl(
        desc: &Description,
        bed: Option<&stlc::bed::Bed>,
        limits: &Limits,
    ) -> Result<String, Diagnostics> {
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
        let seed = desc.effective_seed();
        let terms = seed
            .as_ref()
            .map(|s| {
                s.items
                    .iter()
                    .filter(|i| matches!(i, SeedItem::Term(_) | SeedItem::Repeat(_)))
                    .count()
            })
            .unwrap_or(0);
        let written = if desc.seed.is_some() {
            ""
        } else {
            " (default: F and the first rule)"
        };
        let _ = writeln!(s, "  seed terms  {terms}{written}");
        if let Some(bed) = bed {
            let mut count = Counter::default();
            stlc::interpret::bed::draw(bed, Derivation::Dfs, limits, &mut count, &mut NoProgress)?;
            let _ = writeln!(s, "  stems       {}", count.0);
        }
        match &desc.layout {
            Some(l) => {
                let area =
                    match stlc::grow::region::Region::from_layout(l, limits.max_layout_vertices) {
                        Ok(r) => format!("{:.1} square units", r.area().unsigned_area()),
                        Err(e)
                            if e.iter()
                                .any(|d| matches!(d.kind, stlc::diag::ErrorKind::Limit { .. })) =>
                        {
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
}
