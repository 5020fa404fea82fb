//! The real programs that read moyo's output in these tests — vpype,
//! pygcode and trimesh (one Python), hp2xx, Chromium — found through the
//! variables `tools/test-env.sh` sets.
//!
//! Without one, a test skips its reading and passes; so that a passing run
//! does not hide it, the binary lists at its end, after libtest's summary,
//! what was skipped and how to run it. Under CI a missing reader is a
//! failure instead.

use std::collections::BTreeMap;
use std::ffi::OsString;
use std::sync::{Mutex, Once};

/// Tests that skipped their reading, by the variable that was missing.
static SKIPPED: Mutex<BTreeMap<String, Vec<String>>> = Mutex::new(BTreeMap::new());
static REPORT_AT_EXIT: Once = Once::new();

/// The program the variable `var` names, or `None` (recorded for the list
/// at the end) outside CI.
pub(crate) fn reader(var: &str) -> Option<OsString> {
    let value = std::env::var_os(var);
    if value.is_none() {
        assert!(
            std::env::var_os("CI").is_none(),
            "{var} is not set in CI; .ci/run sets it (tools/test-env.sh)"
        );
        let test = std::thread::current()
            .name()
            .unwrap_or("a test")
            .to_string();
        SKIPPED
            .lock()
            .unwrap_or_else(|e| e.into_inner())
            .entry(var.to_string())
            .or_default()
            .push(test);
        REPORT_AT_EXIT.call_once(|| {
            // Rust has no safe way to run code at exit, and libtest gives
            // none after its summary.
            // SAFETY: `report` is a plain function that neither unwinds
            // (it catches panics) nor calls `exit`.
            #[allow(unsafe_code)]
            unsafe {
                libc::atexit(report)
            };
        });
    }
    value
}

/// Prints the skipped readings once the test binary is done.
extern "C" fn report() {
    let _ = std::panic::catch_unwind(|| {
        let skipped = SKIPPED.lock().unwrap_or_else(|e| e.into_inner());
        let tests: usize = skipped.values().map(Vec::len).sum();
        eprintln!("\nnote: {tests} tests ran without the program that reads their output:");
        for (var, names) in skipped.iter() {
            let mut names = names.clone();
            names.sort();
            eprintln!("  {var} not set: {}", names.join(", "));
        }
        eprintln!(
            "  To run them as CI does: `source tools/test-env.sh && cargo test --locked` \
             (installs vpype, pygcode, trimesh and hp2xx into target/; Chromium needs root)."
        );
    });
}
