//! An .od's root and LAYOUT in the answer of `POST /api/render`: what the
//! page draws and edits, with where each is written in the text (UTF-16
//! offsets: JavaScript string indices).

use serde::Serialize;

use crate::model::Description;
use crate::model::layout::Shape;

/// An .od's root as written, and where (UTF-16 offsets: JavaScript string
/// indices), so the page can move it; a forest's further roots as
/// `others` (drawn, not moved by the page).
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct RootJson {
    x: f64,
    y: f64,
    start: usize,
    end: usize,
    others: Vec<Point>,
}

/// A point.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Point {
    x: f64,
    y: f64,
}

/// The LAYOUT as written: its shapes in painting order, each with its
/// geometry and colour, and where the section is (UTF-16 offsets), so the
/// page can draw the shapes and write the section anew.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct LayoutJson {
    pub(super) start: usize,
    pub(super) end: usize,
    pub(super) shapes: Vec<ShapeJson>,
}

/// A shape as the page draws it, and where it is written (UTF-16 offsets
/// of its `(colour) ...` text, up to its `>` when angled), so the page can
/// rewrite this one shape and leave the rest of the text as it is.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct ShapeJson {
    #[serde(flatten)]
    geometry: Geometry,
    pub(super) start: usize,
    pub(super) end: usize,
    /// `#rrggbb`.
    pub(super) color: String,
    /// The colour's Delphi name if it has one, else `#rrggbb`.
    pub(super) name: String,
}

/// A shape's geometry, tagged by its STL name.
#[derive(Debug, Clone, PartialEq, Serialize)]
#[serde(tag = "type")]
pub(super) enum Geometry {
    Rectangle {
        x: f64,
        y: f64,
        w: f64,
        h: f64,
    },
    RoundRect {
        x: f64,
        y: f64,
        w: f64,
        h: f64,
        rx: f64,
        ry: f64,
    },
    Ellipse {
        x: f64,
        y: f64,
        w: f64,
        h: f64,
    },
    Polygon {
        points: Vec<[f64; 2]>,
    },
}

/// A 2D shape's geometry as the page draws it.
pub(super) fn geometry(shape: &Shape) -> Geometry {
    match shape {
        Shape::Rect { x, y, w, h } => Geometry::Rectangle {
            x: *x,
            y: *y,
            w: *w,
            h: *h,
        },
        Shape::RoundRect { x, y, w, h, rx, ry } => Geometry::RoundRect {
            x: *x,
            y: *y,
            w: *w,
            h: *h,
            rx: *rx,
            ry: *ry,
        },
        Shape::Ellipse { x, y, w, h } => Geometry::Ellipse {
            x: *x,
            y: *y,
            w: *w,
            h: *h,
        },
        Shape::Polygon(points) => Geometry::Polygon {
            points: points.iter().map(|&(x, y)| [x, y]).collect(),
        },
    }
}

pub(super) fn floor_char(text: &str, mut i: usize) -> usize {
    while !text.is_char_boundary(i) {
        i -= 1;
    }
    i
}

/// A byte offset of `text` as a UTF-16 offset (a JavaScript string index).
pub(super) fn utf16(text: &str, byte: usize) -> usize {
    let b = floor_char(text, byte.min(text.len()));
    text[..b].encode_utf16().count()
}

pub(super) fn root_json(text: &str, od: &Description) -> RootJson {
    let span = &od.root_loc.0;
    RootJson {
        x: od.root.0,
        y: od.root.1,
        start: utf16(text, span.start),
        end: utf16(text, span.end),
        others: od
            .forest
            .iter()
            .map(|t| Point {
                x: t.root.0,
                y: t.root.1,
            })
            .collect(),
    }
}

pub(super) fn layout_json(text: &str, od: &Description) -> Option<LayoutJson> {
    let layout = od.layout.as_ref()?;
    let shapes = layout
        .shapes
        .iter()
        .map(|s| ShapeJson {
            geometry: geometry(&s.shape),
            start: utf16(text, s.loc.0.start),
            end: utf16(text, s.loc.0.end),
            color: s.color.to_string(),
            name: s
                .color
                .delphi_name()
                .map_or_else(|| s.color.to_string(), str::to_string),
        })
        .collect();
    let span = &layout.loc.0;
    Some(LayoutJson {
        start: utf16(text, span.start),
        end: utf16(text, span.end),
        shapes,
    })
}
