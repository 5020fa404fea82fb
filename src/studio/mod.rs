//! `moyo studio`: a live design page served on this machine. The page
//! (built into the binary: no Node, no build step, no network) shows the
//! preview, the description as a form of its own fields with their
//! ranges and as raw TOML, and the errors as the command line words them;
//! every change it makes is a change of the description, rendered again
//! in the background through the same library as `moyo render`.
//!
//! The HTTP API the page uses is documented in docs/guide/studio.md.
//! It is safe by default: it listens on 127.0.0.1, answers 403 to a
//! request whose `Host` or `Origin` is not the address it serves, or that
//! a browser marks as coming from another site (so a web page elsewhere
//! cannot reach it, through DNS rebinding or an image or a link), marks
//! every answer `nosniff`, caps what it exports, reads and writes
//! only inside the folder it was started in (regular files only, read
//! and written off the server's threads), and limits what a request may
//! send and how long a connection may take to send it
//! ([`StudioLimits`]).

mod api;
mod edit;
mod folder;
mod gesture;
mod pen;
mod serve;
mod session;

use std::net::SocketAddr;
use std::path::PathBuf;
use std::sync::Arc;
use std::time::Duration;

use crate::error::{Error, Result};

pub use api::{MAX_BODY, MAX_EXPORT_PIXELS};
pub use pen::MAX_STROKE_POINTS;

/// The longest deadline [`StudioLimits`] takes: a day. A longer one is
/// taken as a day (no deadline past the clock's range).
const LONGEST: Duration = Duration::from_secs(24 * 60 * 60);

/// How long a connection may take and how many may be open: what keeps
/// stalled or idle connections from holding the studio.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct StudioLimits {
    /// How long a connection may take to send the head of a request (its
    /// line and headers), counted from when the studio is ready for it
    /// (a new connection, or the answer before on one kept open); past
    /// it the connection is closed. Default 10 s, at most a day.
    pub header_timeout: Duration,
    /// How long a request may take to send its body once its head is
    /// in; past it the answer is 408. Default 30 s, at most a day.
    pub body_timeout: Duration,
    /// Most connections open at once; further ones wait in the system's
    /// queue until one closes. Default 256, at least 1.
    pub connections: usize,
    /// Most bytes of memory the studio may hold (resident) while it
    /// renders an edit: past it, the render stops and the edit is refused
    /// (422, [`Error::MemoryBudget`]), the last good design staying. Read
    /// from the system (Linux) every few milliseconds at the render's
    /// long loops; elsewhere there is no such budget. Default 4 GiB:
    /// above the 2.6 GB the heaviest accepted description was measured
    /// to take (RELIABILITY.md), below what ends a desktop.
    pub memory: u64,
}

impl Default for StudioLimits {
    fn default() -> StudioLimits {
        StudioLimits {
            header_timeout: Duration::from_secs(10),
            body_timeout: Duration::from_secs(30),
            connections: 256,
            memory: 4 << 30,
        }
    }
}

impl StudioLimits {
    fn header_timeout(&self) -> Duration {
        self.header_timeout.min(LONGEST)
    }

    fn body_timeout(&self) -> Duration {
        self.body_timeout.min(LONGEST)
    }

    fn connections(&self) -> usize {
        self.connections
            .clamp(1, tokio::sync::Semaphore::MAX_PERMITS)
    }
}

/// What a studio starts from.
#[derive(Debug, Clone)]
pub struct StudioOptions {
    /// The folder it reads and writes in: the files the description
    /// names, and what the page saves and opens.
    pub folder: PathBuf,
    /// The description to start from (TOML).
    pub text: String,
    /// Where to listen; 127.0.0.1 on a free port unless told otherwise.
    pub addr: SocketAddr,
    /// Deadlines and the connection cap.
    pub limits: StudioLimits,
}

/// A studio listening for the page (see the module docs).
pub struct Studio {
    addr: SocketAddr,
    runtime: tokio::runtime::Runtime,
    stop: Option<tokio::sync::oneshot::Sender<()>>,
    served: Option<tokio::task::JoinHandle<()>>,
}

impl Studio {
    /// Starts listening on `options.addr` and renders the first design.
    /// Requests are answered on background threads until
    /// [`Studio::stop`] or [`Studio::wait`].
    ///
    /// # Errors
    /// [`Error::Io`] when the address cannot be bound or the folder does
    /// not exist.
    pub fn start(options: StudioOptions) -> Result<Studio> {
        // Timers too: the deadlines, and the pause after a failed accept.
        let runtime = tokio::runtime::Builder::new_multi_thread()
            .worker_threads(2)
            .enable_all()
            .build()
            .map_err(|e| Error::io("studio", e))?;
        let folder = folder::Folder::new(&options.folder)?;
        let listener = runtime
            .block_on(tokio::net::TcpListener::bind(options.addr))
            .map_err(|e| Error::io(options.addr.to_string(), e))?;
        let addr = listener
            .local_addr()
            .map_err(|e| Error::io(options.addr.to_string(), e))?;
        let session = Arc::new(session::Session::new(
            options.text.clone(),
            folder,
            options.limits.memory,
        ));
        // The first render, before the page can ask: its error, if any,
        // shows on the page.
        let _ = session.apply(options.text, session::Move::Edit);
        let router = api::router(session, addr, options.limits.body_timeout());
        let (stop, stopped) = tokio::sync::oneshot::channel::<()>();
        let served = runtime.spawn(serve::serve(listener, router, options.limits, stopped));
        Ok(Studio {
            addr,
            runtime,
            stop: Some(stop),
            served: Some(served),
        })
    }

    /// The address it listens on.
    pub fn addr(&self) -> SocketAddr {
        self.addr
    }

    /// The page's address.
    pub fn url(&self) -> String {
        format!("http://{}/", self.addr)
    }

    /// Serves until the process is stopped.
    ///
    /// # Errors
    /// [`Error::Io`] when the server fails.
    pub fn wait(mut self) -> Result<()> {
        match self.served.take() {
            Some(served) => match self.runtime.block_on(served) {
                Ok(()) => Ok(()),
                Err(e) => Err(Error::io(
                    self.addr.to_string(),
                    std::io::Error::other(e.to_string()),
                )),
            },
            None => Ok(()),
        }
    }

    /// Stops listening and waits for the requests under way.
    pub fn stop(mut self) {
        if let Some(stop) = self.stop.take() {
            let _ = stop.send(());
        }
        if let Some(served) = self.served.take() {
            let _ = self.runtime.block_on(served);
        }
    }
}
