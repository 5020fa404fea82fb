//! The studio's HTTP API, over a real socket, as the page and any other
//! client use it: the description in and out, errors as JSON with their
//! place, the last good preview kept through errors, undo and redo,
//! saving and opening inside the folder only, exports, the guard against
//! other hosts and origins, and requests that are malformed or too large.

use std::io::{Read, Write};
use std::net::{SocketAddr, TcpStream};
use std::time::Duration;

use moyo::studio::{Studio, StudioOptions, MAX_BODY};

use crate::cli::tempdir;

pub(crate) const SCENE: &str =
    "version = 1\nseed = 3\n\n[page]\nsize = \"A5\"\n\n[[layers]]\nname = \"front\"\n\n\
                     [[layers.trees]]\nid = \"pine\"\nrule = \"tree1\"\ncount = 2   # two trees\n\
                     centre = [[20, 150], [120, 150]]\n";

/// An answer: status, headers (lower-case names) and body.
pub(crate) struct Answer {
    pub(crate) status: u16,
    headers: Vec<(String, String)>,
    pub(crate) body: Vec<u8>,
}

impl Answer {
    fn header(&self, name: &str) -> Option<&str> {
        self.headers
            .iter()
            .find(|(n, _)| n == name)
            .map(|(_, v)| v.as_str())
    }

    pub(crate) fn text(&self) -> String {
        String::from_utf8_lossy(&self.body).into_owned()
    }

    pub(crate) fn json(&self) -> serde_json::Value {
        serde_json::from_slice(&self.body).unwrap_or_else(|e| panic!("{e}: {}", self.text()))
    }
}

/// Sends raw bytes and reads the whole answer: as long as its
/// `Content-Length` says, or else until the server closes (the request
/// asks it to; chromedriver says it will but does not).
pub(crate) fn raw(addr: SocketAddr, request: &[u8]) -> Answer {
    let mut stream = TcpStream::connect(addr).unwrap();
    stream
        .set_read_timeout(Some(Duration::from_secs(120)))
        .unwrap();
    stream.write_all(request).unwrap();
    let mut bytes = Vec::new();
    let mut chunk = [0_u8; 64 * 1024];
    let mut wanted: Option<usize> = None;
    loop {
        if let Some(split) = bytes.windows(4).position(|w| w == b"\r\n\r\n") {
            if wanted.is_none() {
                let head = String::from_utf8_lossy(&bytes[..split]).to_ascii_lowercase();
                wanted = head
                    .lines()
                    .find_map(|l| l.strip_prefix("content-length:"))
                    .and_then(|v| v.trim().parse::<usize>().ok())
                    .map(|n| split + 4 + n);
            }
            if wanted.is_some_and(|n| bytes.len() >= n) {
                break;
            }
        }
        match stream.read(&mut chunk) {
            Ok(0) | Err(_) => break,
            Ok(n) => bytes.extend_from_slice(&chunk[..n]),
        }
    }
    let split = bytes
        .windows(4)
        .position(|w| w == b"\r\n\r\n")
        .unwrap_or_else(|| panic!("no answer: {:?}", String::from_utf8_lossy(&bytes)));
    let head = String::from_utf8_lossy(&bytes[..split]).into_owned();
    let mut lines = head.lines();
    let status = lines
        .next()
        .unwrap()
        .split(' ')
        .nth(1)
        .unwrap()
        .parse()
        .unwrap();
    let headers: Vec<(String, String)> = lines
        .filter_map(|l| l.split_once(':'))
        .map(|(n, v)| (n.trim().to_ascii_lowercase(), v.trim().to_string()))
        .collect();
    let mut body = bytes[split + 4..].to_vec();
    if headers
        .iter()
        .any(|(n, v)| n == "transfer-encoding" && v == "chunked")
    {
        body = dechunk(&body);
    }
    Answer {
        status,
        headers,
        body,
    }
}

fn dechunk(mut bytes: &[u8]) -> Vec<u8> {
    let mut out = Vec::new();
    loop {
        let end = bytes.windows(2).position(|w| w == b"\r\n").unwrap();
        let size =
            usize::from_str_radix(std::str::from_utf8(&bytes[..end]).unwrap().trim(), 16).unwrap();
        if size == 0 {
            return out;
        }
        out.extend_from_slice(&bytes[end + 2..end + 2 + size]);
        bytes = &bytes[end + 2 + size + 2..];
    }
}

/// A request to the studio at `addr`, with `extra` header lines.
pub(crate) fn call(
    addr: SocketAddr,
    method: &str,
    path: &str,
    extra: &[&str],
    body: &[u8],
) -> Answer {
    let mut request = format!(
        "{method} {path} HTTP/1.1\r\nHost: {addr}\r\nConnection: close\r\nContent-Length: {}\r\n",
        body.len()
    );
    for line in extra {
        request.push_str(line);
        request.push_str("\r\n");
    }
    request.push_str("\r\n");
    let mut bytes = request.into_bytes();
    bytes.extend_from_slice(body);
    raw(addr, &bytes)
}

pub(crate) fn get(addr: SocketAddr, path: &str) -> Answer {
    call(addr, "GET", path, &[], b"")
}

fn json(addr: SocketAddr, method: &str, path: &str, body: &serde_json::Value) -> Answer {
    call(
        addr,
        method,
        path,
        &["Content-Type: application/json"],
        body.to_string().as_bytes(),
    )
}

/// A studio on a free port in a new folder, started on `text`.
pub(crate) fn studio(text: &str) -> (Studio, tempfile::TempDir) {
    let dir = tempdir();
    let studio = Studio::start(StudioOptions {
        folder: dir.path().to_path_buf(),
        text: text.to_string(),
        addr: "127.0.0.1:0".parse().unwrap(),
    })
    .unwrap();
    (studio, dir)
}

#[test]
fn the_description_goes_in_and_the_svg_comes_out() {
    let (studio, _dir) = studio(SCENE);
    let addr = studio.addr();
    let page = get(addr, "/");
    assert_eq!(page.status, 200);
    assert!(page.text().contains("moyo studio"));
    assert_eq!(get(addr, "/api/scene").text(), SCENE);
    let first = get(addr, "/api/svg");
    assert_eq!(first.status, 200);
    assert!(first
        .header("content-type")
        .unwrap()
        .starts_with("image/svg+xml"));
    assert!(first.text().contains("inkscape:groupmode=\"layer\""));

    // A new seed: 200 with the new SVG, which is now the design's.
    let changed = SCENE.replace("seed = 3", "seed = 4");
    let put = call(addr, "PUT", "/api/scene", &[], changed.as_bytes());
    assert_eq!(put.status, 200, "{}", put.text());
    assert_ne!(put.body, first.body);
    assert_eq!(get(addr, "/api/svg").body, put.body);
    assert_eq!(get(addr, "/api/scene").text(), changed);
    assert_eq!(put.header("x-moyo-undo"), Some("1"));
    // The same description renders to the same bytes as the command line.
    let spec = moyo::ValidSpec::parse(&changed, moyo::Format::Toml).unwrap();
    let cli = moyo::render(&spec).unwrap();
    assert_eq!(put.text(), cli.svg);
    // The preview view is the colour preview of the design as drawn, its
    // layers and groups kept for the page to point at (no pen stage).
    let editing = moyo::project::render_for_editing(
        &spec,
        &moyo::motif::Library::new(),
        &mut |_| {},
        &moyo::project::Cancel::default(),
    )
    .unwrap();
    let preview = call(
        addr,
        "PUT",
        "/api/scene?view=preview",
        &[],
        changed.as_bytes(),
    );
    assert_eq!(preview.text(), editing.preview_svg());
    studio.stop();
}

#[test]
fn an_invalid_edit_is_422_with_its_place_and_keeps_the_last_good_svg() {
    let (studio, _dir) = studio(SCENE);
    let addr = studio.addr();
    let good = get(addr, "/api/svg").body;
    let bad = SCENE.replace("count = 2", "count = -4");
    let answer = call(addr, "PUT", "/api/scene", &[], bad.as_bytes());
    assert_eq!(answer.status, 422);
    let e = answer.json();
    assert_eq!(e["path"], "layers[0].trees[0].count");
    assert_eq!(
        (e["line"].as_u64(), e["column"].as_u64()),
        (Some(13), Some(9))
    );
    assert!(
        e["error"]
            .as_str()
            .unwrap()
            .starts_with("13:9: layers[0].trees[0].count"),
        "{e}"
    );
    // The text is kept as written, the SVG is the last good one, and the
    // state says what is wrong.
    assert_eq!(get(addr, "/api/scene").text(), bad);
    assert_eq!(get(addr, "/api/svg").body, good);
    let state = get(addr, "/api/state").json();
    assert_eq!(state["rendered"], false);
    assert_eq!(state["error"]["path"], "layers[0].trees[0].count");
    // Not TOML at all: 422 with the parser's place.
    let answer = call(addr, "PUT", "/api/scene", &[], b"version = 1\n[[layers]\n");
    assert_eq!(answer.status, 422);
    assert_eq!(answer.json()["line"], 2);
    // Not UTF-8.
    assert_eq!(
        call(addr, "PUT", "/api/scene", &[], &[0xff, 0xfe]).status,
        422
    );
    studio.stop();
}

#[test]
fn fields_come_with_their_ranges_and_change_in_place() {
    let (studio, _dir) = studio(SCENE);
    let addr = studio.addr();
    let fields = get(addr, "/api/fields").json();
    let count = fields
        .as_array()
        .unwrap()
        .iter()
        .find(|f| f["field"] == "layers[0].trees[0].count")
        .unwrap()
        .clone();
    assert_eq!(
        (
            count["lo"].as_f64(),
            count["hi"].as_f64(),
            count["value"].as_f64()
        ),
        (Some(0.0), Some(10_000.0), Some(2.0))
    );
    assert_eq!(count["integer"], true);
    let answer = json(
        addr,
        "PATCH",
        "/api/field",
        &serde_json::json!({"field": "layers[0].trees[0].count", "value": 3, "integer": true}),
    );
    assert_eq!(answer.status, 200, "{}", answer.text());
    let d = answer.json();
    // The comment after the value stays.
    assert!(
        d["scene"]
            .as_str()
            .unwrap()
            .contains("count = 3   # two trees"),
        "{d}"
    );
    assert_eq!(d["undo"], 1);
    // Out of range: 422 naming the field; the design stays.
    let answer = json(
        addr,
        "PATCH",
        "/api/field",
        &serde_json::json!({"field": "layers[0].trees[0].count", "value": 20000, "integer": true}),
    );
    assert_eq!(answer.status, 422);
    assert_eq!(answer.json()["path"], "layers[0].trees[0].count");
    studio.stop();
}

#[test]
fn lines_of_points_are_handles_and_a_point_moves_as_one_edit() {
    let text = SCENE.replace(
        "[[layers]]",
        "[lines]\nupper = [[0, 40], [128, 30]]\n\n[[layers]]",
    );
    let (studio, _dir) = studio(&text);
    let addr = studio.addr();
    let handles = get(addr, "/api/handles").json();
    assert_eq!(handles["offset"], serde_json::json!([10.0, 10.0]));
    let fields: Vec<&str> = handles["lines"]
        .as_array()
        .unwrap()
        .iter()
        .map(|l| l["field"].as_str().unwrap())
        .collect();
    assert_eq!(fields, ["layers[0].trees[0].centre", "lines.upper"]);
    assert_eq!(
        handles["lines"][0]["points"],
        serde_json::json!([[20.0, 150.0], [120.0, 150.0]])
    );
    // Both coordinates of a dragged point: one edit, one step of undo.
    let moved = json(
        addr,
        "PATCH",
        "/api/fields",
        &serde_json::json!({"changes": [
            {"field": "layers[0].trees[0].centre[0][0]", "value": 35.5},
            {"field": "layers[0].trees[0].centre[0][1]", "value": 140},
        ]}),
    );
    assert_eq!(moved.status, 200, "{}", moved.text());
    let d = moved.json();
    assert!(
        d["scene"]
            .as_str()
            .unwrap()
            .contains("centre = [[35.5, 140.0], [120, 150]]"),
        "{d}"
    );
    assert_eq!(d["undo"], 1);
    let handles = get(addr, "/api/handles").json();
    assert_eq!(
        handles["lines"][0]["points"][0],
        serde_json::json!([35.5, 140.0])
    );
    studio.stop();
}

#[test]
fn undo_and_redo_walk_the_good_descriptions() {
    let (studio, _dir) = studio(SCENE);
    let addr = studio.addr();
    let first = get(addr, "/api/svg").body;
    assert_eq!(call(addr, "POST", "/api/undo", &[], b"").status, 409);
    let four = SCENE.replace("seed = 3", "seed = 4");
    let five = SCENE.replace("seed = 3", "seed = 5");
    call(addr, "PUT", "/api/scene", &[], four.as_bytes());
    // An invalid edit in between is not a step of the history.
    call(addr, "PUT", "/api/scene", &[], b"version = 2");
    call(addr, "PUT", "/api/scene", &[], five.as_bytes());
    let back = call(addr, "POST", "/api/undo", &[], b"").json();
    assert_eq!(back["scene"], four.as_str());
    assert_eq!(
        (back["undo"].as_u64(), back["redo"].as_u64()),
        (Some(1), Some(1))
    );
    let back = call(addr, "POST", "/api/undo", &[], b"").json();
    assert_eq!(back["scene"], SCENE);
    assert_eq!(get(addr, "/api/svg").body, first);
    let again = call(addr, "POST", "/api/redo", &[], b"").json();
    assert_eq!(again["scene"], four.as_str());
    // A new edit forgets what could be redone.
    call(addr, "PUT", "/api/scene", &[], five.as_bytes());
    assert_eq!(get(addr, "/api/state").json()["redo"], 0);
    studio.stop();
}

#[test]
fn files_are_saved_and_opened_inside_the_folder_only() {
    let (studio, dir) = studio(SCENE);
    let addr = studio.addr();
    let save = |path: &str| {
        json(
            addr,
            "POST",
            "/api/save",
            &serde_json::json!({ "path": path }),
        )
    };
    assert_eq!(save("design.toml").status, 200);
    assert_eq!(
        std::fs::read_to_string(dir.path().join("design.toml")).unwrap(),
        SCENE
    );
    assert_eq!(save("design.svg").status, 200);
    let svg = std::fs::read_to_string(dir.path().join("design.svg")).unwrap();
    assert_eq!(svg.as_bytes(), get(addr, "/api/svg").body);
    for outside in ["../escape.toml", "/tmp/escape.toml", "a/../../escape.svg"] {
        let answer = save(outside);
        assert_eq!(answer.status, 422, "{outside}");
        assert!(answer.json()["error"]
            .as_str()
            .unwrap()
            .contains("only inside its folder"));
    }
    assert!(!dir.path().parent().unwrap().join("escape.toml").exists());
    assert_eq!(save("design.txt").status, 422);
    // Open the SVG back: its embedded description becomes the design.
    call(
        addr,
        "PUT",
        "/api/scene",
        &[],
        SCENE.replace("seed = 3", "seed = 9").as_bytes(),
    );
    let opened = json(
        addr,
        "POST",
        "/api/open",
        &serde_json::json!({"path": "design.svg"}),
    );
    assert_eq!(opened.status, 200, "{}", opened.text());
    assert_eq!(get(addr, "/api/svg").text(), svg);
    let outside = json(
        addr,
        "POST",
        "/api/open",
        &serde_json::json!({"path": "../../etc/passwd"}),
    );
    assert_eq!(outside.status, 422);
    // A description naming a file outside the folder cannot read it.
    let sneaky =
        "version = 1\n[[layers]]\nname = \"a\"\n[[layers.paths]]\nsvg = \"../outside.svg\"\n";
    std::fs::write(dir.path().parent().unwrap().join("outside.svg"), "<svg/>").ok();
    let answer = call(addr, "PUT", "/api/scene", &[], sneaky.as_bytes());
    assert_eq!(answer.status, 422);
    assert!(
        answer.text().contains("only inside its folder"),
        "{}",
        answer.text()
    );
    studio.stop();
}

#[test]
fn exports_go_through_the_plot_pipeline() {
    let (studio, _dir) = studio(SCENE);
    let addr = studio.addr();
    let png = get(addr, "/api/export?format=png&dpi=20");
    assert_eq!(png.status, 200);
    assert_eq!(png.header("content-type"), Some("image/png"));
    assert!(png.body.starts_with(b"\x89PNG"));
    let gcode = get(addr, "/api/export?format=gcode");
    assert_eq!(gcode.status, 200);
    assert!(gcode.text().contains("G1 "), "{}", gcode.text());
    let hpgl = get(addr, "/api/export?format=hpgl");
    assert!(hpgl.text().starts_with("IN;"), "{}", hpgl.text());
    assert_eq!(get(addr, "/api/export?format=pdf").status, 422);
    assert_eq!(get(addr, "/api/export?format=png&dpi=100000").status, 422);
    studio.stop();
}

#[test]
fn other_hosts_and_origins_are_refused() {
    let (studio, _dir) = studio(SCENE);
    let addr = studio.addr();
    let port = addr.port();
    let request = |host: &str, origin: Option<&str>| {
        let mut r = format!("GET /api/scene HTTP/1.1\r\nHost: {host}\r\nConnection: close\r\n");
        if let Some(o) = origin {
            r.push_str(&format!("Origin: {o}\r\n"));
        }
        r.push_str("\r\n");
        raw(addr, r.as_bytes()).status
    };
    assert_eq!(request(&format!("127.0.0.1:{port}"), None), 200);
    assert_eq!(request(&format!("localhost:{port}"), None), 200);
    // DNS rebinding: a name that resolves here but is not this studio.
    assert_eq!(request(&format!("evil.example:{port}"), None), 403);
    assert_eq!(request("127.0.0.1", None), 403);
    // A page elsewhere calling in.
    let own = format!("http://127.0.0.1:{port}");
    assert_eq!(request(&format!("127.0.0.1:{port}"), Some(&own)), 200);
    assert_eq!(
        request(&format!("127.0.0.1:{port}"), Some("http://evil.example")),
        403
    );
    assert_eq!(request(&format!("127.0.0.1:{port}"), Some("null")), 403);
    let no_host = raw(addr, b"GET /api/scene HTTP/1.0\r\n\r\n");
    assert_eq!(no_host.status, 403);
    studio.stop();
}

#[test]
fn malformed_and_oversized_requests_never_stop_the_server() {
    let (studio, _dir) = studio(SCENE);
    let addr = studio.addr();
    let too_big = vec![b'#'; MAX_BODY + 1];
    assert_eq!(call(addr, "PUT", "/api/scene", &[], &too_big).status, 413);
    assert_eq!(
        call(
            addr,
            "PATCH",
            "/api/field",
            &["Content-Type: application/json"],
            b"{nope"
        )
        .status,
        400
    );
    assert_eq!(get(addr, "/api/nothing").status, 404);
    assert_eq!(call(addr, "DELETE", "/api/scene", &[], b"").status, 405);
    for garbage in [
        &b"\x00\x01\x02\r\n\r\n"[..],
        b"GET / HTTP/9.9\r\n\r\n",
        b"PUT /api/scene HTTP/1.1\r\nContent-Length: 99999999999999999999\r\n\r\n",
    ] {
        let mut stream = TcpStream::connect(addr).unwrap();
        stream
            .set_read_timeout(Some(Duration::from_secs(10)))
            .unwrap();
        let _ = stream.write_all(garbage);
        let mut sink = Vec::new();
        let _ = stream.read_to_end(&mut sink);
    }
    // Still answering, with the design unchanged.
    assert_eq!(get(addr, "/api/scene").text(), SCENE);
    studio.stop();
}

#[test]
fn a_newer_edit_calls_off_the_render_before_it() {
    // A heavy design first, then a light one while it renders: the heavy
    // one is answered 409 and the light one is the design.
    let heavy = moyo::templates::get("kimono-tangles").unwrap().text;
    let (studio, _dir) = studio(SCENE);
    let addr = studio.addr();
    let slow = std::thread::spawn(move || call(addr, "PUT", "/api/scene", &[], heavy.as_bytes()));
    std::thread::sleep(Duration::from_millis(300));
    let light = SCENE.replace("seed = 3", "seed = 8");
    let fast = call(addr, "PUT", "/api/scene", &[], light.as_bytes());
    assert_eq!(fast.status, 200);
    let slow = slow.join().unwrap();
    assert_eq!(slow.status, 409, "{}", slow.text());
    assert!(slow.text().contains("cancelled"));
    assert_eq!(get(addr, "/api/scene").text(), light);
    studio.stop();
}

#[test]
fn the_command_starts_on_a_json_description_as_toml_and_names_a_broken_one() {
    use std::io::BufRead;
    let dir = tempdir();
    let spec = moyo::ValidSpec::parse(SCENE, moyo::Format::Toml).unwrap();
    let json = serde_json::to_string_pretty(spec.spec()).unwrap();
    std::fs::write(dir.path().join("scene.json"), &json).unwrap();
    let mut child = std::process::Command::new(assert_cmd::cargo::cargo_bin("moyo"))
        .current_dir(dir.path())
        .args(["studio", "scene.json", "--port", "0"])
        .stderr(std::process::Stdio::piped())
        .spawn()
        .unwrap();
    let mut line = String::new();
    std::io::BufReader::new(child.stderr.take().unwrap())
        .read_line(&mut line)
        .unwrap();
    let url = line
        .split_whitespace()
        .find(|w| w.starts_with("http://"))
        .unwrap_or_else(|| panic!("{line}"));
    let addr: SocketAddr = url
        .trim_start_matches("http://")
        .trim_end_matches('/')
        .parse()
        .unwrap();
    let text = get(addr, "/api/scene").text();
    let _ = child.kill();
    let _ = child.wait();
    // TOML now, the same description.
    let back = moyo::ValidSpec::parse(&text, moyo::Format::Toml).unwrap();
    assert_eq!(back.spec(), spec.spec());
    // A broken one: its file, line and column, and no server.
    std::fs::write(
        dir.path().join("bad.json"),
        "{\n  \"version\": 1,\n  \"seed\": \"x\"\n}",
    )
    .unwrap();
    let out = crate::cli::moyo(&dir)
        .args(["studio", "bad.json", "--port", "0"])
        .output()
        .unwrap();
    assert!(!out.status.success());
    let e = String::from_utf8_lossy(&out.stderr);
    assert!(e.contains("bad.json:3:"), "{e}");
}

#[test]
fn switches_and_words_are_fields_too() {
    let text = moyo::templates::get("lsystem-sketch-s").unwrap().text;
    let (studio, _dir) = studio(text);
    let addr = studio.addr();
    let fields = get(addr, "/api/fields").json();
    let find = |name: &str| {
        fields
            .as_array()
            .unwrap()
            .iter()
            .find(|f| f["field"] == name)
            .unwrap_or_else(|| panic!("{name} in {fields}"))
            .clone()
    };
    let style = find("layers[0].lsystem[0].style");
    assert_eq!(style["kind"], "choice");
    assert_eq!(style["value"], "outline");
    let options = style["options"].as_array().unwrap();
    assert!(
        options.contains(&"outline".into()) && options.len() >= 2,
        "{style}"
    );
    let silhouettes = find("plot.occlude.silhouettes");
    assert_eq!(
        (silhouettes["kind"].clone(), silhouettes["value"].clone()),
        ("bool".into(), true.into())
    );
    // Free text (names, ids, colours) is not a choice.
    assert!(fields
        .as_array()
        .unwrap()
        .iter()
        .all(|f| f["field"] != "layers[0].name"));
    // Both change in place, as one edit.
    let changed = call(
        addr,
        "PATCH",
        "/api/fields",
        &["Content-Type: application/json"],
        serde_json::json!({"changes": [
            {"field": "layers[0].lsystem[0].style", "value": "stroke"},
            {"field": "plot.occlude.silhouettes", "value": false},
        ]})
        .to_string()
        .as_bytes(),
    );
    assert_eq!(changed.status, 200, "{}", changed.text());
    let written = get(addr, "/api/scene").text();
    assert!(
        written.contains("style = \"stroke\"\n") && written.contains("silhouettes = false\n"),
        "{written}"
    );
    // A word the field does not take: 422 with its place, the design as it was.
    let refused = call(
        addr,
        "PATCH",
        "/api/field",
        &["Content-Type: application/json"],
        serde_json::json!({"field": "layers[0].lsystem[0].style", "value": "wavy"})
            .to_string()
            .as_bytes(),
    );
    assert_eq!(refused.status, 422);
    assert_eq!(refused.json()["path"], "layers[0].lsystem[0].style");
    studio.stop();
}
