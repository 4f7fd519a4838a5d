//! The layout, `LAYOUT ... ENDLAYOUT`: coloured shapes the tree grows in.
//!
//! Each shape has two spellings: Table 1's start point and size
//! (`Rectangle (x,y), w, h`) and Delphi's corners (`Rectangle (x1,y1,x2,y2)`);
//! a polygon lists its points. The shape names come from one table,
//! [`ShapeName`].

use pest::iterators::Pair;

use super::super::Rule;
use super::builder::{Builder, not_in_grammar, span_of};
use super::names::{Arg, ShapeName, SolidName};
use super::rules::{KW_ENDLAYOUT, KW_LAYOUT, find_word};
use crate::color::Rgb;
use crate::diag::Help;
use crate::diag::{Diagnostic, Diagnostics, LayoutError, Span, StlError};
use crate::limits::Bound;
use crate::model::{Layout, LayoutShape, LayoutSolid, Loc, Shape, Spelling};

/// Refuses a `Polygon` with more points than a layout may have vertices
/// (`--max-layout-vertices`) before the parser reads it: a generated
/// polygon of a million points would cost the parser hundreds of bytes per
/// byte before the region's own vertex count (`grow::region`) refuses it.
/// A byte scan of the text after `LAYOUT`: each `Polygon` word, then its
/// `(x, y)` groups up to the next group without a comma (a colour) or the
/// next word. A closing point written as the first one is not counted; the
/// region counts exactly (points written differently but equal, `1.0` and
/// `1`, are counted here as two).
pub(super) fn prescan_polygons(src: &str, max_vertices: usize) -> Result<(), Diagnostics> {
    let b = src.as_bytes();
    let Some(layout) = find_word(src, 0, KW_LAYOUT) else {
        return Ok(());
    };
    let mut at = layout + KW_LAYOUT.len();
    while let Some(p) = find_word(src, at, ShapeName::Polygon.name()) {
        let mut i = p + ShapeName::Polygon.name().len();
        let mut points = 0usize;
        // The first and the last point as written: a polygon that repeats
        // its first point at the end has one vertex fewer than points.
        let (mut first, mut last) = ("", "");
        loop {
            while i < b.len() && (b[i].is_ascii_whitespace() || b[i] == b',') {
                i += 1;
            }
            if i >= b.len() || b[i] != b'(' {
                break;
            }
            let close = src[i..].find(')').map_or(b.len(), |k| i + k);
            if !src[i..close].contains(',') {
                break;
            }
            points += 1;
            let group = src[i + 1..close].trim();
            if points == 1 {
                first = group;
            }
            last = group;
            i = close + 1;
        }
        let vertices = if points > 1 && first == last {
            points - 1
        } else {
            points
        };
        if vertices > max_vertices {
            // Point at the shape's line: its colour's `(` before the name.
            let start = src[..p].rfind('(').unwrap_or(p);
            return Err(Bound::LayoutVertices
                .exceeded(vertices, max_vertices as u64)
                .with_span(start..i.min(b.len()))
                .with_help(
                    Help::from("use fewer polygon points, or ")
                        + Bound::LayoutVertices
                        + " (above 16000 the overlay can take minutes on some shapes)",
                )
                .into());
        }
        at = i.max(p + 1);
    }
    Ok(())
}

/// Refuses a LAYOUT of more shapes than `--max-layout-shapes` before the
/// parser reads it: each shape line costs the parser and the model about a
/// kilobyte however short it is (docs/limits.md). A byte scan of the text
/// after `LAYOUT` counting shape and volume names (an extruded or revolved
/// shape counts twice).
pub(super) fn prescan_shapes(src: &str, max_shapes: usize) -> Result<(), Diagnostics> {
    let Some(layout) = find_word(src, 0, KW_LAYOUT) else {
        return Ok(());
    };
    let from = layout + KW_LAYOUT.len();
    let names = ShapeName::ALL
        .iter()
        .map(|s| s.name())
        .chain(SolidName::ALL.iter().map(|s| s.name()));
    let shapes: usize = names
        .map(|name| {
            let mut n = 0;
            let mut at = from;
            while let Some(p) = find_word(src, at, name) {
                n += 1;
                at = p + 1;
            }
            n
        })
        .sum();
    if shapes <= max_shapes {
        return Ok(());
    }
    Err(Bound::LayoutShapes
        .exceeded(shapes, max_shapes as u64)
        .with_span(layout..from)
        .with_label("this section")
        .with_help(Help::from("use fewer shapes, or ") + Bound::LayoutShapes)
        .into())
}

impl Builder<'_> {
    /// Whether a size `what` of a `shape` (`v`, written at `s`) is
    /// positive; if not, reports it (2D shapes and volumes alike).
    pub(super) fn positive_size(
        &mut self,
        shape: &'static str,
        v: f64,
        s: &Span,
        what: &'static str,
    ) -> bool {
        if v > 0.0 {
            return true;
        }
        self.report(
            LayoutError::ShapeSizeNotPositive { shape, what },
            s.clone(),
            "zero or negative",
            &format!("write a positive {what}"),
        );
        false
    }

    /// A colour as written (`clGreen`, `#rrggbb`), or an error at `span`
    /// with the nearest colour name.
    pub(super) fn colour(&mut self, text: &str, span: Span) -> Option<Rgb> {
        if let Some(c) = Rgb::parse(text) {
            return Some(c);
        }
        let help = match Rgb::suggest(text) {
            Some(s) => format!("did you mean `{s}`? Colours are Delphi names or `#rrggbb`"),
            None => "use a Delphi colour name (`clGreen`, `clWhite`, ...) or `#rrggbb`".to_string(),
        };
        self.err(crate::syntax::unknown_colour(text, span, help));
        None
    }

    /// The `LAYOUT` section.
    pub(super) fn layout(&mut self, p: Pair<'_, Rule>) -> Layout {
        let span = span_of(&p);
        let mut shapes = Vec::new();
        let mut solids = Vec::new();
        let mut kw = None;
        let mut closed = false;
        for c in p.into_inner() {
            match c.as_rule() {
                Rule::stl_kw_layout => kw = Some(span_of(&c)),
                Rule::stl_kw_endlayout => closed = true,
                Rule::stl_shape_line => match self.shape_line(c) {
                    Some(Line::Shape(s)) => shapes.push(s),
                    Some(Line::Solid(s)) => solids.push(s),
                    None => {}
                },
                other => not_in_grammar("stl_layout", other),
            }
        }
        if !closed {
            self.err(
                Diagnostic::error(StlError::UnclosedSection {
                    open: KW_LAYOUT,
                    close: KW_ENDLAYOUT,
                })
                .with_span(kw.expect("grammar: stl_layout starts with `LAYOUT`"))
                .with_label("this section is never closed")
                .with_help(format!("end the layout with `{KW_ENDLAYOUT}`")),
            );
        }
        Layout {
            shapes,
            solids,
            loc: Loc(span),
        }
    }

    /// `(colour) shape` or `(colour)< shape >`: a 2D shape in a 2D
    /// description, a volume in a 3D one.
    fn shape_line(&mut self, p: Pair<'_, Rule>) -> Option<Line> {
        let loc = Loc(span_of(&p));
        let mut it = p.into_inner();
        let col = it
            .next()
            .expect("grammar: stl_shape_line starts with a colour");
        let mut shape = it.next().expect("grammar: stl_shape_line has a shape");
        let angled = shape.as_rule() == Rule::stl_angled;
        if angled {
            let inner = shape.into_inner().next();
            shape = inner.expect("grammar: stl_angled holds a shape");
        }
        let color_text = col.as_str().to_string();
        let color = self.colour(&color_text, span_of(&col));
        if !self.dimensions_fit(&shape) {
            return None;
        }
        if self.three_d {
            let solid = self.solid(shape)?;
            return Some(Line::Solid(LayoutSolid {
                color: color?,
                color_text,
                solid,
                loc,
            }));
        }
        let (shape, spelling) = self.shape(shape)?;
        Some(Line::Shape(LayoutShape {
            color: color?,
            color_text,
            shape,
            spelling,
            angled,
            loc,
        }))
    }

    /// A shape argument's numbers (`stl_shape_arg`).
    pub(super) fn arg(&mut self, a: Pair<'_, Rule>) -> Arg {
        let inner = a.into_inner().next();
        let inner = inner.expect("grammar: stl_shape_arg holds a point list or a number");
        let s = span_of(&inner);
        match inner.as_rule() {
            Rule::stl_point_list => Arg::Group(
                inner
                    .into_inner()
                    .map(|n| (self.number(&n), span_of(&n)))
                    .collect(),
            ),
            Rule::number => Arg::Num(self.number(&inner), s),
            other => not_in_grammar("stl_shape_arg", other),
        }
    }

    /// A shape: its name and arguments checked against the name's spellings.
    fn shape(&mut self, p: Pair<'_, Rule>) -> Option<(Shape, Spelling)> {
        let span = span_of(&p);
        let mut it = p.into_inner();
        let name_pair = it.next().expect("grammar: stl_shape starts with a name");
        let name = name_pair.as_str();
        let mut args = Vec::new();
        for a in it {
            match a.as_rule() {
                Rule::stl_shape_arg => args.push(self.arg(a)),
                // `Rectangle Ellipse (...)`, `Rectangle <...>`: a 2D shape
                // holds no shape.
                Rule::stl_inner | Rule::stl_inner_angled => {
                    if let Some(kind) = ShapeName::from_name(name) {
                        return self.shape_arguments(kind, span);
                    }
                }
                other => not_in_grammar("stl_shape", other),
            }
        }
        let Some(kind) = ShapeName::from_name(name) else {
            self.unknown_shape(name, span_of(&name_pair));
            return None;
        };
        self.shape_of(kind, &args, span)
    }

    /// A 2D shape of `kind` from its arguments, checked against its
    /// spellings.
    pub(super) fn shape_of(
        &mut self,
        kind: ShapeName,
        args: &[Arg],
        span: Span,
    ) -> Option<(Shape, Spelling)> {
        if kind == ShapeName::Polygon {
            return self.polygon(args, span);
        }
        let round = kind == ShapeName::RoundRect;
        let positive =
            |b: &mut Self, v: f64, s: &Span, what| b.positive_size(kind.name(), v, s, what);
        // The shape of `kind` at (x, y), w by h; a round rectangle's corner
        // radii are given.
        let boxed = |x, y, w, h, (rx, ry)| match kind {
            ShapeName::RoundRect => Shape::RoundRect { x, y, w, h, rx, ry },
            ShapeName::Ellipse => Shape::Ellipse { x, y, w, h },
            ShapeName::Rectangle => Shape::Rect { x, y, w, h },
            ShapeName::Polygon => unreachable!("polygons are read above"),
        };
        match args {
            // Delphi's corner spelling.
            [Arg::Group(g)] if g.len() == if round { 6 } else { 4 } => {
                let (x1, x2, y1, y2) = (g[0].0, g[2].0, g[1].0, g[3].0);
                let (w, h) = ((x2 - x1).abs(), (y2 - y1).abs());
                let mut ok = true;
                if w == 0.0 {
                    ok &= positive(self, w, &(g[0].1.start..g[2].1.end), "width");
                }
                if h == 0.0 {
                    ok &= positive(self, h, &(g[1].1.start..g[3].1.end), "height");
                }
                let (x, y) = (x1.min(x2), y1.min(y2));
                let mut radii = (0.0, 0.0);
                if round {
                    ok &= positive(self, g[4].0, &g[4].1, "corner width");
                    ok &= positive(self, g[5].0, &g[5].1, "corner height");
                    radii = (g[4].0 / 2.0, g[5].0 / 2.0);
                }
                ok.then(|| (boxed(x, y, w, h, radii), Spelling::Corners))
            }
            // Table 1's start-point spelling.
            [Arg::Group(g), rest @ ..]
                if g.len() == 2
                    && rest.len() == if round { 3 } else { 2 }
                    && rest.iter().all(|a| matches!(a, Arg::Num(..))) =>
            {
                let nums: Vec<(f64, Span)> = rest
                    .iter()
                    .filter_map(|a| match a {
                        Arg::Num(v, s) => Some((*v, s.clone())),
                        Arg::Group(..) => None,
                    })
                    .collect();
                let (x, y) = (g[0].0, g[1].0);
                let (w, h) = (nums[0].0, nums[1].0);
                let mut ok = positive(self, w, &nums[0].1, "width");
                ok &= positive(self, h, &nums[1].1, "height");
                let mut radii = (0.0, 0.0);
                if round {
                    ok &= positive(self, nums[2].0, &nums[2].1, "corner radius");
                    radii = (nums[2].0, nums[2].0);
                }
                ok.then(|| (boxed(x, y, w, h, radii), Spelling::StartSize))
            }
            _ => self.shape_arguments(kind, span),
        }
    }

    /// `Polygon (x1,y1), (x2,y2), (x3,y3), ...`: three points or more.
    fn polygon(&mut self, args: &[Arg], span: Span) -> Option<(Shape, Spelling)> {
        let mut pts = Vec::new();
        for a in args {
            match a {
                Arg::Group(g) if g.len() == 2 => pts.push((g[0].0, g[1].0)),
                _ => return self.shape_arguments(ShapeName::Polygon, span),
            }
        }
        if pts.len() < 3 {
            self.report(
                LayoutError::TooFewPoints { points: pts.len() },
                span,
                "too few points",
                "add points: `Polygon (x1,y1), (x2,y2), (x3,y3)`",
            );
            return None;
        }
        Some((Shape::Polygon(pts), Spelling::Points))
    }

    /// Reports arguments that fit none of `kind`'s spellings.
    fn shape_arguments(&mut self, kind: ShapeName, span: Span) -> Option<(Shape, Spelling)> {
        self.report(
            LayoutError::ShapeArguments { shape: kind.name() },
            span,
            "these arguments",
            &format!("write {}", kind.usage()),
        );
        None
    }

    /// Reports a shape name that is none of [`ShapeName::ALL`], with the
    /// nearest one.
    pub(super) fn unknown_shape(&mut self, name: &str, span: Span) {
        // The names of this description's dimensions.
        let all: Vec<&str> = if self.three_d {
            SolidName::ALL.iter().map(|k| k.name()).collect()
        } else {
            ShapeName::ALL.iter().map(|k| k.name()).collect()
        };
        let (_, best) = all
            .iter()
            .map(|k| {
                let d = strsim::levenshtein(&k.to_ascii_lowercase(), &name.to_ascii_lowercase());
                (d, *k)
            })
            .min()
            .expect("the name lists are not empty");
        let what = if self.three_d { "Volumes" } else { "Shapes" };
        self.report(
            LayoutError::UnknownShape {
                name: name.to_string(),
            },
            span,
            "not a shape",
            &format!("did you mean `{best}`? {what}: {}", all.join(", ")),
        );
    }
}

/// A layout line as read: a 2D shape or a volume.
enum Line {
    Shape(LayoutShape),
    Solid(LayoutSolid),
}

#[cfg(test)]
mod tests {
    /// Points counted by hand: a closing point written as the first is not
    /// a vertex; a colour ends the polygon; other shapes are not counted.
    #[test]
    fn polygons_past_the_vertex_limit_are_refused_before_parsing() {
        use super::prescan_polygons;
        let square =
            "LAYOUT (clGreen) Polygon (0,0), (1,0), (1,1), (0,1) (clRed) Rectangle (0,0), 1, 1";
        assert!(prescan_polygons(square, 4).is_ok());
        let e = prescan_polygons(square, 3).unwrap_err();
        assert!(e.to_string().contains("4 exceeds the limit of 3"), "{e}");
        assert_eq!(e.0[0].span.as_ref().map(|s| s.start), Some(7));
        let closed = "LAYOUT (clGreen) Polygon (0,0), (1,0), (1,1), (0,1), (0,0)";
        assert!(prescan_polygons(closed, 4).is_ok());
        // A word that only contains the name, and polygons before LAYOUT
        // (a comment, a rule name), are not counted.
        let other = "Polygon (0,0), (1,0), (1,1) LAYOUT (clGreen) PolygonX (0,0), (1,0)";
        assert!(prescan_polygons(other, 1).is_ok());
    }

    /// Shapes counted by name after `LAYOUT`, whatever their kind.
    #[test]
    fn shapes_past_the_shape_limit_are_refused_before_parsing() {
        use super::prescan_shapes;
        let src = "T (0,0) RULE R1: [F] LAYOUT (clGreen) Rectangle (0,0), 9, 9 \
                   (clWhite) Ellipse (1,1), 2, 2 (clRed) <RoundRect (0,0), 4, 4, 1, 1> \
                   (clGreen) Polygon (0,0), (1,0), (1,1) ENDLAYOUT";
        assert!(prescan_shapes(src, 4).is_ok());
        let e = prescan_shapes(src, 3).unwrap_err();
        assert_eq!(
            e.0[0].kind,
            ErrorKind::Limit {
                bound: crate::limits::Bound::LayoutShapes,
                what: None,
                value: "4".into(),
                limit: 3
            }
        );
        let at = src.find("LAYOUT").unwrap();
        assert_eq!(e.0[0].span, Some(at..at + 6));
        assert!(prescan_shapes("T (0,0) RULE R1: [F]", 0).is_ok());
    }

    use super::ShapeName;
    use crate::diag::{ErrorKind, LayoutError, StlError};
    use crate::limits::Limits;
    use crate::model::Format;

    #[test]
    fn unknown_parameters_and_shapes_are_named() {
        let bed = |src: &str| super::super::parse(src, Format::Bed, &Limits::default());
        let src = "T (0,0) l=10(0) RULE R1: [F]";
        let e = bed(src).unwrap_err();
        assert_eq!(
            e.0[0].kind,
            ErrorKind::Stl(StlError::UnknownParam { key: "l".into() })
        );
        assert!(
            e.0[0]
                .help
                .as_ref()
                .map(|h| h.flags())
                .unwrap_or_default()
                .contains("`L`")
        );
        let src = "T (0,0) RULE R1: [F] LAYOUT (clRed) Rect (0,0), 1, 1 ENDLAYOUT";
        let e = bed(src).unwrap_err();
        assert_eq!(
            e.0[0].kind,
            ErrorKind::Layout(LayoutError::UnknownShape {
                name: "Rect".into()
            })
        );
        let at = src.find("Rect ").unwrap();
        assert_eq!(e.0[0].span, Some(at..at + 4));
        assert!(
            e.0[0]
                .help
                .as_ref()
                .map(|h| h.flags())
                .unwrap_or_default()
                .contains("Rectangle")
        );
    }

    #[test]
    fn shape_names_round_trip() {
        for s in ShapeName::ALL {
            assert_eq!(ShapeName::from_name(s.name()), Some(s));
        }
        assert_eq!(ShapeName::from_name("rectangle"), None);
    }
}
