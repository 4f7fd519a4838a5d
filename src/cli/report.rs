//! Diagnostics to ariadne reports on stderr: the only file that knows ariadne.

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
    let config = Config::default()
        .with_color(color)
        .with_index_type(IndexType::Byte);
    let mut report = Report::build(kind, (name.clone(), span.clone()))
        .with_config(config)
        .with_message(&headline)
        .with_label(
            Label::new((name.clone(), span))
                .with_message(d.label.clone().unwrap_or_else(|| headline.clone()))
                .with_order(0),
        );
    for (i, l) in d.labels.iter().enumerate() {
        if l.span.end <= s.text.len() {
            report = report.with_label(
                Label::new((name.clone(), widen(l.span.clone(), s.text)))
                    .with_message(&l.message)
                    .with_order(i as i32 + 1),
            );
        }
    }
    if let Some(help) = &d.help {
        report = report.with_help(help);
    }
    let _ = report
        .finish()
        .write((name, Source::from(s.text)), &mut *out);
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
