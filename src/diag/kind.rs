//! What went wrong: [`ErrorKind`], one variant per failure, grouped by the
//! stage that reports it. The message is the `Display` text; where and how
//! to fix it live on [`super::Diagnostic`].

use super::number::{plural, short_number};

/// What went wrong. Each stage owns its variants; the message is the
/// `Display` text, the span and hints live on [`super::Diagnostic`].
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum ErrorKind {
    /// The text does not follow the grammar (pest's report, with rule names
    /// translated into what the user would type).
    #[error("syntax error: {0}")]
    Syntax(String),
    /// The input is not UTF-8 text.
    #[error("input is not UTF-8 text (byte {0} is not valid UTF-8)")]
    NotUtf8(usize),
    /// The input is larger than the configured limit.
    #[error("input is {size} bytes, more than the limit of {limit} bytes")]
    InputTooLarge {
        /// Size of the input in bytes.
        size: u64,
        /// The limit in force.
        limit: u64,
    },
    /// Brackets, braces or parentheses nest deeper than the limit.
    #[error("nesting is deeper than the limit of {limit} levels")]
    NestingTooDeep {
        /// The limit in force.
        limit: usize,
    },
    /// More diagnostics than [`super::MAX_DIAGNOSTICS`]: the rest are
    /// counted, not kept (a generated file can hold a million mistakes).
    #[error("{count} more problem(s) of the same input not shown")]
    MoreDiagnostics {
        /// How many were left out.
        count: usize,
    },
    /// A `[`, `{` or `(` without its partner, or a closing one without an opener.
    #[error("unbalanced `{0}`")]
    Unbalanced(char),
    /// A rule reference names no declared rule.
    #[error("unknown rule `{name}`")]
    UnknownRule {
        /// The name as written.
        name: String,
    },
    /// A term has a different number of slots than its rule has branches.
    #[error("`{rule}` has {expected} branch{}, but this term gives {found} slot{}", plural(*expected, "es"), plural(*found, "s"))]
    SlotCount {
        /// The rule's name.
        rule: String,
        /// Branch count of the rule.
        expected: usize,
        /// Slots written.
        found: usize,
    },
    /// A limit (depth, word length, stems, ...) would be exceeded.
    #[error("{}: {} exceeds the limit of {limit}", what.as_deref().unwrap_or(bound.describe()), short_number(value))]
    Limit {
        /// Which limit.
        bound: crate::limits::Bound,
        /// What was measured against it, where the bound's own words
        /// ([`crate::limits::Bound::describe`]) are not precise enough
        /// (`derived word length at depth 30`).
        what: Option<String>,
        /// The value asked for (decimal; may be a big integer, or a bound
        /// such as `more than 10000`).
        value: String,
        /// The limit in force.
        limit: u64,
    },
    /// The reader of our standard output went away (`stlc expand | head`).
    /// The CLI exits quietly on it.
    #[error("broken pipe")]
    BrokenPipe,

    // ------------------------------------------------ syntax: .lsys --
    /// A `.lsys` line starts with no key of the format.
    #[error("unknown key `{key}`")]
    UnknownKey {
        /// The key as written.
        key: String,
    },
    /// A single-valued `.lsys` key is given on a second line.
    #[error("`{key}` is given twice")]
    DuplicateKey {
        /// The key.
        key: &'static str,
    },
    /// A `.lsys` file lacks a key it needs (`axiom`, `angle`).
    #[error("missing `{key}`")]
    MissingKey {
        /// The key.
        key: &'static str,
    },
    /// A `.lsys` rule's predecessor is more than one symbol.
    #[error("a rule rewrites one symbol, but `{predecessor}` is {symbols} symbols")]
    LongPredecessor {
        /// The predecessor as written.
        predecessor: String,
        /// Its number of symbols.
        symbols: usize,
    },
    /// Two `.lsys` rules rewrite the same symbol.
    #[error("two rules for `{symbol}`")]
    DuplicateProduction {
        /// The symbol both rewrite.
        symbol: char,
    },
    /// A `.lsys` key that takes a whole number is given something else.
    #[error("`{key}` takes a whole number, not `{text}`")]
    NotWholeNumber {
        /// The key.
        key: &'static str,
        /// The value as written.
        text: String,
    },
    /// A `.lsys` number value does not read as a number.
    #[error("malformed number `{text}`")]
    MalformedNumber {
        /// The value as written.
        text: String,
    },
    /// A `.lsys` number value does not fit a 64-bit float.
    #[error("`{key}` {text} is too large")]
    NumberTooLarge {
        /// The key.
        key: &'static str,
        /// The value as written.
        text: String,
    },
    /// A `.lsys` value that must be positive is zero or negative.
    #[error("`{key}` must be greater than 0, not {text}")]
    NotPositive {
        /// The key.
        key: &'static str,
        /// The value as written.
        text: String,
    },
    /// A colour is neither `#rrggbb` nor a known colour name: the value of
    /// a `.lsys` `color` or `background`, or of a layout line.
    #[error("unknown colour `{text}`")]
    UnknownColour {
        /// The colour as written.
        text: String,
    },

    // --------------------------------------------- syntax: .od / .bed --
    /// A header parameter given the wrong kind of value (a colour for `L`,
    /// a number for `S`).
    #[error("`{key}` takes {expected}")]
    ParamValue {
        /// The parameter's key.
        key: &'static str,
        /// What it takes, in words.
        expected: &'static str,
    },
    /// A number in a description does not fit a 64-bit float.
    #[error("`{text}` is not a finite number")]
    NotFinite {
        /// The number as written.
        text: String,
    },
    /// A stem parameter is given twice.
    #[error("`{key}` is given twice")]
    DuplicateParam {
        /// The parameter's name as written.
        key: String,
    },
    /// A stem parameter's name is none of `L`, `B`, `A`, `C`.
    #[error("unknown stem parameter `{key}`")]
    UnknownParam {
        /// The name as written.
        key: String,
    },
    /// The base length `L` or broadness `B` is zero or negative.
    #[error("the stem {what} `{key}` must be positive")]
    StemSizeNotPositive {
        /// `L` or `B`.
        key: &'static str,
        /// `length` or `broadness`.
        what: &'static str,
    },
    /// The decrement of `L` or `B` is negative.
    #[error("the decrement of `{key}` must not be negative")]
    NegativeDecrement {
        /// `L` or `B`.
        key: &'static str,
    },
    /// `A` or `C` is written with a decrement.
    #[error("`{key}` takes no decrement")]
    UnexpectedDecrement {
        /// `A` or `C`.
        key: &'static str,
    },
    /// The clearance `C` is negative.
    #[error("the clearance `C` must not be negative")]
    NegativeClearance,
    /// A rule is given a reserved name: a drawing letter, `I` or a section
    /// keyword.
    #[error("`{name}` is reserved and cannot name a rule")]
    ReservedName {
        /// The name.
        name: String,
    },
    /// A rule name starts with a digit or `_`.
    #[error("rule name `{name}` does not start with a letter")]
    RuleNameNotLetter {
        /// The name.
        name: String,
    },
    /// Two rules have one name.
    #[error("rule `{name}` is defined twice")]
    DuplicateRule {
        /// The name.
        name: String,
    },
    /// A rule definition has no body.
    #[error("syntax error: expected a rule body")]
    MissingBody,
    /// A dot in a rule name where it means nothing: in an OD (dots are
    /// reserved for a BED's alternatives), or `R1.x` with `x` not a number
    /// from 1 in a BED.
    #[error("`{name}` is not a rule name here")]
    DottedName {
        /// The name as written.
        name: String,
    },
    /// A rule with several bodies where one has no probability.
    #[error("`{name}` has several bodies, but not every one has a probability")]
    MissingProbability {
        /// The rule's name.
        name: String,
    },
    /// An alternative's probability is not a finite number above 0.
    #[error("probability {} of an alternative of `{name}` is not a finite number above 0", crate::num::fixed(*value, 9, crate::num::Trim::Zeros))]
    BadProbability {
        /// The rule's name.
        name: String,
        /// The probability written.
        value: f64,
    },
    /// A `.lsys` rule has a parenthesis where a probability goes that does
    /// not hold a decimal number (`rule F (1/3) -> ...`, `(50%)`): read as
    /// it stands it would be part of the successor.
    #[error("`{text}` is not a probability")]
    UnreadableProbability {
        /// The parenthesis as written.
        text: String,
    },
    /// The probabilities of a rule's alternatives do not sum to 1.
    #[error("the probabilities of `{name}`'s alternatives sum to {}, not 1", crate::num::fixed(*sum, 9, crate::num::Trim::Zeros))]
    ProbabilitySum {
        /// The rule's name.
        name: String,
        /// Their sum.
        sum: f64,
    },
    /// A BED names an alternative its rule does not have (`R1.3` of two).
    #[error("`{name}` has no alternative {number}")]
    UnknownAlternative {
        /// The rule's name.
        name: String,
        /// The number written after the dot.
        number: String,
    },
    /// A written-out term names a rule with alternatives but not which one
    /// grew (`R1{,}` where R1 has `R1.1` and `R1.2`).
    #[error("`{name}` has {count} alternatives; a written term names the one that grew")]
    AlternativeNotNamed {
        /// The rule's name.
        name: String,
        /// How many alternatives it has.
        count: usize,
    },
    /// A BED gives a probability to a rule that is not an alternative
    /// (`R1 (0.5): ...` instead of `R1.1 (0.5): ...`).
    #[error("`{name}` has a probability, but a BED's rule without a number is not an alternative")]
    ProbabilityWithoutAlternative {
        /// The rule's name.
        name: String,
    },
    /// A BED repeats a rule with alternatives (`[I 2 R1]` or `[I 2 R1.2]`
    /// where R1 has several bodies): each application would choose, and a
    /// BED records choices instead of making them.
    #[error(
        "`[I n {name}]` would choose among {count} alternatives; a BED writes the terms that grew"
    )]
    RepeatChooses {
        /// The rule's name, without an alternative's number.
        name: String,
        /// How many alternatives it has.
        count: usize,
    },
    /// A BED of a forest has a different number of seeds than roots.
    #[error("{roots} root{} but {seeds} SEED section{}", plural(*roots, "s"), plural(*seeds, "s"))]
    SeedsPerRoot {
        /// Roots on the root line.
        roots: usize,
        /// `SEED ... ENDSEED` sections.
        seeds: usize,
    },

    /// Part of a word that is neither a drawing letter nor a rule name and
    /// does not start with a letter (the `3` of `F3`).
    #[error("unexpected `{text}`")]
    UnexpectedInWord {
        /// The part as written.
        text: String,
    },
    /// `[I 0 X]`.
    #[error("a self-resemblance count must be at least 1")]
    ZeroCount,
    /// `[I n X]` mixes a rule name with drawing components, or names two
    /// rules.
    #[error("`[I n X]` takes one rule name or a string of drawing components")]
    MixedRepeat,
    /// `[I n]` with nothing to repeat.
    #[error("`[I n X]` needs a rule name or drawing components")]
    EmptyRepeat,
    /// `[I n R1]` in a rule body.
    #[error("`[I n X]` with a rule cannot stand in a rule body")]
    RepeatInBody,
    /// `{`, `}` or `,` in a rule body.
    #[error("`{symbol}` cannot stand in a rule body")]
    TermSyntaxInBody {
        /// The symbol.
        symbol: char,
    },
    /// A rule name in a body that does not end a top-level branch.
    #[error("a rule name in a rule body must end a branch")]
    NameNotAtBranchEnd,
    /// A section that is opened and never closed.
    #[error("`{open}` without `{close}`")]
    UnclosedSection {
        /// The keyword that opens it.
        open: &'static str,
        /// The keyword that should close it.
        close: &'static str,
    },
    /// Drawing components in a term's slot.
    #[error("drawing components cannot stand in a slot")]
    DrawingInSlot,
    /// A second term in one slot.
    #[error("a slot holds one term")]
    TwoTermsInSlot,
    /// A `{` that follows no rule name.
    #[error("`{{` must follow a rule name")]
    BraceWithoutRule,
    /// A `,` outside any term.
    #[error("`,` outside a term")]
    CommaOutsideTerm,
    /// A layout shape's name is none of the known shapes.
    #[error("unknown shape `{name}`")]
    UnknownShape {
        /// The name as written.
        name: String,
    },
    /// A shape's arguments fit none of its spellings.
    #[error("wrong arguments for `{shape}`")]
    ShapeArguments {
        /// The shape's name.
        shape: &'static str,
    },
    /// A polygon with fewer than 3 points.
    #[error("a polygon needs at least 3 points, this one has {points}")]
    TooFewPoints {
        /// The points given.
        points: usize,
    },
    /// A shape's width, height or corner size is zero or negative.
    #[error("the {what} of `{shape}` must be positive")]
    ShapeSizeNotPositive {
        /// The shape's name.
        shape: &'static str,
        /// `width`, `height`, `corner width`, `corner height` or `corner radius`.
        what: &'static str,
    },
    // ----------------------------------------------------- growth --
    /// Growth has nothing to start from: no `SEED` and no rule.
    #[error("nothing to grow: the description has no SEED and no rule")]
    NothingToGrow,
    /// The clearance (`C=` or `--clearance`) is negative or not finite.
    #[error("the clearance must be a finite number >= 0, not {value}")]
    BadClearance {
        /// The clearance asked for.
        value: f64,
    },
    /// Warning: a root of a forest on the point of an earlier root.
    #[error(
        "root {root} is on the point of root {first}: the two trees start in one place, and the later finds its room taken"
    )]
    SharedRoot {
        /// The later root, counted from 1 in root-line order.
        root: usize,
        /// The earlier root on the same point.
        first: usize,
    },
    /// The root lies outside the layout region, so nothing can grow.
    #[error("the root ({x}, {y}) lies outside the layout region")]
    RootOutside {
        /// The root's x, as written.
        x: f64,
        /// The root's y, as written.
        y: f64,
    },
    /// A rule reference of the seed names a rule number that is not
    /// declared (a description built by hand; the parser resolves names).
    #[error("rule number {number} is not declared")]
    UndeclaredRule {
        /// The rule's index.
        number: usize,
    },
    /// Growth with nothing to bound it: a growth point without a count whose
    /// rules can branch forever, and no layout, decrement or explicit
    /// `--max-stems`.
    #[error(
        "growth has no bound: `{rule}` can branch forever (through `{through}`), and there is no LAYOUT, no count and no decrement to stop it"
    )]
    UnboundedGrowth {
        /// The rule of the growth point.
        rule: String,
        /// A rule on the endless cycle reachable from it.
        through: String,
    },
    /// Warning: `--max-stems` stopped growth; the BED is cut short.
    #[error(
        "growth stopped at {stems} stems: the next rule application would pass the limit of {} {limit}",
        crate::limits::Bound::Stems.flag()
    )]
    GrowthStopped {
        /// Stems grown when growth stopped.
        stems: u64,
        /// The limit in force.
        limit: u64,
    },
    /// Warning: growth reached `--max-depth`; deeper branches were not grown.
    #[error(
        "growth reached the depth limit of {limit} nested rule applications ({}); deeper branches were not grown",
        crate::limits::Bound::Depth.flag()
    )]
    DepthCapped {
        /// The limit in force.
        limit: u32,
    },
    /// A layout shape has a coordinate that is not a finite number.
    #[error("a layout shape has a coordinate that is not a finite number")]
    LayoutNotFinite,
    /// The layout's shapes leave no area to grow in.
    #[error(
        "the layout leaves no area to grow in: nothing coloured remains once the white shapes are painted"
    )]
    EmptyRegion,
    // -------------------------------------------------------- BED --
    /// A rule is applied at an order where stems would have no positive
    /// length or width (`base - order * decrement <= 0`). Numbers as the
    /// BED writer writes them.
    #[error(
        "`{rule}` is applied at order {order}, where stems have length {} and width {}",
        crate::num::fixed(*length, 3, crate::num::Trim::Zeros),
        crate::num::fixed(*width, 3, crate::num::Trim::Zeros)
    )]
    OrderTooDeep {
        /// The rule's name.
        rule: String,
        /// The order of the application.
        order: u32,
        /// Stem length at that order.
        length: f64,
        /// Stem width at that order.
        width: f64,
    },
    // ------------------------------------------- interpret / stats --

    // ----------------------------------------------------- render --
    /// A layout's canvas is not a proper box (NaN or inverted bounds).
    #[error("the canvas to show is not a proper box ({min_x}, {min_y}) .. ({max_x}, {max_y})")]
    BadCanvas {
        /// Left.
        min_x: f64,
        /// Top.
        min_y: f64,
        /// Right.
        max_x: f64,
        /// Bottom.
        max_y: f64,
    },
    /// The drawing reaches coordinates that are infinite or NaN.
    #[error("the drawing reaches coordinates that are not finite numbers")]
    DrawingNotFinite,
    /// `--size` with a zero side or a side over the maximum.
    #[error("image size {width}x{height} is out of range: each side must be 1 to {max} pixels")]
    ImageSize {
        /// Width asked for.
        width: u32,
        /// Height asked for.
        height: u32,
        /// Largest side allowed.
        max: u32,
    },
    /// The raster could not be allocated.
    #[error("cannot make a {width}x{height} raster")]
    NoRaster {
        /// Width.
        width: u32,
        /// Height.
        height: u32,
    },
    /// PNG encoding failed.
    #[error("cannot encode the PNG image: {error}")]
    PngEncoding {
        /// The encoder's message.
        error: String,
    },

    // ------------------------------------------- pipeline and I/O --
    /// Reading the input or writing the output failed: `doing` says what
    /// (`cannot read \`tree.od\``), `error` is the system's message.
    #[error("{doing}: {error}")]
    Io {
        /// What was being done.
        doing: String,
        /// The operating system's message.
        error: String,
    },
    /// A file's kind cannot be told from its name or its text.
    #[error("cannot tell what kind of file `{name}` is")]
    UnknownInputKind {
        /// The file name as given.
        name: String,
    },
    /// A command was given a kind of input it does not take (`compile` of
    /// an `.lsys`, `stats` of an `.od`).
    #[error("{message}")]
    WrongInputKind {
        /// What the command takes and what it got.
        message: String,
    },
    /// The input holds nothing but white space.
    #[error("the file is empty")]
    EmptyInput,
    /// An L-system has no `generations` and no `--depth` was given.
    #[error("no derivation depth")]
    NoDepth,
    /// `-f` names one format and the output's extension another (a usage
    /// error).
    #[error("`-f {format}` contradicts the output name `{path}`")]
    FormatMismatch {
        /// The format asked for with `-f`.
        format: String,
        /// The output path.
        path: String,
    },
    /// The output's extension names no image format stlc writes (a usage
    /// error).
    #[error("cannot write `{path}`: `.{extension}` is not an image format stlc writes")]
    UnknownOutputExtension {
        /// The output path.
        path: String,
        /// Its extension.
        extension: String,
    },
    /// A flag given that does nothing for this input (a warning).
    #[error("{flag} was ignored: {reason}")]
    IgnoredFlag {
        /// The flag as written (`--depth`).
        flag: String,
        /// Why it does nothing here.
        reason: String,
    },
    /// Nothing was drawn: the picture is only its background (a warning).
    #[error("the picture is empty: the derivation draws no stem")]
    NothingDrawn,
    /// An `.lsys` uses `L` or `R`, which do not turn there (a warning).
    #[error(
        "`{symbol}` does not turn in an .lsys file: it is an ordinary symbol there, and no rule rewrites it"
    )]
    InertTurn {
        /// `L` or `R`.
        symbol: char,
    },
    /// An error only a front end makes (its command line, the files it
    /// writes): the front end's own error type (`frontend/error.rs` in the
    /// binary) converts into this, keeping its message and whether it is a
    /// usage error.
    #[error("{message}")]
    FrontEnd {
        /// The message.
        message: String,
        /// Whether it is a usage error (exit status 2).
        usage: bool,
    },
}

impl ErrorKind {
    /// Whether this is a usage error: the command line asks for something
    /// contradictory, rather than the input or the work failing. The CLI
    /// exits with status 2 on these, as it does on clap's own.
    pub fn is_usage(&self) -> bool {
        matches!(
            self,
            ErrorKind::FormatMismatch { .. }
                | ErrorKind::UnknownOutputExtension { .. }
                | ErrorKind::FrontEnd { usage: true, .. }
        )
    }
}
