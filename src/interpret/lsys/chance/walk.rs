//! The level-of-detail walk of a stochastic system ([`Chance::walk`]):
//! the seed's choices, stand-ins for subtrees whose expected box is under
//! the detail, their ends from trunk walks or expectation.

use super::*;
use crate::progress::NoProgress;
use crate::turtle::Sample;

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
    /// from `pen`.
    fn walk_word<T: Turtle>(
        &self,
        word: (&[u32], u32, Key),
        pen: Pen,
        detail: f64,
        exact_ends: bool,
        mut turtle: T,
        progress: &mut dyn Progress,
    ) -> (Point, u64) {
        struct Frame<'w> {
            word: &'w [u32],
            at: usize,
            r: u32,
            key: Key,
        }
        let mut hd = self.headings.clone();
        let len = self.len;
        let mut frames = vec![Frame {
            word: word.0,
            at: 0,
            r: word.1,
            key: word.2,
        }];
        let mut pen = pen;
        let mut stack: Vec<Pen> = Vec::new();
        let (mut done, mut work) = (0u64, 0u64);
        let mut next_report = PROGRESS_STEP;
        while let Some(top) = frames.last_mut() {
            let Some(&c) = top.word.get(top.at) else {
                frames.pop();
                continue;
            };
            let kc = top.key.child(top.at as u64);
            top.at += 1;
            let r = top.r;
            done += 1;
            if done >= next_report {
                progress.update(done);
                next_report = done.saturating_add(PROGRESS_STEP);
            }
            if self.is_piece(c, r) {
                let p = self.piece(c, r, pen.k);
                if !self.cut(c, r, &p, detail) {
                    let alt = self.st.choose(c, kc).unwrap_or(0);
                    frames.push(Frame {
                        word: &self.alts[c as usize][alt].succ,
                        at: 0,
                        r: r - 1,
                        key: kc,
                    });
                    continue;
                }
                let sg = if pen.flip { -1.0 } else { 1.0 };
                let end = if exact_ends {
                    self.trunk_end(&mut hd, c, r, kc, pen, &mut work)
                } else {
                    Pen {
                        x: pen.x + sg * p.dx,
                        y: pen.y + sg * p.dy,
                        ..pen
                    }
                };
                if p.draws() {
                    let (ex, ey) = (end.x - pen.x, end.y - pen.y);
                    let chord = libm::hypot(ex, ey);
                    let (from, to) = if chord * 2.0 >= p.extent() {
                        (Point::new(pen.x, pen.y), Point::new(end.x, end.y))
                    } else {
                        (
                            Point::new(pen.x + sg * p.min_x, pen.y + sg * p.min_y),
                            Point::new(pen.x + sg * p.max_x, pen.y + sg * p.max_y),
                        )
                    };
                    let at = self.at(c, r);
                    let seg_len = libm::hypot(to.x - from.x, to.y - from.y);
                    let density = if self.jumps[at] {
                        (self.count[at] * len.abs() / seg_len).max(1.0)
                    } else {
                        1.0
                    };
                    let density = if density.is_finite() { density } else { 1.0 };
                    if self.jumps[at] {
                        let (seg, spread) = crate::interpret::lsys::geometry::across(
                            from,
                            to,
                            Point::new(pen.x + sg * p.min_x, pen.y + sg * p.min_y),
                            Point::new(pen.x + sg * p.max_x, pen.y + sg * p.max_y),
                        );
                        // Each call draws the subtree with other choices
                        // (keyed from the first stand-in that asks): the
                        // sample is of the alternatives, as the stand-in
                        // is of the seed's choices.
                        let calls = std::cell::Cell::new(0u64);
                        let draw = |detail: f64, t: &mut dyn Turtle| {
                            let i = calls.replace(calls.get() + 1);
                            let start = Pen {
                                x: 0.0,
                                y: 0.0,
                                ..pen
                            };
                            let word = (&[c][..], r, kc.child(u64::MAX - i));
                            let _ = self.walk_word(word, start, detail, false, t, &mut NoProgress);
                        };
                        // Other choices may reach farther than the
                        // expected box: it is widened by its size.
                        let (w, h) = (p.max_x - p.min_x, p.max_y - p.min_y);
                        let (lo, hi) = Sample::corners(
                            Point::new(sg * p.min_x, sg * p.min_y),
                            Point::new(sg * p.max_x, sg * p.max_y),
                        );
                        let sample = Sample {
                            at: Point::new(pen.x, pen.y),
                            key: Sample::piece_key(c, r, self.period.key(pen.k), pen.flip),
                            bounds: (
                                Point::new(lo.x - w, lo.y - h),
                                Point::new(hi.x + w, hi.y + h),
                            ),
                            segments: self.count[at] as u64,
                            draw: &draw,
                        };
                        turtle.bush(seg, density, spread, self.runs[at], &sample);
                    } else {
                        turtle.run(Segment { from, to, order: 0 }, self.count[at]);
                    }
                }
                let at = self.at(c, r);
                pen = Pen {
                    x: end.x,
                    y: end.y,
                    k: pen.k.wrapping_add(self.turn[at]),
                    flip: pen.flip ^ self.flip[at],
                };
                continue;
            }
            match self.ops[c as usize] {
                Some(Op::Push) => stack.push(pen),
                Some(Op::Pop) => {
                    if let Some(saved) = stack.pop() {
                        pen = saved;
                    }
                }
                op => step(&mut pen, op, &mut hd, len, |s| turtle.segment(s)),
            }
        }
        progress.update(done);
        (Point::new(pen.x, pen.y), work)
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
