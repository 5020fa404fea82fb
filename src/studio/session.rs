//! The design being worked on: its description as the designer last
//! wrote it (which may not be valid), the last render that worked, and
//! the history for undo and redo. Renders run off the server's threads;
//! each new edit calls off the render before it, so only the newest edit
//! is ever waited for. A render that takes the studio past its memory
//! budget is called off the same way ([`crate::Error::MemoryBudget`]),
//! and the last good design stays.

use std::sync::{Arc, Mutex, MutexGuard, OnceLock};

use super::folder::Folder;
use crate::error::{Error, Result};
use crate::motif::Library;
use crate::project::{load_motifs_with, render_for_editing, Cancel, Rendered};
use crate::spec::{Format, ValidSpec};

/// Most undo steps kept.
const HISTORY: usize = 200;

/// A render that worked.
pub(crate) struct Good {
    /// The description it was made from.
    pub text: String,
    /// The description, validated.
    pub spec: ValidSpec,
    /// The scene with its layers, groups and ids, as the page points at
    /// it ([`crate::project::render_for_editing`]).
    pub rendered: Rendered,
    /// What a pen should draw: the render of the command line, made from
    /// `rendered` when first asked for ([`Good::plotted`]).
    plotted: OnceLock<Rendered>,
    /// The colour preview SVG.
    pub preview: String,
    /// The files it read (images, SVG paths, meshes).
    pub library: Library,
    /// The description as a TOML value, every default written out: what
    /// the form and the handles read their numbers from.
    pub value: toml::Value,
}

impl Good {
    /// What `moyo render` writes for this description: the pen stage run
    /// on [`Good::rendered`], once.
    pub(crate) fn plotted(&self) -> Result<&Rendered> {
        if let Some(plotted) = self.plotted.get() {
            return Ok(plotted);
        }
        let plotted = self.rendered.pen_ready(&self.spec)?;
        Ok(self.plotted.get_or_init(|| plotted))
    }
}

/// See the module docs.
pub(crate) struct Session {
    state: Mutex<State>,
    /// The render under way, to call off when a newer edit comes.
    running: Mutex<Arc<Cancel>>,
    folder: Folder,
    /// Most bytes of resident memory while a render runs.
    memory: u64,
}

struct State {
    text: String,
    good: Option<Arc<Good>>,
    /// Why `text` did not render, when its description is not at fault
    /// (a budget): parsing it again would not say.
    refused: Option<String>,
    undo: Vec<String>,
    redo: Vec<String>,
}

/// Which way an edit moves through the history.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum Move {
    /// A new edit: the last good description goes on the undo stack.
    Edit,
    /// Back one step: the current description goes on the redo stack.
    Undo,
    /// Forward again.
    Redo,
    /// A gesture on the page (a stroke, a click): an edit that, when its
    /// description does not render, leaves the text as it was.
    Gesture,
}

impl Session {
    /// A session on `text`, reading files in `folder`, whose renders may
    /// take the process to `memory` bytes.
    pub(crate) fn new(text: String, folder: Folder, memory: u64) -> Session {
        Session {
            state: Mutex::new(State {
                text,
                good: None,
                refused: None,
                undo: Vec::new(),
                redo: Vec::new(),
            }),
            running: Mutex::new(Arc::new(Cancel::default())),
            folder,
            memory,
        }
    }

    /// The folder the session reads and writes in.
    pub(crate) fn folder(&self) -> &Folder {
        &self.folder
    }

    fn state(&self) -> MutexGuard<'_, State> {
        // A panic while the lock was held cannot leave the state half
        // changed (every change is one assignment), so a poisoned lock is
        // still good to use.
        self.state
            .lock()
            .unwrap_or_else(std::sync::PoisonError::into_inner)
    }

    /// The description as last written.
    pub(crate) fn text(&self) -> String {
        self.state().text.clone()
    }

    /// Why the description as last written did not render, when that is
    /// not the description's fault but a budget's (its memory).
    pub(crate) fn refused(&self) -> Option<String> {
        self.state().refused.clone()
    }

    /// The last render that worked.
    pub(crate) fn good(&self) -> Option<Arc<Good>> {
        self.state().good.clone()
    }

    /// How many steps undo and redo can go.
    pub(crate) fn history(&self) -> (usize, usize) {
        let s = self.state();
        (s.undo.len(), s.redo.len())
    }

    /// The description undo (or redo) would go to, if any.
    pub(crate) fn step(&self, direction: Move) -> Option<String> {
        let s = self.state();
        match direction {
            Move::Edit | Move::Gesture => None,
            Move::Undo => s.undo.last().cloned(),
            Move::Redo => s.redo.last().cloned(),
        }
    }

    /// Renders `text` and, when it works and no newer edit came first,
    /// makes it the design; when it does not, the text is kept (as the
    /// designer wrote it) beside the last render that worked. Blocking:
    /// call it off the server's threads.
    ///
    /// # Errors
    /// The description's error, with its field and place,
    /// [`Error::Cancelled`] when a newer edit replaced this one, or
    /// [`Error::MemoryBudget`] when it took the studio past its memory.
    pub(crate) fn apply(&self, text: String, direction: Move) -> Result<Arc<Good>> {
        let cancel = Arc::new(Cancel::with_memory_limit(self.memory));
        {
            let mut running = self
                .running
                .lock()
                .unwrap_or_else(std::sync::PoisonError::into_inner);
            running.raise();
            *running = Arc::clone(&cancel);
        }
        let result = self.render(&text, &cancel);
        let mut s = self.state();
        if cancel.is_raised() {
            return Err(Error::Cancelled);
        }
        match result {
            Ok(good) => {
                let good = Arc::new(good);
                let previous = s.good.as_ref().map(|g| g.text.clone());
                match direction {
                    Move::Edit | Move::Gesture => {
                        if let Some(previous) = previous.filter(|p| *p != text) {
                            s.undo.push(previous);
                            if s.undo.len() > HISTORY {
                                s.undo.remove(0);
                            }
                            s.redo.clear();
                        }
                    }
                    Move::Undo => {
                        s.undo.pop();
                        s.redo.extend(previous);
                    }
                    Move::Redo => {
                        s.redo.pop();
                        s.undo.extend(previous);
                    }
                }
                s.text = text;
                s.good = Some(Arc::clone(&good));
                s.refused = None;
                Ok(good)
            }
            Err(e) => {
                if direction != Move::Gesture {
                    s.text = text;
                    s.refused = matches!(e, Error::MemoryBudget { .. }).then(|| e.to_string());
                }
                Err(e)
            }
        }
    }

    fn render(&self, text: &str, cancel: &Cancel) -> Result<Good> {
        // The preview's SVG, written after the render, stops too when a
        // newer edit comes (`apply` then throws it away).
        let _entered = cancel.enter();
        let spec = ValidSpec::parse(text, Format::Toml)?;
        let library = load_motifs_with(&spec, &|name| match self.folder.resolve(name, name) {
            // Regular files only: a FIFO the description names would hold
            // the render (and its thread) for ever.
            Ok(path) => match crate::input::read_regular_file(&path) {
                // A template's own files (its images) are built in.
                Err(e) if e.kind() == std::io::ErrorKind::NotFound => {
                    match crate::templates::file(name) {
                        Some(bytes) => (format!("built-in {name}"), Ok(bytes.to_vec())),
                        None => (name.to_string(), Err(e)),
                    }
                }
                read => (name.to_string(), read),
            },
            Err(e) => (
                name.to_string(),
                Err(std::io::Error::new(
                    std::io::ErrorKind::PermissionDenied,
                    e.to_string(),
                )),
            ),
        })?;
        let rendered = render_for_editing(&spec, &library, &mut |_| {}, cancel)?;
        let preview = rendered.preview_svg();
        // The preview written in full, and the memory's peak within the
        // budget, to the end.
        cancel.check_now()?;
        // Written by moyo a moment ago, so it reads back.
        let value = toml::from_str(&spec.to_toml())
            .unwrap_or_else(|_| toml::Value::Table(toml::Table::new()));
        Ok(Good {
            text: text.to_string(),
            spec,
            rendered,
            plotted: OnceLock::new(),
            preview,
            library,
            value,
        })
    }
}
