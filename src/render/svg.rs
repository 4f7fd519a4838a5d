//! SVG backend: streamed text, fixed decimals.
//!
//! [`SvgTurtle`] writes SVG 1.1 as the drawing runs: the `<svg>` element of
//! the fitted size, a background `<rect>`, the underlay ([`Fill`]s as
//! `<path fill-rule="evenodd">`), then the segments as stroked
//! `<path d="M.. L..">` elements with round caps and joins. Like the PNG
//! backend it batches one path per stroke width, flushed every
//! [`BATCH_SEGMENTS`] segments and on every width change, and a segment that
//! starts where the previous one ended extends the current subpath.
//!
//! Coordinates are output pixels with exactly two decimals (`-0.00` is
//! written `0.00`); lines end in LF and the file in a newline, so the same
//! drawing gives the same bytes. Its sections mirror `png/mod.rs`.

use std::fmt::Write as _;
use std::io::{self, Write};

use super::svg_merge::{Cells, Run, SVG_FOLD_PX, continues, distance2, push_q, quantise};
use super::{BATCH_SEGMENTS, BLOT_DENSITY, BLOT_EXTRA_PX, Fit, Style, Width, stroke_px};
use crate::color::Rgb;
use crate::diag::{Diagnostics, io_error};
use crate::turtle::Fill;
use crate::turtle::{Point, Segment, StandIn, Turtle};

// ---------------------------------------------------------------------------
// Canvas

/// A turtle that streams SVG text into `W`.
pub struct SvgTurtle<W: Write> {
    out: W,
    /// The first write error; later writes are skipped and `finish` reports it.
    error: Option<io::Error>,
    fit: Fit,
    width: Width,
    stroke: Rgb,
    /// The `d` data being collected: all its segments share `batch_width`.
    batch: String,
    batch_width: f64,
    batch_len: usize,
    /// Where the last segment ended (canvas units), to extend subpaths.
    last_to: Option<Point>,
    /// Segments written so far, and the most allowed; past it nothing more
    /// is written and `finish` reports the limit.
    written: u64,
    max_segments: u64,
    /// Level of detail in canvas units ([`Turtle::detail`]), `None`: exact.
    detail: Option<f64>,
    /// Merging ([`super::svg_merge`]): the cells' visits, `None` when every
    /// segment is written (`--exact`).
    cells: Option<Cells>,
    /// The run being merged.
    run: Option<Run>,
}

impl<W: Write> SvgTurtle<W> {
    /// Writes the `<svg>` start tag of size `fit.width` x `fit.height` and
    /// the background (none when transparent).
    pub fn new(out: W, fit: Fit, style: &Style) -> Result<SvgTurtle<W>, Diagnostics> {
        let mut turtle = SvgTurtle {
            out,
            error: None,
            fit,
            width: style.width,
            stroke: style.stroke,
            batch: String::new(),
            batch_width: 0.0,
            batch_len: 0,
            last_to: None,
            written: 0,
            max_segments: u64::MAX,
            detail: None,
            cells: None,
            run: None,
        };
        let (w, h) = (fit.width, fit.height);
        let mut head = format!(
            "<svg xmlns=\"http://www.w3.org/2000/svg\" version=\"1.1\" \
             width=\"{w}\" height=\"{h}\" viewBox=\"0 0 {w} {h}\">\n"
        );
        if let Some(bg) = style.background {
            let _ = writeln!(head, "<rect width=\"{w}\" height=\"{h}\" fill=\"{bg}\"/>");
        }
        turtle.write(&head);
        match turtle.error.take() {
            Some(e) => Err(io_error(&e, "writing the SVG image").into()),
            None => Ok(turtle),
        }
    }

    /// The same turtle asking for a level of detail of `px` output pixels
    /// (see [`Turtle::detail`]); `None` writes every segment.
    pub fn with_detail(mut self, px: Option<f64>) -> Self {
        self.detail = px.map(|px| px / self.fit.scale);
        self
    }

    // -----------------------------------------------------------------------
    // Underlay

    /// Writes a filled area (a layout shape) with the even-odd rule. Call
    /// before drawing segments: it paints over whatever is there.
    pub fn fill(&mut self, fill: &Fill) {
        self.flush();
        let mut d = String::new();
        for ring in &fill.rings {
            let mut points = ring.iter().map(|&p| self.fit.map(p));
            if let Some(first) = points.next() {
                push_point(&mut d, 'M', first);
                for p in points {
                    push_point(&mut d, 'L', p);
                }
                d.push_str(" Z");
            }
        }
        if !d.is_empty() {
            let text = format!(
                "<path fill=\"{}\" fill-rule=\"evenodd\" d=\"{}\"/>\n",
                fill.color,
                d.trim_start()
            );
            self.write(&text);
        }
    }

    /// The same turtle merging runs into as few path commands as show the
    /// same picture (`render/svg_merge.rs`); `max_segments` then counts
    /// path commands.
    pub fn merging(mut self) -> Self {
        self.cells = Some(Cells::new(self.fit.width, self.fit.height));
        self
    }

    /// The same turtle, refusing to write more than `max` segments.
    pub fn with_max_segments(mut self, max: u64) -> Self {
        self.max_segments = max;
        self
    }

    // -----------------------------------------------------------------------
    // Strokes

    /// Writes the collected path as one `<path>` element and starts an
    /// empty one.
    fn flush(&mut self) {
        self.end_run();
        self.batch_len = 0;
        self.last_to = None;
        if self.batch.is_empty() {
            return;
        }
        let mut width = String::new();
        push_num(&mut width, self.batch_width);
        let text = format!(
            "<path fill=\"none\" stroke=\"{}\" stroke-width=\"{width}\" \
             stroke-linecap=\"round\" stroke-linejoin=\"round\" d=\"{}\"/>\n",
            self.stroke,
            self.batch.trim_start()
        );
        self.batch.clear();
        self.write(&text);
    }

    // -----------------------------------------------------------------------
    // Output

    /// Writes what is left and the end tag; hands back the writer (not
    /// flushed) or the first write error.
    pub fn finish(mut self) -> Result<W, Diagnostics> {
        self.flush();
        self.write_dense();
        if self.written > self.max_segments {
            return Err(super::svg_too_large(None, self.max_segments));
        }
        self.write("</svg>\n");
        match self.error {
            Some(e) => Err(io_error(&e, "writing the SVG image").into()),
            None => Ok(self.out),
        }
    }

    /// Writes `text` unless an earlier write failed.
    fn write(&mut self, text: &str) {
        if self.error.is_none()
            && let Err(e) = self.out.write_all(text.as_bytes())
        {
            self.error = Some(e);
        }
    }
}

impl<W: Write> Turtle for SvgTurtle<W> {
    fn detail(&self) -> Option<f64> {
        self.detail
    }

    fn stand_in(&mut self, stand_in: &StandIn) {
        let (seg, density) = (stand_in.seg, stand_in.density);
        let mut width = stroke_px(&self.width, self.fit.scale, seg.order);
        if density >= BLOT_DENSITY {
            // The PNG backend's blot, as a wider stroke: in SVG a path's
            // strokes are a union, so this is the bush's dilated outline.
            width += BLOT_EXTRA_PX;
        }
        self.stroke(seg, width);
    }

    fn segment(&mut self, seg: Segment) {
        let width = stroke_px(&self.width, self.fit.scale, seg.order);
        self.stroke(seg, width);
    }

    fn paint(&mut self, rgb: Rgb) {
        if rgb == self.stroke {
            return;
        }
        self.flush();
        self.stroke = rgb;
        // Merging leaves out lines over inked cells, which a new colour
        // would change: a drawing with colours is written exactly (its
        // first colour comes before any line).
        self.cells = None;
    }

    fn polygon(&mut self, points: &[Point]) {
        let mut d = String::new();
        for (i, &p) in points.iter().enumerate() {
            let p = self.fit.map(p);
            if !(p.x.is_finite() && p.y.is_finite()) {
                return;
            }
            push_point(&mut d, if i == 0 { 'M' } else { 'L' }, p);
        }
        if points.len() < 3 {
            return;
        }
        self.flush();
        let text = format!(
            "<path fill=\"{}\" d=\"{} Z\"/>\n",
            self.stroke,
            d.trim_start()
        );
        self.write(&text);
    }
}

impl<W: Write> SvgTurtle<W> {
    /// Adds `seg` to the batch of paths `width` pixels wide.
    fn stroke(&mut self, seg: Segment, width: f64) {
        let (from, to) = (self.fit.map(seg.from), self.fit.map(seg.to));
        if ![from.x, from.y, to.x, to.y].iter().all(|v| v.is_finite()) {
            // Not writable as a number; the PNG backend skips it too.
            return;
        }
        if self.cells.is_some() {
            self.merge(seg, quantise(from.x, from.y), quantise(to.x, to.y), width);
            return;
        }
        self.written += 1;
        if self.written > self.max_segments {
            // Over the limit: `finish` reports it; write nothing more.
            return;
        }
        if self.batch_len >= BATCH_SEGMENTS || (self.batch_len > 0 && width != self.batch_width) {
            self.flush();
        }
        self.batch_width = width;
        if self.last_to != Some(seg.from) {
            push_point(&mut self.batch, 'M', from);
        }
        push_point(&mut self.batch, 'L', to);
        self.batch_len += 1;
        self.last_to = Some(seg.to);
    }
}

impl<W: Write> SvgTurtle<W> {
    /// Adds `seg` (its ends on the written grid) to the merged batch.
    fn merge(
        &mut self,
        seg: Segment,
        from: super::svg_merge::Q,
        to: super::svg_merge::Q,
        width: f64,
    ) {
        if self.batch_len >= BATCH_SEGMENTS || (self.batch_len > 0 && width != self.batch_width) {
            self.flush();
        }
        self.batch_width = width;
        if self.last_to != Some(seg.from) || self.run.is_none() {
            self.end_run();
            self.run = Some(Run::at(from));
        }
        self.last_to = Some(seg.to);
        let Some(run) = self.run.as_mut() else {
            return;
        };
        run.at = to;
        let fold = (SVG_FOLD_PX * 100.0) as i128;
        if distance2(run.kept, to) < fold * fold {
            run.pending = true;
        } else {
            self.line_to(to);
        }
    }

    /// Ends the run: its exact end is written (unless its cell is inked).
    fn end_run(&mut self) {
        if let Some(run) = self.run
            && run.pending
        {
            self.line_to(run.at);
        }
        self.run = None;
    }

    /// Writes the line from the run's last vertex to `q`: not at all when
    /// it is short and ends in an inked cell (the pen lifts), as a move of
    /// the last line's end when it goes on in the same direction.
    fn line_to(&mut self, q: super::svg_merge::Q) {
        let (Some(run), Some(cells)) = (self.run.as_mut(), self.cells.as_mut()) else {
            return;
        };
        let k = run.kept;
        run.kept = q;
        run.pending = false;
        let side = i128::from(cells.side());
        let width = self.batch_width as f32;
        if distance2(k, q) < side * side {
            // Written if a cell at either end takes a visit (both are
            // counted), else left out (and counted as such).
            let (at_q, at_k) = (cells.takes(q, width), cells.takes(k, width));
            if !(at_q || at_k) {
                cells.left_out(q);
                cells.left_out(k);
                run.open = false;
                run.last_line = None;
                return;
            }
            if at_q {
                cells.visit(q, width);
            }
            if at_k {
                cells.visit(k, width);
            }
        }
        // A line that goes on in the last one's direction moves its end
        // (the pen is down: `last_line` is reset whenever it lifts).
        let merge = match run.last_line {
            Some((offset, start)) if continues(start, k, q) && offset <= self.batch.len() => {
                Some(offset)
            }
            _ => None,
        };
        if merge.is_none() {
            // The limit counts lines: a move only ever starts one.
            self.written += 1;
            if self.written > self.max_segments {
                // Over the limit: `finish` reports it; write nothing more.
                return;
            }
        }
        if !run.open {
            run.open = true;
            push_q(&mut self.batch, 'M', k);
        }
        match merge {
            Some(offset) => self.batch.truncate(offset),
            None => {
                run.last_line = Some((self.batch.len(), k));
                self.batch_len += 1;
            }
        }
        push_q(&mut self.batch, 'L', q);
    }

    /// Writes what is left and returns the lines written (a counting pass
    /// into a sink).
    pub fn lines(mut self) -> u64 {
        self.flush();
        self.write_dense();
        self.written
    }

    /// Paints the dense cells of a merged SVG whole: each row's runs as
    /// lines a cell wide with flat ends.
    fn write_dense(&mut self) {
        let Some(cells) = self.cells.as_ref() else {
            return;
        };
        let runs = cells.dense_runs();
        let mut width = String::new();
        push_num(&mut width, cells.side() as f64 / 100.0);
        for batch in runs.chunks(BATCH_SEGMENTS) {
            self.written += batch.len() as u64;
            if self.written > self.max_segments {
                return;
            }
            let mut d = String::new();
            for &(a, b) in batch {
                push_q(&mut d, 'M', a);
                push_q(&mut d, 'L', b);
            }
            let text = format!(
                "<path fill=\"none\" stroke=\"{}\" stroke-width=\"{width}\" \
                 stroke-linecap=\"butt\" d=\"{}\"/>\n",
                self.stroke,
                d.trim_start()
            );
            self.write(&text);
        }
    }
}

// ---------------------------------------------------------------------------
// Helpers

/// Appends ` Cx y` (command letter, then the point with two decimals).
fn push_point(buf: &mut String, command: char, p: Point) {
    buf.push(' ');
    buf.push(command);
    push_num(buf, p.x);
    buf.push(' ');
    push_num(buf, p.y);
}

/// Appends `x` with exactly two decimals; `-0.00` becomes `0.00`, so the
/// sign of a rounded-away zero never shows in the bytes.
pub fn push_num(buf: &mut String, x: f64) {
    crate::num::push_fixed(buf, x, 2, crate::num::Trim::Keep);
}

#[cfg(test)]
mod tests {
    use super::*;

    fn num(x: f64) -> String {
        let mut s = String::new();
        push_num(&mut s, x);
        s
    }

    #[test]
    fn numbers_have_two_decimals_and_no_negative_zero() {
        assert_eq!(num(1.0), "1.00");
        assert_eq!(num(-0.0), "0.00");
        assert_eq!(num(-0.004), "0.00");
        assert_eq!(num(-0.006), "-0.01");
        assert_eq!(num(12.345_678), "12.35");
        assert_eq!(num(-3.5), "-3.50");
    }

    /// A 10 x 10 px picture of the view (0, 0)-(10, 10), black 1 px
    /// strokes on no background.
    fn ten_by_ten() -> (Fit, Style) {
        let mut view = crate::turtle::BBox::at(Point::new(0.0, 0.0));
        view.add(Point::new(10.0, 10.0));
        let fit = Fit::view(&view, Some((10, 10))).unwrap();
        let style = Style {
            stroke: Rgb::BLACK,
            background: None,
            width: Width::Pixels(1.0),
        };
        (fit, style)
    }

    #[test]
    fn past_its_segment_limit_the_turtle_writes_nothing_more_and_finish_refuses() {
        let (fit, style) = ten_by_ten();
        let seg = |i: f64| Segment {
            from: Point::new(i, 0.0),
            to: Point::new(i + 1.0, 0.0),
            order: 0,
        };
        for (max, ok) in [(3, true), (2, false)] {
            let mut t = SvgTurtle::new(Vec::new(), fit, &style)
                .unwrap()
                .with_max_segments(max);
            for i in 0..3 {
                t.segment(seg(f64::from(i)));
            }
            match t.finish() {
                Ok(bytes) => {
                    assert!(ok);
                    let text = String::from_utf8(bytes).unwrap();
                    // One subpath: a move and three lines.
                    assert_eq!(text.matches(" L").count(), 3, "{text}");
                    assert_eq!(text.matches("\"M").count(), 1, "{text}");
                }
                Err(e) => {
                    assert!(!ok);
                    assert!(e.to_string().contains("more than 2"), "{e}");
                }
            }
        }
    }

    /// Merging: a run of 200 collinear steps of 0.02 px is one move and one
    /// line; dots alternating between two points of one cell are written
    /// until the cell has had its two visits (a dot visits its cell at both
    /// ends), then left out (each counted twice), and once four are
    /// counted the cell is dense and painted whole (a line across it, a
    /// cell wide, flat ends).
    #[test]
    fn merged_runs_fold_join_and_fill_crowded_cells() {
        let (fit, style) = ten_by_ten();
        let mut t = SvgTurtle::new(Vec::new(), fit, &style).unwrap().merging();
        let seg = |ax: f64, ay: f64, bx: f64, by: f64| Segment {
            from: Point::new(ax, ay),
            to: Point::new(bx, by),
            order: 0,
        };
        // Connected: each step starts exactly where the last one ended.
        let xs: Vec<f64> = (0..=200).map(|i| 1.0 + f64::from(i) * 0.02).collect();
        for w in xs.windows(2) {
            t.segment(seg(w[0], 2.0, w[1], 2.0));
        }
        for i in 0..10 {
            let p = if i % 2 == 0 { 7.3 } else { 7.6 };
            t.segment(seg(p, p, p, p));
        }
        let text = String::from_utf8(t.finish().unwrap()).unwrap();
        let d: Vec<&str> = text
            .split("d=\"")
            .skip(1)
            .map(|s| s.split('"').next().unwrap())
            .collect();
        assert_eq!(
            d,
            [
                "M1.00 2.00 L5.00 2.00 M7.30 7.30 L7.30 7.30",
                "M7.00 7.50 L8.00 7.50"
            ],
            "{text}"
        );
        assert!(text.contains("stroke-width=\"1.00\" stroke-linecap=\"butt\""));
    }
}
