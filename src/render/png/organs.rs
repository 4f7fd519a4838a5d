//! Colours and polygons on the raster (a `.lsys` palette and `{ }`,
//! docs/lsys.md, *Colours, widths and organs*), and the fills they share
//! with the layout's underlay.

use tiny_skia::{FillRule, Paint, PathBuilder, Transform};

use super::PngTurtle;
use super::bands::{Canvas, Op, color};
use super::raster::Recent;
use super::repeat::Repeats;
use super::tiles::Full;
use crate::color::Rgb;
use crate::turtle::Point;

impl PngTurtle {
    /// Fills closed `rings` (canvas units) in `rgb` with `rule`, over
    /// what is drawn so far.
    pub(super) fn fill_rings(&mut self, rings: &[Vec<Point>], rgb: Rgb, rule: FillRule) {
        self.flush();
        let mut pb = PathBuilder::new();
        for ring in rings {
            let mut points = ring.iter().map(|&p| self.fit.map(p));
            if let Some(first) = points.next() {
                pb.move_to(first.x as f32, first.y as f32);
                for p in points {
                    pb.line_to(p.x as f32, p.y as f32);
                }
                pb.close();
            }
        }
        let Some(path) = pb.finish() else {
            return;
        };
        match &mut self.canvas {
            Canvas::Whole(pixmap) => {
                self.repeats.iter_mut().for_each(Repeats::changed);
                let mut paint = Paint::default();
                paint.set_color(color(rgb));
                paint.anti_alias = true;
                pixmap.fill_path(&path, &paint, rule, Transform::identity(), None);
            }
            canvas => canvas.send(
                Op::Fill {
                    path: std::sync::Arc::new(path),
                    color: color(rgb),
                    rule,
                },
                &self.ink,
                &mut self.repeats,
            ),
        }
    }

    /// Strokes, blots and polygons in `rgb` from now on ([`crate::turtle::Turtle::paint`]).
    pub(super) fn repaint(&mut self, rgb: Rgb) {
        if rgb == self.ink.rgb {
            return;
        }
        self.flush();
        self.ink.set(rgb);
        // What was full of the old colour is not of the new one.
        self.covered = false;
        self.full = Full::new();
        self.recent = Recent::new();
        if let Canvas::Sent(_) = self.canvas {
            self.canvas
                .send(Op::Paint(rgb), &self.ink, &mut self.repeats);
        } else {
            // What changed nothing in the old paint may change it now.
            self.repeats.iter_mut().for_each(Repeats::changed);
        }
    }

    /// Fills a polygon in the ink, non-zero ([`crate::turtle::Turtle::polygon`]).
    pub(super) fn fill_polygon(&mut self, points: &[Point]) {
        if self.covered || points.len() < 3 {
            return;
        }
        let rings = [points.to_vec()];
        self.fill_rings(&rings, self.ink.rgb, FillRule::Winding);
    }
}
