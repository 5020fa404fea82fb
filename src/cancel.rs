//! Calling off long work from another thread: the flag a render checks
//! between its steps (the studio raises it when a newer edit comes), and
//! the memory budget checked at the same places.
//!
//! A render's long loops — layer ids, rewriting an L-system word, placing
//! and relaxing sites (where density formulas are evaluated), zentangle
//! steps — sit deep under functions that take no context, so the flag of
//! the render under way is also this thread's ([`Cancel::enter`]) and
//! [`checkpoint`] consults it: no signature between the render and the
//! loop changes, and work run outside a render never stops.
//!
//! The memory budget is checked at those places too, turning "too much"
//! into an error the render returns, like a cancellation, rather than an
//! allocation that fails and aborts the process (a `GlobalAlloc` cannot
//! fail cleanly: Rust aborts on a failed allocation). What is counted is
//! the process's peak resident memory since the flag was made (the
//! system's high-water mark, reset then), read at most every
//! [`PROBE_EVERY`] and at the end of each stage: the studio's whole
//! footprint, which is what the machine runs out of, with the peaks
//! between two reads. The limit of one allocation is not this
//! module's: the budgets of `spec/` bound every table before it is
//! built.

use std::cell::RefCell;
use std::sync::atomic::{AtomicBool, AtomicU64, Ordering};
use std::sync::{Arc, OnceLock};
use std::time::{Duration, Instant};

use crate::error::{Error, Result};

/// How often, at most, the resident memory is read (a file read under
/// `/proc`, some microseconds): often enough that a render cannot grow
/// far past its budget between two reads.
pub(crate) const PROBE_EVERY: Duration = Duration::from_millis(5);

/// A flag another thread raises to call off a render (see
/// [`crate::project::render_cancellable`]), and the memory the process
/// may hold while it runs.
#[derive(Debug, Clone, Default)]
pub struct Cancel(Arc<Flag>);

#[derive(Debug, Default)]
struct Flag {
    raised: AtomicBool,
    /// Most bytes of resident memory, when the work has a budget.
    memory: Option<u64>,
    /// When the memory was last read, in nanoseconds since `start`.
    probed: AtomicU64,
    start: OnceLock<Instant>,
}

impl Cancel {
    /// A flag nobody raises (crate-only: raising it would call off every
    /// render that uses it).
    pub(crate) fn never() -> &'static Cancel {
        static NEVER: OnceLock<Cancel> = OnceLock::new();
        NEVER.get_or_init(Cancel::default)
    }

    /// A flag that also calls the work off when the process's resident
    /// memory passes `bytes` ([`Error::MemoryBudget`]), at its peak from
    /// now on. Where the system does not say (not Linux), there is no
    /// memory budget.
    pub fn with_memory_limit(bytes: u64) -> Cancel {
        reset_peak();
        Cancel(Arc::new(Flag {
            memory: Some(bytes),
            ..Flag::default()
        }))
    }

    /// Calls the work off.
    pub fn raise(&self) {
        self.0.raised.store(true, Ordering::Relaxed);
    }

    /// Whether the work was called off.
    pub fn is_raised(&self) -> bool {
        self.0.raised.load(Ordering::Relaxed)
    }

    /// [`Error::Cancelled`] once the work was called off;
    /// [`Error::MemoryBudget`] when the process holds more memory than
    /// the budget.
    pub(crate) fn check(&self) -> Result<()> {
        self.check_with(false)
    }

    /// [`Cancel::check`] reading the memory whenever it was last read:
    /// for the end of a stage, after which nothing may read it again.
    pub(crate) fn check_now(&self) -> Result<()> {
        self.check_with(true)
    }

    fn check_with(&self, now: bool) -> Result<()> {
        if self.is_raised() {
            return Err(Error::Cancelled);
        }
        match self.0.memory {
            Some(limit) => self.check_memory(limit, now),
            None => Ok(()),
        }
    }

    fn check_memory(&self, limit: u64, force: bool) -> Result<()> {
        let start = *self.0.start.get_or_init(Instant::now);
        let now = u64::try_from(start.elapsed().as_nanos()).unwrap_or(u64::MAX);
        let last = self.0.probed.load(Ordering::Relaxed);
        // The first check reads at once (`probed` starts at 0, `now` may
        // be too); later ones once per PROBE_EVERY.
        if !force && last != 0 && now.saturating_sub(last) < PROBE_EVERY.as_nanos() as u64 {
            return Ok(());
        }
        self.0.probed.store(now.max(1), Ordering::Relaxed);
        match peak_resident_bytes() {
            Some(resident) if resident > limit => Err(Error::MemoryBudget {
                limit_mb: limit / MB,
                resident_mb: resident / MB,
            }),
            _ => Ok(()),
        }
    }

    /// Makes this the flag of the work on this thread, which
    /// [`checkpoint`] consults, until the guard is dropped (the flag
    /// before comes back then).
    pub(crate) fn enter(&self) -> Entered {
        let previous = CURRENT.with(|c| c.replace(Some(self.clone())));
        Entered { previous }
    }
}

const MB: u64 = 1024 * 1024;

thread_local! {
    /// The flag of the render running on this thread, if any.
    static CURRENT: RefCell<Option<Cancel>> = const { RefCell::new(None) };
}

/// While it lives, [`checkpoint`] on this thread consults a flag (see
/// [`Cancel::enter`]).
pub(crate) struct Entered {
    previous: Option<Cancel>,
}

impl Drop for Entered {
    fn drop(&mut self) {
        let previous = self.previous.take();
        CURRENT.with(|c| *c.borrow_mut() = previous);
    }
}

/// [`Cancel::check`] of the work on this thread ([`Cancel::enter`]); work
/// outside one is never called off. A few nanoseconds: for the inside of
/// long loops.
pub(crate) fn checkpoint() -> Result<()> {
    CURRENT.with(|c| match &*c.borrow() {
        Some(cancel) => cancel.check(),
        None => Ok(()),
    })
}

/// Whether the work on this thread was called off (its flag raised; the
/// memory is not read): for a loop that cannot return an error, which
/// stops early instead — its output is thrown away, as the work checks
/// its flag ([`Cancel::check`]) after it.
pub(crate) fn called_off() -> bool {
    CURRENT.with(|c| c.borrow().as_ref().is_some_and(Cancel::is_raised))
}

/// The process's peak resident memory, in bytes, since it started or
/// since [`reset_peak`], where the system says (Linux's
/// `/proc/self/status`, `VmHWM`, in kB: no page size to know).
pub(crate) fn peak_resident_bytes() -> Option<u64> {
    let status = std::fs::read_to_string("/proc/self/status").ok()?;
    let line = status.lines().find(|l| l.starts_with("VmHWM:"))?;
    let kb: u64 = line.split_whitespace().nth(1)?.parse().ok()?;
    Some(kb.saturating_mul(1024))
}

/// Starts the peak of [`peak_resident_bytes`] again from what the process
/// holds now (`5` written to `/proc/self/clear_refs`, Linux 4.0 on); where
/// that cannot be done, the peak counts from the start.
fn reset_peak() {
    // Without it the budget is stricter, never looser: nothing to report.
    let _ = std::fs::write("/proc/self/clear_refs", "5");
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_checkpoint_answers_for_the_flag_entered_on_its_thread_only() {
        assert!(checkpoint().is_ok());
        let cancel = Cancel::default();
        {
            let _entered = cancel.enter();
            assert!(checkpoint().is_ok());
            cancel.raise();
            assert!(matches!(checkpoint(), Err(Error::Cancelled)));
            // Another thread's work is not this flag's.
            assert!(std::thread::spawn(checkpoint).join().unwrap().is_ok());
        }
        assert!(checkpoint().is_ok(), "the guard dropped, no flag");
    }

    #[test]
    fn past_the_memory_budget_the_work_stops_with_its_figures() {
        let Some(resident) = peak_resident_bytes() else {
            return;
        };
        // Any process holds more than a MiB.
        assert!(resident > MB, "{resident}");
        let tight = Cancel::with_memory_limit(MB);
        match tight.check() {
            Err(Error::MemoryBudget {
                limit_mb,
                resident_mb,
            }) => assert!(limit_mb == 1 && resident_mb >= 1, "{resident_mb}"),
            other => panic!("{other:?}"),
        }
        let roomy = Cancel::with_memory_limit(u64::MAX);
        assert!(roomy.check().is_ok() && roomy.check_now().is_ok());
    }
}
