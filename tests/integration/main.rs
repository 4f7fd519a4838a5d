//! One integration-test binary; each area is a module.

mod cli;
mod render;
mod stl;
