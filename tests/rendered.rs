//! Every built-in template rendered once per test binary, for the modules
//! that check all of them (`compat`, `determinism`, `golden`, `pen_stage`,
//! `snapshots`). Rendering every template is most of what these tests
//! cost, and four of those modules rendered the same plotted templates,
//! each for itself.
//!
//! Each kind of render is built on first use, the templates spread over
//! one thread per core (tests waiting for it would otherwise wait for one
//! core to do all the work), and kept, in the order of
//! [`templates::ALL`], until the binary exits. A template that fails to
//! render fails every test that asks for the renders, naming it.
//!
//! Tests that check that rendering is repeatable (determinism) still make
//! the second render themselves: a cached render is compared with a fresh
//! one, never with itself.

use std::num::NonZeroUsize;
use std::sync::atomic::{AtomicUsize, Ordering};
use std::sync::OnceLock;

use moyo::project::{self, Rendered};
use moyo::templates::{self, Template};

/// Every template as `moyo render --template` draws it
/// ([`Template::render`]: the plot stages and the pen stage, one layer per
/// pen).
pub(crate) fn plotted() -> &'static [(&'static Template, Rendered)] {
    static PLOTTED: OnceLock<Vec<(&'static Template, Rendered)>> = OnceLock::new();
    PLOTTED.get_or_init(|| {
        every_template(|t| t.render().unwrap_or_else(|e| panic!("{}: {e}", t.name)))
    })
}

/// Every template as the studio draws it ([`project::render_for_editing`]:
/// without the pen stage, the description's layers, groups and ids kept).
pub(crate) fn for_editing() -> &'static [(&'static Template, Rendered)] {
    static EDITING: OnceLock<Vec<(&'static Template, Rendered)>> = OnceLock::new();
    EDITING.get_or_init(|| {
        every_template(|t| {
            let spec = t.spec().unwrap_or_else(|e| panic!("{}: {e}", t.name));
            let library = t.library().unwrap_or_else(|e| panic!("{}: {e}", t.name));
            project::render_for_editing(&spec, &library, &mut |_| {}, &project::Cancel::default())
                .unwrap_or_else(|e| panic!("{}: {e}", t.name))
        })
    })
}

/// `render` of every template, on one thread per core, in the order of
/// [`templates::ALL`]. A panic in a worker is raised again here, with its
/// own message.
fn every_template(
    render: impl Fn(&'static Template) -> Rendered + Sync,
) -> Vec<(&'static Template, Rendered)> {
    let next = AtomicUsize::new(0);
    let workers = std::thread::available_parallelism().map_or(1, NonZeroUsize::get);
    let mut renders: Vec<Option<Rendered>> = templates::ALL.iter().map(|_| None).collect();
    std::thread::scope(|scope| {
        let handles: Vec<_> = (0..workers)
            .map(|_| {
                scope.spawn(|| {
                    let mut done = Vec::new();
                    loop {
                        let i = next.fetch_add(1, Ordering::Relaxed);
                        let Some(t) = templates::ALL.get(i) else {
                            return done;
                        };
                        done.push((i, render(t)));
                    }
                })
            })
            .collect();
        for handle in handles {
            let done = handle
                .join()
                .unwrap_or_else(|panic| std::panic::resume_unwind(panic));
            for (i, rendered) in done {
                renders[i] = Some(rendered);
            }
        }
    });
    templates::ALL
        .iter()
        .zip(renders)
        .map(|(t, r)| (t, r.expect("every template rendered")))
        .collect()
}
