//! The studio's page in a real browser: Debian's Chromium, driven through
//! ChromeDriver's WebDriver protocol (plain HTTP and JSON, spoken here
//! over the same small client as the API tests). A person's gestures —
//! typing, changing a field, switching a pen off — and what the page
//! shows after them.
//!
//! The tests run when `MOYO_CHROMEDRIVER` names a chromedriver and
//! `MOYO_CHROMIUM` the browser (`.ci/run` installs both from Debian).
//! Without them a test says so and passes, unless `CI` is set, where they
//! are a failure.

use std::net::{SocketAddr, TcpListener};
use std::process::{Child, Command, Stdio};
use std::time::{Duration, Instant};

use serde_json::{json, Value};

use crate::studio::{call, studio, SCENE};

/// The key WebDriver gives an element reference under.
const ELEMENT: &str = "element-6066-11e4-a52e-4f735466cecf";

/// A headless Chromium session (see the module docs).
struct Browser {
    driver: Child,
    addr: SocketAddr,
    session: String,
    /// The browser's own profile, removed with it.
    _profile: tempfile::TempDir,
}

impl Browser {
    /// A new browser, or `None` (outside CI) when none is installed.
    fn start() -> Option<Browser> {
        let (Some(driver), Some(chromium)) = (
            crate::readers::reader("MOYO_CHROMEDRIVER"),
            crate::readers::reader("MOYO_CHROMIUM"),
        ) else {
            return None;
        };
        let port = TcpListener::bind("127.0.0.1:0")
            .unwrap()
            .local_addr()
            .unwrap()
            .port();
        let child = Command::new(driver)
            .arg(format!("--port={port}"))
            .stdout(Stdio::null())
            .stderr(Stdio::null())
            .spawn()
            .expect("chromedriver starts");
        let addr: SocketAddr = format!("127.0.0.1:{port}").parse().unwrap();
        let profile = tempfile::tempdir().unwrap();
        let user_data = format!("--user-data-dir={}", profile.path().display());
        let mut browser = Browser {
            driver: child,
            addr,
            session: String::new(),
            _profile: profile,
        };
        browser.wait_until("chromedriver to start", || {
            std::net::TcpStream::connect(addr).is_ok()
        });
        let created = browser.send(
            "POST",
            "/session",
            &json!({"capabilities": {"alwaysMatch": {
                "browserName": "chrome",
                "goog:chromeOptions": {
                    "binary": chromium.to_string_lossy(),
                    "args": [
                        "--headless", "--no-sandbox", "--disable-gpu", "--disable-quic",
                        "--no-first-run", "--disable-background-networking",
                        "--disable-component-update", "--disable-sync",
                        "--window-size=1400,900",
                        user_data,
                    ]
                }
            }}}),
        );
        browser.session = created["sessionId"].as_str().unwrap().to_string();
        Some(browser)
    }

    /// A WebDriver command; its `value`.
    fn send(&self, method: &str, path: &str, body: &Value) -> Value {
        let body = if method == "GET" || method == "DELETE" {
            Vec::new()
        } else {
            body.to_string().into_bytes()
        };
        let answer = call(
            self.addr,
            method,
            path,
            &["Content-Type: application/json; charset=utf-8"],
            &body,
        );
        let reply = answer.json();
        assert_eq!(answer.status, 200, "{method} {path}: {reply}");
        reply["value"].clone()
    }

    fn command(&self, method: &str, what: &str, body: &Value) -> Value {
        self.send(method, &format!("/session/{}{what}", self.session), body)
    }

    fn open(&self, url: &str) {
        self.command("POST", "/url", &json!({ "url": url }));
    }

    /// Runs `script` in the page (`arguments[0]` … are `args`).
    fn eval(&self, script: &str, args: &[Value]) -> Value {
        self.command(
            "POST",
            "/execute/sync",
            &json!({"script": script, "args": args}),
        )
    }

    fn wait_until(&self, what: &str, mut done: impl FnMut() -> bool) {
        let start = Instant::now();
        while !done() {
            assert!(
                start.elapsed() < Duration::from_secs(60),
                "gave up waiting for {what}"
            );
            std::thread::sleep(Duration::from_millis(50));
        }
    }

    /// Waits until `script` returns something other than null or false,
    /// and gives it.
    fn wait_for(&self, what: &str, script: &str) -> Value {
        let mut got = Value::Null;
        self.wait_until(what, || {
            got = self.eval(script, &[]);
            !(got.is_null() || got == Value::Bool(false))
        });
        got
    }

    fn element(&self, css: &str) -> Value {
        let found = self.command(
            "POST",
            "/element",
            &json!({"using": "css selector", "value": css}),
        );
        found[ELEMENT].clone()
    }

    /// Clicks the element at `css`, as a person does.
    fn click(&self, css: &str) {
        let id = self.element(css);
        self.command(
            "POST",
            &format!("/element/{}/click", id.as_str().unwrap()),
            &json!({}),
        );
    }

    /// Presses the mouse on the element at `css`, moves it by `dx`, `dy`
    /// CSS pixels in steps, and lets go.
    fn drag(&self, css: &str, dx: i64, dy: i64) {
        let id = self.element(css);
        let mut steps = vec![
            json!({"type": "pointerMove", "origin": {ELEMENT: id}, "x": 0, "y": 0}),
            json!({"type": "pointerDown", "button": 0}),
        ];
        for _ in 0..6 {
            steps.push(json!({"type": "pointerMove", "origin": "pointer", "x": dx / 6, "y": dy / 6, "duration": 40}));
        }
        steps.push(json!({"type": "pointerUp", "button": 0}));
        self.point("mouse", steps);
    }

    /// Moves, presses and lifts a pointer (`mouse` or `pen`) as `actions`
    /// say; a pen pressed and not lifted stays down for the next call.
    fn point(&self, kind: &str, actions: Vec<Value>) {
        self.command(
            "POST",
            "/actions",
            &json!({"actions": [{
                "type": "pointer", "id": kind,
                "parameters": {"pointerType": kind},
                "actions": actions,
            }]}),
        );
    }

    /// Types `keys` into the element at `css`, as a person does.
    fn type_into(&self, css: &str, keys: &str) {
        let id = self.element(css);
        self.command(
            "POST",
            &format!("/element/{}/value", id.as_str().unwrap()),
            &json!({ "text": keys }),
        );
    }
}

impl Browser {
    /// Fails on any error the page's own scripts met.
    fn assert_no_page_errors(&self) {
        let errors = self.eval("return document.body.dataset.errors || '';", &[]);
        assert_eq!(errors, json!(""), "the page failed");
    }
}

impl Drop for Browser {
    fn drop(&mut self) {
        if !self.session.is_empty() {
            let _ = call(
                self.addr,
                "DELETE",
                &format!("/session/{}", self.session),
                &[],
                b"",
            );
        }
        let _ = self.driver.kill();
        let _ = self.driver.wait();
    }
}

/// The preview's SVG as the page shows it, without the handles drawn
/// over it.
const PREVIEW: &str = "const s = document.querySelector('#preview svg'); if (!s) return null; \
    const c = s.cloneNode(true); const h = c.querySelector('#studio-handles'); if (h) h.remove(); \
    return c.outerHTML;";

#[test]
fn a_field_changed_in_the_form_redraws_the_preview_and_the_text() {
    let Some(browser) = Browser::start() else {
        return;
    };
    let (studio, _dir) = studio(SCENE);
    browser.open(&studio.url());
    browser.wait_for("the first preview", PREVIEW);
    let before = browser.eval(PREVIEW, &[]);
    browser.wait_for(
        "the form",
        "return document.querySelector('input[type=number][data-field=\"layers[0].trees[0].count\"]');",
    );
    // Select the count, type a new one and leave the field, as a person
    // does: Ctrl+A, 3, Tab.
    let field = "input[type=number][data-field=\"layers[0].trees[0].count\"]";
    browser.type_into(field, "\u{E009}a\u{E000}3\u{E004}");
    let text = browser.wait_for(
        "the text to change",
        "const t = document.getElementById('text').value; return t.includes('count = 3   # two trees') && t;",
    );
    assert!(text.as_str().unwrap().contains("seed = 3"));
    browser.wait_for(
        "a new preview",
        &format!("return (() => {{ {PREVIEW} }})() !== {};", json!(before)),
    );
    // Three trees now, where there were two.
    let trees = "return [...document.querySelectorAll('#preview g')].filter(g => /^front\\.pine\\.tree-\\d+$/.test(g.id)).length;";
    assert_eq!(browser.eval(trees, &[]), json!(3));
    // The history: undo is possible now, and takes the change back.
    browser.click("#undo");
    browser.wait_for(
        "undo",
        "return document.getElementById('text').value.includes('count = 2   # two trees');",
    );
    browser.assert_no_page_errors();
    studio.stop();
}

#[test]
fn an_invalid_edit_shows_its_error_and_keeps_the_last_good_preview() {
    let Some(browser) = Browser::start() else {
        return;
    };
    let (studio, _dir) = studio(SCENE);
    browser.open(&studio.url());
    let before = browser.wait_for("the first preview", PREVIEW);
    // A rotation out of range, typed on a new last line: the number
    // first, then Home and the key, so that no prefix of the line is a
    // valid description (a render between keystrokes would change the
    // preview this test expects to stay).
    browser.eval(
        "const t = document.getElementById('text'); t.focus(); t.setSelectionRange(t.value.length, t.value.length);",
        &[],
    );
    browser.type_into("#text", "999\u{E011}rotate = ");
    let error = browser.wait_for(
        "the error",
        "const e = document.getElementById('error'); return e.classList.contains('shown') && e.textContent;",
    );
    let error = error.as_str().unwrap();
    assert!(
        error.contains("layers[0].trees[0].rotate") && error.contains("-360"),
        "{error}"
    );
    assert!(error.starts_with("15:10: "), "{error}");
    // The last good preview stays, marked stale.
    assert_eq!(browser.eval(PREVIEW, &[]), before);
    assert_eq!(
        browser.eval(
            "return document.getElementById('preview').classList.contains('stale');",
            &[]
        ),
        json!(true)
    );
    // Clicking the error puts the caret at its place.
    browser.click("#error");
    let caret = browser.eval(
        "const t = document.getElementById('text'); return t.value.slice(0, t.selectionStart).split('\\n').length;",
        &[],
    );
    assert_eq!(caret, json!(15));
    browser.assert_no_page_errors();
    studio.stop();
}

#[test]
fn dragging_a_point_of_a_centre_line_moves_the_trees() {
    let Some(browser) = Browser::start() else {
        return;
    };
    let (studio, _dir) = studio(SCENE);
    browser.open(&studio.url());
    let handle = "circle.studio-handle[data-field=\"layers[0].trees[0].centre[0]\"]";
    browser.wait_for(
        "the handles",
        &format!("return document.querySelector({});", json!(handle)),
    );
    let tree = "const t = document.getElementById('front.pine.tree-0'); return t && t.getBoundingClientRect().x;";
    let before = browser.eval(tree, &[]).as_f64().unwrap();
    // Drag the first point of the centre line to the right.
    browser.drag(handle, 120, 0);
    let x = browser.wait_for(
        "the text to follow the drag",
        "const m = document.getElementById('text').value.match(/centre = \\[\\[([-\\d.]+), ([-\\d.]+)\\]/); \
         return m && +m[1] !== 20 && [+m[1], +m[2]];",
    );
    let (x, y) = (x[0].as_f64().unwrap(), x[1].as_f64().unwrap());
    assert!(x > 30.0, "{x}");
    assert!((y - 150.0).abs() < 2.0, "{y}");
    // The first tree stands where the line now starts.
    browser.wait_for(
        "the tree to move",
        &format!("const t = document.getElementById('front.pine.tree-0'); return t && t.getBoundingClientRect().x > {} + 5;", before),
    );
    // The drag is one edit per step sent, and undo goes back.
    assert_eq!(
        browser.eval("return document.getElementById('undo').disabled;", &[]),
        json!(false)
    );
    browser.assert_no_page_errors();
    studio.stop();
}

#[test]
fn a_pen_switched_off_is_hidden_in_the_preview() {
    let Some(browser) = Browser::start() else {
        return;
    };
    let (studio, _dir) = studio(SCENE);
    browser.open(&studio.url());
    browser.wait_for(
        "the pens",
        "return document.querySelector('#layers input');",
    );
    // Pen layers only: the handles drawn over the preview are not one.
    let shown = "return [...document.querySelectorAll('#preview svg > g')].filter(g => \
        g.getAttribute('inkscape:groupmode') === 'layer' && g.style.display !== 'none').length;";
    let all = browser.eval(shown, &[]).as_u64().unwrap();
    browser.click("#layers input");
    assert_eq!(browser.eval(shown, &[]).as_u64().unwrap(), all - 1);
    browser.click("#layers input");
    assert_eq!(browser.eval(shown, &[]).as_u64().unwrap(), all);
    browser.assert_no_page_errors();
    studio.stop();
}

#[test]
fn a_stroke_drawn_with_a_pen_grows_the_sketch_while_the_pen_is_down() {
    let Some(browser) = Browser::start() else {
        return;
    };
    let text = moyo::templates::get("lsystem-sketch-s").unwrap().text;
    let (studio, _dir) = studio(text);
    browser.open(&studio.url());
    let before = browser.wait_for("the first preview", PREVIEW);
    browser.wait_for(
        "the sketches to draw into",
        "return document.getElementById('pen-target').value === 'layers[0].lsystem[0]';",
    );
    browser.click("input[name=tool][value=pen]");
    let steps =
        "const g = document.getElementById('studio-sketch'); return g ? +g.dataset.steps : -1;";
    // The pen goes down low on the page, inside its margins (a stroke that
    // leaves the drawable area stops growing there), and moves up it; the
    // action ends with the pen still down. (The preview is found again
    // each time: a render replaces it.)
    let moves = |from: i64, count: usize| -> Vec<Value> {
        let svg = browser.element("#preview svg");
        let mut list = Vec::new();
        for i in 0..count {
            let k = from + i as i64;
            let x = (30.0 * (k as f64 / 6.0).sin()) as i64;
            list.push(json!({"type": "pointerMove", "origin": {ELEMENT: svg.clone()}, "x": x, "y": 200 - 10 * k, "duration": 30}));
        }
        list
    };
    let pen = |actions: Vec<Value>| browser.point("pen", actions);
    let mut first = moves(0, 1);
    first.push(json!({"type": "pointerDown", "button": 0}));
    first.extend(moves(1, 20));
    pen(first);
    let early = browser
        .wait_for(
            "the sketch to grow under the pen",
            &format!("const n = (() => {{ {steps} }})(); return n > 0 && n;"),
        )
        .as_i64()
        .unwrap();
    // Still drawing: nothing is written yet.
    let now = browser.eval("return document.getElementById('text').value;", &[]);
    assert_eq!(now.as_str().unwrap(), text);
    pen(moves(21, 20));
    browser.wait_for(
        "more growth as the stroke lengthens",
        &format!("return (() => {{ {steps} }})() > {early};"),
    );
    let mut last = vec![json!({"type": "pointerUp", "button": 0})];
    last.insert(0, json!({"type": "pause", "duration": 50}));
    pen(last);
    // The pen lifted: the stroke is the sketch's points, and the preview
    // is the render of it.
    let written = browser.wait_for(
        "the stroke to be written",
        "const t = document.getElementById('text').value; return !t.includes('[40, 182]') && t;",
    );
    let written = written.as_str().unwrap().to_string();
    assert!(written.contains("smooth = false"), "{written}");
    let spec = moyo::ValidSpec::parse(&written, moyo::Format::Toml).unwrap();
    let points = spec.spec().layers[0].lsystem[0]
        .sketch
        .as_ref()
        .unwrap()
        .points
        .clone()
        .unwrap();
    assert!(points.len() > 20, "{points:?}");
    // Drawn up the page: the stroke's end is far above its start.
    assert!(
        points[0][1] - points[points.len() - 1][1] > 50.0,
        "{points:?}"
    );
    browser.wait_for(
        "the render to replace the live drawing",
        &format!(
            "return !document.getElementById('studio-sketch') && (() => {{ {PREVIEW} }})() !== {};",
            json!(before)
        ),
    );
    // A stroke for a new sketch makes a new table, and the choice stays
    // for the next stroke.
    browser.eval(
        "document.getElementById('pen-target').value = 'new:0';",
        &[],
    );
    let mut second = moves(0, 1);
    second.push(json!({"type": "pointerDown", "button": 0}));
    second.extend(moves(1, 12));
    second.push(json!({"type": "pointerUp", "button": 0}));
    pen(second);
    browser.wait_for(
        "a new sketch",
        "return document.getElementById('text').value.includes('id = \"sketch-1\"');",
    );
    browser.wait_for(
        "the targets to be read again",
        "return [...document.getElementById('pen-target').options].some(o => o.textContent.includes('sketch-1'));",
    );
    assert_eq!(
        browser.eval("return document.getElementById('pen-target').value;", &[]),
        json!("new:0")
    );
    browser.assert_no_page_errors();
    studio.stop();
}

#[test]
fn a_click_in_a_zentangle_fills_the_region_under_it() {
    let Some(browser) = Browser::start() else {
        return;
    };
    let (studio, _dir) = studio(crate::studio_gestures::TILE);
    browser.open(&studio.url());
    browser.wait_for("the first preview", PREVIEW);
    browser.wait_for(
        "the fills to choose from",
        "return document.getElementById('tangle-target').value === 'layers[0].zentangle[0]';",
    );
    browser.click("input[name=tool][value=tangle]");
    browser.eval("document.getElementById('procedure').value = '18';", &[]);
    let drawn = "return document.querySelectorAll('#preview [id*=\".step-1-p18\"]').length;";
    assert_eq!(browser.eval(drawn, &[]), json!(0));
    // Click in the lower part of the tile, below the pencil line.
    let svg = browser.element("#preview svg");
    browser.point(
        "mouse",
        vec![
            json!({"type": "pointerMove", "origin": {ELEMENT: svg}, "x": 0, "y": 120}),
            json!({"type": "pointerDown", "button": 0}),
            json!({"type": "pointerUp", "button": 0}),
        ],
    );
    browser.wait_for(
        "the region to be filled",
        "return document.querySelectorAll('#preview [id*=\".step-1-p18\"]').length > 0;",
    );
    let text = browser.eval("return document.getElementById('text').value;", &[]);
    assert!(
        text.as_str().unwrap().contains("procedure = 18 }]"),
        "{text}"
    );
    browser.assert_no_page_errors();
    studio.stop();
}

#[test]
fn a_tree_dragged_in_the_arrange_tool_moves_and_is_written_as_its_adjustment() {
    let Some(browser) = Browser::start() else {
        return;
    };
    let (studio, _dir) = studio(SCENE);
    browser.open(&studio.url());
    browser.wait_for("the first preview", PREVIEW);
    browser.click("input[name=tool][value=arrange]");
    let tree = "const t = document.getElementById('front.pine.tree-1'); return t && t.getBoundingClientRect().x;";
    let before = browser.wait_for("the tree", tree).as_f64().unwrap();
    browser.drag("g[id=\"front.pine.tree-1\"]", -90, 0);
    let text = browser.wait_for(
        "the adjustment",
        "const t = document.getElementById('text').value; return t.includes('[[adjust]]') && t;",
    );
    let text = text.as_str().unwrap();
    assert!(text.contains("id = \"front.pine.tree-1\""), "{text}");
    let spec = moyo::ValidSpec::parse(text, moyo::Format::Toml).unwrap();
    let [dx, dy] = spec.spec().adjust[0].offset.unwrap();
    assert!(dx < -5.0 && dy.abs() < 1.0, "{dx}, {dy}");
    // The rendered tree stands where it was dropped.
    browser.wait_for(
        "the tree to move",
        &format!("const t = document.getElementById('front.pine.tree-1'); return t && !t.hasAttribute('transform') && t.getBoundingClientRect().x < {before} - 20;"),
    );
    // Shift and a sideways drag from the middle turn it: the picture
    // turns while the button is down, and the turn is written on release.
    let tree = browser.element("g[id=\"front.pine.tree-1\"]");
    let mut moves = vec![
        json!({"type": "pointerMove", "origin": {ELEMENT: tree}, "x": 0, "y": 0}),
        json!({"type": "pointerDown", "button": 0}),
    ];
    moves.extend((0..4).map(
        |_| json!({"type": "pointerMove", "origin": "pointer", "x": 10, "y": 0, "duration": 30}),
    ));
    let shift = |kind: &str| json!({"type": "key", "id": "keys", "actions": [{"type": kind, "value": "\u{E008}"}]});
    browser.command("POST", "/actions", &json!({"actions": [
        {"type": "key", "id": "keys", "actions": [{"type": "keyDown", "value": "\u{E008}"}, {"type": "pause"}, {"type": "pause"}, {"type": "pause"}, {"type": "pause"}, {"type": "pause"}]},
        {"type": "pointer", "id": "mouse", "parameters": {"pointerType": "mouse"}, "actions": moves},
    ]}));
    let live = browser.eval(
        "return document.getElementById('front.pine.tree-1').getAttribute('transform');",
        &[],
    );
    assert!(
        live.as_str().is_some_and(|t| t.starts_with("matrix(")),
        "{live}"
    );
    browser.point("mouse", vec![json!({"type": "pointerUp", "button": 0})]);
    browser.command("POST", "/actions", &json!({"actions": [shift("keyUp")]}));
    let turned = browser.wait_for(
        "the turn",
        "const m = document.getElementById('text').value.match(/rotate = ([-\\d.]+)/); return m && +m[1];",
    );
    // 40 px sideways, half a degree a pixel: clockwise.
    assert_eq!(turned, json!(20));
    browser.assert_no_page_errors();
    studio.stop();
}

#[test]
fn a_drag_in_the_turn_tool_turns_the_camera_round_a_vine() {
    let Some(browser) = Browser::start() else {
        return;
    };
    let (studio, _dir) = studio(moyo::templates::get("vine-basic").unwrap().text);
    browser.open(&studio.url());
    let before = browser.wait_for("the first preview", PREVIEW);
    browser.wait_for(
        "the vines to turn",
        "return document.getElementById('vine-target').value === 'layers[0].vine[0]';",
    );
    browser.click("input[name=tool][value=orbit]");
    browser.drag("#preview svg", -120, 40);
    // Dragged 120 px to the left: the camera went round to the right by
    // a quarter degree a pixel; 36 px down (six steps of 6): from above.
    // Every step of the drag counts, even those made while a render was
    // on its way.
    browser.wait_for(
        "the camera to be written",
        "return document.getElementById('text').value.includes('camera = { turn = 30.0, tilt = 9.0 }');",
    );
    browser.wait_for(
        "the turned vine",
        &format!("return (() => {{ {PREVIEW} }})() !== {};", json!(before)),
    );
    browser.assert_no_page_errors();
    studio.stop();
}
