//! The grower: draws the flattened seed and decides growth points one at a
//! time, `bfs` from a queue or `dfs` from a stack, never recursing.
//!
//! Deciding a growth point applies its rule: the whole body is drawn into
//! the application's scratch from the turtle state at the point, every
//! segment tested against the region, the placed segments and the
//! application's own earlier ones. If every segment fits they are placed,
//! the application becomes a node of the grown tree, and its branch tips
//! become the next growth points; otherwise nothing of it remains. The
//! module documentation of [`crate::grow`] states the rules.

use std::collections::VecDeque;

use super::colonize::{Colonizer, DEFAULT_REACH_IN_L};
use super::explain::{LastMiss, RuleTally, kin};
use super::occupancy::{Backend, Cap, Dim, LocalIndex, Occupancy};
use super::options::{GrowOptions, SEED_STEMS};
use super::plane::{Class, Space};
use super::rules::RuleInfo;
use super::seed::{Flat, Instr};
use super::tree::{Budget, NO_NODE, Parent, Tree};
use crate::choice::Key;
use crate::diag::{Diagnostics, MissReason};
use crate::limits::{Bound, Limits};
use crate::model::GrowthOrder;
use crate::model::walk::{self, FixedWord, Levels, Step};
use crate::model::{Description, Fixed, RuleId};
use crate::progress::Progress;

/// A growth point waiting for its decision.
#[derive(Debug, Clone, Copy)]
struct Gp<St> {
    state: St,
    /// The rule named there (with alternatives: any of them; the decision
    /// chooses by `key`).
    rule: RuleId,
    /// The growth point's place ([`crate::choice`]): the seed's `i`-th
    /// point of root `r` has `Key::root(seed).child(r).child(i)`, the tip
    /// of branch `j` of an application at `k` has `k.child(j)`.
    key: Key,
    count: Option<u32>,
    /// The position is known to lie in the region's open interior.
    inside: bool,
    parent: Parent,
}

/// The scratch of one application, reused from one to the next.
#[derive(Debug)]
struct Scratch<const N: usize, St>
where
    Cap<N>: Dim,
{
    /// The segments drawn so far, placed only if all of them fit.
    segs: LocalIndex<N>,
    /// The turtle state at each branch tip, and whether it is known to be
    /// inside the region.
    tips: Vec<(St, bool)>,
    /// The growth points made by the last success, in branch order.
    children: Vec<Gp<St>>,
    /// Whether the turtle was inside the region, saved at each `[` of the
    /// body being drawn (kept to reuse its allocation).
    saved: Vec<bool>,
    /// What the last failed try left, for explaining it.
    miss: LastMiss<N>,
}

/// The growth points waiting for their decision: a FIFO queue in `bfs`, a
/// stack in `dfs`.
#[derive(Debug)]
struct Schedule<St> {
    queue: VecDeque<Gp<St>>,
    stack: Vec<Gp<St>>,
}

/// Why an application did not grow.
enum Miss {
    /// Not here (space, order); growth goes on elsewhere.
    Failed(MissReason),
    /// A limit stopped all growth.
    Stopped,
}

/// The grower's state: what it works in (the description, the space with
/// its turtle and region, the placed segments) and the four groups it
/// keeps up to date. Written once for the plane and for space (`N` = 2
/// or 3, [`Space`]).
pub(super) struct Grower<'a, const N: usize, S: Space<N>>
where
    Cap<N>: Dim,
{
    od: &'a Description,
    growth: GrowthOrder,
    limits: Limits,
    /// By [`RuleId`].
    rules: Vec<RuleInfo>,
    occ: Occupancy<N>,
    /// The turtle and the region.
    space: S,
    tree: Tree,
    budget: Budget,
    scratch: Scratch<N, S::State>,
    schedule: Schedule<S::State>,
    /// The key of the tree being grown: `Key::root(seed).child(r)` for
    /// root `r` ([`Gp::key`]).
    tree_key: Key,
    /// `--seed`.
    seed: u64,
    /// What became of each rule's tries, by [`RuleId`].
    tallies: Vec<RuleTally>,
    /// When asked for ([`super::grow_traced`]): every stem placed, in the
    /// order growth placed it, with its decision (0: the seed's drawing).
    pub(super) trace: Option<Vec<(Cap<N>, u64)>>,
    /// In space-first growth: the attraction points and the waiting
    /// growth points ([`super::colonize`]).
    colonizer: Option<Colonizer<N, Gp<S::State>>>,
    /// The score of the growth point being decided (space-first growth).
    claim: u32,
}

/// The turtle operations of a fixed figure.
fn fixed_ops<const N: usize, S: Space<N>>(f: &Fixed) -> impl Iterator<Item = S::Op> + '_
where
    Cap<N>: Dim,
{
    FixedWord::new(f).filter_map(|c| S::op(char::from(c)))
}

impl<'a, const N: usize, S: Space<N>> Grower<'a, N, S>
where
    Cap<N>: Dim,
{
    /// A grower for `od` in `space`, for `trees` trees of a
    /// seed with `seed_gps` growth points each.
    pub(super) fn new(
        od: &'a Description,
        opts: &GrowOptions,
        backend: Backend,
        clearance: f64,
        space: S,
        seed_gps: usize,
        trees: usize,
    ) -> Self {
        let moves = |c| {
            S::op(c)
                .is_some_and(|o| matches!(S::class(o), Class::Draws | Class::Moves | Class::Turns))
        };
        let colonizer = (opts.growth == GrowthOrder::Space).then(|| {
            let l = od.params.length.base;
            let unit = if N == 2 { l * l } else { l * l * l };
            let points = if l > 0.0 {
                space.attraction(od.params.design.points, unit, opts.seed)
            } else {
                Vec::new()
            };
            Colonizer::new(
                points,
                od.params.design.reach.unwrap_or(DEFAULT_REACH_IN_L * l),
            )
        });
        Grower {
            od,
            growth: opts.growth,
            limits: opts.limits,
            rules: RuleInfo::all(od, moves),
            occ: Occupancy::new(backend, clearance),
            space,
            tree: Tree {
                seed_result: vec![NO_NODE; seed_gps * trees],
                trees,
                ..Tree::default()
            },
            budget: Budget::default(),
            scratch: Scratch {
                segs: LocalIndex::new(clearance),
                tips: Vec::new(),
                children: Vec::new(),
                saved: Vec::new(),
                miss: LastMiss::default(),
            },
            schedule: Schedule {
                queue: VecDeque::new(),
                stack: Vec::new(),
            },
            tree_key: Key::root(opts.seed).child(0),
            seed: opts.seed,
            tallies: vec![RuleTally::default(); od.rules.len()],
            trace: None,
            colonizer,
            claim: 0,
        }
    }

    /// The grown tree, what growth spent, and what became of each rule's
    /// tries (by [`RuleId`]).
    pub(super) fn finish(self) -> (Tree, Budget, Vec<RuleTally>) {
        (self.tree, self.budget, self.tallies)
    }

    /// Grows every tree: draws each tree's seed from its root, in root
    /// order, deciding only the growth points the later drawing depends on
    /// (the module documentation of [`crate::grow`]); then decides the
    /// others (in `dfs` with their subtrees), tree by tree; then, in
    /// `bfs`, the levels that follow, so a forest's trees interleave level
    /// by level. Every tree's seed drawing is so in place before the trees
    /// grow around it (one tree: the order growth always had).
    pub(super) fn grow_trees(
        &mut self,
        flat: &Flat<'_>,
        roots: usize,
        progress: &mut dyn Progress,
    ) -> Result<(), Diagnostics> {
        let mut pending = Vec::with_capacity(roots);
        for t in 0..roots {
            pending.push(self.walk_seed(flat, t, progress)?);
        }
        for tree in pending {
            for p in tree {
                if let Some(c) = &mut self.colonizer {
                    c.push(
                        S::position(&p.state),
                        reach_at(self.od, S::order(&p.state)),
                        p,
                    );
                } else {
                    self.decide_with_subtree(p, progress);
                }
            }
        }
        self.grow_levels(progress);
        Ok(())
    }

    /// Draws the seed of tree `t` from its root, deciding the growth points
    /// the drawing after them depends on; returns the others, in order.
    fn walk_seed(
        &mut self,
        flat: &Flat<'_>,
        t: usize,
        progress: &mut dyn Progress,
    ) -> Result<Vec<Gp<S::State>>, Diagnostics> {
        self.space.start(t);
        self.tree_key = Key::root(self.seed).child(t as u64);
        let first_gp = t * flat.gps.len();
        let mut pending: Vec<Gp<S::State>> = Vec::new();
        for (idx, instr) in flat.instrs.iter().enumerate() {
            match instr {
                Instr::Op(c) => {
                    if let Some(op) = S::op(*c) {
                        self.seed_op(op)?;
                    }
                }
                Instr::Fixed(f) => {
                    for op in fixed_ops::<N, S>(f) {
                        self.seed_op(op)?;
                    }
                }
                Instr::Enter => self.space.enter(),
                Instr::Leave => self.space.leave(),
                Instr::Gp(i) => {
                    let sg = &flat.gps[*i];
                    let gp = Gp {
                        state: self.space.state(),
                        rule: sg.rule,
                        key: self.tree_key.child(*i as u64),
                        count: sg.count,
                        inside: false,
                        parent: Parent::Seed((first_gp + *i) as u32),
                    };
                    let later_drawing_fixed = self.rules[sg.rule.0].neutral
                        || matches!(flat.instrs.get(idx + 1), None | Some(Instr::Op(']')));
                    if later_drawing_fixed {
                        pending.push(gp);
                    } else {
                        let here = self.space.state();
                        for p in pending.drain(..) {
                            self.decide_with_subtree(p, progress);
                        }
                        let end = self.decide_with_subtree(gp, progress);
                        self.space.set_state(end.unwrap_or(here));
                    }
                }
            }
        }
        Ok(pending)
    }

    /// In `bfs`, decides the levels after the seeds', in queue order (a
    /// forest's trees interleave level by level, root order within a
    /// level). Nothing to do in `dfs`.
    fn grow_levels(&mut self, progress: &mut dyn Progress) {
        if self.growth == GrowthOrder::Space {
            while let Some((gp, score)) = self.colonizer.as_mut().and_then(Colonizer::pop) {
                if self.budget.stopped {
                    break;
                }
                self.claim = score;
                if self.decide(gp, progress).is_some() {
                    self.push_children();
                }
            }
        }
        if self.growth == GrowthOrder::Bfs {
            while let Some(gp) = self.schedule.queue.pop_front() {
                if self.budget.stopped {
                    break;
                }
                if self.decide(gp, progress).is_some() {
                    self.schedule.queue.extend(self.scratch.children.drain(..));
                }
            }
        }
    }

    /// One drawing operation of the seed: drawn and placed without a test.
    fn seed_op(&mut self, op: S::Op) -> Result<(), Diagnostics> {
        if let Some(seg) = self.space.apply(op) {
            self.budget.stems += 1;
            self.budget.seed_stems += 1;
            // The seed is always drawn whole (a stop only ends growth), but
            // a seed beyond the limit by itself is an error.
            if self.budget.seed_stems > self.limits.max_stems {
                return Err(Bound::Stems
                    .exceeded_by(SEED_STEMS, self.budget.seed_stems, self.limits.max_stems)
                    .with_help(Bound::Stems.raise() + ", or draw a smaller seed")
                    .into());
            }
            if let Some(t) = &mut self.trace {
                t.push((seg, 0));
            }
            if let Some(c) = &mut self.colonizer {
                c.kill(&seg, stem_length(&seg));
            }
            self.occ.insert_drawn(seg);
        }
        Ok(())
    }

    /// Decides a seed growth point: in `bfs` its children join the queue, in
    /// `dfs` its whole subtree is grown now. Returns the turtle state after
    /// the application if it grew. The turtle's state is clobbered.
    fn decide_with_subtree(
        &mut self,
        gp: Gp<S::State>,
        progress: &mut dyn Progress,
    ) -> Option<S::State> {
        if self.budget.stopped {
            return None;
        }
        let end = self.decide(gp, progress)?;
        match self.growth {
            GrowthOrder::Space => self.push_children(),
            GrowthOrder::Bfs => self.schedule.queue.extend(self.scratch.children.drain(..)),
            GrowthOrder::Dfs => {
                self.schedule
                    .stack
                    .extend(self.scratch.children.drain(..).rev());
                while let Some(g) = self.schedule.stack.pop() {
                    if self.budget.stopped {
                        self.schedule.stack.clear();
                        break;
                    }
                    if self.decide(g, progress).is_some() {
                        self.schedule
                            .stack
                            .extend(self.scratch.children.drain(..).rev());
                    }
                }
            }
        }
        Some(end)
    }

    /// Space-first growth: the last success's growth points wait, scored.
    fn push_children(&mut self) {
        if let Some(c) = &mut self.colonizer {
            for g in self.scratch.children.drain(..) {
                c.push(
                    S::position(&g.state),
                    reach_at(self.od, S::order(&g.state)),
                    g,
                );
            }
        }
    }

    /// Decides one growth point. On success records the node, leaves its
    /// children in `scratch.children` and returns the turtle state after the
    /// application.
    fn decide(&mut self, mut gp: Gp<S::State>, progress: &mut dyn Progress) -> Option<S::State> {
        self.scratch.children.clear();
        if gp.count == Some(0) {
            return None;
        }
        if let Some(c) = &self.rules[gp.rule.0].choice {
            gp.rule = c.1[c.0.pick(gp.key)];
        }
        self.tallies[gp.rule.0].tries += 1;
        self.tallies[gp.rule.0].claimed += u64::from(std::mem::take(&mut self.claim));
        let end = match self.apply(&gp) {
            Ok(end) => end,
            Err(Miss::Failed(reason)) => {
                self.note_miss(&gp, reason);
                return None;
            }
            Err(Miss::Stopped) => {
                self.budget.stopped = true;
                self.note_miss(&gp, MissReason::StemLimit);
                return None;
            }
        };
        self.tallies[gp.rule.0].fits += 1;
        // Commit.
        self.budget.stems += self.scratch.segs.len() as u64;
        let mut killed = 0;
        for s in self.scratch.segs.drain() {
            if let Some(t) = &mut self.trace {
                t.push((s, self.budget.applications + 1));
            }
            if let Some(c) = &mut self.colonizer {
                killed += c.kill(&s, stem_length(&s));
            }
            self.occ.insert(s);
        }
        self.tallies[gp.rule.0].killed += killed;
        self.budget.applications += 1;
        let successors = &self.rules[gp.rule.0].successors;
        let first = self.tree.record(gp.rule, successors.len(), gp.parent);
        // A counted point's tips grow its next level ([`Levels`]), if any.
        let count = match gp.count {
            None => Some(None),
            Some(n) => Levels::of(n).and_then(Levels::next).map(|l| Some(l.get())),
        };
        if let Some(count) = count {
            for (j, &rule) in successors.iter().enumerate() {
                let (state, inside) = self.scratch.tips[j];
                self.scratch.children.push(Gp {
                    state,
                    rule,
                    key: gp.key.child(j as u64),
                    count,
                    inside,
                    parent: Parent::Slot(first + j as u32),
                });
            }
        }
        if self.budget.stems >> 14 != self.budget.reported {
            self.budget.reported = self.budget.stems >> 14;
            progress.update(self.budget.stems);
        }
        Some(end)
    }

    /// Counts a failed try of `gp.rule`; for the rule's first, works out the
    /// numbers from what the try left in the scratch.
    fn note_miss(&mut self, gp: &Gp<S::State>, reason: MissReason) {
        let order = S::order(&gp.state) + 1;
        let (scratch, params, limits) = (&self.scratch, &self.od.params, &self.limits);
        let clearance = self.occ.clearance();
        self.tallies[gp.rule.0].miss(reason, || {
            scratch
                .miss
                .misfit(reason, order, params, limits, clearance, |s| {
                    scratch.segs.position(s)
                })
        });
    }

    /// Draws rule `gp.rule` at the growth point into the scratch, testing
    /// every segment; records the branch tips in `scratch.tips`.
    fn apply(&mut self, gp: &Gp<S::State>) -> Result<S::State, Miss> {
        if self.budget.stopped {
            return Err(Miss::Stopped);
        }
        let order = S::order(&gp.state) + 1;
        if !self.od.params.can_grow_at(order) {
            return Err(Miss::Failed(if self.od.params.length.at(order) > 0.0 {
                MissReason::TooThin
            } else {
                MissReason::TooShort
            }));
        }
        if order > self.limits.max_depth {
            self.budget.cap_depth(self.limits.max_depth);
            return Err(Miss::Failed(MissReason::Depth));
        }
        if self.budget.applications >= self.limits.max_stems {
            self.budget
                .stop(self.limits.max_stems, self.od.params.design.max_stems);
            return Err(Miss::Stopped);
        }
        self.scratch.segs.clear();
        self.scratch.tips.clear();
        let base_depth = self.space.stack_depth();
        self.space.set_state(gp.state);
        self.space.enter();
        let result = self.draw_body(gp);
        // Unwind whatever the body left on the stack (only after a miss).
        while self.space.stack_depth() > base_depth {
            self.space.apply(S::pop());
        }
        result?;
        self.space.leave();
        Ok(self.space.state())
    }

    fn draw_body(&mut self, gp: &Gp<S::State>) -> Result<(), Miss> {
        let mut saved = std::mem::take(&mut self.scratch.saved);
        saved.clear();
        let drawn = self.draw_body_with(gp, &mut saved);
        self.scratch.saved = saved;
        drawn
    }

    /// [`Grower::draw_body`] with the stack of saved inside-flags.
    fn draw_body_with(&mut self, gp: &Gp<S::State>, saved: &mut Vec<bool>) -> Result<(), Miss> {
        let od = self.od;
        let rule = od.rule(gp.rule);
        // Whether the turtle's position is known to be inside the region,
        // saved and restored with the turtle's stack.
        let mut inside = gp.inside;
        let base = self.space.stack_depth();
        // Pops below this depth are ignored: the body's own depth on the
        // trunk, the depth just inside the `[` in a branch.
        let mut floor = base;
        for step in walk::steps(&rule.body) {
            match step {
                Step::Run(r) => {
                    for op in r.text.chars().filter_map(S::op) {
                        self.step(op, &mut inside, saved, floor)?;
                    }
                }
                Step::Fixed(f) => {
                    for op in fixed_ops::<N, S>(f) {
                        self.step(op, &mut inside, saved, floor)?;
                    }
                }
                Step::Open { .. } => {
                    self.step(S::push(), &mut inside, saved, base)?;
                    floor = self.space.stack_depth();
                }
                Step::Tip { .. } => {
                    self.scratch.tips.push((self.space.state(), inside));
                    while self.space.stack_depth() >= floor {
                        self.step(S::pop(), &mut inside, saved, base)?;
                    }
                    floor = base;
                }
            }
        }
        Ok(())
    }

    /// Keeps what the failed stem left for explaining the miss (outside the
    /// layout, or too close to `clash`'s other stem): out of line, so the
    /// tests in [`Grower::step`] stay small.
    #[inline(never)]
    fn missed(&mut self, clash: Option<(Cap<N>, Cap<N>, bool)>) -> Miss {
        self.scratch.miss = LastMiss::at(self.scratch.segs.len(), clash);
        Miss::Failed(match clash {
            None => MissReason::Outside,
            Some((new, other, _)) => MissReason::TooClose(kin(&new, &other)),
        })
    }

    /// One operation inside an application; a drawn segment is tested.
    /// `floor`: pops below this stack depth are ignored (unbalanced input).
    fn step(
        &mut self,
        op: S::Op,
        inside: &mut bool,
        saved: &mut Vec<bool>,
        floor: usize,
    ) -> Result<(), Miss> {
        match S::class(op) {
            Class::Push => saved.push(*inside),
            Class::Pop => {
                if self.space.stack_depth() <= floor {
                    return Ok(());
                }
                *inside = saved.pop().unwrap_or(false);
            }
            Class::Moves => *inside = false,
            Class::Draws | Class::Turns => {}
        }
        let Some(seg) = self.space.apply(op) else {
            return Ok(());
        };
        if self.space.bounded() {
            if !self.space.inside(&seg, *inside) {
                return Err(self.missed(None));
            }
            *inside = true;
        }
        // The try's own stems first: a rule that clashes with itself says so.
        if let Some(other) = self.scratch.segs.conflict(&seg) {
            return Err(self.missed(Some((seg, other, true))));
        }
        if let Some(other) = self.occ.conflict(&seg) {
            return Err(self.missed(Some((seg, other, false))));
        }
        self.scratch.segs.insert(seg);
        if self.budget.stems + self.scratch.segs.len() as u64 > self.limits.max_stems {
            self.budget
                .stop(self.limits.max_stems, self.od.params.design.max_stems);
            return Err(Miss::Stopped);
        }
        Ok(())
    }
}

/// The default reach of a growth point whose stems are drawn at the
/// order after `order`: `Q=` if given, else [`DEFAULT_REACH_IN_L`] stem
/// lengths there.
fn reach_at(od: &Description, order: u32) -> f64 {
    od.params.design.reach.unwrap_or_else(|| {
        DEFAULT_REACH_IN_L * od.params.length.at(order.saturating_add(1)).max(0.0)
    })
}

/// The length of a stem: its kill distance in space-first growth.
fn stem_length<const N: usize>(s: &Cap<N>) -> f64 {
    (0..N)
        .map(|i| (s.b[i] - s.a[i]) * (s.b[i] - s.a[i]))
        .sum::<f64>()
        .sqrt()
}
