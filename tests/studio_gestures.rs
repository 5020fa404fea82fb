//! The studio's gestures through its API, as the page makes them: a
//! stroke drawn with the pen grows a sketch while it comes in and is
//! written into the description when the pen lifts; a click gives a
//! zentangle region its procedure. Each is one plain change of the
//! description, undone like any other.

use std::net::SocketAddr;

use serde_json::{json, Value};

use crate::studio::{call, get, studio, Answer, SCENE};

fn post(addr: SocketAddr, path: &str, body: &Value) -> Answer {
    call(
        addr,
        "POST",
        path,
        &["Content-Type: application/json"],
        body.to_string().as_bytes(),
    )
}

fn scene(addr: SocketAddr) -> String {
    get(addr, "/api/scene").text()
}

/// A pen stroke up the page in `n` batches of points, scene mm.
fn batches(n: usize) -> Vec<Value> {
    (0..n)
        .map(|b| {
            let points: Vec<[f64; 2]> = (1..=10)
                .map(|i| {
                    let t = (b * 10 + i) as f64;
                    [40.0 + 12.0 * (t / 15.0).sin(), 180.0 - 1.5 * t]
                })
                .collect();
            json!({ "points": points })
        })
        .collect()
}

#[test]
fn a_stroke_grows_its_sketch_while_drawn_and_is_written_when_the_pen_lifts() {
    let text = moyo::templates::get("lsystem-sketch-s").unwrap().text;
    let (studio, _dir) = studio(text);
    let addr = studio.addr();
    let targets = get(addr, "/api/targets").json();
    assert_eq!(targets["sketch"][0]["field"], "layers[0].lsystem[0]");

    let begin = post(
        addr,
        "/api/stroke/begin",
        &json!({"target": "layers[0].lsystem[0]", "at": [40, 180]}),
    );
    assert_eq!(begin.status, 200, "{}", begin.text());
    assert_eq!(begin.json()["steps"], 0);
    assert_eq!(begin.json()["outline"], true);
    // Every batch answers with the structure so far: it grows step by
    // step as the stroke lengthens (a module is 8 mm: 15 mm a batch).
    let mut steps = Vec::new();
    let mut limbs = 0;
    for batch in batches(8) {
        let grown = post(addr, "/api/stroke/extend", &batch).json();
        steps.push(grown["steps"].as_u64().unwrap());
        if let Some(paths) = grown["paths"].as_array() {
            assert!(paths.len() >= limbs, "limbs never go away");
            limbs = paths.len();
            assert!(paths.iter().all(|d| d.as_str().unwrap().starts_with("M ")));
        }
    }
    assert!(steps.windows(2).all(|w| w[0] < w[1]), "{steps:?}");
    assert!(steps[0] >= 1 && limbs > 10, "{steps:?}, {limbs} limbs");
    // Nothing is written until the pen lifts.
    assert_eq!(scene(addr), text);

    let end = post(addr, "/api/stroke/end", &json!({}));
    assert_eq!(end.status, 200, "{}", end.text());
    let written = scene(addr);
    assert_eq!(end.json()["scene"], written);
    // The stroke is the sketch's points now, straight between them, each
    // a tenth of a millimetre and at least half a millimetre apart.
    let spec = moyo::ValidSpec::parse(&written, moyo::Format::Toml).unwrap();
    let sketch = spec.spec().layers[0].lsystem[0].sketch.clone().unwrap();
    let points = sketch.points.unwrap();
    assert!(!sketch.smooth);
    assert_eq!(points[0], [40.0, 180.0]);
    assert!(points.len() > 40, "{}", points.len());
    for w in points.windows(2) {
        let gap = (w[1][0] - w[0][0]).hypot(w[1][1] - w[0][1]);
        assert!(gap >= 0.5 - 1e-9, "{w:?}");
    }
    for p in points.iter().flatten() {
        assert_eq!((p * 10.0).round() / 10.0, *p);
    }
    // The rest of the description is as it was, comments and all.
    assert!(written.contains("# The limbs' outlines merge into one silhouette"));
    // The render is the command line's render of that description.
    let svg = get(addr, "/api/svg").text();
    assert_eq!(svg, moyo::render(&spec).unwrap().svg);
    // One step of the history.
    let undone = post(addr, "/api/undo", &json!({}));
    assert_eq!(undone.json()["scene"], text);
    studio.stop();
}

#[test]
fn a_stroke_can_start_a_new_sketch_in_a_layer_of_any_design() {
    let (studio, _dir) = studio(SCENE);
    let addr = studio.addr();
    let targets = get(addr, "/api/targets").json();
    assert_eq!(targets["sketch"], json!([]));
    assert_eq!(targets["layers"][0]["name"], "front");
    assert_eq!(
        post(
            addr,
            "/api/stroke/begin",
            &json!({"target": null, "layer": 0, "at": [60, 170]})
        )
        .status,
        200
    );
    for batch in batches(4) {
        assert_eq!(post(addr, "/api/stroke/extend", &batch).status, 200);
    }
    let end = post(addr, "/api/stroke/end", &json!({}));
    assert_eq!(end.status, 200, "{}", end.text());
    let written = scene(addr);
    assert!(written.starts_with(SCENE), "{written}");
    let spec = moyo::ValidSpec::parse(&written, moyo::Format::Toml).unwrap();
    let table = &spec.spec().layers[0].lsystem[0];
    assert_eq!(table.id.as_deref(), Some("sketch-1"));
    assert!(table.sketch.as_ref().unwrap().points.is_some());
    // The design now has a sketch to draw into.
    let targets = get(addr, "/api/targets").json();
    assert_eq!(targets["sketch"][0]["field"], "layers[0].lsystem[0]");
    studio.stop();
}

#[test]
fn strokes_that_cannot_be_written_leave_the_description_as_it_was() {
    let (studio, _dir) = studio(SCENE);
    let addr = studio.addr();
    // No stroke begun.
    let lost = post(addr, "/api/stroke/extend", &json!({"points": [[1, 2]]}));
    assert_eq!(lost.status, 422);
    assert!(lost.json()["error"].as_str().unwrap().contains("no stroke"));
    // Not a sketch table, not a layer.
    for target in [
        json!({"target": "layers[0].trees[0]", "at": [1, 2]}),
        json!({"target": null, "layer": 7, "at": [1, 2]}),
    ] {
        let refused = post(addr, "/api/stroke/begin", &target);
        assert_eq!(refused.status, 422, "{target}");
    }
    // A dot, not a stroke.
    post(
        addr,
        "/api/stroke/begin",
        &json!({"target": null, "at": [50, 50]}),
    );
    post(
        addr,
        "/api/stroke/extend",
        &json!({"points": [[50.1, 50.2]]}),
    );
    let dot = post(addr, "/api/stroke/end", &json!({}));
    assert_eq!(dot.status, 422);
    assert!(dot.json()["error"].as_str().unwrap().contains("no length"));
    // A point that is no number is refused by the JSON, not a crash.
    post(
        addr,
        "/api/stroke/begin",
        &json!({"target": null, "at": [50, 50]}),
    );
    let bad = call(
        addr,
        "POST",
        "/api/stroke/extend",
        &["Content-Type: application/json"],
        b"{\"points\": [[1e999, 2]]}",
    );
    assert!(bad.status >= 400 && bad.status < 500, "{}", bad.status);
    assert_eq!(scene(addr), SCENE);
    assert_eq!(get(addr, "/api/state").json()["undo"], 0);
    studio.stop();
}

/// A zentangle tile that the loop does not fill: every region is the
/// designer's to choose (the paper's loop, a click filling the white
/// piece it lands in).
pub(crate) const TILE: &str =
    "version = 1\nseed = 11\n\n[page]\nsize = [109, 109]\nmargin = 10\n\n\
    [[layers]]\nname = \"tile\"\n\n[[layers.zentangle]]\nid = \"tile\"\nlook = \"sampler\"\nsteps = 0\n\
    lines = [[[0, 40], [89, 50]]]\n\n[layers.zentangle.region]\n\
    polygon = [[0, 0], [89, 0], [89, 89], [0, 89]]\n";

/// The ids of the steps drawn in the SVG, `step-K-pP`.
fn steps_drawn(svg: &str) -> Vec<String> {
    let mut ids: Vec<String> = svg
        .split("id=\"")
        .skip(1)
        .filter_map(|rest| rest.split('"').next())
        .filter_map(|id| id.split('.').nth(2))
        .filter(|s| s.starts_with("step-") && s.contains("-p"))
        .map(str::to_string)
        .collect();
    // The plot orders paths for the pen: steps interleave.
    ids.sort();
    ids.dedup();
    ids
}

#[test]
fn a_click_gives_the_white_region_under_it_a_procedure() {
    let (studio, _dir) = studio(TILE);
    let addr = studio.addr();
    let targets = get(addr, "/api/targets").json();
    assert_eq!(targets["zentangle"][0]["field"], "layers[0].zentangle[0]");
    assert_eq!(targets["zentangle"][0]["group"], "tile.tile");
    assert!(steps_drawn(&get(addr, "/api/svg").text()).is_empty());
    // Below the line: Voronoi cells there.
    let click = json!({"target": "layers[0].zentangle[0]", "at": [44.44, 70.01], "procedure": 18});
    let filled = post(addr, "/api/fill", &click);
    assert_eq!(filled.status, 200, "{}", filled.text());
    let written = scene(addr);
    assert!(
        written.contains("manual = [{ at = [44.4, 70.0], procedure = 18 }]"),
        "{written}"
    );
    let svg = get(addr, "/api/svg").text();
    assert_eq!(steps_drawn(&svg), ["step-1-p18"]);
    // Above the line, contour lines: a second step, appended.
    let click = json!({"target": "layers[0].zentangle[0]", "at": [44, 10], "procedure": 16});
    assert_eq!(post(addr, "/api/fill", &click).status, 200);
    let svg = get(addr, "/api/svg").text();
    assert_eq!(steps_drawn(&svg), ["step-1-p18", "step-2-p16"]);
    // Off the tile: nothing there to fill, and nothing changes.
    let before = scene(addr);
    let click = json!({"target": "layers[0].zentangle[0]", "at": [95, 95], "procedure": 2});
    let refused = post(addr, "/api/fill", &click);
    assert_eq!(refused.status, 422);
    let e = refused.json();
    assert!(
        e["error"]
            .as_str()
            .unwrap()
            .contains("lies in no white region"),
        "{e}"
    );
    assert_eq!(e["path"], "layers[0].zentangle[0].manual[2].at");
    assert_eq!(scene(addr), before);
    // Not a fill, not a procedure.
    for click in [
        json!({"target": "layers[0].trees[0]", "at": [4, 4], "procedure": 2}),
        json!({"target": "layers[0].zentangle[0]", "at": [4, 4], "procedure": 32}),
    ] {
        assert_eq!(post(addr, "/api/fill", &click).status, 422, "{click}");
    }
    assert_eq!(scene(addr), before);
    // Each click was one step of the history.
    let undone = post(addr, "/api/undo", &json!({}));
    let preview = undone.json()["preview"].as_str().unwrap().to_string();
    assert_eq!(steps_drawn(&preview), ["step-1-p18"]);
    studio.stop();
}

#[test]
fn a_click_on_a_filled_tile_touches_up_what_the_loop_left_white() {
    let text = TILE.replace("steps = 0", "steps = 4");
    let (studio, _dir) = studio(&text);
    let addr = studio.addr();
    let before = steps_drawn(&get(addr, "/api/svg").text());
    // Some point of the tile that the four steps left white.
    let filled = (1..15)
        .flat_map(|i| (1..15).map(move |j| [f64::from(i) * 6.0, f64::from(j) * 6.0]))
        .map(|at| {
            post(
                addr,
                "/api/fill",
                &json!({"target": "layers[0].zentangle[0]", "at": at, "procedure": 2}),
            )
        })
        .find(|answer| answer.status == 200)
        .expect("four steps leave some region white");
    let written = filled.json()["scene"].as_str().unwrap().to_string();
    assert!(
        written.contains("procedure = 2, after = true }]"),
        "{written}"
    );
    let after = steps_drawn(&get(addr, "/api/svg").text());
    // The loop's steps as they were, and one more.
    assert_eq!(after[..before.len()], before[..]);
    assert_eq!(after.len(), before.len() + 1);
    assert!(after.last().unwrap().ends_with("-p2"), "{after:?}");
    studio.stop();
}

/// An SVG without its embedded description (which names the change).
fn drawing(svg: &str) -> String {
    match (svg.find("<metadata"), svg.find("</metadata>")) {
        (Some(a), Some(b)) => format!("{}{}", &svg[..a], &svg[b..]),
        _ => svg.to_string(),
    }
}

#[test]
fn pinned_voronoi_sites_draw_the_same_and_then_drag_as_handles() {
    let text = moyo::templates::get("voronoi-stained-glass").unwrap().text;
    let (studio, _dir) = studio(text);
    let addr = studio.addr();
    let targets = get(addr, "/api/targets").json();
    assert_eq!(targets["voronoi"][0]["field"], "layers[0].voronoi[0]");
    assert_eq!(targets["voronoi"][0]["pinned"], false);
    let before = get(addr, "/api/svg").text();
    let pinned = post(addr, "/api/pin", &json!({"target": "layers[0].voronoi[0]"}));
    assert_eq!(pinned.status, 200, "{}", pinned.text());
    let written = scene(addr);
    // The sites are written out; what spread them is gone from that
    // table; the comments stay.
    let spec = moyo::ValidSpec::parse(&written, moyo::Format::Toml).unwrap();
    let sites = &spec.spec().layers[0].voronoi[0].sites;
    let points = sites.points.clone().unwrap();
    assert!(points.len() > 100, "{}", points.len());
    assert_eq!(sites.distribution, None);
    assert!(written.contains("# The lead: every edge between two panes once"));
    // And the design is as it was.
    let after = get(addr, "/api/svg").text();
    assert_eq!(drawing(&after), drawing(&before));
    assert_eq!(
        get(addr, "/api/targets").json()["voronoi"][0]["pinned"],
        true
    );
    // The glass is the same window in another pen: pinned with it.
    assert_eq!(
        spec.spec().layers[1].voronoi[0].sites.points.as_ref(),
        Some(&points)
    );
    // Every site is now a handle, one for both windows, not joined by a
    // line; moving one moves its cell in both.
    let handles = get(addr, "/api/handles").json();
    let lines: Vec<&Value> = handles["lines"]
        .as_array()
        .unwrap()
        .iter()
        .filter(|l| l["field"].as_str().unwrap().ends_with("sites.points"))
        .collect();
    assert_eq!(lines.len(), 1, "{lines:?}");
    let line = lines[0];
    assert_eq!(line["field"], "layers[0].voronoi[0].sites.points");
    assert_eq!(line["also"], json!(["layers[1].voronoi[0].sites.points"]));
    assert_eq!(line["joined"], false);
    assert_eq!(line["points"].as_array().unwrap().len(), points.len());
    let [x, y] = points[0];
    let mut changes = Vec::new();
    for table in ["layers[0].voronoi[0]", "layers[1].voronoi[0]"] {
        changes.push(json!({"field": format!("{table}.sites.points[0][0]"), "value": x + 3.0}));
        changes.push(json!({"field": format!("{table}.sites.points[0][1]"), "value": y + 2.0}));
    }
    let moved = call(
        addr,
        "PATCH",
        "/api/fields",
        &["Content-Type: application/json"],
        json!({ "changes": changes }).to_string().as_bytes(),
    );
    assert_eq!(moved.status, 200, "{}", moved.text());
    let dragged = get(addr, "/api/svg").text();
    assert_ne!(drawing(&dragged), drawing(&after));
    let handles = get(addr, "/api/handles").json();
    assert_eq!(
        handles["lines"]
            .as_array()
            .unwrap()
            .iter()
            .filter(|l| l["field"].as_str().unwrap().ends_with("sites.points"))
            .count(),
        1,
        "the two windows move as one"
    );
    // Not a Voronoi table.
    let refused = post(addr, "/api/pin", &json!({"target": "layers[0].trees[0]"}));
    assert_eq!(refused.status, 422);
    studio.stop();
}

#[test]
fn arranging_a_tree_is_written_as_its_adjustment() {
    let (studio, _dir) = studio(SCENE);
    let addr = studio.addr();
    let adjust = |change: Value| {
        let answer = post(addr, "/api/adjust", &change);
        assert_eq!(answer.status, 200, "{change}: {}", answer.text());
        let spec = moyo::ValidSpec::parse(&scene(addr), moyo::Format::Toml).unwrap();
        spec.spec().adjust[0].clone()
    };
    let tree = "front.pine.tree-0";
    let first = get(addr, "/api/svg").text();
    // A drag, then another: the moves add up, to a tenth of a millimetre.
    let a = adjust(json!({"id": tree, "move": [10.04, -2.0]}));
    assert_eq!((a.id.as_str(), a.offset), (tree, Some([10.0, -2.0])));
    let a = adjust(json!({"id": tree, "move": [5.0, 2.0]}));
    assert_eq!(a.offset, Some([15.0, 0.0]));
    assert_ne!(get(addr, "/api/svg").text(), first);
    // Turns stay within a half turn either way; scales multiply.
    let a = adjust(json!({"id": tree, "rotate": 150}));
    assert_eq!(a.rotate, Some(150.0));
    let a = adjust(json!({"id": tree, "rotate": 50}));
    assert_eq!(a.rotate, Some(-160.0));
    adjust(json!({"id": tree, "scale": 1.5}));
    let a = adjust(json!({"id": tree, "scale": 1.5}));
    assert_eq!(a.scale, Some(2.25));
    // One entry for the tree, written where [[adjust]] tables go.
    let written = scene(addr);
    assert!(written.starts_with(SCENE), "{written}");
    assert_eq!(written.matches("[[adjust]]").count(), 1, "{written}");
    // Hidden: gone from the drawing.
    adjust(json!({"id": tree, "hide": true}));
    let svg = get(addr, "/api/svg").text();
    // (Paths keep their ids in the plot: a tree's start with its own.)
    assert!(!svg.contains(&format!("id=\"{tree}.")));
    assert!(svg.contains("id=\"front.pine.tree-1."));
    // Something that is not drawn cannot be arranged, and nothing changes.
    let before = scene(addr);
    let refused = post(
        addr,
        "/api/adjust",
        &json!({"id": "front.pine.tree-9", "move": [1, 1]}),
    );
    assert_eq!(refused.status, 422);
    assert!(refused.json()["error"]
        .as_str()
        .unwrap()
        .contains("matches nothing drawn"));
    assert_eq!(scene(addr), before);
    // Each gesture was one step of the history.
    assert_eq!(get(addr, "/api/state").json()["undo"], 7);
    studio.stop();
}

#[test]
fn turning_the_camera_round_a_vine_writes_its_orbit() {
    let text = moyo::templates::get("vine-basic").unwrap().text;
    let (studio, _dir) = studio(text);
    let addr = studio.addr();
    let targets = get(addr, "/api/targets").json();
    assert_eq!(targets["vine"][0]["field"], "layers[0].vine[0]");
    assert_eq!(targets["vine"][0]["orbits"], true);
    let turn = |turn: f64, tilt: f64| {
        let answer = post(
            addr,
            "/api/orbit",
            &json!({"target": "layers[0].vine[0]", "turn": turn, "tilt": tilt}),
        );
        assert_eq!(answer.status, 200, "{}", answer.text());
        let spec = moyo::ValidSpec::parse(&scene(addr), moyo::Format::Toml).unwrap();
        spec.spec().layers[0].vine[0].camera.orbit().unwrap()
    };
    let front = get(addr, "/api/svg").text();
    // From the front preset: the turns add up, to a tenth of a degree.
    let o = turn(30.04, 10.0);
    assert_eq!((o.turn, o.tilt, o.perspective), (30.0, 10.0, None));
    assert!(scene(addr).contains("camera = { turn = 30.0, tilt = 10.0 }"));
    assert_ne!(get(addr, "/api/svg").text(), front);
    let o = turn(170.0, 100.0);
    // Round past the back; never straight down.
    assert_eq!((o.turn, o.tilt), (-160.0, 89.0));
    // Back to the front: the drawing is the front preset's again.
    turn(160.0, -89.0);
    assert_eq!(drawing(&get(addr, "/api/svg").text()), drawing(&front));
    // A camera that does not turn says so, and nothing changes.
    studio.stop();
    let below = text.replace("[[layers.vine]]\n", "[[layers.vine]]\ncamera = \"below\"\n");
    let (studio, _dir) = crate::studio::studio(&below);
    let addr = studio.addr();
    assert_eq!(get(addr, "/api/targets").json()["vine"][0]["orbits"], false);
    let refused = post(
        addr,
        "/api/orbit",
        &json!({"target": "layers[0].vine[0]", "turn": 5}),
    );
    assert_eq!(refused.status, 422);
    assert_eq!(refused.json()["path"], "layers[0].vine[0].camera");
    assert_eq!(scene(addr), below);
    let refused = post(
        addr,
        "/api/orbit",
        &json!({"target": "layers[0].vine[3]", "turn": 5}),
    );
    assert_eq!(refused.status, 422);
    studio.stop();
}

#[test]
fn malformed_gestures_are_refused_and_the_studio_goes_on() {
    let (studio, _dir) = studio(SCENE);
    let addr = studio.addr();
    let bodies: [&[u8]; 6] = [
        b"",
        b"{",
        b"[]",
        b"{\"target\": 5, \"at\": \"x\"}",
        b"{\"id\": \"front.pine.tree-0\", \"move\": [1e309, 0]}",
        b"{\"target\": \"layers[0].vine[0]\", \"turn\": \"left\"}",
    ];
    for path in [
        "/api/stroke/begin",
        "/api/stroke/extend",
        "/api/stroke/end",
        "/api/fill",
        "/api/pin",
        "/api/adjust",
        "/api/orbit",
    ] {
        for body in bodies {
            let answer = call(
                addr,
                "POST",
                path,
                &["Content-Type: application/json"],
                body,
            );
            assert!(
                (400..500).contains(&answer.status),
                "{path} {}: {}",
                String::from_utf8_lossy(body),
                answer.status
            );
        }
    }
    // Nothing changed, and the studio still answers.
    assert_eq!(scene(addr), SCENE);
    assert_eq!(get(addr, "/api/state").json()["undo"], 0);
    assert_eq!(get(addr, "/api/svg").status, 200);
    studio.stop();
}
