//! The studio's HTTP API and what stands in front of it: the guard
//! (`Host`, `Origin`, `Sec-Fetch-Site`), the body's size and deadline,
//! and `X-Content-Type-Options: nosniff` on every answer. Every answer
//! about a description that does not work is 422 with the error as JSON
//! (`{"error", "path", "line", "column"}`), worded as the command line
//! words it (a render past the studio's memory is one); an edit that a
//! newer one replaced is 409. Everything that costs in proportion to the
//! description — parsing it, rendering, listing its fields and handles,
//! reading and writing files — runs off the server's threads
//! ([`off_thread`]), so that a heavy request cannot hold the others.

use std::net::{IpAddr, SocketAddr};
use std::sync::{Arc, Mutex};
use std::time::Duration;

use axum::body::{Body, Bytes};
use axum::extract::{DefaultBodyLimit, Query, Request, State};
use axum::http::{header, HeaderMap, HeaderValue, StatusCode};
use axum::middleware::{self, Next};
use axum::response::{IntoResponse, Response};
use axum::routing::{get, patch, post};
use axum::{Json, Router};
use serde::Deserialize;
use serde_json::{json, Value};

use super::edit::Edit;
use super::folder;
use super::gesture;
use super::pen::Stroke;
use super::session::{Good, Move, Session};
use crate::error::Error;
use crate::output::write_atomic;
use crate::project::{plot_scene, PlotFormat, PlotJob};
use crate::spec::field::{booleans, choices, number_at, point_lists, value_at, xy};

/// The most bytes a request may send (a description, a field change).
pub const MAX_BODY: usize = 4 * 1024 * 1024;

/// The largest PNG the studio exports, in pixels (40 megapixels: an A0
/// page at 150 dpi); a larger one is refused with 422 before any is
/// drawn.
pub const MAX_EXPORT_PIXELS: f64 = 40e6;

/// The page, built in.
const PAGE: &str = include_str!("page.html");

#[derive(Clone)]
pub(super) struct App {
    pub(super) session: Arc<Session>,
    /// The address the studio listens on: the `Host` it answers to.
    addr: SocketAddr,
    /// The stroke being drawn with the page's pen.
    pub(super) stroke: Arc<Mutex<Option<Stroke>>>,
}

/// The routes, behind the guard, for the studio listening on `addr`;
/// a request's body must come within `body_timeout`.
pub(super) fn router(session: Arc<Session>, addr: SocketAddr, body_timeout: Duration) -> Router {
    let app = App {
        session,
        addr,
        stroke: Arc::new(Mutex::new(None)),
    };
    Router::new()
        .route("/", get(page))
        .route("/api/scene", get(scene).put(put_scene))
        .route("/api/svg", get(svg))
        .route("/api/preview", get(preview))
        .route("/api/state", get(state))
        .route("/api/fields", get(fields))
        .route("/api/field", patch(patch_field))
        .route("/api/fields", patch(patch_fields))
        .route("/api/handles", get(handles))
        .route("/api/undo", post(undo))
        .route("/api/redo", post(redo))
        .route("/api/save", post(save))
        .route("/api/open", post(open))
        .route("/api/export", get(export))
        .merge(gesture::routes())
        // Past the router's own default (2 MB); `read_body` has already
        // held the body to this.
        .layer(DefaultBodyLimit::max(MAX_BODY))
        .layer(middleware::from_fn_with_state(body_timeout, read_body))
        .layer(middleware::from_fn_with_state(app.clone(), guard))
        .layer(middleware::map_response(nosniff))
        .with_state(app)
}

/// Every answer, refusals and errors included: a browser must take it as
/// the type it says (an SVG or a description is never run as a script).
async fn nosniff(mut response: Response) -> Response {
    response.headers_mut().insert(
        header::X_CONTENT_TYPE_OPTIONS,
        HeaderValue::from_static("nosniff"),
    );
    response
}

/// 403 for a request whose `Host` is not the studio's address, whose
/// `Origin` (sent by browsers) is not the studio's own page, or, but for
/// the page itself, that a browser says comes from another site.
async fn guard(State(app): State<App>, request: Request, next: Next) -> Response {
    let headers = request.headers();
    let host = headers.get(header::HOST).and_then(|h| h.to_str().ok());
    if !host.is_some_and(|h| names_studio(h, app.addr)) {
        return (
            StatusCode::FORBIDDEN,
            "forbidden: not this studio's address",
        )
            .into_response();
    }
    if let Some(origin) = headers.get(header::ORIGIN) {
        let ok = origin.to_str().ok().is_some_and(|o| {
            o.strip_prefix("http://")
                .is_some_and(|h| names_studio(h, app.addr))
        });
        if !ok {
            return (StatusCode::FORBIDDEN, "forbidden: not this studio's page").into_response();
        }
    }
    // A GET from an image or a link on another site carries no `Origin`
    // but, in today's browsers, `Sec-Fetch-Site`: without this, any page
    // could have the studio export (or read) the design. `none` is the
    // designer typing the address; the page itself may be opened from
    // anywhere, it does nothing until used.
    if request.uri().path() != "/" {
        if let Some(site) = headers.get("sec-fetch-site") {
            if !(site == "same-origin" || site == "none") {
                return (
                    StatusCode::FORBIDDEN,
                    "forbidden: a request from another site",
                )
                    .into_response();
            }
        }
    }
    next.run(request).await
}

/// Whether `host` (a `Host` header, or an `Origin` without its scheme)
/// names the studio listening on `addr`: its port (80 when none is
/// written), and its address — any loopback name for a studio on a
/// loopback address, and any address of the machine, or `localhost`,
/// for one listening on all of them (`0.0.0.0`, `::`). A name other than
/// `localhost` never does: a page elsewhere could make it lead here
/// (DNS rebinding).
fn names_studio(host: &str, addr: SocketAddr) -> bool {
    let (name, port) = match host.strip_prefix('[') {
        // `[::1]:7878`
        Some(rest) => match rest.split_once(']') {
            Some((name, port)) => (name, port),
            None => return false,
        },
        None => match host.rsplit_once(':') {
            Some((name, port)) => (name, port),
            None => (host, ""),
        },
    };
    let port = match port {
        "" => 80,
        port => match port.strip_prefix(':').unwrap_or(port).parse::<u16>() {
            Ok(port) => port,
            Err(_) => return false,
        },
    };
    if port != addr.port() {
        return false;
    }
    let listening = addr.ip();
    if name.eq_ignore_ascii_case("localhost") {
        return listening.is_loopback() || listening.is_unspecified();
    }
    match name.parse::<IpAddr>() {
        Ok(ip) => {
            ip == listening
                || (ip.is_loopback() && listening.is_loopback())
                // A studio on every address: the one the request came to
                // is one of the machine's (and only the studio serves
                // pages at that address and port).
                || listening.is_unspecified()
        }
        Err(_) => false,
    }
}

/// Reads the body whole before the route sees it, within `timeout` and
/// [`MAX_BODY`]: a client that sends its headers and then stalls, or
/// trickles, is answered 408 rather than holding the connection.
async fn read_body(State(timeout): State<Duration>, request: Request, next: Next) -> Response {
    use http_body_util::{BodyExt, LengthLimitError, Limited};
    let (parts, body) = request.into_parts();
    let limited = Limited::new(body, MAX_BODY);
    let bytes = match tokio::time::timeout(timeout, limited.collect()).await {
        Ok(Ok(collected)) => collected.to_bytes(),
        Ok(Err(e)) if e.is::<LengthLimitError>() => {
            return (
                StatusCode::PAYLOAD_TOO_LARGE,
                format!("the body is larger than {MAX_BODY} bytes"),
            )
                .into_response()
        }
        Ok(Err(e)) => {
            return (
                StatusCode::BAD_REQUEST,
                format!("the body could not be read: {e}"),
            )
                .into_response()
        }
        Err(_) => {
            return (
                StatusCode::REQUEST_TIMEOUT,
                format!("the body did not come within {} s", timeout.as_secs_f64()),
            )
                .into_response()
        }
    };
    next.run(Request::from_parts(parts, Body::from(bytes)))
        .await
}

async fn page() -> Response {
    (
        [
            (header::CONTENT_TYPE, "text/html; charset=utf-8"),
            (header::CACHE_CONTROL, "no-store"),
            (
                header::CONTENT_SECURITY_POLICY,
                "default-src 'self'; script-src 'self' 'unsafe-inline'; \
                 style-src 'self' 'unsafe-inline'; img-src 'self' data: blob:",
            ),
        ],
        PAGE,
    )
        .into_response()
}

/// The error as JSON, with the status it calls for.
pub(super) fn failure(e: &Error) -> Response {
    let status = match e {
        Error::Cancelled => StatusCode::CONFLICT,
        _ => StatusCode::UNPROCESSABLE_ENTITY,
    };
    (status, Json(error_fields(e))).into_response()
}

fn svg_response(svg: &str, app: &App) -> Response {
    let (undo, redo) = app.session.history();
    let mut response = (
        [(header::CONTENT_TYPE, "image/svg+xml; charset=utf-8")],
        svg.to_string(),
    )
        .into_response();
    let headers = response.headers_mut();
    headers.insert("x-moyo-undo", HeaderValue::from(undo));
    headers.insert("x-moyo-redo", HeaderValue::from(redo));
    response
}

/// Runs `work` on the blocking pool, off the server's threads: a
/// description of up to [`MAX_BODY`] takes time to parse, and a render
/// far more. Its error is answered as [`failure`] says; a panic (none is
/// known) is 500.
pub(super) async fn off_thread<T: Send + 'static>(
    work: impl FnOnce() -> Result<T, Error> + Send + 'static,
) -> Result<T, Response> {
    match tokio::task::spawn_blocking(work).await {
        Ok(Ok(t)) => Ok(t),
        Ok(Err(e)) => Err(failure(&e)),
        Err(e) => Err((
            StatusCode::INTERNAL_SERVER_ERROR,
            format!("the work failed: {e}"),
        )
            .into_response()),
    }
}

/// Renders `text` off the server's threads.
pub(super) async fn apply(app: &App, text: String, direction: Move) -> Result<Arc<Good>, Response> {
    let session = Arc::clone(&app.session);
    off_thread(move || session.apply(text, direction)).await
}

/// The design after a change the page did not write itself: its text,
/// preview and history.
pub(super) fn changed(app: &App, good: &Good) -> Response {
    let (undo, redo) = app.session.history();
    Json(json!({
        "scene": good.text,
        "preview": good.preview,
        "undo": undo,
        "redo": redo,
    }))
    .into_response()
}

async fn scene(State(app): State<App>) -> Response {
    (
        [(header::CONTENT_TYPE, "application/toml; charset=utf-8")],
        app.session.text(),
    )
        .into_response()
}

#[derive(Deserialize)]
struct ViewQuery {
    /// `preview` for the colour preview instead of the plot SVG.
    view: Option<String>,
}

async fn put_scene(State(app): State<App>, Query(q): Query<ViewQuery>, body: Bytes) -> Response {
    let text = match String::from_utf8(body.to_vec()) {
        Ok(text) => text,
        Err(e) => {
            return failure(&Error::Parse {
                at: None,
                field: None,
                message: format!("the description is not UTF-8 text: {}", e.utf8_error()),
            })
        }
    };
    match apply(&app, text, Move::Edit).await {
        Ok(good) if q.view.as_deref() == Some("preview") => svg_response(&good.preview, &app),
        Ok(good) => plot_svg_response(&good, &app).await,
        Err(response) => response,
    }
}

pub(super) fn nothing_rendered() -> Response {
    (
        StatusCode::NOT_FOUND,
        Json(json!({"error": "no description has rendered yet"})),
    )
        .into_response()
}

async fn svg(State(app): State<App>) -> Response {
    match app.session.good() {
        Some(good) => plot_svg_response(&good, &app).await,
        None => nothing_rendered(),
    }
}

/// What `moyo render` writes for the design.
async fn plot_svg_response(good: &Arc<Good>, app: &App) -> Response {
    match plot_svg(Arc::clone(good)).await {
        Ok(svg) => svg_response(&svg, app),
        Err(response) => response,
    }
}

/// What `moyo render` writes for the design, made off the server's
/// threads (the pen stage runs once per design).
async fn plot_svg(good: Arc<Good>) -> Result<String, Response> {
    off_thread(move || good.plotted().map(|p| p.svg.clone())).await
}

async fn preview(State(app): State<App>) -> Response {
    match app.session.good() {
        Some(good) => svg_response(&good.preview, &app),
        None => nothing_rendered(),
    }
}

async fn state(State(app): State<App>) -> Response {
    let (undo, redo) = app.session.history();
    let text = app.session.text();
    let good = app.session.good();
    let current = good.as_ref().is_some_and(|g| g.text == text);
    let refused = app.session.refused();
    let error = if current {
        Value::Null
    } else {
        // Say again what is wrong with the text as written (parsed off
        // the server's threads: it may be megabytes), or what refused it.
        let parsed = off_thread(move || {
            Ok(crate::spec::ValidSpec::parse(&text, crate::spec::Format::Toml).err())
        })
        .await;
        match parsed {
            Ok(Some(e)) => error_fields(&e),
            Ok(None) => refused.map_or(
                Value::Null,
                |message| json!({"error": message, "path": null, "line": null, "column": null}),
            ),
            Err(response) => return response,
        }
    };
    Json(json!({
        "undo": undo,
        "redo": redo,
        "rendered": current,
        "error": error,
        "folder": app.session.folder().root().display().to_string(),
    }))
    .into_response()
}

/// `{"error", "path", "line", "column"}` of an error; the message is the
/// command line's, the rest is null where unknown.
fn error_fields(e: &Error) -> Value {
    let (at, field) = match e {
        Error::Parse { at, field, .. } => (*at, field.clone()),
        Error::Invalid { at, field, .. } => (*at, Some(field.clone())),
        _ => (None, None),
    };
    json!({
        "error": e.to_string(),
        "path": field,
        "line": at.map(|a| a.line),
        "column": at.map(|a| a.column),
    })
}

/// Every field of the last good description the form shows: each number
/// with its range (`"kind": "number"`), each `true`/`false` (`"bool"`),
/// each text that takes one of a few words, with them (`"choice"`).
async fn fields(State(app): State<App>) -> Response {
    let Some(good) = app.session.good() else {
        return nothing_rendered();
    };
    let listed = off_thread(move || {
        let value = &good.value;
        let mut seen = std::collections::BTreeSet::new();
        let mut list: Vec<Value> = good
            .spec
            .ranges()
            .into_iter()
            // A field checked twice (a margin on each side) is listed once.
            .filter(|r| seen.insert(r.field.clone()))
            .map(|r| {
                let now = number_at(value, &r.field);
                // Whole-number bounds are written exactly (a seed's
                // 2⁶³−1 has no float); a reader in JavaScript gets the
                // nearest float, and the text for showing it.
                let (lo, hi, text) = match r.exact {
                    Some([lo, hi]) => (json!(lo), json!(hi), format!("{lo} – {hi}")),
                    None => (json!(r.lo), json!(r.hi), format!("{} – {}", r.lo, r.hi)),
                };
                json!({"field": r.field, "kind": "number", "lo": lo, "hi": hi,
                       "range": text, "integer": r.integer, "value": now})
            })
            .collect();
        list.extend(
            booleans(value)
                .into_iter()
                .map(|(field, b)| json!({"field": field, "kind": "bool", "value": b})),
        );
        list.extend(choices(value).into_iter().map(
            |c| json!({"field": c.field, "kind": "choice", "value": c.value, "options": c.options}),
        ));
        Ok(list)
    })
    .await;
    match listed {
        Ok(list) => Json(list).into_response(),
        Err(response) => response,
    }
}

#[derive(Deserialize)]
struct FieldChange {
    field: String,
    /// A number, `true`/`false` or a word.
    value: Value,
    /// A number written as a whole number.
    #[serde(default)]
    integer: bool,
}

async fn patch_field(State(app): State<App>, Json(change): Json<FieldChange>) -> Response {
    edit_fields(&app, vec![change]).await
}

#[derive(Deserialize)]
struct FieldChanges {
    changes: Vec<FieldChange>,
}

/// Several numbers changed as one edit (both coordinates of a dragged
/// point).
async fn patch_fields(State(app): State<App>, Json(request): Json<FieldChanges>) -> Response {
    edit_fields(&app, request.changes).await
}

async fn edit_fields(app: &App, changes: Vec<FieldChange>) -> Response {
    let text = app.session.text();
    let written = off_thread(move || {
        let mut edit = Edit::parse(&text)?;
        for change in &changes {
            match &change.value {
                Value::Number(n) => {
                    let n = n.as_f64().unwrap_or(f64::NAN);
                    edit.set_number(&change.field, n, change.integer)?;
                }
                Value::Bool(b) => edit.set(&change.field, *b)?,
                Value::String(word) => edit.set(&change.field, word.as_str())?,
                _ => {
                    return Err(Error::invalid(
                        &change.field,
                        "give a number, true or false, or a word",
                    ))
                }
            }
        }
        Ok(edit.text())
    })
    .await;
    let text = match written {
        Ok(text) => text,
        Err(response) => return response,
    };
    match apply(app, text, Move::Edit).await {
        Ok(good) => changed(app, &good),
        Err(response) => response,
    }
}

/// The keys whose lists of points are places on the page (millimetres
/// inside the margins): the flow and region lines, tree centre lines,
/// strokes, guides, polygons and zentangle strings. Other lists of pairs
/// (a Tree8 base curve, in trunk lengths) are not.
const PLACES: [&str; 8] = [
    "upper", "lower", "centre", "at", "along", "points", "polygon", "lines",
];

/// Every line of points on the page the designer can drag, with the
/// offset of the area inside the margins. A line whose points are those
/// of another (a pattern pinned in two tables) is not listed again: the
/// first names it in `"also"`, so that a drag moves both. Sites are not
/// `"joined"` by a line.
async fn handles(State(app): State<App>) -> Response {
    let Some(good) = app.session.good() else {
        return nothing_rendered();
    };
    match off_thread(move || Ok(handles_of(&good))).await {
        Ok(handles) => Json(handles).into_response(),
        Err(response) => response,
    }
}

/// What `GET /api/handles` answers for `good`.
fn handles_of(good: &Good) -> Value {
    let value = &good.value;
    let mut lines: Vec<(String, Vec<[f64; 2]>, Vec<String>)> = Vec::new();
    for field in point_lists(value) {
        let last = field.rsplit('.').next().unwrap_or(&field);
        let key = last.split('[').next().unwrap_or(last);
        if !PLACES.contains(&key) {
            continue;
        }
        let Some(list) = value_at(value, &field).and_then(toml::Value::as_array) else {
            continue;
        };
        let points: Vec<[f64; 2]> = list.iter().filter_map(xy).collect();
        match lines.iter_mut().find(|(_, p, _)| *p == points) {
            Some((_, _, also)) => also.push(field),
            None => lines.push((field, points, Vec::new())),
        }
    }
    let lines: Vec<Value> = lines
        .into_iter()
        .map(|(field, points, also)| {
            let joined = !field.ends_with("sites.points");
            json!({"field": field, "points": points, "also": also, "joined": joined})
        })
        .collect();
    let margins = good.spec.page().margins;
    json!({"offset": [margins.left, margins.top], "lines": lines})
}

async fn step(app: App, direction: Move) -> Response {
    let Some(text) = app.session.step(direction) else {
        let what = if direction == Move::Undo {
            "undo"
        } else {
            "redo"
        };
        return (
            StatusCode::CONFLICT,
            Json(json!({"error": format!("nothing to {what}")})),
        )
            .into_response();
    };
    match apply(&app, text, direction).await {
        Ok(good) => changed(&app, &good),
        Err(response) => response,
    }
}

async fn undo(State(app): State<App>) -> Response {
    step(app, Move::Undo).await
}

async fn redo(State(app): State<App>) -> Response {
    step(app, Move::Redo).await
}

#[derive(Deserialize)]
struct FileRequest {
    /// A path inside the studio's folder.
    path: String,
}

/// Writes the description (`.toml`, as written) or the SVG (`.svg`, the
/// last good render, with its description embedded), off the server's
/// threads, over a regular file or none.
async fn save(State(app): State<App>, Json(request): Json<FileRequest>) -> Response {
    let bytes = if request.path.ends_with(".toml") {
        app.session.text().into_bytes()
    } else if request.path.ends_with(".svg") {
        let Some(good) = app.session.good() else {
            return nothing_rendered();
        };
        match plot_svg(good).await {
            Ok(svg) => svg.into_bytes(),
            Err(response) => return response,
        }
    } else {
        return failure(&Error::invalid("path", "save a .toml or an .svg file"));
    };
    let session = Arc::clone(&app.session);
    let name = request.path.clone();
    let written = off_thread(move || {
        let path = session.folder().resolve(&name, "path")?;
        folder::check_writable(&path, "path")?;
        write_atomic(&path, &bytes)
    })
    .await;
    match written {
        Ok(()) => Json(json!({"saved": request.path})).into_response(),
        Err(response) => response,
    }
}

/// Opens a description (`.toml`) or an SVG moyo wrote (its embedded
/// description) from the folder, as a new edit. The file is read off the
/// server's threads, and only a regular file is (a FIFO would never
/// end).
async fn open(State(app): State<App>, Json(request): Json<FileRequest>) -> Response {
    let session = Arc::clone(&app.session);
    let name = request.path.clone();
    let read = off_thread(move || {
        let path = session.folder().resolve(&name, "path")?;
        folder::read_text(&path).map_err(|e| Error::io(&path, e))
    })
    .await;
    let text = match read {
        Ok(text) if request.path.ends_with(".svg") => {
            match crate::scene::embedded_description(&text) {
                Some(description) => description,
                None => {
                    return failure(&Error::invalid(
                        "path",
                        format!("{} carries no scene description", request.path),
                    ))
                }
            }
        }
        Ok(text) => text,
        Err(response) => return response,
    };
    match apply(&app, text, Move::Edit).await {
        Ok(good) => changed(&app, &good),
        Err(response) => response,
    }
}

#[derive(Deserialize)]
struct ExportQuery {
    /// `png`, `gcode` or `hpgl`.
    format: String,
    /// PNG resolution (default 96).
    dpi: Option<f64>,
}

/// [`Error::Invalid`] at `dpi` when a PNG of `page` at `dpi` would have
/// more than [`MAX_EXPORT_PIXELS`]: counted from the page, before any
/// pixel is drawn.
fn check_export_size(page: &crate::units::Page, dpi: f64) -> Result<(), Error> {
    // As the PNG writer rounds each side.
    let side = |mm: f64| (mm / 25.4 * dpi).round().max(1.0);
    let (width, height) = (side(page.width), side(page.height));
    if width * height > MAX_EXPORT_PIXELS {
        return Err(Error::invalid(
            "dpi",
            format!(
                "a {width}×{height} pixel PNG at {dpi} dpi is {:.0} megapixels; \
                 the studio exports at most {:.0}: lower the dpi",
                width * height / 1e6,
                MAX_EXPORT_PIXELS / 1e6
            ),
        ));
    }
    Ok(())
}

/// The last good design as PNG, G-code or HPGL, through the same
/// pipeline as the command line.
async fn export(State(app): State<App>, Query(q): Query<ExportQuery>) -> Response {
    let Some(good) = app.session.good() else {
        return nothing_rendered();
    };
    let job = off_thread(move || -> Result<(Vec<u8>, &str, &str), Error> {
        match q.format.as_str() {
            "png" => {
                let dpi = q.dpi.unwrap_or(96.0);
                if !(10.0..=600.0).contains(&dpi) {
                    return Err(Error::invalid("dpi", format!("must be 10–600, got {dpi}")));
                }
                check_export_size(&good.rendered.scene.page, dpi)?;
                Ok((good.rendered.png(dpi)?, "image/png", "png"))
            }
            "gcode" | "hpgl" => {
                let format = if q.format == "gcode" {
                    PlotFormat::Gcode(Default::default())
                } else {
                    PlotFormat::Hpgl(Default::default())
                };
                let scene = good.plotted()?.scene.clone();
                let plotted = plot_scene(scene, &PlotJob::new(format))?;
                let extension = if q.format == "gcode" { "gcode" } else { "hpgl" };
                Ok((
                    plotted.bytes.into_bytes(),
                    "text/plain; charset=utf-8",
                    extension,
                ))
            }
            other => Err(Error::invalid(
                "format",
                format!("'{other}': export png, gcode or hpgl"),
            )),
        }
    })
    .await;
    match job {
        Ok((bytes, kind, extension)) => {
            let disposition = format!("attachment; filename=\"moyo.{extension}\"");
            let mut headers = HeaderMap::new();
            headers.insert(header::CONTENT_TYPE, HeaderValue::from_static(kind));
            if let Ok(v) = HeaderValue::from_str(&disposition) {
                headers.insert(header::CONTENT_DISPOSITION, v);
            }
            (headers, bytes).into_response()
        }
        Err(response) => response,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_studio_answers_to_its_own_names_only() {
        let loopback: SocketAddr = "127.0.0.1:7878".parse().unwrap();
        let every: SocketAddr = "0.0.0.0:7878".parse().unwrap();
        let lan: SocketAddr = "192.168.1.5:7878".parse().unwrap();
        for host in [
            "127.0.0.1:7878",
            "localhost:7878",
            "LOCALHOST:7878",
            "[::1]:7878",
        ] {
            assert!(names_studio(host, loopback), "{host}");
            assert!(names_studio(host, every), "{host}");
        }
        assert!(names_studio("192.168.1.5:7878", every));
        assert!(names_studio("192.168.1.5:7878", lan));
        assert!(!names_studio("localhost:7878", lan));
        assert!(!names_studio("127.0.0.1:7878", lan));
        for host in [
            "evil.example:7878",
            "127.0.0.1:7879",
            "127.0.0.1",
            "[::1]",
            "[::1:7878",
            "127.0.0.1:x",
            "",
        ] {
            assert!(!names_studio(host, loopback), "{host}");
            assert!(!names_studio(host, every), "{host}");
        }
        // Port 80 may go unwritten.
        let eighty: SocketAddr = "127.0.0.1:80".parse().unwrap();
        assert!(names_studio("localhost", eighty));
        assert!(names_studio("127.0.0.1:80", eighty));
    }

    #[test]
    fn a_png_past_the_cap_is_refused_by_its_page_and_dpi() {
        let a0 = crate::units::Page::sized(
            841.0,
            1189.0,
            crate::units::Orientation::Portrait,
            Default::default(),
        );
        assert!(check_export_size(&a0, 150.0).is_ok());
        let e = check_export_size(&a0, 600.0).unwrap_err().to_string();
        assert!(e.starts_with("dpi: a 19866×28087 pixel PNG"), "{e}");
    }
}
