//! The page's gestures, each a plain change of the description: a stroke
//! drawn with the pen grows a sketch (live, then written as its points),
//! a click gives a zentangle region its procedure (a manual step), a
//! Voronoi table's sites are pinned (written as its `points`, which the
//! page then drags as handles), a tree, flower, leaf or plant dragged,
//! turned, scaled or hidden becomes its `[[adjust]]`, a vine's camera
//! turned round it becomes its `camera = { turn, tilt }`. What each table
//! offers to a gesture, and what the gesture writes, is its family's
//! (`crate::family::gesture`); this module routes the gestures to the
//! tables they name and lists the tables that offer each by
//! `GET /api/targets`.

use axum::extract::State;
use axum::response::{IntoResponse, Response};
use axum::routing::{get, post};
use axum::{Json, Router};
use serde::Deserialize;
use serde_json::{json, Value};

use super::api::{apply, changed, failure, nothing_rendered, off_thread, App};
use super::edit::table_index;
use super::edit::Edit;
use super::pen::{Stroke, Target};
use super::session::{Good, Move};
use crate::error::Error;
use crate::family::gesture::{tenth, Gesture, Gestures};
use crate::spec::SceneSpec;

/// The gestures' routes.
pub(super) fn routes() -> Router<App> {
    Router::new()
        .route("/api/targets", get(targets))
        .route("/api/stroke/begin", post(stroke_begin))
        .route("/api/stroke/extend", post(stroke_extend))
        .route("/api/stroke/end", post(stroke_end))
        .route("/api/fill", post(fill))
        .route("/api/pin", post(pin))
        .route("/api/adjust", post(adjust))
        .route("/api/orbit", post(orbit))
}

/// What the gestures can work on in the last good design: the layers (a
/// new sketch goes in one) and, for each gesture, the tables that offer
/// it with what the page shows of each (whether a Voronoi table is
/// pinned, whether a vine's camera turns).
async fn targets(State(app): State<App>) -> Response {
    let Some(good) = app.session.good() else {
        return nothing_rendered();
    };
    match off_thread(move || Ok(targets_of(&good))).await {
        Ok(targets) => Json(targets).into_response(),
        Err(response) => response,
    }
}

/// What `GET /api/targets` answers for `good`.
fn targets_of(good: &Good) -> Value {
    let spec = good.spec.spec();
    let scene = &good.rendered.scene;
    let mut lists = serde_json::Map::new();
    for gesture in Gesture::ALL {
        lists.insert(gesture.list().into(), Value::Array(Vec::new()));
    }
    let layers: Vec<Value> = spec
        .layers
        .iter()
        .enumerate()
        .map(|(l, layer)| {
            let layer_id = scene.layers.get(l).map_or("", |s| s.id.as_str());
            for item in layer.items() {
                let Some(gestures) = item.table.family().gestures() else {
                    continue;
                };
                for (gesture, facts) in gestures.offers() {
                    let mut target = json!({
                        "field": format!("layers[{l}].{}", item.field),
                        "label": format!("{} · {}", layer.name, item.id),
                        // The group the table's drawing is in the preview.
                        "group": format!("{layer_id}.{}", item.id),
                    });
                    if let (Some(target), Value::Object(facts)) = (target.as_object_mut(), facts) {
                        target.extend(facts);
                    }
                    if let Some(Value::Array(list)) = lists.get_mut(gesture.list()) {
                        list.push(target);
                    }
                }
            }
            json!({"index": l, "name": layer.name})
        })
        .collect();
    lists.insert("layers".into(), Value::Array(layers));
    Value::Object(lists)
}

/// The table at `field` (`layers[0].zentangle[1]`) of `spec` when it
/// offers `gesture`.
fn offering<'a>(spec: &'a SceneSpec, field: &str, gesture: Gesture) -> Option<&'a dyn Gestures> {
    spec.layers.iter().enumerate().find_map(|(l, layer)| {
        layer
            .items()
            .into_iter()
            .find(|item| format!("layers[{l}].{}", item.field) == field)
            .and_then(|item| item.table.family().gestures())
            .filter(|g| g.offers().iter().any(|(o, _)| *o == gesture))
    })
}

#[derive(Deserialize)]
struct Begin {
    /// The sketch table's field path, or none for a new sketch.
    target: Option<String>,
    /// For a new sketch: the layer's index (default: the last).
    layer: Option<usize>,
    /// The first point, scene mm.
    at: [f64; 2],
}

#[derive(Deserialize)]
struct Extend {
    points: Vec<[f64; 2]>,
}

/// Runs `work` on the stroke off the server's threads (growing and
/// drawing a sketch takes time in proportion to its size).
async fn with_stroke<T: Send + 'static>(
    app: &App,
    work: impl FnOnce(&mut Option<Stroke>) -> Result<T, Error> + Send + 'static,
) -> Result<T, Response> {
    let stroke = std::sync::Arc::clone(&app.stroke);
    off_thread(move || {
        let mut stroke = stroke
            .lock()
            .unwrap_or_else(std::sync::PoisonError::into_inner);
        work(&mut stroke)
    })
    .await
}

/// A gesture's new description, written by `edit` off the server's
/// threads (it parses the description, which may be megabytes) and
/// rendered as one edit; where it does not render, the description stays
/// as it was.
async fn write(
    app: &App,
    edit: impl FnOnce() -> Result<String, Error> + Send + 'static,
) -> Response {
    let text = match off_thread(edit).await {
        Ok(text) => text,
        Err(response) => return response,
    };
    match apply(app, text, Move::Gesture).await {
        Ok(good) => changed(app, &good),
        Err(response) => response,
    }
}

fn no_stroke() -> Error {
    Error::invalid("stroke", "no stroke is being drawn: begin one first")
}

/// Starts a stroke: `{"target": field | null, "layer": i, "at": [x, y]}`.
async fn stroke_begin(State(app): State<App>, Json(begin): Json<Begin>) -> Response {
    let Some(good) = app.session.good() else {
        return nothing_rendered();
    };
    let target = match begin.target {
        Some(field) => Target::Table(field),
        None => Target::New(
            begin
                .layer
                .unwrap_or_else(|| good.spec.spec().layers.len().saturating_sub(1)),
        ),
    };
    let started = with_stroke(&app, move |stroke| {
        let (new, growth) = Stroke::begin(&good, target, begin.at)?;
        *stroke = Some(new);
        Ok(growth)
    })
    .await;
    match started {
        Ok(growth) => Json(growth).into_response(),
        Err(response) => response,
    }
}

/// More of the stroke: `{"points": [[x, y], …]}`; answers what grew.
async fn stroke_extend(State(app): State<App>, Json(more): Json<Extend>) -> Response {
    let grown = with_stroke(&app, move |stroke| {
        stroke.as_mut().ok_or_else(no_stroke)?.extend(&more.points)
    })
    .await;
    match grown {
        Ok(growth) => Json(growth).into_response(),
        Err(response) => response,
    }
}

/// The pen lifts: the stroke is written into the description and the
/// design renders (one step of the history).
async fn stroke_end(State(app): State<App>) -> Response {
    // The stroke began on the last good design: it goes into that.
    let Some(good) = app.session.good() else {
        return nothing_rendered();
    };
    let text = good.text.clone();
    let written = with_stroke(&app, move |stroke| {
        stroke.take().ok_or_else(no_stroke)?.finish(&text)
    })
    .await;
    match written {
        Ok(text) => write(&app, move || Ok(text)).await,
        Err(response) => response,
    }
}

#[derive(Deserialize)]
struct Fill {
    /// The zentangle table's field path.
    target: String,
    /// The click, scene mm.
    at: [f64; 2],
    /// The procedure: 0–19 the paper's, 20–31 the named tangles.
    procedure: u32,
}

/// A click in a zentangle fill: the white region under it gets the
/// procedure, as a manual step — after the table's automatic steps when
/// it has any (a touch-up of the tile the designer sees), from the blank
/// tile on when it has none. A click where no white region is changes
/// nothing (422, saying why).
async fn fill(State(app): State<App>, Json(click): Json<Fill>) -> Response {
    let Some(good) = app.session.good() else {
        return nothing_rendered();
    };
    let [x, y] = click.at;
    if !(x.is_finite() && y.is_finite()) {
        return failure(&Error::invalid("at", "the click is not a finite point"));
    }
    write(&app, move || {
        let table = offering(good.spec.spec(), &click.target, Gesture::Fill).ok_or_else(|| {
            Error::invalid(&click.target, "is not a zentangle fill of the design")
        })?;
        let changes = table.click(&click.target, click.at, click.procedure)?;
        Edit::with_changes(&good.text, changes)
    })
    .await
}

#[derive(Deserialize)]
struct Pin {
    /// The Voronoi table's field path.
    target: String,
}

/// Writes the sites a Voronoi table spreads as its `points`, exactly, so
/// that the design does not change and every site becomes a handle to
/// drag; the keys that spread them go. Tables that spread the very same
/// sites (the same id over the same region, as a pattern drawn with two
/// pens is) are pinned with it, so that they stay one pattern: their
/// handles are one (see `GET /api/handles`).
async fn pin(State(app): State<App>, Json(pin): Json<Pin>) -> Response {
    let Some(good) = app.session.good() else {
        return nothing_rendered();
    };
    let place = table_index(&pin.target, "voronoi")
        .filter(|_| offering(good.spec.spec(), &pin.target, Gesture::Pin).is_some());
    let Some((l, t)) = place else {
        return failure(&Error::invalid(
            &pin.target,
            "is not a Voronoi table of the design",
        ));
    };
    // Each table's sites; those equal to the target's are pinned.
    let work = {
        let good = std::sync::Arc::clone(&good);
        off_thread(move || {
            let spec = good.spec.spec();
            let sites = crate::project::voronoi_sites(&good.spec, &good.library, l, t)?;
            let target = offering(spec, &pin.target, Gesture::Pin)
                .ok_or_else(|| Error::invalid(&pin.target, "is not a Voronoi table"))?;
            let mut changes = Vec::new();
            for (ol, layer) in spec.layers.iter().enumerate() {
                for item in layer.items() {
                    let field = format!("layers[{ol}].{}", item.field);
                    let Some(other) = offering(spec, &field, Gesture::Pin) else {
                        continue;
                    };
                    let twin = field == pin.target
                        || (other.pin_key().is_some()
                            && other.pin_key() == target.pin_key()
                            && !other.is_pinned()
                            && table_index(&field, "voronoi").is_some_and(|(ol, ot)| {
                                crate::project::voronoi_sites(&good.spec, &good.library, ol, ot)
                                    .is_ok_and(|p| p == sites)
                            }));
                    if twin {
                        changes.extend(other.pin(&field, &sites)?);
                    }
                }
            }
            Edit::with_changes(&good.text, changes)
        })
    };
    match work.await {
        Ok(text) => write(&app, move || Ok(text)).await,
        Err(response) => response,
    }
}

#[derive(Deserialize)]
struct Adjust {
    /// The id as in the SVG (`front.pine.tree-0.flower-3`).
    id: String,
    /// Moved by `[dx, dy]` mm more.
    #[serde(rename = "move")]
    offset: Option<[f64; 2]>,
    /// Turned by this many degrees more, clockwise.
    rotate: Option<f64>,
    /// Scaled by this factor more.
    scale: Option<f64>,
    /// Hidden (or shown again).
    hide: Option<bool>,
}

/// A drag, turn, scale or hide of one thing drawn: its `[[adjust]]`
/// entry changed by as much (made when it has none), as one edit.
async fn adjust(State(app): State<App>, Json(change): Json<Adjust>) -> Response {
    let Some(good) = app.session.good() else {
        return nothing_rendered();
    };
    let finite = change
        .offset
        .iter()
        .flatten()
        .chain(&change.rotate)
        .chain(&change.scale);
    if finite.clone().any(|v| !v.is_finite()) {
        return failure(&Error::invalid(
            "adjust",
            "the change is not a finite number",
        ));
    }
    let list = &good.spec.spec().adjust;
    let old = list.iter().position(|a| a.id == change.id);
    let was = old.map(|i| &list[i]);
    let offset = change.offset.map(|[dx, dy]| {
        let [x, y] = was.and_then(|a| a.offset).unwrap_or([0.0, 0.0]);
        [tenth(x + dx), tenth(y + dy)]
    });
    // Turns kept in −180–180, scales in what the description allows.
    let rotate = change.rotate.map(|d| {
        let r = was.and_then(|a| a.rotate).unwrap_or(0.0) + d;
        tenth(180.0 - (180.0 - r).rem_euclid(360.0))
    });
    let scale = change.scale.map(|f| {
        let s = was.and_then(|a| a.scale).unwrap_or(1.0) * f;
        ((s * 1000.0).round() / 1000.0).clamp(0.01, 100.0)
    });
    write(&app, move || {
        let mut edit = Edit::parse(&good.text)?;
        let mut values: Vec<(&str, toml_edit::Value)> = Vec::new();
        if let Some([x, y]) = offset {
            values.push(("move", toml_edit::Array::from_iter([x, y]).into()));
        }
        if let Some(r) = rotate {
            values.push(("rotate", r.into()));
        }
        if let Some(s) = scale {
            values.push(("scale", s.into()));
        }
        if let Some(h) = change.hide {
            values.push(("hide", h.into()));
        }
        if let Some(i) = old {
            for (key, value) in values {
                edit.set(&format!("adjust[{i}].{key}"), value)?;
            }
        } else {
            let mut table = toml_edit::Table::new();
            table.insert("id", toml_edit::value(change.id.as_str()));
            for (key, value) in values {
                table.insert(key, toml_edit::Item::Value(value));
            }
            edit.push_table("adjust", table, false)?;
        }
        Ok(edit.text())
    })
    .await
}

#[derive(Deserialize)]
struct Turn {
    /// The vine table's field path.
    target: String,
    /// Degrees more about the vertical (positive: the camera goes round
    /// towards +x).
    #[serde(default)]
    turn: f64,
    /// Degrees more above the horizontal.
    #[serde(default)]
    tilt: f64,
}

/// The camera of a vine turned round it: written as `camera = { turn,
/// tilt }` (a preset or a placed camera first becomes the orbit that sees
/// the same), the turn kept in −180–180 and the tilt in −89–89.
async fn orbit(State(app): State<App>, Json(change): Json<Turn>) -> Response {
    let Some(good) = app.session.good() else {
        return nothing_rendered();
    };
    if !(change.turn.is_finite() && change.tilt.is_finite()) {
        return failure(&Error::invalid("turn", "the turn is not a finite number"));
    }
    write(&app, move || {
        let table = offering(good.spec.spec(), &change.target, Gesture::Orbit)
            .ok_or_else(|| Error::invalid(&change.target, "is not a vine of the design"))?;
        let changes = table.turn(&change.target, change.turn, change.tilt)?;
        Edit::with_changes(&good.text, changes)
    })
    .await
}
