//! SVG backend: streamed text, fixed decimals.
