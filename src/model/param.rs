//! The book's L-systems (docs/lsys.md, *Parametric systems*): modules with
//! real parameters, rules with left and right context, conditions and
//! expressions, `define` constants, `ignore`, tropism.
//!
//! A `.lsys` file that uses none of these is an [`super::lsys::LSystem`]
//! without a [`Parametric`] part and takes the classic path unchanged.

use super::Loc;

/// The most formal parameters a module may have in a rule, and the most
/// parameters a module may carry.
pub const MAX_PARAMS: usize = 64;

/// The deepest an expression may nest (parentheses, operators, calls).
pub const MAX_EXPR_DEPTH: usize = 64;

/// The step of the widths a parametric system's segments carry: a
/// segment's stem order is its width in canvas units over this quantum,
/// rounded (the renderer's `Canvas` width `0 + order x quantum` gives it
/// back within half a quantum).
pub const WIDTH_QUANTUM: f64 = 1.0 / 1024.0;

/// A binary operator of an expression.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum BinOp {
    /// `+`
    Add,
    /// `-`
    Sub,
    /// `*`
    Mul,
    /// `/`
    Div,
    /// `^`: power (right-associative).
    Pow,
    /// `<`
    Lt,
    /// `<=`
    Le,
    /// `>`
    Gt,
    /// `>=`
    Ge,
    /// `==`
    Eq,
    /// `!=`
    Ne,
    /// `&&`
    And,
    /// `||`
    Or,
}

/// A function of an expression; angles in degrees.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Func {
    /// `sin(deg)`
    Sin,
    /// `cos(deg)`
    Cos,
    /// `tan(deg)`
    Tan,
    /// `asin(x)`, in degrees
    Asin,
    /// `acos(x)`, in degrees
    Acos,
    /// `atan(x)`, in degrees
    Atan,
    /// `atan2(y, x)`, in degrees
    Atan2,
    /// `sqrt(x)`
    Sqrt,
    /// `abs(x)`
    Abs,
    /// `exp(x)`
    Exp,
    /// `ln(x)`
    Ln,
    /// `floor(x)`
    Floor,
    /// `ceil(x)`
    Ceil,
    /// `round(x)`: half away from zero
    Round,
    /// `min(a, b)`
    Min,
    /// `max(a, b)`
    Max,
}

/// Every function name, with its function and number of arguments.
pub const FUNCS: [(&str, Func, usize); 16] = [
    ("sin", Func::Sin, 1),
    ("cos", Func::Cos, 1),
    ("tan", Func::Tan, 1),
    ("asin", Func::Asin, 1),
    ("acos", Func::Acos, 1),
    ("atan", Func::Atan, 1),
    ("atan2", Func::Atan2, 2),
    ("sqrt", Func::Sqrt, 1),
    ("abs", Func::Abs, 1),
    ("exp", Func::Exp, 1),
    ("ln", Func::Ln, 1),
    ("floor", Func::Floor, 1),
    ("ceil", Func::Ceil, 1),
    ("round", Func::Round, 1),
    ("min", Func::Min, 2),
    ("max", Func::Max, 2),
];

/// An expression: constants are folded in when read, names of formal
/// parameters are slots of the rule's bindings.
#[derive(Debug, Clone, PartialEq)]
pub enum Expr {
    /// A number (or a `define`d constant).
    Num(f64),
    /// The value bound to a rule's formal parameter: its index in the
    /// bindings (left context, predecessor, right context, in order).
    Var(u16),
    /// `-x`
    Neg(Box<Expr>),
    /// `!x`: 1 if x is 0, else 0.
    Not(Box<Expr>),
    /// `a op b`
    Bin(BinOp, Box<Expr>, Box<Expr>),
    /// `f(args)`
    Call(Func, Vec<Expr>),
}

/// A module as written in an axiom or a successor: a symbol and its
/// parameters' expressions.
#[derive(Debug, Clone, PartialEq)]
pub struct ModuleExpr {
    /// The symbol.
    pub symbol: char,
    /// Its parameters (none for a plain symbol).
    pub args: Vec<Expr>,
    /// Where each parameter's expression is written (one per `args`):
    /// an error its value makes points there.
    pub spans: Vec<Loc>,
}

/// A module in a rule's head: a symbol and the number of its formal
/// parameters (their names are slots of the bindings).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Formal {
    /// The symbol.
    pub symbol: char,
    /// How many formal parameters it has.
    pub arity: usize,
}

/// One rule `LC < PRED > RC : COND -> SUCC`, or one alternative `(p)`.
#[derive(Debug, Clone, PartialEq)]
pub struct ParamRule {
    /// The left context, in reading order (empty: none).
    pub left: Vec<Formal>,
    /// The module rewritten.
    pub pred: Formal,
    /// The right context (empty: none).
    pub right: Vec<Formal>,
    /// The probability of a stochastic alternative (may use the formals).
    pub probability: Option<Expr>,
    /// The condition (`None`: always).
    pub condition: Option<Expr>,
    /// The successor.
    pub successor: Vec<ModuleExpr>,
    /// Where the `rule` line is.
    pub loc: Loc,
}

impl ParamRule {
    /// How many values a match binds (every formal of the contexts and the
    /// predecessor).
    pub fn slots(&self) -> usize {
        self.left
            .iter()
            .chain(&self.right)
            .map(|f| f.arity)
            .sum::<usize>()
            + self.pred.arity
    }

    /// Whether the rule looks at its neighbours.
    pub fn has_context(&self) -> bool {
        !self.left.is_empty() || !self.right.is_empty()
    }
}

/// The parametric part of a `.lsys` file.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct Parametric {
    /// `define NAME EXPR`, in file order, with their values.
    pub defines: Vec<(String, f64, Loc)>,
    /// The axiom's modules (its expressions use only constants).
    pub axiom: Vec<ModuleExpr>,
    /// The rules in file order (the first that matches applies).
    pub rules: Vec<ParamRule>,
    /// `ignore SYMBOLS`: skipped when contexts are matched.
    pub ignore: Vec<char>,
    /// `tropism TX TY TZ`: the vector the heading bends toward.
    pub tropism: Option<[f64; 3]>,
    /// `elasticity e` (default 0: nothing bends).
    pub elasticity: f64,
    /// Colours, organs and `!` (docs/lsys.md, *Colours, widths and
    /// organs*).
    pub organs: Organs,
}

/// A file's colours, width decay and surfaces (stl-language.md section 13).
#[derive(Debug, Clone, PartialEq, Default)]
pub struct Organs {
    /// `palette C0 C1 ...`: the colours `'`, `;` and `,` step through
    /// (empty: the file's `color` is the only one).
    pub palette: Vec<crate::color::Rgb>,
    /// `width_decay r`: what a bare `!` multiplies the width by (`None`:
    /// [`DEFAULT_WIDTH_DECAY`]).
    pub width_decay: Option<f64>,
    /// `surface X { word }`: organs placed by `~X`, in file order.
    pub surfaces: Vec<Surface>,
    /// Where the first `{` of the axiom or a successor is written: a
    /// polygon derived past [`MAX_POLYGON_VERTICES`] is reported there.
    pub first_polygon: Option<Loc>,
}

/// What a bare `!` multiplies the width by without `width_decay`.
pub const DEFAULT_WIDTH_DECAY: f64 = 0.7;

/// The most vertices one polygon `{ ... }` may record (`f` and `.`):
/// more is an error, in a word as written or as derived.
pub const MAX_POLYGON_VERTICES: usize = 4096;

/// The symbols that gained a meaning for colours and organs (section 13):
/// a file using one of them, or `!`, `G`, `g`, reads through the
/// parametric path.
pub const ORGAN_SYMBOLS: [char; 10] = ['{', '}', '.', '~', '\'', ';', ',', '!', 'G', 'g'];

/// An OD's or BED's `SURFACES` block: each `surface X { word }` line read
/// as the `.lsys` key, and its text as written (the BED writer copies it).
#[derive(Debug, Clone, PartialEq)]
pub struct SurfaceBlock {
    /// The surfaces, in file order.
    pub surfaces: Vec<Surface>,
    /// Each surface's line as written, trimmed, comments cut off.
    pub lines: Vec<String>,
    /// Where the block is.
    pub loc: Loc,
}

/// One `surface X { word }`.
#[derive(Debug, Clone, PartialEq)]
pub struct Surface {
    /// Its name, `X`.
    pub name: char,
    /// Its word (constants only).
    pub word: Vec<ModuleExpr>,
    /// Where the line is.
    pub loc: Loc,
}

impl Organs {
    /// What a bare `!` multiplies the width by.
    pub fn decay(&self) -> f64 {
        self.width_decay.unwrap_or(DEFAULT_WIDTH_DECAY)
    }
}

impl Parametric {
    /// Whether some rule has a context (the word then derives level by
    /// level).
    pub fn has_context(&self) -> bool {
        self.rules.iter().any(ParamRule::has_context)
    }

    /// Whether some rule is a stochastic alternative.
    pub fn is_stochastic(&self) -> bool {
        self.rules.iter().any(|r| r.probability.is_some())
    }

    /// Whether some module sets the width (`!(w)` or `!`): its pictures then
    /// stroke each segment with the width in force, in canvas units
    /// ([`WIDTH_QUANTUM`]).
    pub fn sets_width(&self) -> bool {
        std::iter::once(&self.axiom)
            .chain(self.rules.iter().map(|r| &r.successor))
            .chain(self.organs.surfaces.iter().map(|s| &s.word))
            .flatten()
            .any(|m| m.symbol == '!')
    }

    /// Whether the system changes colour, draws polygons or places
    /// surfaces: its pictures are then drawn exactly (no level of detail:
    /// a stand-in could not say which colours it covers).
    pub fn paints(&self) -> bool {
        !self.organs.palette.is_empty()
            || !self.organs.surfaces.is_empty()
            || std::iter::once(&self.axiom)
                .chain(self.rules.iter().map(|r| &r.successor))
                .flatten()
                .any(|m| matches!(m.symbol, '{' | '}' | '.' | '~' | '\'' | ';' | ','))
    }

    /// Whether the turtle bends toward the tropism vector.
    pub fn bends(&self) -> bool {
        self.tropism.is_some() && self.elasticity != 0.0
    }
}

/// The value of an expression without formal parameters (a `define`, an
/// axiom's parameter).
pub fn eval_const(e: &Expr) -> f64 {
    eval(e, &[])
}

/// The value of `e` with the formal parameters bound to `vars`. True is 1,
/// false 0; trigonometry in degrees, through `libm` (the same bits on
/// every machine). A `Var` outside `vars` is NaN (never made by the
/// parser).
pub fn eval(e: &Expr, vars: &[f64]) -> f64 {
    let truth = |b: bool| if b { 1.0 } else { 0.0 };
    match e {
        Expr::Num(v) => *v,
        Expr::Var(k) => vars.get(*k as usize).copied().unwrap_or(f64::NAN),
        Expr::Neg(a) => -eval(a, vars),
        Expr::Not(a) => truth(eval(a, vars) == 0.0),
        Expr::Bin(op, a, b) => {
            let x = eval(a, vars);
            // `&&` and `||` look at their right side only when needed.
            match op {
                BinOp::And => return truth(x != 0.0 && eval(b, vars) != 0.0),
                BinOp::Or => return truth(x != 0.0 || eval(b, vars) != 0.0),
                _ => {}
            }
            let y = eval(b, vars);
            match op {
                BinOp::Add => x + y,
                BinOp::Sub => x - y,
                BinOp::Mul => x * y,
                BinOp::Div => x / y,
                BinOp::Pow => libm::pow(x, y),
                BinOp::Lt => truth(x < y),
                BinOp::Le => truth(x <= y),
                BinOp::Gt => truth(x > y),
                BinOp::Ge => truth(x >= y),
                BinOp::Eq => truth(x == y),
                BinOp::Ne => truth(x != y),
                BinOp::And | BinOp::Or => unreachable!("handled above"),
            }
        }
        Expr::Call(f, args) => {
            let a = args.first().map_or(f64::NAN, |a| eval(a, vars));
            let b = || args.get(1).map_or(f64::NAN, |b| eval(b, vars));
            let deg = |r: f64| r.to_degrees();
            match f {
                Func::Sin => libm::sin(a.to_radians()),
                Func::Cos => libm::cos(a.to_radians()),
                Func::Tan => libm::tan(a.to_radians()),
                Func::Asin => deg(libm::asin(a)),
                Func::Acos => deg(libm::acos(a)),
                Func::Atan => deg(libm::atan(a)),
                Func::Atan2 => deg(libm::atan2(a, b())),
                Func::Sqrt => libm::sqrt(a),
                Func::Abs => a.abs(),
                Func::Exp => libm::exp(a),
                Func::Ln => libm::log(a),
                Func::Floor => libm::floor(a),
                Func::Ceil => libm::ceil(a),
                Func::Round => libm::round(a),
                Func::Min => a.min(b()),
                Func::Max => a.max(b()),
            }
        }
    }
}
