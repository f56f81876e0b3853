//! The C-ABI exports of the wasm module: one [`Session`] per module instance. Point edits go
//! to the active contour ([`kp_set_active`]).
//!
//! Every function takes and returns numbers only. Indices are `u32` (JavaScript's `-1`
//! arrives as `u32::MAX`: out of range, which changes nothing); flags are `0`/`1`; schemes
//! are the codes of [`scheme_from_code`]. Functions that fill a buffer return its length
//! (in `f64`s or bytes); the matching `kp_*_ptr` gives its address in the module's memory,
//! valid until the next call. Edits return the number of pieces that failed to solve
//! (`kp_last_error` says why), or `u32::MAX` for an unknown scheme code.

use std::cell::RefCell;

use crate::{scheme_from_code, Session};

thread_local! {
    static SESSION: RefCell<Session> = RefCell::new(Session::new(kappa::Scheme::Kappa));
}

fn with<R>(f: impl FnOnce(&mut Session) -> R) -> R {
    SESSION.with_borrow_mut(f)
}

fn index(i: u32) -> usize {
    usize::try_from(i).unwrap_or(usize::MAX)
}

fn len(n: usize) -> u32 {
    u32::try_from(n).unwrap_or(u32::MAX)
}

/// Starts an empty drawing with scheme `scheme`; 0, or `u32::MAX` for an unknown code.
#[no_mangle]
pub extern "C" fn kp_reset(scheme: u32) -> u32 {
    match scheme_from_code(scheme) {
        Some(s) => with(|x| *x = Session::new(s)),
        None => return u32::MAX,
    }
    0
}

/// The number of contours.
#[no_mangle]
pub extern "C" fn kp_contour_count() -> u32 {
    with(|s| len(s.drawing().len()))
}

/// The active contour, or -1.
#[no_mangle]
pub extern "C" fn kp_active() -> i32 {
    with(|s| s.active())
        .and_then(|k| i32::try_from(k).ok())
        .unwrap_or(-1)
}

/// Makes contour `k` active (-1, or any index out of range, for none).
#[no_mangle]
pub extern "C" fn kp_set_active(k: u32) {
    with(|s| s.set_active(Some(index(k))))
}

/// Starts a new contour at `(x, y)` (the active one); its index.
#[no_mangle]
pub extern "C" fn kp_start_contour(x: f64, y: f64) -> u32 {
    with(|s| len(s.start_contour(x, y)))
}

/// Deletes contour `k`: 1 if there was one.
#[no_mangle]
pub extern "C" fn kp_delete_contour(k: u32) -> u32 {
    u32::from(with(|s| s.delete_contour(index(k))))
}

/// Removes every contour (one undo step): 1 if there was any.
#[no_mangle]
pub extern "C" fn kp_clear() -> u32 {
    u32::from(with(|s| s.clear()))
}

/// Appends a point to the active contour (or starts one).
#[no_mangle]
pub extern "C" fn kp_add_point(x: f64, y: f64) -> u32 {
    with(|s| s.add_point(x, y))
}

/// Inserts a point on the curve nearest to `(x, y)`: its index in the contour it went to
/// (now active), or -1 without a curve.
#[no_mangle]
pub extern "C" fn kp_insert_point(x: f64, y: f64) -> i32 {
    with(|s| s.insert_point(x, y))
        .and_then(|i| i32::try_from(i).ok())
        .unwrap_or(-1)
}

/// Moves point `i` of the active contour (one undo step).
#[no_mangle]
pub extern "C" fn kp_move_point(i: u32, x: f64, y: f64) -> u32 {
    with(|s| s.move_point(index(i), x, y))
}

/// Moves point `i` of the active contour within a drag gesture (one undo step until
/// [`kp_end_drag`]).
#[no_mangle]
pub extern "C" fn kp_drag_point(i: u32, x: f64, y: f64) -> u32 {
    with(|s| s.drag_point(index(i), x, y))
}

/// Ends the drag gesture; the number of pieces that failed to solve.
#[no_mangle]
pub extern "C" fn kp_end_drag() -> u32 {
    with(|s| s.end_drag())
}

/// Deletes point `i` of the active contour.
#[no_mangle]
pub extern "C" fn kp_delete_point(i: u32) -> u32 {
    with(|s| s.delete_point(index(i)))
}

/// Sets the shape of point `i` of the active contour.
#[no_mangle]
pub extern "C" fn kp_set_shape(i: u32, a: f64) -> u32 {
    with(|s| s.set_shape(index(i), a))
}

/// Sets the shape of point `i` within a slider drag (one undo step until [`kp_end_drag`]).
#[no_mangle]
pub extern "C" fn kp_drag_shape(i: u32, a: f64) -> u32 {
    with(|s| s.drag_shape(index(i), a))
}

/// Toggles the corner flag of point `i` of the active contour.
#[no_mangle]
pub extern "C" fn kp_toggle_corner(i: u32) -> u32 {
    with(|s| s.toggle_corner(index(i)))
}

/// Sets the prescribed tangent of point `i` of the active contour to `(x, y)` (`incoming`
/// 1: the side of a corner where a piece arrives).
#[no_mangle]
pub extern "C" fn kp_set_tangent(i: u32, x: f64, y: f64, incoming: u32) -> u32 {
    with(|s| s.set_tangent(index(i), x, y, incoming != 0))
}

/// Sets the prescribed tangent of point `i` of the active contour within a handle drag (one
/// undo step until [`kp_end_drag`]).
#[no_mangle]
pub extern "C" fn kp_drag_tangent(i: u32, x: f64, y: f64, incoming: u32) -> u32 {
    with(|s| s.drag_tangent(index(i), x, y, incoming != 0))
}

/// Clears the prescribed tangent of point `i` of the active contour.
#[no_mangle]
pub extern "C" fn kp_clear_tangent(i: u32, incoming: u32) -> u32 {
    with(|s| s.clear_tangent(index(i), incoming != 0))
}

/// Makes corner `i` of the active contour a smooth line-to-curve join; `u32::MAX` where it
/// has no line on one side and curve on the other.
#[no_mangle]
pub extern "C" fn kp_smooth_join(i: u32) -> u32 {
    with(|s| s.smooth_join(index(i)))
}

/// Writes the tangents of contour `k` to the numbers ([`Session::fill_tangents`]).
#[no_mangle]
pub extern "C" fn kp_tangents(k: u32) -> u32 {
    with(|s| len(s.fill_tangents(index(k))))
}

/// Encodes the outline of contour `k` into the path buffer
/// ([`Session::fill_contour_path`]).
#[no_mangle]
pub extern "C" fn kp_contour_path(k: u32) -> u32 {
    with(|s| len(s.fill_contour_path(index(k))))
}

/// The neutral shape parameter of scheme `scheme` (NaN for an unknown code).
#[no_mangle]
pub extern "C" fn kp_neutral_shape(scheme: u32) -> f64 {
    scheme_from_code(scheme).map_or(f64::NAN, |s| s.neutral_shape())
}

/// Closes (`1`) or opens (`0`) the active contour.
#[no_mangle]
pub extern "C" fn kp_set_closed(closed: u32) -> u32 {
    with(|s| s.set_closed(closed != 0))
}

/// Switches the scheme of every contour.
#[no_mangle]
pub extern "C" fn kp_set_scheme(scheme: u32) -> u32 {
    match scheme_from_code(scheme) {
        Some(code) => with(|s| s.set_scheme(code)),
        None => u32::MAX,
    }
}

/// Undoes the last step: 1 if there was one.
#[no_mangle]
pub extern "C" fn kp_undo() -> u32 {
    u32::from(with(|s| s.undo()))
}

/// Redoes the last undone step: 1 if there was one.
#[no_mangle]
pub extern "C" fn kp_redo() -> u32 {
    u32::from(with(|s| s.redo()))
}

/// 1 if there is a step to undo.
#[no_mangle]
pub extern "C" fn kp_can_undo() -> u32 {
    u32::from(with(|s| s.drawing().can_undo()))
}

/// 1 if there is a step to redo.
#[no_mangle]
pub extern "C" fn kp_can_redo() -> u32 {
    u32::from(with(|s| s.drawing().can_redo()))
}

/// The number of points of contour `k`.
#[no_mangle]
pub extern "C" fn kp_point_count(k: u32) -> u32 {
    with(|s| {
        len(s
            .drawing()
            .contour(index(k))
            .map_or(0, |e| e.doc().points.len()))
    })
}

/// 1 if contour `k` is closed.
#[no_mangle]
pub extern "C" fn kp_closed(k: u32) -> u32 {
    with(|s| {
        u32::from(
            s.drawing()
                .contour(index(k))
                .is_some_and(|e| e.doc().closed),
        )
    })
}

/// The scheme code.
#[no_mangle]
pub extern "C" fn kp_scheme() -> u32 {
    with(|s| crate::scheme_code(s.drawing().scheme()))
}

/// Solver iterations of the last edit.
#[no_mangle]
pub extern "C" fn kp_last_iterations() -> u32 {
    with(|s| len(s.last_change().iterations))
}

/// The number of pieces of contour `k`.
#[no_mangle]
pub extern "C" fn kp_piece_count(k: u32) -> u32 {
    with(|s| len(s.drawing().contour(index(k)).map_or(0, |e| e.pieces())))
}

/// Writes the points of contour `k` to the numbers ([`Session::fill_points`]).
#[no_mangle]
pub extern "C" fn kp_points(k: u32) -> u32 {
    with(|s| len(s.fill_points(index(k))))
}

/// Writes piece `j` of contour `k` to the numbers ([`Session::fill_piece`]).
#[no_mangle]
pub extern "C" fn kp_piece(k: u32, j: u32) -> u32 {
    with(|s| len(s.fill_piece(index(k), index(j))))
}

/// Writes `x, y, κ` of segment `g` of piece `j` of contour `k` at `t` to the numbers
/// ([`Session::eval`]).
#[no_mangle]
pub extern "C" fn kp_eval(k: u32, j: u32, g: u32, t: f64) -> u32 {
    with(|s| len(s.eval(index(k), index(j), index(g), t)))
}

/// Writes the nearest curve point to the numbers ([`Session::hit`]).
#[no_mangle]
pub extern "C" fn kp_hit(x: f64, y: f64) -> u32 {
    with(|s| len(s.hit(x, y)))
}

/// Writes `contour, index` of the point nearest to `(x, y)` within `radius` to the
/// numbers ([`Session::nearest_point`]).
#[no_mangle]
pub extern "C" fn kp_nearest_point(x: f64, y: f64, radius: f64) -> u32 {
    with(|s| len(s.nearest_point(x, y, radius)))
}

/// Writes the points' bounding box to the numbers ([`Session::fill_bounds`]).
#[no_mangle]
pub extern "C" fn kp_bounds() -> u32 {
    with(|s| len(s.fill_bounds()))
}

/// Encodes the outline ([`Session::fill_path`]).
#[no_mangle]
pub extern "C" fn kp_path() -> u32 {
    with(|s| len(s.fill_path()))
}

/// Encodes the preview of a click at `(x, y)` into the path buffer
/// ([`Session::fill_preview`]).
#[no_mangle]
pub extern "C" fn kp_preview(x: f64, y: f64) -> u32 {
    with(|s| len(s.fill_preview(x, y)))
}

/// Encodes piece `j` of contour `k` into the path buffer ([`Session::fill_piece_path`]).
#[no_mangle]
pub extern "C" fn kp_piece_path(k: u32, j: u32) -> u32 {
    with(|s| len(s.fill_piece_path(index(k), index(j))))
}

/// Encodes the curvature comb ([`Session::fill_comb`]).
#[no_mangle]
pub extern "C" fn kp_comb(
    length: f64,
    percentile: f64,
    clip: f64,
    samples: u32,
    scale: f64,
) -> u32 {
    with(|s| len(s.fill_comb(length, percentile, clip, index(samples), scale)))
}

/// The scale of the last comb.
#[no_mangle]
pub extern "C" fn kp_comb_scale() -> f64 {
    with(|s| s.comb_scale())
}

/// Writes the SVG export, with the drawing's file inside, to the bytes
/// ([`Session::export_svg`]).
#[no_mangle]
pub extern "C" fn kp_export_svg(width: f64, height: f64, fill: u32) -> u32 {
    with(|s| len(s.export_svg(width, height, fill != 0)))
}

/// Writes the drawing's file (JSON) to the bytes ([`Session::save`]).
#[no_mangle]
pub extern "C" fn kp_save() -> u32 {
    with(|s| len(s.save()))
}

/// Makes an input buffer of `n` bytes and returns its address, for the page to write a
/// file into before [`kp_open`].
#[no_mangle]
pub extern "C" fn kp_input(n: u32) -> usize {
    with(|s| s.input_buffer(index(n)).as_mut_ptr() as usize)
}

/// Opens the file in the input buffer ([`Session::open_input`]; as an undo step with
/// `undoable` 1): the number of pieces that failed to solve, or `u32::MAX` if it did not
/// open (`kp_last_error` says why).
#[no_mangle]
pub extern "C" fn kp_open(undoable: u32) -> u32 {
    with(|s| s.open_input(undoable != 0).unwrap_or(u32::MAX))
}

/// Writes the errors of the last edit to the bytes ([`Session::last_error`]).
#[no_mangle]
pub extern "C" fn kp_last_error() -> u32 {
    with(|s| len(s.last_error()))
}

/// Address of the numbers.
#[no_mangle]
pub extern "C" fn kp_nums_ptr() -> usize {
    with(|s| s.nums().as_ptr() as usize)
}

/// Address of the encoded path.
#[no_mangle]
pub extern "C" fn kp_path_ptr() -> usize {
    with(|s| s.path().as_ptr() as usize)
}

/// Address of the encoded comb.
#[no_mangle]
pub extern "C" fn kp_comb_ptr() -> usize {
    with(|s| s.comb().as_ptr() as usize)
}

/// Address of the bytes.
#[no_mangle]
pub extern "C" fn kp_bytes_ptr() -> usize {
    with(|s| s.bytes().as_ptr() as usize)
}

#[cfg(test)]
mod tests {
    use super::*;

    // The exports share one session per thread; each test runs on its own thread.
    #[test]
    fn exports_edit_one_session() {
        assert_eq!(kp_reset(7), u32::MAX);
        assert_eq!(kp_reset(1), 0);
        assert_eq!(kp_active(), -1);
        for (x, y) in [
            (100.0, 100.0),
            (200.0, 50.0),
            (300.0, 120.0),
            (250.0, 250.0),
        ] {
            assert_eq!(kp_add_point(x, y), 0);
        }
        assert_eq!(kp_active(), 0);
        assert_eq!(kp_point_count(0), 4);
        assert_eq!(kp_scheme(), 1);
        assert_eq!(kp_set_closed(1), 0);
        assert_eq!(kp_closed(0), 1);
        assert_eq!(kp_piece_count(0), 1);
        assert_eq!(kp_piece(0, 0), 4 + 4 + 4);
        assert_eq!(kp_set_shape(2, 0.9), 0);
        assert_eq!(kp_drag_shape(3, 0.8), 0);
        assert_eq!(kp_drag_shape(3, 0.85), 0);
        kp_end_drag();
        assert_eq!(kp_points(0), 16);
        with(|s| assert_eq!(s.nums()[2 * 4 + 2], 0.9));
        // Out-of-range indices (JavaScript's -1) change nothing.
        assert_eq!(kp_move_point(u32::MAX, 0.0, 0.0), 0);
        assert_eq!(kp_points(0), 16);
        assert_eq!(kp_nearest_point(201.0, 52.0, 5.0), 2);
        assert_eq!(kp_nearest_point(0.0, 0.0, 5.0), 0);
        for k in 0..5 {
            assert_eq!(kp_drag_point(1, 200.0 + k as f64, 50.0), 0);
        }
        kp_end_drag();
        assert!(kp_last_iterations() > 0);
        assert_eq!(kp_set_scheme(9), u32::MAX);
        assert_eq!(kp_set_scheme(2), 0);
        assert!(kp_path() > 0 && kp_comb(50.0, 0.75, 3.0, 4, 0.0) > 0);
        assert!(kp_comb_scale() > 0.0);
        assert!(kp_export_svg(400.0, 300.0, 0) > 0);
        assert_eq!(kp_eval(0, 0, 0, 0.5), 3);
        assert_eq!(kp_hit(150.0, 90.0), 7);
        assert_eq!(kp_toggle_corner(0), 0);
        assert_eq!(kp_insert_point(150.0, 80.0), 1);
        assert_eq!(kp_delete_point(1), 0);
        // A tangent far from the free curve may not converge: the count says so.
        assert!(kp_set_tangent(2, 1.0, 0.1, 0) <= 1);
        assert_eq!(kp_tangents(0), 16);
        with(|s| assert_eq!(s.nums()[2 * 4], 1.0));
        assert!(kp_drag_tangent(2, 1.0, 0.2, 0) <= 1);
        assert!(kp_drag_tangent(2, 1.0, 0.3, 0) <= 1);
        kp_end_drag();
        assert_eq!(kp_clear_tangent(2, 0), 0);
        assert_eq!(kp_smooth_join(2), u32::MAX);
        assert!(kp_contour_path(0) > 0);
        assert!(kp_neutral_shape(9).is_nan());
        assert_eq!(kp_last_error(), 0);
        assert_eq!(kp_preview(0.0, 0.0), 0);
        // A second contour; then open a file.
        assert_eq!(kp_start_contour(500.0, 500.0), 1);
        assert_eq!(kp_contour_count(), 2);
        assert_eq!(kp_bounds(), 4);
        let n = kp_save();
        assert!(n > 0);
        let file = with(|s| s.bytes().to_vec());
        assert_ne!(kp_input(len(file.len())), 0);
        with(|s| s.input_buffer(file.len()).copy_from_slice(&file));
        assert_eq!(kp_open(1), 0);
        assert_eq!(kp_contour_count(), 2);
        kp_input(2);
        assert_eq!(kp_open(1), u32::MAX);
        assert!(kp_last_error() > 0);
        kp_set_active(1);
        assert_eq!(kp_active(), 1);
        assert_eq!(kp_delete_contour(1), 1);
        assert_eq!(kp_clear(), 1);
        // Undo back to the empty drawing.
        let mut steps = 0;
        while kp_undo() == 1 {
            steps += 1;
        }
        // 4 points (the first starts the contour), close, shape, a slider gesture, a drag
        // gesture, scheme, corner, insert, delete, a tangent, a handle drag, the tangent's
        // clearing, a contour, the open, a delete, the clear.
        assert_eq!(steps, 19);
        assert_eq!(kp_contour_count(), 0);
        assert_eq!(kp_can_undo(), 0);
        assert_eq!(kp_redo(), 1);
        assert_eq!(kp_can_redo(), 1);
        assert_eq!(kp_point_count(0), 1);
        assert_ne!(kp_nums_ptr(), 0);
        assert_ne!(kp_path_ptr(), 0);
        assert_ne!(kp_comb_ptr(), 0);
        assert_ne!(kp_bytes_ptr(), 0);
    }
}
