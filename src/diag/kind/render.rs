//! Drawing the picture and writing it (`render`, and `pipeline::draw`'s
//! choice of format and its warning of an empty picture).

/// A problem, or a warning, of drawing and writing the picture.
/// Wrapped in [`super::ErrorKind::Render`].
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum RenderError {
    /// A layout's canvas is not a proper box (NaN or inverted bounds).
    #[error("the canvas to show is not a proper box ({min_x}, {min_y}) .. ({max_x}, {max_y})")]
    BadCanvas {
        /// Left.
        min_x: f64,
        /// Top.
        min_y: f64,
        /// Right.
        max_x: f64,
        /// Bottom.
        max_y: f64,
    },
    /// The drawing reaches coordinates that are infinite or NaN.
    #[error("the drawing reaches coordinates that are not finite numbers")]
    DrawingNotFinite,
    /// `--size` with a zero side or a side over the maximum.
    #[error("image size {width}x{height} is out of range: each side must be 1 to {max} pixels")]
    ImageSize {
        /// Width asked for.
        width: u32,
        /// Height asked for.
        height: u32,
        /// Largest side allowed.
        max: u32,
    },
    /// The raster could not be allocated.
    #[error("cannot make a {width}x{height} raster")]
    NoRaster {
        /// Width.
        width: u32,
        /// Height.
        height: u32,
    },
    /// PNG encoding failed.
    #[error("cannot encode the PNG image: {error}")]
    PngEncoding {
        /// The encoder's message.
        error: String,
    },
    /// A 3D view would hold more stems than it may sort.
    #[error("a 3D view of {segments} stems is over the limit of {limit}")]
    ViewTooLarge {
        /// The stems, in decimal digits (or "more than N").
        segments: String,
        /// The limit.
        limit: u64,
    },
    /// A 3D view drawn at a coarser level of detail than half a pixel, to
    /// stay within its work (a warning).
    #[error(
        "the 3D view is drawn at a level of detail of {px} px, not 0.5 px: parts of the tree smaller than that are stand-ins"
    )]
    CoarseView {
        /// The detail used, in output pixels (fixed decimals).
        px: String,
    },
    /// A mesh would have more triangles than `--max-triangles`.
    #[error("a mesh of {triangles} triangles is over the limit of {limit}")]
    MeshTooLarge {
        /// The triangles, in decimal digits.
        triangles: String,
        /// The limit.
        limit: u64,
    },
    /// Nothing was drawn: the picture is only its background (a warning).
    #[error("the picture is empty: the derivation draws no stem")]
    NothingDrawn,
    /// `-f` names one format and the output's extension another (a usage
    /// error).
    #[error("`-f {format}` contradicts the output name `{path}`")]
    FormatMismatch {
        /// The format asked for with `-f`.
        format: String,
        /// The output path.
        path: String,
    },
    /// `--solid` asked of an input or format that cannot hold a solid, or
    /// an `.stl` asked without `--solid` (a usage error).
    #[error("{message}")]
    SolidUsage {
        /// What is wrong.
        message: String,
    },
    /// The boolean union of a solid failed (the library's status).
    #[error("the solid's union failed: {status}")]
    SolidUnion {
        /// The boolean library's status.
        status: String,
    },
    /// The output's extension names no image format stlc writes (a usage
    /// error).
    #[error("cannot write `{path}`: `.{extension}` is not an image format stlc writes")]
    UnknownOutputExtension {
        /// The output path.
        path: String,
        /// Its extension.
        extension: String,
    },
}
