//! The studio's HTTP API, over a real socket, as the page and any other
//! client use it: the description in and out, errors as JSON with their
//! place, the last good preview kept through errors, undo and redo,
//! saving and opening inside the folder only (regular files only),
//! exports (capped in size), the guard against other hosts, origins and
//! sites, `nosniff` on every answer, requests that are malformed or too
//! large, strokes out of range, and connections that stall — past the
//! connection cap, and past the process's open-file limit.

use std::io::{BufRead, Read, Write};
use std::net::{SocketAddr, TcpStream};
use std::path::Path;
use std::process::{Child, Command, Stdio};
use std::time::Duration;

use moyo::studio::{Studio, StudioLimits, StudioOptions, MAX_BODY};

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
    studio_with(text, "127.0.0.1:0", StudioLimits::default())
}

/// A studio on `addr` in a new folder, started on `text`, with `limits`.
fn studio_with(text: &str, addr: &str, limits: StudioLimits) -> (Studio, tempfile::TempDir) {
    let dir = tempdir();
    let studio = Studio::start(StudioOptions {
        folder: dir.path().to_path_buf(),
        text: text.to_string(),
        addr: addr.parse().unwrap(),
        limits,
    })
    .unwrap();
    (studio, dir)
}

/// `moyo studio` running as its own process, ended when dropped.
struct Running {
    child: Child,
    addr: SocketAddr,
}

impl Drop for Running {
    fn drop(&mut self) {
        let _ = self.child.kill();
        let _ = self.child.wait();
    }
}

/// Starts `moyo studio ARGS --port 0` in `dir` with `env`, with at most
/// `files` open files when given (`ulimit -n` in the shell that runs it),
/// and reads the address it prints.
fn command(dir: &Path, args: &[&str], env: &[(&str, &str)], files: Option<u32>) -> Running {
    let moyo = assert_cmd::cargo::cargo_bin("moyo");
    let mut cmd = match files {
        Some(n) => {
            let mut sh = Command::new("sh");
            sh.arg("-c")
                .arg(format!("ulimit -n {n} && exec \"$0\" \"$@\""))
                .arg(moyo);
            sh
        }
        None => Command::new(moyo),
    };
    cmd.current_dir(dir)
        .arg("studio")
        .args(args)
        .args(["--port", "0"])
        .envs(env.iter().copied())
        .stderr(Stdio::piped());
    let mut child = cmd.spawn().unwrap();
    let mut line = String::new();
    std::io::BufReader::new(child.stderr.take().unwrap())
        .read_line(&mut line)
        .unwrap();
    let url = line
        .split_whitespace()
        .find(|w| w.starts_with("http://"))
        .unwrap_or_else(|| panic!("{line}"));
    let addr = url
        .trim_start_matches("http://")
        .trim_end_matches('/')
        .parse()
        .unwrap();
    Running { child, addr }
}

/// Whether the server has closed `stream` (waiting as long as it takes,
/// up to two minutes): an end of file or a reset, not a timeout.
fn closed_by_server(stream: &mut TcpStream) -> bool {
    stream
        .set_read_timeout(Some(Duration::from_secs(120)))
        .unwrap();
    let mut byte = [0_u8; 1];
    match stream.read(&mut byte) {
        Ok(0) => true,
        Ok(_) => false,
        Err(e) => matches!(
            e.kind(),
            std::io::ErrorKind::ConnectionReset | std::io::ErrorKind::ConnectionAborted
        ),
    }
}

/// The page's procedure picker offers every procedure a click may give:
/// the paper's twenty and each named tangle, in the order of their ids.
#[test]
fn the_procedure_picker_offers_the_named_tangles_too() {
    let (studio, _dir) = studio(SCENE);
    let page = get(studio.addr(), "/").text();
    let list = page
        .split("const PROCEDURES = [")
        .nth(1)
        .and_then(|rest| rest.split("];").next())
        .expect("the page lists the procedures");
    let names: Vec<String> = list
        .split(',')
        .map(|n| n.trim().trim_matches('"').to_lowercase())
        .collect();
    assert_eq!(names.len(), 20 + moyo::spec::TANGLES.len(), "{names:?}");
    for (k, tangle) in moyo::spec::TANGLES.iter().enumerate() {
        let shown = names[20 + k].replace(' ', "-").replace('\'', "");
        assert_eq!(&shown, tangle, "procedure {}", 20 + k);
    }
    studio.stop();
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
    // The seed's range is exact (2⁶³−1 has no float), and a bad seed is
    // refused in the words of `moyo render --seed`, not the parser's.
    let seed = get(addr, "/api/fields")
        .json()
        .as_array()
        .unwrap()
        .iter()
        .find(|f| f["field"] == "seed")
        .unwrap()
        .clone();
    assert_eq!(seed["hi"].as_u64(), Some(9_223_372_036_854_775_807));
    assert_eq!(seed["range"], "0 – 9223372036854775807");
    // (A whole-number field from the form is rounded: 1.5 as typed.)
    for (bad, integer) in [
        (serde_json::json!(-1), true),
        (serde_json::json!(1.5), false),
    ] {
        let answer = json(
            addr,
            "PATCH",
            "/api/field",
            &serde_json::json!({"field": "seed", "value": bad, "integer": integer}),
        );
        assert_eq!(answer.status, 422, "{bad}");
        let text = answer.text();
        assert!(
            text.contains("must be a whole number between 0 and 9223372036854775807")
                && !text.contains("expected u64"),
            "{bad}: {text}"
        );
    }
    let answer = json(
        addr,
        "PATCH",
        "/api/field",
        &serde_json::json!({"field": "seed", "value": 3, "integer": true}),
    );
    assert_eq!(answer.status, 200, "{}", answer.text());
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

/// 2,000 sites relaxed `relax` steps (within the scene's site-step
/// budget at 500): seconds of work, one unit of progress a step.
fn relaxation(relax: u32) -> String {
    format!(
        "version = 1\nseed = 4\n\n[page]\nsize = \"A5\"\n\n[[layers]]\nname = \"cells\"\n\n\
         [[layers.voronoi]]\nid = \"heavy\"\nrelax = {relax}\n\n[layers.voronoi.sites]\n\
         distribution = \"uniform\"\ncount = 2000\n"
    )
}

#[test]
fn a_relaxation_called_off_runs_no_step_after() {
    // Counted in steps, not time: the flag raised as step 3 reports, the
    // render stops at the start of step 4 (checked before each step and
    // each cell), where before it ran every step and stopped after.
    let spec = moyo::ValidSpec::parse(&relaxation(400), moyo::Format::Toml).unwrap();
    let library = moyo::project::load_motifs(&spec, Path::new(".")).unwrap();
    let cancel = moyo::project::Cancel::default();
    let (mut steps, mut after) = (0, 0);
    let result = moyo::project::render_cancellable(
        &spec,
        &library,
        &mut |_| {
            if cancel.is_raised() {
                after += 1;
            } else {
                steps += 1;
                if steps == 3 {
                    cancel.raise();
                }
            }
        },
        &cancel,
    );
    assert!(matches!(result, Err(moyo::Error::Cancelled)), "{result:?}");
    assert_eq!((steps, after), (3, 0));
}

#[test]
fn a_heavy_relaxation_is_called_off_by_a_light_edit() {
    // 400 steps on 2,000 sites take tens of seconds here; the light edit
    // behind it is the design, the heavy one is answered 409.
    let (studio, _dir) = studio(SCENE);
    let addr = studio.addr();
    let heavy = relaxation(400);
    let slow = std::thread::spawn(move || call(addr, "PUT", "/api/scene", &[], heavy.as_bytes()));
    std::thread::sleep(Duration::from_millis(500));
    let light = SCENE.replace("seed = 3", "seed = 9");
    let fast = call(addr, "PUT", "/api/scene", &[], light.as_bytes());
    assert_eq!(fast.status, 200, "{}", fast.text());
    let slow = slow.join().unwrap();
    assert_eq!(slow.status, 409, "{}", slow.text());
    assert_eq!(get(addr, "/api/scene").text(), light);
    let state = get(addr, "/api/state").json();
    assert_eq!(state["rendered"], true, "{state}");
    studio.stop();
}

#[test]
fn an_edit_past_the_memory_budget_is_422_and_the_last_good_design_stays() {
    // The Hilbert curve at 11 iterations (4.2 million segments, 1.5 GB in
    // release) to a studio allowed 200 MiB: refused while it draws, where
    // it would have grown until the machine ran out.
    let dir = tempdir();
    let mut running = command(dir.path(), &["--memory-mb", "200"], &[], None);
    let addr = running.addr;
    let good = get(addr, "/api/svg");
    assert_eq!(good.status, 200);
    let heavy = std::fs::read_to_string(
        Path::new(env!("CARGO_MANIFEST_DIR")).join("templates/lsystem-hilbert.toml"),
    )
    .unwrap()
    .replace("iterations = 6", "iterations = 11");
    let refused = call(addr, "PUT", "/api/scene", &[], heavy.as_bytes());
    assert_eq!(refused.status, 422, "{}", refused.text());
    let error = refused.json()["error"].as_str().unwrap().to_string();
    assert!(
        error.starts_with("memory budget exceeded: the render held ")
            && error.contains("past the budget of 200 MB"),
        "{error}"
    );
    assert!(
        running.child.try_wait().unwrap().is_none(),
        "the studio ended"
    );
    // The state says why; the design is the last good one.
    let state = get(addr, "/api/state").json();
    assert_eq!(state["rendered"], false, "{state}");
    assert_eq!(state["error"]["error"], error.as_str(), "{state}");
    assert_eq!(get(addr, "/api/svg").body, good.body);
    // And it goes on: a light edit renders.
    let light = call(addr, "PUT", "/api/scene", &[], SCENE.as_bytes());
    assert_eq!(light.status, 200, "{}", light.text());
    assert!(
        running.child.try_wait().unwrap().is_none(),
        "the studio ended"
    );
}

#[test]
fn the_command_starts_on_a_json_description_as_toml_and_names_a_broken_one() {
    let dir = tempdir();
    let spec = moyo::ValidSpec::parse(SCENE, moyo::Format::Toml).unwrap();
    let json = serde_json::to_string_pretty(spec.spec()).unwrap();
    std::fs::write(dir.path().join("scene.json"), &json).unwrap();
    let running = command(dir.path(), &["scene.json"], &[], None);
    let text = get(running.addr, "/api/scene").text();
    drop(running);
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

#[test]
fn stalled_connections_past_the_open_file_limit_do_not_stop_the_studio() {
    // 300 connections that send nothing to a studio that may open 256
    // files: it runs out of descriptors while accepting them, pauses,
    // and lets the stalled ones go at their deadline (shortened here).
    let dir = tempdir();
    let mut running = command(
        dir.path(),
        &[],
        &[("MOYO_STUDIO_HEADER_TIMEOUT_MS", "1000")],
        Some(256),
    );
    let addr = running.addr;
    let mut stalled: Vec<TcpStream> = (0..300)
        .map(|_| TcpStream::connect(addr).unwrap())
        .collect();
    let answer = get(addr, "/api/state");
    assert_eq!(answer.status, 200, "{}", answer.text());
    for (i, stream) in stalled.iter_mut().enumerate() {
        assert!(
            closed_by_server(stream),
            "stalled connection {i} still open"
        );
    }
    assert!(
        running.child.try_wait().unwrap().is_none(),
        "the studio ended"
    );
    assert_eq!(get(addr, "/").status, 200);
}

#[test]
fn connections_past_the_cap_wait_and_a_body_that_stalls_is_answered_408() {
    let limits = StudioLimits {
        header_timeout: Duration::from_millis(300),
        body_timeout: Duration::from_millis(300),
        connections: 2,
        ..StudioLimits::default()
    };
    let (studio, _dir) = studio_with(SCENE, "127.0.0.1:0", limits);
    let addr = studio.addr();
    let mut stalled: Vec<TcpStream> = (0..5).map(|_| TcpStream::connect(addr).unwrap()).collect();
    // Waits behind them, and is answered once they are let go.
    assert_eq!(get(addr, "/api/scene").text(), SCENE);
    for stream in &mut stalled {
        assert!(closed_by_server(stream));
    }
    // A head that comes whole, then a body that does not.
    let mut stream = TcpStream::connect(addr).unwrap();
    stream
        .set_read_timeout(Some(Duration::from_secs(120)))
        .unwrap();
    write!(
        stream,
        "PUT /api/scene HTTP/1.1\r\nHost: {addr}\r\nContent-Length: 100\r\n\r\nversion = "
    )
    .unwrap();
    let mut answer = String::new();
    let _ = stream.read_to_string(&mut answer);
    assert!(answer.starts_with("HTTP/1.1 408"), "{answer}");
    assert_eq!(get(addr, "/api/scene").text(), SCENE);
    studio.stop();
}

#[test]
fn every_answer_says_nosniff() {
    let (studio, _dir) = studio(SCENE);
    let addr = studio.addr();
    let port = addr.port();
    let foreign = raw(
        addr,
        format!(
            "GET /api/scene HTTP/1.1\r\nHost: evil.example:{port}\r\nConnection: close\r\n\r\n"
        )
        .as_bytes(),
    );
    let answers = [
        ("page", get(addr, "/")),
        ("description", get(addr, "/api/scene")),
        ("svg", get(addr, "/api/svg")),
        ("no such route", get(addr, "/api/nothing")),
        ("foreign host", foreign),
        (
            "invalid edit",
            call(addr, "PUT", "/api/scene", &[], b"version = 1\nseed = -1\n"),
        ),
    ];
    for (what, answer) in answers {
        assert_eq!(
            answer.header("x-content-type-options"),
            Some("nosniff"),
            "{what}: {}",
            answer.status
        );
    }
    studio.stop();
}

#[test]
fn exports_from_other_sites_and_oversized_pngs_are_refused() {
    // A0.
    let (studio, _dir) = studio(&SCENE.replace("\"A5\"", "[841, 1189]"));
    let addr = studio.addr();
    let export = "/api/export?format=png&dpi=20";
    let with = |header: &str| call(addr, "GET", export, &[header], b"").status;
    // A page elsewhere: by its Origin, or, for a GET from an image or a
    // link, which carries none, by what the browser says of the site.
    assert_eq!(with("Origin: http://evil.example"), 403);
    assert_eq!(with("Sec-Fetch-Site: cross-site"), 403);
    assert_eq!(with("Sec-Fetch-Site: same-site"), 403);
    // The studio's own page, the address typed, a program.
    assert_eq!(with("Sec-Fetch-Site: same-origin"), 200);
    assert_eq!(with("Sec-Fetch-Site: none"), 200);
    assert_eq!(get(addr, export).status, 200);
    // The page itself may be opened from a link anywhere.
    assert_eq!(
        call(addr, "GET", "/", &["Sec-Fetch-Site: cross-site"], b"").status,
        200
    );
    // An A0 page at 300 dpi would be 139 megapixels (under the PNG
    // writer's own 400): refused before any pixel is drawn.
    let huge = get(addr, "/api/export?format=png&dpi=300");
    assert_eq!(huge.status, 422, "{}", huge.text());
    let error = huge.json();
    assert_eq!(error["path"], "dpi");
    assert!(
        error["error"].as_str().unwrap().contains("at most 40"),
        "{error}"
    );
    studio.stop();
}

#[cfg(unix)]
#[test]
fn a_fifo_in_the_folder_is_refused_and_the_studio_goes_on() {
    let (studio, dir) = studio(SCENE);
    let addr = studio.addr();
    for name in ["pipe.toml", "pipe.svg"] {
        let made = Command::new("mkfifo")
            .arg(dir.path().join(name))
            .status()
            .unwrap();
        assert!(made.success());
    }
    let file =
        |what: &str, path: &str| json(addr, "POST", what, &serde_json::json!({ "path": path }));
    // Twice: once froze one of the server's two threads.
    for _ in 0..2 {
        for path in ["pipe.toml", "pipe.svg"] {
            let opened = file("/api/open", path);
            assert_eq!(opened.status, 422, "{}", opened.text());
            assert!(
                opened.text().contains("not a regular file"),
                "{}",
                opened.text()
            );
        }
    }
    let saved = file("/api/save", "pipe.toml");
    assert_eq!(saved.status, 422, "{}", saved.text());
    assert!(
        saved.text().contains("not a regular file"),
        "{}",
        saved.text()
    );
    // A description naming it.
    let naming = "version = 1\n[[layers]]\nname = \"a\"\n[[layers.paths]]\nsvg = \"pipe.svg\"\n";
    let put = call(addr, "PUT", "/api/scene", &[], naming.as_bytes());
    assert_eq!(put.status, 422, "{}", put.text());
    assert!(put.text().contains("not a regular file"), "{}", put.text());
    assert_eq!(get(addr, "/").status, 200);
    assert_eq!(get(addr, "/api/svg").status, 200);
    studio.stop();
}

#[test]
fn stroke_points_out_of_range_or_too_many_are_refused_as_they_come() {
    let (studio, _dir) = studio(SCENE);
    let addr = studio.addr();
    let post = |path: &str, body: serde_json::Value| json(addr, "POST", path, &body);
    let begun = post(
        "/api/stroke/begin",
        serde_json::json!({"target": null, "at": [50, 50]}),
    );
    assert_eq!(begun.status, 200, "{}", begun.text());
    let far = post(
        "/api/stroke/extend",
        serde_json::json!({"points": [[60, 50], [1e6, 50]]}),
    );
    assert_eq!(far.status, 422);
    assert_eq!(far.json()["path"], "points[1]");
    assert!(far.text().contains("100000"), "{}", far.text());
    // 10,001 points a millimetre apart, with the first: 10,002.
    let many: Vec<[f64; 2]> = (0..10_001)
        .map(|i| [f64::from(i % 100), 60.0 + f64::from(i / 100)])
        .collect();
    let long = post("/api/stroke/extend", serde_json::json!({ "points": many }));
    assert_eq!(long.status, 422);
    assert!(
        long.text().contains("at most 10000 points"),
        "{}",
        long.text()
    );
    // Neither added anything: the stroke goes on from where it was.
    let on = post(
        "/api/stroke/extend",
        serde_json::json!({"points": [[50, 60], [50, 70]]}),
    );
    assert_eq!(on.status, 200, "{}", on.text());
    let end = post("/api/stroke/end", serde_json::json!({}));
    assert_eq!(end.status, 200, "{}", end.text());
    let scene = get(addr, "/api/scene").text();
    assert!(
        scene.contains("points = [[50.0, 50.0], [50.0, 60.0], [50.0, 70.0]]"),
        "{scene}"
    );
    studio.stop();
}

#[test]
fn a_studio_on_every_address_answers_to_its_loopback_names() {
    let (studio, _dir) = studio_with(SCENE, "0.0.0.0:0", StudioLimits::default());
    let port = studio.addr().port();
    let addr: SocketAddr = format!("127.0.0.1:{port}").parse().unwrap();
    let status = |host: &str| {
        raw(
            addr,
            format!("GET /api/scene HTTP/1.1\r\nHost: {host}\r\nConnection: close\r\n\r\n")
                .as_bytes(),
        )
        .status
    };
    for host in [
        format!("127.0.0.1:{port}"),
        format!("localhost:{port}"),
        format!("0.0.0.0:{port}"),
    ] {
        assert_eq!(status(&host), 200, "{host}");
    }
    for host in [
        format!("evil.example:{port}"),
        format!("127.0.0.1:{}", port.wrapping_add(1)),
        "127.0.0.1".to_string(),
    ] {
        assert_eq!(status(&host), 403, "{host}");
    }
    studio.stop();
}
