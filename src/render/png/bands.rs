//! Drawing in horizontal bands, on one thread or several.
//!
//! A big picture ([`super::super::BANDED_SEGMENTS`] segments or more) is
//! painted as bands of [`BAND_ROWS`] rows, each band drawing every batch
//! of the stream, in order, clipped to its rows: the producer (the
//! interpreter feeding [`super::PngTurtle`]) maps, folds and batches the
//! segments once, and hands each finished batch ([`Op`]) to every band. A
//! band keeps only the subpaths that reach its rows and strokes them into
//! its own rows of the raster, shifted up by its first row.
//!
//! The bands are a function of the picture (its height), never of the
//! number of threads: with one thread the bands are painted one after the
//! other, with N each thread paints every Nth band, and since a band's
//! pixels depend only on the batches and on the band, the bytes are the
//! same. (They are not the bytes of one unbanded raster: tiny-skia chops
//! a line that leaves its clip and steps the chopped line anew, so a line
//! crossing a band's edge is anti-aliased a little differently; that is
//! why only big pictures are banded.)
//!
//! Threads come from `std::thread::scope` and are asked for only with more
//! than one thread, so one thread (the web build's only choice) never
//! spawns.

use std::ops::Range;
use std::sync::Arc;
use std::sync::mpsc::{Receiver, SyncSender, sync_channel};

use tiny_skia::{Color, FillRule, Paint, Path, PathBuilder, Pixmap, PixmapMut, Transform};

use super::raster::{self, Blot};
use super::repeat::Repeats;
use crate::color::Rgb;

/// Rows of one band (the last band of a picture may have fewer). Small
/// bands spread uneven drawings evenly over the threads (band `i` goes to
/// thread `i % N`); a subpath near an edge is drawn by both bands, so each
/// band costs a little more than its share.
pub const BAND_ROWS: u32 = 64;

/// Batches a thread may have queued before the producer waits for it.
/// Deep enough that the producer, which shares the cores with the band
/// threads, never waits on a band that a burst of batches reaches: on two
/// cores abop-1.24a `--exact` at depth 11, 2048 px, takes 7.3 s on one
/// thread and 5.6 s on two with 16 queued, 4.7 s with 64, 4.2 s with 256
/// (peak 39 MB against 24 MB; a batch is at most `BATCH_SEGMENTS`
/// segments, so the queues stay bounded).
const QUEUE: usize = 256;

/// What the producer hands to the bands, in drawing order.
pub(super) enum Op {
    /// Stroke each band's part of a batch, `width` pixels wide, round caps
    /// and joins: `(band, path)`, the path moved up by the band's first row.
    Stroke {
        /// The bands' paths (bands the batch does not reach have none).
        paths: Vec<(usize, Path)>,
        /// Stroke width in pixels.
        width: f32,
    },
    /// Fill `path` (an underlay shape, even-odd; a polygon, non-zero).
    Fill {
        /// The shape's rings, in output pixels of the whole picture.
        path: Arc<Path>,
        /// Its colour.
        color: Color,
        /// Its rule.
        rule: FillRule,
    },
    /// The stroke colour changes (a `.lsys` palette): later strokes,
    /// blots and covers are this colour.
    Paint(Rgb),
    /// Blots ([`raster::stamp`]): ends in output pixels and shape.
    Blots(Arc<Vec<Blot>>),
    /// A stroke covered the whole picture: every pixel the ink.
    Cover,
}

/// What every band paints with: the stroke paint and colour, the width of
/// the raster.
#[derive(Clone)]
pub(super) struct Ink {
    /// Anti-aliased, the stroke colour.
    pub paint: Paint<'static>,
    /// The stroke colour, for blots and cover.
    pub rgb: Rgb,
    /// The raster's width in pixels.
    pub width: u32,
}

impl Ink {
    /// Strokes, blots and covers in `rgb` from now on.
    pub(super) fn set(&mut self, rgb: Rgb) {
        self.rgb = rgb;
        self.paint.set_color(color(rgb));
    }
}

/// Splits a batch into the bands' paths as the producer writes it: each
/// subpath is gathered, then added to every band whose rows it reaches
/// (with anti-aliasing and caps: half the stroke width and two pixels
/// more), moved up by that band's first row.
pub(super) struct Router {
    /// A path being built for each band of the picture.
    paths: Vec<PathBuilder>,
    /// The subpath being gathered, and its rows.
    sub: Vec<(f32, f32)>,
    min: f32,
    max: f32,
}

impl Router {
    /// A router for a picture `height` rows tall.
    pub(super) fn new(height: u32) -> Router {
        let count = height.div_ceil(BAND_ROWS).max(1) as usize;
        Router {
            paths: (0..count).map(|_| PathBuilder::new()).collect(),
            sub: Vec::new(),
            min: f32::INFINITY,
            max: f32::NEG_INFINITY,
        }
    }

    /// Adds a vertex to the subpath (its first is where it starts).
    #[inline]
    pub(super) fn point(&mut self, x: f32, y: f32) {
        self.min = self.min.min(y);
        self.max = self.max.max(y);
        self.sub.push((x, y));
    }

    /// Ends the subpath: adds it to the bands it reaches, strokes `width`
    /// pixels wide.
    pub(super) fn end(&mut self, width: f32) {
        if self.sub.is_empty() {
            return;
        }
        let margin = width / 2.0 + 2.0;
        let (min, max) = (self.min, self.max);
        let rows = BAND_ROWS as f32;
        let last = (self.paths.len() - 1) as f32;
        let from = ((min - margin) / rows).floor().clamp(0.0, last) as usize;
        let to = ((max + margin) / rows).floor().clamp(0.0, last) as usize;
        for band in from..=to {
            let top = (band as u32 * BAND_ROWS) as f32;
            if max < top - margin || min > top + rows + margin {
                continue;
            }
            let pb = &mut self.paths[band];
            let (x, y) = self.sub[0];
            pb.move_to(x, y - top);
            for &(x, y) in &self.sub[1..] {
                pb.line_to(x, y - top);
            }
        }
        self.sub.clear();
        self.min = f32::INFINITY;
        self.max = f32::NEG_INFINITY;
    }

    /// Drops what is gathered.
    pub(super) fn clear(&mut self) {
        self.sub.clear();
        self.min = f32::INFINITY;
        self.max = f32::NEG_INFINITY;
        for pb in &mut self.paths {
            pb.clear();
        }
    }

    /// The bands' paths of the batch so far, and empty ones for the next.
    pub(super) fn take(&mut self) -> Vec<(usize, Path)> {
        self.paths
            .iter_mut()
            .enumerate()
            .filter_map(|(i, pb)| std::mem::take(pb).finish().map(|p| (i, p)))
            .collect()
    }
}

/// One band: its rows of the raster.
struct Band<'a> {
    data: &'a mut [u8],
    rows: Range<u32>,
}

impl Band<'_> {
    /// Paints `op` into the band; `path`: its part of a stroke;
    /// `repeats`: what the band was stroked with lately.
    fn apply(&mut self, op: &Op, path: Option<&Path>, ink: &Ink, repeats: &mut Repeats) {
        let top = self.rows.start;
        let height = self.rows.end - top;
        let Some(mut pixmap) = PixmapMut::from_bytes(self.data, ink.width, height) else {
            return;
        };
        match op {
            Op::Stroke { width, .. } => {
                if let Some(path) = path {
                    repeats.stroke(&mut pixmap, path, *width, &ink.paint);
                }
            }
            Op::Fill { path, color, rule } => {
                repeats.changed();
                let mut paint = Paint::default();
                paint.set_color(*color);
                paint.anti_alias = true;
                pixmap.fill_path(
                    path,
                    &paint,
                    *rule,
                    Transform::from_translate(0.0, -(top as f32)),
                    None,
                );
            }
            Op::Blots(blots) => {
                for blot in blots.iter().filter(|b| b.reaches(&self.rows)) {
                    repeats.changed();
                    let rows = self.rows.clone();
                    let (a, b) = (blot.a, blot.b);
                    raster::stamp(self.data, ink.width, rows, ink.rgb, a, b, &blot.shape);
                }
            }
            Op::Cover => {
                repeats.changed();
                pixmap.fill(color(ink.rgb));
            }
            // The producer's ink or the thread's own has changed already;
            // what changed nothing in the old paint may change it now.
            Op::Paint(_) => repeats.changed(),
        }
    }
}

/// Paints `op` into `bands`, which are the picture's bands `first`,
/// `first + step`, ..., each with its [`Repeats`] (the same index in
/// `repeats`).
fn paint(
    bands: &mut [Band<'_>],
    repeats: &mut [Repeats],
    (first, step): (usize, usize),
    op: &Op,
    ink: &Ink,
) {
    match op {
        Op::Stroke { paths, .. } => {
            for (band, path) in paths {
                if let Some(d) = band.checked_sub(first).filter(|d| d % step == 0)
                    && let (Some(b), Some(r)) = (bands.get_mut(d / step), repeats.get_mut(d / step))
                {
                    b.apply(op, Some(path), ink, r);
                }
            }
        }
        _ => {
            for (b, r) in bands.iter_mut().zip(repeats) {
                b.apply(op, None, ink, r);
            }
        }
    }
}

/// The [`Repeats`] of a canvas's bands: one for a whole raster, one a
/// band for bands painted on the producer's thread, none for band
/// threads (each holds its own).
pub(super) fn repeats_for(canvas: &Canvas) -> Vec<Repeats> {
    let n = match canvas {
        Canvas::Whole(_) => 1,
        Canvas::Bands(p) => p.height().div_ceil(BAND_ROWS).max(1) as usize,
        Canvas::Sent(_) => 0,
    };
    (0..n).map(|_| Repeats::default()).collect()
}

/// The bands of `pixmap`, top to bottom.
fn bands(pixmap: &mut Pixmap) -> Vec<Band<'_>> {
    let height = pixmap.height();
    let stride = pixmap.width() as usize * 4 * BAND_ROWS as usize;
    pixmap
        .data_mut()
        .chunks_mut(stride)
        .enumerate()
        .map(|(i, data)| {
            let top = i as u32 * BAND_ROWS;
            Band {
                data,
                rows: top..(top + BAND_ROWS).min(height),
            }
        })
        .collect()
}

/// Where a [`super::PngTurtle`] paints.
pub(super) enum Canvas {
    /// One raster, no bands: every stroke straight into it.
    Whole(Pixmap),
    /// In bands, one after the other, on the producer's thread.
    Bands(Pixmap),
    /// In bands, by the band threads (a queue each; thread `k` paints
    /// bands `k`, `k + N`, ...; [`in_threads`] owns the raster).
    Sent(Vec<SyncSender<Op>>),
}

impl Canvas {
    /// Hands `op` to the bands (for [`Canvas::Whole`], which paints
    /// strokes itself, only fills, blots and cover, as one band).
    /// `repeats`: [`repeats_for`] this canvas.
    pub(super) fn send(&mut self, op: Op, ink: &Ink, repeats: &mut [Repeats]) {
        match self {
            Canvas::Whole(pixmap) => {
                let rows = 0..pixmap.height();
                let mut whole = [Band {
                    data: pixmap.data_mut(),
                    rows,
                }];
                paint(&mut whole, repeats, (0, 1), &op, ink);
            }
            Canvas::Bands(pixmap) => paint(&mut bands(pixmap), repeats, (0, 1), &op, ink),
            Canvas::Sent(queues) => {
                let n = queues.len();
                let mut each: Vec<Op> = match op {
                    Op::Stroke { paths, width } => {
                        let mut split: Vec<Vec<(usize, Path)>> =
                            (0..n).map(|_| Vec::new()).collect();
                        for (band, path) in paths {
                            split[band % n].push((band, path));
                        }
                        split
                            .into_iter()
                            .map(|paths| Op::Stroke { paths, width })
                            .collect()
                    }
                    Op::Fill { path, color, rule } => (0..n)
                        .map(|_| Op::Fill {
                            path: Arc::clone(&path),
                            color,
                            rule,
                        })
                        .collect(),
                    Op::Paint(rgb) => (0..n).map(|_| Op::Paint(rgb)).collect(),
                    Op::Blots(b) => (0..n).map(|_| Op::Blots(Arc::clone(&b))).collect(),
                    Op::Cover => (0..n).map(|_| Op::Cover).collect(),
                };
                for (q, op) in queues.iter().zip(each.drain(..)) {
                    // A thread gone (it panicked) ends the scope with its
                    // panic; nothing to do here.
                    let _ = q.send(op);
                }
            }
        }
    }
}

/// Paints `pixmap` with `threads` threads (at least 2): runs `produce`
/// with a canvas whose batches the band threads paint, and returns what
/// it returns once every band has painted every batch.
pub(super) fn in_threads<R>(
    pixmap: &mut Pixmap,
    threads: usize,
    ink: &Ink,
    produce: impl FnOnce(Canvas) -> R,
) -> R {
    let mut own: Vec<Vec<Band<'_>>> = (0..threads).map(|_| Vec::new()).collect();
    for (i, band) in bands(pixmap).into_iter().enumerate() {
        own[i % threads].push(band);
    }
    std::thread::scope(|scope| {
        let mut queues = Vec::with_capacity(threads);
        for (first, mut bands) in own.into_iter().enumerate() {
            let (tx, rx): (SyncSender<Op>, Receiver<Op>) = sync_channel(QUEUE);
            queues.push(tx);
            let mut ink = ink.clone();
            scope.spawn(move || {
                let mut repeats: Vec<Repeats> = bands.iter().map(|_| Repeats::default()).collect();
                for op in rx {
                    match op {
                        Op::Paint(rgb) => {
                            ink.set(rgb);
                            repeats.iter_mut().for_each(Repeats::changed);
                        }
                        op => paint(&mut bands, &mut repeats, (first, threads), &op, &ink),
                    }
                }
            });
        }
        // The queues are dropped when `produce` is done with the canvas,
        // which ends the threads' loops; the scope waits for them.
        produce(Canvas::Sent(queues))
    })
}

/// The opaque tiny-skia colour of `c`.
pub(super) fn color(c: Rgb) -> Color {
    Color::from_rgba8(c.r, c.g, c.b, 255)
}
