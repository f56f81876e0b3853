//! Intrinsic curves (seed 003): segments, G1/G2 Hermite interpolation, analysis, splines.

use kappa::intrinsic::{Hermite, Profile};
use kurbo::Point;

/// The degree-1 G1 solution equals the clothoid of Bertolazzi & Frego on every problem of the
/// shared 40-digit reference (`tests/data/clothoid_g1.json`), to 1e-8 relative in length and
/// end curvatures.
#[cfg(feature = "serde")]
#[test]
fn intrinsic_g1_degree1_matches_clothoid_reference() {
    let text = include_str!("data/clothoid_g1.json");
    let json: serde_json::Value = serde_json::from_str(text).unwrap();
    let problems = json["problems"].as_array().unwrap();
    assert_eq!(problems.len(), 20);
    let num = |v: &serde_json::Value| -> f64 {
        v.as_f64()
            .unwrap_or_else(|| v.as_str().unwrap().parse::<f64>().unwrap())
    };
    for p in problems {
        let h = Hermite::g1(
            Point::new(num(&p["x0"]), num(&p["y0"])),
            num(&p["theta0"]),
            Point::new(num(&p["x1"]), num(&p["y1"])),
            num(&p["theta1"]),
        );
        let r = &p["ref"];
        let (l, k0, k1) = (num(&r["L"]), num(&r["kappa0"]), num(&r["kappa1"]));
        for degree in [1, 3] {
            let seg = h.solve(&Profile::free(degree)).unwrap();
            let scale = l.recip().max(k0.abs()).max(k1.abs());
            let id = &p["id"];
            assert!(
                (seg.length() - l).abs() <= 1e-8 * l,
                "problem {id}: L {} vs {l}",
                seg.length()
            );
            assert!(
                (seg.curvatures()[0] - k0).abs() <= 1e-8 * scale,
                "problem {id}: κ0 {} vs {k0}",
                seg.curvatures()[0]
            );
            assert!(
                (seg.curvatures()[degree] - k1).abs() <= 1e-8 * scale,
                "problem {id}: κ1"
            );
            assert!(h.end_error(&seg) < 1e-10);
        }
    }
}
