//! A stroke drawn again that cannot change a pixel (issue 37, item 2): a
//! path stroked onto a raster is a function of the path, the width and
//! the raster. When a stroke left its raster as it was, and nothing has
//! changed the raster since, the same stroke again leaves it as it is:
//! it is skipped. 2 million `F+` draw one square over and over, in
//! batches that are all the same path; once its pixels have taken all
//! the ink they will take, every later batch is a repeat that changed
//! nothing, and costs its walk and this comparison, not its pixels.
//!
//! Kept per raster a stroke paints (the whole picture, or each band, on
//! whichever thread paints it), so it holds on every path: `--exact`,
//! bands, threads. The pixels are the same by construction: nothing is
//! skipped that was not seen to change nothing on this very raster.

use tiny_skia::{LineCap, LineJoin, Paint, Path, PixmapMut, Stroke, Transform};

/// Strokes remembered: those drawn last (a drawing that repeats with a
/// period of a few batches), and those seen to change nothing.
const KEPT: usize = 4;

/// Rows a stroke may reach past its path's bounds: half its width,
/// anti-aliasing and a hairline's cap, with room to spare.
const REACH_ROWS: f32 = 3.0;

#[cfg(test)]
thread_local! {
    /// Tests draw every stroke to compare bytes.
    pub(super) static DRAW_ALL: std::cell::Cell<bool> = const { std::cell::Cell::new(false) };
}

/// What a raster (or a band of it) has been stroked with lately.
#[derive(Default)]
pub(super) struct Repeats {
    /// The last strokes drawn (width, path), oldest overwritten first.
    drawn: Vec<(f32, Path)>,
    next: usize,
    /// Strokes seen to change nothing since the raster last changed.
    still: Vec<(f32, Path)>,
    /// Strokes skipped (tests count them).
    pub(super) skipped: u64,
}

fn same(a: &(f32, Path), width: f32, path: &Path) -> bool {
    a.0 == width && a.1.points() == path.points() && a.1.verbs() == path.verbs()
}

impl Repeats {
    /// Something else painted the raster: what changed nothing before
    /// may change it now.
    pub(super) fn changed(&mut self) {
        self.still.clear();
    }

    /// Strokes `path` `width` pixels wide (round caps and joins) onto
    /// `pixmap` in `paint`, unless it is a stroke seen to change nothing
    /// on this raster as it is.
    pub(super) fn stroke(
        &mut self,
        pixmap: &mut PixmapMut<'_>,
        path: &Path,
        width: f32,
        paint: &Paint<'_>,
    ) {
        #[cfg(test)]
        let skips = !DRAW_ALL.with(std::cell::Cell::get);
        #[cfg(not(test))]
        let skips = true;
        if skips && self.still.iter().any(|s| same(s, width, path)) {
            self.skipped += 1;
            return;
        }
        let stroke = Stroke {
            width,
            line_cap: LineCap::Round,
            line_join: LineJoin::Round,
            ..Stroke::default()
        };
        let again = self.drawn.iter().any(|s| same(s, width, path));
        if !again {
            pixmap.stroke_path(path, paint, &stroke, Transform::identity(), None);
            self.still.clear();
            self.remember(width, path);
            return;
        }
        // Drawn lately: watch whether it changes anything this time.
        let b = path.bounds();
        let reach = width / 2.0 + REACH_ROWS;
        let row_bytes = pixmap.width() as usize * 4;
        let h = pixmap.height() as f32;
        let top = (b.top() - reach).floor().clamp(0.0, h) as usize;
        let bottom = (b.bottom() + reach).ceil().clamp(0.0, h) as usize;
        let before = pixmap.data_mut()[top * row_bytes..bottom * row_bytes].to_vec();
        pixmap.stroke_path(path, paint, &stroke, Transform::identity(), None);
        if pixmap.data_mut()[top * row_bytes..bottom * row_bytes] == before[..] {
            if self.still.len() >= KEPT {
                self.still.remove(0);
            }
            self.still.push((width, path.clone()));
        } else {
            self.still.clear();
        }
    }

    fn remember(&mut self, width: f32, path: &Path) {
        if self.drawn.len() < KEPT {
            self.drawn.push((width, path.clone()));
        } else {
            self.drawn[self.next] = (width, path.clone());
            self.next = (self.next + 1) % KEPT;
        }
    }
}

#[cfg(test)]
#[path = "repeat_tests.rs"]
mod tests;
