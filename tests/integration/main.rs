//! One integration-test binary; each area is a module.

mod cli;
mod diagnostics;
mod docs;
mod golden;
mod grow;
mod lsys;
mod newuser;
mod render;
mod robustness;
mod stl;
