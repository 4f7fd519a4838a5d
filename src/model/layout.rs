//! The layout as written: shapes painted in order on a white canvas.
//! Geometry (rings, fills, the canvas view) is [`crate::rings`].

use super::Loc;
use crate::color::Rgb;

/// `LAYOUT ... ENDLAYOUT`: shapes painted in order on a white canvas.
#[derive(Debug, Clone, PartialEq)]
pub struct Layout {
    /// Shapes in painting order.
    pub shapes: Vec<LayoutShape>,
    /// The section.
    pub loc: Loc,
}

/// `(clGreen) RoundRect (0,0,180,192,7,7)`.
#[derive(Debug, Clone, PartialEq)]
pub struct LayoutShape {
    /// Fill colour; white erases.
    pub color: Rgb,
    /// The colour as written (`clGreen`, `#00ff00`), kept for the writer.
    pub color_text: String,
    /// The geometry, normalised.
    pub shape: Shape,
    /// Which of the paper's two spellings was used (the writer keeps it).
    pub spelling: Spelling,
    /// Whether the paper's `< ... >` brackets were written around the shape.
    pub angled: bool,
    /// The whole line.
    pub loc: Loc,
}

impl LayoutShape {
    /// A shape of `color`, spelled with a start point and sizes, at no
    /// place in any text (for shapes made by a program, not read).
    pub fn new(color: Rgb, shape: Shape) -> Self {
        LayoutShape {
            color,
            color_text: String::new(),
            shape,
            spelling: Spelling::StartSize,
            angled: false,
            loc: Loc::default(),
        }
    }
}

impl Layout {
    /// A layout of `shapes`, at no place in any text.
    pub fn new(shapes: Vec<LayoutShape>) -> Self {
        Layout {
            shapes,
            loc: Loc::default(),
        }
    }
}

/// The two ways the paper writes shape arguments.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Spelling {
    /// `Rectangle (x,y), w, h` / `RoundRect (x,y), w, h, r` (Table 1).
    StartSize,
    /// `Rectangle (x1,y1,x2,y2)` / `RoundRect (x1,y1,x2,y2,rx,ry)` (Delphi's
    /// `TCanvas` arguments: two corners, then the corner ellipse's size).
    Corners,
    /// `Polygon (x1,y1), (x2,y2), ...`.
    Points,
}

/// Layout geometry in canvas units, normalised: `(x, y)` is the top-left
/// corner, `w` and `h` are positive.
#[derive(Debug, Clone, PartialEq)]
pub enum Shape {
    /// An axis-aligned rectangle.
    Rect {
        /// Left.
        x: f64,
        /// Top.
        y: f64,
        /// Width.
        w: f64,
        /// Height.
        h: f64,
    },
    /// A rectangle with elliptic corners of radii `rx`, `ry`.
    RoundRect {
        /// Left.
        x: f64,
        /// Top.
        y: f64,
        /// Width.
        w: f64,
        /// Height.
        h: f64,
        /// Corner radius along x (half Delphi's ellipse width).
        rx: f64,
        /// Corner radius along y.
        ry: f64,
    },
    /// The ellipse inscribed in the box.
    Ellipse {
        /// Left.
        x: f64,
        /// Top.
        y: f64,
        /// Width.
        w: f64,
        /// Height.
        h: f64,
    },
    /// A closed polygon (at least 3 points, in written order).
    Polygon(Vec<(f64, f64)>),
}

/// Builders the layout and region tests share.
#[cfg(test)]
pub(crate) mod testing {
    use super::{Layout, LayoutShape, Shape};
    use crate::color::Rgb;

    /// Delphi's `clGreen`.
    pub const GREEN: Rgb = Rgb::new(0, 128, 0);

    /// A shape of `color`.
    pub fn shape(color: Rgb, shape: Shape) -> LayoutShape {
        LayoutShape::new(color, shape)
    }

    /// A layout of `shapes`, painted in order.
    pub fn layout(shapes: Vec<LayoutShape>) -> Layout {
        Layout::new(shapes)
    }

    /// The rectangle at `(x, y)`, `w` by `h`.
    pub fn rect(x: f64, y: f64, w: f64, h: f64) -> Shape {
        Shape::Rect { x, y, w, h }
    }
}
