//! Tests of `kappa::render`: SVG output, rendering, golden images.
#![cfg(feature = "render")]

use std::path::{Path, PathBuf};

use kappa::render::golden::{
    check_golden, check_golden_with, compare, diff_image, diff_image_with, load_png, GoldenError,
    Tolerance,
};
use kappa::render::{
    hstack, Color, Pixmap, PointStyle, RenderError, Scene, Style, TextAlign, MAX_PIXELS,
};
use kurbo::{Affine, BezPath, Point, Rect};

/// Handle length of a 4-cubic circle: 4/3 (√2 − 1).
const CIRCLE_K: f64 = 0.552_284_749_830_793_4;

/// Circle of radius `r` about `c` as four cubics, with its 12 control points
/// (on-curve points at indices 0, 3, 6, 9).
fn circle(c: Point, r: f64) -> (BezPath, Vec<Point>) {
    let k = CIRCLE_K * r;
    let p = |x: f64, y: f64| Point::new(c.x + x, c.y + y);
    let ctrl = vec![
        p(r, 0.0),
        p(r, k),
        p(k, r),
        p(0.0, r),
        p(-k, r),
        p(-r, k),
        p(-r, 0.0),
        p(-r, -k),
        p(-k, -r),
        p(0.0, -r),
        p(k, -r),
        p(r, -k),
    ];
    let mut path = BezPath::new();
    path.move_to(ctrl[0]);
    for i in 0..4 {
        path.curve_to(ctrl[3 * i + 1], ctrl[3 * i + 2], ctrl[(3 * i + 3) % 12]);
    }
    path.close_path();
    (path, ctrl)
}

/// A hand-made comb for the circle: outward teeth of constant length (the
/// curvature is constant) at `n` angles, and the polyline through the tips.
fn circle_comb(c: Point, r: f64, tooth: f64, n: usize) -> BezPath {
    let mut comb = BezPath::new();
    let dir = |i: usize| {
        let a = std::f64::consts::TAU * i as f64 / n as f64;
        kurbo::Vec2::new(a.cos(), a.sin())
    };
    for i in 0..n {
        comb.move_to(c + r * dir(i));
        comb.line_to(c + (r + tooth) * dir(i));
    }
    comb.move_to(c + (r + tooth) * dir(0));
    for i in 1..=n {
        comb.line_to(c + (r + tooth) * dir(i % n));
    }
    comb
}

/// The golden scene: circle, its control polygon, on-curve points, comb, and
/// a green marker below the circle (larger y) to show the orientation.
fn circle_scene(width: u32, height: u32) -> Scene {
    let c = Point::new(0.0, 0.0);
    let (path, ctrl) = circle(c, 100.0);
    let on_curve: Vec<Point> = ctrl.iter().step_by(3).copied().collect();
    Scene::new()
        .with_size(width, height)
        .control_polygon(&ctrl, true)
        .comb(&circle_comb(c, 100.0, 30.0, 48))
        .curve(&path)
        .input_points(&on_curve)
        .points(
            &[Point::new(0.0, 160.0)],
            PointStyle::new(6.0, Color::GREEN),
        )
}

fn golden_path(name: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("tests/golden")
        .join(name)
}

/// A unique scratch directory under the system temp dir.
fn scratch_dir(test: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("kappa-render-{}-{test}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

fn solid(width: u32, height: u32, color: Color) -> Pixmap {
    let mut p = Pixmap::new(width, height).unwrap();
    p.fill(resvg::tiny_skia::Color::from_rgba8(
        color.r, color.g, color.b, color.a,
    ));
    p
}

fn get(p: &Pixmap, x: u32, y: u32) -> [u8; 4] {
    let i = 4 * (y * p.width() + x) as usize;
    p.data()[i..i + 4].try_into().unwrap()
}

fn set(p: &mut Pixmap, x: u32, y: u32, rgba: [u8; 4]) {
    let i = 4 * (y * p.width() + x) as usize;
    p.data_mut()[i..i + 4].copy_from_slice(&rgba);
}

/// Centroid of the pixels within 8 levels of `color`.
fn centroid(p: &Pixmap, color: Color) -> Option<(f64, f64)> {
    let (mut n, mut sx, mut sy) = (0.0, 0.0, 0.0);
    for y in 0..p.height() {
        for x in 0..p.width() {
            let [r, g, b, _] = get(p, x, y);
            if r.abs_diff(color.r) <= 8 && g.abs_diff(color.g) <= 8 && b.abs_diff(color.b) <= 8 {
                n += 1.0;
                sx += f64::from(x);
                sy += f64::from(y);
            }
        }
    }
    (n > 0.0).then(|| (sx / n, sy / n))
}

fn two_dots(y_down: bool) -> Scene {
    Scene::new()
        .with_size(100, 200)
        .with_y_down(y_down)
        .points(&[Point::new(0.0, 0.0)], PointStyle::new(5.0, Color::RED))
        .points(&[Point::new(0.0, 100.0)], PointStyle::new(5.0, Color::BLUE))
}

// ---- Golden images -------------------------------------------------------

#[test]
fn golden_circle() {
    let pixmap = circle_scene(400, 400).render().unwrap();
    check_golden(&golden_path("circle.png"), &pixmap, Tolerance::default()).unwrap();
}

#[test]
fn golden_circle_y_down_and_up() {
    let panels = [
        circle_scene(300, 300).render().unwrap(),
        circle_scene(300, 300).with_y_down(false).render().unwrap(),
    ];
    let pixmap = hstack(&panels, 10).unwrap();
    check_golden(
        &golden_path("circle_y_down_y_up.png"),
        &pixmap,
        Tolerance::default(),
    )
    .unwrap();
}

// ---- SVG -----------------------------------------------------------------

#[test]
fn scene_svg_is_standalone_and_deterministic() {
    let scene = circle_scene(400, 300);
    let svg = scene.to_svg().unwrap();
    assert_eq!(svg, scene.to_svg().unwrap());
    assert_eq!(svg, scene.clone().to_svg().unwrap());
    assert!(svg.starts_with(
        r#"<svg xmlns="http://www.w3.org/2000/svg" width="400" height="300" viewBox="0 0 400 300">"#
    ));
    assert!(svg.contains(r##"<rect x="0" y="0" width="400" height="300" fill="#ffffff"/>"##));
    assert!(svg.contains(r#"stroke-linejoin="round""#));
    assert!(svg.contains(r#"stroke-dasharray="4 3""#));
    assert!(svg.contains("<circle "));
    assert!(!svg.contains("<text"));
    assert!(!svg.contains("NaN") && !svg.contains("inf"));
    assert!(svg.trim_end().ends_with("</svg>"));
}

#[test]
fn scene_svg_numbers_are_rounded() {
    let mut path = BezPath::new();
    path.move_to((0.1 + 0.2, -1e-9));
    path.line_to((100.0 / 3.0, 10.0));
    let svg = Scene::new()
        .with_size(100, 100)
        .with_view_box(Rect::new(0.0, 0.0, 100.0, 100.0))
        .with_margin(0.0)
        .path(&path, Style::new(Color::BLACK, 1.0 / 3.0))
        .to_svg()
        .unwrap();
    assert!(svg.contains(r#"d="M0.3,0 L33.333,10""#), "{svg}");
    assert!(svg.contains(r#"stroke-width="0.333""#), "{svg}");
}

#[test]
fn scene_svg_writes_opacity_and_fill() {
    let mut path = BezPath::new();
    path.move_to((0.0, 0.0));
    path.line_to((10.0, 0.0));
    path.line_to((10.0, 10.0));
    path.close_path();
    let svg = Scene::new()
        .path(
            &path,
            Style::new(Color::RED.with_alpha(128), 2.0).with_fill(Color::BLUE),
        )
        .to_svg()
        .unwrap();
    assert!(svg.contains(r##"fill="#1f77b4""##), "{svg}");
    assert!(svg.contains(r##"stroke="#d62728""##), "{svg}");
    assert!(svg.contains(r#"stroke-opacity="0.5020""#), "{svg}");
}

#[test]
fn scene_view_transform_fits_and_centres() {
    let scene = Scene::new().with_size(300, 200).with_margin(10.0).polygon(
        &[Point::new(0.0, 0.0), Point::new(10.0, 5.0)],
        false,
        Style::CURVE,
    );
    let t = scene.view_transform().unwrap();
    // 10 x 5 into 280 x 180: scale min(28, 36) = 28, centred.
    assert_eq!(t * Point::new(0.0, 0.0), Point::new(10.0, 30.0));
    assert_eq!(t * Point::new(10.0, 5.0), Point::new(290.0, 170.0));
    let up = scene.with_y_down(false).view_transform().unwrap();
    assert_eq!(up * Point::new(0.0, 0.0), Point::new(10.0, 170.0));
    assert_eq!(up * Point::new(10.0, 5.0), Point::new(290.0, 30.0));
}

#[test]
fn scene_title_takes_a_band_above_the_drawing() {
    let square = [Point::new(0.0, 0.0), Point::new(10.0, 10.0)];
    let scene = Scene::new()
        .with_size(200, 200)
        .with_margin(10.0)
        .polygon(&square, false, Style::CURVE)
        .with_title("κ-curve, a = 0.75");
    let t = scene.view_transform().unwrap();
    let band = Scene::TITLE_BAND;
    // 10 x 10 into 180 x (180 − band): the height decides, centred below the band.
    let side = 180.0 - band;
    let top = t * Point::new(0.0, 0.0);
    assert!((top.y - (10.0 + band)).abs() < 1e-9, "{top:?}");
    assert!(((t * Point::new(10.0, 10.0)).y - 190.0).abs() < 1e-9);
    assert!(((t * Point::new(10.0, 0.0)).x - top.x - side).abs() < 1e-9);
    // The title's ink is in the band, centred.
    let image = scene.render().unwrap();
    let (mut dark_in_band, mut sum_x) = (0, 0.0);
    for y in 0..band as u32 {
        for x in 0..200 {
            if get(&image, x, y)[0] < 128 {
                dark_in_band += 1;
                sum_x += f64::from(x);
            }
        }
    }
    // Between the title and the drawing (which starts at 10 + band, its stroke 1 px above)
    // the image is white.
    for y in band as u32 + 1..band as u32 + 8 {
        for x in 0..200 {
            assert_eq!(get(&image, x, y), [255; 4], "({x}, {y})");
        }
    }
    assert!(dark_in_band > 50, "{dark_in_band} dark pixels in the band");
    let mean_x = sum_x / f64::from(dark_in_band);
    assert!((mean_x - 100.0).abs() < 15.0, "ink centred at x = {mean_x}");
    // The SVG holds outlines, not text.
    let svg = scene.to_svg().unwrap();
    assert!(!svg.contains("<text"));
}

#[test]
fn scene_labels_are_in_pixels_and_do_not_move_the_view() {
    let dots = [Point::new(0.0, 0.0), Point::new(1.0, 1.0)];
    let scene = Scene::new()
        .with_size(100, 100)
        .points(&dots, PointStyle::INPUT);
    let labelled = scene.clone().label(
        "808",
        Point::new(50.0, 95.0),
        20.0,
        TextAlign::Middle,
        Color::BLUE,
    );
    assert_eq!(
        scene.view_transform().unwrap(),
        labelled.view_transform().unwrap()
    );
    let image = labelled.render().unwrap();
    let (x, y) = centroid(&image, Color::BLUE).unwrap();
    assert!((x - 50.0).abs() < 2.0 && y > 80.0 && y < 92.0, "({x}, {y})");
}

#[test]
fn scene_view_transform_explicit_view_box() {
    let scene = Scene::new()
        .with_size(200, 100)
        .with_margin(0.0)
        .with_view_box(Rect::new(0.0, 0.0, 10.0, 10.0));
    // 10 x 10 into 200 x 100: scale 10, centred horizontally.
    let t = scene.view_transform().unwrap();
    assert_eq!(t * Point::new(0.0, 0.0), Point::new(50.0, 0.0));
    assert_eq!(t * Point::new(10.0, 10.0), Point::new(150.0, 100.0));
}

#[test]
fn scene_view_transform_degenerate_content() {
    // A horizontal segment fits on its width; a single point is centred.
    let line = Scene::new().with_size(120, 100).with_margin(10.0).polygon(
        &[Point::new(0.0, 5.0), Point::new(10.0, 5.0)],
        false,
        Style::CURVE,
    );
    let t = line.view_transform().unwrap();
    assert_eq!(t * Point::new(0.0, 5.0), Point::new(10.0, 50.0));
    assert_eq!(t * Point::new(10.0, 5.0), Point::new(110.0, 50.0));
    let dot = Scene::new()
        .with_size(100, 100)
        .points(&[Point::new(7.0, 7.0)], PointStyle::INPUT);
    assert_eq!(
        dot.view_transform().unwrap() * Point::new(7.0, 7.0),
        Point::new(50.0, 50.0)
    );
    assert_eq!(Scene::new().view_transform().unwrap(), Affine::IDENTITY);
}

// ---- Rendering -----------------------------------------------------------

#[test]
fn scene_render_twice_identical() {
    let scene = circle_scene(400, 300);
    let a = scene.render().unwrap();
    let b = scene.render().unwrap();
    assert_eq!(a.data(), b.data());
    assert_eq!(scene.render_png().unwrap(), scene.render_png().unwrap());
    let decoded = Pixmap::decode_png(&scene.render_png().unwrap()).unwrap();
    assert_eq!(decoded.data(), a.data());
}

#[test]
fn scene_render_is_opaque_on_white() {
    let p = circle_scene(200, 150).render().unwrap();
    assert_eq!((p.width(), p.height()), (200, 150));
    assert!(p.pixels().iter().all(|px| px.alpha() == 255));
    assert_eq!(get(&p, 0, 0), [255, 255, 255, 255]);
    assert_eq!(get(&p, 199, 149), [255, 255, 255, 255]);
    let empty = Scene::new().with_size(10, 10).render().unwrap();
    assert!(empty.data().iter().all(|&b| b == 255));
}

#[test]
fn scene_render_y_orientation() {
    let down = two_dots(true).render().unwrap();
    let (_, red_y) = centroid(&down, Color::RED).unwrap();
    let (_, blue_y) = centroid(&down, Color::BLUE).unwrap();
    assert!(blue_y > red_y + 100.0, "y down: larger y must be lower");
    let up = two_dots(false).render().unwrap();
    let (_, red_y) = centroid(&up, Color::RED).unwrap();
    let (_, blue_y) = centroid(&up, Color::BLUE).unwrap();
    assert!(blue_y + 100.0 < red_y, "y up: larger y must be higher");
}

#[test]
fn scene_render_dots_are_centred() {
    let p = Scene::new()
        .with_size(101, 101)
        .points(&[Point::new(3.0, 3.0)], PointStyle::new(6.0, Color::RED))
        .render()
        .unwrap();
    let (x, y) = centroid(&p, Color::RED).unwrap();
    assert!((x - 50.0).abs() < 0.5 && (y - 50.0).abs() < 0.5, "{x} {y}");
    assert_eq!(get(&p, 50, 50), [214, 39, 40, 255]);
}

#[test]
fn scene_render_stroke_width_in_pixels() {
    // A horizontal 4 px line, pixel-aligned: exactly 4 black rows.
    let mut path = BezPath::new();
    path.move_to((10.0, 50.0));
    path.line_to((90.0, 50.0));
    let p = Scene::new()
        .with_size(100, 100)
        .with_margin(0.0)
        .with_view_box(Rect::new(0.0, 0.0, 100.0, 100.0))
        .path(&path, Style::new(Color::BLACK, 4.0))
        .render()
        .unwrap();
    let column: Vec<u8> = (0..100).map(|y| get(&p, 50, y)[0]).collect();
    let black: Vec<usize> = (0..100).filter(|&y| column[y] == 0).collect();
    assert_eq!(black, vec![48, 49, 50, 51]);
    assert_eq!(column[47], 255);
    assert_eq!(column[52], 255);
}

#[test]
fn scene_render_png_round_trip_through_file() {
    let dir = scratch_dir("png_round_trip");
    let file = dir.join("scene.png");
    let scene = circle_scene(120, 90);
    std::fs::write(&file, scene.render_png().unwrap()).unwrap();
    assert_eq!(
        load_png(&file).unwrap().data(),
        scene.render().unwrap().data()
    );
    let _ = std::fs::remove_dir_all(dir);
}

// ---- Errors --------------------------------------------------------------

fn line(a: (f64, f64), b: (f64, f64)) -> BezPath {
    let mut p = BezPath::new();
    p.move_to(a);
    p.line_to(b);
    p
}

#[test]
fn scene_error_non_finite() {
    let nan = Scene::new()
        .curve(&line((0.0, 0.0), (1.0, 1.0)))
        .curve(&line((0.0, f64::NAN), (1.0, 1.0)));
    for result in [
        nan.to_svg().map(drop),
        nan.render().map(drop),
        nan.render_png().map(drop),
    ] {
        assert!(
            matches!(
                result,
                Err(RenderError::NonFinite {
                    layer: 1,
                    kind: "path"
                })
            ),
            "{result:?}"
        );
    }
    let inf = Scene::new().input_points(&[Point::new(f64::INFINITY, 0.0)]);
    assert!(matches!(
        inf.render(),
        Err(RenderError::NonFinite {
            layer: 0,
            kind: "points"
        })
    ));
    let poly =
        Scene::new().control_polygon(&[Point::new(0.0, 0.0), Point::new(f64::NAN, 0.0)], false);
    assert!(matches!(
        poly.render(),
        Err(RenderError::NonFinite {
            layer: 0,
            kind: "polygon"
        })
    ));
    // Finite input that overflows when mapped to pixels.
    let huge = Scene::new()
        .with_view_box(Rect::new(0.0, 0.0, 1e-300, 1e-300))
        .curve(&line((0.0, 0.0), (1e300, 1e300)));
    assert!(matches!(
        huge.render(),
        Err(RenderError::NonFinite { layer: 0, .. })
    ));
    let message = nan.render().unwrap_err().to_string();
    assert!(message.contains("layer 1 (path)"), "{message}");
}

#[test]
fn scene_error_size() {
    for (w, h) in [(0, 10), (10, 0), (0, 0), (100_000, 100_000), (u32::MAX, 1)] {
        let result = Scene::new().with_size(w, h).render();
        assert!(
            matches!(result, Err(RenderError::InvalidSize { .. })),
            "{w}x{h}: {result:?}"
        );
    }
    assert!(Scene::new().with_size(1, 1).render().is_ok());
    let message = Scene::new()
        .with_size(0, 5)
        .render()
        .unwrap_err()
        .to_string();
    assert!(message.contains("0x5"), "{message}");
    const { assert!(MAX_PIXELS >= 16384 * 4096) };
}

#[test]
fn scene_error_margin_and_view_box() {
    for margin in [-1.0, f64::NAN, f64::INFINITY, 50.0, 60.0] {
        let result = Scene::new()
            .with_size(100, 200)
            .with_margin(margin)
            .render();
        assert!(
            matches!(result, Err(RenderError::InvalidMargin { .. })),
            "{margin}: {result:?}"
        );
    }
    for view_box in [
        Rect::new(0.0, 0.0, 0.0, 10.0),
        Rect::new(0.0, 0.0, f64::NAN, 10.0),
        Rect::new(0.0, 0.0, f64::INFINITY, 10.0),
    ] {
        let result = Scene::new().with_view_box(view_box).render();
        assert!(
            matches!(result, Err(RenderError::InvalidViewBox { .. })),
            "{view_box:?}: {result:?}"
        );
    }
    // A reversed rectangle is accepted.
    assert!(Scene::new()
        .with_view_box(Rect::new(10.0, 10.0, 0.0, 0.0))
        .render()
        .is_ok());
    // Content bounds that overflow.
    let result = Scene::new()
        .input_points(&[Point::new(-1e308, 0.0), Point::new(1e308, 0.0)])
        .render();
    assert!(
        matches!(result, Err(RenderError::InvalidViewBox { .. })),
        "{result:?}"
    );
}

#[test]
fn scene_error_style() {
    let l = line((0.0, 0.0), (1.0, 1.0));
    let bad_styles = [
        Style::new(Color::BLACK, -1.0),
        Style::new(Color::BLACK, f64::NAN),
        Style::new(Color::BLACK, 1.0).with_dash(0.0, 0.0),
        Style::new(Color::BLACK, 1.0).with_dash(-1.0, 2.0),
        Style::new(Color::BLACK, 1.0).with_dash(f64::INFINITY, 2.0),
    ];
    for style in bad_styles {
        let result = Scene::new().path(&l, style).render();
        assert!(
            matches!(result, Err(RenderError::InvalidStyle { layer: 0, .. })),
            "{style:?}: {result:?}"
        );
    }
    for radius in [-1.0, f64::NAN] {
        let result = Scene::new()
            .points(&[Point::ORIGIN], PointStyle::new(radius, Color::RED))
            .render();
        assert!(
            matches!(result, Err(RenderError::InvalidStyle { .. })),
            "{result:?}"
        );
    }
    // Zero widths and radii are valid and draw nothing.
    let nothing = Scene::new()
        .with_size(20, 20)
        .path(&l, Style::new(Color::BLACK, 0.0))
        .points(&[Point::ORIGIN], PointStyle::new(0.0, Color::RED))
        .path(&l, Style::new(Color::TRANSPARENT, 3.0))
        .path(&BezPath::new(), Style::CURVE)
        .polygon(&[Point::ORIGIN], true, Style::CURVE)
        .render()
        .unwrap();
    assert!(nothing.data().iter().all(|&b| b == 255));
}

#[test]
fn load_png_errors() {
    let dir = scratch_dir("load_png_errors");
    let missing = dir.join("missing.png");
    assert!(matches!(load_png(&missing), Err(RenderError::Io { .. })));
    let text = dir.join("not_a_png.png");
    std::fs::write(&text, "hello").unwrap();
    let err = load_png(&text).unwrap_err();
    assert!(matches!(err, RenderError::PngDecode { .. }), "{err:?}");
    assert!(err.to_string().contains("not_a_png.png"), "{err}");
    let empty = dir.join("empty.png");
    std::fs::write(&empty, "").unwrap();
    assert!(matches!(
        load_png(&empty),
        Err(RenderError::PngDecode { .. })
    ));
    // A truncated PNG.
    let png = Scene::new().with_size(20, 20).render_png().unwrap();
    let truncated = dir.join("truncated.png");
    std::fs::write(&truncated, &png[..png.len() / 2]).unwrap();
    assert!(matches!(
        load_png(&truncated),
        Err(RenderError::PngDecode { .. })
    ));
    assert!(matches!(load_png(&dir), Err(RenderError::Io { .. })));
    let _ = std::fs::remove_dir_all(dir);
}

// ---- Comparison ----------------------------------------------------------

#[test]
fn compare_self_passes() {
    let p = circle_scene(200, 150).render().unwrap();
    let c = compare(&p, &p, Tolerance::EXACT);
    assert!(c.passed());
    assert_eq!(c.bad_pixels, 0);
    assert_eq!(c.max_channel_diff, 0);
    assert_eq!(c.total_pixels, 200 * 150);
    assert_eq!(c.size_mismatch, None);
    assert_eq!(c.bad_region, None);
}

#[test]
fn compare_one_pixel_change() {
    let expected = circle_scene(200, 150).render().unwrap();
    let mut actual = expected.clone();
    set(&mut actual, 17, 23, [0, 0, 0, 255]);
    let strict = compare(&expected, &actual, Tolerance::new(1, 0));
    assert!(!strict.passed());
    assert_eq!(strict.bad_pixels, 1);
    assert_eq!(strict.max_channel_diff, 255);
    assert_eq!(strict.bad_region, Some((17, 23, 18, 24)));
    assert!(compare(&expected, &actual, Tolerance::new(1, 1)).passed());
    assert!(compare(&expected, &actual, Tolerance::new(254, 0)).bad_pixels == 1);
    assert!(compare(&expected, &actual, Tolerance::new(255, 0)).passed());
}

#[test]
fn compare_channel_tolerance() {
    let expected = solid(10, 10, Color::rgb(100, 100, 100));
    let mut actual = expected.clone();
    set(&mut actual, 3, 4, [100, 101, 100, 255]);
    let tol1 = compare(&expected, &actual, Tolerance::new(1, 0));
    assert!(tol1.passed());
    assert_eq!(tol1.max_channel_diff, 1);
    let tol0 = compare(&expected, &actual, Tolerance::new(0, 0));
    assert!(!tol0.passed());
    assert_eq!(tol0.bad_pixels, 1);
    assert_eq!(Tolerance::default(), Tolerance::new(1, 0));
    // A difference of 2 fails the default.
    set(&mut actual, 3, 4, [98, 100, 100, 255]);
    assert!(!compare(&expected, &actual, Tolerance::default()).passed());
}

#[test]
fn compare_size_mismatch() {
    let a = solid(10, 10, Color::WHITE);
    let b = solid(12, 10, Color::WHITE);
    let c = compare(&a, &b, Tolerance::new(255, usize::MAX));
    assert!(!c.passed());
    assert_eq!(c.size_mismatch, Some(((10, 10), (12, 10))));
    assert_eq!(c.bad_pixels, 20);
    assert_eq!(c.total_pixels, 120);
    assert_eq!(c.bad_region, Some((10, 0, 12, 10)));
    let message = compare(&a, &b, Tolerance::default()).to_string();
    assert!(
        message.contains("expected 10x10, actual 12x10"),
        "{message}"
    );
    // Same pixel count, different shape.
    let tall = solid(5, 20, Color::WHITE);
    assert!(!compare(&a, &solid(20, 5, Color::WHITE), Tolerance::default()).passed());
    assert!(!compare(&tall, &solid(20, 5, Color::WHITE), Tolerance::default()).passed());
}

#[test]
fn diff_image_layout() {
    let expected = solid(10, 8, Color::WHITE);
    let mut actual = expected.clone();
    set(&mut actual, 2, 3, [0, 0, 0, 255]);
    set(&mut actual, 5, 5, [254, 255, 255, 255]);
    let d = diff_image(&expected, &actual).unwrap();
    // expected | 4 px | diff | 4 px | actual
    assert_eq!((d.width(), d.height()), (10 + 4 + 10 + 4 + 10, 8));
    assert_eq!(get(&d, 14 + 2, 3), [255, 0, 0, 255]);
    assert_eq!(get(&d, 14 + 5, 5), [255, 0, 0, 255]);
    assert_eq!(get(&d, 14, 0), [255, 255, 255, 255]);
    assert_eq!(get(&d, 28 + 2, 3), [0, 0, 0, 255]);
    assert_eq!(get(&d, 11, 0), [128, 128, 128, 255]);
    // With tolerance 1 the near pixel is orange.
    let d = diff_image_with(&expected, &actual, Tolerance::default()).unwrap();
    assert_eq!(get(&d, 14 + 5, 5), [255, 165, 0, 255]);
    // Black fades to a light grey.
    let black = solid(2, 2, Color::BLACK);
    let d = diff_image(&black, &black).unwrap();
    assert_eq!(get(&d, 2 + 4, 0), [191, 191, 191, 255]);
}

#[test]
fn diff_image_different_sizes() {
    let expected = solid(10, 8, Color::WHITE);
    let actual = solid(6, 12, Color::WHITE);
    let d = diff_image(&expected, &actual).unwrap();
    assert_eq!((d.width(), d.height()), (10 + 4 + 10 + 4 + 6, 12));
    let magenta = [255, 0, 255, 255];
    assert_eq!(get(&d, 14 + 9, 0), magenta); // only in expected
    assert_eq!(get(&d, 14, 11), magenta); // only in actual
    assert_eq!(get(&d, 14 + 9, 11), magenta); // in neither
    assert_eq!(get(&d, 14, 0), [255, 255, 255, 255]);
    // Below the shorter panel: background grey.
    assert_eq!(get(&d, 0, 11), [128, 128, 128, 255]);
}

#[test]
fn hstack_layout() {
    let a = solid(3, 2, Color::RED);
    let b = solid(2, 4, Color::BLUE);
    let s = hstack(&[a, b], 5).unwrap();
    assert_eq!((s.width(), s.height()), (3 + 5 + 2, 4));
    assert_eq!(get(&s, 0, 0), [214, 39, 40, 255]);
    assert_eq!(get(&s, 4, 0), [255, 255, 255, 255]);
    assert_eq!(get(&s, 8, 3), [31, 119, 180, 255]);
    assert_eq!(get(&s, 0, 3), [255, 255, 255, 255]);
    // Translucent pixels are composited over white.
    let clear = solid(1, 1, Color::TRANSPARENT);
    assert_eq!(
        get(&hstack(&[clear], 0).unwrap(), 0, 0),
        [255, 255, 255, 255]
    );
    assert!(matches!(hstack(&[], 3), Err(RenderError::NoImages)));
    let one = solid(1, 1, Color::BLACK);
    assert!(matches!(hstack(&[one], u32::MAX).map(|p| p.width()), Ok(1)));
    let wide = solid(1, 1, Color::BLACK);
    assert!(matches!(
        hstack(&[wide.clone(), wide], u32::MAX),
        Err(RenderError::InvalidSize { .. })
    ));
}

// ---- check_golden --------------------------------------------------------

#[test]
fn check_golden_missing_reference() {
    let dir = scratch_dir("missing_reference");
    let reference = dir.join("sub/ref.png");
    let image = circle_scene(60, 40).render().unwrap();
    let err = check_golden_with(&reference, &image, Tolerance::default(), false).unwrap_err();
    assert!(
        matches!(err, GoldenError::MissingReference { .. }),
        "{err:?}"
    );
    let message = err.to_string();
    assert!(message.contains("KAPPA_BLESS=1"), "{message}");
    assert!(message.contains("ref.png"), "{message}");
    // Blessing creates the directory and the file; then the check passes.
    check_golden_with(&reference, &image, Tolerance::default(), true).unwrap();
    assert_eq!(load_png(&reference).unwrap().data(), image.data());
    check_golden_with(&reference, &image, Tolerance::EXACT, false).unwrap();
    let _ = std::fs::remove_dir_all(dir);
}

#[test]
fn check_golden_mismatch_writes_failure_image() {
    let dir = scratch_dir("mismatch");
    let reference = dir.join("kappa_render_test_mismatch.png");
    let expected = circle_scene(60, 40).render().unwrap();
    std::fs::write(&reference, expected.encode_png().unwrap()).unwrap();
    let mut actual = expected.clone();
    set(&mut actual, 1, 2, [0, 0, 0, 255]);
    set(&mut actual, 3, 4, [0, 0, 0, 255]);
    let err = check_golden_with(&reference, &actual, Tolerance::default(), false).unwrap_err();
    let GoldenError::Mismatch {
        comparison,
        failure_image,
        ..
    } = &err
    else {
        panic!("{err:?}");
    };
    assert_eq!(comparison.bad_pixels, 2);
    let failure_image = failure_image.as_ref().expect("failure image written");
    assert!(failure_image.ends_with("golden-failures/kappa_render_test_mismatch.png"));
    let message = err.to_string();
    assert!(
        message.contains(&failure_image.display().to_string()),
        "{message}"
    );
    assert!(message.contains("2 of 2400 pixels"), "{message}");
    assert!(message.contains("KAPPA_BLESS=1"), "{message}");
    let triptych = load_png(failure_image).unwrap();
    assert_eq!((triptych.width(), triptych.height()), (3 * 60 + 8, 40));
    assert_eq!(get(&triptych, 64 + 1, 2), [255, 0, 0, 255]);
    // Accepted with a budget of 2 bad pixels.
    check_golden_with(&reference, &actual, Tolerance::new(1, 2), false).unwrap();
    // Blessing replaces the reference.
    check_golden_with(&reference, &actual, Tolerance::default(), true).unwrap();
    check_golden_with(&reference, &actual, Tolerance::EXACT, false).unwrap();
    let _ = std::fs::remove_file(failure_image);
    let _ = std::fs::remove_dir_all(dir);
}

#[test]
fn check_golden_bad_reference() {
    let dir = scratch_dir("bad_reference");
    let reference = dir.join("garbage.png");
    std::fs::write(&reference, b"\x89PNG\r\n\x1a\nnot really").unwrap();
    let image = solid(4, 4, Color::WHITE);
    let err = check_golden_with(&reference, &image, Tolerance::default(), false).unwrap_err();
    assert!(matches!(err, GoldenError::Reference(_)), "{err:?}");
    assert!(err.to_string().contains("garbage.png"), "{err}");
    // Blessing overwrites a corrupt reference.
    check_golden_with(&reference, &image, Tolerance::default(), true).unwrap();
    check_golden_with(&reference, &image, Tolerance::default(), false).unwrap();
    // A size change is a mismatch.
    let err = check_golden_with(
        &reference,
        &solid(5, 4, Color::WHITE),
        Tolerance::default(),
        false,
    )
    .unwrap_err();
    assert!(err.to_string().contains("size mismatch"), "{err}");
    let _ = std::fs::remove_dir_all(dir);
}
