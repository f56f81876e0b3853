// The engine's path encoding (web/src/lib.rs), as the Editor's pathData(), combData() and
// the like return it: drawing it on a canvas, and reading it as elements.

// Path verb codes (web/src/lib.rs) and the number of coordinates after each.
export const MOVE_TO = 0, LINE_TO = 1, QUAD_TO = 2, CURVE_TO = 3, CLOSE = 4;
const ARITY = [2, 2, 4, 6, 0];

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
