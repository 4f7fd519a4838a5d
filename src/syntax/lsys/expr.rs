//! Expressions of parametric `.lsys` files (docs/lsys.md, *Expressions*):
//! numbers, names, `+ - * / ^`, comparisons, `&& || !`, functions.
//!
//! Read by recursive descent, at most [`MAX_EXPR_DEPTH`] levels deep (a
//! deeper expression is an error, never a stack overflow). `define`d names
//! are folded into numbers; formal parameters become slots.

use crate::diag::{Diagnostic, LsysError, Span};
use crate::model::param::{BinOp, Expr, FUNCS, MAX_EXPR_DEPTH};

/// What names mean where an expression is read.
pub(crate) struct Scope<'a> {
    /// Formal parameters, in slot order.
    pub formals: &'a [String],
    /// `define`d constants seen so far, with their values.
    pub defines: &'a [(String, f64)],
}

impl Scope<'_> {
    /// Every name an expression may use here (for "did you mean").
    fn names(&self) -> impl Iterator<Item = &str> {
        self.formals
            .iter()
            .map(String::as_str)
            .chain(self.defines.iter().map(|(n, _)| n.as_str()))
            .chain(FUNCS.iter().map(|(n, _, _)| *n))
    }
}

/// An error of the parametric syntax at `span`, with a help.
pub(crate) fn error(
    message: impl Into<String>,
    span: Span,
    help: impl Into<crate::diag::Help>,
) -> Box<Diagnostic> {
    Box::new(
        Diagnostic::error(LsysError::Param {
            message: message.into(),
        })
        .with_span(span)
        .with_help(help),
    )
}

/// Reads `text` (found at byte `at` of the file) as one expression.
pub(crate) fn parse(text: &str, at: usize, scope: &Scope) -> Result<Expr, Box<Diagnostic>> {
    let mut p = P {
        s: text.as_bytes(),
        text,
        i: 0,
        at,
        scope,
        depth: 0,
    };
    p.ws();
    if p.i == p.s.len() {
        return Err(error(
            "an empty expression",
            at..at + text.len(),
            "write a number, a name or a formula, e.g. `l*0.9`",
        ));
    }
    let e = p.or()?;
    p.ws();
    if p.i < p.s.len() {
        let span = p.span(p.i, p.s.len());
        return Err(error(
            format!("unexpected `{}` in an expression", &text[p.i..]),
            span,
            "join terms with an operator (`+ - * / ^`, a comparison, `&&`, `||`)",
        ));
    }
    Ok(e)
}

/// Whether `e` is a truth value (a comparison, `&&`, `||` or `!`): what a
/// condition must be.
pub(crate) fn is_boolean(e: &Expr) -> bool {
    match e {
        Expr::Not(_) => true,
        Expr::Bin(op, _, _) => matches!(
            op,
            BinOp::Lt
                | BinOp::Le
                | BinOp::Gt
                | BinOp::Ge
                | BinOp::Eq
                | BinOp::Ne
                | BinOp::And
                | BinOp::Or
        ),
        _ => false,
    }
}

struct P<'a> {
    s: &'a [u8],
    text: &'a str,
    i: usize,
    at: usize,
    scope: &'a Scope<'a>,
    depth: usize,
}

impl P<'_> {
    fn span(&self, from: usize, to: usize) -> Span {
        self.at + from..self.at + to
    }

    fn ws(&mut self) {
        while self.i < self.s.len() && matches!(self.s[self.i], b' ' | b'\t') {
            self.i += 1;
        }
    }

    /// Consumes `tok` (after spaces) if it is next.
    fn eat(&mut self, tok: &str) -> bool {
        self.ws();
        if self.text[self.i..].starts_with(tok) {
            self.i += tok.len();
            true
        } else {
            false
        }
    }

    fn deeper(&mut self) -> Result<(), Box<Diagnostic>> {
        self.depth += 1;
        if self.depth > MAX_EXPR_DEPTH {
            return Err(error(
                format!("an expression nested more than {MAX_EXPR_DEPTH} levels deep"),
                self.span(self.i.min(self.s.len()), self.s.len()),
                "split it with `define` constants",
            ));
        }
        Ok(())
    }

    fn or(&mut self) -> Result<Expr, Box<Diagnostic>> {
        self.deeper()?;
        let mut e = self.and()?;
        while self.eat("||") {
            e = Expr::Bin(BinOp::Or, Box::new(e), Box::new(self.and()?));
        }
        self.depth -= 1;
        Ok(e)
    }

    fn and(&mut self) -> Result<Expr, Box<Diagnostic>> {
        let mut e = self.cmp()?;
        while self.eat("&&") {
            e = Expr::Bin(BinOp::And, Box::new(e), Box::new(self.cmp()?));
        }
        Ok(e)
    }

    fn cmp(&mut self) -> Result<Expr, Box<Diagnostic>> {
        let e = self.add()?;
        let ops = [
            ("<=", BinOp::Le),
            (">=", BinOp::Ge),
            ("==", BinOp::Eq),
            ("!=", BinOp::Ne),
            ("<", BinOp::Lt),
            (">", BinOp::Gt),
        ];
        for (tok, op) in ops {
            if self.eat(tok) {
                return Ok(Expr::Bin(op, Box::new(e), Box::new(self.add()?)));
            }
        }
        Ok(e)
    }

    fn add(&mut self) -> Result<Expr, Box<Diagnostic>> {
        let mut e = self.mul()?;
        loop {
            let op = if self.eat("+") {
                BinOp::Add
            } else if self.eat("-") {
                BinOp::Sub
            } else {
                return Ok(e);
            };
            e = Expr::Bin(op, Box::new(e), Box::new(self.mul()?));
        }
    }

    fn mul(&mut self) -> Result<Expr, Box<Diagnostic>> {
        let mut e = self.unary()?;
        loop {
            let op = if self.eat("*") {
                BinOp::Mul
            } else if self.eat("/") {
                BinOp::Div
            } else {
                return Ok(e);
            };
            e = Expr::Bin(op, Box::new(e), Box::new(self.unary()?));
        }
    }

    fn unary(&mut self) -> Result<Expr, Box<Diagnostic>> {
        self.deeper()?;
        let e = if self.eat("-") {
            Expr::Neg(Box::new(self.unary()?))
        } else if self.text[self.i..].trim_start().starts_with("!=") {
            return Err(self.unexpected());
        } else if self.eat("!") {
            Expr::Not(Box::new(self.unary()?))
        } else {
            let base = self.atom()?;
            if self.eat("^") {
                Expr::Bin(BinOp::Pow, Box::new(base), Box::new(self.unary()?))
            } else {
                base
            }
        };
        self.depth -= 1;
        Ok(e)
    }

    fn unexpected(&self) -> Box<Diagnostic> {
        let rest = &self.text[self.i..];
        let shown = rest
            .chars()
            .next()
            .map_or("the end".to_string(), |c| format!("`{c}`"));
        error(
            format!("expected a number, a name or `(`, found {shown}"),
            self.span(self.i, (self.i + 1).min(self.s.len()).max(self.i)),
            "an expression is made of numbers, names, `( )` and operators",
        )
    }

    fn atom(&mut self) -> Result<Expr, Box<Diagnostic>> {
        self.ws();
        let start = self.i;
        let Some(&c) = self.s.get(self.i) else {
            return Err(self.unexpected());
        };
        if c == b'(' {
            self.i += 1;
            let e = self.or()?;
            if !self.eat(")") {
                return Err(error(
                    "a `(` without its `)`",
                    self.span(start, self.s.len()),
                    "close the parenthesis",
                ));
            }
            return Ok(e);
        }
        if c.is_ascii_digit() || c == b'.' {
            while self.i < self.s.len()
                && (self.s[self.i].is_ascii_digit() || self.s[self.i] == b'.')
            {
                self.i += 1;
            }
            if self.i < self.s.len() && matches!(self.s[self.i], b'e' | b'E') {
                let save = self.i;
                self.i += 1;
                if self.i < self.s.len() && matches!(self.s[self.i], b'+' | b'-') {
                    self.i += 1;
                }
                let digits = self.i;
                while self.i < self.s.len() && self.s[self.i].is_ascii_digit() {
                    self.i += 1;
                }
                if self.i == digits {
                    self.i = save;
                }
            }
            let t = &self.text[start..self.i];
            return match t.parse::<f64>() {
                Ok(v) if v.is_finite() => Ok(Expr::Num(v)),
                _ => Err(error(
                    format!("malformed number `{t}`"),
                    self.span(start, self.i),
                    "write a decimal number such as `0.9` or `1e-3`",
                )),
            };
        }
        if c.is_ascii_alphabetic() || c == b'_' {
            while self.i < self.s.len()
                && (self.s[self.i].is_ascii_alphanumeric() || self.s[self.i] == b'_')
            {
                self.i += 1;
            }
            let name = &self.text[start..self.i];
            let span = self.span(start, self.i);
            if let Some(k) = self.scope.formals.iter().position(|f| f == name) {
                return Ok(Expr::Var(k as u16));
            }
            if let Some((_, v)) = self.scope.defines.iter().rev().find(|(n, _)| n == name) {
                return Ok(Expr::Num(*v));
            }
            if let Some(&(_, f, arity)) = FUNCS.iter().find(|(n, _, _)| *n == name) {
                return self.call(f, arity, name, span);
            }
            let near = self
                .scope
                .names()
                .map(|n| (strsim::damerau_levenshtein(n, name), n))
                .filter(|(d, n)| *d <= 2.max(n.len() / 3) && *d < name.len())
                .min()
                .map(|(_, n)| n.to_string());
            let help = match near {
                Some(n) => format!("did you mean `{n}`?"),
                None => {
                    "use a formal parameter of the rule, a `define`d constant or a function".into()
                }
            };
            return Err(error(format!("unknown name `{name}`"), span, help));
        }
        Err(self.unexpected())
    }

    fn call(
        &mut self,
        f: crate::model::param::Func,
        arity: usize,
        name: &str,
        span: Span,
    ) -> Result<Expr, Box<Diagnostic>> {
        if !self.eat("(") {
            return Err(error(
                format!("`{name}` is a function"),
                span,
                format!("call it with {arity} argument(s): `{name}(...)`"),
            ));
        }
        let mut args = Vec::new();
        if !self.eat(")") {
            loop {
                args.push(self.or()?);
                if self.eat(",") {
                    continue;
                }
                if self.eat(")") {
                    break;
                }
                return Err(error(
                    format!("`{name}(` without its `)`"),
                    span.start..self.at + self.s.len(),
                    "separate the arguments with `,` and close the parenthesis",
                ));
            }
        }
        if args.len() != arity {
            return Err(error(
                format!("`{name}` takes {arity} argument(s), not {}", args.len()),
                span.start..self.at + self.i,
                format!("write `{name}` with {arity} argument(s)"),
            ));
        }
        Ok(Expr::Call(f, args))
    }
}
