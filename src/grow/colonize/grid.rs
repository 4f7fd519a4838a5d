//! A uniform grid over the attraction points' box, cells as wide as the
//! reach (or wider, so that there are at most [`MAX_CELLS`]): the points
//! in cells fixed once (sorted by cell), the waiting growth points in a
//! list per cell. A query visits the cells a box meets; positions outside
//! the box fall into its border cells (clamping keeps every answer: a
//! point within the query's distance lies in a visited cell). Answers are
//! sets, filtered by exact distance by the caller.

/// At most this many cells.
const MAX_CELLS: usize = 1 << 22;

/// The grid's shape.
#[derive(Debug)]
pub(super) struct Grid<const N: usize> {
    lo: [f64; N],
    cell: f64,
    dims: [usize; N],
}

impl<const N: usize> Grid<N> {
    /// A grid over `pts` with cells at least `reach` wide.
    pub(super) fn new(pts: &[[f64; N]], reach: f64) -> Self {
        let mut lo = [f64::INFINITY; N];
        let mut hi = [f64::NEG_INFINITY; N];
        for p in pts {
            for i in 0..N {
                lo[i] = lo[i].min(p[i]);
                hi[i] = hi[i].max(p[i]);
            }
        }
        let mut cell = if reach > 0.0 && reach.is_finite() {
            reach
        } else {
            1.0
        };
        loop {
            let dims: [usize; N] =
                std::array::from_fn(|i| (((hi[i] - lo[i]) / cell) as usize).saturating_add(1));
            let total = dims.iter().try_fold(1usize, |a, &d| a.checked_mul(d));
            if total.is_some_and(|t| t <= MAX_CELLS) {
                return Grid { lo, cell, dims };
            }
            cell *= 2.0;
        }
    }

    /// The number of cells.
    pub(super) fn cells(&self) -> usize {
        self.dims.iter().product()
    }

    /// The cell index along axis `i` of coordinate `x`, clamped.
    fn axis(&self, i: usize, x: f64) -> usize {
        let k = (x - self.lo[i]) / self.cell;
        // Truncation is the floor for k > 0 (no call to `floor` in the
        // hot loop); below and NaN: the first cell.
        if k > 0.0 {
            (k as usize).min(self.dims[i] - 1)
        } else {
            0
        }
    }

    /// The cell of `p`.
    pub(super) fn cell_of(&self, p: [f64; N]) -> usize {
        (0..N)
            .rev()
            .fold(0, |a, i| a * self.dims[i] + self.axis(i, p[i]))
    }

    /// Calls `f` with every cell the box `lo`..`hi` meets.
    pub(super) fn each_cell(&self, lo: [f64; N], hi: [f64; N], mut f: impl FnMut(usize)) {
        let a: [usize; N] = std::array::from_fn(|i| self.axis(i, lo[i]));
        let b: [usize; N] = std::array::from_fn(|i| self.axis(i, hi[i]));
        let mut k = a;
        loop {
            f((0..N).rev().fold(0, |acc, i| acc * self.dims[i] + k[i]));
            let mut i = 0;
            loop {
                if i == N {
                    return;
                }
                if k[i] < b[i] {
                    k[i] += 1;
                    break;
                }
                k[i] = a[i];
                i += 1;
            }
        }
    }

    /// Calls `f` with every cell within `r` of `p` (its box).
    pub(super) fn near(&self, p: [f64; N], r: f64, f: impl FnMut(usize)) {
        self.each_cell(
            std::array::from_fn(|i| p[i] - r),
            std::array::from_fn(|i| p[i] + r),
            f,
        );
    }
}

/// Points fixed in their cells, numbered by cell: points
/// `start[c]..start[c + 1]` lie in cell `c`.
#[derive(Debug)]
pub(super) struct Fixed {
    start: Vec<u32>,
}

impl Fixed {
    /// `pts` sorted by their cells of `grid` (stably: a counting sort, one
    /// `cell_of` per point), and the cells.
    pub(super) fn sort<const N: usize>(grid: &Grid<N>, pts: &[[f64; N]]) -> (Self, Vec<[f64; N]>) {
        let cells: Vec<u32> = pts.iter().map(|&p| grid.cell_of(p) as u32).collect();
        let mut start = vec![0u32; grid.cells() + 1];
        for &c in &cells {
            start[c as usize + 1] += 1;
        }
        for c in 0..grid.cells() {
            start[c + 1] += start[c];
        }
        let mut next = start.clone();
        let mut sorted = vec![[0.0; N]; pts.len()];
        for (p, &c) in pts.iter().zip(&cells) {
            sorted[next[c as usize] as usize] = *p;
            next[c as usize] += 1;
        }
        (Fixed { start }, sorted)
    }

    /// The points in cell `c`.
    pub(super) fn in_cell(&self, c: usize) -> std::ops::Range<u32> {
        self.start[c]..self.start[c + 1]
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_cells_near_a_point_hold_every_point_within_reach() {
        // A 10 x 10 block of points 1 apart; reach 2.5.
        let pts: Vec<[f64; 2]> = (0..100)
            .map(|i| [f64::from(i % 10), f64::from(i / 10)])
            .collect();
        let grid = Grid::new(&pts, 2.5);
        let (fixed, sorted) = Fixed::sort(&grid, &pts);
        // Sorted by cell, stably: the order `sort_by_key` gives.
        let mut by_key = pts.clone();
        by_key.sort_by_key(|&p| grid.cell_of(p));
        assert_eq!(sorted, by_key);
        for q in [[0.0, 0.0], [4.5, 7.2], [12.0, -3.0], [9.0, 9.0]] {
            let mut found = Vec::new();
            grid.near(q, 2.5, |c| found.extend(fixed.in_cell(c)));
            let by_hand: Vec<u32> = (0..100u32)
                .filter(|&i| {
                    let p = sorted[i as usize];
                    (p[0] - q[0]).powi(2) + (p[1] - q[1]).powi(2) <= 6.25
                })
                .collect();
            assert!(by_hand.iter().all(|i| found.contains(i)), "{q:?}");
        }
    }
}
