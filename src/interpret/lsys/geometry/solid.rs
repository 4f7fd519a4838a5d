//! Solid pieces: subtrees whose strokes cover their whole box, drawn as
//! one hatched box instead of being expanded (a space-filling curve past
//! the pixel, a dense bush).
//!
//! Whether a piece is solid depends on the stroke, which is at least a
//! hairline: [`crate::render::HAIRLINE`], half a pixel, which is the level
//! of detail itself. So the test asks whether every point of the piece's
//! box, widened by `delta` = half the detail on every side, is within
//! `delta` of a drawn segment: then every point of the box widened by
//! half the real stroke is within half the stroke of a segment (triangle
//! inequality), and the exact drawing inks the whole widened box, which is
//! what a hatched box stroked with the same width inks.
//!
//! The test is a coverage mask per `(symbol, depth, heading)`: the widened
//! box as 8 x 8 cells, a cell covered when 3 x 3 sample points in it are
//! each within `delta` of a segment of the piece's successor or in a
//! covered cell of one of its child pieces (whose masks are computed the
//! same way, down to pieces much smaller than `delta`, where a sample is
//! covered when it is within `delta` of every point of one side of the
//! piece's box: each side of a drawing's box touches the drawing). Sampling can miss
//! a hole narrower than a third of a cell (a few hundredths of the box);
//! the corner cells may stay uncovered (strokes have round ends). Masks
//! are computed on demand, only for pieces between the detail and
//! [`SOLID_MAX`] times it, and kept for the render.

use super::*;

/// Largest solid stand-in, in details (16 px at the default half pixel):
/// bigger boxes mean fewer stand-ins, smaller ones keep a sampling error
/// local.
pub const SOLID_MAX: f64 = 32.0;

/// Smallest solid stand-in, in details (2 px): below, an ordinary
/// stand-in is as cheap and keeps a curve a line.
pub const SOLID_MIN: f64 = 4.0;

/// Cells per side of a coverage mask.
const CELLS: usize = 8;

/// The corner cells, which a solid piece may leave uncovered.
const CORNERS: u64 =
    1 | (1 << (CELLS - 1)) | (1 << (CELLS * (CELLS - 1))) | (1 << (CELLS * CELLS - 1));

/// Coverage masks by `(symbol, depth, heading key)`, for one `delta`.
#[derive(Default)]
pub(crate) struct Masks {
    delta: f64,
    masks: HashMap<(u32, u32, i64), u64>,
}

/// A child of a successor, placed: a segment, or a piece at a pen.
enum Child {
    Segment(f64, f64, f64, f64),
    Piece {
        c: u32,
        k: i64,
        x: f64,
        y: f64,
        sg: f64,
        p: Piece,
    },
}

/// Distance from `(px, py)` to the segment `(ax, ay)`-`(bx, by)`, squared.
fn dist2(px: f64, py: f64, ax: f64, ay: f64, bx: f64, by: f64) -> f64 {
    let (dx, dy) = (bx - ax, by - ay);
    let l2 = dx * dx + dy * dy;
    let t = if l2 > 0.0 {
        (((px - ax) * dx + (py - ay) * dy) / l2).clamp(0.0, 1.0)
    } else {
        0.0
    };
    let (qx, qy) = (ax + t * dx - px, ay + t * dy - py);
    qx * qx + qy * qy
}

/// The cell of `(x, y)` in the box of `p` widened by `d`, if inside.
fn cell_of(x: f64, y: f64, p: &Piece, d: f64) -> Option<usize> {
    let (w, h) = (p.max_x - p.min_x + 2.0 * d, p.max_y - p.min_y + 2.0 * d);
    let (u, v) = ((x - p.min_x + d) / w, (y - p.min_y + d) / h);
    if !(0.0..1.0).contains(&u) || !(0.0..1.0).contains(&v) {
        return None;
    }
    let n = CELLS as f64;
    Some(
        (libm::floor(v * n) as usize).min(CELLS - 1) * CELLS
            + (libm::floor(u * n) as usize).min(CELLS - 1),
    )
}

impl Geometry {
    /// Whether piece `(c, r)` at heading `k`, of box `p`, is solid at
    /// `detail` (see the module documentation): it draws, its box is
    /// between [`SOLID_MIN`] and [`SOLID_MAX`] details and at least two
    /// thick (a thinner one is as well drawn by its chord), and its mask
    /// is covered.
    pub(super) fn solid(&self, c: u32, r: u32, k: i64, p: &Piece, detail: f64) -> bool {
        let e = p.extent();
        let thin = (p.max_x - p.min_x).min(p.max_y - p.min_y) < 2.0 * detail;
        if !p.draws()
            || detail.partial_cmp(&0.0) != Some(std::cmp::Ordering::Greater)
            || thin
            || e < SOLID_MIN * detail
            || e >= SOLID_MAX * detail
        {
            return false;
        }
        let mut masks = self.masks.borrow_mut();
        if masks.delta != detail / 2.0 {
            *masks = Masks {
                delta: detail / 2.0,
                masks: HashMap::default(),
            };
        }
        self.mask(&mut masks, c, r, k) | CORNERS == u64::MAX
    }

    /// The coverage mask of piece `(c, r)` at heading `k`.
    fn mask(&self, masks: &mut Masks, c: u32, r: u32, k: i64) -> u64 {
        let key = (c, r, self.period.key(k));
        if let Some(&m) = masks.masks.get(&key) {
            return m;
        }
        let d = masks.delta;
        let p = self.piece(c, r, k);
        let m = if p.draws() {
            // A piece much smaller than `d` covers a sample when every
            // point of its box (where it draws) is within `d` of it; a
            // larger one through its successor's segments and pieces.
            let tiny = p.extent() < d / 4.0;
            let children = if tiny {
                Vec::new()
            } else {
                self.children(c, r, k)
            };
            let child_masks: Vec<u64> = children
                .iter()
                .map(|ch| match ch {
                    Child::Piece { c, k, .. } => self.mask(masks, *c, r - 1, *k),
                    Child::Segment(..) => 0,
                })
                .collect();
            let covered = |x: f64, y: f64| {
                if tiny {
                    // Each side of the box touches the drawing somewhere:
                    // covered if some side is within `d` all along.
                    let (ax, bx) = ((x - p.min_x).abs(), (x - p.max_x).abs());
                    let (ay, by) = ((y - p.min_y).abs(), (y - p.max_y).abs());
                    let (fx, fy) = (ax.max(bx), ay.max(by));
                    let side = (ax.min(bx).powi(2) + fy * fy).min(fx * fx + ay.min(by).powi(2));
                    return side <= d * d;
                }
                children.iter().zip(&child_masks).any(|(ch, &m)| match ch {
                    Child::Segment(ax, ay, bx, by) => dist2(x, y, *ax, *ay, *bx, *by) <= d * d,
                    Child::Piece {
                        x: px,
                        y: py,
                        sg,
                        p: q,
                        ..
                    } => {
                        let (lx, ly) = ((x - px) * sg, (y - py) * sg);
                        cell_of(lx, ly, q, d / 2.0).is_some_and(|i| m >> i & 1 == 1)
                    }
                })
            };
            let (x0, y0) = (p.min_x - d / 2.0, p.min_y - d / 2.0);
            let cw = (p.max_x - p.min_x + d) / CELLS as f64;
            let ch = (p.max_y - p.min_y + d) / CELLS as f64;
            let mut m = 0u64;
            for i in 0..CELLS * CELLS {
                let (cx, cy) = ((i % CELLS) as f64, (i / CELLS) as f64);
                let all = (0..9).all(|s| {
                    let (a, b) = ((s % 3) as f64, (s / 3) as f64);
                    covered(
                        x0 + (cx + (a + 0.5) / 3.0) * cw,
                        y0 + (cy + (b + 0.5) / 3.0) * ch,
                    )
                });
                if all {
                    m |= 1 << i;
                }
            }
            m
        } else {
            0
        };
        masks.masks.insert(key, m);
        m
    }

    /// The successor of `(c, r)` at heading `k` from the origin, as placed
    /// segments and child pieces.
    fn children(&self, c: u32, r: u32, k: i64) -> Vec<Child> {
        let succ = self.alpha.succ[c as usize].as_deref().unwrap_or(&[]);
        let mut pen = Pen {
            x: 0.0,
            y: 0.0,
            k,
            flip: false,
        };
        let mut out = Vec::new();
        let mut stack: Vec<Pen> = Vec::new();
        let r = r - 1;
        for &s in succ {
            match self.ops[s as usize] {
                Some(Op::Push) => stack.push(pen),
                Some(Op::Pop) => {
                    if let Some(saved) = stack.pop() {
                        pen = saved;
                    }
                }
                _ if self.is_piece(s, r) => {
                    let p = self.piece(s, r, pen.k);
                    let sg = if pen.flip { -1.0 } else { 1.0 };
                    if p.draws() {
                        out.push(Child::Piece {
                            c: s,
                            k: pen.k,
                            x: pen.x,
                            y: pen.y,
                            sg,
                            p,
                        });
                    }
                    pen.x += sg * p.dx;
                    pen.y += sg * p.dy;
                    pen.k = self
                        .period
                        .add_turn(pen.k, self.turn_of(s, r))
                        .unwrap_or(pen.k);
                    pen.flip ^= self.flip_of(s, r);
                }
                Some(Op::Draw) => {
                    let (dx, dy) = self.headings.borrow_mut().dir(pen.k, pen.flip);
                    let (x, y) = (pen.x + dx * self.len, pen.y + dy * self.len);
                    out.push(Child::Segment(pen.x, pen.y, x, y));
                    (pen.x, pen.y) = (x, y);
                }
                Some(Op::Move) => {
                    let (dx, dy) = self.headings.borrow_mut().dir(pen.k, pen.flip);
                    pen.x += dx * self.len;
                    pen.y += dy * self.len;
                }
                Some(Op::Turn(t)) => {
                    pen.k = self.period.add_turn(pen.k, i64::from(t)).unwrap_or(pen.k)
                }
                Some(Op::Flip) => pen.flip = !pen.flip,
                _ => {}
            }
        }
        out
    }
}

/// Rows of a hatched box of piece `p` at `detail`: one detail apart (a
/// hairline's width), so any stroke covers the box. (Rows spaced like a
/// curve's own lines, to shade as the exact drawing does, were tried:
/// darker differences and seven times the time; docs/rendering.md.)
pub(super) fn hatch_rows(p: &Piece, detail: f64) -> u64 {
    let rows = libm::ceil((p.max_y - p.min_y) / detail);
    if rows.is_finite() { rows as u64 } else { 1 }.max(1) + 1
}
