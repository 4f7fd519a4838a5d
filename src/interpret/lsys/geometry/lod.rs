//! The level of detail on the memo: which pieces are cut at a detail,
//! what a walk at that detail will visit (counted before drawing), and the
//! walk itself ([`Geometry::draw_lod`]), which draws a cut piece as one
//! stand-in and every other symbol as the exact drawing does.

use super::*;
use crate::interpret::lsys::lod::{self, Part2, Stand2};
use crate::progress::NoProgress;
use crate::turtle::{Footprint, Sample, StandIn};

/// A piece of at least this many segments that is not cut is first
/// offered to [`Turtle::covered`], and skipped if all it could ink is
/// full ink already. (Smaller ones cost less to draw than to ask about.)
const PRUNE_SEGMENTS: u64 = 64;

/// A bush not cut, of at least [`PRUNE_SEGMENTS`] and under this many
/// details across, is offered whole to [`Turtle::dense`]: drawn once per
/// distinct piece as the coverage it leaves where its own strokes ink its
/// footprint fully, not walked again at every occurrence.
const DENSE_MAX: f64 = 16.0;

/// Draws a solid piece's box (at `x`, `y`, turned around if `sg` is -1)
/// as one zigzag of rows at most `detail` apart: one connected run, so
/// the backend strokes it as one outline, which covers the box widened
/// by half the stroke, as the exact drawing does (geometry/solid.rs).
fn hatch<T: Turtle>(turtle: &mut T, x: f64, y: f64, sg: f64, p: &Piece, rows: u64) {
    let (x0, x1) = (x + sg * p.min_x, x + sg * p.max_x);
    let (y0, y1) = (y + sg * p.min_y, y + sg * p.max_y);
    let row_y = |i: u64| y0 + (y1 - y0) * i as f64 / (rows - 1).max(1) as f64;
    let mut at = Point::new(x0, row_y(0));
    for i in 0..rows {
        let yi = row_y(i);
        let (a, b) = if i % 2 == 0 { (x0, x1) } else { (x1, x0) };
        let from = Point::new(a, yi);
        if from != at {
            turtle.segment(Segment {
                from: at,
                to: from,
                order: 0,
            });
        }
        let to = Point::new(b, yi);
        turtle.segment(Segment { from, to, order: 0 });
        at = to;
    }
}

impl Geometry {
    /// Whether a piece is drawn as a stand-in at `detail`: one whose box is
    /// smaller than `detail`, or one that draws nothing and moves less than
    /// `detail` or not at all (only its net turn matters; exact). At
    /// `detail` 0 nothing that draws or moves is cut, so the segments are
    /// the exact drawing's, bit for bit.
    fn cut(&self, c: u32, r: u32, k: i64, p: &Piece, detail: f64) -> bool {
        if p.draws() {
            if self.solid(c, r, k, p, detail) {
                return true;
            }
            // A connected run's stand-in is its chord, one line where the
            // exact drawing folds a winding line at FOLD_PX: cut it at half
            // the detail, about that tolerance.
            let at = r as usize * self.alpha.chars.len() + c as usize;
            let d = if self.jumps[at] == 0 {
                detail / 2.0
            } else {
                detail
            };
            p.extent() < d
        } else {
            !p.moves || libm::hypot(p.dx, p.dy) < detail
        }
    }

    /// What [`Geometry::draw_lod`] at `detail` will do, counted from the
    /// memo before drawing (saturating): `[units, segments, stand-ins]`,
    /// the symbols and stand-ins it visits, the segments and stand-ins it
    /// hands over, and the stand-ins that draw or move (the approximations:
    /// with none, the drawing is the exact one).
    pub(crate) fn lod_cost(&self, detail: f64) -> [u64; 3] {
        let add = |a: [u64; 3], b: [u64; 3]| {
            [
                a[0].saturating_add(b[0]),
                a[1].saturating_add(b[1]),
                a[2].saturating_add(b[2]),
            ]
        };
        let n = self.pieces.len();
        let mut cost: Vec<[u64; 3]> = Vec::with_capacity(n);
        let child = |c: u32, r: u32, k: i64, cost: &[[u64; 3]]| -> [u64; 3] {
            if self.is_piece(c, r) {
                let i = self
                    .index
                    .get(&(c, r, self.period.key(k)))
                    .copied()
                    .unwrap_or(0) as usize;
                let p = self.pieces.get(i).copied().unwrap_or(Piece::EMPTY);
                if self.cut(c, r, k, &p, detail) {
                    let drawn = if self.solid(c, r, k, &p, detail) {
                        2 * solid::hatch_rows(&p, detail)
                    } else {
                        u64::from(p.draws())
                    };
                    [1, drawn, u64::from(p.draws() || p.moves)]
                } else {
                    add([1, 0, 0], cost.get(i).copied().unwrap_or([0; 3]))
                }
            } else {
                [1, u64::from(self.ops[c as usize] == Some(Op::Draw)), 0]
            }
        };
        let sum = |word: &[u32], r: u32, key: i64, cost: &[[u64; 3]]| -> [u64; 3] {
            let mut acc = [0u64; 3];
            let _ = self.walk_headings_all(word, r, key, |c, k| {
                acc = add(acc, child(c, r, k, cost));
            });
            acc
        };
        for r in 1..=self.depth {
            for &(s, key) in &self.needed[r as usize] {
                let succ = self.alpha.succ[s as usize].as_deref().unwrap_or(&[]);
                let c = sum(succ, r - 1, key, &cost);
                cost.push(c);
            }
        }
        sum(&self.alpha.axiom, self.depth, 0, &cost)
    }

    /// Like `walk_headings`, but calls `f(c, k)` for every symbol (pieces,
    /// terminals and brackets) with the heading before it.
    fn walk_headings_all(
        &self,
        word: &[u32],
        r: u32,
        mut k: i64,
        mut f: impl FnMut(u32, i64),
    ) -> Option<()> {
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
                _ if self.is_piece(c, r) => k = self.period.add_turn(k, self.turn_of(c, r))?,
                Some(Op::Turn(t)) => k = self.period.add_turn(k, i64::from(t))?,
                _ => {}
            }
        }
        Some(())
    }

    /// The piece `c` at remaining depth `r`, heading `k` and `flip`,
    /// starting at `at`, as [`Turtle::stand_in`] with a sample and [`Turtle::solid`] take it.
    fn sample<'a>(
        &self,
        (c, r, k, flip): (u32, u32, i64, bool),
        at: (f64, f64),
        p: &Piece,
        draw: &'a dyn Fn(f64, &mut dyn Turtle),
    ) -> Sample<'a> {
        let sg = if flip { -1.0 } else { 1.0 };
        Sample {
            at: Point::new(at.0, at.1),
            key: Sample::piece_key(c, r, self.period.key(k), flip),
            bounds: Sample::corners(
                Point::new(sg * p.min_x, sg * p.min_y),
                Point::new(sg * p.max_x, sg * p.max_y),
            ),
            segments: self.count[r as usize * self.alpha.chars.len() + c as usize],
            draw,
        }
    }

    /// Draws the word into `turtle` with a level of detail: a subtree whose
    /// box fits inside `detail` canvas units is one stand-in segment (its
    /// chord, or its box's diagonal when the chord is less than half the
    /// box), a subtree that draws nothing is its net move and turn; every
    /// other symbol is interpreted as [`Interp`](crate::turtle::Interp)
    /// does, with its expression, so where nothing is cut the segments are
    /// bit-identical to the exact drawing. Returns where the turtle ends.
    pub(crate) fn draw_lod<T: Turtle>(
        &self,
        detail: f64,
        turtle: T,
        progress: &mut dyn Progress,
    ) -> Point {
        self.draw_word(
            &self.alpha.axiom,
            self.depth,
            (0, false),
            detail,
            turtle,
            progress,
        )
    }

    /// [`Geometry::draw_lod`] of `word` at remaining depth `r`, starting
    /// at the origin with heading and flip `start`: the one walk
    /// ([`lod::walk`]) over this memo.
    fn draw_word<T: Turtle>(
        &self,
        word: &[u32],
        r: u32,
        start: (i64, bool),
        detail: f64,
        turtle: T,
        progress: &mut dyn Progress,
    ) -> Point {
        let mut w = Walk2 {
            g: self,
            detail,
            turtle,
            headings: self.headings.borrow().clone(),
            pen: Pen {
                x: 0.0,
                y: 0.0,
                k: start.0,
                flip: start.1,
            },
            stack: Vec::new(),
        };
        lod::walk(&mut w, word, r, (), progress);
        Point::new(w.pen.x, w.pen.y)
    }
}

/// A walk of the deterministic 2D memo at a detail: its turtle and pen.
struct Walk2<'m, T> {
    g: &'m Geometry,
    detail: f64,
    turtle: T,
    headings: Headings,
    pen: Pen,
    stack: Vec<Pen>,
}

impl<'m, T: Turtle> lod::Memo<'m> for Walk2<'m, T> {
    type Ctx = ();

    #[inline]
    fn child(_: (), _: usize) {}

    #[inline]
    fn is_piece(&self, c: u32, r: u32) -> bool {
        self.g.is_piece(c, r)
    }

    fn piece(&mut self, c: u32, r: u32, _: ()) -> Option<&'m [u32]> {
        let g = self.g;
        let detail = self.detail;
        let Pen { x, y, k, flip } = self.pen;
        let p = g.piece(c, r, k);
        let sg = if flip { -1.0 } else { 1.0 };
        let (lo, hi) = (
            Point::new(x + sg * p.min_x, y + sg * p.min_y),
            Point::new(x + sg * p.max_x, y + sg * p.max_y),
        );
        let at = r as usize * g.alpha.chars.len() + c as usize;
        let cut = g.cut(c, r, k, &p, detail);
        // A piece not cut whose reach is all full ink already (and big
        // enough to be worth asking about) is skipped.
        let big = !cut && g.count[at] >= PRUNE_SEGMENTS && p.draws();
        let full = big && self.turtle.covered(lo, hi);
        let (ex, ey) = (x + sg * p.dx, y + sg * p.dy);
        // Draws the piece itself, for a backend that samples it.
        let draw = |detail: f64, t: &mut dyn Turtle| {
            g.draw_word(&[c], r, (k, flip), detail, t, &mut NoProgress);
        };
        // A bush whose own strokes ink its footprint fully: drawn whole.
        let dense = big
            && !full
            && g.jumps[at] != 0
            && p.extent() < DENSE_MAX * detail
            && self
                .turtle
                .dense(&g.sample((c, r, k, flip), (x, y), &p, &draw));
        if !(cut || full || dense) {
            return Some(g.alpha.succ[c as usize].as_deref().unwrap_or(&[]));
        }
        let turtle = &mut self.turtle;
        if full || dense {
            // Its move and turn only, as a stand-in's.
        } else if g.solid(c, r, k, &p, detail) {
            if !turtle.solid(&g.sample((c, r, k, flip), (x, y), &p, &draw)) {
                let rows = solid::hatch_rows(&p, detail);
                hatch(turtle, x, y, sg, &p, rows);
            }
        } else if p.draws() {
            let part = Part2 {
                start: Point::new(x, y),
                end: Point::new(ex, ey),
                chord: libm::hypot(p.dx, p.dy),
                lo,
                hi,
                piece: p,
                segments: g.count[at] as f64,
                jumps: g.jumps[at] != 0,
                len: g.len,
            };
            match lod::stand_in_2d(&part) {
                Stand2::Run(seg, n) => turtle.run(seg, n),
                Stand2::Bush(seg, density, spread) => {
                    let sample = g.sample((c, r, k, flip), (x, y), &p, &draw);
                    turtle.stand_in(&StandIn {
                        seg,
                        density,
                        footprint: Some(Footprint {
                            spread,
                            runs: g.jumps[at] as f64,
                        }),
                        sample: Some(&sample),
                    });
                }
            }
        }
        self.pen = Pen {
            x: ex,
            y: ey,
            k: k.wrapping_add(g.turn_of(c, r)),
            flip: flip ^ g.flip_of(c, r),
        };
        None
    }

    #[inline]
    fn terminal(&mut self, c: u32) {
        let len = self.g.len;
        let pen = &mut self.pen;
        match self.g.ops[c as usize] {
            Some(Op::Draw) => {
                // Interp::forward: pos + dir * len.
                let (dx, dy) = self.headings.dir(pen.k, pen.flip);
                let to = Point::new(pen.x + dx * len, pen.y + dy * len);
                self.turtle.segment(Segment {
                    from: Point::new(pen.x, pen.y),
                    to,
                    order: 0,
                });
                (pen.x, pen.y) = (to.x, to.y);
            }
            Some(Op::Move) => {
                let (dx, dy) = self.headings.dir(pen.k, pen.flip);
                (pen.x, pen.y) = (pen.x + dx * len, pen.y + dy * len);
            }
            Some(Op::Turn(t)) => pen.k = pen.k.wrapping_add(i64::from(t)),
            Some(Op::Flip) => pen.flip = !pen.flip,
            Some(Op::Push) => self.stack.push(*pen),
            Some(Op::Pop) => {
                if let Some(s) = self.stack.pop() {
                    *pen = s;
                }
            }
            Some(Op::Enter | Op::Leave) | None => {}
        }
    }
}

#[cfg(test)]
mod tests {
    use super::super::super::Memo;
    use super::*;
    use crate::color::Rgb;
    use crate::limits::Limits;
    use crate::render::{Fit, LOD_PX, PngTurtle, Style, Width};

    /// Forwards everything, [`Turtle::covered`] too unless `blind`
    /// (then nothing is skipped), and counts the parts skipped.
    struct Watch<'a> {
        t: &'a mut PngTurtle,
        blind: bool,
        skipped: u64,
        /// Dense pieces drawn whole; `None`: none offered on.
        dense: Option<u64>,
        /// Solid pieces of over 2^16 segments: `Some` counts those the
        /// backend drew; `None` refuses them (they are hatched here).
        big_solids: Option<u64>,
    }

    impl Turtle for Watch<'_> {
        fn segment(&mut self, seg: Segment) {
            self.t.segment(seg);
        }
        fn detail(&self) -> Option<f64> {
            self.t.detail()
        }
        fn stand_in(&mut self, stand_in: &StandIn) {
            self.t.stand_in(stand_in);
        }
        fn solid(&mut self, sample: &Sample) -> bool {
            if sample.segments <= 1 << 16 {
                return self.t.solid(sample);
            }
            let Some(n) = self.big_solids.as_mut() else {
                return false;
            };
            let drawn = self.t.solid(sample);
            *n += u64::from(drawn);
            drawn
        }
        fn run(&mut self, seg: Segment, segments: f64) {
            self.t.run(seg, segments);
        }
        fn dense(&mut self, sample: &Sample) -> bool {
            let Some(n) = self.dense.as_mut() else {
                return false;
            };
            let drawn = self.t.dense(sample);
            *n += u64::from(drawn);
            drawn
        }
        fn covered(&mut self, lo: Point, hi: Point) -> bool {
            let full = !self.blind && self.t.covered(lo, hi);
            self.skipped += u64::from(full);
            full
        }
    }

    /// ABOP 1.24b's memo at `depth` and two banded 300 x 300 pictures of
    /// it at the level of detail, to draw two ways and compare.
    fn bush_1_24b(depth: u32) -> (Memo, PngTurtle, PngTurtle) {
        pair("axiom F\nrule F -> F[+F]F[-F][F]\nangle 20\n", depth)
    }

    /// The memo of `src` at `depth` and two banded 300 x 300 pictures of
    /// it at the level of detail.
    fn pair(src: &str, depth: u32) -> (Memo, PngTurtle, PngTurtle) {
        let sys = crate::syntax::lsys::parse(src, &Limits::DEFAULT).unwrap();
        let memo = Memo::new(&sys, depth).unwrap();
        let width = Width::Pixels(1.0);
        let fit = Fit::content(memo.measured().bbox, 0, &width, Some((300, 300))).unwrap();
        let style = Style {
            stroke: Rgb::BLACK,
            background: Some(Rgb::WHITE),
            width,
        };
        let turtle = || {
            PngTurtle::banded(fit, &style)
                .unwrap()
                .with_detail(Some(LOD_PX))
        };
        (memo, turtle(), turtle())
    }

    /// ABOP 1.24b, whose subtrees overlap many times over, at depth 10
    /// in 300 x 300: the walk skips parts of it whose reach is already
    /// full ink, and every pixel is what drawing them paints.
    #[test]
    fn skipping_what_is_full_ink_changes_no_pixel() {
        let (memo, mut a, mut b) = bush_1_24b(10);
        let detail = a.detail().unwrap();
        let mut skipping = Watch {
            t: &mut a,
            blind: false,
            skipped: 0,
            dense: Some(0),
            big_solids: Some(0),
        };
        memo.g.draw_lod(detail, &mut skipping, &mut NoProgress);
        let skipped = skipping.skipped;
        let mut blind = Watch {
            t: &mut b,
            blind: true,
            skipped: 0,
            dense: Some(0),
            big_solids: Some(0),
        };
        memo.g.draw_lod(detail, &mut blind, &mut NoProgress);
        assert_eq!(blind.skipped, 0);
        let (a, b) = (a.into_raster().unwrap(), b.into_raster().unwrap());
        assert!(skipped > 100, "{skipped} skipped");
        assert!(a.data() == b.data(), "the pixels differ");
    }

    /// ABOP 1.24b at depth 12 in 300 x 300: pieces whose own strokes ink
    /// their footprint fully are drawn whole, and the picture is within
    /// the level of detail's bars of the one walked piece by piece (mean
    /// difference under 2/255, inked pixels within 3 %).
    #[test]
    fn dense_bushes_drawn_whole_ink_what_walking_them_inks() {
        let (memo, mut a, mut b) = bush_1_24b(12);
        let detail = a.detail().unwrap();
        let mut whole = Watch {
            t: &mut a,
            blind: false,
            skipped: 0,
            dense: Some(0),
            big_solids: Some(0),
        };
        memo.g.draw_lod(detail, &mut whole, &mut NoProgress);
        let drawn = whole.dense.unwrap();
        let mut walked = Watch {
            t: &mut b,
            blind: false,
            skipped: 0,
            dense: None,
            big_solids: Some(0),
        };
        memo.g.draw_lod(detail, &mut walked, &mut NoProgress);
        assert!(drawn > 10, "{drawn} drawn whole");
        let (a, b) = (a.into_raster().unwrap(), b.into_raster().unwrap());
        let (mean, ia, ib) = differ(a.data(), b.data());
        assert!(mean < 2.0, "mean {mean} / 255");
        assert!(ib > 1000.0, "{ib} inked");
        assert!(
            (ia - ib).abs() <= 0.03 * ib,
            "inked {ia} whole, {ib} walked"
        );
    }

    /// The mean difference (/255, red channel) of two pictures and the
    /// pixels each inks (red under 128).
    fn differ(a: &[u8], b: &[u8]) -> (f64, f64, f64) {
        let diff: u64 = a
            .chunks(4)
            .zip(b.chunks(4))
            .map(|(x, y)| u64::from(x[0].abs_diff(y[0])))
            .sum();
        let inked = |p: &[u8]| p.chunks(4).filter(|c| c[0] < 128).count() as f64;
        (diff as f64 / (a.len() / 4) as f64, inked(a), inked(b))
    }

    /// Hilbert at depth 30 in 300 x 300: its solid pieces (2-16 px, far
    /// over 2^16 segments each) are stamped from their hatched box drawn
    /// once per distinct piece, not hatched one by one, and the picture
    /// is within the level of detail's bars of the hatched one (mean
    /// difference under 2/255, inked pixels within 3 %; measured: 1,024
    /// stamped, 1.66/255, the same 76,176 pixels inked: the hatches' dark
    /// tone, an eighth of a pixel off).
    #[test]
    fn big_solid_pieces_are_stamped_as_their_hatch_inks() {
        let src = "axiom L\nrule L -> +RF-LFL-FR+\nrule R -> -LF+RFR+FL-\nangle 90\n";
        let (memo, mut a, mut b) = pair(src, 30);
        let detail = a.detail().unwrap();
        let mut stamped = Watch {
            t: &mut a,
            blind: false,
            skipped: 0,
            dense: Some(0),
            big_solids: Some(0),
        };
        memo.g.draw_lod(detail, &mut stamped, &mut NoProgress);
        let drawn = stamped.big_solids.unwrap();
        let mut hatched = Watch {
            t: &mut b,
            blind: false,
            skipped: 0,
            dense: Some(0),
            big_solids: None,
        };
        memo.g.draw_lod(detail, &mut hatched, &mut NoProgress);
        // 300 px less the margins, in pieces of at most 16 px a side.
        assert!(drawn > 300, "{drawn} stamped");
        let (a, b) = (a.into_raster().unwrap(), b.into_raster().unwrap());
        let (mean, ia, ib) = differ(a.data(), b.data());
        assert!(ib > 50_000.0, "{ib} inked");
        assert!(mean < 2.0, "mean {mean} / 255");
        assert!(
            (ia - ib).abs() <= 0.03 * ib,
            "inked {ia} stamped, {ib} hatched"
        );
    }
}
