//! One integration-test binary; each area is a module.

mod cli;
mod diagnostics;
mod golden;
mod grow;
mod lsys;
mod render;
mod robustness;
mod stl;
mod support;
