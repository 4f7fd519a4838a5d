//! The tiles of a raster found full ink ([`full`](super::full)): ink only
//! grows, so a tile found full stays full and is not read again.

/// Side of a tile, pixels.
const TILE: usize = 8;

/// The tiles of a raster found full so far.
pub(super) struct Full {
    tiles: Vec<bool>,
    across: usize,
}

impl Full {
    pub(super) fn new() -> Full {
        Full {
            tiles: Vec::new(),
            across: 0,
        }
    }

    /// Whether every pixel of columns `xs` and rows `ys` (inclusive, within
    /// the raster) of `data` (`width` x `height`, RGBA) is `ink`.
    pub(super) fn covered(
        &mut self,
        (data, width, height): (&[u8], usize, usize),
        ink: [u8; 4],
        xs: (usize, usize),
        ys: (usize, usize),
    ) -> bool {
        if self.tiles.is_empty() {
            self.across = width.div_ceil(TILE);
            self.tiles = vec![false; self.across * height.div_ceil(TILE)];
        }
        let full = |x0: usize, x1: usize, y0: usize, y1: usize| {
            (y0..=y1).all(|y| {
                let row = &data[(y * width + x0) * 4..(y * width + x1 + 1) * 4];
                row.chunks_exact(4).all(|p| p == ink)
            })
        };
        for ty in ys.0 / TILE..=ys.1 / TILE {
            for tx in xs.0 / TILE..=xs.1 / TILE {
                let t = ty * self.across + tx;
                if self.tiles[t] {
                    continue;
                }
                let (x0, y0) = (tx * TILE, ty * TILE);
                let (x1, y1) = ((x0 + TILE).min(width) - 1, (y0 + TILE).min(height) - 1);
                if full(x0, x1, y0, y1) {
                    self.tiles[t] = true;
                    continue;
                }
                // Not all of the tile: perhaps the part of it asked about.
                if !full(x0.max(xs.0), x1.min(xs.1), y0.max(ys.0), y1.min(ys.1)) {
                    return false;
                }
            }
        }
        true
    }
}
