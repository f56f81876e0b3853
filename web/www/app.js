// The path-tool page: canvas drawing, mouse and keyboard editing, and the `window.kappa`
// API that the browser test (web/test/) drives.

import { Engine, tracePath, pathElements } from "./kappa.js";

// Comb teeth per segment: dense on short paths, 8 from 60 points on (the native bench's).
const combSamples = (n) => Math.max(8, Math.min(32, Math.round(480 / Math.max(n, 1))));
const COMB_LENGTH = 50;       // longest comb tooth, px (set after each edit, kept while dragging)
const PICK_RADIUS = 8;        // px around a point that grabs it
const INSERT_RADIUS = 10;     // px around the curve where Shift+click inserts
const WARNING_COLOR = "#e07000"; // a piece whose solve did not converge (its best curve)

const $ = (id) => document.getElementById(id);
const canvas = $("canvas");
const ctx = canvas.getContext("2d");
const W = canvas.width, H = canvas.height;
const dpr = window.devicePixelRatio || 1;
canvas.width = W * dpr;
canvas.height = H * dpr;
canvas.style.width = `${W}px`;
canvas.style.height = `${H}px`;

const engine = await Engine.load(new URL("kappa_web.wasm", import.meta.url));
engine.reset($("scheme").value);

const ui = {
  selected: -1,
  dragging: -1,
  comb: $("comb").checked,
  combScale: 0,
  lastUpdateMs: null,
  message: "",
};

// Shape slider range per scheme ([min, max) of the scheme; κ has no shape).
const SHAPE_RANGE = { "kappa": null, "ek-cubic": [0.667, 0.99], "ek-trig": [0.5, 0.99] };

function draw() {
  ctx.setTransform(dpr, 0, 0, dpr, 0, 0);
  ctx.fillStyle = "#fff";
  ctx.fillRect(0, 0, W, H);
  if (ui.comb && ui.combScale > 0) {
    const comb = engine.combData(ui.combScale, combSamples(engine.pointCount()));
    ctx.beginPath();
    tracePath(ctx, comb);
    ctx.strokeStyle = "rgba(40, 110, 220, 0.55)";
    ctx.lineWidth = 1;
    ctx.stroke();
  }
  const path = engine.pathData();
  ctx.beginPath();
  tracePath(ctx, path);
  ctx.strokeStyle = "#111";
  ctx.lineWidth = 2;
  ctx.lineJoin = "round";
  ctx.stroke();
  // Pieces whose solve did not converge show their best curve, in a warning style.
  engine.pieces().forEach((piece, k) => {
    if (!piece.failed) return;
    ctx.beginPath();
    tracePath(ctx, engine.piecePathData(k));
    ctx.strokeStyle = WARNING_COLOR;
    ctx.lineWidth = 2.5;
    ctx.setLineDash([8, 5]);
    ctx.stroke();
    ctx.setLineDash([]);
  });
  const pts = engine.points();
  pts.forEach((p, i) => {
    const r = i === ui.selected ? 6 : 4.5;
    ctx.beginPath();
    if (p.corner) ctx.rect(p.x - r, p.y - r, 2 * r, 2 * r);
    else ctx.arc(p.x, p.y, r, 0, 2 * Math.PI);
    ctx.fillStyle = i === ui.selected ? "#d11" : "#fff";
    ctx.fill();
    ctx.strokeStyle = "#d11";
    ctx.lineWidth = 1.5;
    ctx.stroke();
  });
}

function status() {
  const n = engine.pointCount();
  const pieces = engine.x.kp_piece_count();
  let text = `${n} point${n === 1 ? "" : "s"} · ${pieces} piece${pieces === 1 ? "" : "s"} · ` +
    `${engine.scheme()}${engine.closed() ? ", closed" : ", open"}`;
  const iterations = engine.lastIterations();
  if (iterations > 0) text += ` · last edit ${iterations} solver iterations`;
  if (ui.lastUpdateMs !== null) text += ` · drag update ${ui.lastUpdateMs.toFixed(3)} ms`;
  const el = $("status");
  el.textContent = text;
  if (ui.message) {
    const err = document.createElement("span");
    err.className = "error";
    err.textContent = ` · ${ui.message}`;
    el.appendChild(err);
  }
}

function syncControls() {
  const n = engine.pointCount();
  if (ui.selected >= n) ui.selected = n - 1;
  const scheme = engine.scheme();
  $("scheme").value = scheme;
  $("closed").checked = engine.closed();
  const range = SHAPE_RANGE[scheme];
  const slider = $("shape");
  const pts = engine.points();
  const sel = ui.selected >= 0 ? pts[ui.selected] : null;
  slider.disabled = !range || !sel;
  if (range) {
    slider.min = range[0];
    slider.max = range[1];
  }
  if (sel && range) slider.value = sel.shape;
  $("shape-value").textContent = sel && range ? sel.shape.toFixed(3) : "";
  $("corner").disabled = !sel;
  $("delete").disabled = !sel;
}

// After an edit that is not a drag update: the last edit's errors, new comb scale, controls,
// drawing.
function refresh() {
  ui.message = engine.lastError();
  const k = engine.maxCurvature();
  ui.combScale = k > 0 ? COMB_LENGTH / k : 0;
  syncControls();
  draw();
  status();
}

function mouse(e) {
  const r = canvas.getBoundingClientRect();
  return { x: e.clientX - r.left - canvas.clientLeft, y: e.clientY - r.top - canvas.clientTop };
}

canvas.addEventListener("mousedown", (e) => {
  const p = mouse(e);
  let i = engine.nearestPoint(p.x, p.y, PICK_RADIUS);
  if (i < 0 && e.shiftKey) {
    const hit = engine.hit(p.x, p.y);
    if (hit && hit.distance <= INSERT_RADIUS) i = engine.insertPoint(p.x, p.y);
  }
  if (i < 0) {
    engine.addPoint(p.x, p.y);
    i = engine.pointCount() - 1;
  }
  ui.selected = i;
  ui.dragging = i;
  refresh();
});

canvas.addEventListener("mousemove", (e) => {
  const p = mouse(e);
  if (ui.dragging < 0) {
    canvas.style.cursor = engine.nearestPoint(p.x, p.y, PICK_RADIUS) >= 0 ? "move" : "crosshair";
    return;
  }
  const t0 = performance.now();
  const errors = engine.dragPoint(ui.dragging, p.x, p.y);
  draw();
  ui.lastUpdateMs = performance.now() - t0;
  ui.message = errors > 0 ? engine.lastError() : "";
  status();
});

function endDrag() {
  if (ui.dragging < 0) return;
  ui.dragging = -1;
  engine.endDrag();
  refresh();
}
canvas.addEventListener("mouseup", endDrag);
canvas.addEventListener("mouseleave", endDrag);

$("scheme").addEventListener("change", (e) => { engine.setScheme(e.target.value); refresh(); });
$("closed").addEventListener("change", (e) => { engine.setClosed(e.target.checked); refresh(); });
$("comb").addEventListener("change", (e) => { ui.comb = e.target.checked; draw(); });
$("shape").addEventListener("input", (e) => {
  if (ui.selected < 0) return;
  engine.dragShape(ui.selected, Number(e.target.value));
  refresh();
});
$("shape").addEventListener("change", () => { engine.endDrag(); });
$("corner").addEventListener("click", () => {
  if (ui.selected < 0) return;
  engine.toggleCorner(ui.selected);
  refresh();
});
function deleteSelected() {
  if (ui.selected < 0) return;
  engine.deletePoint(ui.selected);
  ui.selected = Math.min(ui.selected, engine.pointCount() - 1);
  refresh();
}
$("delete").addEventListener("click", deleteSelected);
$("undo").addEventListener("click", () => { engine.undo(); refresh(); });
$("redo").addEventListener("click", () => { engine.redo(); refresh(); });
$("clear").addEventListener("click", () => {
  engine.reset(engine.scheme());
  ui.selected = -1;
  refresh();
});
$("export").addEventListener("click", () => {
  const blob = new Blob([engine.exportSvg(W, H, false)], { type: "image/svg+xml" });
  const a = document.createElement("a");
  a.href = URL.createObjectURL(blob);
  a.download = "kappa-path.svg";
  a.click();
  URL.revokeObjectURL(a.href);
});

document.addEventListener("keydown", (e) => {
  if (e.target instanceof HTMLInputElement || e.target instanceof HTMLSelectElement) return;
  const mod = e.ctrlKey || e.metaKey;
  if (mod && e.key.toLowerCase() === "z") {
    if (e.shiftKey) engine.redo(); else engine.undo();
    refresh();
    e.preventDefault();
  } else if (mod && e.key.toLowerCase() === "y") {
    engine.redo();
    refresh();
    e.preventDefault();
  } else if (e.key === "Delete" || e.key === "Backspace") {
    deleteSelected();
  } else if (e.key === "c" && ui.selected >= 0) {
    engine.toggleCorner(ui.selected);
    refresh();
  }
});

// Summary statistics of per-update times (ms).
function stats(times, total) {
  const sorted = Float64Array.from(times).sort();
  const at = (q) => sorted[Math.min(sorted.length - 1, Math.floor(q * sorted.length))];
  return {
    updates: times.length,
    mean: total / times.length,
    p50: at(0.5),
    p95: at(0.95),
    max: sorted[sorted.length - 1],
  };
}

// The page's API (used by the browser test; handy from the console too).
window.kappa = {
  engine,
  reset(scheme = "ek-cubic") { engine.reset(scheme); ui.selected = -1; refresh(); },
  points: () => engine.points(),
  pieces: () => engine.pieces(),
  scheme: () => engine.scheme(),
  closed: () => engine.closed(),
  addPoint(x, y) { const e = engine.addPoint(x, y); refresh(); return e; },
  insertPoint(x, y) { const i = engine.insertPoint(x, y); refresh(); return i; },
  drag(i, x, y) { const e = engine.dragPoint(i, x, y); draw(); return e; },
  endDrag() { engine.endDrag(); refresh(); },
  movePoint(i, x, y) { const e = engine.movePoint(i, x, y); refresh(); return e; },
  deletePoint(i) { const e = engine.deletePoint(i); refresh(); return e; },
  setShape(i, a) { const e = engine.setShape(i, a); refresh(); return e; },
  toggleCorner(i) { const e = engine.toggleCorner(i); refresh(); return e; },
  setClosed(c) { const e = engine.setClosed(c); refresh(); return e; },
  setScheme(s) { const e = engine.setScheme(s); refresh(); return e; },
  undo() { const r = engine.undo(); refresh(); return r; },
  redo() { const r = engine.redo(); refresh(); return r; },
  select(i) { ui.selected = i; refresh(); },
  selected: () => ui.selected,
  setComb(on) { ui.comb = on; $("comb").checked = on; draw(); },
  evalCurve: (piece, seg, t) => engine.evalCurve(piece, seg, t),
  hit: (x, y) => engine.hit(x, y),
  pathElements: () => pathElements(engine.pathData()),
  exportSvg: (withPoints = true) => engine.exportSvg(W, H, withPoints),
  lastError: () => engine.lastError(),
  status: () => $("status").textContent,

  // Drag latency measured here in the page: `updates` drag updates of point `index`, back
  // and forth by up to `amplitude` px like a hand (one gesture). Each update is the move, the
  // warm re-solve, the path and the curvature comb written to wasm memory and viewed from
  // JavaScript; with `draw`, also the canvas drawing of path, comb and points, rasterized
  // (a pixel read back). Times in ms.
  benchDrag({ index = 30, updates = 1000, amplitude = 1.25, draw: withDraw = false } = {}) {
    const base = engine.points()[index];
    const scale = ui.combScale;
    const samples = combSamples(engine.pointCount());
    const times = new Float64Array(updates);
    let errors = 0, iterations = 0, sink = 0;
    const start = performance.now();
    for (let k = 1; k <= updates; k++) {
      const off = amplitude * ((k % 8) / 4 - 1);
      const t0 = performance.now();
      errors += engine.dragPoint(index, base.x + off, base.y - off);
      if (withDraw) {
        draw();
        // Reading a pixel back makes the canvas rasterize now, inside the measurement.
        ctx.getImageData(0, 0, 1, 1);
      } else {
        sink += engine.pathData().length;
        sink += engine.combData(scale, samples).length;
      }
      times[k - 1] = performance.now() - t0;
      iterations += engine.lastIterations();
    }
    const total = performance.now() - start;
    // The gesture is one undo step: undo it to leave the path as it was.
    engine.endDrag();
    engine.undo();
    refresh();
    return {
      ...stats(times, total),
      errors,
      iterations: iterations / updates,
      elements: sink > 0,
      crossOriginIsolated: window.crossOriginIsolated,
    };
  },
};

refresh();
document.body.dataset.ready = "1";
