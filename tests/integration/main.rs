//! One integration-test binary; each area is a module.

mod cli;
mod grow;
mod lsys;
mod render;
mod stl;
