//! The integration test binary (`cargo test --test integration`).
//!
//! One binary, one module per area; see tests/README.md.

// `unused_crate_dependencies` (Cargo.toml) is for the library: the tests use the library and some dev-dependencies, not each dependency.
#![allow(unused_crate_dependencies)]

mod cli;
mod compat;
mod design_reference;
mod determinism;
mod devices;
mod fill_cli;
mod fuzz_regressions;
mod golden;
mod kimono;
mod lsystem_cli;
mod pen_stage;
mod plot_cli;
mod readers;
mod readme;
mod rendered;
mod resource_bounds;
mod safe_writes;
mod snapshots;
mod stencil_cli;
#[cfg(feature = "studio")]
mod studio;
#[cfg(feature = "studio")]
mod studio_browser;
#[cfg(feature = "studio")]
mod studio_gestures;
mod valid_spec;
mod vine_cli;
