//! PNG backend (tiny-skia).
