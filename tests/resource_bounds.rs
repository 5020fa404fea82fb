//! The resource bounds of each command hold from the command line: past
//! them moyo stops with a message naming the limit, exits non-zero and
//! writes nothing — never a hang or an out-of-memory kill. The limits and
//! the peak memory within them are in RELIABILITY.md.

use std::fs;

use predicates::prelude::*;

use crate::cli::{entries, moyo, tempdir};

/// An SVG page around `body`.
fn svg(body: &str) -> String {
    format!(
        r#"<svg xmlns="http://www.w3.org/2000/svg" width="100mm" height="100mm" viewBox="0 0 100 100">{body}</svg>"#
    )
}

#[cfg(unix)]
#[test]
fn a_file_that_never_ends_is_refused_at_256_mib() {
    let dir = tempdir();
    moyo(&dir)
        .args(["plot", "/dev/zero", "-o", "out.svg"])
        .assert()
        .failure()
        .stderr(predicate::str::contains(
            "/dev/zero: larger than 256 MiB, the largest file moyo reads",
        ));
    moyo(&dir)
        .args(["render", "/dev/zero", "-o", "out.svg"])
        .assert()
        .failure()
        .stderr(predicate::str::contains("larger than 256 MiB"));
    assert!(entries(dir.path()).is_empty());
}

/// `moyo plot NAME` on `text` (with `args`) fails saying `message` and
/// leaves only its input in the folder.
fn plot_is_refused(name: &str, text: &str, args: &[&str], message: &str) {
    let dir = tempdir();
    fs::write(dir.path().join(name), text).unwrap();
    moyo(&dir)
        .arg("plot")
        .arg(name)
        .args(args)
        .args(["-o", "out.svg"])
        .assert()
        .failure()
        .stderr(predicate::str::contains(message));
    assert_eq!(entries(dir.path()), [name.to_string()].into());
}

#[test]
fn groups_nested_past_1024_are_refused_with_the_limit() {
    let depth = 1100;
    let body = format!(
        "{}<path d=\"M0 0 L10 10\" stroke=\"black\"/>{}",
        "<g>".repeat(depth),
        "</g>".repeat(depth)
    );
    plot_is_refused(
        "deep.svg",
        &svg(&body),
        &[],
        "deep.svg: the document has more than 1,000,000 elements, or elements nested more than 1,024 deep",
    );
}

#[test]
fn more_than_a_million_elements_are_refused_with_the_limit() {
    plot_is_refused(
        "many.svg",
        &svg(&"<g/>".repeat(1_000_001)),
        &["--merge", "--sort"],
        "many.svg: the document has more than 1,000,000 elements",
    );
}

#[test]
fn more_than_ten_million_segments_are_refused_before_the_plot() {
    // One path of 10,000,002 short lines back and forth: 25 MB of text,
    // well within the file limit.
    let path = format!(
        r#"<path stroke="black" d="M1 1{}"/>"#,
        "h1h-1".repeat(5_000_001)
    );
    plot_is_refused(
        "long.svg",
        &svg(&path),
        &[],
        "long.svg: svg: the paths hold more than 10,000,000 segments in all",
    );
}

#[test]
fn hatching_past_a_million_lines_a_region_is_refused() {
    // A 100 mm square at 0.00005 mm: 2.8 million lines across its
    // diagonal at the default 45° (inside the outline's clearance).
    plot_is_refused(
        "square.svg",
        &svg(r#"<rect width="100" height="100" fill="black"/>"#),
        &["--hatch", "0.00005"],
        "hatch.spacing: 0.00005 mm would need 2818245 lines across this region (at most 1000000)",
    );
}

#[test]
fn an_entity_bomb_is_refused() {
    let mut dtd = String::from("<!DOCTYPE svg [<!ENTITY a0 \"lol\">");
    for i in 1..10 {
        let prev = format!("&a{};", i - 1);
        dtd.push_str(&format!("<!ENTITY a{i} \"{}\">", prev.repeat(10)));
    }
    dtd.push(']');
    dtd.push('>');
    let text = format!("{dtd}{}", svg("<text>&a9;</text>"));
    plot_is_refused(
        "bomb.svg",
        &text,
        &[],
        "bomb.svg: 1:63: malformed SVG (not well-formed XML): a possible entity reference loop",
    );
}

#[test]
fn a_scene_past_its_segment_budget_stops_naming_the_limit() {
    let dir = tempdir();
    let text = "version = 1\nlimits = { max_segments = 5000 }\n[[layers]]\nname = \"l\"\n\
                [[layers.lsystem]]\nid = \"koch\"\naxiom = \"F--F--F\"\n\
                rules = [\"F -> F+F--F+F\"]\niterations = 6\nangle = 60\n";
    fs::write(dir.path().join("koch.toml"), text).unwrap();
    moyo(&dir)
        .args(["render", "koch.toml", "-o", "out.svg"])
        .assert()
        .failure()
        .stderr(predicate::str::contains("5000").and(predicate::str::contains("segments")));
    assert_eq!(entries(dir.path()), ["koch.toml".to_string()].into());
    // Iterations 5 (3 × 4⁵ = 3072 segments) fit.
    fs::write(dir.path().join("koch.toml"), text.replace("= 6", "= 5")).unwrap();
    moyo(&dir)
        .args(["render", "koch.toml", "-o", "out.svg"])
        .assert()
        .success();
    // A family that counts no segments itself is stopped after its table.
    let trees = "version = 1\nlimits = { max_segments = 50 }\n[[layers]]\nname = \"a\"\n\
                 [[layers.trees]]\nid = \"t\"\nrule = \"tree1\"\ncount = 3\n\
                 centre = [[10, 100], [100, 100]]\n";
    fs::write(dir.path().join("trees.toml"), trees).unwrap();
    moyo(&dir)
        .args(["render", "trees.toml", "-o", "trees.svg"])
        .assert()
        .failure()
        .stderr(predicate::str::contains(
            "`a.t` would make more than 50 path segments",
        ));
}

/// 100,000 stroke colours: one pen each is refused (past pen 999), so they
/// are clustered into the most pens a plot may have, 999. Every stage that
/// goes pen by pen once scanned every layer for every pen (more than 120 s
/// for `stats` when each colour was a pen); now they group the layers
/// once, and the clustering's work is bounded. Ten times as many colours
/// would pass the import's limit of a million elements, so this is the
/// most a file can ask for.
#[test]
fn a_hundred_thousand_colours_are_plotted_pen_by_pen_in_one_pass() {
    let dir = tempdir();
    let body: String = (0..100_000u32)
        .map(|i| {
            let (x, y) = (f64::from(i % 400) * 0.25, f64::from(i / 400) * 0.4);
            format!(
                r##"<path d="M{x} {y}h0.2" stroke="#{:06x}"/>"##,
                i * 167 % 0x100_0000
            )
        })
        .collect();
    fs::write(dir.path().join("colours.svg"), svg(&body)).unwrap();
    moyo(&dir)
        .args(["stats", "colours.svg", "--json", "--pens", "999"])
        .assert()
        .success()
        .stdout(predicate::str::contains("\"paths\": 100000"))
        .stderr(predicate::str::contains(
            "100,000 colours merged into 999 pens",
        ));
    moyo(&dir)
        .args(["stats", "colours.svg", "--pens", "0"])
        .assert()
        .failure()
        .stderr(predicate::str::contains(
            "one pen per colour would make 100,000 pens, more than the 999",
        ));
    moyo(&dir)
        .args([
            "plot",
            "colours.svg",
            "--pens",
            "999",
            "--merge",
            "--sort",
            "-o",
            "out.gcode",
        ])
        .assert()
        .success();
    let gcode = fs::read_to_string(dir.path().join("out.gcode")).unwrap();
    // Every stroke drawn; --merge joins the few of one pen that meet end
    // to end (0.05 mm apart), which it could not when each had a pen.
    let strokes = gcode.matches("M3 S1000").count();
    assert!((99_900..=100_000).contains(&strokes), "{strokes} strokes");
    assert_eq!(
        gcode.matches("M0 ; load pen").count(),
        999,
        "one change per pen"
    );
    assert!(!gcode.contains("load pen 1000 "), "no pen past 999");
}

/// A description that names a FIFO (someone else's description, a file
/// swapped for a pipe) is refused at once: opening a FIFO would wait for
/// a writer that never comes.
#[cfg(unix)]
#[test]
fn a_description_naming_a_fifo_is_refused_without_waiting() {
    let dir = tempdir();
    let made = std::process::Command::new("mkfifo")
        .arg(dir.path().join("pipe.svg"))
        .status()
        .unwrap();
    assert!(made.success());
    fs::write(
        dir.path().join("scene.toml"),
        "version = 1\n[[layers]]\nname = \"a\"\n[[layers.paths]]\nsvg = \"pipe.svg\"\n",
    )
    .unwrap();
    moyo(&dir)
        .args(["render", "scene.toml", "-o", "out.svg"])
        .timeout(std::time::Duration::from_secs(60))
        .assert()
        .failure()
        .stderr(predicate::str::contains("not a regular file"));
    assert!(!dir.path().join("out.svg").exists());
}

/// A description of `tests/data/hostile/`.
fn hostile(name: &str) -> String {
    let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("tests/data/hostile")
        .join(name);
    fs::read_to_string(&path).unwrap_or_else(|e| panic!("{}: {e}", path.display()))
}

/// `moyo render` of the description `text` (beside the built-in images)
/// fails saying `message` — the field, the estimate and the limit — and
/// writes nothing.
fn render_is_refused(text: &str, message: &str) {
    let dir = tempdir();
    fs::write(dir.path().join("scene.toml"), text).unwrap();
    let images = dir.path().join("images");
    fs::create_dir(&images).unwrap();
    let portrait =
        std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("templates/images/portrait.jpg");
    fs::copy(portrait, images.join("portrait.jpg")).unwrap();
    moyo(&dir)
        .args(["render", "scene.toml", "-o", "out.svg", "--png", "out.png"])
        .assert()
        .failure()
        .stderr(predicate::str::contains(message))
        .stderr(predicate::str::contains("panicked").not());
    assert_eq!(
        entries(dir.path()),
        ["images".to_string(), "scene.toml".to_string()].into()
    );
}

/// The slow case the fuzzer kept (`fuzz/slow/scene_extremes/`): 1,000
/// relaxation steps on 1,103 sites, then on 508. Refused by the scene's
/// site-step budget before the first step; with 900 steps on the first
/// table it fits, and the second table is refused for what is left.
#[test]
fn relaxation_past_its_site_steps_is_refused_before_a_step() {
    let text = hostile("relax-1000-steps-on-1103-sites.toml");
    render_is_refused(
        &text,
        "layers[0].voronoi[0].relax: 1000 steps × 1103 sites is 1103000 site-steps of \
         relaxation, more than the 1000000 left of a scene's 1000000",
    );
    let first = text.replacen("relax = 1000", "relax = 900", 1);
    render_is_refused(
        &first,
        "layers[0].voronoi[1].relax: 1000 steps × 508 sites is 508000 site-steps of \
         relaxation, more than the 7300 left of a scene's 1000000 (992700 taken by earlier \
         tables)",
    );
}

/// A leaf on each of a million symbols is counted from the turtle's marks
/// before any leaf is drawn: past the paths left with the largest path
/// budget; with half as many, past the segments left (48 a leaf).
#[test]
fn a_million_ornaments_are_refused_before_one_is_drawn() {
    let text = hostile("lsystem-a-leaf-on-each-of-a-million-symbols.toml");
    render_is_refused(
        &text,
        "layers[0].lsystem[0].leaves: the turtle meets `L` 1048575 times: 1048575 ornaments \
         would make 1048575 paths, more than the 999999 left of limits.max_paths",
    );
    render_is_refused(
        &text.replace("iterations = 20", "iterations = 19"),
        "layers[0].lsystem[0].leaves: the turtle meets `L` 524287 times: 524287 ornaments \
         would make about",
    );
}

#[test]
fn a_vine_guide_past_twenty_metres_is_refused() {
    render_is_refused(
        &hostile("vine-guide-280-m.toml"),
        "layers[0].vine[0].guide: is 280014 mm long; a vine grows along at most 20000 mm",
    );
}

/// A 4 MB density formula (`u+u+…`, about 1 KB a term once parsed) is
/// refused by its length before it is parsed.
#[test]
fn a_four_megabyte_formula_is_refused_by_its_length() {
    let formula = "u+".repeat(2_000_000) + "u";
    let text = format!(
        "version = 1\n[[layers]]\nname = \"a\"\n[[layers.voronoi]]\nrelax = 1\n\
         [layers.voronoi.sites]\ndistribution = \"uniform\"\ncount = 10\ndensity = \"{formula}\"\n"
    );
    render_is_refused(
        &text,
        "layers[0].voronoi[0].sites.density: is 4000001 characters long; a formula may be at \
         most 200",
    );
}

/// 80,000 layers took 15 s and 1.1 GB; a description holds at most
/// 10,000.
#[test]
fn more_layers_than_ten_thousand_are_refused() {
    let layers: String = (0..10_001)
        .map(|i| format!("[[layers]]\nname = \"l{i}\"\n"))
        .collect();
    render_is_refused(
        &format!("version = 1\n{layers}"),
        "layers: has 10001 layers; a description may have at most 10000",
    );
}

/// 5,000 steps of elements 0.05 of their region wide: refused before the
/// loop, by the work its steps would ask for.
#[test]
fn zentangle_steps_past_their_work_are_refused_before_the_loop() {
    render_is_refused(
        &hostile("zentangle-5000-steps-at-scale-0.05.toml"),
        "layers[0].zentangle[0].steps: 5000 steps at scale 0.05 are about 40000000 units of \
         work (steps ÷ scale³), more than 150000: fewer steps, or a larger scale (at 0.05, 18 \
         steps)",
    );
}

/// A shape that makes linesweeper 0.5.0 panic in both of its modes (a
/// cubic running out and back over itself, beside a lens) in front of a
/// line: the polygon reference takes over, the line is hidden where the
/// shape covers it, and stderr holds no panic (issue 36, item 5).
#[test]
fn a_shape_linesweeper_panics_on_hides_the_line_behind_it_and_prints_no_panic() {
    let dir = tempdir();
    let name = "linesweeper-retraced-cubic.svg";
    fs::write(dir.path().join(name), hostile(name)).unwrap();
    let out = moyo(&dir)
        .args(["plot", name, "--occlude", "-o", "out.svg"])
        .assert()
        .success()
        .stderr(predicate::str::contains("panicked").not())
        .stderr(predicate::str::contains("backtrace").not());
    let stderr = String::from_utf8_lossy(&out.get_output().stderr);
    assert!(
        stderr.starts_with("wrote out.svg") && stderr.lines().count() == 1,
        "{stderr}"
    );
    let svg = fs::read_to_string(dir.path().join("out.svg")).unwrap();
    // The line runs at y = −15 from x = −20 to 10 (30 to 60 on the page);
    // shapely, on both contours sampled finely, hides it from x = −5.5624
    // to 0.4266.
    let d = svg
        .split("d=\"")
        .find(|d| d.starts_with("M 30 335"))
        .and_then(|d| d.split('"').next())
        .expect("the line is drawn");
    let numbers: Vec<f64> = d
        .split([' ', 'M', 'L'])
        .filter_map(|t| t.parse().ok())
        .collect();
    let [_, _, hidden_from, _, hidden_to, _, _, _] = numbers[..] else {
        panic!("the line is not in two pieces: {d}");
    };
    assert!((hidden_from - 44.4376).abs() < 0.01, "{d}");
    assert!((hidden_to - 50.4266).abs() < 0.01, "{d}");
}

/// 400 nested `scale(10)`: each number is fine, together they overflow,
/// and usvg dropped the path without a word. Refused naming the element
/// and its transform (issue 36, item 7).
#[test]
fn transforms_nested_past_what_can_be_plotted_are_refused_naming_the_element() {
    let name = "svg-400-nested-scale-10.svg";
    plot_is_refused(
        name,
        &hostile(name),
        &[],
        "<g> transform: 'scale(10)' with the transforms of the elements around it comes to \
         1.0e39, beyond ±3.4028235e38",
    );
}
