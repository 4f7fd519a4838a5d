//! Diagnostics to ariadne reports on stderr: the only file that knows ariadne.

use std::borrow::Cow;
use std::io::Write;

use ariadne::{Config, IndexType, Label, Report, ReportKind, Source};
use stlc::{Diagnostic, Severity};

/// Where a diagnostic's spans point: the input's display name and text.
pub struct SourceText<'a> {
    /// `tree.od`, or `<stdin>`.
    pub name: &'a str,
    /// The text (empty when the input could not be read as text).
    pub text: &'a str,
}

/// Writes one diagnostic as an ariadne report (or a plain two-liner when it
/// has no location in the text).
pub fn write(out: &mut dyn Write, d: &Diagnostic, src: Option<&SourceText<'_>>, color: bool) {
    let kind = match d.severity {
        Severity::Error => ReportKind::Error,
        Severity::Warning => ReportKind::Warning,
    };
    let headline = d.kind.to_string();
    let located = match (src, &d.span) {
        (Some(s), Some(span)) if span.end <= s.text.len() => Some((s, span.clone())),
        _ => None,
    };
    let Some((s, span)) = located else {
        let word = match d.severity {
            Severity::Error => "error",
            Severity::Warning => "warning",
        };
        let place = src.map(|s| format!("{}: ", s.name)).unwrap_or_default();
        let _ = writeln!(out, "{word}: {place}{headline}");
        if let Some(help) = &d.help {
            let _ = writeln!(out, "  help: {help}");
        }
        return;
    };
    let name = s.name.to_string();
    // ariadne wants a non-empty span to draw an arrow; widen an empty one
    // onto the next character (or the last, at end of input).
    let span = widen(span, s.text);
    let extra: Vec<(std::ops::Range<usize>, &str)> = d
        .labels
        .iter()
        .filter(|l| l.span.end <= s.text.len())
        .map(|l| (widen(l.span.clone(), s.text), l.message.as_str()))
        .collect();
    // Long lines (a generated polygon, binary garbage) are shown cut down
    // around the spans, or the report would print megabytes.
    let points: Vec<usize> = std::iter::once(&span)
        .chain(extra.iter().map(|(r, _)| r))
        .flat_map(|r| [r.start, r.end])
        .collect();
    let shown = Cropped::new(s.text, &points);
    let config = Config::default()
        .with_color(color)
        .with_index_type(IndexType::Byte);
    // Labels are ordered by where they stand in the file: ariadne starts a
    // new source group (whose header repeats the report's line) whenever a
    // label comes before the previous one, so a note on an earlier line
    // would otherwise show under the wrong line number.
    let rank = |start: usize| {
        std::iter::once(span.start)
            .chain(extra.iter().map(|(r, _)| r.start))
            .filter(|&s| s < start)
            .count() as i32
    };
    let mut report = Report::build(kind, (name.clone(), shown.range(&span)))
        .with_config(config)
        .with_message(&headline)
        .with_label(
            Label::new((name.clone(), shown.range(&span)))
                .with_message(d.label.clone().unwrap_or_else(|| headline.clone()))
                .with_order(rank(span.start)),
        );
    for (range, message) in &extra {
        report = report.with_label(
            Label::new((name.clone(), shown.range(range)))
                .with_message(message)
                .with_order(rank(range.start)),
        );
    }
    if shown.cut {
        let (line, column) = line_column(s.text, span.start);
        report = report.with_note(format!(
            "long lines are shown shortened (`{ELLIPSIS}`); the span starts at line {line}, column {column}"
        ));
    }
    if let Some(help) = &d.help {
        report = report.with_help(help);
    }
    // ariadne writes in many small pieces: render into memory, write once.
    let mut buf = Vec::new();
    let _ = report
        .finish()
        .write((name, Source::from(&*shown.text)), &mut buf);
    let _ = out.write_all(&buf);
}

/// Lines longer than this many bytes are cut down for display.
const LONG_LINE: usize = 160;

/// Bytes kept on each side of a span's end in a cut line.
const CONTEXT: usize = 40;

/// Marks what a cut line leaves out.
const ELLIPSIS: &str = " … ";

/// The source as shown: each line longer than [`LONG_LINE`] keeps only its
/// start and the neighbourhood of every span end on it, the rest replaced
/// by [`ELLIPSIS`]. Line breaks are all kept, so line numbers hold.
struct Cropped<'a> {
    text: Cow<'a, str>,
    /// `(original start, shown start, length)` of every kept piece of a cut
    /// line, in order.
    pieces: Vec<(usize, usize, usize)>,
    /// Whether any line was cut.
    cut: bool,
}

impl<'a> Cropped<'a> {
    fn new(text: &'a str, points: &[usize]) -> Cropped<'a> {
        if text.split('\n').all(|l| l.len() <= LONG_LINE) {
            return Cropped {
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
        Cropped {
            text: Cow::Owned(shown),
            pieces,
            cut: true,
        }
    }

    /// Where original byte offset `p` (a kept one) lies in the shown text.
    fn offset(&self, p: usize) -> usize {
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

    fn range(&self, r: &std::ops::Range<usize>) -> std::ops::Range<usize> {
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

/// 1-based line and column (in characters) of byte offset `p`.
fn line_column(text: &str, p: usize) -> (usize, usize) {
    let before = &text[..p];
    let line = before.matches('\n').count() + 1;
    let line_start = before.rfind('\n').map_or(0, |i| i + 1);
    (line, text[line_start..p].chars().count() + 1)
}

fn widen(span: std::ops::Range<usize>, text: &str) -> std::ops::Range<usize> {
    if span.start < span.end {
        return span;
    }
    let start = span.start.min(text.len());
    match text[start..].chars().next() {
        Some(c) => start..start + c.len_utf8(),
        None => match text[..start].chars().next_back() {
            Some(c) => start - c.len_utf8()..start,
            None => start..start,
        },
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use stlc::diag::ErrorKind;

    /// A 2,000-byte line of two-byte characters with an `X` in the middle:
    /// the cut keeps the `X` under its span, cuts only at character
    /// boundaries, keeps every line break, and the report stays short.
    #[test]
    fn long_lines_are_cut_around_the_spans_at_character_boundaries() {
        let line = format!("{}X{}", "é".repeat(500), "é".repeat(499));
        let text = format!("first\n{line}\nlast\n");
        let x = text.find('X').unwrap();
        let whole = 6..6 + line.len();
        let shown = Cropped::new(&text, &[x, x + 1, whole.start, whole.end]);
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

        let d = Diagnostic::error(ErrorKind::NoDepth).with_span(x..x + 1);
        let src = SourceText {
            name: "t.od",
            text: &text,
        };
        let mut out = Vec::new();
        write(&mut out, &d, Some(&src), false);
        let out = String::from_utf8(out).unwrap();
        assert!(out.contains("line 2, column 501"), "{out}");
        assert!(out.len() < 1_000, "{out}");
    }

    /// Short lines are shown as they are.
    #[test]
    fn short_lines_are_left_alone() {
        let text = "a\nbb\n";
        let shown = Cropped::new(text, &[2, 4]);
        assert!(!shown.cut);
        assert!(matches!(shown.text, Cow::Borrowed(t) if t == text));
        assert_eq!(shown.range(&(2..4)), 2..4);
    }
}
