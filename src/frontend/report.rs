//! Diagnostics to ariadne reports on stderr: the only file that knows ariadne.

use std::io::Write;

use ariadne::{Config, IndexType, Label, Report, ReportKind, Source};
use stlc::diag::excerpt::ELLIPSIS;
use stlc::diag::line_column;
use stlc::diag::{Diagnostic, Severity};

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
            let _ = writeln!(out, "  help: {}", help.flags());
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
    let shown = stlc::diag::Excerpt::new(s.text, &points);
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
        report = report.with_help(help.flags());
    }
    // ariadne writes in many small pieces: render into memory, write once.
    let mut buf = Vec::new();
    let _ = report
        .finish()
        .write((name, Source::from(&*shown.text)), &mut buf);
    let _ = out.write_all(&buf);
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
    use stlc::diag::LsysError;

    /// A report on a 2,000-byte line is short and gives the true line and
    /// column of the span in a note.
    #[test]
    fn a_report_on_a_long_line_is_short_and_says_where_the_span_is() {
        let line = format!("{}X{}", "é".repeat(500), "é".repeat(499));
        let text = format!("first\n{line}\nlast\n");
        let x = text.find('X').unwrap();
        let d = Diagnostic::error(LsysError::NoDepth).with_span(x..x + 1);
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
}
