//! What is already full ink
//! ([`Turtle::covered`](crate::turtle::Turtle::covered)): a drawing that
//! only adds the stroke colour source-over cannot change a pixel that is
//! that colour, opaque, so the level-of-detail walk may skip a part of
//! the drawing whose whole reach is such pixels: the same pixels, less
//! work where subtrees overlap many times over (ABOP 1.24b). Tiles of
//! 8 x 8 pixels found full are remembered: ink only grows, so a full
//! tile stays full.

use super::PngTurtle;
use super::bands::Canvas;
use crate::turtle::Point;

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

impl PngTurtle {
    /// [`Turtle::covered`](crate::turtle::Turtle::covered): whether the
    /// pixels within the strokes' reach of the canvas box `lo`-`hi` are all
    /// the opaque stroke colour.
    pub(super) fn full_ink(&mut self, lo: Point, hi: Point) -> bool {
        if self.covered {
            return true;
        }
        let pixmap = match &self.canvas {
            Canvas::Whole(p) | Canvas::Bands(p) => p,
            Canvas::Sent(_) => return false,
        };
        let (w, h) = (f64::from(pixmap.width()), f64::from(pixmap.height()));
        let (a, b) = (self.fit.map(lo), self.fit.map(hi));
        let reach = super::sample::reach_px(self.width, self.fit.scale);
        let (x0, x1) = (a.x.min(b.x) - reach, a.x.max(b.x) + reach);
        let (y0, y1) = (a.y.min(b.y) - reach, a.y.max(b.y) + reach);
        if !([x0, x1, y0, y1].iter().all(|v| v.is_finite())) {
            return false;
        }
        if x1 < 0.0 || y1 < 0.0 || x0 >= w || y0 >= h {
            // Wholly outside the picture: nothing shows.
            return true;
        }
        let clamp = |v: f64, n: f64| libm::floor(v.clamp(0.0, n - 1.0)) as usize;
        let (xs, ys) = ((clamp(x0, w), clamp(x1, w)), (clamp(y0, h), clamp(y1, h)));
        let c = self.ink.rgb;
        let raster = (
            pixmap.data(),
            pixmap.width() as usize,
            pixmap.height() as usize,
        );
        self.full.covered(raster, [c.r, c.g, c.b, 255], xs, ys)
    }
}
