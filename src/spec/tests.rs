use super::*;

const MINIMAL: &str = r#"
version = 1
seed = 5

[[layers]]
name = "front"

[[layers.trees]]
rule = "tree3"
count = 2
centre = [[10, 100], [150, 120]]

[layers.trees.params]
generations = 5
"#;

fn parse(text: &str) -> Result<ValidSpec> {
    SceneSpec::parse(text, Format::Toml)
}

#[test]
fn minimal_file_gets_defaults() {
    let s = parse(MINIMAL).unwrap();
    assert_eq!(s.pens.len(), 1);
    assert_eq!(s.output.precision, 3);
    let p = s.layers[0].trees[0].params.resolve();
    assert_eq!(p.generations, 5);
    assert_eq!(p.ratio1, 0.85);
    assert_eq!(s.page().width, 210.0);
}

#[test]
fn round_trips_through_toml_and_json() {
    let s = parse(MINIMAL).unwrap();
    let again = parse(&s.to_toml()).unwrap();
    assert_eq!(s, again);
    let json = serde_json::to_string(s.spec()).unwrap();
    assert_eq!(SceneSpec::parse(&json, Format::Json).unwrap(), s);
}

#[test]
fn unknown_key_is_rejected_with_its_place() {
    let text = MINIMAL.replace("generations = 5", "generations = 5\nratio9 = 1");
    let e = parse(&text).unwrap_err();
    let msg = e.to_string();
    assert!(msg.contains("ratio9"), "{msg}");
    assert!(msg.starts_with("15:1:"), "{msg}");
}

#[test]
fn wrong_type_names_the_field() {
    let text = MINIMAL.replace("count = 2", "count = \"two\"");
    let msg = parse(&text).unwrap_err().to_string();
    assert!(msg.contains("layers[0].trees[0].count"), "{msg}");
    assert!(msg.starts_with("10:9:"), "{msg}");
}

#[test]
fn out_of_range_value_names_range_and_place() {
    let text = MINIMAL.replace("generations = 5", "generations = 500");
    let msg = parse(&text).unwrap_err().to_string();
    assert_eq!(
        msg,
        "14:15: layers[0].trees[0].params.generations: must be between 0 and 64, got 500"
    );
}

#[test]
fn non_finite_numbers_are_rejected() {
    let text = MINIMAL.replace("[[10, 100]", "[[nan, 100]");
    let msg = parse(&text).unwrap_err().to_string();
    assert!(msg.contains("layers[0].trees[0].centre[0]"), "{msg}");
    let text = MINIMAL.replace("generations = 5", "ratio1 = inf");
    assert!(parse(&text).unwrap_err().to_string().contains("got inf"));
}

#[test]
fn references_must_exist() {
    let text = MINIMAL.replace("name = \"front\"", "name = \"front\"\npen = 4");
    let msg = parse(&text).unwrap_err().to_string();
    assert!(msg.contains("no pen 4 is defined (defined: 1)"), "{msg}");

    let text = format!("{MINIMAL}\n[[layers.trees.overrides]]\nid = \"tree-7\"\nscale = 2\n");
    let msg = parse(&text).unwrap_err().to_string();
    assert!(
        msg.contains("'tree-7' matches no tree (trees are tree-0 … tree-1)"),
        "{msg}"
    );
}

#[test]
fn json_errors_have_line_and_column() {
    let e = SceneSpec::parse("{\"version\": 1,\n \"sed\": 3}", Format::Json).unwrap_err();
    let msg = e.to_string();
    assert!(msg.starts_with("2:"), "{msg}");
    assert!(msg.contains("sed"), "{msg}");
}

#[test]
fn broken_toml_is_a_parse_error_with_place() {
    let e = parse("version = 1\n[[layers]\nname = 'x'\n").unwrap_err();
    assert!(
        matches!(
            e,
            Error::Parse {
                at: Some(LineCol { line: 2, .. }),
                ..
            }
        ),
        "{e}"
    );
}

#[test]
fn version_is_checked() {
    let msg = parse("version = 2").unwrap_err().to_string();
    assert!(msg.contains("unsupported format version 2"), "{msg}");
}

#[test]
fn custom_size_keeps_its_sides_unless_an_orientation_is_given() {
    let wide = parse("version = 1\npage = { size = [400, 100] }").unwrap();
    assert_eq!((wide.page().width, wide.page().height), (400.0, 100.0));
    let turned =
        parse("version = 1\npage = { size = [400, 100], orientation = \"portrait\" }").unwrap();
    assert_eq!((turned.page().width, turned.page().height), (100.0, 400.0));
    let a4 = parse("version = 1\npage = { size = \"A4\" }").unwrap();
    assert_eq!((a4.page().width, a4.page().height), (210.0, 297.0));
}

#[test]
fn bokashi_values_are_checked_with_their_place() {
    let text = MINIMAL.replace(
        "generations = 5",
        "generations = 5\n[layers.trees.flowers]\nmotifs = [\"ume\"]\npaint = { bokashi = { growth = 0.5 } }",
    );
    let msg = parse(&text).unwrap_err().to_string();
    assert!(
        msg.contains(
            "layers[0].trees[0].flowers.paint.bokashi.growth: must be between 1 and 4, got 0.5"
        ),
        "{msg}"
    );
    let text = text.replace("growth = 0.5", "from = \"middle\"");
    let msg = parse(&text).unwrap_err().to_string();
    assert!(
        msg.contains("bokashi.from") && msg.contains("edge"),
        "{msg}"
    );
}

#[test]
fn palettes_are_named_and_their_slots_checked() {
    let text = format!("palette = \"kyoto\"\n{MINIMAL}");
    let msg = parse(&text).unwrap_err().to_string();
    assert!(
        msg.contains("palette: unknown palette 'kyoto'") && msg.contains("kaga-gosai"),
        "{msg}"
    );
    let text = MINIMAL.replace(
        "generations = 5",
        "generations = 5\n[layers.trees.flowers]\nmotifs = [\"ume\"]\npaint = { fill = \"@6\" }",
    );
    let msg = parse(&text).unwrap_err().to_string();
    assert!(
        msg.contains("flowers.paint.fill: '@6' is not a colour"),
        "{msg}"
    );
    assert!(parse(&text.replace("@6", "@5")).is_ok());
    assert!(parse(&text.replace("@6", "sakura-iro")).is_ok());
}

#[test]
fn voronoi_sites_read_and_write_back_with_or_without_points() {
    let table = |sites: &str| {
        format!("version = 1\n[[layers]]\nname = \"v\"\n[[layers.voronoi]]\n[layers.voronoi.sites]\n{sites}")
    };
    // No distribution and no points: poisson, written out as before.
    let s = parse(&table("spacing = 8\n")).unwrap();
    assert_eq!(
        s.layers[0].voronoi[0].sites,
        SitesSpec {
            spacing: Some(8.0),
            ..SitesSpec::default()
        }
    );
    assert!(
        s.to_toml().contains("distribution = \"poisson\""),
        "{}",
        s.to_toml()
    );
    // Points: no distribution, none written; the points come back exactly.
    let s = parse(&table("points = [[1.5, 2], [0.1, 1e-3], [3, 4]]\n")).unwrap();
    let sites = &s.layers[0].voronoi[0].sites;
    assert_eq!(sites.distribution, None);
    assert_eq!(
        sites.points.as_deref(),
        Some(&[[1.5, 2.0], [0.1, 1e-3], [3.0, 4.0]][..])
    );
    let toml = s.to_toml();
    assert!(!toml.contains("distribution"), "{toml}");
    assert_eq!(parse(&toml).unwrap(), s);
    let json = serde_json::to_string(s.spec()).unwrap();
    assert_eq!(SceneSpec::parse(&json, Format::Json).unwrap(), s);
    // A wrong point names its place in the text.
    let msg = parse(&table("points = [[1, 2],\n  [3, inf]]\n"))
        .unwrap_err()
        .to_string();
    assert!(
        msg.starts_with("7:")
            && msg.contains("layers[0].voronoi[0].sites.points[1]: y must be a finite number"),
        "{msg}"
    );
}

/// A description with one vine whose table ends with `camera`.
fn vine(camera: &str) -> String {
    format!("version = 1\n\n[[layers]]\nname = \"v\"\n\n[[layers.vine]]\n{camera}\n")
}

#[test]
fn every_kind_of_vine_camera_reads_back_from_toml_and_json() {
    for camera in [
        "camera = \"three-quarter\"",
        "camera = { turn = -120.5, tilt = 30 }",
        "camera = { turn = 40 }",
        "camera = { tilt = -10, perspective = 50 }",
        "camera = { eye = [1, 2, 3], target = [0, 50, 0], perspective = 40 }",
    ] {
        let s = parse(&vine(camera)).unwrap();
        let toml = s.to_toml();
        assert_eq!(parse(&toml).unwrap(), s, "{camera}:\n{toml}");
        let json = serde_json::to_string(s.spec()).unwrap();
        assert_eq!(SceneSpec::parse(&json, Format::Json).unwrap(), s, "{json}");
    }
    let s = parse(&vine("camera = { turn = 40 }")).unwrap();
    assert_eq!(
        s.layers[0].vine[0].camera,
        CameraSpec::Orbit(Orbit {
            turn: 40.0,
            ..Orbit::FRONT
        })
    );
    assert!(s
        .to_toml()
        .contains("[layers.vine.camera]\nturn = 40.0\ntilt = 0.0\n"));
}

#[test]
fn an_orbit_lists_its_ranges_for_the_form() {
    let s = parse(&vine("camera = { turn = 30, tilt = 15, perspective = 40 }")).unwrap();
    let ranges = s.ranges();
    for (field, lo, hi) in [
        ("turn", -360.0, 360.0),
        ("tilt", -89.0, 89.0),
        ("perspective", 1.0, 170.0),
    ] {
        let field = format!("layers[0].vine[0].camera.{field}");
        let range = ranges.iter().find(|r| r.field == field);
        assert_eq!(
            range.map(|r| (r.lo, r.hi, r.integer)),
            Some((lo, hi, false)),
            "{field}"
        );
    }
}

#[test]
fn a_wrong_vine_camera_is_named_at_its_key() {
    for (camera, message) in [
        (
            "camera = { turn = 30, tilt = 95 }",
            "7:30: layers[0].vine[0].camera.tilt: must be between -89 and 89, got 95",
        ),
        (
            "camera = { turn = -400 }",
            "7:19: layers[0].vine[0].camera.turn: must be between -360 and 360, got -400",
        ),
        (
            "camera = { tilt = 10, perspective = 171 }",
            "7:37: layers[0].vine[0].camera.perspective: must be between 1 and 170, got 171",
        ),
        (
            "camera = { eye = [1, 2] }",
            "7:18: layers[0].vine[0].camera.eye: invalid length 2, expected an array of length 3",
        ),
        (
            "camera = { eye = [1, 2, 3] }",
            "7:10: layers[0].vine[0].camera: missing field `target`",
        ),
        (
            "camera = { turn = \"left\" }",
            "7:19: layers[0].vine[0].camera.turn: invalid type: string \"left\", expected f64",
        ),
        (
            "camera = { turn = 30, roll = 5 }",
            "7:23: layers[0].vine[0].camera.roll: unknown field `roll`, expected one of \
             `eye`, `target`, `up`, `perspective`, `turn`, `tilt`",
        ),
        (
            "camera = { turn = 30, eye = [1, 2, 3] }",
            "7:10: layers[0].vine[0].camera: mixes an orbit (`turn`, `tilt`) with a placed \
             camera (`eye`, `target`, `up`): give one or the other",
        ),
        (
            "camera = { perspective = 40 }",
            "7:10: layers[0].vine[0].camera: needs `turn` and `tilt` (an orbit round the \
             vine) or `eye` and `target` (a placed camera)",
        ),
        (
            "camera = \"side\"",
            "7:10: layers[0].vine[0].camera: unknown variant `side`, expected one of \
             `front`, `three-quarter`, `below`",
        ),
        (
            "camera = 5",
            "7:10: layers[0].vine[0].camera: invalid type: integer `5`, expected a camera: \
             \"front\", \"three-quarter\", \"below\", { turn = …, tilt = … } or \
             { eye = [x, y, z], target = [x, y, z] }",
        ),
    ] {
        assert_eq!(parse(&vine(camera)).unwrap_err().to_string(), message);
    }
    // JSON names the same keys.
    let json = r#"{"version": 1, "layers": [{"name": "v", "vine": [{"camera": {"turn": 1, "tilt": "x"}}]}]}"#;
    let msg = SceneSpec::parse(json, Format::Json)
        .unwrap_err()
        .to_string();
    assert!(
        msg.contains("layers[0].vine[0].camera.tilt: invalid type"),
        "{msg}"
    );
}
