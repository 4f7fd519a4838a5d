//! One integration-test binary; each area is a module.

mod cli;
mod lsys;
mod render;
mod robustness;
mod stl;
