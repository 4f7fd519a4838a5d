//! The SVG writer's merging (every SVG but `--exact`'s): a run of
//! connected segments is written as few path commands as show the same
//! picture, so an SVG's size is bounded by the picture, not by the
//! drawing (docs/rendering.md, *SVG size*).
//!
//! Along a run, vertices are on the written grid (hundredths of a pixel)
//! and
//! - a vertex closer than [`SVG_FOLD_PX`] to the last one written is not
//!   written (only the run's exact end is), as the PNG backend folds;
//! - a vertex that continues the last written line in the same direction
//!   moves that line's end instead of adding a command (collinear runs);
//! - a line shorter than a cell ([`Cells`], one pixel at the default size)
//!   whose two ends lie in cells each already reached [`CELL_VISITS`]
//!   times by lines at least as wide is not written: the pen lifts, and
//!   the next line written starts with a move. Such a line lies within
//!   about a pixel of two line ends already written.
//!
//! A cell where four lines were left out is dense: at the end each row's runs
//! of dense cells are painted whole, as one line a cell wide with flat
//! ends (at most one line per two cells), so a crowded area is solid ink,
//! as the many overlapping lines left out would have made it.
//!
//! So a short line is written only when a cell at one of its ends takes
//! a visit, and every other line is at least a cell long: at most
//! `CELL_VISITS * cells` short lines per stroke width, a move at most
//! before each line, plus a line per drawn segment a cell long or longer,
//! which a deep drawing (whose segments shrink with depth at a fixed size)
//! does not have.

/// Folding tolerance of a merged SVG, in output pixels.
pub const SVG_FOLD_PX: f64 = 0.5;

/// Short lines that may end in one cell (per width) before the cell
/// counts as inked.
pub const CELL_VISITS: u8 = 2;

/// A cell's count once this many lines were left out in it (beyond its
/// [`CELL_VISITS`]): it is dense, and is painted whole at the end
/// ([`Cells::dense_runs`]).
const DENSE: u8 = CELL_VISITS + 4;

/// Most cells of the table: a picture of more pixels than this has cells
/// of several pixels (so the table stays within 32 MB).
const MAX_CELLS: u64 = 1 << 22;

/// A point on the written grid, in hundredths of a pixel.
pub(super) type Q = (i64, i64);

/// The grid point of `x`, `y` (output pixels).
pub(super) fn quantise(x: f64, y: f64) -> Q {
    ((x * 100.0).round() as i64, (y * 100.0).round() as i64)
}

/// How many short lines of what width have ended in each cell.
pub(super) struct Cells {
    /// Cell side in hundredths of a pixel.
    side: i64,
    columns: i64,
    rows: i64,
    /// Visits and the widest width that visited, per cell.
    cells: Vec<(u8, f32)>,
}

impl Cells {
    /// The cells of a `width` x `height` picture.
    pub(super) fn new(width: u32, height: u32) -> Cells {
        let pixels = u64::from(width) * u64::from(height);
        let mut side = 1u64;
        while pixels.div_ceil(side * side) > MAX_CELLS {
            side += 1;
        }
        let columns = u64::from(width).div_ceil(side) as i64;
        let rows = u64::from(height).div_ceil(side) as i64;
        Cells {
            side: side as i64 * 100,
            columns,
            rows,
            cells: vec![(0, 0.0); (columns * rows) as usize],
        }
    }

    /// The cell side in hundredths of a pixel.
    pub(super) fn side(&self) -> i64 {
        self.side
    }

    /// The runs of dense cells, row by row, left to right: `(row, first,
    /// last)` column, as the picture's grid points of their centre line's
    /// ends (hundredths of a pixel).
    pub(super) fn dense_runs(&self) -> Vec<(Q, Q)> {
        let mut runs = Vec::new();
        for r in 0..self.rows {
            let row = &self.cells[(r * self.columns) as usize..((r + 1) * self.columns) as usize];
            let y = r * self.side + self.side / 2;
            let mut c = 0;
            while c < self.columns {
                if row[c as usize].0 < DENSE {
                    c += 1;
                    continue;
                }
                let first = c;
                while c < self.columns && row[c as usize].0 >= DENSE {
                    c += 1;
                }
                runs.push(((first * self.side, y), (c * self.side, y)));
            }
        }
        runs
    }

    /// The cell of `q`, if inside the picture.
    fn index(&self, q: Q) -> Option<usize> {
        let (c, r) = (q.0.div_euclid(self.side), q.1.div_euclid(self.side));
        ((0..self.columns).contains(&c) && (0..self.rows).contains(&r))
            .then(|| (r * self.columns + c) as usize)
    }

    /// Whether the cell of `q` takes a visit of a short line `width` wide:
    /// it had fewer than [`CELL_VISITS`] at that width, or only thinner
    /// lines, or `q` is outside the picture (nothing to see or count).
    pub(super) fn takes(&self, q: Q, width: f32) -> bool {
        self.index(q)
            .is_none_or(|i| width > self.cells[i].1 || self.cells[i].0 < CELL_VISITS)
    }

    /// Counts a visit of a short line `width` wide ending at `q`, if its
    /// cell [`takes`](Cells::takes) it; returns whether it did.
    pub(super) fn visit(&mut self, q: Q, width: f32) -> bool {
        if !self.takes(q, width) {
            return false;
        }
        if let Some(i) = self.index(q) {
            let cell = &mut self.cells[i];
            *cell = if width > cell.1 {
                (1, width)
            } else {
                (cell.0 + 1, width)
            };
        }
        true
    }

    /// Counts a line left out at `q`, towards its cell being dense.
    pub(super) fn left_out(&mut self, q: Q) {
        if let Some(i) = self.index(q) {
            let cell = &mut self.cells[i];
            cell.0 = cell.0.saturating_add(1);
        }
    }
}

/// A run of connected segments being written.
#[derive(Debug, Clone, Copy)]
pub(super) struct Run {
    /// The last vertex written (or skipped in an inked cell).
    pub kept: Q,
    /// Where the pen is: the end of the last segment.
    pub at: Q,
    /// `at` is not written yet (closer than [`SVG_FOLD_PX`] to `kept`).
    pub pending: bool,
    /// The batch's last subpath ends at `kept`: a line may follow it.
    pub open: bool,
    /// The last line command of that subpath: its offset in the batch and
    /// where it starts.
    pub last_line: Option<(usize, Q)>,
}

impl Run {
    /// A run starting at `q`, nothing written yet.
    pub(super) fn at(q: Q) -> Run {
        Run {
            kept: q,
            at: q,
            pending: false,
            open: false,
            last_line: None,
        }
    }
}

/// The squared distance of two grid points, in hundredths squared.
pub(super) fn distance2(a: Q, b: Q) -> i128 {
    let (dx, dy) = (
        i128::from(b.0) - i128::from(a.0),
        i128::from(b.1) - i128::from(a.1),
    );
    dx * dx + dy * dy
}

/// Whether `b` -> `c` continues `a` -> `b` in the same direction.
pub(super) fn continues(a: Q, b: Q, c: Q) -> bool {
    let d1 = (
        i128::from(b.0) - i128::from(a.0),
        i128::from(b.1) - i128::from(a.1),
    );
    let d2 = (
        i128::from(c.0) - i128::from(b.0),
        i128::from(c.1) - i128::from(b.1),
    );
    d1.0 * d2.1 == d1.1 * d2.0 && d1.0 * d2.0 + d1.1 * d2.1 > 0
}

/// Appends ` Cx y` for a grid point: exactly two decimals, never `-0.00`.
pub(super) fn push_q(buf: &mut String, command: char, q: Q) {
    buf.push(' ');
    buf.push(command);
    push_hundredths(buf, q.0);
    buf.push(' ');
    push_hundredths(buf, q.1);
}

fn push_hundredths(buf: &mut String, v: i64) {
    use std::fmt::Write as _;
    if v < 0 {
        buf.push('-');
    }
    let a = v.unsigned_abs();
    let _ = write!(buf, "{}.{:02}", a / 100, a % 100);
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn grid_points_are_written_with_two_decimals() {
        let mut s = String::new();
        push_q(&mut s, 'L', quantise(12.345_6, -0.004));
        push_q(&mut s, 'M', quantise(-3.5, 0.0));
        push_q(&mut s, 'L', quantise(-0.06, 100.0));
        assert_eq!(s, " L12.35 0.00 M-3.50 0.00 L-0.06 100.00");
    }

    #[test]
    fn a_cell_takes_its_visits_then_only_wider_lines() {
        let mut c = Cells::new(10, 10);
        let q = quantise(3.2, 4.7);
        assert!(c.visit(q, 1.0));
        assert!(c.visit(quantise(3.9, 4.1), 1.0), "same cell, second visit");
        assert!(!c.visit(q, 1.0), "full");
        assert!(!c.visit(q, 0.5), "thinner: under the ink already there");
        assert!(c.visit(q, 2.0), "wider: drawn, and the cell counts anew");
        assert!(c.visit(quantise(4.0, 4.7), 1.0), "the next cell");
        assert!(c.visit(quantise(-5.0, 4.7), 1.0), "outside: always");
        assert_eq!(c.dense_runs(), []);
        // Cells (5, 4) and (6, 4): two visits, then four lines left out
        // make a cell dense; (7, 4) has three left out.
        for (x, out) in [(5.5, 4), (6.5, 4), (7.5, 3)] {
            let q = quantise(x, 4.5);
            assert!(c.visit(q, 1.0) && c.visit(q, 1.0));
            assert!(!c.visit(q, 1.0), "full: no visit");
            for _ in 0..out {
                c.left_out(q);
            }
        }
        assert_eq!(c.dense_runs(), [((500, 450), (700, 450))]);
        assert!(c.visit(q, 2.0), "second visit at 2.0");
        assert!(!c.visit(q, 2.0));
    }

    #[test]
    fn continuing_is_collinear_and_onwards() {
        assert!(continues((0, 0), (100, 50), (300, 150)));
        assert!(!continues((0, 0), (100, 50), (300, 151)), "a bend");
        assert!(!continues((0, 0), (100, 50), (0, 0)), "back");
        assert!(!continues((0, 0), (0, 0), (5, 5)), "no direction");
        assert_eq!(distance2((0, 0), (30, 40)), 2500);
    }

    #[test]
    fn big_pictures_have_cells_of_several_pixels() {
        assert_eq!(Cells::new(800, 800).side(), 100);
        assert_eq!(Cells::new(2048, 2048).side(), 100);
        assert_eq!(Cells::new(4096, 4096).side(), 200);
        assert!(Cells::new(16_384, 16_384).cells.len() as u64 <= MAX_CELLS);
    }
}
