//! Memoized geometry of a deterministic L-system: per `(symbol, remaining
//! depth, starting heading)` the net displacement, net turn and bounding box
//! of its expansion relative to its start, composed exactly instead of
//! traversed.
//!
//! Brackets restore what they saved, so the drawing of `W(s, r)` started
//! at position `p`, heading `k`, flip `f` is the drawing started at the
//! origin, heading `k`, unflipped, translated by `p` and (if `f`) turned
//! around: a turn adds to `k` whatever the flip, and a flip negates every
//! direction. Its net turn and flip do not depend on the start at all. So
//! one [`Piece`] per `(s, r, k)` gives everything: a parent's piece is its
//! successor's pieces (at `r - 1`, each at the heading reached) composed in
//! order. Headings stay exact integers; positions are sums of the same
//! directions in another order, so they match a traversal to
//! floating-point accuracy, not bit for bit.
//!
//! Only the headings the word reaches are computed: first the net turns of
//! every `(symbol, r)` (heading-independent), then, from the axiom down,
//! the `(symbol, r, k)` each level needs, then the pieces bottom-up. When
//! the angle has a period (`p` turns make a whole number of full turns,
//! `p` at most [`MAX_PERIOD`]), headings are keyed modulo `p`. The work is
//! O(alphabet x depth x headings reached x successor length), whatever the
//! word's length; when the pieces would pass [`GEOMETRY_ENTRIES`] the memo
//! is refused and callers fall back (`stats` to its bounded traversal, the
//! renderer to drawing every segment).
//!
//! The memo applies when every successor is bracket-balanced and `[` and
//! `]` have no rule (then every expansion is balanced); the axiom may be
//! anything (it is walked with a real stack, an extra `]` ignored as the
//! turtle ignores it).
//!
//! The same memo gives the renderer its level of detail ([`Geometry::draw_lod`]):
//! a subtree whose whole drawing fits inside `detail` canvas units is drawn
//! as one stand-in segment instead of being expanded.

use std::cell::RefCell;
/// The memo's map, hashed by foldhash's fixed state: SipHash cost about
/// 5 % of a dense picture (issue 37); nothing iterates it into output.
type HashMap<K, V> = std::collections::HashMap<K, V, foldhash::fast::FixedState>;

mod lod;
mod solid;

use super::alphabet::Alphabet;
use crate::model::lsys::LSystem;
use crate::progress::Progress;
use crate::turtle::{BBox, Headings, Op, Point, Segment, Turtle};

/// Most pieces (and per-level turn and count entries) one memo may hold:
/// about 100 bytes each with the map, so at most about 50 MB.
pub const GEOMETRY_ENTRIES: usize = 1 << 19;

/// Longest heading period looked for: `p` turns of the angle that make a
/// whole number of full turns (25.7 degrees: 3600).
pub const MAX_PERIOD: i64 = 1 << 16;

/// Why the memo does not apply.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Refusal {
    /// A successor is not bracket-balanced, or `[` or `]` has a rule.
    Brackets,
    /// More than [`GEOMETRY_ENTRIES`] pieces (headings reached x depth x symbols).
    Budget,
    /// A net turn does not fit 64 bits and the angle has no period.
    Turns,
    /// The system has stochastic rules: occurrences of one symbol at one
    /// depth differ, so no piece can stand for all of them.
    Stochastic,
    /// A stochastic rule's alternatives turn or flip differently (outside
    /// their brackets, at some depth): the heading after a subtree would
    /// depend on its choices.
    Choices,
    /// The system is parametric (docs/lsys.md): it is drawn exactly.
    Parametric,
}

/// The drawing of one `(symbol, remaining depth, heading)` relative to its
/// start, unflipped.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct Piece {
    /// Net displacement.
    pub dx: f64,
    /// Net displacement.
    pub dy: f64,
    /// Box of every drawn point; `min > max` when nothing is drawn.
    pub min_x: f64,
    /// See `min_x`.
    pub min_y: f64,
    /// See `min_x`.
    pub max_x: f64,
    /// See `min_x`.
    pub max_y: f64,
    /// Whether it moves without drawing somewhere (an `f`).
    pub moves: bool,
}

impl Piece {
    pub(super) const EMPTY: Piece = Piece {
        dx: 0.0,
        dy: 0.0,
        min_x: f64::INFINITY,
        min_y: f64::INFINITY,
        max_x: f64::NEG_INFINITY,
        max_y: f64::NEG_INFINITY,
        moves: false,
    };

    /// Whether anything is drawn.
    pub fn draws(&self) -> bool {
        self.min_x <= self.max_x && self.min_y <= self.max_y
    }

    /// The longer side of the box (0 when nothing is drawn).
    pub fn extent(&self) -> f64 {
        if self.draws() {
            (self.max_x - self.min_x).max(self.max_y - self.min_y)
        } else {
            0.0
        }
    }

    /// Adds the point `(x, y)` to the box.
    #[inline]
    pub(super) fn add(&mut self, x: f64, y: f64) {
        self.min_x = self.min_x.min(x);
        self.min_y = self.min_y.min(y);
        self.max_x = self.max_x.max(x);
        self.max_y = self.max_y.max(y);
    }
}

/// The composing turtle: position, exact heading, flip, and the box so far.
#[derive(Clone, Copy)]
struct Pen {
    x: f64,
    y: f64,
    k: i64,
    flip: bool,
}

/// The memo; see the module documentation.
pub(crate) struct Geometry {
    alpha: Alphabet,
    /// Saturating length of the whole word (what the exact path visits).
    word: u64,
    depth: u32,
    /// Terminal op of every symbol.
    ops: Vec<Option<Op>>,
    period: Period,
    /// Net turn of `(s, r)`: `turn[r * n + s]` (reduced modulo the period
    /// only if it would not fit 64 bits).
    turn: Vec<i64>,
    /// Net flip of `(s, r)`, same index.
    flip: Vec<bool>,
    /// Saturating number of `F` in `W(s, r)`, same index.
    count: Vec<u64>,
    /// Saturating number of `]` and `f` in `W(s, r)` (where a drawn run
    /// breaks off and a new one starts), same index.
    jumps: Vec<u64>,
    /// `(s, r, key)` to its index in `pieces`, for `r >= 1` and `s` ruled.
    index: HashMap<(u32, u32, i64), u32>,
    /// Per level `r`, the `(s, key)` needed, in the order first needed.
    needed: Vec<Vec<(u32, i64)>>,
    pieces: Vec<Piece>,
    /// Directions (a lazily filled cache, hence the cell: the memo is
    /// shared by the render's passes).
    headings: RefCell<Headings>,
    len: f64,
    /// Coverage masks of the solid test (geometry/solid.rs), for the
    /// detail last asked.
    masks: RefCell<solid::Masks>,
}

/// Headings counted in turns of the angle, and the angle's period: the
/// least `p` in `1..=MAX_PERIOD` with `p * angle` a whole number of full
/// turns (within 1e-9 of a degree), if it has one.
#[derive(Debug, Clone, Copy)]
pub(super) struct Period(Option<i64>);

impl Period {
    /// The period of `angle`.
    pub(super) fn of(angle: f64) -> Period {
        if !angle.is_finite() {
            return Period(None);
        }
        Period((1..=MAX_PERIOD).find(|&p| {
            let turns = p as f64 * angle / 360.0;
            (turns - libm::round(turns)).abs() * 360.0 < 1e-9
        }))
    }

    /// The memo key of heading `k`: modulo the period, if any.
    pub(super) fn key(self, k: i64) -> i64 {
        match self.0 {
            Some(p) => k.rem_euclid(p),
            None => k,
        }
    }

    /// `k + t`, exact when it fits, else modulo the period; `None` when it
    /// does not fit and there is no period.
    pub(super) fn add_turn(self, k: i64, t: i64) -> Option<i64> {
        match (k.checked_add(t), self.0) {
            (Some(v), _) => Some(v),
            (None, Some(p)) => Some(k.rem_euclid(p) + t.rem_euclid(p)),
            (None, None) => None,
        }
    }
}

/// Whether `word` is bracket-balanced: never more `]` than `[` so far, and
/// as many of each in all.
pub(super) fn balanced(word: &[u32], ops: &[Option<Op>]) -> bool {
    let mut open = 0usize;
    for &c in word {
        match ops[c as usize] {
            Some(Op::Push) => open += 1,
            Some(Op::Pop) => match open.checked_sub(1) {
                Some(o) => open = o,
                None => return false,
            },
            _ => {}
        }
    }
    open == 0
}

impl Geometry {
    /// The memo of `alpha` (of `sys`) derived to `depth`, unit step `len`,
    /// for the headings the axiom reaches; at most `budget` pieces.
    pub(crate) fn new(
        alpha: Alphabet,
        sys: &LSystem,
        depth: u32,
        len: f64,
        budget: usize,
    ) -> Result<Self, Refusal> {
        let n = alpha.chars.len();
        let ops: Vec<Option<Op>> = alpha.chars.iter().map(|&c| Op::of_lsys(c)).collect();
        for (s, succ) in alpha.succ.iter().enumerate() {
            if let Some(succ) = succ
                && (matches!(ops[s], Some(Op::Push | Op::Pop)) || !balanced(succ, &ops))
            {
                return Err(Refusal::Brackets);
            }
        }
        let levels = depth as usize + 1;
        if n.saturating_mul(levels) > budget.saturating_mul(4) {
            return Err(Refusal::Budget);
        }
        let period = Period::of(sys.angle);
        let word = alpha.word_lengths(depth)[depth as usize];
        let mut g = Geometry {
            alpha,
            word,
            depth,
            ops,
            period,
            turn: vec![0; n * levels],
            flip: vec![false; n * levels],
            count: vec![0; n * levels],
            jumps: vec![0; n * levels],
            index: HashMap::default(),
            needed: vec![Vec::new(); levels],
            pieces: Vec::new(),
            headings: RefCell::new(Headings::starting(sys.heading, sys.angle)),
            len,
            masks: RefCell::new(solid::Masks::default()),
        };
        g.turns()?;
        g.demand(budget)?;
        g.compose_all();
        Ok(g)
    }

    /// Net turns, flips and `F` counts of every `(s, r)`, level by level.
    fn turns(&mut self) -> Result<(), Refusal> {
        let n = self.alpha.chars.len();
        for s in 0..n {
            let (t, f) = match self.ops[s] {
                Some(Op::Turn(t)) => (i64::from(t), false),
                Some(Op::Flip) => (0, true),
                _ => (0, false),
            };
            self.turn[s] = t;
            self.flip[s] = f;
            self.count[s] = u64::from(self.ops[s] == Some(Op::Draw));
            self.jumps[s] = u64::from(matches!(self.ops[s], Some(Op::Pop | Op::Move)));
        }
        for r in 1..=self.depth as usize {
            for s in 0..n {
                let (mut t, mut f, mut c, mut j) = (0i64, false, 0u64, 0u64);
                match &self.alpha.succ[s] {
                    None => {
                        t = self.turn[s];
                        f = self.flip[s];
                        c = self.count[s];
                        j = self.jumps[s];
                    }
                    Some(succ) => {
                        let mut open = 0usize;
                        for &ch in succ {
                            let i = (r - 1) * n + ch as usize;
                            c = c.saturating_add(self.count[i]);
                            j = j.saturating_add(self.jumps[i]);
                            match self.ops[ch as usize] {
                                Some(Op::Push) => open += 1,
                                Some(Op::Pop) => open -= 1,
                                _ if open == 0 => {
                                    t = self
                                        .period
                                        .add_turn(t, self.turn[i])
                                        .ok_or(Refusal::Turns)?;
                                    f ^= self.flip[i];
                                }
                                _ => {}
                            }
                        }
                    }
                }
                self.turn[r * n + s] = t;
                self.flip[r * n + s] = f;
                self.count[r * n + s] = c;
                self.jumps[r * n + s] = j;
            }
        }
        Ok(())
    }

    fn turn_of(&self, s: u32, r: u32) -> i64 {
        self.turn[r as usize * self.alpha.chars.len() + s as usize]
    }

    fn flip_of(&self, s: u32, r: u32) -> bool {
        self.flip[r as usize * self.alpha.chars.len() + s as usize]
    }

    /// Saturating length of the whole word: the symbols the exact path
    /// visits.
    pub(crate) fn word(&self) -> u64 {
        self.word
    }

    /// Saturating number of `F` in the whole word.
    pub(crate) fn segments(&self) -> u64 {
        let n = self.alpha.chars.len();
        let base = self.depth as usize * n;
        self.alpha.axiom.iter().fold(0u64, |a, &s| {
            a.saturating_add(self.count[base + s as usize])
        })
    }

    /// Whether child `c` at remaining depth `r` is a piece (else terminal).
    fn is_piece(&self, c: u32, r: u32) -> bool {
        r >= 1 && self.alpha.succ[c as usize].is_some()
    }

    /// Walks `word`, whose symbols are at remaining depth `r`, from heading
    /// `k`, calling `need(c, key)` for every piece, in order.
    fn walk_headings(
        &self,
        word: &[u32],
        r: u32,
        mut k: i64,
        mut need: impl FnMut(u32, i64) -> Result<(), Refusal>,
    ) -> Result<(), Refusal> {
        let mut stack: Vec<i64> = Vec::new();
        for &c in word {
            match self.ops[c as usize] {
                Some(Op::Push) => stack.push(k),
                Some(Op::Pop) => {
                    if let Some(saved) = stack.pop() {
                        k = saved;
                    }
                }
                _ if self.is_piece(c, r) => {
                    need(c, self.period.key(k))?;
                    k = self
                        .period
                        .add_turn(k, self.turn_of(c, r))
                        .ok_or(Refusal::Turns)?;
                }
                Some(Op::Turn(t)) => {
                    k = self
                        .period
                        .add_turn(k, i64::from(t))
                        .ok_or(Refusal::Turns)?;
                }
                _ => {}
            }
        }
        Ok(())
    }

    /// The `(s, r, key)` the word needs, from the axiom down.
    fn demand(&mut self, budget: usize) -> Result<(), Refusal> {
        let mut index = std::mem::take(&mut self.index);
        let mut needed = std::mem::take(&mut self.needed);
        let mut total = 0usize;
        let mut add = |c: u32, r: u32, key: i64, needed: &mut Vec<Vec<(u32, i64)>>| {
            if let std::collections::hash_map::Entry::Vacant(v) = index.entry((c, r, key)) {
                if total >= budget {
                    return Err(Refusal::Budget);
                }
                v.insert(total as u32);
                total += 1;
                needed[r as usize].push((c, key));
            }
            Ok(())
        };
        let depth = self.depth;
        let mut last = None;
        let result = self.walk_headings(&self.alpha.axiom, depth, 0, |c, key| {
            if last == Some((c, key)) {
                return Ok(());
            }
            last = Some((c, key));
            add(c, depth, key, &mut needed)
        });
        result?;
        for r in (2..=depth).rev() {
            let level = std::mem::take(&mut needed[r as usize]);
            for &(s, key) in &level {
                let succ = self.alpha.succ[s as usize].as_deref().unwrap_or(&[]);
                self.walk_headings(succ, r - 1, key, |c, ck| add(c, r - 1, ck, &mut needed))?;
            }
            needed[r as usize] = level;
        }
        // Indices were handed out top-down; renumber bottom-up so pieces
        // can be pushed in order.
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

    /// The piece of `(c, r)` at heading `k` (which must have been needed).
    fn piece(&self, c: u32, r: u32, k: i64) -> Piece {
        match self.index.get(&(c, r, self.period.key(k))) {
            Some(&i) => self.pieces[i as usize],
            None => Piece::EMPTY,
        }
    }

    /// Applies child `c` (at remaining depth `r`) to the pen, adding what it
    /// draws to `acc`.
    fn apply(&self, c: u32, r: u32, pen: &mut Pen, acc: &mut Piece) {
        if self.is_piece(c, r) {
            let p = self.piece(c, r, pen.k);
            let sg = if pen.flip { -1.0 } else { 1.0 };
            acc.moves |= p.moves;
            if p.draws() {
                if pen.flip {
                    acc.add(pen.x - p.max_x, pen.y - p.max_y);
                    acc.add(pen.x - p.min_x, pen.y - p.min_y);
                } else {
                    acc.add(pen.x + p.min_x, pen.y + p.min_y);
                    acc.add(pen.x + p.max_x, pen.y + p.max_y);
                }
            }
            pen.x += sg * p.dx;
            pen.y += sg * p.dy;
            pen.k = self
                .period
                .add_turn(pen.k, self.turn_of(c, r))
                .unwrap_or(pen.k);
            pen.flip ^= self.flip_of(c, r);
            return;
        }
        match self.ops[c as usize] {
            Some(Op::Draw) => {
                let (dx, dy) = self.headings.borrow_mut().dir(pen.k, pen.flip);
                acc.add(pen.x, pen.y);
                pen.x += dx * self.len;
                pen.y += dy * self.len;
                acc.add(pen.x, pen.y);
            }
            Some(Op::Move) => {
                let (dx, dy) = self.headings.borrow_mut().dir(pen.k, pen.flip);
                pen.x += dx * self.len;
                pen.y += dy * self.len;
                acc.moves = true;
            }
            Some(Op::Turn(t)) => pen.k = self.period.add_turn(pen.k, i64::from(t)).unwrap_or(pen.k),
            Some(Op::Flip) => pen.flip = !pen.flip,
            _ => {}
        }
    }

    /// Composes `word` (symbols at remaining depth `r`) from the origin at
    /// heading `k`: its piece and where it ends.
    fn compose(&self, word: &[u32], r: u32, k: i64) -> (Piece, Pen) {
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
                _ => self.apply(c, r, &mut pen, &mut acc),
            }
        }
        acc.dx = pen.x;
        acc.dy = pen.y;
        (acc, pen)
    }

    fn compose_all(&mut self) {
        for r in 1..=self.depth {
            let level = std::mem::take(&mut self.needed[r as usize]);
            for &(s, key) in &level {
                let succ = self.alpha.succ[s as usize].as_deref().unwrap_or(&[]);
                let (piece, _) = self.compose(succ, r - 1, key);
                self.pieces.push(piece);
            }
            self.needed[r as usize] = level;
        }
    }

    /// The box of the whole drawing (`None` if nothing is drawn) and where
    /// the turtle ends, starting at the origin.
    pub(crate) fn whole(&self) -> (Option<BBox>, Point) {
        let (p, pen) = self.compose(&self.alpha.axiom, self.depth, 0);
        let bbox = p.draws().then_some(BBox {
            min_x: p.min_x,
            min_y: p.min_y,
            max_x: p.max_x,
            max_y: p.max_y,
        });
        (bbox, Point::new(pen.x, pen.y))
    }
}
