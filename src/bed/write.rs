//! The canonical BED writer: deterministic, diff-friendly text.
//!
//! ```text
//! 2DTree
//! (76, 150)
//! L=10(0) B=1(0) A=30
//! RULE
//! R1: [+F][-F]
//! SEED
//! F
//! R1{
//!   R1{,},
//!   ,
//! }
//! ENDSEED
//! LAYOUT
//! (clGreen) <RoundRect (0, 0, 180, 192, 7, 7)>
//! ENDLAYOUT
//! ```
//!
//! - header: name, root, then `L=l(dl) B=b(db)`, `A=` and `C=` only if given;
//! - `RULE`, one rule per line as `NAME: body`, a successor name separated
//!   from the branch's drawing by a space (`[+F R2]`); an alternative as
//!   `R1.2 (0.25): body` in a BED and `R1 (0.25): body` in an OD;
//! - seed: one term per line, indented two spaces per nesting depth up to
//!   depth [`MAX_INDENT_DEPTH`] (deeper terms stay at that column, so a
//!   deep vine's file grows linearly with its depth, not quadratically). A term
//!   whose slots are all empty stays on one line (`R1{,,}`). Otherwise its
//!   slots follow on their own lines, a comma after every slot but the last;
//!   an empty slot that is not the last is a line holding just `,`, an
//!   empty last slot writes nothing. Drawing runs, `[I n X]` and fixed
//!   figures get their own lines. In a BED every term is written in full
//!   (`R1{,}`); a growth point of an OD (`bare`) stays a bare name;
//! - layout shapes in the spelling they were read in; a 3D layout's
//!   volumes as section 11 spells them (`Extrude <Ellipse (0, 0), 10, 20>,
//!   -5, 5`, the inner shape in its start-and-size spelling);
//! - a 3D description's roots with three coordinates and its `D=`;
//! - numbers with at most three decimals, integers without a dot (the root
//!   and the stem parameters with more when three would change them: the
//!   BED must draw the tree that grew); LF line
//!   ends and a trailing newline.
//!
//! Drawing letters that could be read back as a rule name (with a rule
//! called `FF`, the drawing `FF`) are written one letter at a time (`F F`).
//!
//! The writer is iterative: a depth-first-grown vine can nest its terms
//! thousands deep.

/// Nesting depth beyond which seed lines are indented no further.
pub const MAX_INDENT_DEPTH: usize = 24;

use std::fmt::Write as _;

use crate::model::seed_walk::{At, SeedStep, SeedWalk};
use crate::model::walk::{self, Step};
use crate::model::{
    Body, Description, Fixed, LayoutShape, Repeat, Seed, Shape, Solid, Spelling, Term,
};

/// Writes `desc` as a `.bed` file: header, rules, one seed term per line
/// indented by depth, at most three decimals, LF line ends, trailing newline.
pub fn write(desc: &Description) -> String {
    let w = Writer { desc };
    let mut out = String::new();
    out.push_str(&desc.name);
    out.push('\n');
    out.push_str(&root(desc.root, desc.root_z));
    for t in &desc.forest {
        out.push(' ');
        out.push_str(&root(t.root, t.root_z));
    }
    out.push('\n');
    let p = &desc.params;
    let _ = write!(
        out,
        "L={}({}) B={}({})",
        exact(p.length.base),
        exact(p.length.decrement),
        exact(p.width.base),
        exact(p.width.decrement)
    );
    if let Some(a) = p.angle {
        let _ = write!(out, " A={}", exact(a));
    }
    if let Some(c) = p.clearance {
        let _ = write!(out, " C={}", exact(c));
    }
    if let Some(d) = p.divergence {
        let _ = write!(out, " D={}", exact(d));
    }
    if let Some(s) = &p.stroke {
        let _ = write!(out, " S={}", s.text);
    }
    if let Some(g) = &p.background {
        let _ = write!(out, " G={}", g.text);
    }
    if let Some((name, _)) = &p.leaf {
        let _ = write!(out, " P={name}");
    }
    out.push_str("\nRULE\n");
    for r in &desc.rules {
        // An OD gives a name several bodies (`R1 (0.6): ...`); a BED names
        // each alternative (`R1.1 (0.6): ...`).
        let name = match desc.format {
            crate::model::Format::Od => std::borrow::Cow::Borrowed(r.name.as_str()),
            crate::model::Format::Bed => r.full_name(),
        };
        let _ = match r.alternative.as_ref().and_then(|a| a.probability) {
            Some(p) => writeln!(out, "{name} ({}): {}", num_p(p), w.body(&r.body)),
            None => writeln!(out, "{name}: {}", w.body(&r.body)),
        };
    }
    let seeds = std::iter::once(desc.seed.as_ref())
        .chain(desc.forest.iter().map(|t| t.seed.as_ref()))
        .flatten();
    for seed in seeds {
        out.push_str("SEED\n");
        w.seed(seed, &mut out);
        out.push_str("ENDSEED\n");
    }
    if let Some(block) = &desc.surfaces {
        out.push_str("SURFACES\n");
        for line in &block.lines {
            out.push_str(line);
            out.push('\n');
        }
        out.push_str("ENDSURFACES\n");
    }
    if let Some(layout) = &desc.layout {
        out.push_str("LAYOUT\n");
        for s in &layout.shapes {
            out.push_str(&shape_line(s));
            out.push('\n');
        }
        for s in &layout.solids {
            let _ = writeln!(out, "({}) {}", s.color_text, solid(&s.solid));
        }
        out.push_str("ENDLAYOUT\n");
    }
    out
}

/// A root: `(x, y)`, or `(x, y, z)` in a 3D description.
fn root((x, y): (f64, f64), z: Option<f64>) -> String {
    match z {
        Some(z) => format!("({}, {}, {})", exact(x), exact(y), exact(z)),
        None => format!("({}, {})", exact(x), exact(y)),
    }
}

/// A probability: up to six decimals (they must sum to 1 within 1e-6),
/// trailing zeros trimmed.
fn num_p(v: f64) -> String {
    crate::num::fixed(v, 6, crate::num::Trim::Zeros)
}

/// A number with at most three decimals; integers without a dot; no `-0`.
pub fn num(v: f64) -> String {
    crate::num::fixed(v, 3, crate::num::Trim::Zeros)
}

/// [`num`] when that reads back exactly, else every digit needed
/// ([`crate::num::exact`]): the root and the stem parameters, so the BED
/// draws the tree that grew (a width decrement of 0.9999999999 written as
/// `1` would leave order 3 of `B=3` without width, and the BED invalid).
fn exact(v: f64) -> String {
    crate::num::exact(v, 3)
}

struct Writer<'a> {
    desc: &'a Description,
}

impl Writer<'_> {
    /// The name a term writes: the alternative that grew (`R1.2`).
    fn term_name(&self, id: crate::model::RuleId) -> std::borrow::Cow<'_, str> {
        self.desc
            .rules
            .get(id.0)
            .map_or(std::borrow::Cow::Borrowed("?"), |r| r.full_name())
    }

    /// The name a body or a repeat writes: the rule, any alternative.
    fn name(&self, id: crate::model::RuleId) -> &str {
        self.desc
            .rules
            .get(id.0)
            .map(|r| r.name.as_str())
            .unwrap_or("?")
    }

    /// Whether some rule name starts inside this run of letters, so that
    /// reading it back would find a rule.
    fn ambiguous(&self, letters: &str) -> bool {
        (0..letters.len()).any(|i| {
            self.desc
                .rules
                .iter()
                .any(|r| !r.name.is_empty() && letters[i..].starts_with(r.name.as_str()))
        })
    }

    /// Drawing components as text that reads back as the same components.
    fn draw(&self, text: &str) -> String {
        let mut out = String::with_capacity(text.len());
        let mut letters = String::new();
        let flush = |letters: &mut String, out: &mut String| {
            if letters.is_empty() {
                return;
            }
            if self.ambiguous(letters) {
                if out.ends_with(|c: char| c.is_ascii_alphanumeric()) {
                    out.push(' ');
                }
                let spaced: Vec<String> = letters.chars().map(String::from).collect();
                out.push_str(&spaced.join(" "));
            } else {
                out.push_str(letters);
            }
            letters.clear();
        };
        for c in text.chars() {
            if c.is_ascii_alphanumeric() || c == '_' {
                letters.push(c);
            } else {
                flush(&mut letters, &mut out);
                out.push(c);
            }
        }
        flush(&mut letters, &mut out);
        out
    }

    fn fixed(&self, f: &Fixed) -> String {
        format!("[I {} {}]", f.count, self.draw(&f.word))
    }

    fn repeat(&self, r: &Repeat) -> String {
        format!("[I {} {}]", r.count, self.name(r.rule))
    }

    fn body(&self, body: &Body) -> String {
        let mut out = String::new();
        for step in walk::steps(body) {
            match step {
                Step::Run(d) => out.push_str(&self.draw(&d.text)),
                Step::Fixed(f) => out.push_str(&self.fixed(f)),
                Step::Open { .. } => out.push('['),
                Step::Tip { branch, .. } => {
                    if let Some(s) = &branch.successor {
                        if !branch.pieces.is_empty() {
                            out.push(' ');
                        }
                        out.push_str(self.name(s.rule));
                    }
                    out.push(']');
                }
            }
        }
        out
    }

    /// A term on one line if it has no filled slot: `R1{,,}` (or `R1` for
    /// an OD growth point).
    fn flat(&self, t: Term<'_>) -> Option<String> {
        if t.bare() {
            return Some(self.name(t.rule()).to_string());
        }
        t.all_empty().then(|| {
            format!(
                "{}{{{}}}",
                self.term_name(t.rule()),
                ",".repeat(t.slot_count().saturating_sub(1))
            )
        })
    }

    /// Writes the seed's items, one line per item and per term of a term
    /// written out (slots indented by depth), in one walk.
    fn seed(&self, seed: &Seed, out: &mut String) {
        // Indentation stops growing at MAX_INDENT_DEPTH: a depth-first vine
        // can nest thousands of levels, and indenting each by its depth
        // would make the file grow with the square of the depth.
        let spaces = " ".repeat(2 * MAX_INDENT_DEPTH);
        let indent = |out: &mut String, order: u32| {
            let depth = order.saturating_sub(1) as usize;
            out.push_str(&spaces[..2 * depth.min(MAX_INDENT_DEPTH)]);
        };
        // Ends a line, with the comma of a slot before the last.
        let end = |out: &mut String, at: At| {
            if matches!(at, At::Slot { .. }) && !at.last_slot() {
                out.push(',');
            }
            out.push('\n');
        };
        let mut walk = SeedWalk::written(seed);
        while let Some(step) = walk.next() {
            match step {
                SeedStep::Run(d) => {
                    out.push_str(&self.draw(&d.text));
                    out.push('\n');
                }
                SeedStep::Fixed(f) => {
                    out.push_str(&self.fixed(f));
                    out.push('\n');
                }
                SeedStep::Repeat { repeat, order, at } => {
                    indent(out, order);
                    out.push_str(&self.repeat(repeat));
                    end(out, at);
                }
                // A term with no filled slot on one line, else its opening
                // line, its slots, and its `}` line.
                SeedStep::Term { term, order, at } => {
                    indent(out, order);
                    match self.flat(term) {
                        Some(line) => {
                            out.push_str(&line);
                            end(out, at);
                            walk.step_over();
                        }
                        None => {
                            out.push_str(&self.term_name(term.rule()));
                            out.push_str("{\n");
                        }
                    }
                }
                SeedStep::Empty { order, at } => {
                    if !at.last_slot() {
                        indent(out, order);
                        out.push_str(",\n");
                    }
                }
                SeedStep::End { order, at } => {
                    indent(out, order);
                    out.push('}');
                    end(out, at);
                }
                SeedStep::Level { .. } | SeedStep::Open | SeedStep::Close => {}
            }
        }
    }
}

/// `(clGreen) <RoundRect (0, 0, 180, 192, 7, 7)>`.
fn shape_line(s: &LayoutShape) -> String {
    let body = shape(&s.shape, s.spelling);
    if s.angled {
        format!("({}) <{}>", s.color_text, body)
    } else {
        format!("({}) {}", s.color_text, body)
    }
}

/// A volume as section 11 spells it; an extruded or revolved shape in
/// angle brackets, in its start-and-size spelling (a round rectangle with
/// two corner radii, a polygon: their own).
fn solid(s: &Solid) -> String {
    let n = |v: f64| num(v);
    let p = |v: [f64; 3]| format!("({}, {}, {})", n(v[0]), n(v[1]), n(v[2]));
    match s {
        Solid::Box { corner, size } => format!(
            "Box {}, {}, {}, {}",
            p(*corner),
            n(size[0]),
            n(size[1]),
            n(size[2])
        ),
        Solid::Sphere { centre, r } => format!("Sphere {}, {}", p(*centre), n(*r)),
        Solid::Ellipsoid { centre, radii } => format!(
            "Ellipsoid {}, {}, {}, {}",
            p(*centre),
            n(radii[0]),
            n(radii[1]),
            n(radii[2])
        ),
        Solid::Cylinder { base, r, h } => format!("Cylinder {}, {}, {}", p(*base), n(*r), n(*h)),
        Solid::Extrude { shape: s, z1, z2 } => format!(
            "Extrude <{}>, {}, {}",
            shape(s, canonical(s)),
            n(*z1),
            n(*z2)
        ),
        Solid::Revolve { shape: s } => format!("Revolve <{}>", shape(s, canonical(s))),
    }
}

/// The spelling a shape inside a volume is written in.
fn canonical(s: &Shape) -> Spelling {
    match s {
        Shape::Polygon(_) => Spelling::Points,
        _ => Spelling::StartSize,
    }
}

fn shape(shape: &Shape, spelling: Spelling) -> String {
    let n = |v: f64| num(v);
    match *shape {
        Shape::Rect { x, y, w, h } | Shape::Ellipse { x, y, w, h } => {
            let name = if matches!(shape, Shape::Rect { .. }) {
                "Rectangle"
            } else {
                "Ellipse"
            };
            if spelling == Spelling::Corners {
                format!("{name} ({}, {}, {}, {})", n(x), n(y), n(x + w), n(y + h))
            } else {
                format!("{name} ({}, {}), {}, {}", n(x), n(y), n(w), n(h))
            }
        }
        Shape::RoundRect { x, y, w, h, rx, ry } => {
            if spelling == Spelling::Corners || rx != ry {
                format!(
                    "RoundRect ({}, {}, {}, {}, {}, {})",
                    n(x),
                    n(y),
                    n(x + w),
                    n(y + h),
                    n(2.0 * rx),
                    n(2.0 * ry)
                )
            } else {
                format!(
                    "RoundRect ({}, {}), {}, {}, {}",
                    n(x),
                    n(y),
                    n(w),
                    n(h),
                    n(rx)
                )
            }
        }
        Shape::Polygon(ref pts) => {
            let p: Vec<String> = pts
                .iter()
                .map(|&(x, y)| format!("({}, {})", n(x), n(y)))
                .collect();
            format!("Polygon {}", p.join(", "))
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn numbers_have_at_most_three_decimals() {
        assert_eq!(num(10.0), "10");
        assert_eq!(num(-0.0), "0");
        assert_eq!(num(2.5), "2.5");
        assert_eq!(num(1.0 / 3.0), "0.333");
        assert_eq!(num(-0.0001), "0");
        assert_eq!(num(12.345), "12.345");
    }
}
