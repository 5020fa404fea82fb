//! The integration test binary (`cargo test --test integration`).
//!
//! One binary, one module per area; see tests/README.md.

mod cli;
mod compat;
mod determinism;
mod golden;
mod kimono;
mod plot_cli;
mod readme;
mod snapshots;
mod valid_spec;
