//! The colour and organ lines of a `.lsys` file (stl-language.md section
//! 13; docs/lsys.md, *Colours, widths and organs*): `palette`,
//! `width_decay`, `surface X { word }`, and the polygons `{ }` of every
//! word, checked where they are written.

use super::expr::{Scope, error};
use crate::color::Rgb;
use crate::diag::{Diagnostic, Diagnostics, Span};
use crate::model::Loc;
use crate::model::param::{MAX_POLYGON_VERTICES, ModuleExpr, Organs, Surface};

/// One line of a file: its key, the text after it, and where that text
/// starts (comments cut off), and where the line starts and ends.
pub(super) struct Line<'a> {
    pub(super) key: &'a str,
    pub(super) rest: &'a str,
    pub(super) at: usize,
    pub(super) start: usize,
    pub(super) end: usize,
}

/// Reads a word of modules written at a byte of the file (the
/// parametric parser's).
type Word = fn(&str, usize, &Scope) -> Result<Vec<ModuleExpr>, Box<Diagnostic>>;

/// The keys of this part.
pub const ORGAN_KEYS: [&str; 3] = ["palette", "width_decay", "surface"];

/// Whether a word uses a symbol that gained a meaning for colours and
/// organs (outside a module's parameters, where `,` separates them).
pub(super) fn word_uses_organs(w: &str) -> bool {
    let mut depth = 0usize;
    w.chars().any(|c| {
        match c {
            '(' => depth += 1,
            ')' => depth = depth.saturating_sub(1),
            _ => {}
        }
        depth == 0 && crate::model::param::ORGAN_SYMBOLS.contains(&c)
    })
}

/// Reads one organ line into `o`: `palette`, `width_decay` or `surface`.
pub(super) fn line(
    text: &str,
    l: &Line,
    scope: &Scope,
    word: Word,
    o: &mut Organs,
) -> Result<(), Box<Diagnostic>> {
    match l.key {
        "palette" => palette(text, l, o),
        "width_decay" => {
            let t = l.rest.trim();
            let at = l.at + l.rest.len() - l.rest.trim_start().len();
            let e = super::expr::parse(t, at, scope)?;
            let v = crate::model::param::eval_const(&e);
            if !(v.is_finite() && v >= 0.0) || t.is_empty() {
                return Err(error(
                    "`width_decay` takes one number, 0 or more",
                    l.at..l.end,
                    "write `width_decay 0.7`: a bare `!` multiplies the width by it",
                ));
            }
            o.width_decay = Some(v);
            Ok(())
        }
        "surface" => surface(l, scope, word).map(|s| o.surfaces.push(s)),
        _ => Ok(()),
    }
}

/// `palette C0 C1 ...`: colours as `color` takes them; a `#` that starts
/// no colour starts a comment.
fn palette(text: &str, l: &Line, o: &mut Organs) -> Result<(), Box<Diagnostic>> {
    let raw = &text[l.at..l.end];
    let mut colours = Vec::new();
    let mut off = 0;
    for part in raw.split_whitespace() {
        let i = part.as_ptr() as usize - raw.as_ptr() as usize;
        if i < off {
            continue;
        }
        if part.starts_with('#') && !crate::syntax::is_colour_at(raw, i) {
            break;
        }
        off = i + part.len();
        match Rgb::parse(part) {
            Some(c) => colours.push(c),
            None => {
                let help = match Rgb::suggest(part) {
                    Some(name) => format!("did you mean `{name}`?"),
                    None => "write `#rrggbb` or a Delphi colour name such as `clGreen`".into(),
                };
                let span = l.at + i..l.at + i + part.len();
                return Err(Box::new(crate::syntax::unknown_colour(part, span, help)));
            }
        }
    }
    if colours.is_empty() {
        return Err(error(
            "`palette` takes one colour or more",
            l.at..l.end,
            "write `palette #2e7d32 #f2c14e`: `'` and `;` step to the next colour, `,` back",
        ));
    }
    o.palette = colours;
    Ok(())
}

/// The lines of an OD's or BED's `SURFACES` block (section 13), `text`
/// found at byte `at` of the file: each non-empty line `surface X { word }`
/// as the `.lsys` key reads it (comments cut off), checked for surfaces
/// that place themselves. Returns the surfaces and each one's text.
pub(super) fn surface_block(
    text: &str,
    at: usize,
    word: Word,
    diags: &mut Diagnostics,
) -> (Vec<Surface>, Vec<String>) {
    let mut o = Organs::default();
    let mut lines = Vec::new();
    let no_formals: Vec<String> = Vec::new();
    let scope = Scope {
        formals: &no_formals,
        defines: &[],
    };
    let mut start = 0;
    for raw in text.split_inclusive('\n') {
        let line_at = at + start;
        start += raw.len();
        let body = raw.split('#').next().unwrap_or("");
        let t = body.trim();
        if t.is_empty() {
            continue;
        }
        let lead = body.len() - body.trim_start().len();
        let (s, e) = (line_at + lead, line_at + lead + t.len());
        let key_len = t.find(char::is_whitespace).unwrap_or(t.len());
        if &t[..key_len] != "surface" {
            diags.push(*error(
                "a SURFACES block holds lines `surface X { word }`",
                s..e,
                "write `surface L { [{.+f.-f.-f.+f.}] }` and name it with `P=L` in the header",
            ));
            continue;
        }
        let l = Line {
            key: "surface",
            rest: &t[key_len..],
            at: s + key_len,
            start: s,
            end: e,
        };
        match surface(&l, &scope, word) {
            Ok(sf) => {
                o.surfaces.push(sf);
                lines.push(t.to_string());
            }
            Err(d) => diags.push(*d),
        }
    }
    cycles(&o, diags);
    (o.surfaces, lines)
}

/// `surface X { word }`.
fn surface(l: &Line, scope: &Scope, word: Word) -> Result<Surface, Box<Diagnostic>> {
    let t = l.rest.trim();
    let at = l.at + l.rest.len() - l.rest.trim_start().len();
    let bad = || {
        error(
            "a surface is `surface X { word }`",
            l.at..l.end,
            "name it with one character and write its word in braces: \
             `surface L { [{.+f.-f.-f.+f.}] }`, placed by `~L` (scaled by `~L(s)`)",
        )
    };
    let name = t.chars().next().ok_or_else(bad)?;
    let body = t[name.len_utf8()..].trim_start();
    if name == '{' || !body.starts_with('{') || !body.ends_with('}') || body.len() < 2 {
        return Err(bad());
    }
    let inner = &body[1..body.len() - 1];
    let inner_at = at + (inner.as_ptr() as usize - t.as_ptr() as usize);
    braces(inner, inner_at)?;
    let w = word(inner, inner_at, scope)?;
    Ok(Surface {
        name,
        word: w,
        loc: Loc(l.start..l.end),
    })
}

/// Checks the polygons of a word written at byte `at`: every `{` closed
/// in the word, no `}` without its `{`, at most [`MAX_POLYGON_VERTICES`]
/// vertices written in one. Returns where its first `{` is.
pub(super) fn braces(s: &str, at: usize) -> Result<Option<usize>, Box<Diagnostic>> {
    let mut open: Vec<(usize, usize)> = Vec::new();
    let mut first = None;
    let mut depth = 0usize;
    for (i, c) in s.char_indices() {
        match c {
            '(' => depth += 1,
            ')' => depth = depth.saturating_sub(1),
            _ if depth > 0 => {}
            '{' => {
                first.get_or_insert(at + i);
                open.push((at + i, 0));
            }
            '}' if open.pop().is_none() => {
                return Err(error(
                    "`}` without its `{`",
                    at + i..at + i + 1,
                    "a polygon is `{ ... }` within one word (the axiom, a successor or a surface)",
                ));
            }
            'f' | '.' => {
                if let Some(top) = open.last_mut() {
                    top.1 += 1;
                    if top.1 > MAX_POLYGON_VERTICES {
                        return Err(too_many(top.0..top.0 + 1));
                    }
                }
            }
            _ => {}
        }
    }
    if let Some(&(k, _)) = open.last() {
        return Err(error(
            "this `{` is not closed",
            k..k + 1,
            "close the polygon with `}` in the same word (the axiom, a successor or a surface)",
        ));
    }
    Ok(first)
}

/// The error of a polygon over [`MAX_POLYGON_VERTICES`], at its `{`.
pub fn too_many(span: Span) -> Box<Diagnostic> {
    error(
        format!("a polygon of more than {MAX_POLYGON_VERTICES} vertices"),
        span,
        format!(
            "a polygon records at most {MAX_POLYGON_VERTICES} vertices (each `f` and `.` \
             inside `{{ }}`): close it sooner, or draw it as several"
        ),
    )
}

/// Surfaces placed by themselves, directly or through others: an error
/// at the first such surface's line, naming the way round.
pub(super) fn cycles(o: &Organs, diags: &mut Diagnostics) {
    let index = |c: char| o.surfaces.iter().position(|s| s.name == c);
    let places = |k: usize| -> Vec<usize> {
        let w = &o.surfaces[k].word;
        w.windows(2)
            .filter(|p| p[0].symbol == '~')
            .filter_map(|p| index(p[1].symbol))
            .collect()
    };
    for start in 0..o.surfaces.len() {
        // Depth-first from `start`, looking for a way back to it.
        let mut path = vec![start];
        let mut stack = vec![places(start)];
        let mut seen = vec![false; o.surfaces.len()];
        while let Some(next) = stack.last_mut() {
            let Some(k) = next.pop() else {
                stack.pop();
                path.pop();
                continue;
            };
            if k == start {
                let names: Vec<String> = path
                    .iter()
                    .chain(std::iter::once(&start))
                    .map(|&i| format!("~{}", o.surfaces[i].name))
                    .collect();
                let s = &o.surfaces[start];
                diags.push(*error(
                    format!(
                        "surface `{}` places itself ({})",
                        s.name,
                        names.join(" -> ")
                    ),
                    s.loc.0.clone(),
                    "a surface may place other surfaces, never itself, directly or through another",
                ));
                return;
            }
            if !seen[k] {
                seen[k] = true;
                path.push(k);
                stack.push(places(k));
            }
        }
    }
}
