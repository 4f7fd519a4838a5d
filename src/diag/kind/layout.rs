//! A LAYOUT: its shapes as written (`syntax::stl::layout`) and the region
//! they make (`grow::region`).

/// A problem with a LAYOUT's shapes or the region they make.
/// Wrapped in [`super::ErrorKind::Layout`].
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum LayoutError {
    /// A layout shape's name is none of the known shapes.
    #[error("unknown shape `{name}`")]
    UnknownShape {
        /// The name as written.
        name: String,
    },
    /// A shape's arguments fit none of its spellings.
    #[error("wrong arguments for `{shape}`")]
    ShapeArguments {
        /// The shape's name.
        shape: &'static str,
    },
    /// A polygon with fewer than 3 points.
    #[error("a polygon needs at least 3 points, this one has {points}")]
    TooFewPoints {
        /// The points given.
        points: usize,
    },
    /// A shape's width, height or corner size is zero or negative.
    #[error("the {what} of `{shape}` must be positive")]
    ShapeSizeNotPositive {
        /// The shape's name.
        shape: &'static str,
        /// `width`, `height`, `corner width`, `corner height` or `corner radius`.
        what: &'static str,
    },
    /// A 2D shape in the layout of a 3D description.
    #[error("`{shape}` is a 2D shape, but this description is 3D")]
    FlatShapeIn3d {
        /// The shape's name.
        shape: &'static str,
    },
    /// A volume in the layout of a 2D description.
    #[error("`{shape}` is a volume: it needs a 3D root")]
    SolidIn2d {
        /// The volume's name.
        shape: &'static str,
    },
    /// `Extrude <shape>, z1, z2` with z1 not below z2.
    #[error("`Extrude` needs z1 below z2")]
    ExtrudeRange,
    /// A layout shape has a coordinate that is not a finite number.
    #[error("a layout shape has a coordinate that is not a finite number")]
    LayoutNotFinite,
    /// The layout's shapes leave no area to grow in.
    #[error(
        "the layout leaves no area to grow in: nothing coloured remains once the white shapes are painted"
    )]
    EmptyRegion,
}
