//! The studio's connections: accepted up to a cap, each given a deadline
//! for the head of every request it sends, served by hyper with the
//! API's router. A failed `accept()` (the process is out of file
//! descriptors) pauses the loop instead of ending the studio. The body's
//! deadline is the API's (`api::read_body`): hyper has none.

use std::io::ErrorKind;
use std::sync::Arc;
use std::time::Duration;

use axum::Router;
use hyper::server::conn::http1;
use hyper_util::rt::{TokioIo, TokioTimer};
use hyper_util::service::TowerToHyperService;
use tokio::net::TcpListener;
use tokio::sync::{oneshot, watch, Semaphore};

use super::StudioLimits;

/// How long the loop waits after `accept()` fails for want of a resource
/// (file descriptors, memory) before it tries again: long enough not to
/// spin, short enough that a freed descriptor is soon used. The
/// connection waits in the listen queue meanwhile.
const ACCEPT_PAUSE: Duration = Duration::from_millis(100);

/// Serves `router` on `listener` until `stop` fires (or its sender is
/// dropped), then lets the requests under way finish and returns.
pub(super) async fn serve(
    listener: TcpListener,
    router: Router,
    limits: StudioLimits,
    mut stop: oneshot::Receiver<()>,
) {
    let mut http = http1::Builder::new();
    http.timer(TokioTimer::new())
        .header_read_timeout(limits.header_timeout());
    // A permit for each open connection: past the cap the loop does not
    // accept, and the connections beyond wait in the kernel's queue.
    let permits = Arc::new(Semaphore::new(limits.connections()));
    // Each connection holds a receiver: a send asks them to finish, and
    // the sender sees when the last is gone.
    let (closing, open) = watch::channel(false);
    loop {
        let permit = tokio::select! {
            biased;
            _ = &mut stop => break,
            permit = Arc::clone(&permits).acquire_owned() => match permit {
                Ok(permit) => permit,
                // Never closed while the loop runs.
                Err(_) => break,
            },
        };
        let stream = tokio::select! {
            biased;
            _ = &mut stop => break,
            accepted = listener.accept() => match accepted {
                Ok((stream, _)) => stream,
                // That one connection went away before it was taken: the
                // next is fine.
                Err(e) if matches!(
                    e.kind(),
                    ErrorKind::ConnectionAborted
                        | ErrorKind::ConnectionReset
                        | ErrorKind::ConnectionRefused
                        | ErrorKind::Interrupted
                ) => continue,
                // Out of descriptors or memory: the connections that hold
                // them end (they have deadlines), so wait and try again.
                Err(_) => {
                    tokio::select! {
                        biased;
                        _ = &mut stop => break,
                        () = tokio::time::sleep(ACCEPT_PAUSE) => continue,
                    }
                }
            },
        };
        let connection = http.serve_connection(
            TokioIo::new(stream),
            TowerToHyperService::new(router.clone()),
        );
        let mut closing = open.clone();
        tokio::spawn(async move {
            // Given back when the connection ends, however it ends.
            let _permit = permit;
            let mut connection = std::pin::pin!(connection);
            tokio::select! {
                // A connection that fails (a timeout, a malformed request)
                // is simply closed: hyper has answered what it could.
                _ = connection.as_mut() => return,
                _ = closing.changed() => {}
            }
            connection.as_mut().graceful_shutdown();
            let _ = connection.await;
        });
    }
    drop(open);
    let _ = closing.send(true);
    closing.closed().await;
}
