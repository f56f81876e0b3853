// Glue for the kappa path-tool engine compiled to wasm32-unknown-unknown (web/src/ffi.rs).
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

  addPoint(x, y) { return this.x.kp_add_point(x, y); }
  insertPoint(x, y) { return this.x.kp_insert_point(x, y); }
  movePoint(i, x, y) { return this.x.kp_move_point(i, x, y); }
  dragPoint(i, x, y) { return this.x.kp_drag_point(i, x, y); }
  endDrag() { return this.x.kp_end_drag(); }
  deletePoint(i) { return this.x.kp_delete_point(i); }
  setShape(i, a) { return this.x.kp_set_shape(i, a); }
  dragShape(i, a) { return this.x.kp_drag_shape(i, a); }
  toggleCorner(i) { return this.x.kp_toggle_corner(i); }
  setClosed(closed) { return this.x.kp_set_closed(closed ? 1 : 0); }
  closed() { return this.x.kp_closed() === 1; }
  undo() { return this.x.kp_undo() === 1; }
  redo() { return this.x.kp_redo() === 1; }
  lastIterations() { return this.x.kp_last_iterations(); }
  pointCount() { return this.x.kp_point_count(); }
  maxCurvature() { return this.x.kp_max_curvature(); }
  nearestPoint(x, y, radius) { return this.x.kp_nearest_point(x, y, radius); }

  setScheme(scheme) {
    const code = SCHEMES.indexOf(scheme);
    if (code < 0) throw new Error(`unknown scheme ${scheme}`);
    return this.x.kp_set_scheme(code);
  }

  scheme() { return SCHEMES[this.x.kp_scheme()]; }

  points() {
    const n = this.x.kp_points();
    const v = this.nums(n);
    const out = [];
    for (let i = 0; i < n; i += 4) {
      out.push({ x: v[i], y: v[i + 1], shape: v[i + 2], corner: v[i + 3] === 1 });
    }
    return out;
  }

  pieces() {
    const out = [];
    const count = this.x.kp_piece_count();
    for (let k = 0; k < count; k++) {
      const v = this.nums(this.x.kp_piece(k));
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

  // The exact curve: {x, y, curvature} of segment `seg` of piece `piece` at `t`, or null.
  evalCurve(piece, seg, t) {
    const n = this.x.kp_eval(piece, seg, t);
    if (n !== 3) return null;
    const v = this.nums(3);
    return { x: v[0], y: v[1], curvature: v[2] };
  }

  hit(x, y) {
    const n = this.x.kp_hit(x, y);
    if (n !== 6) return null;
    const v = this.nums(6);
    return { piece: v[0], segment: v[1], t: v[2], x: v[3], y: v[4], distance: v[5] };
  }

  // The encoded path and comb as Float64Array views (valid until the next engine call).
  pathData() {
    const n = this.x.kp_path();
    return this.f64(this.x.kp_path_ptr(), n);
  }
  piecePathData(k) {
    const n = this.x.kp_piece_path(k);
    return this.f64(this.x.kp_path_ptr(), n);
  }
  combData(scale, samples) {
    const n = this.x.kp_comb(scale, samples);
    return this.f64(this.x.kp_comb_ptr(), n);
  }

  exportSvg(width, height, withPoints) {
    return this.text(this.x.kp_export_svg(width, height, withPoints ? 1 : 0));
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
