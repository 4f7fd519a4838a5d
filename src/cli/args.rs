//! The command line, as clap derive types. Doc comments are the help text:
//! the first paragraph shows with `-h`, all of it with `--help`.

use clap::{Args, Parser, Subcommand, ValueEnum};

use stlc::pipeline::{
    DEFAULT_MAX_SVG_SEGMENTS, DEFAULT_MAX_TRIANGLES, DEFAULT_SIDES, DEFAULT_UNIT, Derivation,
    GrowthOrder, ImageFormat, InputKind, Limits, MeshFormat, View,
};

/// Compile and render Structural Tree Language trees and classic L-systems.
///
/// stlc reads three kinds of text file:
///   .od    Outline Description: rules, a seed, and a LAYOUT outline the tree grows into
///   .bed   Branch-Expansion Description: the same with every branching decision written out
///   .lsys  classic L-system: generations, axiom, rule X SUCC, angle
///
/// Rules with several bodies choose by probability (`R1 (0.6): ...` in an
/// .od, `rule F (0.6) -> ...` in an .lsys): --seed N picks the plant, and
/// the same seed always draws the same one.
///
/// Use `-` for standard input or output. Exit status: 0 success, 1 the input
/// or the work failed (nothing is written), 2 usage error.
#[derive(Debug, Parser)]
#[command(
    name = "stlc",
    verbatim_doc_comment,
    version,
    max_term_width = 100,
    after_help = "Examples:\n  stlc render examples/koch-snowflake.lsys -o koch.png\n  stlc compile examples/2dtree.od -o 2dtree.bed --growth dfs\n  stlc render 2dtree.bed --show-layout -o 2dtree.svg\n  stlc stats examples/abop-1.24a.lsys --depth 57 --json\n  stlc render examples/grove.od --seed 7 --show-layout -o grove.png\n\nDocumentation: docs/ in the source tree (language.md, cli.md, limits.md)."
)]
pub struct Cli {
    /// What to do.
    #[command(subcommand)]
    pub command: Command,

    /// Colour in diagnostics: auto (when stderr is a terminal), always, never.
    #[arg(long, value_enum, default_value_t = ColorChoice::Auto, global = true)]
    pub color: ColorChoice,

    /// Print no warnings and no progress bar; errors are still printed.
    #[arg(short, long, global = true)]
    pub quiet: bool,
}

/// When to colour diagnostics.
#[derive(Debug, Clone, Copy, PartialEq, Eq, ValueEnum)]
pub enum ColorChoice {
    /// When stderr is a terminal and NO_COLOR is unset.
    Auto,
    /// Always.
    Always,
    /// Never.
    Never,
}

/// The subcommands.
#[derive(Debug, Subcommand)]
pub enum Command {
    /// Draw an .lsys, .od or .bed file to PNG or SVG.
    ///
    /// The picture is fitted to --size from a first bounding pass; a BED or
    /// OD with a LAYOUT uses the layout's canvas instead. An .od is grown
    /// first (--growth, default bfs), then drawn: `render tree.od` draws
    /// exactly what `render` of `compile tree.od` draws.
    ///
    /// Examples:
    ///   stlc render examples/koch-snowflake.lsys -o koch.png
    ///   stlc render examples/abop-1.24a.lsys --depth 6 --derivation bfs -o tree.svg
    ///   stlc render examples/2dtree.od --growth dfs --show-layout -o vine.png
    ///   cat tree.bed | stlc render - --from bed -f svg -o - > tree.svg
    #[command(verbatim_doc_comment)]
    Render(RenderArgs),

    /// Grow an Outline Description (.od) into a Branch-Expansion Description (.bed).
    ///
    /// Every growth point in the seed grows under space occupancy: a rule
    /// application succeeds only if all its stems lie inside the LAYOUT and
    /// keep the clearance from stems already grown. The result records every
    /// decision and is byte-identical for the same input and options.
    ///
    /// Examples:
    ///   stlc compile examples/2dtree.od -o 2dtree.bed
    ///   stlc compile examples/fig9.od --growth dfs -o -
    #[command(
        verbatim_doc_comment,
        mut_arg("input", |a| a.help("Outline Description (.od), or `-` for standard input")),
        mut_arg("from", |a| a.help("Read the input as this kind (only od grows; bed and lsys are refused)"))
    )]
    Compile(CompileArgs),

    /// Print the derived word: an .lsys's symbols at the depth, or a .bed's
    /// (or grown .od's) seed as drawing components only.
    ///
    /// Examples:
    ///   stlc expand examples/abop-1.24a.lsys --depth 2
    ///   stlc expand examples/paper-worked.bed
    #[command(verbatim_doc_comment)]
    Expand(ExpandArgs),

    /// Exact word length and symbol counts of an .lsys at any depth, and
    /// the extent of a unit-step turtle when the word is small enough to walk.
    ///
    /// Counts are exact big integers (memoised per symbol and depth), so
    /// depth 57 of F -> F[+F]F[-F]F prints its 41-digit length at once.
    ///
    /// Examples:
    ///   stlc stats examples/abop-1.24a.lsys --depth 5
    ///   stlc stats examples/abop-1.24a.lsys --depth 57 --json
    #[command(
        verbatim_doc_comment,
        mut_arg("input", |a| a.help("Classic L-system (.lsys), or `-` for standard input")),
        mut_arg("from", |a| a.help("Read the input as this kind (only lsys is counted)"))
    )]
    Stats(StatsArgs),

    /// Validate an .od, .bed or .lsys file and print a short summary.
    ///
    /// Answers "would compile and render succeed?": an .od is grown (with
    /// --growth, without drawing) and every check compile makes is made; a
    /// BED is validated and measured; the stems are counted from the measure.
    ///
    /// Examples:
    ///   stlc check examples/2dtree.od
    ///   stlc check tree.bed
    #[command(verbatim_doc_comment)]
    Check(CheckArgs),

    /// Open the Tree Maker in a web browser: edit an .od, draw its LAYOUT
    /// with the mouse, and watch the tree grow (also renders .bed and .lsys).
    ///
    /// Serves a page on 127.0.0.1 only and prints its address as the first
    /// line on standard output; Ctrl-C stops it. With FILE the page opens
    /// it and Save writes it back (atomically); without, it starts from an
    /// example and Save downloads. docs/serve.md describes the page and its
    /// HTTP API.
    ///
    /// Examples:
    ///   stlc serve examples/2dtree.od
    ///   stlc serve --port 8080
    #[command(verbatim_doc_comment)]
    Serve(ServeArgs),
}

/// `stlc serve`.
#[derive(Debug, Args)]
pub struct ServeArgs {
    /// The file to open and save (.od, .bed, .lsys); none: an example.
    pub file: Option<String>,

    /// Port on 127.0.0.1; 0 picks a free one.
    #[arg(long, value_name = "N", default_value_t = 8765)]
    pub port: u16,

    /// Most stems one growth may add; a page's max-stems above it is refused.
    #[arg(long, value_name = "N")]
    pub max_stems: Option<u64>,

    /// Most segments an SVG may hold.
    #[arg(long, value_name = "N", default_value_t = DEFAULT_MAX_SVG_SEGMENTS)]
    pub max_svg_segments: u64,

    /// Seconds one request's work may run before it stops with an error
    /// (work whose page has gone, or a newer edit replaced, stops at once).
    #[arg(long, value_name = "SECONDS", default_value_t = 30.0, value_parser = parse_budget)]
    pub time_budget: f64,

    /// Most heap memory, in MiB, the server holds for all requests together
    /// (one request may have half): a request that does not fit waits, then
    /// gets 503 "busy"; heavy work stops past it (docs/limits.md).
    #[arg(long, value_name = "MIB", default_value_t = 2048, value_parser = clap::value_parser!(u64).range(64..=1 << 30))]
    pub memory_budget: u64,

    #[command(flatten)]
    pub limits: LimitArgs,

    #[command(flatten)]
    pub derive_limits: DeriveLimitArgs,
}

/// A time budget: a number of seconds, more than 0 and at most a day.
fn parse_budget(s: &str) -> Result<f64, String> {
    match s.trim().parse::<f64>() {
        Ok(x) if x > 0.0 && x <= 86_400.0 => Ok(x),
        _ => Err(format!(
            "`{s}` is not a number of seconds from 0 (excluded) to 86400"
        )),
    }
}

/// The input file and how to read it.
#[derive(Debug, Args)]
pub struct InputArgs {
    /// Input file (.od, .bed, .lsys), or `-` for standard input.
    pub input: String,

    /// Input kind, when the extension does not tell (stdin, other names).
    #[arg(long, value_enum)]
    pub from: Option<InputKind>,

    /// Seed of stochastic rules: the same seed draws the same plant, another
    /// seed another one. Overrides an .lsys's `seed` key; an .od grows with
    /// seed 0 unless given. A .bed has its choices written out and ignores it.
    #[arg(long, value_name = "N")]
    pub seed: Option<u64>,
}

/// Limits every command takes: on reading the input. Each default is
/// explained in docs/limits.md.
#[derive(Debug, Args, Clone)]
pub struct LimitArgs {
    /// Largest input file in bytes (at most 4 GiB: positions are 32-bit).
    #[arg(long, value_name = "BYTES", default_value_t = Limits::default().max_input_bytes)]
    pub max_input: u64,
    /// Deepest nesting of brackets and braces accepted.
    #[arg(long, value_name = "N", default_value_t = Limits::default().max_nesting)]
    pub max_nesting: usize,
    /// Largest derivation depth, `generations`, or count in `[I n X]`.
    #[arg(long, value_name = "N", default_value_t = Limits::default().max_depth)]
    pub max_depth: u32,
    /// Most rule definitions plus top-level branches and fixed figures in
    /// an .od or .bed's RULE section.
    #[arg(long, value_name = "N", default_value_t = Limits::default().max_rule_parts)]
    pub max_rule_parts: usize,
    /// Most shapes in an .od or .bed's LAYOUT.
    #[arg(long, value_name = "N", default_value_t = Limits::default().max_layout_shapes)]
    pub max_layout_shapes: usize,
}

/// Limits of a traversal (commands that walk a derivation).
#[derive(Debug, Args, Clone)]
pub struct SymbolLimitArgs {
    /// Most symbols one traversal (render, expand, stats extent, a BED's
    /// expansion) may visit.
    #[arg(long, value_name = "N", default_value_t = Limits::default().max_symbols)]
    pub max_symbols: u64,
}

/// The limit of the bfs derivation (commands with `--derivation`).
#[derive(Debug, Args, Clone)]
pub struct WordLimitArgs {
    /// Most symbols the bfs derivation may hold in memory as one word.
    #[arg(long, value_name = "N", default_value_t = Limits::default().max_word)]
    pub max_word: u64,
}

/// The limit of a layout's outline (commands that grow an .od).
#[derive(Debug, Args, Clone)]
pub struct LayoutLimitArgs {
    /// Most vertices of a LAYOUT's outline: each shape (curves flattened) and
    /// the painted area after each shape.
    #[arg(long, value_name = "N", default_value_t = Limits::default().max_layout_vertices)]
    pub max_layout_vertices: usize,
}

/// The limits of commands that derive, grow and draw (`render`, `expand`).
#[derive(Debug, Args, Clone)]
pub struct DeriveLimitArgs {
    #[command(flatten)]
    pub symbols: SymbolLimitArgs,

    #[command(flatten)]
    pub word: WordLimitArgs,

    #[command(flatten)]
    pub layout: LayoutLimitArgs,
}

impl ServeArgs {
    /// The server's configuration these flags ask for.
    pub fn config(&self) -> crate::serve::Config {
        crate::serve::Config {
            file: self.file.clone(),
            port: self.port,
            limits: self.derive_limits.limits(&self.limits, self.max_stems),
            max_stems: self.max_stems,
            max_svg_segments: self.max_svg_segments,
            time_budget: std::time::Duration::from_secs_f64(self.time_budget),
            memory_budget: self.memory_budget << 20,
        }
    }
}

impl DeriveLimitArgs {
    /// All the limits, with `base` and the stem limit.
    pub fn limits(&self, base: &LimitArgs, stems: Option<u64>) -> Limits {
        base.limits(
            Some(&self.symbols),
            Some(&self.word),
            Some(&self.layout),
            stems,
        )
    }
}

impl LimitArgs {
    /// The limits these flags set, with the others from the groups a
    /// command takes (defaults where it takes none).
    pub fn limits(
        &self,
        symbols: Option<&SymbolLimitArgs>,
        word: Option<&WordLimitArgs>,
        layout: Option<&LayoutLimitArgs>,
        stems: Option<u64>,
    ) -> Limits {
        let d = Limits::default();
        Limits {
            max_input_bytes: self.max_input,
            max_nesting: self.max_nesting,
            max_depth: self.max_depth,
            max_repeat: self.max_depth,
            max_symbols: symbols.map_or(d.max_symbols, |a| a.max_symbols),
            max_word: word.map_or(d.max_word, |a| a.max_word),
            max_stems: stems.unwrap_or(d.max_stems),
            max_layout_vertices: layout.map_or(d.max_layout_vertices, |a| a.max_layout_vertices),
            max_rule_parts: self.max_rule_parts,
            max_layout_shapes: self.max_layout_shapes,
        }
    }
}

/// Options of growth, shared by every command that grows an .od.
#[derive(Debug, Args, Clone)]
pub struct GrowArgs {
    /// Growth order of an .od: bfs (the default) grows level by level,
    /// balanced; dfs grows a branch's whole subtree before its sibling;
    /// space grows toward the most free space of the LAYOUT first.
    #[arg(long, value_enum, value_name = "ORDER")]
    pub growth: Option<GrowthOrder>,
    /// Stop growth after N stems (drawn segments), with a warning. Needed
    /// when an .od has no LAYOUT, count or decrement to end growth.
    #[arg(long, value_name = "N")]
    pub max_stems: Option<u64>,
    /// Clearance kept between stems, canvas units (overrides the file's C=).
    /// A finite number >= 0; write a value that starts with `-` as
    /// `--clearance=-1` (it is refused all the same).
    #[arg(long, value_name = "C", value_parser = parse_clearance, allow_negative_numbers = true)]
    pub clearance: Option<f64>,
}

/// `stlc render`.
#[derive(Debug, Args)]
pub struct RenderArgs {
    #[command(flatten)]
    pub input: InputArgs,

    /// Output file (.png or .svg; a mesh: .glb, .gltf or .obj; a solid:
    /// .stl, .3mf or .glb), or `-` for
    /// standard output. Default: the input's name with the format's
    /// extension.
    #[arg(short, long, value_name = "OUT")]
    pub output: Option<String>,

    /// Output format; default from the output's extension, else png.
    #[arg(short, long, value_enum)]
    pub format: Option<ImageFormat>,

    /// Derivation order (default dfs): dfs streams, bfs rewrites the whole
    /// word first. Same picture, different cost. `--strategy` is its old
    /// name. An .od's growth order, which does change the tree, is --growth.
    #[arg(
        short = 's',
        long,
        visible_alias = "strategy",
        value_enum,
        value_name = "ORDER"
    )]
    pub derivation: Option<Derivation>,

    /// Derivation depth of an .lsys (overrides its `generations`).
    #[arg(short, long, value_name = "N")]
    pub depth: Option<u32>,

    /// Output size in pixels, WxH (e.g. 1024x768). Default: 800 on the
    /// longest side, the other from the picture's aspect ratio.
    #[arg(long, value_name = "WxH", value_parser = parse_size)]
    pub size: Option<(u32, u32)>,

    /// Paint the LAYOUT shapes in their colours under the tree.
    #[arg(long)]
    pub show_layout: bool,

    /// Most lines an SVG may hold (about 22 bytes each): every segment
    /// with --exact, merged runs without; a PNG has no such limit.
    #[arg(long, value_name = "N", default_value_t = DEFAULT_MAX_SVG_SEGMENTS)]
    pub max_svg_segments: u64,

    /// Draw every segment of an .lsys. By default a subtree smaller than
    /// half a pixel is drawn as one stand-in stroke (level of detail), so
    /// any depth renders in bounded time.
    #[arg(long)]
    pub exact: bool,

    /// Threads that paint a big PNG (a drawing of 2^20 segments or more,
    /// painted in bands of 64 rows): the same pixels with any number.
    /// Default: the machine's cores. A deterministic .lsys at its level of
    /// detail (no --exact) is painted on one thread, so that it can skip
    /// what is already full ink.
    #[arg(long, value_name = "N", value_parser = clap::value_parser!(u16).range(1..=1024))]
    pub threads: Option<u16>,

    /// The view of a 3D input, degrees: the camera turned AZ about the
    /// vertical axis (toward +x), then raised EL (docs/3d.md). Default 30,20.
    #[arg(long, value_name = "AZ,EL", value_parser = parse_view, allow_hyphen_values = true)]
    pub view: Option<View>,

    /// Write a mesh instead of a picture (default: from the output's
    /// extension, .glb, .gltf or .obj; with --solid .stl, .3mf or .glb);
    /// needed for `-o -`.
    #[arg(long, value_enum, value_name = "FORMAT", conflicts_with = "format")]
    pub mesh: Option<MeshFormat>,

    /// Sides of each stem's tube in a mesh (.glb, .gltf, .obj), 3 to 64.
    #[arg(long, value_name = "N", default_value_t = DEFAULT_SIDES,
          value_parser = clap::value_parser!(u32).range(3..=64))]
    pub sides: u32,

    /// Metres per canvas unit in a mesh (default 0.01: a 300-unit tree is 3 m).
    #[arg(long, value_name = "M", default_value_t = DEFAULT_UNIT, value_parser = parse_unit)]
    pub unit: f64,

    /// Most triangles a mesh may have (each stem is 4 x sides - 4).
    #[arg(long, value_name = "N", default_value_t = DEFAULT_MAX_TRIANGLES)]
    pub max_triangles: u64,

    /// Write one closed body for 3D printing: the stems' tubes and a sphere
    /// at each joint united (docs/3d.md). As binary STL or 3MF (millimetres,
    /// z up) or a .glb (metres, y up), by the output's extension; a 3D input
    /// only. Without -o: .stl beside the input.
    #[arg(long)]
    pub solid: bool,

    /// Stroke colour (#rrggbb or a Delphi name such as clMaroon).
    #[arg(long, value_name = "COLOR")]
    pub stroke: Option<String>,

    /// Background colour (#rrggbb, a Delphi name, or `none` for transparent).
    #[arg(long, value_name = "COLOR")]
    pub background: Option<String>,

    #[command(flatten)]
    pub grow: GrowArgs,

    #[command(flatten)]
    pub limits: LimitArgs,

    #[command(flatten)]
    pub derive_limits: DeriveLimitArgs,
}

/// `stlc compile`.
#[derive(Debug, Args)]
pub struct CompileArgs {
    #[command(flatten)]
    pub input: InputArgs,

    /// Output .bed file, or `-` for standard output. Default: the input's
    /// name with .bed (standard output when reading standard input).
    #[arg(short, long, value_name = "OUT")]
    pub output: Option<String>,

    /// The old name of --growth, kept for scripts (with a warning): bfs
    /// grows level by level (balanced trees), dfs a branch's whole subtree
    /// before its sibling (vines, ornament).
    #[arg(
        short,
        long,
        value_enum,
        value_name = "ORDER",
        conflicts_with = "growth"
    )]
    pub strategy: Option<GrowthOrder>,

    #[command(flatten)]
    pub grow: GrowArgs,

    #[command(flatten)]
    pub limits: LimitArgs,

    #[command(flatten)]
    pub layout_limits: LayoutLimitArgs,
}

/// `stlc expand`.
#[derive(Debug, Args)]
pub struct ExpandArgs {
    #[command(flatten)]
    pub input: InputArgs,

    /// Output file, or `-` (the default) for standard output.
    #[arg(short, long, value_name = "OUT", default_value = "-")]
    pub output: String,

    /// Derivation order (default dfs): dfs streams, bfs builds the word in
    /// memory. `--strategy` is its old name. (An .od's growth order is
    /// --growth.)
    #[arg(
        short = 's',
        long,
        visible_alias = "strategy",
        value_enum,
        value_name = "ORDER"
    )]
    pub derivation: Option<Derivation>,

    /// Derivation depth of an .lsys (overrides its `generations`).
    #[arg(short, long, value_name = "N")]
    pub depth: Option<u32>,

    #[command(flatten)]
    pub grow: GrowArgs,

    #[command(flatten)]
    pub limits: LimitArgs,

    #[command(flatten)]
    pub derive_limits: DeriveLimitArgs,
}

/// `stlc stats`.
#[derive(Debug, Args)]
pub struct StatsArgs {
    #[command(flatten)]
    pub input: InputArgs,

    /// Derivation depth (overrides the file's `generations`).
    #[arg(short, long, value_name = "N")]
    pub depth: Option<u32>,

    /// Print JSON: {"length", "segments", "bbox", "end", "symbols"}, exact
    /// integers as decimal strings.
    #[arg(long)]
    pub json: bool,

    #[command(flatten)]
    pub limits: LimitArgs,

    #[command(flatten)]
    pub symbol_limits: SymbolLimitArgs,
}

/// `stlc check`.
#[derive(Debug, Args)]
pub struct CheckArgs {
    #[command(flatten)]
    pub input: InputArgs,

    #[command(flatten)]
    pub grow: GrowArgs,

    #[command(flatten)]
    pub limits: LimitArgs,

    #[command(flatten)]
    pub symbol_limits: SymbolLimitArgs,

    #[command(flatten)]
    pub layout_limits: LayoutLimitArgs,
}

/// Parses `AZ,EL`.
/// Parses `AZ,EL`: any azimuth, an elevation from -90 (looking up from
/// below) to 90 (straight down), as the editor's view clamps it.
fn parse_view(s: &str) -> Result<View, String> {
    let view = View::parse(s)
        .ok_or_else(|| format!("`{s}` is not AZ,EL (two numbers of degrees, e.g. 30,20)"))?;
    let range = -90.0..=90.0;
    if !range.contains(&view.el) {
        let mut msg = format!(
            "the elevation {} is past 90 degrees: it goes from -90 (looking from below) \
             to 90 (from above)",
            view.el
        );
        // Over the top is the other side, upright: turn the azimuth instead.
        let over = (180.0 - view.el.abs()) * view.el.signum();
        if range.contains(&over) {
            msg += &format!(
                "; to look over the top, turn the azimuth: {},{over}",
                view.az + 180.0
            );
        }
        return Err(msg);
    }
    Ok(view)
}

/// Parses a positive, finite number of metres.
fn parse_unit(s: &str) -> Result<f64, String> {
    match s.trim().parse::<f64>() {
        Ok(u) if u.is_finite() && u > 0.0 => Ok(u),
        _ => Err(format!(
            "`{s}` is not a positive number of metres, e.g. 0.01"
        )),
    }
}

/// Parses `WxH`.
fn parse_size(s: &str) -> Result<(u32, u32), String> {
    let (w, h) = s
        .split_once(['x', 'X'])
        .ok_or_else(|| format!("`{s}` is not WxH, e.g. 800x600"))?;
    let num = |t: &str| {
        t.trim()
            .parse::<u32>()
            .map_err(|_| format!("`{t}` is not a whole number of pixels"))
    };
    let (w, h) = (num(w)?, num(h)?);
    if w == 0 || h == 0 || w > 16384 || h > 16384 {
        return Err("each side must be between 1 and 16384 pixels".into());
    }
    Ok((w, h))
}

fn parse_clearance(s: &str) -> Result<f64, String> {
    let c: f64 = s
        .trim()
        .parse()
        .map_err(|_| format!("`{s}` is not a number"))?;
    if c.is_finite() && c >= 0.0 {
        Ok(c)
    } else {
        Err("the clearance must be a finite number >= 0, e.g. 0.5".into())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn sizes_parse_and_absurd_ones_are_refused() {
        assert_eq!(parse_size("800x600"), Ok((800, 600)));
        assert_eq!(parse_size("64X64"), Ok((64, 64)));
        assert!(parse_size("0x10").is_err());
        assert_eq!(parse_clearance("0.5"), Ok(0.5));
        assert_eq!(parse_clearance("0"), Ok(0.0));
        for bad in ["-1", "nan", "inf", "1e400", "x"] {
            assert!(parse_clearance(bad).is_err(), "{bad}");
        }
        assert!(parse_size("800").is_err());
        assert!(parse_size("20000x10").is_err());
    }

    #[test]
    fn the_command_line_is_well_formed() {
        use clap::CommandFactory;
        Cli::command().debug_assert();
    }
}
