//! The layout as written: shapes painted in order on a white canvas.
//! Geometry (rings, fills, the canvas view) is [`crate::rings`].

use super::Loc;
use crate::color::Rgb;

/// `LAYOUT ... ENDLAYOUT`: shapes painted in order on a white canvas.
#[derive(Debug, Clone, PartialEq)]
pub struct Layout {
    /// Shapes in painting order (a 2D layout).
    pub shapes: Vec<LayoutShape>,
    /// Volumes in painting order (a 3D layout; `stl-language.md` section
    /// 11). A layout holds shapes or volumes, never both: a 2D shape in a
    /// 3D layout must be extruded or revolved.
    pub solids: Vec<LayoutSolid>,
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
            solids: Vec::new(),
            loc: Loc::default(),
        }
    }
}

/// `(clGreen) Sphere (150, 150, 0), 100`: one volume of a 3D layout.
#[derive(Debug, Clone, PartialEq)]
pub struct LayoutSolid {
    /// Fill colour; white carves.
    pub color: Rgb,
    /// The colour as written (`clGreen`, `#00ff00`), kept for the writer.
    pub color_text: String,
    /// The volume.
    pub solid: Solid,
    /// The whole line.
    pub loc: Loc,
}

/// A volume of a 3D layout, in canvas units (x right, y down, z away from
/// the viewer), as `stl-language.md` section 11 defines them.
#[derive(Debug, Clone, PartialEq)]
pub enum Solid {
    /// `Box (x, y, z), w, h, d`: the corner with the smallest coordinates,
    /// then the (positive) sizes along +x, +y and +z.
    Box {
        /// The smallest corner.
        corner: [f64; 3],
        /// Sizes along x, y, z.
        size: [f64; 3],
    },
    /// `Sphere (cx, cy, cz), r`.
    Sphere {
        /// Centre.
        centre: [f64; 3],
        /// Radius.
        r: f64,
    },
    /// `Ellipsoid (cx, cy, cz), rx, ry, rz`.
    Ellipsoid {
        /// Centre.
        centre: [f64; 3],
        /// Radii along x, y, z.
        radii: [f64; 3],
    },
    /// `Cylinder (x, y, z), r, h`: vertical, the bottom centre given,
    /// rising `h` up the screen (towards -y).
    Cylinder {
        /// The bottom centre.
        base: [f64; 3],
        /// Radius.
        r: f64,
        /// Height (upwards, -y).
        h: f64,
    },
    /// `Extrude <2D shape>, z1, z2`: the shape between `z1` and `z2`.
    Extrude {
        /// The 2D shape.
        shape: Shape,
        /// The smaller z.
        z1: f64,
        /// The larger z.
        z2: f64,
    },
    /// `Revolve <2D shape>`: turned about the vertical line through the
    /// first root (its x and z).
    Revolve {
        /// The 2D profile.
        shape: Shape,
    },
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
