//! Hostile input to the command-line tool: malformed JSON, wrong types, empty arrays, NaN
//! literals, shape parameters out of range, and arrays of 10⁷ elements. Every case must end
//! with exit code 2, nothing on stdout and exactly one `kappa: error:` line on stderr — fast:
//! the size limit (`--max-points`) is checked while the JSON is read.
#![cfg(feature = "cli")]

mod common;

use std::time::{Duration, Instant};

/// Generous bound on the time of a rejected 10⁷-element input (measured well below; see
/// docs/hostile-input.md).
const HUGE_INPUT_TIME: Duration = Duration::from_secs(5);

/// Runs `kappa args` on `stdin`, asserts the error contract, and returns the message and the
/// time taken.
fn rejects(args: &[&str], stdin: &str) -> (String, Duration) {
    let start = Instant::now();
    let out = common::run_kappa(args, stdin);
    let took = start.elapsed();
    let err = String::from_utf8(out.stderr).unwrap();
    assert_eq!(out.status.code(), Some(2), "kappa {args:?}: {err}");
    assert!(out.stdout.is_empty(), "kappa {args:?}: stdout not empty");
    assert_eq!(
        err.lines().count(),
        1,
        "kappa {args:?}: not one line: {err}"
    );
    assert!(err.starts_with("kappa: error: "), "{err}");
    assert!(!err.contains("internal error"), "kappa {args:?}: {err}");
    (err, took)
}

fn rejects_with(args: &[&str], stdin: &str, needle: &str) {
    let (err, _) = rejects(args, stdin);
    assert!(
        err.contains(needle),
        "kappa {args:?} on {stdin:.200}: {err}"
    );
}

const TRIANGLE: &str = "[[0, 0], [100, 0], [50, 80]]";
const TRIANGLE3: &str = "[[0, 0, 0], [100, 0, 10], [50, 80, 0]]";
const HERMITE: &str =
    r#""start": {"point": [0, 0], "angle": 0}, "end": {"point": [10, 4], "angle": 1.2}"#;

#[test]
fn malformed_json_and_wrong_types() {
    for cmd in ["curve", "bspline", "space", "hermite"] {
        for (stdin, needle) in [
            ("", "JSON"),
            ("{", "JSON"),
            ("[]", "JSON"),
            ("null", "JSON"),
            ("42", "JSON"),
            ("\"points\"", "JSON"),
            ("{\"points\": 1}", "JSON"),
            ("{\"points\": [[0, 0]]} trailing", "JSON"),
            ("\u{feff}{}", "JSON"),
            ("{\"points\": [[0, 0], [1, 1]], \"points\": []}", "JSON"),
        ] {
            rejects_with(&[cmd], stdin, needle);
        }
    }
    for (cmd, stdin, needle) in [
        ("curve", r#"{"points": "abc"}"#, "a list of points"),
        ("curve", r#"{"points": [["0", "1"]]}"#, "invalid type"),
        ("curve", r#"{"points": [{"x": 0, "y": 1}]}"#, "invalid type"),
        (
            "curve",
            r#"{"points": [[0, 0], [1, 0], [0, 1]], "closed": "yes"}"#,
            "invalid type",
        ),
        (
            "curve",
            r#"{"points": [[0, 0], [1, 0], [0, 1]], "scheme": 3}"#,
            "JSON",
        ),
        (
            "curve",
            r#"{"points": [[0, 0], [1, 0], [0, 1]], "shape": true}"#,
            "shape is true",
        ),
        (
            "bspline",
            r#"{"points": [[0, 0], [1, 0, 0]]}"#,
            "coordinates",
        ),
        ("bspline", r#"{"points": [[0]]}"#, "1 coordinates"),
        (
            "space",
            r#"{"points": [[0, 0], [1, 0], [0, 1]]}"#,
            "expected 3",
        ),
        (
            "space",
            &format!(r#"{{"points": {TRIANGLE3}, "replace": "a"}}"#),
            "invalid type",
        ),
        (
            "hermite",
            &format!(r#"{{{HERMITE}, "degree": -1}}"#),
            "invalid value",
        ),
        (
            "hermite",
            &format!(r#"{{{HERMITE}, "degree": 2.5}}"#),
            "invalid type",
        ),
        (
            "hermite",
            &format!(r#"{{{HERMITE}, "degree": 3, "weights": "heavy"}}"#),
            "invalid type",
        ),
    ] {
        rejects_with(&[cmd], stdin, needle);
    }
}

#[test]
fn empty_arrays_and_nan_literals() {
    for (cmd, stdin, needle) in [
        ("curve", r#"{"points": []}"#, "too few points"),
        ("curve", r#"{"points": [[]]}"#, "0 coordinates"),
        (
            "curve",
            r#"{"points": [[0, 0], [1, 0], [0, 1]], "scheme": "ek-cubic", "shape": []}"#,
            "expected 3 shape parameters (one per point), got 0",
        ),
        ("bspline", r#"{"points": []}"#, "too few points"),
        ("bspline", r#"{"points": [[]]}"#, "0 coordinates"),
        ("space", r#"{"points": []}"#, "too few points"),
        (
            "hermite",
            &format!(r#"{{{HERMITE}, "degree": 1, "control_curvatures": []}}"#),
            "entries",
        ),
        (
            "hermite",
            &format!(r#"{{{HERMITE}, "degree": 1, "weights": []}}"#),
            "one weight per control curvature",
        ),
        ("curve", r#"{"points": [[0, 0], [1, NaN], [0, 1]]}"#, "JSON"),
        (
            "curve",
            r#"{"points": [[0, 0], [1, Infinity], [0, 1]]}"#,
            "JSON",
        ),
        (
            "curve",
            r#"{"points": [[0, 0], [1, 1e999], [0, 1]]}"#,
            "out of range",
        ),
        (
            "curve",
            r#"{"points": [[0, 0], [1, null], [0, 1]]}"#,
            "null",
        ),
        (
            "curve",
            r#"{"points": [[0, 0], [1, 0], [0, 1]], "scheme": "ek-cubic", "shape": NaN}"#,
            "JSON",
        ),
        ("bspline", r#"{"points": [[0, 0], [1, NaN]]}"#, "JSON"),
        (
            "space",
            r#"{"points": [[0, 0, 0], [1, 0, -Infinity], [0, 1, 0]]}"#,
            "JSON",
        ),
        (
            "hermite",
            r#"{"start": {"point": [0, 0], "angle": NaN}, "end": {"point": [1, 0], "angle": 0}, "degree": 1}"#,
            "JSON",
        ),
    ] {
        rejects_with(&[cmd], stdin, needle);
    }
}

#[test]
fn shape_parameters_out_of_range() {
    for (scheme, shape, needle) in [
        ("ek-cubic", "-0.8", "-0.8"),
        ("ek-cubic", "0.5", "0.5"),
        ("ek-cubic", "1", "outside [0.6666666666666666, 1)"),
        ("ek-cubic", "1e308", "outside"),
        ("ek-cubic", "-1e308", "outside"),
        ("ek-trig", "0.49", "0.49"),
        ("ek-trig", "1e300", "outside [0.5, 1)"),
        ("ek-cubic", "[0.8, -1, 0.8]", "shape parameter 1 is -1"),
        ("ek-trig", "[0.8, 0.8, 7e100]", "shape parameter 2"),
        ("kappa", "0.8", "the kappa scheme has no shape parameter"),
    ] {
        let stdin = format!(r#"{{"points": {TRIANGLE}, "scheme": "{scheme}", "shape": {shape}}}"#);
        rejects_with(&["curve"], &stdin, needle);
    }
    // Huge or negative parameters elsewhere.
    for (cmd, stdin, needle) in [
        (
            "space",
            format!(r#"{{"points": {TRIANGLE3}, "replace": -0.5}}"#),
            "replace is -0.5",
        ),
        (
            "space",
            format!(r#"{{"points": {TRIANGLE3}, "replace": 1e300}}"#),
            "replace is",
        ),
        (
            "hermite",
            format!(r#"{{{HERMITE}, "degree": 18446744073709551615}}"#),
            "above the limit",
        ),
        (
            "hermite",
            format!(r#"{{{HERMITE}, "degree": 1e300}}"#),
            "invalid type",
        ),
        (
            "hermite",
            format!(r#"{{{HERMITE}, "degree": 3, "weights": [1, -1, 1, 1]}}"#),
            "weight",
        ),
        (
            "hermite",
            format!(
                r#"{{{HERMITE}, "degree": 3, "control_curvatures": [null, 1e300, null, null]}}"#
            ),
            "no curve",
        ),
    ] {
        rejects_with(&[cmd], &stdin, needle);
    }
    for args in [
        ["curve", "--tolerance", "-1"],
        ["curve", "--tolerance", "NaN"],
        ["curve", "--max-iterations", "-3"],
        ["curve", "--max-points", "-1"],
        ["curve", "--max-points", "1e20"],
    ] {
        rejects(&args, &format!(r#"{{"points": {TRIANGLE}}}"#));
    }
}

/// `n` copies of `item`, comma-separated.
fn repeat(item: &str, n: usize) -> String {
    let mut s = String::with_capacity((item.len() + 1) * n);
    for i in 0..n {
        if i > 0 {
            s.push(',');
        }
        s.push_str(item);
    }
    s
}

#[test]
fn arrays_of_ten_million_elements_are_rejected_fast() {
    const N: usize = 10_000_000;
    let points2 = format!(r#"{{"points": [{}]}}"#, repeat("[0,1]", N));
    let points3 = format!(r#"{{"points": [{}]}}"#, repeat("[0,1,2]", N));
    let coords = format!(r#"{{"points": [[{}]]}}"#, repeat("0", N));
    let shapes = format!(
        r#"{{"points": {TRIANGLE}, "scheme": "ek-cubic", "shape": [{}]}}"#,
        repeat("0.7", N)
    );
    let weights = format!(
        r#"{{{HERMITE}, "degree": 3, "weights": [{}]}}"#,
        repeat("1", N)
    );
    let mut worst = Duration::ZERO;
    for (args, stdin, needle) in [
        (&["curve"][..], &points2, "more than 1000000 points"),
        (&["bspline"][..], &points2, "more than 1000000 points"),
        (&["space"][..], &points3, "more than 1000000 points"),
        (&["curve"][..], &coords, "10000000 coordinates"),
        (&["bspline"][..], &coords, "10000000 coordinates"),
        (
            &["curve"][..],
            &shapes,
            "more than 1000000 shape parameters",
        ),
        (&["hermite"][..], &weights, "more than 65 entries"),
        (
            &["curve", "--max-points", "100"][..],
            &points2,
            "more than 100 points",
        ),
    ] {
        let (err, took) = rejects(args, stdin);
        assert!(err.contains(needle), "kappa {args:?}: {err}");
        assert!(
            took < HUGE_INPUT_TIME,
            "kappa {args:?} took {took:?} to reject a 10^7-element input"
        );
        worst = worst.max(took);
    }
    eprintln!("slowest rejection of a 10^7-element input: {worst:?}");
}

#[test]
fn point_limit_is_configurable() {
    let four = r#"{"points": [[0, 0], [100, 0], [120, 60], [50, 90]]}"#;
    rejects_with(&["curve", "--max-points", "3"], four, "more than 3 points");
    rejects_with(
        &["bspline", "--max-points", "3"],
        four,
        "more than 3 points",
    );
    let out = common::run_kappa(&["curve", "--max-points", "4"], four);
    assert!(out.status.success());
    // A drawing is limited by its total number of points.
    rejects_with(
        &["curve", "--builtin", "bear", "--max-points", "10"],
        "",
        "more than the limit of 10",
    );
}
