//! The words a layout line starts with: a 2D shape's ([`ShapeName`]) or
//! a 3D volume's ([`SolidName`]), and a shape's arguments as read.

use crate::diag::Span;

/// A shape a layout line may draw.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum ShapeName {
    /// `Rectangle`.
    Rectangle,
    /// `RoundRect`: a rectangle with rounded corners.
    RoundRect,
    /// `Ellipse`.
    Ellipse,
    /// `Polygon`.
    Polygon,
}

impl ShapeName {
    /// Every shape, in the order the docs list them.
    pub const ALL: [ShapeName; 4] = [
        ShapeName::Rectangle,
        ShapeName::RoundRect,
        ShapeName::Ellipse,
        ShapeName::Polygon,
    ];

    /// The name as written.
    pub fn name(self) -> &'static str {
        match self {
            ShapeName::Rectangle => "Rectangle",
            ShapeName::RoundRect => "RoundRect",
            ShapeName::Ellipse => "Ellipse",
            ShapeName::Polygon => "Polygon",
        }
    }

    /// The shape named exactly `name`.
    pub fn from_name(name: &str) -> Option<ShapeName> {
        ShapeName::ALL.into_iter().find(|s| s.name() == name)
    }

    /// Its spellings, for hints.
    pub(super) fn usage(self) -> &'static str {
        match self {
            ShapeName::Rectangle => "`Rectangle (x,y), w, h` or `Rectangle (x1,y1,x2,y2)`",
            ShapeName::Ellipse => "`Ellipse (x,y), w, h` or `Ellipse (x1,y1,x2,y2)`",
            ShapeName::RoundRect => "`RoundRect (x,y), w, h, r` or `RoundRect (x1,y1,x2,y2,rx,ry)`",
            ShapeName::Polygon => "`Polygon (x1,y1), (x2,y2), (x3,y3), ...`",
        }
    }
}

/// A shape argument, with spans: a parenthesised group or a single number.
pub(super) enum Arg {
    Group(Vec<(f64, Span)>),
    Num(f64, Span),
}

/// A volume a 3D layout line may hold (section 11).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum SolidName {
    /// `Box (x, y, z), w, h, d`.
    Box,
    /// `Sphere (cx, cy, cz), r`.
    Sphere,
    /// `Ellipsoid (cx, cy, cz), rx, ry, rz`.
    Ellipsoid,
    /// `Cylinder (x, y, z), r, h`.
    Cylinder,
    /// `Extrude <2D shape>, z1, z2`.
    Extrude,
    /// `Revolve <2D shape>`.
    Revolve,
}

impl SolidName {
    /// Every volume, in the order the docs list them.
    pub const ALL: [SolidName; 6] = [
        SolidName::Box,
        SolidName::Sphere,
        SolidName::Ellipsoid,
        SolidName::Cylinder,
        SolidName::Extrude,
        SolidName::Revolve,
    ];

    /// The name as written.
    pub fn name(self) -> &'static str {
        match self {
            SolidName::Box => "Box",
            SolidName::Sphere => "Sphere",
            SolidName::Ellipsoid => "Ellipsoid",
            SolidName::Cylinder => "Cylinder",
            SolidName::Extrude => "Extrude",
            SolidName::Revolve => "Revolve",
        }
    }

    /// The volume named exactly `name`.
    pub fn from_name(name: &str) -> Option<SolidName> {
        SolidName::ALL.into_iter().find(|s| s.name() == name)
    }

    /// Its spelling, for hints.
    pub(super) fn usage(self) -> &'static str {
        match self {
            SolidName::Box => "`Box (x, y, z), w, h, d` (the smallest corner, then the sizes)",
            SolidName::Sphere => "`Sphere (cx, cy, cz), r`",
            SolidName::Ellipsoid => "`Ellipsoid (cx, cy, cz), rx, ry, rz`",
            SolidName::Cylinder => {
                "`Cylinder (x, y, z), r, h` (the bottom centre, then radius and height)"
            }
            SolidName::Extrude => {
                "`Extrude <2D shape>, z1, z2`, as in `Extrude Ellipse (0, 0), 10, 20, -5, 5` \
                 or `Extrude <Ellipse (0, 0), 10, 20>, -5, 5`"
            }
            SolidName::Revolve => "`Revolve <2D shape>`, as in `Revolve Ellipse (0, 0), 10, 20`",
        }
    }
}
