//! Tests of `kappa hermite`: its JSON contract, the end conditions of what it prints, and
//! its errors. They run the built binary.
#![cfg(feature = "cli")]

mod common;

use std::process::Output;

use kurbo::{BezPath, ParamCurve, Point};
use serde_json::Value;

fn kappa(args: &[&str], stdin: &str) -> Output {
    common::run_kappa(args, stdin)
}

fn json(args: &[&str], stdin: &str) -> Value {
    let out = kappa(args, stdin);
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(out.status.success(), "kappa {args:?} failed: {err}");
    assert!(err.is_empty(), "{err}");
    serde_json::from_str(&String::from_utf8(out.stdout).unwrap()).expect("stdout is JSON")
}

fn floats(v: &Value) -> Vec<f64> {
    v.as_array()
        .unwrap()
        .iter()
        .map(|x| x.as_f64().unwrap())
        .collect()
}

/// The path's start and end points.
fn path_ends(svg: &str) -> (Point, Point) {
    let path = BezPath::from_svg(svg).unwrap();
    let segs: Vec<_> = path.segments().collect();
    (segs[0].start(), segs.last().unwrap().end())
}

#[test]
fn hermite_g1_contract() {
    let v = json(
        &["hermite"],
        r#"{"start": {"point": [0, 0], "angle": 0}, "end": {"point": [10, 4], "angle": 1.2},
            "degree": 1}"#,
    );
    let keys: Vec<&str> = v.as_object().unwrap().keys().map(|k| k.as_str()).collect();
    assert_eq!(
        keys,
        [
            "control_curvatures",
            "end_error",
            "inflections",
            "length",
            "monotone",
            "svg_path"
        ]
    );
    assert!(v["end_error"].as_f64().unwrap() <= 1e-9);
    let k = floats(&v["control_curvatures"]);
    assert_eq!(k.len(), 2);
    // A clothoid's curvature is linear: monotone; it changes sign where the line crosses 0.
    assert_eq!(v["monotone"], Value::Bool(true));
    let infl = floats(&v["inflections"]);
    if k[0] * k[1] < 0.0 {
        assert_eq!(infl.len(), 1);
        assert!((infl[0] - k[0] / (k[0] - k[1])).abs() < 1e-12);
    } else {
        assert!(infl.is_empty());
    }
    let (a, b) = path_ends(v["svg_path"].as_str().unwrap());
    assert!(a.distance(Point::ZERO) < 1e-9 && b.distance(Point::new(10.0, 4.0)) < 1e-9);
}

#[test]
fn hermite_g2_rational_contract() {
    let v = json(
        &["hermite"],
        r#"{"start": {"point": [1, 1], "angle": 0.2, "curvature": 0.05},
            "end": {"point": [11, 5], "angle": 1.4, "curvature": 0.3}, "degree": 3,
            "weights": [1, 2, 0.5, 1]}"#,
    );
    assert!(v["end_error"].as_f64().unwrap() <= 1e-9);
    let k = floats(&v["control_curvatures"]);
    assert_eq!(k.len(), 4);
    assert!(
        (k[0] - 0.05).abs() < 1e-12 && (k[3] - 0.3).abs() < 1e-12,
        "{k:?}"
    );
    assert_eq!(floats(&v["weights"]), [1.0, 2.0, 0.5, 1.0]);
    assert!(v["length"].as_f64().unwrap() > (Point::new(10.0, 4.0).to_vec2()).hypot());
}

#[test]
fn hermite_given_and_tied_controls() {
    let v = json(
        &["hermite"],
        r#"{"start": {"point": [0, 0], "angle": 0.3}, "end": {"point": [10, 4], "angle": 1.6},
            "degree": 3, "control_curvatures": [null, {"same_as": 0}, {"same_as": 3}, null]}"#,
    );
    let k = floats(&v["control_curvatures"]);
    assert!(
        (k[0] - k[1]).abs() < 1e-15 && (k[2] - k[3]).abs() < 1e-15,
        "{k:?}"
    );
    let v = json(
        &["hermite"],
        r#"{"start": {"point": [0, 0], "angle": 0.3}, "end": {"point": [10, 4], "angle": 1.6},
            "degree": 2, "control_curvatures": [null, 0.25, null], "turning": "as-given"}"#,
    );
    assert!((floats(&v["control_curvatures"])[1] - 0.25).abs() < 1e-15);
}

#[test]
fn hermite_pictures() {
    let dir = std::env::temp_dir().join(format!("kappa-hermite-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let (svg, png) = (dir.join("h.svg"), dir.join("h.png"));
    json(
        &[
            "hermite",
            "--svg",
            svg.to_str().unwrap(),
            "--png",
            png.to_str().unwrap(),
            "--size",
            "200",
        ],
        r#"{"start": {"point": [0, 0], "angle": 0, "curvature": 0.05},
            "end": {"point": [10, 4], "angle": 1.2, "curvature": 0.3}, "degree": 5}"#,
    );
    assert!(std::fs::read_to_string(&svg).unwrap().starts_with("<svg"));
    assert!(std::fs::read(&png).unwrap().starts_with(b"\x89PNG"));
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn hermite_errors_are_one_line() {
    for bad in [
        // No cubic reaches these G2 data from the clothoid.
        r#"{"start": {"point": [0, 0], "angle": 0, "curvature": 40}, "end": {"point": [1, 0], "angle": 0, "curvature": 40}, "degree": 3}"#,
        // Coincident ends, one curvature only, degree too low, bad weights, bad JSON.
        r#"{"start": {"point": [0, 0], "angle": 0}, "end": {"point": [0, 0], "angle": 1}, "degree": 3}"#,
        r#"{"start": {"point": [0, 0], "angle": 0, "curvature": 1}, "end": {"point": [1, 0], "angle": 1}, "degree": 3}"#,
        r#"{"start": {"point": [0, 0], "angle": 0, "curvature": 1}, "end": {"point": [1, 0], "angle": 1, "curvature": 1}, "degree": 2}"#,
        r#"{"start": {"point": [0, 0], "angle": 0}, "end": {"point": [1, 0], "angle": 1}, "degree": 1, "weights": [1, 0]}"#,
        r#"{"start": {"point": [0, 0], "angle": 0}, "end": {"point": [1, 0], "angle": 1}, "degree": 1, "control_curvatures": [1, null]}"#,
        r#"{"start": {"point": [0, 0]}, "end": {"point": [1, 0], "angle": 1}, "degree": 1}"#,
        "not json",
    ] {
        let out = kappa(&["hermite"], bad);
        assert_eq!(out.status.code(), Some(2), "{bad}");
        assert!(out.stdout.is_empty());
        let err = String::from_utf8(out.stderr).unwrap();
        assert!(
            err.starts_with("kappa: error: ") && err.lines().count() == 1,
            "{err}"
        );
    }
}
