// Glue for the kappa path-tool engine compiled to wasm32-unknown-unknown (web/src/ffi.rs):
// a drawing of several contours with one undo history.
// The module exports plain functions of numbers; results are read straight from its
// memory. A view must be made after the call that filled the buffer (memory may grow).

export const SCHEMES = ["kappa", "ek-cubic", "ek-trig"];

// Path verb codes (web/src/lib.rs) and the number of coordinates after each.
export const MOVE_TO = 0, LINE_TO = 1, QUAD_TO = 2, CURVE_TO = 3, CLOSE = 4;
const ARITY = [2, 2, 4, 6, 0];

export class Engine {
  constructor(instance) {
    this.x = instance.exports;
    this.decoder = new TextDecoder();
  }

  static async load(url) {
    const response = await fetch(url);
    const { instance } = await WebAssembly.instantiateStreaming(response, {});
    return new Engine(instance);
  }

  f64(ptr, len) {
    return new Float64Array(this.x.memory.buffer, ptr, len);
  }

  nums(len) {
    return this.f64(this.x.kp_nums_ptr(), len);
  }

  text(len) {
    return this.decoder.decode(new Uint8Array(this.x.memory.buffer, this.x.kp_bytes_ptr(), len));
  }

  reset(scheme) {
    const code = SCHEMES.indexOf(scheme);
    if (code < 0) throw new Error(`unknown scheme ${scheme}`);
    this.x.kp_reset(code);
  }

  // Contours: point edits go to the active one (-1: none; a click then starts one).
  contourCount() { return this.x.kp_contour_count(); }
  active() { return this.x.kp_active(); }
  setActive(k) { this.x.kp_set_active(k < 0 ? 0xffffffff : k); }
  startContour(x, y) { return this.x.kp_start_contour(x, y); }
  deleteContour(k) { return this.x.kp_delete_contour(k) === 1; }
  clear() { return this.x.kp_clear() === 1; }

  addPoint(x, y) { return this.x.kp_add_point(x, y); }
  insertPoint(x, y) { return this.x.kp_insert_point(x, y); }
  movePoint(i, x, y) { return this.x.kp_move_point(i, x, y); }
  dragPoint(i, x, y) { return this.x.kp_drag_point(i, x, y); }
  endDrag() { return this.x.kp_end_drag(); }
  deletePoint(i) { return this.x.kp_delete_point(i); }
  setShape(i, a) { return this.x.kp_set_shape(i, a); }
  dragShape(i, a) { return this.x.kp_drag_shape(i, a); }
  toggleCorner(i) { return this.x.kp_toggle_corner(i); }
  // Prescribed tangents (`incoming`: the side of a corner where a piece arrives). A drag of a
  // handle is one undo step until endDrag().
  setTangent(i, x, y, incoming = false) { return this.x.kp_set_tangent(i, x, y, incoming ? 1 : 0); }
  dragTangent(i, x, y, incoming = false) { return this.x.kp_drag_tangent(i, x, y, incoming ? 1 : 0); }
  clearTangent(i, incoming = false) { return this.x.kp_clear_tangent(i, incoming ? 1 : 0); }
  // Corner i becomes a smooth line-to-curve join: the count of failed pieces, or -1 where it
  // has no line on one side and curve on the other.
  smoothJoin(i) {
    const r = this.x.kp_smooth_join(i);
    return r < 0 ? -1 : r;
  }
  // Per point {out: [x, y] | null, in: [x, y] | null}.
  tangents(k) {
    const n = this.x.kp_tangents(k);
    const v = this.nums(n);
    const out = [];
    const vec = (a, b) => (Number.isNaN(a) ? null : [a, b]);
    for (let i = 0; i < n; i += 4) out.push({ out: vec(v[i], v[i + 1]), in: vec(v[i + 2], v[i + 3]) });
    return out;
  }
  neutralShape(scheme) { return this.x.kp_neutral_shape(SCHEMES.indexOf(scheme)); }
  setClosed(closed) { return this.x.kp_set_closed(closed ? 1 : 0); }
  closed(k) { return this.x.kp_closed(k) === 1; }
  undo() { return this.x.kp_undo() === 1; }
  redo() { return this.x.kp_redo() === 1; }
  canUndo() { return this.x.kp_can_undo() === 1; }
  canRedo() { return this.x.kp_can_redo() === 1; }
  lastIterations() { return this.x.kp_last_iterations(); }
  pointCount(k) { return this.x.kp_point_count(k); }

  // {contour, index} of the point nearest to (x, y) within `radius`, or null.
  nearestPoint(x, y, radius) {
    if (this.x.kp_nearest_point(x, y, radius) !== 2) return null;
    const v = this.nums(2);
    return { contour: v[0], index: v[1] };
  }

  setScheme(scheme) {
    const code = SCHEMES.indexOf(scheme);
    if (code < 0) throw new Error(`unknown scheme ${scheme}`);
    return this.x.kp_set_scheme(code);
  }

  scheme() { return SCHEMES[this.x.kp_scheme()]; }

  points(k) {
    const n = this.x.kp_points(k);
    const v = this.nums(n);
    const out = [];
    for (let i = 0; i < n; i += 4) {
      out.push({ x: v[i], y: v[i + 1], shape: v[i + 2], corner: v[i + 3] === 1 });
    }
    return out;
  }

  pieces(k) {
    const out = [];
    const count = this.x.kp_piece_count(k);
    for (let j = 0; j < count; j++) {
      const v = this.nums(this.x.kp_piece(k, j));
      const m = v[2], n = v[3];
      out.push({
        closed: v[0] === 1,
        failed: v[1] === 1,
        points: Array.from(v.subarray(4, 4 + m)),
        tMax: Array.from(v.subarray(4 + m, 4 + m + n)),
      });
    }
    return out;
  }

  // The exact curve: {x, y, curvature} of segment `seg` of piece `piece` of contour `k` at
  // `t`, or null.
  evalCurve(k, piece, seg, t) {
    const n = this.x.kp_eval(k, piece, seg, t);
    if (n !== 3) return null;
    const v = this.nums(3);
    return { x: v[0], y: v[1], curvature: v[2] };
  }

  hit(x, y) {
    const n = this.x.kp_hit(x, y);
    if (n !== 7) return null;
    const v = this.nums(7);
    return { contour: v[0], piece: v[1], segment: v[2], t: v[3], x: v[4], y: v[5], distance: v[6] };
  }

  // The points' bounding box {x0, y0, x1, y1}, or null without points.
  bounds() {
    if (this.x.kp_bounds() !== 4) return null;
    const v = this.nums(4);
    return { x0: v[0], y0: v[1], x1: v[2], y1: v[3] };
  }

  // The encoded path and comb as Float64Array views (valid until the next engine call).
  pathData() {
    const n = this.x.kp_path();
    return this.f64(this.x.kp_path_ptr(), n);
  }
  // The outline of contour k alone (one subpath, closed when the contour is).
  contourPathData(k) {
    const n = this.x.kp_contour_path(k);
    return this.f64(this.x.kp_path_ptr(), n);
  }
  piecePathData(k, j) {
    const n = this.x.kp_piece_path(k, j);
    return this.f64(this.x.kp_path_ptr(), n);
  }
  previewData(x, y) {
    const n = this.x.kp_preview(x, y);
    return this.f64(this.x.kp_path_ptr(), n);
  }
  // The comb: teeth `length` long at the `percentile` of |κ|, cut at `clip` × length; a
  // positive `scale` fixes the scale instead. combScale() gives the scale used.
  combData(length, percentile, clip, samples, scale = 0) {
    const n = this.x.kp_comb(length, percentile, clip, samples, scale);
    return this.f64(this.x.kp_comb_ptr(), n);
  }
  combScale() { return this.x.kp_comb_scale(); }

  exportSvg(width, height, fill) {
    return this.text(this.x.kp_export_svg(width, height, fill ? 1 : 0));
  }

  save() { return this.text(this.x.kp_save()); }

  // Opens a drawing file, a single path's file or an exported SVG: the number of pieces that
  // failed to solve, or -1 if it did not open (lastError() says why).
  open(text, undoable = true) {
    const bytes = new TextEncoder().encode(text);
    const ptr = this.x.kp_input(bytes.length);
    new Uint8Array(this.x.memory.buffer, ptr, bytes.length).set(bytes);
    const r = this.x.kp_open(undoable ? 1 : 0);
    return r < 0 ? -1 : r; // u32::MAX arrives as -1 (wasm i32)
  }

  lastError() { return this.text(this.x.kp_last_error()); }
}

// Draws an encoded path onto a canvas 2D context (as the current path).
export function tracePath(ctx, data) {
  let i = 0;
  while (i < data.length) {
    const verb = data[i];
    const c = i + 1;
    switch (verb) {
      case MOVE_TO: ctx.moveTo(data[c], data[c + 1]); break;
      case LINE_TO: ctx.lineTo(data[c], data[c + 1]); break;
      case QUAD_TO: ctx.quadraticCurveTo(data[c], data[c + 1], data[c + 2], data[c + 3]); break;
      case CURVE_TO:
        ctx.bezierCurveTo(data[c], data[c + 1], data[c + 2], data[c + 3], data[c + 4], data[c + 5]);
        break;
      case CLOSE: ctx.closePath(); break;
      default: throw new Error(`bad path verb ${verb} at ${i}`);
    }
    i += 1 + ARITY[verb];
  }
}

// The encoded path as an array of [verb, ...coordinates] elements.
export function pathElements(data) {
  const out = [];
  let i = 0;
  while (i < data.length) {
    const verb = data[i];
    out.push([verb, ...data.subarray(i + 1, i + 1 + ARITY[verb])]);
    i += 1 + ARITY[verb];
  }
  return out;
}
