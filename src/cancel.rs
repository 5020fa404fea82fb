//! Calling off long work from another thread: the flag a render checks
//! between its steps (the studio raises it when a newer edit comes).

use crate::error::{Error, Result};

/// A flag another thread raises to call off a render (see
/// [`crate::project::render_cancellable`]).
#[derive(Debug, Default)]
pub struct Cancel(std::sync::atomic::AtomicBool);

/// The flag of work that is never called off.
static NEVER: Cancel = Cancel(std::sync::atomic::AtomicBool::new(false));

impl Cancel {
    /// A flag nobody raises (crate-only: raising it would call off every
    /// render that uses it).
    pub(crate) fn never() -> &'static Cancel {
        &NEVER
    }

    /// Calls the work off.
    pub fn raise(&self) {
        self.0.store(true, std::sync::atomic::Ordering::Relaxed);
    }

    /// Whether the work was called off.
    pub fn is_raised(&self) -> bool {
        self.0.load(std::sync::atomic::Ordering::Relaxed)
    }

    /// [`Error::Cancelled`] once the work was called off.
    pub(crate) fn check(&self) -> Result<()> {
        if self.is_raised() {
            Err(Error::Cancelled)
        } else {
            Ok(())
        }
    }
}
