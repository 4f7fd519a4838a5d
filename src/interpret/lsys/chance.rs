//! Level of detail for stochastic L-systems: expected geometry per
//! `(symbol, remaining depth, heading)`, and a walk that follows the
//! seed's own choices and cuts subtrees too small to see.
//!
//! A stochastic symbol's occurrences differ (each chooses by its key,
//! [`crate::choice`]), so no piece can be *the* drawing of `(s, r, k)`
//! as in the deterministic memo (`geometry.rs`). What stays true:
//!
//! - **choices are keyed by place**: a place's key is its parent's key and
//!   its index in the parent's successor, never a position in a stream, so
//!   a walk that skips a subtree makes every later choice exactly as the
//!   full derivation does;
//! - **net turns**, when every alternative of a rule has the same net turn
//!   and flip outside its brackets at every depth (ABOP 1.27: all three
//!   turn 0): then the heading after a subtree does not depend on its
//!   choices, headings are exact integers reached as in the deterministic
//!   memo, and the pieces can be keyed by heading. A system whose
//!   alternatives turn differently is refused ([`Refusal::Choices`]) and
//!   drawn exactly.
//!
//! A piece here is the *expected* drawing: net move averaged over the
//! alternatives with their probabilities (exact in expectation: children
//! choose independently), and the box averaged likewise (a typical size,
//! not a bound). A subtree whose expected box is under the detail is a
//! stand-in, as in the deterministic walk. Where it ends, which everything
//! drawn after it starts from, depends on its choices:
//!
//! - **exact ends** ([`Chance::plan`] says whether they fit the work
//!   budget [`LOD_WORK`]): the stand-in's *trunk* (the symbols outside
//!   brackets, at every level) is walked with the seed's choices, with the
//!   same floating-point steps as the exact drawing, so every segment not
//!   cut is bit-identical to `--exact`'s and the picture is that seed's,
//!   with sub-pixel bushes drawn as stand-ins;
//! - **expected ends** beyond the budget: the stand-in ends at its
//!   expected net move. Every choice above the cut is still the seed's,
//!   so the picture is a faithful-looking approximation of that seed's
//!   plant, not its exact drawing (docs/rendering.md).

/// The memo's map, hashed by foldhash's fixed state: SipHash cost about
/// 5 % of a dense picture (issue 37); nothing iterates it into output.
type HashMap<K, V> = std::collections::HashMap<K, V, foldhash::fast::FixedState>;

mod walk;

pub use walk::draw_chance;

use super::geometry::{GEOMETRY_ENTRIES, Period, Piece, Refusal, balanced};
use super::stochastic::Stochastic;
use crate::choice::Key;
use crate::diag::Diagnostics;
use crate::limits::{Bound, Limits};
use crate::model::lsys::LSystem;
use crate::num::Linear;
use crate::progress::Progress;
use crate::turtle::{BBox, Headings, Op, Point, Segment, Turtle};

/// Symbols a level-of-detail drawing of a stochastic system may visit,
/// stand-ins and trunk walks counted, and still give every stand-in its
/// exact end (about 0.3 s at the stochastic path's 37 M symbols/s);
/// beyond, stand-ins end at their expected net move.
pub const LOD_WORK: f64 = 1e7;

/// A stochastic drawing at a level of detail is fitted by an exact
/// bounding pass (the box `--exact` uses) when its expected word is at
/// most this long; beyond, by a bounding walk at the level of detail.
pub const FIT_SYMBOLS: f64 = 4e6;

/// One alternative of a rule.
struct Alt {
    p: f64,
    succ: Vec<u32>,
    /// The successor's symbols outside brackets, with their index in
    /// `succ` (their key is the parent's child at that index).
    trunk: Vec<(u32, u32)>,
}

/// The turtle of a walk: position, exact heading, flip.
#[derive(Clone, Copy)]
struct Pen {
    x: f64,
    y: f64,
    k: i64,
    flip: bool,
}

/// What a walk at a detail will do, in expectation over the choices
/// ([`Chance::plan`]).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ChancePlan {
    /// Symbols and stand-ins the walk visits.
    pub visits: f64,
    /// Symbols the stand-ins' trunk walks visit.
    pub trunks: f64,
    /// Stand-ins that draw or move.
    pub cuts: f64,
    /// Whether stand-ins get their exact ends: `visits + trunks` within
    /// [`LOD_WORK`].
    pub exact_ends: bool,
}

/// The expected geometry of a stochastic system at one depth; see the
/// module documentation.
pub struct Chance {
    st: Stochastic,
    ops: Vec<Option<Op>>,
    /// By symbol: its alternatives (empty without a rule).
    alts: Vec<Vec<Alt>>,
    depth: u32,
    period: Period,
    /// Net turn of `(s, r)` at `r * n + s`, the same for every choice.
    turn: Vec<i64>,
    /// Net flip, same index.
    flip: Vec<bool>,
    /// Expected number of `F`, same index.
    count: Vec<f64>,
    /// Whether some choice has a `]` or `f` inside, same index.
    jumps: Vec<bool>,
    /// Expected number of `]` and `f` (where a drawn run breaks off),
    /// same index.
    runs: Vec<f64>,
    /// Expected symbols a trunk walk of `(s, r)` visits, same index.
    trunk: Vec<f64>,
    /// Expected word length, same index.
    size: Vec<f64>,
    /// `(s, r, key)` to its index in `pieces`.
    index: HashMap<(u32, u32, i64), u32>,
    /// Per level, the `(s, key)` needed, bottom-up order after `demand`.
    needed: Vec<Vec<(u32, i64)>>,
    pieces: Vec<Piece>,
    headings: Headings,
    len: f64,
}

impl Chance {
    /// The expected geometry of stochastic `sys` at `depth`, or why it
    /// does not apply (at most [`GEOMETRY_ENTRIES`] pieces).
    pub fn new(sys: &LSystem, depth: u32) -> Result<Chance, Refusal> {
        let st = Stochastic::new(sys);
        let n = st.chars.len();
        let ops: Vec<Option<Op>> = st.chars.iter().map(|&c| Op::of_lsys(c)).collect();
        let mut alts = Vec::with_capacity(n);
        for s in 0..n as u32 {
            let mut list = Vec::new();
            for (p, succ) in st.alternatives(s) {
                if matches!(ops[s as usize], Some(Op::Push | Op::Pop)) || !balanced(succ, &ops) {
                    return Err(Refusal::Brackets);
                }
                let mut open = 0usize;
                let mut trunk = Vec::new();
                for (j, &c) in succ.iter().enumerate() {
                    match ops[c as usize] {
                        Some(Op::Push) => open += 1,
                        Some(Op::Pop) => open -= 1,
                        _ if open == 0 => trunk.push((j as u32, c)),
                        _ => {}
                    }
                }
                list.push(Alt {
                    p,
                    succ: succ.to_vec(),
                    trunk,
                });
            }
            alts.push(list);
        }
        let levels = depth as usize + 1;
        if n.saturating_mul(levels) > GEOMETRY_ENTRIES.saturating_mul(4) {
            return Err(Refusal::Budget);
        }
        let mut c = Chance {
            st,
            ops,
            alts,
            depth,
            period: Period::of(sys.angle),
            turn: vec![0; n * levels],
            flip: vec![false; n * levels],
            count: vec![0.0; n * levels],
            jumps: vec![false; n * levels],
            runs: vec![0.0; n * levels],
            trunk: vec![0.0; n * levels],
            size: vec![0.0; n * levels],
            index: HashMap::default(),
            needed: vec![Vec::new(); levels],
            pieces: Vec::new(),
            headings: Headings::starting(sys.heading, sys.angle),
            len: Linear::constant(sys.length).at(0),
        };
        c.per_level()?;
        c.demand(GEOMETRY_ENTRIES)?;
        c.compose_all();
        Ok(c)
    }

    fn at(&self, s: u32, r: u32) -> usize {
        r as usize * self.alts.len() + s as usize
    }

    fn is_piece(&self, c: u32, r: u32) -> bool {
        r >= 1 && !self.alts[c as usize].is_empty()
    }

    /// Net turns and flips (refused unless every choice agrees), expected
    /// counts, jumps, trunk walks and lengths of every `(s, r)`.
    fn per_level(&mut self) -> Result<(), Refusal> {
        let n = self.alts.len();
        for s in 0..n {
            let (t, f) = match self.ops[s] {
                Some(Op::Turn(t)) => (i64::from(t), false),
                Some(Op::Flip) => (0, true),
                _ => (0, false),
            };
            self.turn[s] = t;
            self.flip[s] = f;
            self.count[s] = f64::from(u8::from(self.ops[s] == Some(Op::Draw)));
            self.jumps[s] = matches!(self.ops[s], Some(Op::Pop | Op::Move));
            self.runs[s] = f64::from(u8::from(self.jumps[s]));
            self.size[s] = 1.0;
        }
        for r in 1..=self.depth {
            for s in 0..n as u32 {
                let (below, here) = (self.at(s, r - 1), self.at(s, r));
                if self.alts[s as usize].is_empty() {
                    self.turn[here] = self.turn[below];
                    self.flip[here] = self.flip[below];
                    self.count[here] = self.count[below];
                    self.jumps[here] = self.jumps[below];
                    self.runs[here] = self.runs[below];
                    self.size[here] = 1.0;
                    continue;
                }
                let mut net: Option<(i64, bool)> = None;
                let (mut count, mut jumps, mut trunk, mut size) = (0.0, false, 0.0, 0.0);
                let mut runs = 0.0;
                for alt in &self.alts[s as usize] {
                    let (mut t, mut f) = (0i64, false);
                    for &(_, c) in &alt.trunk {
                        let i = self.at(c, r - 1);
                        t = self
                            .period
                            .add_turn(t, self.turn[i])
                            .ok_or(Refusal::Turns)?;
                        f ^= self.flip[i];
                        trunk += alt.p * (1.0 + self.trunk[i]);
                    }
                    match net {
                        None => net = Some((t, f)),
                        Some(x) if x == (t, f) => {}
                        Some(_) => return Err(Refusal::Choices),
                    }
                    for &c in &alt.succ {
                        let i = self.at(c, r - 1);
                        count += alt.p * self.count[i];
                        size += alt.p * self.size[i];
                        jumps |= self.jumps[i];
                        runs += alt.p * self.runs[i];
                    }
                }
                let (t, f) = net.unwrap_or((0, false));
                self.turn[here] = t;
                self.flip[here] = f;
                self.count[here] = count;
                self.jumps[here] = jumps;
                self.runs[here] = runs;
                self.trunk[here] = trunk;
                self.size[here] = size;
            }
        }
        Ok(())
    }

    /// Calls `f(c, heading before c)` for every symbol of `word` (at
    /// remaining depth `r`) from heading `k`.
    fn headings_of(&self, word: &[u32], r: u32, mut k: i64, mut f: impl FnMut(u32, i64)) {
        let mut stack: Vec<i64> = Vec::new();
        for &c in word {
            f(c, k);
            match self.ops[c as usize] {
                Some(Op::Push) => stack.push(k),
                Some(Op::Pop) => {
                    if let Some(saved) = stack.pop() {
                        k = saved;
                    }
                }
                _ if self.is_piece(c, r) => {
                    k = self
                        .period
                        .add_turn(k, self.turn[self.at(c, r)])
                        .unwrap_or(k);
                }
                Some(Op::Turn(t)) => k = self.period.add_turn(k, i64::from(t)).unwrap_or(k),
                _ => {}
            }
        }
    }

    /// The `(s, r, key)` any choices need, from the axiom down.
    fn demand(&mut self, budget: usize) -> Result<(), Refusal> {
        let mut index = std::mem::take(&mut self.index);
        let mut needed = std::mem::take(&mut self.needed);
        let over = std::cell::Cell::new(false);
        let mut total = 0usize;
        let mut add = |c: u32, r: u32, key: i64, needed: &mut Vec<Vec<(u32, i64)>>| {
            if let std::collections::hash_map::Entry::Vacant(v) = index.entry((c, r, key)) {
                if total >= budget {
                    over.set(true);
                    return;
                }
                total += 1;
                v.insert(0);
                needed[r as usize].push((c, key));
            }
        };
        let depth = self.depth;
        self.headings_of(&self.st.axiom, depth, 0, |c, k| {
            if self.is_piece(c, depth) {
                add(c, depth, self.period.key(k), &mut needed);
            }
        });
        for r in (2..=depth).rev() {
            let level = std::mem::take(&mut needed[r as usize]);
            for &(s, key) in &level {
                for alt in &self.alts[s as usize] {
                    self.headings_of(&alt.succ, r - 1, key, |c, k| {
                        if self.is_piece(c, r - 1) {
                            add(c, r - 1, self.period.key(k), &mut needed);
                        }
                    });
                }
            }
            needed[r as usize] = level;
            if over.get() {
                return Err(Refusal::Budget);
            }
        }
        if over.get() {
            return Err(Refusal::Budget);
        }
        let mut next = 0u32;
        for r in 1..=depth {
            for &(s, key) in &needed[r as usize] {
                index.insert((s, r, key), next);
                next += 1;
            }
        }
        self.index = index;
        self.needed = needed;
        Ok(())
    }

    fn piece(&self, c: u32, r: u32, k: i64) -> Piece {
        match self.index.get(&(c, r, self.period.key(k))) {
            Some(&i) => self.pieces.get(i as usize).copied().unwrap_or(Piece::EMPTY),
            None => Piece::EMPTY,
        }
    }

    /// The expected piece of `word` (symbols at remaining depth `r`) from
    /// the origin at heading `k`.
    fn compose(&self, hd: &mut Headings, word: &[u32], r: u32, k: i64) -> Piece {
        let mut pen = Pen {
            x: 0.0,
            y: 0.0,
            k,
            flip: false,
        };
        let mut acc = Piece::EMPTY;
        let mut stack: Vec<Pen> = Vec::new();
        for &c in word {
            match self.ops[c as usize] {
                Some(Op::Push) => stack.push(pen),
                Some(Op::Pop) => {
                    if let Some(saved) = stack.pop() {
                        pen = saved;
                    }
                }
                _ if self.is_piece(c, r) => {
                    let p = self.piece(c, r, pen.k);
                    let sg = if pen.flip { -1.0 } else { 1.0 };
                    acc.moves |= p.moves;
                    if p.draws() {
                        acc.add(pen.x + sg * p.min_x, pen.y + sg * p.min_y);
                        acc.add(pen.x + sg * p.max_x, pen.y + sg * p.max_y);
                    }
                    pen.x += sg * p.dx;
                    pen.y += sg * p.dy;
                    let i = self.at(c, r);
                    pen.k = self.period.add_turn(pen.k, self.turn[i]).unwrap_or(pen.k);
                    pen.flip ^= self.flip[i];
                }
                op => {
                    let (dx, dy) = hd.dir(pen.k, pen.flip);
                    match op {
                        Some(Op::Draw) => {
                            acc.add(pen.x, pen.y);
                            pen.x += dx * self.len;
                            pen.y += dy * self.len;
                            acc.add(pen.x, pen.y);
                        }
                        Some(Op::Move) => {
                            pen.x += dx * self.len;
                            pen.y += dy * self.len;
                            acc.moves = true;
                        }
                        Some(Op::Turn(t)) => {
                            pen.k = self.period.add_turn(pen.k, i64::from(t)).unwrap_or(pen.k);
                        }
                        Some(Op::Flip) => pen.flip = !pen.flip,
                        _ => {}
                    }
                }
            }
        }
        acc.dx = pen.x;
        acc.dy = pen.y;
        acc
    }

    /// The pieces, level by level: each the alternatives' composed pieces
    /// averaged with their probabilities (the box over those that draw).
    fn compose_all(&mut self) {
        let mut hd = self.headings.clone();
        for r in 1..=self.depth {
            let mut level = Vec::with_capacity(self.needed[r as usize].len());
            for &(s, key) in &self.needed[r as usize] {
                let mut mixed = Piece::EMPTY;
                let (mut drawn, mut boxes) = (0.0, [0.0f64; 4]);
                for alt in &self.alts[s as usize] {
                    let p = self.compose(&mut hd, &alt.succ, r - 1, key);
                    mixed.dx += alt.p * p.dx;
                    mixed.dy += alt.p * p.dy;
                    mixed.moves |= p.moves;
                    if p.draws() {
                        drawn += alt.p;
                        for (b, v) in boxes.iter_mut().zip([p.min_x, p.min_y, p.max_x, p.max_y]) {
                            *b += alt.p * v;
                        }
                    }
                }
                if drawn > 0.0 {
                    [mixed.min_x, mixed.min_y, mixed.max_x, mixed.max_y] = boxes.map(|b| b / drawn);
                }
                level.push(mixed);
            }
            self.pieces.extend(level);
        }
    }

    /// Expected length of the whole word.
    pub fn expected_symbols(&self) -> f64 {
        let r = self.depth;
        self.st
            .axiom
            .iter()
            .map(|&s| self.size[self.at(s, r)])
            .sum()
    }

    /// Expected number of segments of the whole drawing.
    pub fn expected_segments(&self) -> f64 {
        let r = self.depth;
        self.st
            .axiom
            .iter()
            .map(|&s| self.count[self.at(s, r)])
            .sum()
    }

    /// The expected drawing's box (see the module documentation), `None`
    /// when nothing is drawn: a first estimate of the picture's size.
    pub fn expected_box(&self) -> Option<BBox> {
        let mut hd = self.headings.clone();
        let p = self.compose(&mut hd, &self.st.axiom, self.depth, 0);
        p.draws().then_some(BBox {
            min_x: p.min_x,
            min_y: p.min_y,
            max_x: p.max_x,
            max_y: p.max_y,
        })
    }

    /// Whether a piece is a stand-in at `detail` (the deterministic
    /// memo's rule, on the expected piece).
    fn cut(&self, c: u32, r: u32, p: &Piece, detail: f64) -> bool {
        if p.draws() {
            let d = if self.jumps[self.at(c, r)] {
                detail
            } else {
                detail / 2.0
            };
            p.extent() < d
        } else {
            !p.moves || libm::hypot(p.dx, p.dy) < detail
        }
    }

    /// What a walk at `detail` will do, in expectation over the choices.
    pub fn plan(&self, detail: f64) -> ChancePlan {
        // Per needed piece: [visits, trunk symbols, stand-ins].
        let mut cost: Vec<[f64; 3]> = Vec::with_capacity(self.pieces.len());
        let word_cost = |word: &[u32], r: u32, key: i64, cost: &[[f64; 3]]| {
            let mut acc = [0.0f64; 3];
            self.headings_of(word, r, key, |c, k| {
                acc[0] += 1.0;
                if !self.is_piece(c, r) {
                    return;
                }
                let i = self
                    .index
                    .get(&(c, r, self.period.key(k)))
                    .copied()
                    .unwrap_or(0) as usize;
                let p = self.pieces.get(i).copied().unwrap_or(Piece::EMPTY);
                if self.cut(c, r, &p, detail) {
                    acc[1] += self.trunk[self.at(c, r)];
                    acc[2] += f64::from(u8::from(p.draws() || p.moves));
                } else if let Some(x) = cost.get(i) {
                    (0..3).for_each(|j| acc[j] += x[j]);
                }
            });
            acc
        };
        for r in 1..=self.depth {
            for &(s, key) in &self.needed[r as usize] {
                let mut mixed = [0.0f64; 3];
                for alt in &self.alts[s as usize] {
                    let x = word_cost(&alt.succ, r - 1, key, &cost);
                    (0..3).for_each(|j| mixed[j] += alt.p * x[j]);
                }
                cost.push(mixed);
            }
        }
        let [visits, trunks, cuts] = word_cost(&self.st.axiom, self.depth, 0, &cost);
        ChancePlan {
            visits,
            trunks,
            cuts,
            exact_ends: visits + trunks <= LOD_WORK,
        }
    }
}
