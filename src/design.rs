//! Drawings: several curves with their points, closedness and optional per-point shapes, in
//! the JSON format `{"name", "source"?, "curves": [{"closed"?, "points": [[x, y], …],
//! "shape"?: [a, …]}]}` (`closed` defaults to true; `null` counts as missing).

use kurbo::Point;
use serde::{Deserialize, Serialize};

/// A drawing made of curves.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct Design {
    /// The drawing's name.
    #[serde(default)]
    pub name: String,
    /// Where it comes from.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub source: Option<String>,
    /// The curves.
    pub curves: Vec<DesignCurve>,
}

/// One curve of a [`Design`].
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct DesignCurve {
    /// Closed (default) or open.
    #[serde(default)]
    pub closed: Option<bool>,
    /// The input points.
    pub points: Vec<[f64; 2]>,
    /// Optional per-point shape parameters.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub shape: Option<Vec<f64>>,
}

impl DesignCurve {
    /// Whether the curve is closed (`true` unless the file says otherwise).
    pub fn is_closed(&self) -> bool {
        self.closed.unwrap_or(true)
    }

    /// The points as kurbo points.
    pub fn kurbo_points(&self) -> Vec<Point> {
        self.points.iter().map(|&[x, y]| Point::new(x, y)).collect()
    }
}

impl Design {
    /// Parse from JSON text.
    pub fn from_json(text: &str) -> Result<Design, serde_json::Error> {
        serde_json::from_str(text)
    }

    /// The largest side of the bounding box of all points (the "drawing size").
    pub fn size(&self) -> f64 {
        let mut r: Option<kurbo::Rect> = None;
        for p in self.curves.iter().flat_map(|c| c.points.iter()) {
            let p = Point::new(p[0], p[1]);
            r = Some(match r {
                None => kurbo::Rect::from_points(p, p),
                Some(r) => r.union_pt(p),
            });
        }
        r.map_or(0.0, |r| r.width().max(r.height()))
    }
}
