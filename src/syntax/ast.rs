//! Typed syntax trees of Outline Descriptions (`.od`) and Branch-Expansion
//! Descriptions (`.bed`), after name resolution.
//!
//! One type serves both formats: a BED is a [`Description`] whose seed holds
//! its growth decisions written out. Every node keeps the byte [`Span`] of its
//! text; spans never take part in equality ([`Spanned`] and the `span` fields
//! compare equal whatever they hold), so `parse(write(x)) == x` can be tested.
//!
//! Numbers are `f64` as written; the writer prints them with at most three
//! decimals.

use std::fmt;

use crate::color::Rgb;
use crate::diag::Span;

/// A byte span that every comparison ignores.
#[derive(Debug, Clone, Default)]
pub struct Loc(pub Span);

impl PartialEq for Loc {
    fn eq(&self, _other: &Self) -> bool {
        true
    }
}

impl From<Span> for Loc {
    fn from(s: Span) -> Self {
        Loc(s)
    }
}

/// Which of the two STL formats a description came from (or goes to).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Format {
    /// Outline Description: rule references in the seed are growth points.
    Od,
    /// Branch-Expansion Description: every decision written out.
    Bed,
}

/// A whole `.od` or `.bed` file.
#[derive(Debug, Clone, PartialEq)]
pub struct Description {
    /// Which format it was read as.
    pub format: Format,
    /// Tree name (`2DTree`).
    pub name: String,
    /// Where the name is.
    pub name_loc: Loc,
    /// Root coordinate, canvas units.
    pub root: (f64, f64),
    /// Where the root is.
    pub root_loc: Loc,
    /// Stem parameters.
    pub params: StemParams,
    /// Growth rules, in declaration order; [`RuleId`] indexes this.
    pub rules: Vec<RuleDef>,
    /// The seed as written, `None` if the file has no `SEED` section (then
    /// the seed is `F` followed by the first rule: see [`Description::effective_seed`]).
    pub seed: Option<Seed>,
    /// The layout, if any.
    pub layout: Option<Layout>,
}

/// `L=10(0) B=1(0) A=30 C=1`.
#[derive(Debug, Clone, PartialEq)]
pub struct StemParams {
    /// `L`: segment length at order 0.
    pub length: f64,
    /// `L`'s decrement per order.
    pub length_dec: f64,
    /// `B`: stroke width (broadness) at order 0.
    pub width: f64,
    /// `B`'s decrement per order.
    pub width_dec: f64,
    /// `A`: turning angle in degrees (ours; default 30), `None` if not written.
    pub angle: Option<f64>,
    /// `C`: clearance between stems (ours), `None` if not written.
    pub clearance: Option<f64>,
    /// Where the parameters are.
    pub loc: Loc,
}

/// Default turning angle when `A=` is not given (degrees).
pub const DEFAULT_ANGLE: f64 = 30.0;

impl StemParams {
    /// The turning angle in force.
    pub fn angle(&self) -> f64 {
        self.angle.unwrap_or(DEFAULT_ANGLE)
    }

    /// Segment length of a stem of `order`.
    pub fn length_at(&self, order: u32) -> f64 {
        self.length - f64::from(order) * self.length_dec
    }

    /// Stroke width of a stem of `order`.
    pub fn width_at(&self, order: u32) -> f64 {
        self.width - f64::from(order) * self.width_dec
    }

    /// Whether a stem of `order` can exist (length and width both positive).
    pub fn can_grow_at(&self, order: u32) -> bool {
        self.length_at(order) > 0.0 && self.width_at(order) > 0.0
    }
}

/// Index of a rule in [`Description::rules`].
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord, Hash)]
pub struct RuleId(pub usize);

/// `R1: [+F][-F]`.
#[derive(Debug, Clone, PartialEq)]
pub struct RuleDef {
    /// The rule's name.
    pub name: String,
    /// Where the name is.
    pub name_loc: Loc,
    /// What the rule draws.
    pub body: Body,
    /// The whole definition.
    pub loc: Loc,
}

impl RuleDef {
    /// Number of branches (top-level bracket groups): the slot count of its terms.
    pub fn branch_count(&self) -> usize {
        self.body
            .items
            .iter()
            .filter(|i| matches!(i, BodyItem::Branch(_)))
            .count()
    }
}

/// A rule's body: trunk pieces and branches, in written order.
#[derive(Debug, Clone, PartialEq)]
pub struct Body {
    /// The items in written order.
    pub items: Vec<BodyItem>,
}

/// One top-level item of a rule body.
#[derive(Debug, Clone, PartialEq)]
pub enum BodyItem {
    /// Drawing components outside any branch (trunk); no brackets.
    Draw(DrawRun),
    /// A fixed figure `[I n w]` (classic rewriting of `F` by `w`, n times).
    Fixed(Fixed),
    /// A top-level bracket group: one branch, one slot.
    Branch(Branch),
}

/// One branch: `[+F R2]`.
#[derive(Debug, Clone, PartialEq)]
pub struct Branch {
    /// What the branch draws (may hold nested brackets, which are drawing).
    pub pieces: Vec<Piece>,
    /// The rule named at the end of the branch, growing at its tip in an OD
    /// (`None`: the enclosing rule itself, self-resemblance). Draws nothing.
    pub successor: Option<RuleRef>,
    /// The whole bracket group.
    pub loc: Loc,
}

/// Drawing inside a branch.
#[derive(Debug, Clone, PartialEq)]
pub enum Piece {
    /// Drawing components, nested brackets included.
    Draw(DrawRun),
    /// A fixed figure `[I n w]`.
    Fixed(Fixed),
}

/// A run of drawing components `F f + - L R [ ] |` (whitespace removed).
#[derive(Debug, Clone, PartialEq)]
pub struct DrawRun {
    /// The components, one char each.
    pub text: String,
    /// Where they are.
    pub loc: Loc,
}

/// A reference to a rule by name, resolved.
#[derive(Debug, Clone, PartialEq)]
pub struct RuleRef {
    /// Which rule.
    pub rule: RuleId,
    /// Where the name is.
    pub loc: Loc,
}

/// `[I n w]` with `w` a string of drawing components: `F` rewritten by `w`,
/// `n` times (`[I 1 w]` draws `w`).
#[derive(Debug, Clone, PartialEq)]
pub struct Fixed {
    /// `n`.
    pub count: u32,
    /// `w`: drawing components only.
    pub word: String,
    /// The whole form.
    pub loc: Loc,
}

/// The seed: what grows from the root.
#[derive(Debug, Clone, PartialEq)]
pub struct Seed {
    /// Items in written order.
    pub items: Vec<SeedItem>,
    /// The `SEED ... ENDSEED` section.
    pub loc: Loc,
}

/// One item of a seed. Brackets in `Draw` runs may enclose later items
/// (`[+F R1]` is `Draw("[+F")`, `Term(R1)`, `Draw("]")`); the seed as a whole
/// is balanced.
#[derive(Debug, Clone, PartialEq)]
pub enum SeedItem {
    /// Drawing components.
    Draw(DrawRun),
    /// A fixed figure `[I n w]`.
    Fixed(Fixed),
    /// A branch-expansion term or a bare rule reference.
    Term(Term),
    /// `[I n X]` with `X` a rule.
    Repeat(Repeat),
}

/// `X{s1,...,sm}`: rule `X` drawn here, slot `i` growing at the tip of branch `i`.
///
/// Terms nest as deep as the input does (up to `--max-nesting`), so
/// `Clone`, `PartialEq` and `Drop` are written with explicit stacks rather
/// than derived: derived ones recurse once per level and would overflow a
/// thread's stack on a deeply nested BED. `Debug` shows the first
/// [`DEBUG_DEPTH`] levels and elides the rest.
pub struct Term {
    /// The rule.
    pub rule: RuleId,
    /// One entry per branch of the rule; `None` for an empty slot.
    pub slots: Vec<Option<Slot>>,
    /// Written as a bare name (`R1`) rather than `R1{...}`. In an OD a bare
    /// reference is a growth point. In a BED a bare name means every slot
    /// empty, so the BED parser stores it as `bare: false` with empty slots
    /// (the writer always writes the full form).
    pub bare: bool,
    /// The whole term.
    pub loc: Loc,
}

impl Clone for Term {
    fn clone(&self) -> Self {
        /// A term being copied: its source and the slots copied so far.
        struct Frame<'a> {
            src: &'a Term,
            slots: Vec<Option<Slot>>,
        }
        fn frame(src: &Term) -> Frame<'_> {
            Frame {
                src,
                slots: Vec::with_capacity(src.slots.len()),
            }
        }
        let mut stack = vec![frame(self)];
        loop {
            let top = stack.last_mut().expect("a frame until the root is done");
            if let Some(slot) = top.src.slots.get(top.slots.len()) {
                match slot {
                    None => top.slots.push(None),
                    Some(Slot::Repeat(r)) => top.slots.push(Some(Slot::Repeat(r.clone()))),
                    Some(Slot::Term(t)) => stack.push(frame(t)),
                }
                continue;
            }
            let done = stack.pop().expect("the top frame");
            let copy = Term {
                rule: done.src.rule,
                slots: done.slots,
                bare: done.src.bare,
                loc: done.src.loc.clone(),
            };
            match stack.last_mut() {
                Some(parent) => parent.slots.push(Some(Slot::Term(copy))),
                None => return copy,
            }
        }
    }
}

impl PartialEq for Term {
    fn eq(&self, other: &Self) -> bool {
        let mut stack = vec![(self, other)];
        while let Some((a, b)) = stack.pop() {
            if a.rule != b.rule
                || a.bare != b.bare
                || a.loc != b.loc
                || a.slots.len() != b.slots.len()
            {
                return false;
            }
            for pair in a.slots.iter().zip(&b.slots) {
                match pair {
                    (None, None) => {}
                    (Some(Slot::Term(x)), Some(Slot::Term(y))) => stack.push((x, y)),
                    (Some(Slot::Repeat(x)), Some(Slot::Repeat(y))) if x == y => {}
                    _ => return false,
                }
            }
        }
        true
    }
}

impl Drop for Term {
    fn drop(&mut self) {
        // Detach every nested term's slots before it is dropped, so each
        // drop below meets empty slots and nothing recurses.
        let mut pending = std::mem::take(&mut self.slots);
        while let Some(slot) = pending.pop() {
            if let Some(Slot::Term(mut t)) = slot {
                pending.append(&mut t.slots);
            }
        }
    }
}

/// How many levels of nested terms `{:?}` shows; deeper terms print as
/// `Term { rule: .., .. }`. Formatting recurses once per level shown, so the
/// cap keeps `{:?}` of a hostile, 10 000-deep term within an ordinary stack.
pub const DEBUG_DEPTH: usize = 32;

impl fmt::Debug for Term {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        TermDebug(self, DEBUG_DEPTH).fmt(f)
    }
}

/// A term formatted with `levels` more levels of nesting to show.
struct TermDebug<'a>(&'a Term, usize);

/// A slot inside a [`TermDebug`].
struct SlotDebug<'a>(&'a Option<Slot>, usize);

impl fmt::Debug for TermDebug<'_> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let TermDebug(term, levels) = *self;
        let mut s = f.debug_struct("Term");
        s.field("rule", &term.rule);
        if levels == 0 {
            return s.finish_non_exhaustive();
        }
        let slots: Vec<SlotDebug<'_>> = term
            .slots
            .iter()
            .map(|slot| SlotDebug(slot, levels - 1))
            .collect();
        s.field("slots", &slots)
            .field("bare", &term.bare)
            .field("loc", &term.loc)
            .finish()
    }
}

impl fmt::Debug for SlotDebug<'_> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        /// The slot inside `Some(..)`.
        struct Inner<'a>(&'a Slot, usize);
        impl fmt::Debug for Inner<'_> {
            fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
                match self.0 {
                    Slot::Term(t) => f.debug_tuple("Term").field(&TermDebug(t, self.1)).finish(),
                    Slot::Repeat(r) => f.debug_tuple("Repeat").field(r).finish(),
                }
            }
        }
        match self.0 {
            None => f.write_str("None"),
            Some(slot) => f.debug_tuple("Some").field(&Inner(slot, self.1)).finish(),
        }
    }
}

/// What grows at a branch tip.
#[derive(Debug, Clone, PartialEq)]
pub enum Slot {
    /// Another term (or bare reference).
    Term(Term),
    /// `[I n X]`.
    Repeat(Repeat),
}

/// `[I n X]` with `X` a rule: `X` here and again at every branch tip, `n`
/// levels in all.
#[derive(Debug, Clone, PartialEq)]
pub struct Repeat {
    /// `n`.
    pub count: u32,
    /// `X`.
    pub rule: RuleId,
    /// The whole form.
    pub loc: Loc,
}

/// `LAYOUT ... ENDLAYOUT`: shapes painted in order on a white canvas.
#[derive(Debug, Clone, PartialEq)]
pub struct Layout {
    /// Shapes in painting order.
    pub shapes: Vec<LayoutShape>,
    /// The section.
    pub loc: Loc,
}

/// `(clGreen) RoundRect (0,0,180,192,7,7)`.
#[derive(Debug, Clone, PartialEq)]
pub struct LayoutShape {
    /// Fill colour; white erases.
    pub color: Rgb,
    /// The colour as written (`clGreen`, `#00ff00`), kept for the writer.
    pub color_text: String,
    /// The geometry, normalised.
    pub shape: Shape,
    /// Which of the paper's two spellings was used (the writer keeps it).
    pub spelling: Spelling,
    /// Whether the paper's `< ... >` brackets were written around the shape.
    pub angled: bool,
    /// The whole line.
    pub loc: Loc,
}

/// The two ways the paper writes shape arguments.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Spelling {
    /// `Rectangle (x,y), w, h` / `RoundRect (x,y), w, h, r` (Table 1).
    StartSize,
    /// `Rectangle (x1,y1,x2,y2)` / `RoundRect (x1,y1,x2,y2,rx,ry)` (Delphi's
    /// `TCanvas` arguments: two corners, then the corner ellipse's size).
    Corners,
    /// `Polygon (x1,y1), (x2,y2), ...`.
    Points,
}

/// Layout geometry in canvas units, normalised: `(x, y)` is the top-left
/// corner, `w` and `h` are positive.
#[derive(Debug, Clone, PartialEq)]
pub enum Shape {
    /// An axis-aligned rectangle.
    Rect {
        /// Left.
        x: f64,
        /// Top.
        y: f64,
        /// Width.
        w: f64,
        /// Height.
        h: f64,
    },
    /// A rectangle with elliptic corners of radii `rx`, `ry`.
    RoundRect {
        /// Left.
        x: f64,
        /// Top.
        y: f64,
        /// Width.
        w: f64,
        /// Height.
        h: f64,
        /// Corner radius along x (half Delphi's ellipse width).
        rx: f64,
        /// Corner radius along y.
        ry: f64,
    },
    /// The ellipse inscribed in the box.
    Ellipse {
        /// Left.
        x: f64,
        /// Top.
        y: f64,
        /// Width.
        w: f64,
        /// Height.
        h: f64,
    },
    /// A closed polygon (at least 3 points, in written order).
    Polygon(Vec<(f64, f64)>),
}

impl Description {
    /// The rule a [`RuleId`] names.
    pub fn rule(&self, id: RuleId) -> &RuleDef {
        &self.rules[id.0]
    }

    /// Looks a rule up by name.
    pub fn rule_id(&self, name: &str) -> Option<RuleId> {
        self.rules.iter().position(|r| r.name == name).map(RuleId)
    }

    /// The seed in force: the written one, or `F` and a bare reference to
    /// the first rule (Figure 9's `Seed(T) = FR1`). `None` if there is no
    /// seed and no rule.
    pub fn effective_seed(&self) -> Option<std::borrow::Cow<'_, Seed>> {
        if let Some(s) = &self.seed {
            return Some(std::borrow::Cow::Borrowed(s));
        }
        if self.rules.is_empty() {
            return None;
        }
        Some(std::borrow::Cow::Owned(Seed {
            items: vec![
                SeedItem::Draw(DrawRun {
                    text: "F".into(),
                    loc: Loc::default(),
                }),
                SeedItem::Term(Term {
                    rule: RuleId(0),
                    slots: vec![None; self.rules[0].branch_count()],
                    bare: true,
                    loc: Loc::default(),
                }),
            ],
            loc: Loc::default(),
        }))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn term(rule: usize, slots: Vec<Option<Slot>>) -> Term {
        Term {
            rule: RuleId(rule),
            slots,
            bare: false,
            loc: Loc(0..1),
        }
    }

    fn repeat(count: u32) -> Option<Slot> {
        Some(Slot::Repeat(Repeat {
            count,
            rule: RuleId(0),
            loc: Loc(0..1),
        }))
    }

    /// `R1{R2{[I 2 R1],},,R1{,}}` and variants differing in one place.
    fn sample(inner_count: u32, inner_rule: usize) -> Term {
        term(
            0,
            vec![
                Some(Slot::Term(term(1, vec![repeat(inner_count), None]))),
                None,
                Some(Slot::Term(term(inner_rule, vec![None, None]))),
            ],
        )
    }

    #[test]
    fn terms_clone_equal_and_differ_where_they_differ() {
        let a = sample(2, 0);
        let copy = a.clone();
        assert!(copy == a);
        assert!(sample(3, 0) != a, "a repeat count deep inside");
        assert!(sample(2, 1) != a, "the last slot's rule");
        let mut other_kind = a.clone();
        other_kind.slots[1] = repeat(2);
        assert!(other_kind != a, "empty slot against a repeat");
        let mut fewer = a.clone();
        fewer.slots.pop();
        assert!(fewer != a, "slot count");
        // Locations never count.
        let mut moved = a.clone();
        moved.loc = Loc(5..9);
        assert!(moved == a);
    }

    /// `{:?}` reads like the derived form for shallow terms and stops at
    /// `DEBUG_DEPTH` levels for deep ones.
    #[test]
    fn debug_shows_shallow_terms_whole_and_elides_deep_ones() {
        assert_eq!(
            format!("{:?}", term(0, vec![None, repeat(2)])),
            "Term { rule: RuleId(0), slots: [None, Some(Repeat(Repeat { count: 2, \
             rule: RuleId(0), loc: Loc(0..1) }))], bare: false, loc: Loc(0..1) }"
        );
        let mut deep = term(0, vec![None]);
        for _ in 0..50_000 {
            deep = term(0, vec![Some(Slot::Term(deep))]);
        }
        let text = format!("{deep:?}");
        assert_eq!(text.matches("Term {").count(), DEBUG_DEPTH + 1);
        assert!(text.contains("Term { rule: RuleId(0), .. }"));
        let pretty = format!("{deep:#?}");
        assert_eq!(pretty.matches("Term {").count(), DEBUG_DEPTH + 1);
    }
}
