//! The page's gestures, each a plain change of the description: a stroke
//! drawn with the pen grows a sketch (live, then written as its points),
//! a click gives a zentangle region its procedure (a manual step), a
//! Voronoi table's sites are pinned (written as its `points`, which the
//! page then drags as handles), a tree, flower, leaf or plant dragged,
//! turned, scaled or hidden becomes its `[[adjust]]`, a vine's camera
//! turned round it becomes its `camera = { turn, tilt }`. What each family
//! offers to a gesture is listed by `GET /api/targets`.

use axum::extract::State;
use axum::http::StatusCode;
use axum::response::{IntoResponse, Response};
use axum::routing::{get, post};
use axum::{Json, Router};
use serde::Deserialize;
use serde_json::{json, Value};

use super::api::{apply, changed, failure, nothing_rendered, App};
use super::edit::{point_list, table_index, tenth, Edit};
use super::pen::{Stroke, Target};
use super::session::Move;
use crate::error::Error;
use crate::spec::Table;

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
/// new sketch goes in one), the sketch tables, the zentangle fills, the
/// Voronoi tables (pinned or not) and the vines (whether their camera
/// turns).
async fn targets(State(app): State<App>) -> Response {
    let Some(good) = app.session.good() else {
        return nothing_rendered();
    };
    let spec = good.spec.spec();
    let scene = &good.rendered.scene;
    let mut sketch = Vec::new();
    let mut zentangle = Vec::new();
    let mut voronoi = Vec::new();
    let mut vine = Vec::new();
    let layers: Vec<Value> = spec
        .layers
        .iter()
        .enumerate()
        .map(|(l, layer)| {
            let layer_id = scene.layers.get(l).map_or("", |s| s.id.as_str());
            for item in layer.items() {
                let target = json!({
                    "field": format!("layers[{l}].{}", item.field),
                    "label": format!("{} · {}", layer.name, item.id),
                    // The group the table's drawing is in the preview.
                    "group": format!("{layer_id}.{}", item.id),
                });
                match item.table {
                    Table::LSystem(t) if t.sketch.is_some() => sketch.push(target),
                    Table::Zentangle(_) => zentangle.push(target),
                    Table::Voronoi(v) => {
                        let mut target = target;
                        target["pinned"] = v.sites.points.is_some().into();
                        voronoi.push(target);
                    }
                    Table::Vine(v) => {
                        let mut target = target;
                        // "below" and placed perspective cameras do not
                        // turn: the page says so rather than jump.
                        target["orbits"] = v.camera.orbit().is_some().into();
                        vine.push(target);
                    }
                    _ => {}
                }
            }
            json!({"index": l, "name": layer.name})
        })
        .collect();
    Json(json!({
        "layers": layers,
        "sketch": sketch,
        "zentangle": zentangle,
        "voronoi": voronoi,
        "vine": vine,
    }))
    .into_response()
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
    let done = tokio::task::spawn_blocking(move || {
        let mut stroke = stroke
            .lock()
            .unwrap_or_else(std::sync::PoisonError::into_inner);
        work(&mut stroke)
    })
    .await;
    match done {
        Ok(Ok(t)) => Ok(t),
        Ok(Err(e)) => Err(failure(&e)),
        Err(e) => Err((StatusCode::INTERNAL_SERVER_ERROR, e.to_string()).into_response()),
    }
}

/// A gesture's new description, rendered as one edit; where it does not
/// render, the description stays as it was.
async fn write(app: &App, text: Result<String, Error>) -> Response {
    match text {
        Ok(text) => match apply(app, text, Move::Gesture).await {
            Ok(good) => changed(app, &good),
            Err(response) => response,
        },
        Err(e) => failure(&e),
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
        Ok(text) => write(&app, Ok(text)).await,
        Err(response) => response,
    }
}

#[derive(Deserialize)]
struct Fill {
    /// The zentangle table's field path.
    target: String,
    /// The click, scene mm.
    at: [f64; 2],
    /// The procedure (0–19).
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
    let table = table_index(&click.target, "zentangle")
        .and_then(|(l, t)| good.spec.spec().layers.get(l)?.zentangle.get(t));
    let Some(table) = table else {
        return failure(&Error::invalid(
            &click.target,
            "is not a zentangle fill of the design",
        ));
    };
    let [x, y] = click.at;
    if !(x.is_finite() && y.is_finite()) {
        return failure(&Error::invalid("at", "the click is not a finite point"));
    }
    let mut step = toml_edit::Table::new();
    let mut at = toml_edit::Array::new();
    at.push(tenth(x));
    at.push(tenth(y));
    step.insert("at", toml_edit::value(at));
    step.insert("procedure", toml_edit::value(i64::from(click.procedure)));
    if table.steps > 0 {
        step.insert("after", toml_edit::value(true));
    }
    let text = Edit::parse(&good.text).and_then(|mut edit| {
        edit.push_table(&format!("{}.manual", click.target), step, true)?;
        Ok(edit.text())
    });
    write(&app, text).await
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
    let Some((l, t)) = table_index(&pin.target, "voronoi").filter(|&(l, t)| {
        good.spec
            .spec()
            .layers
            .get(l)
            .is_some_and(|x| x.voronoi.len() > t)
    }) else {
        return failure(&Error::invalid(
            &pin.target,
            "is not a Voronoi table of the design",
        ));
    };
    // Each table's sites; those equal to the target's are pinned.
    let work = {
        let good = std::sync::Arc::clone(&good);
        tokio::task::spawn_blocking(move || {
            let spec = good.spec.spec();
            let points = crate::project::voronoi_sites(&good.spec, &good.library, l, t)?;
            let mut same = Vec::new();
            for (ol, layer) in spec.layers.iter().enumerate() {
                for (ot, other) in layer.voronoi.iter().enumerate() {
                    let twin = (ol, ot) == (l, t)
                        || (other.id.is_some()
                            && other.id == spec.layers[l].voronoi[t].id
                            && other.sites.points.is_none()
                            && crate::project::voronoi_sites(&good.spec, &good.library, ol, ot)
                                .is_ok_and(|p| p == points));
                    if twin {
                        same.push((
                            format!("layers[{ol}].voronoi[{ot}]"),
                            other.pinned(points.clone()).sites,
                        ));
                    }
                }
            }
            Ok::<_, Error>((points, same))
        })
    };
    let (points, same) = match work.await {
        Ok(Ok(found)) => found,
        Ok(Err(e)) => return failure(&e),
        Err(e) => return (StatusCode::INTERNAL_SERVER_ERROR, e.to_string()).into_response(),
    };
    let text = Edit::parse(&good.text).and_then(|mut edit| {
        for (table, pinned) in &same {
            let sites = format!("{table}.sites");
            // The sites' keys as they will be: each kept, set or removed.
            let now =
                toml::Value::try_from(pinned).map_err(|e| Error::invalid(&sites, e.to_string()))?;
            for key in [
                "distribution",
                "count",
                "spacing",
                "jitter",
                "image",
                "density",
            ] {
                match now.get(key) {
                    Some(v) => edit.set(&format!("{sites}.{key}"), toml_value(v)?)?,
                    None => edit.remove(&format!("{sites}.{key}"))?,
                }
            }
            edit.set(&format!("{sites}.points"), point_list(&points))?;
        }
        Ok(edit.text())
    });
    write(&app, text).await
}

/// A plain TOML value (a number, a string) as an editable one.
fn toml_value(v: &toml::Value) -> Result<toml_edit::Value, Error> {
    v.to_string()
        .parse()
        .map_err(|e: toml_edit::TomlError| Error::invalid("studio", e.to_string()))
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
    let text = Edit::parse(&good.text).and_then(|mut edit| {
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
    });
    write(&app, text).await
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
    let table = table_index(&change.target, "vine")
        .and_then(|(l, t)| good.spec.spec().layers.get(l)?.vine.get(t));
    let Some(table) = table else {
        return failure(&Error::invalid(
            &change.target,
            "is not a vine of the design",
        ));
    };
    let field = format!("{}.camera", change.target);
    let Some(now) = table.camera.orbit() else {
        return failure(&Error::invalid(
            &field,
            "this camera does not turn round the vine (\"below\" and perspective cameras              placed by hand): give camera = { turn = 0, tilt = 10 } to turn it",
        ));
    };
    let turn = tenth(180.0 - (180.0 - (now.turn + change.turn)).rem_euclid(360.0));
    let tilt = tenth((now.tilt + change.tilt).clamp(-89.0, 89.0));
    let mut camera = toml_edit::InlineTable::new();
    camera.insert("turn", turn.into());
    camera.insert("tilt", tilt.into());
    if let Some(fov) = now.perspective {
        camera.insert("perspective", fov.into());
    }
    let text = Edit::parse(&good.text).and_then(|mut edit| {
        edit.set(&field, camera)?;
        Ok(edit.text())
    });
    write(&app, text).await
}
