//! The grower: an Outline Description into a Branch-Expansion Description
//! under space occupancy, breadth-first or depth-first.
//!
//! `docs/growth.md` states the semantics this module implements; in short:
//!
//! - **Growth points** are the rule references of the seed: bare ones (`R1`,
//!   no count) and `[I n R1]` (n levels), at the top level of the seed or in
//!   a slot of a term written out in the seed (`R1{R1,}`). Everything else in
//!   the seed (drawing components, fixed figures, written terms) is drawn as
//!   given and occupies space without being tested.
//! - **Applying** rule `X` at a growth point of order `c` draws all of `X`
//!   (trunk, fixed figures, every branch) from the turtle state there, at
//!   order `c+1`. It succeeds only if that order has a positive length and
//!   width, the order does not exceed `--max-depth`, every segment lies in
//!   the open interior of the layout region ([`region::Region`]) and keeps the
//!   clearance from every segment already placed and from the application's
//!   own earlier segments ([`occupancy::conflicts`], with its joint
//!   exception). On success its segments are placed and the tip of each
//!   branch becomes a growth point for the rule named at the branch's end, or
//!   `X` again, with one level fewer if counted. On failure the slot stays
//!   empty (a failed growth point of the seed is left out of the BED).
//! - **Order of decisions.** `bfs`: a FIFO queue, so every growth point of a
//!   level is decided before the next level, in the order the points were
//!   made (branches in written order); the seed's points are level 1. `dfs`:
//!   a stack, so a branch's whole subtree is decided before its next
//!   sibling. Neither recurses.
//! - **The seed** is walked once in written order. Its drawing is laid down
//!   before its growth points are decided whenever the positions of that
//!   drawing cannot depend on a decision: a growth point is deferred unless
//!   its rule moves or turns the turtle outside its branches *and* more seed
//!   follows it before the enclosing `]`; such a point (and every deferred
//!   one before it) is decided when the walk reaches it, because the drawing
//!   after it starts where its trunk ends.
//! - **Stops.** Counts, decrements, the region and clearance end growth
//!   naturally. `--max-stems` (stems = drawn segments, the seed's included)
//!   stops all growth with a warning when the next application would pass
//!   it; growth applications are limited to the same number (rules that
//!   draw nothing). Growth with no LAYOUT, where a growth point can branch
//!   forever with neither count nor decrement, is refused unless
//!   `--max-stems` was given explicitly ([`GrowOptions::max_stems_explicit`]).

pub mod occupancy;
pub mod region;

use std::collections::VecDeque;

use crate::bed::Bed;
use crate::diag::{Diagnostic, Diagnostics, ErrorKind, Span};
use crate::limits::Limits;
use crate::model::{
    BodyItem, Description, Fixed, Format, Loc, Piece, RuleId, Seed, SeedItem, Slot, StemParams,
    Term,
};
use crate::progress::Progress;
use crate::turtle::{Interp, Op, State};
use crate::turtle::{Point, Recorder};

use occupancy::{Backend, Occupancy, Seg};
use region::Region;

/// The default clearance as a fraction of `L` (the order-0 segment length):
/// `C = L / 10`, so the paper's `L=10` gives `C=1`. A fraction of `L` keeps
/// growth scale-free: scaling root, `L` and layout by a factor scales the
/// grown tree by the same factor, decision for decision.
pub const DEFAULT_CLEARANCE_FRACTION: f64 = 0.1;

/// The clearance used when neither `--clearance` nor `C=` gives one.
pub fn default_clearance(params: &StemParams) -> f64 {
    (params.length.base * DEFAULT_CLEARANCE_FRACTION).max(0.0)
}

/// The order in which growth points are decided (`--strategy` of `compile`):
/// the two orders grow different trees from one outline (section 7 of the
/// language notes). The default is breadth-first, the paper's conventional
/// order: balanced trees, level by level.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum GrowthOrder {
    /// Breadth-first growth: every growth point of a level before the next.
    #[default]
    Bfs,
    /// Depth-first growth: a branch's whole subtree before its next sibling.
    Dfs,
}

/// Options of one growth.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct GrowOptions {
    /// Breadth-first (levels) or depth-first (a branch's subtree before its sibling).
    pub growth: GrowthOrder,
    /// Clearance override (`--clearance`); else `C=` of the OD, else the default.
    pub clearance: Option<f64>,
    /// Limits (`max_stems` among them).
    pub limits: Limits,
    /// Whether `limits.max_stems` was asked for explicitly (`--max-stems N`
    /// on the command line). Only an explicit limit lets growth with no
    /// other bound (no layout, count or decrement) go ahead; the default
    /// limit is a safety net, not a design.
    pub max_stems_explicit: bool,
}

impl Default for GrowOptions {
    /// Breadth-first (the paper's conventional strategy), no clearance
    /// override, default limits, `--max-stems` not given.
    fn default() -> Self {
        GrowOptions {
            growth: GrowthOrder::Bfs,
            clearance: None,
            limits: Limits::default(),
            max_stems_explicit: false,
        }
    }
}

/// The result of growth: the BED and any warnings (a limit that stopped growth).
#[derive(Debug, Clone, PartialEq)]
pub struct Grown {
    /// The Branch-Expansion Description, validated and measured.
    pub bed: Bed,
    /// Warnings, e.g. `--max-stems` reached.
    pub warnings: Vec<Diagnostic>,
    /// Number of stems (segments) in the grown tree.
    pub stems: u64,
}

/// Grows `od` into a BED, with the R-tree occupancy index.
pub fn grow(
    od: &Description,
    opts: &GrowOptions,
    progress: &mut dyn Progress,
) -> Result<Grown, Diagnostics> {
    grow_with(od, opts, Backend::Rstar, progress)
}

/// Grows `od` into a BED with a chosen occupancy index (both give the same
/// result; the choice is for measuring).
pub fn grow_with(
    od: &Description,
    opts: &GrowOptions,
    backend: Backend,
    progress: &mut dyn Progress,
) -> Result<Grown, Diagnostics> {
    let seed = od.effective_seed().ok_or_else(|| {
        Diagnostic::error(ErrorKind::Grow(
            "nothing to grow: the description has no SEED and no rule".into(),
        ))
        .with_help("declare a rule after RULE, or write a SEED")
    })?;
    let clearance = opts
        .clearance
        .or(od.params.clearance)
        .unwrap_or_else(|| default_clearance(&od.params));
    if !clearance.is_finite() || clearance < 0.0 {
        return Err(Diagnostic::error(ErrorKind::Grow(format!(
            "the clearance must be a finite number >= 0, not {clearance}"
        )))
        .with_help("give C= (or --clearance) a value such as 1")
        .into());
    }
    let flat = flatten(od, &seed)?;
    check_bounded(od, &flat.gps, opts)?;

    let region = match &od.layout {
        Some(l) => Some(Region::from_layout(l, opts.limits.max_layout_vertices)?),
        None => None,
    };
    let root = Point::new(od.root.0, od.root.1);
    if let Some(r) = &region {
        if !r.covers_point(root) {
            let mut d = Diagnostic::error(ErrorKind::Grow(format!(
                "the root ({}, {}) lies outside the layout region",
                od.root.0, od.root.1
            )))
            .with_help(
                "move the root into a coloured (non-white) layout shape, or change the LAYOUT",
            );
            if let Some(s) = span_of(&od.root_loc) {
                d = d.with_span(s).with_label("the root");
            }
            return Err(d.into());
        }
    }

    let mut g = Grower::new(od, opts, backend, clearance, region, root, flat.gps.len());
    progress.start("stems", opts.limits.max_stems);
    let walked = g.walk_seed(&flat, progress);
    progress.finish();
    walked?;

    let stems = g.stems;
    let warnings = std::mem::take(&mut g.warnings);
    let items = g.build_seed(&seed);
    let mut params = od.params.clone();
    params.clearance = Some(clearance);
    let desc = Description {
        format: Format::Bed,
        name: od.name.clone(),
        name_loc: od.name_loc.clone(),
        root: od.root,
        root_loc: od.root_loc.clone(),
        params,
        rules: od.rules.clone(),
        seed: Some(Seed {
            items,
            loc: seed.loc.clone(),
        }),
        layout: od.layout.clone(),
    };
    Ok(Grown {
        bed: Bed::new(desc, &opts.limits)?,
        warnings,
        stems,
    })
}

fn span_of(loc: &Loc) -> Option<Span> {
    (loc.0.end > loc.0.start).then(|| loc.0.clone())
}

/// A growth point written in the seed.
#[derive(Debug, Clone)]
struct SeedGp {
    rule: RuleId,
    count: Option<u32>,
    loc: Loc,
}

/// The seed as a flat program.
#[derive(Debug)]
enum Instr<'a> {
    Op(Op),
    Fixed(&'a Fixed),
    Gp(usize),
}

struct Flat<'a> {
    instrs: Vec<Instr<'a>>,
    gps: Vec<SeedGp>,
}

fn rule_error(od: &Description, rule: RuleId, loc: &Loc) -> Option<Diagnostic> {
    if rule.0 < od.rules.len() {
        return None;
    }
    let mut d = Diagnostic::error(ErrorKind::Grow(format!(
        "rule number {} is not declared",
        rule.0
    )));
    if let Some(s) = span_of(loc) {
        d = d.with_span(s);
    }
    Some(d)
}

/// Flattens the seed into drawing operations, fixed figures and growth
/// points, in drawing order (an explicit stack: written terms may nest deep).
fn flatten<'a>(od: &'a Description, seed: &'a Seed) -> Result<Flat<'a>, Diagnostics> {
    enum Task<'a> {
        Item(&'a SeedItem),
        Slot(&'a Slot),
        Term(&'a Term),
        Run(&'a str),
        Piece(&'a Piece),
        Fixed(&'a Fixed),
        Op(Op),
    }
    let mut flat = Flat {
        instrs: Vec::new(),
        gps: Vec::new(),
    };
    let mut stack: Vec<Task<'a>> = seed.items.iter().rev().map(Task::Item).collect();
    while let Some(task) = stack.pop() {
        match task {
            Task::Item(SeedItem::Draw(r)) => stack.push(Task::Run(&r.text)),
            Task::Item(SeedItem::Fixed(f)) | Task::Fixed(f) | Task::Piece(Piece::Fixed(f)) => {
                flat.instrs.push(Instr::Fixed(f))
            }
            Task::Item(SeedItem::Term(t)) | Task::Slot(Slot::Term(t)) => stack.push(Task::Term(t)),
            Task::Item(SeedItem::Repeat(r)) | Task::Slot(Slot::Repeat(r)) => {
                if let Some(d) = rule_error(od, r.rule, &r.loc) {
                    return Err(d.into());
                }
                flat.instrs.push(Instr::Gp(flat.gps.len()));
                flat.gps.push(SeedGp {
                    rule: r.rule,
                    count: Some(r.count),
                    loc: r.loc.clone(),
                });
            }
            Task::Run(text) => flat
                .instrs
                .extend(text.chars().filter_map(Op::of_stl).map(Instr::Op)),
            Task::Piece(Piece::Draw(r)) => stack.push(Task::Run(&r.text)),
            Task::Op(op) => flat.instrs.push(Instr::Op(op)),
            Task::Term(t) => {
                if let Some(d) = rule_error(od, t.rule, &t.loc) {
                    return Err(d.into());
                }
                let rule = od.rule(t.rule);
                if t.bare {
                    flat.instrs.push(Instr::Gp(flat.gps.len()));
                    flat.gps.push(SeedGp {
                        rule: t.rule,
                        count: None,
                        loc: t.loc.clone(),
                    });
                    continue;
                }
                if t.slots.len() != rule.branch_count() {
                    let mut d = Diagnostic::error(ErrorKind::SlotCount {
                        rule: rule.name.clone(),
                        expected: rule.branch_count(),
                        found: t.slots.len(),
                    });
                    if let Some(s) = span_of(&t.loc) {
                        d = d.with_span(s);
                    }
                    return Err(d.into());
                }
                // Enter, the body with slot i at the tip of branch i, Leave;
                // pushed in reverse.
                let mut tasks: Vec<Task<'a>> = vec![Task::Op(Op::Enter)];
                let mut branch = 0;
                for item in &rule.body.items {
                    match item {
                        BodyItem::Draw(r) => tasks.push(Task::Run(&r.text)),
                        BodyItem::Fixed(f) => tasks.push(Task::Fixed(f)),
                        BodyItem::Branch(b) => {
                            tasks.push(Task::Op(Op::Push));
                            tasks.extend(b.pieces.iter().map(Task::Piece));
                            if let Some(s) = &t.slots[branch] {
                                tasks.push(Task::Slot(s));
                            }
                            tasks.push(Task::Op(Op::Pop));
                            branch += 1;
                        }
                    }
                }
                tasks.push(Task::Op(Op::Leave));
                stack.extend(tasks.into_iter().rev());
            }
        }
    }
    Ok(flat)
}

/// Refuses growth that nothing bounds: no layout, no decrement, no explicit
/// `--max-stems`, and a growth point without a count from which the rules
/// can branch forever (a cycle of rules with branches, following each
/// branch's successor).
fn check_bounded(od: &Description, gps: &[SeedGp], opts: &GrowOptions) -> Result<(), Diagnostics> {
    let p = &od.params;
    if od.layout.is_some()
        || p.length.decrement > 0.0
        || p.width.decrement > 0.0
        || opts.max_stems_explicit
    {
        return Ok(());
    }
    for gp in gps.iter().filter(|g| g.count.is_none()) {
        if let Some(cycle_rule) = endless_from(od, gp.rule) {
            let name = &od.rule(gp.rule).name;
            let mut d = Diagnostic::error(ErrorKind::Grow(format!(
                "growth has no bound: `{name}` can branch forever (through `{}`), and there is no LAYOUT, no count and no decrement to stop it",
                od.rule(cycle_rule).name
            )))
            .with_help(format!(
                "add a LAYOUT section, write `[I n {name}]` to grow n levels, give L or B a decrement (`L=10(1)`), or pass `--max-stems N` to stop after N stems"
            ));
            if let Some(s) = span_of(&gp.loc) {
                d = d.with_span(s).with_label("this growth point");
            } else if let Some(s) = span_of(&od.rule(gp.rule).name_loc) {
                // The default seed `F R1` has no text of its own.
                d = d.with_span(s).with_label(
                    "the seed's default growth point (no SEED section) grows this rule",
                );
            }
            return Err(d.into());
        }
    }
    Ok(())
}

/// A rule on a cycle of the successor graph reachable from `start`, if any
/// (iterative depth-first search with colours).
fn endless_from(od: &Description, start: RuleId) -> Option<RuleId> {
    let succ = |r: RuleId| -> Vec<RuleId> {
        od.rule(r)
            .body
            .items
            .iter()
            .filter_map(|i| match i {
                BodyItem::Branch(b) => Some(b.successor.as_ref().map_or(r, |s| s.rule)),
                _ => None,
            })
            .filter(|s| s.0 < od.rules.len())
            .collect()
    };
    // 0 unvisited, 1 on the path, 2 done.
    let mut colour = vec![0u8; od.rules.len()];
    let mut stack: Vec<(RuleId, Vec<RuleId>)> = vec![(start, succ(start))];
    colour[start.0] = 1;
    while let Some((r, next)) = stack.last_mut() {
        match next.pop() {
            Some(n) => match colour[n.0] {
                1 => return Some(n),
                0 => {
                    colour[n.0] = 1;
                    let s = succ(n);
                    stack.push((n, s));
                }
                _ => {}
            },
            None => {
                colour[r.0] = 2;
                stack.pop();
            }
        }
    }
    None
}

/// The operations of a fixed figure `[I n w]`: `F` rewritten by `w`, `n`
/// times (`n = 1` draws `w`, `n = 0` a single `F`), streamed with an
/// explicit stack of depth `n`. The brackets of `[I n w]` are syntax: the
/// figure does not save and restore the turtle around itself.
struct FixedOps<'a> {
    word: &'a [u8],
    /// (levels left at this depth, next index into `word`).
    stack: Vec<(u32, usize)>,
    single_f: bool,
}

impl<'a> FixedOps<'a> {
    fn new(f: &'a Fixed) -> Self {
        FixedOps {
            word: f.word.as_bytes(),
            stack: if f.count > 0 {
                vec![(f.count, 0)]
            } else {
                Vec::new()
            },
            single_f: f.count == 0,
        }
    }
}

impl Iterator for FixedOps<'_> {
    type Item = Op;
    fn next(&mut self) -> Option<Op> {
        if self.single_f {
            self.single_f = false;
            return Some(Op::Draw);
        }
        loop {
            let (level, i) = self.stack.last_mut()?;
            if *i >= self.word.len() {
                self.stack.pop();
                continue;
            }
            let c = self.word[*i];
            *i += 1;
            let level = *level;
            if c == b'F' && level > 1 {
                self.stack.push((level - 1, 0));
                continue;
            }
            if let Some(op) = Op::of_stl(c as char) {
                return Some(op);
            }
        }
    }
}

/// Where a decision is recorded.
#[derive(Debug, Clone, Copy)]
enum Parent {
    /// Growth point number `i` of the seed.
    Seed(u32),
    /// Entry `i` of [`Grower::slot_child`].
    Slot(u32),
}

/// A growth point waiting for its decision.
#[derive(Debug, Clone, Copy)]
struct Gp {
    state: State,
    rule: RuleId,
    count: Option<u32>,
    /// The position is known to lie in the region's open interior.
    inside: bool,
    parent: Parent,
}

/// A successful application.
#[derive(Debug, Clone, Copy)]
struct Node {
    rule: RuleId,
    /// First of its entries in [`Grower::slot_child`].
    slots: u32,
}

const NO_NODE: u32 = u32::MAX;

/// Why an application did not grow.
enum Miss {
    /// Not here (space, order, count); growth goes on elsewhere.
    Failed,
    /// A limit stopped all growth.
    Stopped,
}

/// Own segments of an application checked linearly up to this many; beyond,
/// through a local R-tree.
const LOCAL_LINEAR: usize = 64;

struct Grower<'a> {
    od: &'a Description,
    params: &'a StemParams,
    growth: GrowthOrder,
    limits: Limits,
    region: Option<Region>,
    occ: Occupancy,
    interp: Interp<Recorder>,
    /// Whether each rule leaves the turtle where it found it.
    neutral: Vec<bool>,
    nodes: Vec<Node>,
    slot_child: Vec<u32>,
    /// The node grown at each seed growth point.
    seed_result: Vec<u32>,
    stems: u64,
    seed_stems: u64,
    applications: u64,
    stopped: bool,
    depth_capped: bool,
    warnings: Vec<Diagnostic>,
    // Scratch of one application.
    scratch: Vec<Seg>,
    local: Option<rstar::RTree<Seg>>,
    tips: Vec<(State, bool)>,
    /// Children of the last success, in branch order.
    children: Vec<Gp>,
    queue: VecDeque<Gp>,
    stack: Vec<Gp>,
    reported: u64,
}

impl<'a> Grower<'a> {
    fn new(
        od: &'a Description,
        opts: &GrowOptions,
        backend: Backend,
        clearance: f64,
        region: Option<Region>,
        root: Point,
        seed_gps: usize,
    ) -> Self {
        let neutral = od
            .rules
            .iter()
            .map(|r| {
                r.body.items.iter().all(|i| match i {
                    BodyItem::Branch(_) => true,
                    BodyItem::Draw(d) => d.text.chars().all(|c| {
                        !matches!(
                            Op::of_stl(c),
                            Some(Op::Draw | Op::Move | Op::Turn(_) | Op::Flip)
                        )
                    }),
                    BodyItem::Fixed(_) => false,
                })
            })
            .collect();
        let length = od.params.length;
        Grower {
            od,
            params: &od.params,
            growth: opts.growth,
            limits: opts.limits,
            region,
            occ: Occupancy::new(backend, clearance),
            interp: Interp::new(Recorder::default(), root, od.params.angle(), length),
            neutral,
            nodes: Vec::new(),
            slot_child: Vec::new(),
            seed_result: vec![NO_NODE; seed_gps],
            stems: 0,
            seed_stems: 0,
            applications: 0,
            stopped: false,
            depth_capped: false,
            warnings: Vec::new(),
            scratch: Vec::new(),
            local: None,
            tips: Vec::new(),
            children: Vec::new(),
            queue: VecDeque::new(),
            stack: Vec::new(),
            reported: 0,
        }
    }

    /// Draws the seed, deciding its growth points (and, in `dfs`, their
    /// subtrees) as described in the module documentation; then, in `bfs`,
    /// the levels that follow.
    fn walk_seed(
        &mut self,
        flat: &Flat<'_>,
        progress: &mut dyn Progress,
    ) -> Result<(), Diagnostics> {
        let mut pending: Vec<Gp> = Vec::new();
        for (idx, instr) in flat.instrs.iter().enumerate() {
            match instr {
                Instr::Op(op) => self.seed_op(*op)?,
                Instr::Fixed(f) => {
                    for op in FixedOps::new(f) {
                        self.seed_op(op)?;
                    }
                }
                Instr::Gp(i) => {
                    let sg = &flat.gps[*i];
                    let gp = Gp {
                        state: self.interp.state,
                        rule: sg.rule,
                        count: sg.count,
                        inside: false,
                        parent: Parent::Seed(*i as u32),
                    };
                    let later_drawing_fixed = self.neutral[sg.rule.0]
                        || matches!(flat.instrs.get(idx + 1), None | Some(Instr::Op(Op::Pop)));
                    if later_drawing_fixed {
                        pending.push(gp);
                    } else {
                        let here = self.interp.state;
                        for p in pending.drain(..) {
                            self.decide_with_subtree(p, progress);
                        }
                        let end = self.decide_with_subtree(gp, progress);
                        self.interp.state = end.unwrap_or(here);
                    }
                }
            }
        }
        for p in pending {
            self.decide_with_subtree(p, progress);
        }
        if self.growth == GrowthOrder::Bfs {
            while let Some(gp) = self.queue.pop_front() {
                if self.stopped {
                    break;
                }
                if self.decide(gp, progress).is_some() {
                    self.queue.extend(self.children.drain(..));
                }
            }
        }
        Ok(())
    }

    /// One drawing operation of the seed: drawn and placed without a test.
    fn seed_op(&mut self, op: Op) -> Result<(), Diagnostics> {
        self.interp.apply(op);
        if let Some(s) = self.interp.turtle.segments.pop() {
            self.stems += 1;
            self.seed_stems += 1;
            // The seed is always drawn whole (a stop only ends growth), but
            // a seed beyond the limit by itself is an error.
            if self.seed_stems > self.limits.max_stems {
                return Err(Diagnostic::error(ErrorKind::Limit {
                    what: "stems drawn by the seed alone".into(),
                    value: self.seed_stems.to_string(),
                    limit: self.limits.max_stems.to_string(),
                })
                .with_help("raise the limit with --max-stems N, or draw a smaller seed")
                .into());
            }
            self.occ
                .insert(Seg::new([s.from.x, s.from.y], [s.to.x, s.to.y]));
        }
        Ok(())
    }

    /// Decides a seed growth point: in `bfs` its children join the queue, in
    /// `dfs` its whole subtree is grown now. Returns the turtle state after
    /// the application if it grew. The turtle's state is clobbered.
    fn decide_with_subtree(&mut self, gp: Gp, progress: &mut dyn Progress) -> Option<State> {
        if self.stopped {
            return None;
        }
        let end = self.decide(gp, progress)?;
        match self.growth {
            GrowthOrder::Bfs => self.queue.extend(self.children.drain(..)),
            GrowthOrder::Dfs => {
                self.stack.extend(self.children.drain(..).rev());
                while let Some(g) = self.stack.pop() {
                    if self.stopped {
                        self.stack.clear();
                        break;
                    }
                    if self.decide(g, progress).is_some() {
                        self.stack.extend(self.children.drain(..).rev());
                    }
                }
            }
        }
        Some(end)
    }

    /// Decides one growth point. On success records the node, leaves its
    /// children in `self.children` and returns the turtle state after the
    /// application.
    fn decide(&mut self, gp: Gp, progress: &mut dyn Progress) -> Option<State> {
        self.children.clear();
        let end = match self.apply(&gp) {
            Ok(end) => end,
            Err(Miss::Failed) => return None,
            Err(Miss::Stopped) => {
                self.stopped = true;
                return None;
            }
        };
        // Commit.
        self.stems += self.scratch.len() as u64;
        for s in self.scratch.drain(..) {
            self.occ.insert(s);
        }
        self.applications += 1;
        let id = self.nodes.len() as u32;
        let rule = self.od.rule(gp.rule);
        self.nodes.push(Node {
            rule: gp.rule,
            slots: self.slot_child.len() as u32,
        });
        let first = self.slot_child.len() as u32;
        self.slot_child
            .extend(std::iter::repeat_n(NO_NODE, rule.branch_count()));
        match gp.parent {
            Parent::Seed(i) => self.seed_result[i as usize] = id,
            Parent::Slot(i) => self.slot_child[i as usize] = id,
        }
        let count = gp.count.map(|n| n.saturating_sub(1));
        if count != Some(0) {
            let mut j = 0u32;
            for item in &rule.body.items {
                if let BodyItem::Branch(b) = item {
                    let (state, inside) = self.tips[j as usize];
                    self.children.push(Gp {
                        state,
                        rule: b.successor.as_ref().map_or(gp.rule, |s| s.rule),
                        count,
                        inside,
                        parent: Parent::Slot(first + j),
                    });
                    j += 1;
                }
            }
        }
        if self.stems >> 14 != self.reported {
            self.reported = self.stems >> 14;
            progress.update(self.stems);
        }
        Some(end)
    }

    /// Draws rule `gp.rule` at the growth point into `self.scratch`, testing
    /// every segment; records the branch tips in `self.tips`.
    fn apply(&mut self, gp: &Gp) -> Result<State, Miss> {
        if self.stopped {
            return Err(Miss::Stopped);
        }
        if gp.count == Some(0) {
            return Err(Miss::Failed);
        }
        let order = gp.state.order + 1;
        if !self.params.can_grow_at(order) {
            return Err(Miss::Failed);
        }
        if order > self.limits.max_depth {
            if !self.depth_capped {
                self.depth_capped = true;
                self.warnings.push(
                    Diagnostic::warning(ErrorKind::Grow(format!(
                        "growth reached the depth limit of {} nested rule applications (--max-depth); deeper branches were not grown",
                        self.limits.max_depth
                    )))
                    .with_help("raise it with --max-depth N"),
                );
            }
            return Err(Miss::Failed);
        }
        if self.applications >= self.limits.max_stems {
            self.stop_warning();
            return Err(Miss::Stopped);
        }
        self.scratch.clear();
        self.local = None;
        self.tips.clear();
        let base_depth = self.interp.stack_depth();
        self.interp.state = gp.state;
        self.interp.apply(Op::Enter);
        let result = self.draw_body(gp);
        // Unwind whatever the body left on the stack (only after a miss).
        while self.interp.stack_depth() > base_depth {
            self.interp.apply(Op::Pop);
        }
        result?;
        self.interp.apply(Op::Leave);
        Ok(self.interp.state)
    }

    fn draw_body(&mut self, gp: &Gp) -> Result<(), Miss> {
        let od = self.od;
        let rule = od.rule(gp.rule);
        // Whether the turtle's position is known to be inside the region,
        // saved and restored with the turtle's stack.
        let mut inside = gp.inside;
        let mut saved: Vec<bool> = Vec::new();
        let base = self.interp.stack_depth();
        for item in &rule.body.items {
            match item {
                BodyItem::Draw(r) => {
                    for op in r.text.chars().filter_map(Op::of_stl) {
                        self.step(op, &mut inside, &mut saved, base)?;
                    }
                }
                BodyItem::Fixed(f) => {
                    for op in FixedOps::new(f) {
                        self.step(op, &mut inside, &mut saved, base)?;
                    }
                }
                BodyItem::Branch(b) => {
                    self.step(Op::Push, &mut inside, &mut saved, base)?;
                    let depth = self.interp.stack_depth();
                    for p in &b.pieces {
                        match p {
                            Piece::Draw(r) => {
                                for op in r.text.chars().filter_map(Op::of_stl) {
                                    self.step(op, &mut inside, &mut saved, depth)?;
                                }
                            }
                            Piece::Fixed(f) => {
                                for op in FixedOps::new(f) {
                                    self.step(op, &mut inside, &mut saved, depth)?;
                                }
                            }
                        }
                    }
                    self.tips.push((self.interp.state, inside));
                    while self.interp.stack_depth() >= depth {
                        self.step(Op::Pop, &mut inside, &mut saved, base)?;
                    }
                }
            }
        }
        Ok(())
    }

    /// One operation inside an application; a drawn segment is tested.
    /// `floor`: pops below this stack depth are ignored (unbalanced input).
    fn step(
        &mut self,
        op: Op,
        inside: &mut bool,
        saved: &mut Vec<bool>,
        floor: usize,
    ) -> Result<(), Miss> {
        match op {
            Op::Push => saved.push(*inside),
            Op::Pop => {
                if self.interp.stack_depth() <= floor {
                    return Ok(());
                }
                *inside = saved.pop().unwrap_or(false);
            }
            Op::Move => *inside = false,
            _ => {}
        }
        self.interp.apply(op);
        let Some(s) = self.interp.turtle.segments.pop() else {
            return Ok(());
        };
        let seg = Seg::new([s.from.x, s.from.y], [s.to.x, s.to.y]);
        if let Some(r) = &self.region {
            if !r.segment_inside(s.from, s.to, *inside) {
                return Err(Miss::Failed);
            }
            *inside = true;
        }
        let c = self.occ.clearance();
        if c > 0.0 {
            if self.occ.conflicts(&seg) {
                return Err(Miss::Failed);
            }
            match &mut self.local {
                Some(t) => {
                    let env = rstar::AABB::from_corners(
                        [seg.a[0].min(seg.b[0]) - c, seg.a[1].min(seg.b[1]) - c],
                        [seg.a[0].max(seg.b[0]) + c, seg.a[1].max(seg.b[1]) + c],
                    );
                    if t.locate_in_envelope_intersecting(&env)
                        .any(|o| occupancy::conflicts(&seg, o, c))
                    {
                        return Err(Miss::Failed);
                    }
                    t.insert(seg);
                }
                None => {
                    if self
                        .scratch
                        .iter()
                        .any(|o| occupancy::conflicts(&seg, o, c))
                    {
                        return Err(Miss::Failed);
                    }
                    if self.scratch.len() + 1 == LOCAL_LINEAR {
                        let mut all = self.scratch.clone();
                        all.push(seg);
                        self.local = Some(rstar::RTree::bulk_load(all));
                    }
                }
            }
        }
        self.scratch.push(seg);
        if self.stems + self.scratch.len() as u64 > self.limits.max_stems {
            self.stop_warning();
            return Err(Miss::Stopped);
        }
        Ok(())
    }

    fn stop_warning(&mut self) {
        if self.stopped {
            return;
        }
        self.stopped = true;
        self.warnings.push(
            Diagnostic::warning(ErrorKind::Grow(format!(
                "growth stopped at {} stems: the next rule application would pass the limit of --max-stems {}",
                self.stems, self.limits.max_stems
            )))
            .with_help("the BED is valid but its tree is cut short; raise the limit with --max-stems N"),
        );
    }

    /// The grown seed: the seed's items with every growth point replaced by
    /// its grown term (or left out / left empty where nothing grew), built
    /// bottom-up without recursion.
    fn build_seed(&mut self, seed: &Seed) -> Vec<SeedItem> {
        // Terms of all nodes, children first (a child is always made after
        // its parent, so it has a larger id).
        let mut terms: Vec<Option<Term>> = Vec::with_capacity(self.nodes.len());
        terms.resize_with(self.nodes.len(), || None);
        for id in (0..self.nodes.len()).rev() {
            let n = self.nodes[id];
            let k = self.od.rule(n.rule).branch_count();
            let slots = (0..k)
                .map(|j| {
                    let c = self.slot_child[n.slots as usize + j];
                    (c != NO_NODE)
                        .then(|| terms[c as usize].take().map(Slot::Term))
                        .flatten()
                })
                .collect();
            terms[id] = Some(Term {
                rule: n.rule,
                slots,
                bare: false,
                loc: Loc::default(),
            });
        }
        let mut gp_index = 0usize;
        let mut next_gp = |terms: &mut Vec<Option<Term>>| -> Option<Term> {
            let id = self.seed_result[gp_index];
            gp_index += 1;
            (id != NO_NODE).then(|| terms[id as usize].take()).flatten()
        };
        struct Frame<'t> {
            term: &'t Term,
            next: usize,
            built: Vec<Option<Slot>>,
        }
        let mut items = Vec::with_capacity(seed.items.len());
        for item in &seed.items {
            let top = match item {
                SeedItem::Draw(_) | SeedItem::Fixed(_) => {
                    items.push(item.clone());
                    continue;
                }
                SeedItem::Repeat(_) => {
                    items.extend(next_gp(&mut terms).map(SeedItem::Term));
                    continue;
                }
                SeedItem::Term(t) if t.bare => {
                    items.extend(next_gp(&mut terms).map(SeedItem::Term));
                    continue;
                }
                SeedItem::Term(t) => t,
            };
            let mut stack = vec![Frame {
                term: top,
                next: 0,
                built: Vec::new(),
            }];
            while let Some(f) = stack.last_mut() {
                if f.next < f.term.slots.len() {
                    let slot = &f.term.slots[f.next];
                    f.next += 1;
                    match slot {
                        None => f.built.push(None),
                        Some(Slot::Repeat(_)) => f.built.push(next_gp(&mut terms).map(Slot::Term)),
                        Some(Slot::Term(t)) if t.bare => {
                            f.built.push(next_gp(&mut terms).map(Slot::Term))
                        }
                        Some(Slot::Term(t)) => stack.push(Frame {
                            term: t,
                            next: 0,
                            built: Vec::new(),
                        }),
                    }
                } else {
                    let Some(f) = stack.pop() else { break };
                    let t = Term {
                        rule: f.term.rule,
                        slots: f.built,
                        bare: false,
                        loc: f.term.loc.clone(),
                    };
                    match stack.last_mut() {
                        Some(parent) => parent.built.push(Some(Slot::Term(t))),
                        None => items.push(SeedItem::Term(t)),
                    }
                }
            }
        }
        items
    }
}
