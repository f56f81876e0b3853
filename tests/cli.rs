//! Tests of the `kappa` command-line tool: the JSON contract of `kappa curve`, its errors, and
//! the `diff`, `gallery` and `bench` subcommands. They run the built binary.
#![cfg(feature = "cli")]

mod common;

use std::path::{Path, PathBuf};
use std::process::Output;

use kurbo::Point;
use serde_json::Value;

/// Interpolation error allowed at `t_max`, relative to the drawing size.
const INTERPOLATION_TOLERANCE: f64 = 1e-9;

const CLOSED_INPUT: &str = r#"{"points": [[0, 0], [100, 0], [120, 60], [50, 90], [-10, 50]]}"#;
const OPEN_POINTS: [[f64; 2]; 5] = [
    [0.0, 0.0],
    [40.0, 30.0],
    [90.0, 10.0],
    [130.0, 60.0],
    [100.0, 110.0],
];

fn kappa(args: &[&str], stdin: &str) -> Output {
    common::run_kappa(args, stdin)
}

fn stdout(out: &Output) -> String {
    String::from_utf8(out.stdout.clone()).unwrap()
}

fn stderr(out: &Output) -> String {
    String::from_utf8(out.stderr.clone()).unwrap()
}

/// Runs successfully and parses stdout as JSON.
fn kappa_json(args: &[&str], stdin: &str) -> Value {
    let out = kappa(args, stdin);
    assert!(
        out.status.success(),
        "kappa {args:?} failed: {}",
        stderr(&out)
    );
    assert!(
        stderr(&out).is_empty(),
        "unexpected stderr: {}",
        stderr(&out)
    );
    serde_json::from_str(&stdout(&out)).expect("stdout is JSON")
}

/// Exit code 2, exactly one `kappa: error:` line on stderr, nothing on stdout; returns the line.
fn assert_error(args: &[&str], stdin: &str) -> String {
    let out = kappa(args, stdin);
    let err = stderr(&out);
    assert_eq!(out.status.code(), Some(2), "kappa {args:?}: {err}");
    assert!(out.stdout.is_empty(), "stdout not empty: {}", stdout(&out));
    assert_eq!(err.lines().count(), 1, "not one line: {err}");
    assert!(err.starts_with("kappa: error: "), "{err}");
    assert!(err.ends_with('\n'));
    err
}

fn scratch_dir(name: &str) -> PathBuf {
    let dir = Path::new(env!("CARGO_TARGET_TMPDIR"))
        .join("cli")
        .join(name);
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

fn points_of(value: &Value) -> Vec<Point> {
    value
        .as_array()
        .unwrap()
        .iter()
        .map(|p| {
            let p = p.as_array().unwrap();
            assert_eq!(p.len(), 2);
            Point::new(p[0].as_f64().unwrap(), p[1].as_f64().unwrap())
        })
        .collect()
}

/// De Casteljau on the printed control points.
fn de_casteljau(ctrl: &[Point], t: f64) -> Point {
    let mut pts = ctrl.to_vec();
    for level in 1..pts.len() {
        for i in 0..pts.len() - level {
            pts[i] = pts[i].lerp(pts[i + 1], t);
        }
    }
    pts[0]
}

fn drawing_size(points: &[Point]) -> f64 {
    let r = points
        .iter()
        .fold(kurbo::Rect::from_points(points[0], points[0]), |r, &p| {
            r.union_pt(p)
        });
    r.width().max(r.height())
}

/// A point of a trigonometric curve by repeated blending `u P_j + v P_{j+1} + w P_{j+2}`.
fn trig_blend(points: &[Point], t: f64) -> Point {
    let (s, c) = (std::f64::consts::FRAC_PI_2 * t).sin_cos();
    let (u, v, w) = (1.0 - s, s + c - 1.0, 1.0 - c);
    let mut p = points.to_vec();
    while p.len() > 1 {
        p = p
            .windows(3)
            .map(|q| (u * q[0].to_vec2() + v * q[1].to_vec2() + w * q[2].to_vec2()).to_point())
            .collect();
    }
    p[0]
}

/// Checks one curve object of the contract against its input points.
fn check_curve(curve: &Value, input: &[Point], closed: bool, scheme: &str, degree: u64) {
    let obj = curve.as_object().unwrap();
    let keys: Vec<&str> = obj.keys().map(String::as_str).collect();
    let mut sorted = keys.clone();
    sorted.sort_unstable();
    let trig = scheme == "ek-trig";
    let mut expected_keys = vec![
        "closed",
        "converged",
        "iterations",
        "scheme",
        "segments",
        "svg_path",
    ];
    if trig {
        expected_keys.insert(2, "fit");
    }
    assert_eq!(sorted, expected_keys);
    if trig {
        let fit = &curve["fit"];
        let tol = fit["tolerance"].as_f64().unwrap();
        assert!(fit["max_distance"].as_f64().unwrap() <= tol);
        assert_eq!(
            fit["cubics"].as_array().unwrap().len(),
            curve["segments"].as_array().unwrap().len()
        );
    }
    assert_eq!(curve["scheme"], scheme);
    assert_eq!(curve["closed"], closed);
    assert_eq!(curve["converged"], true);
    assert!(curve["iterations"].as_u64().is_some());
    assert!(curve["svg_path"].as_str().unwrap().starts_with('M'));
    let segments = curve["segments"].as_array().unwrap();
    // One segment per input point (closed) or per interior point (open); a two-point open
    // curve is one straight segment, through its midpoint at t = 1/2.
    let interior: Vec<Point> = if closed {
        input.to_vec()
    } else if input.len() == 2 {
        vec![input[0].midpoint(input[1])]
    } else {
        input[1..input.len() - 1].to_vec()
    };
    assert_eq!(segments.len(), interior.len());
    let size = drawing_size(input);
    for (seg, &p) in segments.iter().zip(&interior) {
        let mut seg_keys: Vec<&str> = seg
            .as_object()
            .unwrap()
            .keys()
            .map(String::as_str)
            .collect();
        seg_keys.sort_unstable();
        if trig {
            assert_eq!(seg_keys, ["basis", "degree", "extremum", "points", "t_max"]);
            assert_eq!(seg["basis"], "trig");
        } else {
            assert_eq!(seg_keys, ["degree", "extremum", "points", "t_max"]);
        }
        assert!(seg["extremum"] == "max" || seg["extremum"] == "min");
        assert_eq!(seg["degree"].as_u64(), Some(degree));
        let ctrl = points_of(&seg["points"]);
        let t = seg["t_max"].as_f64().unwrap();
        assert!((0.0..=1.0).contains(&t));
        let at = if trig {
            assert_eq!(ctrl.len() as u64, 2 * degree + 1);
            trig_blend(&ctrl, t)
        } else {
            assert_eq!(ctrl.len() as u64, degree + 1);
            de_casteljau(&ctrl, t)
        };
        assert!(
            (at - p).hypot() <= INTERPOLATION_TOLERANCE * size,
            "segment at t_max is {at:?}, input point {p:?}"
        );
    }
    // Consecutive segments join.
    for pair in segments.windows(2) {
        let a = points_of(&pair[0]["points"]);
        let b = points_of(&pair[1]["points"]);
        assert!(
            (*a.last().unwrap() - b[0]).hypot() <= INTERPOLATION_TOLERANCE * drawing_size(input)
        );
    }
    if !closed {
        let first = points_of(&segments[0]["points"]);
        let last = points_of(&segments[segments.len() - 1]["points"]);
        assert!((first[0] - input[0]).hypot() <= INTERPOLATION_TOLERANCE * size);
        assert!(
            (*last.last().unwrap() - *input.last().unwrap()).hypot()
                <= INTERPOLATION_TOLERANCE * size
        );
    }
}

fn closed_points() -> Vec<Point> {
    let v: Value = serde_json::from_str(CLOSED_INPUT).unwrap();
    points_of(&v["points"])
}

fn open_points() -> Vec<Point> {
    OPEN_POINTS.iter().map(|&[x, y]| Point::new(x, y)).collect()
}

fn open_input(extra: &str) -> String {
    format!(
        r#"{{"points": {}, "closed": false{extra}}}"#,
        serde_json::to_string(&OPEN_POINTS).unwrap()
    )
}

#[test]
fn cli_curve_closed_contract() {
    let v = kappa_json(&["curve"], CLOSED_INPUT);
    check_curve(&v, &closed_points(), true, "kappa", 2);
}

#[test]
fn cli_curve_open_contract() {
    let v = kappa_json(&["curve"], &open_input(""));
    check_curve(&v, &open_points(), false, "kappa", 2);
    assert!(!v["svg_path"].as_str().unwrap().contains('Z'));
}

#[test]
fn cli_curve_defaults() {
    // `closed` omitted means closed; `scheme` omitted means kappa; same as spelled out.
    let implicit = kappa_json(&["curve"], CLOSED_INPUT);
    let explicit = kappa_json(
        &["curve"],
        &CLOSED_INPUT.replace('}', r#", "closed": true, "scheme": "kappa"}"#),
    );
    assert_eq!(implicit, explicit);
    assert_eq!(implicit["closed"], true);
    assert_eq!(implicit["scheme"], "kappa");
}

#[test]
fn cli_curve_input_file() {
    let dir = scratch_dir("input_file");
    let path = dir.join("curve.json");
    std::fs::write(&path, CLOSED_INPUT).unwrap();
    let from_file = kappa_json(&["curve", "--input", path.to_str().unwrap()], "");
    assert_eq!(from_file, kappa_json(&["curve"], CLOSED_INPUT));
}

#[test]
fn cli_curve_ek_cubic_shapes() {
    let global = kappa_json(
        &["curve"],
        &CLOSED_INPUT.replace('}', r#", "scheme": "ek-cubic", "shape": 0.85}"#),
    );
    check_curve(&global, &closed_points(), true, "ek-cubic", 3);
    let per_point = kappa_json(
        &["curve"],
        &CLOSED_INPUT
            .replace(
                '}',
                r#", "scheme": "ek-cubic", "shape": [0.7, 0.8, 0.9, 0.95, 2e0]}"#,
            )
            .replace("2e0", "0.75"),
    );
    check_curve(&per_point, &closed_points(), true, "ek-cubic", 3);
    assert_ne!(global["segments"], per_point["segments"]);
    let open = kappa_json(
        &["curve"],
        &open_input(r#", "scheme": "ek-cubic", "shape": [0.7, 0.8, 0.9, 0.95, 0.75]"#),
    );
    check_curve(&open, &open_points(), false, "ek-cubic", 3);
    // The neutral shape gives the κ-curve, as cubics.
    let neutral = kappa_json(
        &["curve"],
        &CLOSED_INPUT.replace('}', r#", "scheme": "ek-cubic"}"#),
    );
    check_curve(&neutral, &closed_points(), true, "ek-cubic", 3);
}

#[test]
fn cli_curve_ek_trig() {
    for shape in ["0.55", "0.75", "[0.6, 0.7, 0.8, 0.9, 0.99]"] {
        let closed = kappa_json(
            &["curve"],
            &CLOSED_INPUT.replace(
                '}',
                &format!(r#", "scheme": "ek-trig", "shape": {shape}}}"#),
            ),
        );
        check_curve(&closed, &closed_points(), true, "ek-trig", 2);
        let open = kappa_json(
            &["curve"],
            &open_input(&format!(r#", "scheme": "ek-trig", "shape": {shape}"#)),
        );
        check_curve(&open, &open_points(), false, "ek-trig", 2);
    }
    // The default shape keeps every peak a maximum here.
    let default = kappa_json(
        &["curve"],
        &CLOSED_INPUT.replace('}', r#", "scheme": "ek-trig"}"#),
    );
    check_curve(&default, &closed_points(), true, "ek-trig", 2);
    for seg in default["segments"].as_array().unwrap() {
        assert_eq!(seg["extremum"], "max");
    }
}

#[test]
fn cli_curve_design_file() {
    let bear = concat!(env!("CARGO_MANIFEST_DIR"), "/data/designs/bear.json");
    let v = kappa_json(&["curve", "--design", bear], "");
    assert_eq!(v["name"], "bear");
    let curves = v["curves"].as_array().unwrap();
    assert_eq!(curves.len(), 28);
    let design = kappa::Design::from_json(&std::fs::read_to_string(bear).unwrap()).unwrap();
    for (curve, input) in curves.iter().zip(&design.curves) {
        check_curve(curve, &input.kurbo_points(), input.is_closed(), "kappa", 2);
    }
    let ek = kappa_json(
        &[
            "curve", "--design", bear, "--scheme", "ek-cubic", "--shape", "0.85",
        ],
        "",
    );
    assert_eq!(ek["curves"].as_array().unwrap().len(), 28);
    assert_eq!(ek["curves"][0]["scheme"], "ek-cubic");
    assert_eq!(ek["curves"][0]["segments"][0]["degree"], 3);
    // --builtin gives the same as the file.
    assert_eq!(kappa_json(&["curve", "--builtin", "bear"], ""), v);
}

#[test]
fn cli_curve_design_per_curve_shapes() {
    let dir = scratch_dir("design_shapes");
    let path = dir.join("d.json");
    let points = closed_points();
    let pts =
        serde_json::to_string(&points.iter().map(|p| [p.x, p.y]).collect::<Vec<_>>()).unwrap();
    let shape = "[0.7, 0.8, 0.9, 0.95, 0.75]";
    std::fs::write(
        &path,
        format!(r#"{{"name": "d", "curves": [{{"points": {pts}, "shape": {shape}}}]}}"#),
    )
    .unwrap();
    let design = path.to_str().unwrap();
    // Without --shape, ek-cubic takes the curve's own list: as the single-curve input.
    let own = kappa_json(&["curve", "--design", design, "--scheme", "ek-cubic"], "");
    let single = kappa_json(
        &["curve"],
        &format!(r#"{{"points": {pts}, "scheme": "ek-cubic", "shape": {shape}}}"#),
    );
    assert_eq!(own["name"], "d");
    assert_eq!(own["curves"][0], single);
    // --shape overrides the list.
    let global = kappa_json(
        &[
            "curve", "--design", design, "--scheme", "ek-cubic", "--shape", "0.85",
        ],
        "",
    );
    let single = kappa_json(
        &["curve"],
        &format!(r#"{{"points": {pts}, "scheme": "ek-cubic", "shape": 0.85}}"#),
    );
    assert_eq!(global["curves"][0], single);
    // κ ignores the list.
    let kappa_curves = kappa_json(&["curve", "--design", design], "");
    assert_eq!(
        kappa_curves["curves"][0],
        kappa_json(&["curve"], CLOSED_INPUT)
    );
}

#[test]
fn cli_curve_pictures() {
    let dir = scratch_dir("pictures");
    let (svg, png) = (dir.join("c.svg"), dir.join("c.png"));
    kappa_json(
        &[
            "curve",
            "--svg",
            svg.to_str().unwrap(),
            "--png",
            png.to_str().unwrap(),
            "--size",
            "200",
        ],
        CLOSED_INPUT,
    );
    assert!(std::fs::read_to_string(&svg).unwrap().starts_with("<svg"));
    let image = kappa::render::golden::load_png(&png).unwrap();
    assert_eq!((image.width(), image.height()), (200, 200));
}

#[test]
fn cli_curve_unconverged() {
    let msg = assert_error(&["curve", "--max-iterations", "1"], CLOSED_INPUT);
    assert!(msg.contains("did not converge"), "{msg}");
    let v = kappa_json(
        &["curve", "--max-iterations", "1", "--allow-unconverged"],
        CLOSED_INPUT,
    );
    assert_eq!(v["converged"], false);
    assert_eq!(v["segments"].as_array().unwrap().len(), 5);
}

#[test]
fn cli_curve_bad_input() {
    let cases: &[(&[&str], &str, &str)] = &[
        (
            &["curve"],
            r#"{"points": [[0, 0], [1, 0]]}"#,
            "too few points",
        ),
        (
            &["curve"],
            r#"{"points": [[0, 0], [1, null], [0, 1]]}"#,
            "null",
        ),
        (
            &["curve"],
            r#"{"points": [[0, 0], [1, 0], [0, 1]], "scheme": "ek-cubic", "shape": 1.5}"#,
            "1.5",
        ),
        (
            &["curve"],
            r#"{"points": [[0, 0], [1, 0], [0, 1]], "colour": 1}"#,
            "unknown field `colour`",
        ),
        (
            &["curve", "--input", "/nonexistent/kappa.json"],
            "",
            "cannot read",
        ),
        (
            &["curve"],
            r#"{"points": [[0, 0], [1, 0], [0, 1]"#,
            "invalid curve JSON",
        ),
        (&["curve"], "", "invalid curve JSON"),
        (
            &["curve"],
            r#"{"points": [[0, 0], [0, 0], [0, 1]]}"#,
            "coincide",
        ),
        (
            &["curve"],
            r#"{"points": [[0, 0], [1, 0], [2, 0]]}"#,
            "collinear",
        ),
        (
            &["curve"],
            r#"{"points": [[0, 0], [1, 0], [0, 1]], "scheme": "ek"}"#,
            "unknown variant",
        ),
        (
            &["curve"],
            r#"{"points": [[0, 0, 0], [1, 0], [0, 1]]}"#,
            "3 coordinates",
        ),
        (
            &["curve"],
            r#"{"points": [[0, 0], [1, 0], [0, 1e999]]}"#,
            "out of range",
        ),
        (
            &["curve"],
            r#"{"points": [[0, 0], [1, 0], [0, 1]], "shape": 0.8}"#,
            "shape",
        ),
        (
            &["curve"],
            r#"{"points": [[0, 0], [1, 0], [0, 1]], "scheme": "ek-cubic", "shape": [0.8]}"#,
            "expected 3 shape parameters",
        ),
        (&["curve", "--tolerance", "-1"], CLOSED_INPUT, "tolerance"),
        (
            &["curve", "--design", "/nonexistent/design.json"],
            "",
            "cannot read",
        ),
        (&["curve", "--builtin", "unicorn"], "", "unicorn"),
        (
            &[
                "curve",
                "--builtin",
                "bear",
                "--scheme",
                "ek-cubic",
                "--shape",
                "1.5",
            ],
            "",
            "curve 0",
        ),
        (&["curve", "--shape", "0.8"], CLOSED_INPUT, "--design"),
        (&["curve", "--bogus"], CLOSED_INPUT, "--bogus"),
        // A bare `kappa`: one line pointing at the help, not the help itself.
        (&[], "", "kappa --help"),
    ];
    for (args, stdin, needle) in cases {
        let msg = assert_error(args, stdin);
        assert!(msg.contains(needle), "{args:?} {stdin}: {msg}");
    }
}

#[test]
fn cli_curve_bad_design() {
    let dir = scratch_dir("bad_design");
    let path = dir.join("d.json");
    std::fs::write(
        &path,
        r#"{"name": "x", "curves": [{"points": [[0, 0], [1, 0], [0, 1]]}, {"points": [[0, 0]]}]}"#,
    )
    .unwrap();
    let msg = assert_error(&["curve", "--design", path.to_str().unwrap()], "");
    assert!(msg.contains("curve 1: too few points"), "{msg}");
    std::fs::write(&path, r#"{"name": "x", "curves": []}"#).unwrap();
    assert_error(&["curve", "--design", path.to_str().unwrap()], "");
    std::fs::write(&path, "not json").unwrap();
    let msg = assert_error(&["curve", "--design", path.to_str().unwrap()], "");
    assert!(msg.contains("invalid drawing"), "{msg}");
}

#[test]
fn cli_diff() {
    let dir = scratch_dir("diff");
    let a = dir.join("a.png");
    let b = dir.join("b.png");
    let out = dir.join("diff.png");
    kappa_json(
        &["curve", "--png", a.to_str().unwrap(), "--size", "120"],
        CLOSED_INPUT,
    );
    let mut image = kappa::render::golden::load_png(&a).unwrap();
    for px in image.data_mut()[..4 * 10].chunks_exact_mut(4) {
        px.copy_from_slice(&[0, 0, 0, 255]);
    }
    std::fs::write(&b, image.encode_png().unwrap()).unwrap();
    let (a, b, out_s) = (
        a.to_str().unwrap(),
        b.to_str().unwrap(),
        out.to_str().unwrap(),
    );

    let same = kappa(&["diff", a, a], "");
    assert_eq!(same.status.code(), Some(0), "{}", stderr(&same));
    assert_eq!(stdout(&same).lines().count(), 1);
    assert!(
        stdout(&same).contains("0 of 14400 pixels"),
        "{}",
        stdout(&same)
    );

    let differ = kappa(&["diff", a, b, "--out", out_s], "");
    assert_eq!(differ.status.code(), Some(1), "{}", stderr(&differ));
    assert_eq!(stdout(&differ).lines().count(), 1);
    assert!(
        stdout(&differ).contains("10 of 14400 pixels"),
        "{}",
        stdout(&differ)
    );
    let diff = kappa::render::golden::load_png(&out).unwrap();
    assert_eq!(diff.height(), 120);
    assert!(diff.width() > 3 * 120);

    let tolerated = kappa(&["diff", a, b, "--max-bad-pixels", "10"], "");
    assert_eq!(tolerated.status.code(), Some(0));
    let tolerated = kappa(&["diff", a, b, "--channel", "255"], "");
    assert_eq!(tolerated.status.code(), Some(0));

    let msg = assert_error(&["diff", a, "/nonexistent/kappa.png"], "");
    assert!(msg.contains("cannot read"), "{msg}");
    let msg = assert_error(
        &[
            "diff",
            a,
            concat!(env!("CARGO_MANIFEST_DIR"), "/Cargo.toml"),
        ],
        "",
    );
    assert!(msg.contains("not a readable PNG"), "{msg}");
}

#[test]
fn cli_gallery() {
    let dir = scratch_dir("gallery");
    let out = kappa(&["gallery", "--out", dir.join("sub").to_str().unwrap()], "");
    assert!(out.status.success(), "{}", stderr(&out));
    let printed: Vec<String> = stdout(&out).lines().map(str::to_owned).collect();
    let mut expected = Vec::new();
    for name in ["bear", "elephant", "bird", "designer"] {
        expected.push(format!("{name}.png"));
        for variant in ["kappa", "ek-0.75", "ek-0.85", "ek-0.95"] {
            expected.push(format!("{name}-{variant}.svg"));
        }
    }
    for name in ["eps-ClosedEkcurveKTM1", "rose"] {
        expected.push(format!("{name}-trig.png"));
    }
    expected.push("drawings.png".to_owned());
    expected.push("space-helix.png".to_owned());
    expected.push("space-trefoil.png".to_owned());
    expected.push("intrinsic-variety.png".to_owned());
    expected.push("intrinsic-viable.png".to_owned());
    expected.push("bsplines.png".to_owned());
    expected.push("glyph-sample.png".to_owned());
    expected.push("glyph-garamond.png".to_owned());
    assert_eq!(printed.len(), expected.len(), "{printed:?}");
    for file in &expected {
        let path = dir.join("sub").join(file);
        assert!(path.is_file(), "{} missing", path.display());
        assert!(
            printed.iter().any(|p| Path::new(p) == path),
            "{file} not printed"
        );
        if file.ends_with(".svg") {
            assert!(std::fs::read_to_string(&path).unwrap().starts_with("<svg"));
        }
    }
    let figure = kappa::render::golden::load_png(&dir.join("sub/bear.png")).unwrap();
    assert_eq!(figure.height(), 360);
    let trig = kappa::render::golden::load_png(&dir.join("sub/rose-trig.png")).unwrap();
    assert_eq!((trig.width(), trig.height()), (7 * 300 + 6 * 8, 300));
    let drawings = kappa::render::golden::load_png(&dir.join("sub/drawings.png")).unwrap();
    assert!(drawings.width() >= 3 * 300 && drawings.height() >= 3 * 300);
    // The glyph figures are the golden images of tests/glyph.rs.
    for name in ["glyph-sample.png", "glyph-garamond.png"] {
        let glyphs = kappa::render::golden::load_png(&dir.join("sub").join(name)).unwrap();
        let golden = Path::new(env!("CARGO_MANIFEST_DIR"))
            .join("tests/golden")
            .join(name);
        kappa::render::golden::check_golden(
            &golden,
            &glyphs,
            kappa::render::golden::Tolerance::DEFAULT,
        )
        .unwrap();
    }
}

#[test]
fn cli_bench() {
    let out = kappa(
        &[
            "bench",
            "--repeat",
            "1",
            "--case",
            "bear",
            "--case",
            "warm_move_one_point_50",
        ],
        "",
    );
    assert!(out.status.success(), "{}", stderr(&out));
    let table: Value = serde_json::from_str(&stdout(&out)).unwrap();
    let rows = table.as_array().unwrap();
    assert_eq!(rows.len(), 5);
    let bear: Vec<&Value> = rows.iter().filter(|r| r["case"] == "bear").collect();
    assert_eq!(bear.len(), 4);
    for row in &bear {
        assert_eq!(row["curves"], 28);
        assert_eq!(row["points"], 96);
        assert!(row["median_us"].as_f64().unwrap() > 0.0);
        assert!(row["iterations"].as_u64().unwrap() > 0);
        assert_eq!(row["converged"], true);
    }
    assert_eq!(rows[1]["scheme"], "ek-cubic");
    assert_eq!(rows[1]["shape"], 0.85);
    // Curve by curve on one thread, then the same curves as one batch: the same solves.
    assert_eq!(rows[0]["threads"], 1);
    assert_eq!(rows[1]["threads"], 1);
    assert!(rows[2]["threads"].as_u64().unwrap() >= 1);
    assert_eq!(rows[2]["scheme"], "kappa");
    assert_eq!(rows[3]["scheme"], "ek-cubic");
    assert_eq!(rows[2]["iterations"], rows[0]["iterations"]);
    assert_eq!(rows[3]["iterations"], rows[1]["iterations"]);
    assert_eq!(rows[4]["case"], "warm_move_one_point_50");
    assert_error(&["bench", "--case", "unicorn"], "");
}
