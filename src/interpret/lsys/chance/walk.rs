//! The level-of-detail walk of a stochastic system ([`Chance::walk`]):
//! the seed's choices, stand-ins for subtrees whose expected box is under
//! the detail, their ends from trunk walks or expectation.

use super::*;
use crate::interpret::lsys::lod::{self, Part2, Stand2};
use crate::progress::NoProgress;
use crate::turtle::{Footprint, Sample, StandIn};

impl Chance {
    /// Where the subtree of `c` (remaining depth `r`, key `key`) started
    /// at `pen` ends, by walking its trunk with the seed's choices and the
    /// exact drawing's floating-point steps. Adds the symbols visited to
    /// `work`.
    fn trunk_end(
        &self,
        hd: &mut Headings,
        c: u32,
        r: u32,
        key: Key,
        pen: Pen,
        work: &mut u64,
    ) -> Pen {
        struct Frame<'a> {
            trunk: &'a [(u32, u32)],
            at: usize,
            r: u32,
            key: Key,
        }
        let mut pen = pen;
        let alt = self.st.choose(c, key).unwrap_or(0);
        let mut frames = vec![Frame {
            trunk: &self.alts[c as usize][alt].trunk,
            at: 0,
            r: r - 1,
            key,
        }];
        while let Some(top) = frames.last_mut() {
            let Some(&(j, s)) = top.trunk.get(top.at) else {
                frames.pop();
                continue;
            };
            top.at += 1;
            *work += 1;
            let (r, ks) = (top.r, top.key.child(u64::from(j)));
            if self.is_piece(s, r) {
                let alt = self.st.choose(s, ks).unwrap_or(0);
                frames.push(Frame {
                    trunk: &self.alts[s as usize][alt].trunk,
                    at: 0,
                    r: r - 1,
                    key: ks,
                });
                continue;
            }
            step(&mut pen, self.ops[s as usize], hd, self.len, |_| {});
        }
        pen
    }

    /// Draws the seed's drawing at `detail` canvas units into `turtle`
    /// (see the module documentation): stand-ins for subtrees whose
    /// expected box is under the detail, ending exactly where they end
    /// if `exact_ends`, else at their expected net move. Returns where the
    /// turtle ends and the symbols the trunk walks visited.
    pub(crate) fn walk<T: Turtle>(
        &self,
        detail: f64,
        exact_ends: bool,
        turtle: T,
        progress: &mut dyn Progress,
    ) -> (Point, u64) {
        let start = Pen {
            x: 0.0,
            y: 0.0,
            k: 0,
            flip: false,
        };
        let word = (&self.st.axiom[..], self.depth, self.st.root());
        self.walk_word(word, start, detail, exact_ends, turtle, progress)
    }

    /// [`Chance::walk`] of `word` (its symbols, remaining depth and key)
    /// from `pen`: the one walk ([`lod::walk`]) over this memo, whose
    /// frames carry the choices' keys.
    fn walk_word<T: Turtle>(
        &self,
        word: (&[u32], u32, Key),
        pen: Pen,
        detail: f64,
        exact_ends: bool,
        turtle: T,
        progress: &mut dyn Progress,
    ) -> (Point, u64) {
        let mut w = WalkChance {
            c: self,
            detail,
            exact_ends,
            turtle,
            hd: self.headings.clone(),
            pen,
            stack: Vec::new(),
            work: 0,
        };
        lod::walk(&mut w, word.0, word.1, word.2, progress);
        (Point::new(w.pen.x, w.pen.y), w.work)
    }
}

/// A walk of the stochastic memo at a detail: its turtle and pen, and the
/// symbols its trunk walks visited.
struct WalkChance<'m, T> {
    c: &'m Chance,
    detail: f64,
    exact_ends: bool,
    turtle: T,
    hd: Headings,
    pen: Pen,
    stack: Vec<Pen>,
    work: u64,
}

impl<'m, T: Turtle> lod::Memo<'m> for WalkChance<'m, T> {
    type Ctx = Key;

    #[inline]
    fn child(key: Key, at: usize) -> Key {
        key.child(at as u64)
    }

    #[inline]
    fn is_piece(&self, c: u32, r: u32) -> bool {
        self.c.is_piece(c, r)
    }

    fn piece(&mut self, c: u32, r: u32, kc: Key) -> Option<&'m [u32]> {
        let ch = self.c;
        let pen = self.pen;
        let p = ch.piece(c, r, pen.k);
        if !ch.cut(c, r, &p, self.detail) {
            let alt = ch.st.choose(c, kc).unwrap_or(0);
            return Some(&ch.alts[c as usize][alt].succ);
        }
        let sg = if pen.flip { -1.0 } else { 1.0 };
        let end = if self.exact_ends {
            ch.trunk_end(&mut self.hd, c, r, kc, pen, &mut self.work)
        } else {
            Pen {
                x: pen.x + sg * p.dx,
                y: pen.y + sg * p.dy,
                ..pen
            }
        };
        let at = ch.at(c, r);
        if p.draws() {
            let (ex, ey) = (end.x - pen.x, end.y - pen.y);
            let part = Part2 {
                start: Point::new(pen.x, pen.y),
                end: Point::new(end.x, end.y),
                chord: libm::hypot(ex, ey),
                lo: Point::new(pen.x + sg * p.min_x, pen.y + sg * p.min_y),
                hi: Point::new(pen.x + sg * p.max_x, pen.y + sg * p.max_y),
                piece: p,
                segments: ch.count[at],
                jumps: ch.jumps[at],
                len: ch.len,
            };
            match lod::stand_in_2d(&part) {
                Stand2::Run(seg, n) => self.turtle.run(seg, n),
                Stand2::Bush(seg, density, spread) => {
                    // Each call draws the subtree with other choices
                    // (keyed from the first stand-in that asks): the
                    // sample is of the alternatives, as the stand-in is
                    // of the seed's choices.
                    let calls = std::cell::Cell::new(0u64);
                    let draw = |detail: f64, t: &mut dyn Turtle| {
                        let i = calls.replace(calls.get() + 1);
                        let start = Pen {
                            x: 0.0,
                            y: 0.0,
                            ..pen
                        };
                        let word = (&[c][..], r, kc.child(u64::MAX - i));
                        let _ = ch.walk_word(word, start, detail, false, t, &mut NoProgress);
                    };
                    // Other choices may reach farther than the expected
                    // box: it is widened by its size.
                    let (w, h) = (p.max_x - p.min_x, p.max_y - p.min_y);
                    let (lo, hi) = Sample::corners(
                        Point::new(sg * p.min_x, sg * p.min_y),
                        Point::new(sg * p.max_x, sg * p.max_y),
                    );
                    let sample = Sample {
                        at: Point::new(pen.x, pen.y),
                        key: Sample::piece_key(c, r, ch.period.key(pen.k), pen.flip),
                        bounds: (
                            Point::new(lo.x - w, lo.y - h),
                            Point::new(hi.x + w, hi.y + h),
                        ),
                        segments: ch.count[at] as u64,
                        draw: &draw,
                    };
                    self.turtle.stand_in(&StandIn {
                        seg,
                        density,
                        footprint: Some(Footprint {
                            spread,
                            runs: ch.runs[at],
                        }),
                        sample: Some(&sample),
                    });
                }
            }
        }
        self.pen = Pen {
            x: end.x,
            y: end.y,
            k: pen.k.wrapping_add(ch.turn[at]),
            flip: pen.flip ^ ch.flip[at],
        };
        None
    }

    #[inline]
    fn terminal(&mut self, c: u32) {
        match self.c.ops[c as usize] {
            Some(Op::Push) => self.stack.push(self.pen),
            Some(Op::Pop) => {
                if let Some(saved) = self.stack.pop() {
                    self.pen = saved;
                }
            }
            op => {
                let turtle = &mut self.turtle;
                step(&mut self.pen, op, &mut self.hd, self.c.len, |s| {
                    turtle.segment(s)
                });
            }
        }
    }
}

/// Applies a terminal `op` to `pen` as [`Interp`](crate::turtle::Interp)
/// does (`pos + dir * len`), handing a drawn segment to `draw`.
#[inline]
fn step(pen: &mut Pen, op: Option<Op>, hd: &mut Headings, len: f64, mut draw: impl FnMut(Segment)) {
    match op {
        Some(Op::Draw) => {
            let (dx, dy) = hd.dir(pen.k, pen.flip);
            let to = Point::new(pen.x + dx * len, pen.y + dy * len);
            draw(Segment {
                from: Point::new(pen.x, pen.y),
                to,
                order: 0,
            });
            (pen.x, pen.y) = (to.x, to.y);
        }
        Some(Op::Move) => {
            let (dx, dy) = hd.dir(pen.k, pen.flip);
            (pen.x, pen.y) = (pen.x + dx * len, pen.y + dy * len);
        }
        Some(Op::Turn(t)) => pen.k = pen.k.wrapping_add(i64::from(t)),
        Some(Op::Flip) => pen.flip = !pen.flip,
        _ => {}
    }
}

/// Draws stochastic `sys`'s [`Chance`] at `detail` canvas units into
/// `turtle`, with exact ends where [`Chance::plan`] says they fit
/// [`LOD_WORK`]; returns where the turtle ends. Refused when the walk would visit more than the
/// stochastic traversal budget (a tenth of `limits.max_symbols`).
pub fn draw_chance(
    chance: &Chance,
    detail: f64,
    limits: &Limits,
    turtle: &mut dyn Turtle,
    progress: &mut dyn Progress,
) -> Result<Point, Diagnostics> {
    let plan = chance.plan(detail);
    let within = super::super::stochastic::budget(limits);
    if plan.visits > within.max_symbols as f64 {
        return Err(super::super::stochastic::explain_budget(
            Bound::Symbols
                .exceeded_by(
                    format!(
                        "symbols to visit at depth {} at this level of detail (expected)",
                        chance.depth
                    ),
                    format!("{:.0}", plan.visits),
                    within.max_symbols,
                )
                .into(),
            limits,
        ));
    }
    progress.start("symbols", plan.visits as u64);
    let (end, _) = chance.walk(detail, plan.exact_ends, turtle, progress);
    progress.finish();
    Ok(end)
}
