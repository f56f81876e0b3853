//! Fill and stroke meshes of outlines through lyon, for GPU renderers.
//!
//! The core stays `f64`; the conversion to lyon's `f32` happens only here: each subpath is a
//! `begin` … `end(closed)` pair.

use kurbo::{BezPath, PathEl};
use lyon::math::point;
use lyon::path::Path as LyonPath;
use lyon::tessellation::{
    BuffersBuilder, FillOptions, FillRule, FillTessellator, FillVertex, LineCap, LineJoin,
    StrokeOptions, StrokeTessellator, StrokeVertex, VertexBuffers,
};

use crate::Error;

/// An indexed triangle list ready to upload as two buffers:
///
/// - `vertices`: `[f32; 2]` positions in the path's units (font units, y up), tightly packed
///   (stride 8 bytes, `vec2<f32>` at offset 0);
/// - `indices`: `u32`, three per triangle; every triangle is **counter-clockwise in y-up
///   coordinates** (positive signed area), so back-face culling with CCW front faces keeps
///   all of them.
///
/// Fills use the non-zero rule (TrueType's); the fill triangles do not overlap, so their union
/// is the filled outline. Strokes use round joins and caps; stroke triangles may overlap, so
/// draw them with a union (the same colour, no blending of overlaps).
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Mesh {
    /// Vertex positions.
    pub vertices: Vec<[f32; 2]>,
    /// Triangle indices into `vertices`, three per triangle, counter-clockwise (y up).
    pub indices: Vec<u32>,
}

impl Mesh {
    /// The number of triangles.
    pub fn triangle_count(&self) -> usize {
        self.indices.len() / 3
    }

    /// The triangles as point triples (f64).
    pub fn triangles(&self) -> impl Iterator<Item = [kurbo::Point; 3]> + '_ {
        self.indices.chunks_exact(3).map(|t| {
            [t[0], t[1], t[2]].map(|i| {
                let [x, y] = self.vertices[i as usize];
                kurbo::Point::new(f64::from(x), f64::from(y))
            })
        })
    }

    /// The sum of the triangles' areas.
    pub fn area(&self) -> f64 {
        self.triangles()
            .map(|[a, b, c]| 0.5 * (b - a).cross(c - a).abs())
            .sum()
    }

    /// Makes every triangle counter-clockwise (y up).
    fn orient(&mut self) {
        for t in self.indices.chunks_exact_mut(3) {
            let [a, b, c] = [t[0], t[1], t[2]].map(|i| {
                let [x, y] = self.vertices[i as usize];
                (f64::from(x), f64::from(y))
            });
            let cross = (b.0 - a.0) * (c.1 - a.1) - (b.1 - a.1) * (c.0 - a.0);
            if cross < 0.0 {
                t.swap(1, 2);
            }
        }
    }
}

/// Checks the tolerance and the path, and converts the path to lyon's `f32` path.
fn to_lyon(path: &BezPath, tolerance: f64) -> Result<LyonPath, Error> {
    if !(tolerance.is_finite() && tolerance > 0.0) {
        return Err(Error::InvalidOption(
            "tessellation tolerance must be finite and positive",
        ));
    }
    let mut b = LyonPath::builder();
    let mut open = false;
    let p = |q: kurbo::Point| point(q.x as f32, q.y as f32);
    for (index, el) in path.elements().iter().enumerate() {
        if let Some(q) = el.end_point() {
            if !(q.is_finite() && (p(q).x.is_finite() && p(q).y.is_finite())) {
                return Err(Error::NonFinitePoint { index });
            }
        }
        match *el {
            PathEl::MoveTo(q) => {
                if open {
                    b.end(false);
                }
                b.begin(p(q));
                open = true;
            }
            PathEl::LineTo(q) if open => {
                b.line_to(p(q));
            }
            PathEl::QuadTo(c, q) if open => {
                b.quadratic_bezier_to(p(c), p(q));
            }
            PathEl::CurveTo(c1, c2, q) if open => {
                b.cubic_bezier_to(p(c1), p(c2), p(q));
            }
            PathEl::ClosePath if open => {
                b.end(true);
                open = false;
            }
            _ => {
                return Err(Error::InvalidOption("path segment without a MoveTo"));
            }
        }
    }
    if open {
        b.end(false);
    }
    Ok(b.build())
}

/// The fill mesh of an outline (non-zero rule), its curves flattened within `tolerance`.
///
/// # Errors
///
/// [`Error::InvalidOption`] for a tolerance that is not finite and positive or a segment
/// before any `MoveTo`, [`Error::NonFinitePoint`] for a coordinate that is not finite in
/// `f32`, and [`Error::Tessellation`] if lyon fails.
pub fn fill_mesh(path: &BezPath, tolerance: f64) -> Result<Mesh, Error> {
    let lyon_path = to_lyon(path, tolerance)?;
    let mut buffers: VertexBuffers<[f32; 2], u32> = VertexBuffers::new();
    let options = FillOptions::tolerance(tolerance as f32).with_fill_rule(FillRule::NonZero);
    FillTessellator::new()
        .tessellate_path(
            &lyon_path,
            &options,
            &mut BuffersBuilder::new(&mut buffers, |v: FillVertex| v.position().to_array()),
        )
        .map_err(|e| Error::Tessellation(format!("{e:?}")))?;
    let mut mesh = Mesh {
        vertices: buffers.vertices,
        indices: buffers.indices,
    };
    mesh.orient();
    Ok(mesh)
}

/// The stroke mesh of an outline: `width` wide, round joins and caps, curves flattened within
/// `tolerance`.
///
/// # Errors
///
/// As [`fill_mesh`], and [`Error::InvalidOption`] for a width that is not finite and positive.
pub fn stroke_mesh(path: &BezPath, width: f64, tolerance: f64) -> Result<Mesh, Error> {
    if !(width.is_finite() && width > 0.0) {
        return Err(Error::InvalidOption(
            "stroke width must be finite and positive",
        ));
    }
    let lyon_path = to_lyon(path, tolerance)?;
    let mut buffers: VertexBuffers<[f32; 2], u32> = VertexBuffers::new();
    let options = StrokeOptions::tolerance(tolerance as f32)
        .with_line_width(width as f32)
        .with_line_join(LineJoin::Round)
        .with_line_cap(LineCap::Round);
    StrokeTessellator::new()
        .tessellate_path(
            &lyon_path,
            &options,
            &mut BuffersBuilder::new(&mut buffers, |v: StrokeVertex| v.position().to_array()),
        )
        .map_err(|e| Error::Tessellation(format!("{e:?}")))?;
    let mut mesh = Mesh {
        vertices: buffers.vertices,
        indices: buffers.indices,
    };
    mesh.orient();
    Ok(mesh)
}
