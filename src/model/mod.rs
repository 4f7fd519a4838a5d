//! The model: what stlc's inputs mean, independent of how they are spelled.
//!
//! [`syntax`](crate::syntax) produces these types; [`grow`](crate::grow),
//! [`bed`](crate::bed), [`interpret`](crate::interpret) and
//! [`render`](crate::render) consume them.
//!
//! - [`Description`]: an Outline Description (`.od`) or a Branch-Expansion
//!   Description (`.bed`) after name resolution. A BED is a description whose
//!   seed holds its growth decisions written out; [`crate::bed::Bed`] is the
//!   validated, measured form the renderer takes.
//! - [`term`]: branch-expansion terms, the recursive part of a seed.
//! - [`layout`]: the layout shapes as written.
//! - [`walk`]: the one walk over a rule body's steps, the one expander
//!   of fixed figures `[I n w]` and the one of rule repeats `[I n X]`,
//!   used by every pass.
//! - [`seed_walk`]: the one walk over a seed, in written or drawing order.
//! - [`lsys`]: classic L-systems.
//!
//! Every node keeps the byte span of its text in a [`Loc`]; locations never
//! take part in equality, so `parse(write(x)) == x` can be tested. Numbers
//! are `f64` as written; the writer prints them with at most three decimals.

pub mod layout;
pub mod lsys;
pub mod param;
pub use param::SurfaceBlock;
pub mod seed_walk;
pub mod term;
pub mod walk;

pub use layout::{Layout, LayoutShape, LayoutSolid, Shape, Solid, Spelling};
pub use term::{Repeat, Slot, SlotId, Term, TermId, Terms};

use crate::diag::Span;
use crate::num::Linear;

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
    /// The root's third coordinate: `Some` makes the description 3D
    /// (`stl-language.md` section 11; every root of a forest alike).
    pub root_z: Option<f64>,
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
    /// A forest's further trees (roots 2, 3, ... of the root line), empty
    /// for one tree. All trees share the layout; in an OD they all grow
    /// [`Description::seed`], in a BED each has its own.
    pub forest: Vec<Tree>,
    /// `SURFACES ... ENDSURFACES`: the organs `P=` places at the tips
    /// (`stl-language.md` section 13), kept in a BED as written.
    pub surfaces: Option<SurfaceBlock>,
}

/// A tree's root and the seed in force there ([`Description::trees`]).
pub type TreeSeed<'a> = ((f64, f64), Option<std::borrow::Cow<'a, Seed>>);

/// A tree of a forest after the first: its root and, in a BED, its seed.
#[derive(Debug, Clone, PartialEq)]
pub struct Tree {
    /// Root coordinate, canvas units.
    pub root: (f64, f64),
    /// The root's third coordinate in a 3D forest (as [`Description::root_z`]).
    pub root_z: Option<f64>,
    /// Where the root is.
    pub root_loc: Loc,
    /// In a BED, what grew from it; `None` in an OD.
    pub seed: Option<Seed>,
}

/// `L=10(0) B=1(0) A=30 C=1`.
#[derive(Debug, Clone, PartialEq)]
pub struct StemParams {
    /// `L(dL)`: segment length at order 0 and its decrement per order.
    pub length: Linear,
    /// `B(dB)`: stroke width (broadness) at order 0 and its decrement.
    pub width: Linear,
    /// `A`: turning angle in degrees (ours; default 30), `None` if not written.
    pub angle: Option<f64>,
    /// `C`: clearance between stems (ours), `None` if not written.
    pub clearance: Option<f64>,
    /// `D`: divergence in degrees, 3D only (section 11: every rule
    /// application first rolls its frame by it), `None` if not written.
    pub divergence: Option<f64>,
    /// `S`: the stroke colour the tree is drawn with (ours), `None` if not
    /// written (the renderer's default, or `--stroke`). A ramp
    /// (`S=#5b3a1e..#3b5e2b`) keeps its start here, its text whole.
    pub stroke: Option<Colour>,
    /// The end of an `S=` ramp (section 13): the colour of the deepest
    /// order grown in a tree; `None` for one colour.
    pub stroke_end: Option<crate::color::Rgb>,
    /// `P=X`: the surface drawn at every tip that grew no further, and
    /// where its name is written.
    pub leaf: Option<(char, Loc)>,
    /// `G`: the background (ground) colour, or `none` for transparent
    /// (ours), `None` if not written (white, or `--background`).
    pub background: Option<Colour>,
    /// `O=`, `V=`, `M=`: how an OD grows, kept in its file.
    pub design: Design,
    /// Where the parameters are.
    pub loc: Loc,
}

/// What shapes an OD's growth beyond its rules, kept in the file so that a
/// tree made in the editor grows the same everywhere
/// (`stl-language.md` section 10). The command line overrides each for one
/// run; a BED has none (its decisions are written out).
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct Design {
    /// `O=bfs`, `O=dfs` or `O=space`: the growth order (`--growth`
    /// overrides it).
    pub order: Option<GrowthOrder>,
    /// `V=n`: the seed of the choices (`--seed` overrides it).
    pub seed: Option<u64>,
    /// `M=n`: growth stops after n stems, part of the design (`--max-stems`
    /// stays the resource limit: the smaller wins).
    pub max_stems: Option<u64>,
    /// `N=n`: the number of attraction points space-first growth scatters
    /// over the region (`stl-language.md` section 14); `None`: the default,
    /// one per `L` x `L` of the region's area (`L` cubed of a volume).
    pub points: Option<u64>,
    /// `Q=d`: the radius of influence of a growth point in space-first
    /// growth, canvas units; `None`: the default, 4 stem lengths at the
    /// order the growth point's stems would be drawn (4 `L` without a
    /// length decrement).
    pub reach: Option<f64>,
}

/// The most attraction points space-first growth scatters (`N=`, section
/// 14): a million cost about 100 MB with their grid (docs/growth.md); a
/// larger `N=` is refused where it is written, a default that would pass
/// it is cut down to it.
pub const MAX_ATTRACTION_POINTS: u64 = 1_000_000;

/// The order in which growth points are decided: `O=` in a file,
/// `--growth` of `compile` and `render`, `growth` in the API: the two
/// orders grow different trees from one outline (section 7 of the
/// language notes). The default is breadth-first, the paper's
/// conventional order: balanced trees, level by level. The variants' doc
/// comments are the help of `--growth`.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
#[cfg_attr(feature = "cli", derive(clap::ValueEnum))]
#[cfg_attr(feature = "serde", derive(serde::Deserialize, serde::Serialize))]
#[cfg_attr(feature = "serde", serde(rename_all = "lowercase"))]
pub enum GrowthOrder {
    /// Breadth-first growth (the default): every growth point of a level
    /// before the next; balanced trees.
    #[default]
    Bfs,
    /// Depth-first growth: a branch's whole subtree before its sibling;
    /// vines and spirals.
    Dfs,
    /// Space-first growth: the growth point nearest the most free space
    /// (attraction points scattered over the region) first; crowns that
    /// reach into every corner of their outline.
    Space,
}

impl GrowthOrder {
    /// The name a file, the command line and the API write: `bfs`, `dfs`,
    /// `space`.
    pub fn name(self) -> &'static str {
        match self {
            GrowthOrder::Bfs => "bfs",
            GrowthOrder::Dfs => "dfs",
            GrowthOrder::Space => "space",
        }
    }
}

impl std::fmt::Display for GrowthOrder {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(self.name())
    }
}

/// A colour as a description writes it: `clMaroon`, `#4a2c12`, or `none`
/// (transparent, for a background).
#[derive(Debug, Clone, PartialEq)]
pub struct Colour {
    /// The colour; `None` for `none`.
    pub rgb: Option<crate::color::Rgb>,
    /// As written (the writer keeps it).
    pub text: String,
}

/// Default turning angle when `A=` is not given (degrees).
pub const DEFAULT_ANGLE: f64 = 30.0;

impl StemParams {
    /// The turning angle in force.
    pub fn angle(&self) -> f64 {
        self.angle.unwrap_or(DEFAULT_ANGLE)
    }

    /// Whether a stem of `order` can exist (length and width both positive).
    pub fn can_grow_at(&self, order: u32) -> bool {
        self.length.at(order) > 0.0 && self.width.at(order) > 0.0
    }
}

/// Index of a rule in [`Description::rules`].
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord, Hash)]
pub struct RuleId(pub usize);

/// `R1: [+F][-F]`, or one alternative of a rule: `R1 (0.6): [+F][-F]` in
/// an OD, `R1.1 (0.6): [+F][-F]` in a BED.
#[derive(Debug, Clone, PartialEq)]
pub struct RuleDef {
    /// The rule's name (`R1`; without the alternative's number).
    pub name: String,
    /// Where the name is.
    pub name_loc: Loc,
    /// Which alternative of `name` this is, if the name has several bodies
    /// to choose from.
    pub alternative: Option<Alternative>,
    /// What the rule draws.
    pub body: Body,
    /// The whole definition.
    pub loc: Loc,
}

/// The rules a reference chooses from, for every rule: itself alone, or
/// all the alternatives of its name in number order (a group).
#[derive(Debug, Clone)]
pub struct RuleGroups {
    /// The group of each rule, by [`RuleId`].
    pub of_rule: Vec<usize>,
    /// The groups' members.
    pub groups: Vec<Vec<RuleId>>,
}

impl RuleGroups {
    /// The rules a reference to `r` chooses from (`r` among them).
    pub fn members(&self, r: RuleId) -> &[RuleId] {
        &self.groups[self.of_rule[r.0]]
    }
}

/// One of a rule's bodies, chosen at each application with its probability
/// (section 9 of the language notes).
#[derive(Debug, Clone, PartialEq)]
pub struct Alternative {
    /// 1-based, in the order of the OD's lines: the BED names it `R1.2`.
    pub number: u32,
    /// The probability of choosing it (an OD requires it; a BED keeps it
    /// for the reader, it chooses nothing).
    pub probability: Option<f64>,
}

impl RuleDef {
    /// The name a BED writes and reads: `R1`, or `R1.2` for an alternative.
    pub fn full_name(&self) -> std::borrow::Cow<'_, str> {
        match &self.alternative {
            None => std::borrow::Cow::Borrowed(&self.name),
            Some(a) => std::borrow::Cow::Owned(format!("{}.{}", self.name, a.number)),
        }
    }

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
#[derive(Debug, Clone)]
pub struct Seed {
    /// Items in written order.
    pub items: Vec<SeedItem>,
    /// The terms the items (and their slots) refer to.
    pub terms: Terms,
    /// The `SEED ... ENDSEED` section.
    pub loc: Loc,
}

impl Seed {
    /// The term `id` of this seed.
    pub fn term(&self, id: TermId) -> Term<'_> {
        self.terms.get(id)
    }

    /// Where item `item` is written.
    pub fn item_span(&self, item: &SeedItem) -> Span {
        match item {
            SeedItem::Draw(d) => d.loc.0.clone(),
            SeedItem::Fixed(f) => f.loc.0.clone(),
            SeedItem::Term(t) => self.term(*t).loc(),
            SeedItem::Repeat(r) => r.loc.0.clone(),
        }
    }
}

/// Seeds are equal when their items are, terms compared by shape.
impl PartialEq for Seed {
    fn eq(&self, other: &Self) -> bool {
        self.items.len() == other.items.len()
            && self.items.iter().zip(&other.items).all(|pair| match pair {
                (SeedItem::Term(a), SeedItem::Term(b)) => self.term(*a) == other.term(*b),
                (a, b) => a == b,
            })
    }
}

/// One item of a seed. Brackets in `Draw` runs may enclose later items
/// (`[+F R1]` is `Draw("[+F")`, `Term(R1)`, `Draw("]")`); the seed as a whole
/// is balanced.
///
/// 16 bytes: a generated seed can hold millions of items, so the rarer,
/// larger ones are boxed (docs/limits.md).
#[derive(Debug, Clone, PartialEq)]
pub enum SeedItem {
    /// Drawing components.
    Draw(Box<DrawRun>),
    /// A fixed figure `[I n w]`.
    Fixed(Box<Fixed>),
    /// A branch-expansion term or a bare rule reference, in the seed's
    /// [`Terms`] (compare with [`Seed::term`]s, not ids).
    Term(TermId),
    /// `[I n X]` with `X` a rule.
    Repeat(Box<Repeat>),
}

impl DrawRun {
    /// Drawing components at no place in any text (made by a program).
    pub fn new(text: &str) -> Self {
        DrawRun {
            text: text.into(),
            loc: Loc::default(),
        }
    }
}

impl Fixed {
    /// `[I count word]` at no place in any text (made by a program).
    pub fn new(count: u32, word: &str) -> Self {
        Fixed {
            count,
            word: word.into(),
            loc: Loc::default(),
        }
    }
}

impl Description {
    /// Whether the description is 3D (its root has three coordinates).
    pub fn is_3d(&self) -> bool {
        self.root_z.is_some()
    }

    /// The rule a [`RuleId`] names.
    pub fn rule(&self, id: RuleId) -> &RuleDef {
        &self.rules[id.0]
    }

    /// Looks a rule up by name (`R1`: its first alternative if it has
    /// several; `R1.2`: that alternative).
    pub fn rule_id(&self, name: &str) -> Option<RuleId> {
        self.rules
            .iter()
            .position(|r| r.name == name || r.full_name() == name)
            .map(RuleId)
    }

    /// The rules each reference chooses from ([`RuleGroups`]).
    pub fn groups(&self) -> RuleGroups {
        let mut by_name: std::collections::BTreeMap<&str, usize> = Default::default();
        let mut groups: Vec<Vec<RuleId>> = Vec::new();
        let mut of_rule = Vec::with_capacity(self.rules.len());
        for (i, r) in self.rules.iter().enumerate() {
            let g = match r.alternative {
                None => None,
                Some(_) => by_name.get(r.name.as_str()).copied(),
            };
            let g = g.unwrap_or_else(|| {
                groups.push(Vec::new());
                if r.alternative.is_some() {
                    by_name.insert(&r.name, groups.len() - 1);
                }
                groups.len() - 1
            });
            groups[g].push(RuleId(i));
            of_rule.push(g);
        }
        for g in &mut groups {
            g.sort_by_key(|&r| self.rule(r).alternative.as_ref().map_or(0, |a| a.number));
        }
        RuleGroups { of_rule, groups }
    }

    /// The trees in root order, each with its root and the seed in force
    /// there: in an OD every tree grows [`Description::effective_seed`],
    /// in a BED each tree has its own (the first's is `seed`).
    pub fn trees(&self) -> Vec<TreeSeed<'_>> {
        let mut v = vec![(self.root, self.effective_seed())];
        for t in &self.forest {
            let seed = match self.format {
                Format::Od => self.effective_seed(),
                Format::Bed => t.seed.as_ref().map(std::borrow::Cow::Borrowed),
            };
            v.push((t.root, seed));
        }
        v
    }

    /// Whether any rule has alternatives (the description chooses).
    pub fn chooses(&self) -> bool {
        self.rules.iter().any(|r| r.alternative.is_some())
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
        let mut terms = Terms::new();
        let first = terms.push_leaf(RuleId(0), true, 0..0, self.rules[0].branch_count());
        Some(std::borrow::Cow::Owned(Seed {
            items: vec![
                SeedItem::Draw(Box::new(DrawRun {
                    text: "F".into(),
                    loc: Loc::default(),
                })),
                SeedItem::Term(first),
            ],
            terms,
            loc: Loc::default(),
        }))
    }
}
