//! `moyo studio`: a live design page served on this machine. The page
//! (built into the binary: no Node, no build step, no network) shows the
//! preview, the description as a form of its own fields with their
//! ranges and as raw TOML, and the errors as the command line words them;
//! every change it makes is a change of the description, rendered again
//! in the background through the same library as `moyo render`.
//!
//! The HTTP API the page uses is documented in the README ("The studio").
//! It is safe by default: it listens on 127.0.0.1, answers 403 to a
//! request whose `Host` or `Origin` is not the address it serves (so a web
//! page elsewhere cannot reach it through DNS rebinding), reads and writes
//! only inside the folder it was started in, and limits what a request
//! may send.

mod api;
mod edit;
mod folder;
mod gesture;
mod pen;
mod session;

use std::net::SocketAddr;
use std::path::PathBuf;
use std::sync::Arc;

use crate::error::{Error, Result};

pub use api::MAX_BODY;

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
}

/// A studio listening for the page (see the module docs).
pub struct Studio {
    addr: SocketAddr,
    runtime: tokio::runtime::Runtime,
    stop: Option<tokio::sync::oneshot::Sender<()>>,
    served: Option<tokio::task::JoinHandle<std::io::Result<()>>>,
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
        let runtime = tokio::runtime::Builder::new_multi_thread()
            .worker_threads(2)
            .enable_io()
            .build()
            .map_err(|e| Error::io("studio", e))?;
        let folder = folder::Folder::new(&options.folder)?;
        let listener = runtime
            .block_on(tokio::net::TcpListener::bind(options.addr))
            .map_err(|e| Error::io(options.addr.to_string(), e))?;
        let addr = listener
            .local_addr()
            .map_err(|e| Error::io(options.addr.to_string(), e))?;
        let session = Arc::new(session::Session::new(options.text.clone(), folder));
        // The first render, before the page can ask: its error, if any,
        // shows on the page.
        let _ = session.apply(options.text, session::Move::Edit);
        let router = api::router(session, addr);
        let (stop, stopped) = tokio::sync::oneshot::channel::<()>();
        let served = runtime.spawn(async move {
            axum::serve(listener, router)
                .with_graceful_shutdown(async {
                    let _ = stopped.await;
                })
                .await
        });
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
                Ok(result) => result.map_err(|e| Error::io(self.addr.to_string(), e)),
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
