//! A panic inside a third-party geometry engine (linesweeper, spade,
//! i_overlay), caught where moyo has an answer without it, and kept off
//! stderr.
//!
//! The engines are called where moyo can do without them: a boolean falls
//! back on the polygon reference, a triangulation or a slicing on a
//! coarser path. Catching their panic keeps the render going, but Rust's
//! panic hook prints the message (and a backtrace) before the unwinding
//! reaches `catch_unwind`: a valid render that exits 0 would still show
//! `panicked at …` on stderr (issue 36, item 5). So [`catch`] marks its
//! thread while the engine runs, and a hook installed once — the first
//! time [`catch`] runs — stays silent for a marked thread and hands every
//! other panic to the hook that was there before it (the default one, or
//! the program's own).

use std::cell::Cell;
use std::panic::{self, AssertUnwindSafe};
use std::sync::Once;

thread_local! {
    /// Whether this thread is inside [`catch`], whose panics are expected.
    static QUIET: Cell<bool> = const { Cell::new(false) };
}

/// Installs the hook once a process.
static HOOK: Once = Once::new();

/// Runs the engine call `f`: its result, or `None` if it panicked, with
/// nothing printed for that panic (see the module documentation).
pub(crate) fn catch<T>(f: impl FnOnce() -> T) -> Option<T> {
    HOOK.call_once(|| {
        let previous = panic::take_hook();
        panic::set_hook(Box::new(move |info| {
            if !QUIET.with(Cell::get) {
                previous(info);
            }
        }));
    });
    // Nested calls restore what they found, so an outer catch stays quiet.
    let was = QUIET.with(|q| q.replace(true));
    let result = panic::catch_unwind(AssertUnwindSafe(f));
    QUIET.with(|q| q.set(was));
    result.ok()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_caught_panic_is_none_and_the_thread_is_loud_again_after() {
        assert_eq!(catch(|| 3), Some(3));
        let caught: Option<()> = catch(|| panic!("an engine gave up"));
        assert_eq!(caught, None);
        assert!(!QUIET.with(Cell::get));
        // Nested: the outer call stays quiet after the inner one returns.
        let outer = catch(|| {
            let inner: Option<()> = catch(|| panic!("inner"));
            assert!(inner.is_none());
            assert!(QUIET.with(Cell::get));
        });
        assert_eq!(outer, Some(()));
    }
}
