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
use super::field::reach_px;
use crate::turtle::Point;

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
        let reach = reach_px(self.width, self.fit.scale);
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
