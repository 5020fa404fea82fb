//! The `moyo` command: a thin layer over the library (see `cli`).

// `unused_crate_dependencies` (Cargo.toml) is for the library: the command uses the library, clap and indicatif; the library's own dependencies are checked in the library.
#![allow(unused_crate_dependencies)]
#![forbid(unsafe_code)]

mod cli;

fn main() -> std::process::ExitCode {
    cli::run()
}
