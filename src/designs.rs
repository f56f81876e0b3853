//! The built-in drawings (`data/designs/`), compiled into the crate.

/// `(name, JSON text)` of every built-in drawing, in the format of [`crate::Design`].
pub const BUILTIN_DESIGNS: &[(&str, &str)] = &[
    ("bear", include_str!("../data/designs/bear.json")),
    ("bird", include_str!("../data/designs/bird.json")),
    ("deer", include_str!("../data/designs/deer.json")),
    ("dinosaur", include_str!("../data/designs/dinosaur.json")),
    ("elephant", include_str!("../data/designs/elephant.json")),
    ("plane", include_str!("../data/designs/plane.json")),
    ("pumpkin", include_str!("../data/designs/pumpkin.json")),
    ("rabbit", include_str!("../data/designs/rabbit.json")),
    ("rose", include_str!("../data/designs/rose.json")),
    ("designer", include_str!("../data/designs/designer.json")),
    (
        "eps-ClosedEkcurveKTM1",
        include_str!("../data/designs/eps-ClosedEkcurveKTM1.json"),
    ),
    (
        "eps-EkcurvePoints_20220524",
        include_str!("../data/designs/eps-EkcurvePoints_20220524.json"),
    ),
    (
        "eps-OpenEkcurveKTM2",
        include_str!("../data/designs/eps-OpenEkcurveKTM2.json"),
    ),
    (
        "eps-OpenEkcurveKTM3",
        include_str!("../data/designs/eps-OpenEkcurveKTM3.json"),
    ),
    (
        "eps-dolphinpts",
        include_str!("../data/designs/eps-dolphinpts.json"),
    ),
];

/// The JSON text of a built-in drawing by name.
pub fn builtin_design(name: &str) -> Option<&'static str> {
    BUILTIN_DESIGNS
        .iter()
        .find(|(n, _)| *n == name)
        .map(|(_, t)| *t)
}
