//! The C-ABI exports of the wasm module: one [`Session`] per module instance.
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
    static SESSION: RefCell<Session> = RefCell::new(Session::default());
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

/// Starts an empty path with scheme `scheme`; 0, or `u32::MAX` for an unknown code.
#[no_mangle]
pub extern "C" fn kp_reset(scheme: u32) -> u32 {
    match scheme_from_code(scheme) {
        Some(s) => with(|x| *x = Session::new(s)),
        None => return u32::MAX,
    }
    0
}

/// Appends a point.
#[no_mangle]
pub extern "C" fn kp_add_point(x: f64, y: f64) -> u32 {
    with(|s| s.add_point(x, y))
}

/// Inserts a point on the curve nearest to `(x, y)`: its index, or -1 without a curve.
#[no_mangle]
pub extern "C" fn kp_insert_point(x: f64, y: f64) -> i32 {
    with(|s| s.insert_point(x, y))
        .and_then(|i| i32::try_from(i).ok())
        .unwrap_or(-1)
}

/// Moves point `i` (one undo step).
#[no_mangle]
pub extern "C" fn kp_move_point(i: u32, x: f64, y: f64) -> u32 {
    with(|s| s.move_point(index(i), x, y))
}

/// Moves point `i` within a drag gesture (one undo step until [`kp_end_drag`]).
#[no_mangle]
pub extern "C" fn kp_drag_point(i: u32, x: f64, y: f64) -> u32 {
    with(|s| s.drag_point(index(i), x, y))
}

/// Ends the drag gesture; the number of pieces that failed to solve.
#[no_mangle]
pub extern "C" fn kp_end_drag() -> u32 {
    with(|s| s.end_drag())
}

/// Deletes point `i`.
#[no_mangle]
pub extern "C" fn kp_delete_point(i: u32) -> u32 {
    with(|s| s.delete_point(index(i)))
}

/// Sets the shape of point `i`.
#[no_mangle]
pub extern "C" fn kp_set_shape(i: u32, a: f64) -> u32 {
    with(|s| s.set_shape(index(i), a))
}

/// Sets the shape of point `i` within a slider drag (one undo step until [`kp_end_drag`]).
#[no_mangle]
pub extern "C" fn kp_drag_shape(i: u32, a: f64) -> u32 {
    with(|s| s.drag_shape(index(i), a))
}

/// Toggles the corner flag of point `i`.
#[no_mangle]
pub extern "C" fn kp_toggle_corner(i: u32) -> u32 {
    with(|s| s.toggle_corner(index(i)))
}

/// Closes (`1`) or opens (`0`) the path.
#[no_mangle]
pub extern "C" fn kp_set_closed(closed: u32) -> u32 {
    with(|s| s.set_closed(closed != 0))
}

/// Switches the scheme.
#[no_mangle]
pub extern "C" fn kp_set_scheme(scheme: u32) -> u32 {
    match scheme_from_code(scheme) {
        Some(code) => with(|s| s.set_scheme(code)),
        None => u32::MAX,
    }
}

/// Undoes the last edit: 1 if there was one.
#[no_mangle]
pub extern "C" fn kp_undo() -> u32 {
    u32::from(with(|s| s.undo()))
}

/// Redoes the last undone edit: 1 if there was one.
#[no_mangle]
pub extern "C" fn kp_redo() -> u32 {
    u32::from(with(|s| s.redo()))
}

/// The number of points.
#[no_mangle]
pub extern "C" fn kp_point_count() -> u32 {
    with(|s| len(s.editor().doc().points.len()))
}

/// 1 if the path is closed.
#[no_mangle]
pub extern "C" fn kp_closed() -> u32 {
    with(|s| u32::from(s.editor().doc().closed))
}

/// The scheme code.
#[no_mangle]
pub extern "C" fn kp_scheme() -> u32 {
    with(|s| crate::scheme_code(s.editor().doc().scheme))
}

/// Solver iterations of the last edit.
#[no_mangle]
pub extern "C" fn kp_last_iterations() -> u32 {
    with(|s| len(s.last_change().iterations))
}

/// The number of pieces.
#[no_mangle]
pub extern "C" fn kp_piece_count() -> u32 {
    with(|s| len(s.editor().pieces()))
}

/// Writes the points to the numbers ([`Session::fill_points`]).
#[no_mangle]
pub extern "C" fn kp_points() -> u32 {
    with(|s| len(s.fill_points()))
}

/// Writes piece `k` to the numbers ([`Session::fill_piece`]).
#[no_mangle]
pub extern "C" fn kp_piece(k: u32) -> u32 {
    with(|s| len(s.fill_piece(index(k))))
}

/// Writes `x, y, κ` of segment `j` of piece `k` at `t` to the numbers ([`Session::eval`]).
#[no_mangle]
pub extern "C" fn kp_eval(k: u32, j: u32, t: f64) -> u32 {
    with(|s| len(s.eval(index(k), index(j), t)))
}

/// Writes the nearest curve point to the numbers ([`Session::hit`]).
#[no_mangle]
pub extern "C" fn kp_hit(x: f64, y: f64) -> u32 {
    with(|s| len(s.hit(x, y)))
}

/// The index of the point nearest to `(x, y)` within `radius`, or -1.
#[no_mangle]
pub extern "C" fn kp_nearest_point(x: f64, y: f64, radius: f64) -> i32 {
    with(|s| s.nearest_point(x, y, radius))
        .and_then(|i| i32::try_from(i).ok())
        .unwrap_or(-1)
}

/// Encodes the path ([`Session::fill_path`]).
#[no_mangle]
pub extern "C" fn kp_path() -> u32 {
    with(|s| len(s.fill_path()))
}

/// Encodes piece `k` into the path buffer ([`Session::fill_piece_path`]).
#[no_mangle]
pub extern "C" fn kp_piece_path(k: u32) -> u32 {
    with(|s| len(s.fill_piece_path(index(k))))
}

/// Encodes the curvature comb ([`Session::fill_comb`]).
#[no_mangle]
pub extern "C" fn kp_comb(scale: f64, samples: u32) -> u32 {
    with(|s| len(s.fill_comb(scale, index(samples))))
}

/// The largest |κ| of the curve.
#[no_mangle]
pub extern "C" fn kp_max_curvature() -> f64 {
    with(|s| s.max_curvature())
}

/// Writes the SVG export to the bytes ([`Session::export_svg`]).
#[no_mangle]
pub extern "C" fn kp_export_svg(width: f64, height: f64, with_points: u32) -> u32 {
    with(|s| len(s.export_svg(width, height, with_points != 0)))
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
        for (x, y) in [
            (100.0, 100.0),
            (200.0, 50.0),
            (300.0, 120.0),
            (250.0, 250.0),
        ] {
            assert_eq!(kp_add_point(x, y), 0);
        }
        assert_eq!(kp_point_count(), 4);
        assert_eq!(kp_scheme(), 1);
        assert_eq!(kp_set_closed(1), 0);
        assert_eq!(kp_closed(), 1);
        assert_eq!(kp_piece_count(), 1);
        assert_eq!(kp_piece(0), 4 + 4 + 4);
        assert_eq!(kp_set_shape(2, 0.9), 0);
        assert_eq!(kp_drag_shape(3, 0.8), 0);
        assert_eq!(kp_drag_shape(3, 0.85), 0);
        kp_end_drag();
        assert_eq!(kp_points(), 16);
        with(|s| assert_eq!(s.nums()[2 * 4 + 2], 0.9));
        // Out-of-range indices (JavaScript's -1) change nothing.
        assert_eq!(kp_move_point(u32::MAX, 0.0, 0.0), 0);
        assert_eq!(kp_points(), 16);
        assert_eq!(kp_nearest_point(201.0, 52.0, 5.0), 1);
        assert_eq!(kp_nearest_point(0.0, 0.0, 5.0), -1);
        for k in 0..5 {
            assert_eq!(kp_drag_point(1, 200.0 + k as f64, 50.0), 0);
        }
        kp_end_drag();
        assert!(kp_last_iterations() > 0);
        assert_eq!(kp_set_scheme(9), u32::MAX);
        assert_eq!(kp_set_scheme(2), 0);
        assert!(kp_path() > 0 && kp_comb(100.0, 4) > 0);
        assert!(kp_max_curvature() > 0.0);
        assert!(kp_export_svg(400.0, 300.0, 0) > 0);
        assert_eq!(kp_eval(0, 0, 0.5), 3);
        assert_eq!(kp_hit(150.0, 90.0), 6);
        assert_eq!(kp_toggle_corner(0), 0);
        assert_eq!(kp_insert_point(150.0, 80.0), 1);
        assert_eq!(kp_delete_point(1), 0);
        assert_eq!(kp_last_error(), 0);
        // Undo back to the empty path.
        let mut steps = 0;
        while kp_undo() == 1 {
            steps += 1;
        }
        // 4 adds, close, shape, a slider gesture, a drag gesture, scheme, corner, insert,
        // delete.
        assert_eq!(steps, 12);
        assert_eq!(kp_point_count(), 0);
        assert_eq!(kp_redo(), 1);
        assert_eq!(kp_point_count(), 1);
        assert_ne!(kp_nums_ptr(), 0);
        assert_ne!(kp_path_ptr(), 0);
        assert_ne!(kp_comb_ptr(), 0);
        assert_ne!(kp_bytes_ptr(), 0);
    }
}
