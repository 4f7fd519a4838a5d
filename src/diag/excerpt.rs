//! Source text for showing diagnostics: 1-based line and column of a byte
//! offset (what an editor or a JSON report gives), and an [`Excerpt`] that
//! cuts lines too long to show (a generated polygon, binary garbage) down to
//! the neighbourhood of the spans, so a report never prints megabytes.

use std::borrow::Cow;

/// Lines longer than this many bytes are cut down for display.
const LONG_LINE: usize = 160;

/// Bytes kept on each side of a span's end in a cut line.
const CONTEXT: usize = 40;

/// Marks what a cut line leaves out.
pub const ELLIPSIS: &str = " … ";

/// The source as shown: each line longer than `LONG_LINE` bytes keeps only its
/// start and the neighbourhood of every span end on it, the rest replaced
/// by [`ELLIPSIS`]. Line breaks are all kept, so line numbers hold.
pub struct Excerpt<'a> {
    /// The text as shown.
    pub text: Cow<'a, str>,
    /// `(original start, shown start, length)` of every kept piece of a cut
    /// line, in order.
    pieces: Vec<(usize, usize, usize)>,
    /// Whether any line was cut.
    pub cut: bool,
}

impl<'a> Excerpt<'a> {
    /// `text` as shown, keeping the neighbourhood of each byte offset in
    /// `points` on cut lines.
    pub fn new(text: &'a str, points: &[usize]) -> Excerpt<'a> {
        if text.split('\n').all(|l| l.len() <= LONG_LINE) {
            return Excerpt {
                text: Cow::Borrowed(text),
                pieces: Vec::new(),
                cut: false,
            };
        }
        let mut points = points.to_vec();
        points.sort_unstable();
        let mut shown = String::new();
        let mut pieces = Vec::new();
        let mut line_start = 0;
        for line in text.split_inclusive('\n') {
            let line_end = line_start + line.len();
            if line.len() <= LONG_LINE {
                pieces.push((line_start, shown.len(), line.len()));
                shown.push_str(line);
                line_start = line_end;
                continue;
            }
            // Windows to keep: the line's start, and around each point on it.
            let mut keep: Vec<(usize, usize)> = vec![(line_start, line_start + CONTEXT)];
            for &p in points.iter().filter(|&&p| p >= line_start && p <= line_end) {
                keep.push((p.saturating_sub(CONTEXT).max(line_start), p + CONTEXT));
            }
            let mut merged: Vec<(usize, usize)> = Vec::new();
            for (a, b) in keep {
                let a = floor_char(text, a);
                let b = ceil_char(text, b.min(line_end));
                match merged.last_mut() {
                    Some(last) if a <= last.1 => last.1 = last.1.max(b),
                    _ => merged.push((a, b)),
                }
            }
            for (i, &(a, b)) in merged.iter().enumerate() {
                if i > 0 || a > line_start {
                    shown.push_str(ELLIPSIS);
                }
                pieces.push((a, shown.len(), b - a));
                shown.push_str(&text[a..b]);
            }
            if merged.last().is_some_and(|&(_, b)| b < line_end) {
                shown.push_str(ELLIPSIS);
                if line.ends_with('\n') {
                    shown.push('\n');
                }
            }
            line_start = line_end;
        }
        Excerpt {
            text: Cow::Owned(shown),
            pieces,
            cut: true,
        }
    }

    /// Where original byte offset `p` (a kept one) lies in the shown text.
    pub fn offset(&self, p: usize) -> usize {
        if !self.cut {
            return p;
        }
        let i = self.pieces.partition_point(|&(start, _, _)| start <= p);
        match i.checked_sub(1).map(|i| self.pieces[i]) {
            Some((start, at, len)) if p <= start + len => at + (p - start),
            Some((_, at, len)) => at + len,
            None => 0,
        }
    }

    /// [`Excerpt::offset`] of both ends.
    pub fn range(&self, r: &std::ops::Range<usize>) -> std::ops::Range<usize> {
        self.offset(r.start)..self.offset(r.end)
    }
}

fn floor_char(text: &str, mut i: usize) -> usize {
    while !text.is_char_boundary(i) {
        i -= 1;
    }
    i
}

fn ceil_char(text: &str, mut i: usize) -> usize {
    while !text.is_char_boundary(i) {
        i += 1;
    }
    i
}

/// 1-based line and column (in characters) of byte offset `p` of `text`.
pub fn line_column(text: &str, p: usize) -> (usize, usize) {
    let before = &text[..p];
    let line = before.matches('\n').count() + 1;
    let line_start = before.rfind('\n').map_or(0, |i| i + 1);
    (line, text[line_start..p].chars().count() + 1)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A 2,000-byte line of two-byte characters with an `X` in the middle:
    /// the cut keeps the `X` under its span, cuts only at character
    /// boundaries, keeps every line break, and the report stays short.
    #[test]
    fn long_lines_are_cut_around_the_spans_at_character_boundaries() {
        let line = format!("{}X{}", "é".repeat(500), "é".repeat(499));
        let text = format!("first\n{line}\nlast\n");
        let x = text.find('X').unwrap();
        let whole = 6..6 + line.len();
        let shown = Excerpt::new(&text, &[x, x + 1, whole.start, whole.end]);
        assert!(shown.cut);
        assert_eq!(&shown.text[shown.range(&(x..x + 1))], "X");
        assert_eq!(shown.text.lines().count(), 3);
        assert!(shown.text.starts_with("first\n"));
        assert!(shown.text.ends_with("\nlast\n"));
        // A span over the whole line maps onto the whole shown line: from
        // its first character to its last, with the cuts in between.
        let r = shown.range(&whole);
        let second = shown.text.lines().nth(1).unwrap();
        assert_eq!(&shown.text[r], second);
        assert_eq!(second.matches(" … ").count(), 2, "{second}");
        assert!(second.len() < 400);
        // Lines and columns count characters, 1-based.
        assert_eq!(line_column(&text, x), (2, 501));
        assert_eq!(line_column(&text, 0), (1, 1));
    }

    /// Short lines are shown as they are.
    #[test]
    fn short_lines_are_left_alone() {
        let text = "a\nbb\n";
        let shown = Excerpt::new(text, &[2, 4]);
        assert!(!shown.cut);
        assert!(matches!(shown.text, Cow::Borrowed(t) if t == text));
        assert_eq!(shown.range(&(2..4)), 2..4);
    }
}
