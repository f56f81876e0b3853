// The path-tool page: a drawing of several contours on a zoomable canvas, edited with the
// pointer (mouse, pen or touch) and the keyboard in the conventions of a curvature pen, kept
// in localStorage and in files; and the `window.kappa` API that the browser test
// (web/test/) drives.

import init, { Editor } from "./pkg/kappa_web.js";
import { tracePath, pathElements } from "./path.js";
import { isGlif, parseGlif, writeGlif } from "./glif.js";

// Comb teeth per segment: 16 on short drawings, fewer on long ones (4 from 300 points on), so
// that the comb costs a drag update no more than about a millisecond.
const combSamples = (n) => Math.max(4, Math.min(16, Math.round(1200 / Math.max(n, 1))));
const COMB_LENGTH = 40;       // comb tooth at the reference |κ|, screen px (× the comb slider)
const COMB_PERCENTILE = 0.75; // the reference |κ|: this percentile of the samples
const COMB_CLIP = 3;          // teeth longer than this × COMB_LENGTH are cut
const PICK_RADIUS = 8;        // screen px around a point that grabs it (mouse and pen)
const TOUCH_RADIUS = 18;      // the same for a finger
const INSERT_RADIUS = 10;     // screen px around the curve where Shift+click inserts
const DOUBLE_CLICK_MS = 400;  // two presses on one point this close make a double click
const TAP_SLOP = 10;          // screen px a finger may move and still tap
const HANDLE_PX = 40;         // screen px from a point to the knob of its tangent handle
const HANDLE_COLOR = "#1a6fd6";
const MIN_SCALE = 0.02, MAX_SCALE = 64;
const WARNING_COLOR = "#e07000"; // a piece whose solve did not converge (its best curve)
const STORAGE_KEY = "kappa-path-tool/drawing";
const VIEW_KEY = "kappa-path-tool/view";
const SNAP_KEY = "kappa-path-tool/snap";

const $ = (id) => document.getElementById(id);
const canvas = $("canvas");
const stage = $("stage");
const ctx = canvas.getContext("2d");
let W = 0, H = 0, dpr = 1;

await init();
const engine = new Editor($("scheme").value);

// Screen = doc × scale + (tx, ty), in CSS px of the canvas.
const view = { scale: 1, tx: 0, ty: 0 };

const ui = {
  sel: null,          // the selected point {contour, index}
  drag: null,         // a point drag {id, contour, index}
  tdrag: null,        // a tangent handle drag {id, contour, index, incoming}
  glyph: null,        // the glyph file last opened (an XML document), kept when saving .glif
  pan: null,          // a pan drag {id, x, y, tx, ty}
  tap: null,          // a finger down away from the points {id, s, p}: a tap until it moves
  pinch: null,        // two fingers {d0, m0, scale0, tx0, ty0}
  pointers: new Map(),// pointers down: id → screen position
  space: false,       // Space held: drags pan
  hover: null,        // the pointer in doc coordinates (for the preview), or null
  lastDown: null,     // the last press on a point {time, contour, index}
  comb: $("comb").checked,
  snap: false,        // new, dragged and nudged points land on whole units
  combScale: 0,       // the comb's scale, kept during a drag
  lastUpdateMs: null,
  message: "",
};

const SHAPE_RANGE = { "kappa": null, "ek-cubic": [0.667, 0.99], "ek-trig": [0.5, 0.99] };

const toDoc = (s) => ({ x: (s.x - view.tx) / view.scale, y: (s.y - view.ty) / view.scale });
// A point in doc coordinates where a click, a drag or a nudge puts it: on whole units when
// snapping is on.
const placed = (p) => (ui.snap ? { x: Math.round(p.x), y: Math.round(p.y) } : p);
const toScreen = (p) => ({ x: p.x * view.scale + view.tx, y: p.y * view.scale + view.ty });
const totalPoints = () => {
  let n = 0;
  for (let k = 0; k < engine.contourCount(); k++) n += engine.pointCount(k);
  return n;
};
const combLength = () => COMB_LENGTH * 2 ** Number($("comb-scale").value) / view.scale;

function resize() {
  const r = stage.getBoundingClientRect();
  dpr = window.devicePixelRatio || 1;
  W = Math.max(1, r.width);
  H = Math.max(1, r.height);
  canvas.width = Math.round(W * dpr);
  canvas.height = Math.round(H * dpr);
  draw();
}

function draw() {
  ctx.setTransform(dpr, 0, 0, dpr, 0, 0);
  ctx.fillStyle = "#fff";
  ctx.fillRect(0, 0, W, H);
  const s = view.scale;
  ctx.setTransform(dpr * s, 0, 0, dpr * s, dpr * view.tx, dpr * view.ty);
  if (ui.comb) {
    const comb = engine.combData(combLength(), COMB_PERCENTILE, COMB_CLIP,
      combSamples(totalPoints()), ui.drag || ui.tdrag ? ui.combScale : 0);
    if (!ui.drag && !ui.tdrag) ui.combScale = engine.combScale();
    ctx.beginPath();
    tracePath(ctx, comb);
    ctx.strokeStyle = "rgba(40, 110, 220, 0.55)";
    ctx.lineWidth = 1 / s;
    ctx.stroke();
  }
  ctx.beginPath();
  tracePath(ctx, engine.pathData());
  ctx.strokeStyle = "#111";
  ctx.lineWidth = 2 / s;
  ctx.lineJoin = "round";
  ctx.stroke();
  // Pieces whose solve did not converge show their best curve, in a warning style.
  const contours = engine.contourCount();
  for (let k = 0; k < contours; k++) {
    engine.pieces(k).forEach((piece, j) => {
      if (!piece.failed) return;
      ctx.beginPath();
      tracePath(ctx, engine.piecePathData(k, j));
      ctx.strokeStyle = WARNING_COLOR;
      ctx.lineWidth = 2.5 / s;
      ctx.setLineDash([8 / s, 5 / s]);
      ctx.stroke();
      ctx.setLineDash([]);
    });
  }
  // The rubber band: what a click here would add to the contour being drawn.
  const active = engine.active();
  let closeHint = false;
  if (!ui.drag && !ui.pan && !ui.pinch && ui.hover && active >= 0 && !engine.closed(active)) {
    const near = engine.nearestPoint(ui.hover.x, ui.hover.y, PICK_RADIUS / s);
    closeHint = near && near.contour === active && near.index === 0 &&
      engine.pointCount(active) >= 3;
    if (!near) {
      ctx.beginPath();
      tracePath(ctx, engine.previewData(ui.hover.x, ui.hover.y));
      ctx.strokeStyle = "rgba(200, 20, 20, 0.7)";
      ctx.lineWidth = 1.25 / s;
      ctx.setLineDash([6 / s, 4 / s]);
      ctx.stroke();
      ctx.setLineDash([]);
    }
  }
  // Points, in screen pixels: the active contour's red, the others' grey. Each marker is a
  // small bitmap drawn once (see `marker`) and copied per point: rasterizing hundreds of
  // circles as one path costs a 300-point drawing about 5 ms a frame on a software canvas.
  ctx.setTransform(1, 0, 0, 1, 0, 0);
  for (let k = 0; k < contours; k++) {
    const on = k === active;
    engine.points(k).forEach((p) => {
      const m = marker(on, p.corner);
      const q = toScreen(p);
      ctx.drawImage(m.image, Math.round(q.x * dpr) - m.half, Math.round(q.y * dpr) - m.half);
    });
  }
  ctx.setTransform(dpr, 0, 0, dpr, 0, 0);
  const sel = ui.sel && ui.sel.contour < contours ? engine.points(ui.sel.contour)[ui.sel.index] : null;
  if (sel) {
    const q = toScreen(sel);
    ctx.beginPath();
    if (sel.corner) ctx.rect(q.x - 6, q.y - 6, 12, 12);
    else ctx.arc(q.x, q.y, 6, 0, 2 * Math.PI);
    ctx.fillStyle = "#d11";
    ctx.fill();
    ctx.strokeStyle = "#d11";
    ctx.stroke();
  }
  drawHandles();
  if (closeHint) {
    const q = toScreen(engine.points(active)[0]);
    ctx.beginPath();
    ctx.arc(q.x, q.y, 9, 0, 2 * Math.PI);
    ctx.strokeStyle = "#d11";
    ctx.stroke();
  }
}

// A point marker as a bitmap at the canvas's device pixels: a white disc (a square for a
// corner) with a red outline on the active contour, grey on the others, of radius 4.5 or 3.5
// CSS px and a 1.5 px line. `half` is the device pixel of the centre. Cached per look and
// device pixel ratio.
const markers = new Map();
function marker(active, corner) {
  const key = `${active}/${corner}/${dpr}`;
  let m = markers.get(key);
  if (m) return m;
  const r = active ? 4.5 : 3.5;
  const half = Math.ceil((r + 1.5) * dpr);
  const sprite = new OffscreenCanvas(2 * half + 1, 2 * half + 1);
  const g = sprite.getContext("2d");
  g.setTransform(dpr, 0, 0, dpr, half + 0.5, half + 0.5);
  g.beginPath();
  if (corner) g.rect(-r, -r, 2 * r, 2 * r);
  else g.arc(0, 0, r, 0, 2 * Math.PI);
  g.fillStyle = "#fff";
  g.fill();
  g.lineWidth = 1.5;
  g.strokeStyle = active ? "#d11" : "#888";
  g.stroke();
  m = { image: sprite.transferToImageBitmap(), half };
  markers.set(key, m);
  return m;
}

// ---- Tangent handles ----

const unit = (v) => {
  const l = Math.hypot(v[0], v[1]);
  return l > 0 && Number.isFinite(l) ? [v[0] / l, v[1] / l] : null;
};

// The direction of the curve at point i of contour k where no tangent is prescribed: from
// the solved curve at a smooth point, along the neighbouring segment at a corner (the side
// `incoming`), else between the neighbours.
function freeDirection(k, i, incoming) {
  const pts = engine.points(k);
  const n = pts.length, p = pts[i];
  const closed = engine.closed(k);
  const prev = i > 0 ? pts[i - 1] : closed ? pts[n - 1] : null;
  const next = i + 1 < n ? pts[i + 1] : closed ? pts[0] : null;
  if (p.corner) {
    if (incoming) return prev && unit([p.x - prev.x, p.y - prev.y]);
    return next && unit([next.x - p.x, next.y - p.y]);
  }
  const h = engine.hit(p.x, p.y);
  if (h && h.contour === k && h.distance < 1e-6 * (1 + Math.hypot(p.x, p.y))) {
    const dt = 1e-4;
    const a = engine.evalCurve(k, h.piece, h.segment, Math.max(0, h.t - dt));
    const b = engine.evalCurve(k, h.piece, h.segment, Math.min(1, h.t + dt));
    const d = a && b && unit([b.x - a.x, b.y - a.y]);
    if (d) return d;
  }
  const a = prev ?? p, b = next ?? p;
  return unit([b.x - a.x, b.y - a.y]);
}

// The handles of the selected point, in screen px: [{incoming, set, dir, at, knob}]. A smooth
// point has one (the direction the curve passes it, drawn through the point); a corner one
// per side that has a piece (its outgoing and its incoming tangent).
function handles() {
  const sel = selection();
  if (!sel) return [];
  const { contour: k, index: i } = sel;
  const pts = engine.points(k);
  const p = pts[i];
  const t = engine.tangents(k)[i];
  const closed = engine.closed(k);
  const sides = p.corner
    ? [[false, i + 1 < pts.length || closed], [true, i > 0 || closed]]
    : [[false, pts.length > 1]];
  const at = toScreen(p);
  const out = [];
  for (const [incoming, exists] of sides) {
    if (!exists) continue;
    const v = incoming ? t.in : t.out;
    const dir = (v && unit(v)) ?? freeDirection(k, i, incoming);
    if (!dir) continue;
    const sign = incoming ? -1 : 1;
    out.push({
      incoming, set: !!v, dir, at,
      knob: { x: at.x + sign * dir[0] * HANDLE_PX, y: at.y + sign * dir[1] * HANDLE_PX },
    });
  }
  return out;
}

function drawHandles() {
  for (const h of handles()) {
    ctx.beginPath();
    // A smooth point's handle runs through the point; a corner's from the point to one side.
    const smooth = !engine.points(ui.sel.contour)[ui.sel.index].corner;
    const from = smooth ? { x: 2 * h.at.x - h.knob.x, y: 2 * h.at.y - h.knob.y } : h.at;
    ctx.moveTo(from.x, from.y);
    ctx.lineTo(h.knob.x, h.knob.y);
    ctx.strokeStyle = HANDLE_COLOR;
    ctx.lineWidth = 1.25;
    ctx.setLineDash(h.set ? [] : [3, 3]);
    ctx.stroke();
    ctx.setLineDash([]);
    ctx.beginPath();
    ctx.arc(h.knob.x, h.knob.y, 4.5, 0, 2 * Math.PI);
    ctx.fillStyle = h.set ? HANDLE_COLOR : "#fff";
    ctx.fill();
    ctx.strokeStyle = HANDLE_COLOR;
    ctx.stroke();
  }
}

// The handle whose knob is within `radius` screen px of `s`, or null.
function pickHandle(s, radius) {
  let best = null, bestD = radius;
  for (const h of handles()) {
    const d = Math.hypot(h.knob.x - s.x, h.knob.y - s.y);
    if (d <= bestD) { best = h; bestD = d; }
  }
  return best;
}

// A handle drag update: the tangent points from the point to the pointer (from the pointer
// to the point on a corner's incoming side).
function dragHandle(s) {
  const { contour: k, index: i, incoming } = ui.tdrag;
  const p = engine.points(k)[i];
  const q = toDoc(s);
  const v = incoming ? [p.x - q.x, p.y - q.y] : [q.x - p.x, q.y - p.y];
  if (Math.hypot(v[0], v[1]) * view.scale < 1) return;
  const t0 = performance.now();
  engine.setActive(k);
  const errors = engine.dragTangent(i, v[0], v[1], incoming);
  draw();
  ui.lastUpdateMs = performance.now() - t0;
  ui.message = errors > 0 ? engine.lastError() : "";
  status();
}

// Frees the selected point's tangents (the curve's own direction again).
function clearTangent() {
  const sel = selection();
  if (!sel) return;
  engine.setActive(sel.contour);
  const t = engine.tangents(sel.contour)[sel.index];
  if (t.out) engine.clearTangent(sel.index, false);
  if (t.in) engine.clearTangent(sel.index, true);
  refresh();
}

// The selected corner becomes a smooth line-to-curve join (the curve side's tangent along
// the line, kept along it when the line's ends move).
function smoothJoin() {
  const sel = selection();
  if (!sel) return;
  engine.setActive(sel.contour);
  if (engine.smoothJoin(sel.index) < 0) {
    refresh();
    ui.message = "a smooth join needs a corner with a straight segment (two corners in a row) " +
      "on one side and a curve on the other";
    status();
    return;
  }
  refresh();
}

function status() {
  const contours = engine.contourCount();
  const k = engine.active();
  let text = `${contours} contour${contours === 1 ? "" : "s"} · ${engine.scheme()}`;
  if (k >= 0) {
    const n = engine.pointCount(k);
    const pieces = engine.pieces(k).length;
    text += ` · contour ${k + 1}: ${n} point${n === 1 ? "" : "s"}, ${pieces} piece` +
      `${pieces === 1 ? "" : "s"}, ${engine.closed(k) ? "closed" : "open"}`;
  }
  text += ` · zoom ${Math.round(view.scale * 100)}%`;
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

// The selected point, if it still exists (an undo may have taken it).
function selection() {
  const s = ui.sel;
  if (!s || s.contour >= engine.contourCount() || s.index >= engine.pointCount(s.contour)) {
    ui.sel = null;
    return null;
  }
  return s;
}

function syncControls() {
  const sel = selection();
  const scheme = engine.scheme();
  $("scheme").value = scheme;
  const active = engine.active();
  $("closed").checked = active >= 0 && engine.closed(active);
  $("closed").disabled = active < 0;
  const range = SHAPE_RANGE[scheme];
  const slider = $("shape");
  const point = sel ? engine.points(sel.contour)[sel.index] : null;
  slider.disabled = !range || !point;
  if (range) {
    slider.min = range[0];
    slider.max = range[1];
  }
  if (point && range) slider.value = point.shape;
  $("shape-value").textContent = point && range ? point.shape.toFixed(3) : "";
  $("corner").disabled = !point;
  $("free-tangent").disabled = !point;
  $("join").disabled = !point || !point.corner;
  $("delete").disabled = !point;
  $("delete-contour").disabled = active < 0;
  $("new-contour").disabled = active < 0;
  $("undo").disabled = !engine.canUndo();
  $("redo").disabled = !engine.canRedo();
}

let saveTimer = 0;
function autosave() {
  clearTimeout(saveTimer);
  saveTimer = setTimeout(saveNow, 250);
}
function saveNow() {
  clearTimeout(saveTimer);
  try {
    localStorage.setItem(STORAGE_KEY, engine.save());
    localStorage.setItem(VIEW_KEY, JSON.stringify(view));
  } catch (e) {
    ui.message = `not saved in this browser: ${e.message}`;
  }
}

// After an edit that is not a drag update: errors, controls, drawing, status, autosave.
function refresh({ keepMessage = false } = {}) {
  if (!keepMessage) ui.message = engine.lastError();
  syncControls();
  draw();
  status();
  autosave();
}

// Makes contour k active with point i selected.
function select(k, i) {
  engine.setActive(k);
  ui.sel = k >= 0 && i >= 0 ? { contour: k, index: i } : null;
}

function screenPos(e) {
  const r = canvas.getBoundingClientRect();
  return { x: e.clientX - r.left, y: e.clientY - r.top };
}

function zoomAbout(s, factor) {
  const scale = Math.min(MAX_SCALE, Math.max(MIN_SCALE, view.scale * factor));
  const q = toDoc(s);
  view.scale = scale;
  view.tx = s.x - q.x * scale;
  view.ty = s.y - q.y * scale;
  draw();
  status();
  autosave();
}

// Fits the drawing in the window (the identity view without points).
function fit() {
  const b = engine.bounds();
  if (!b) {
    Object.assign(view, { scale: 1, tx: 0, ty: 0 });
  } else {
    const margin = Math.min(60, 0.1 * Math.min(W, H));
    const bw = Math.max(b.x1 - b.x0, 1e-9), bh = Math.max(b.y1 - b.y0, 1e-9);
    let scale = Math.min((W - 2 * margin) / bw, (H - 2 * margin) / bh);
    if (!Number.isFinite(scale) || scale <= 0) scale = 1;
    view.scale = Math.min(MAX_SCALE, Math.max(MIN_SCALE, scale));
    view.tx = W / 2 - view.scale * (b.x0 + b.x1) / 2;
    view.ty = H / 2 - view.scale * (b.y0 + b.y1) / 2;
  }
  draw();
  status();
  autosave();
}

// ---- Pointer: points, pan, pinch ----

function endDrag() {
  if (!ui.drag && !ui.tdrag) return;
  ui.drag = null;
  ui.tdrag = null;
  engine.endDrag();
  refresh();
}

function startPinch() {
  const [a, b] = [...ui.pointers.values()];
  ui.pinch = {
    d0: Math.max(1, Math.hypot(b.x - a.x, b.y - a.y)),
    m0: { x: (a.x + b.x) / 2, y: (a.y + b.y) / 2 },
    scale0: view.scale, tx0: view.tx, ty0: view.ty,
  };
}

function applyPinch() {
  const [a, b] = [...ui.pointers.values()];
  const p = ui.pinch;
  const d = Math.max(1, Math.hypot(b.x - a.x, b.y - a.y));
  const m = { x: (a.x + b.x) / 2, y: (a.y + b.y) / 2 };
  const scale = Math.min(MAX_SCALE, Math.max(MIN_SCALE, p.scale0 * d / p.d0));
  // The doc point under the first midpoint stays under the fingers.
  const q = { x: (p.m0.x - p.tx0) / p.scale0, y: (p.m0.y - p.ty0) / p.scale0 };
  view.scale = scale;
  view.tx = m.x - q.x * scale;
  view.ty = m.y - q.y * scale;
  draw();
  status();
}

canvas.addEventListener("contextmenu", (e) => e.preventDefault());

canvas.addEventListener("pointerdown", (e) => {
  // Only the primary button adds or picks; the middle one pans; the right one does nothing.
  if (e.pointerType === "mouse" && e.button !== 0 && e.button !== 1) return;
  e.preventDefault();
  canvas.setPointerCapture(e.pointerId);
  const s = screenPos(e);
  ui.pointers.set(e.pointerId, s);
  if (ui.pointers.size === 2) {
    // A second finger: the gesture becomes a pinch (zoom and pan); a point drag ends.
    endDrag();
    ui.pan = null;
    ui.tap = null;
    startPinch();
    return;
  }
  if (ui.pointers.size > 2) return;
  if (e.button === 1 || ui.space) {
    ui.pan = { id: e.pointerId, x: s.x, y: s.y, tx: view.tx, ty: view.ty };
    canvas.classList.add("pan");
    return;
  }
  const p = toDoc(s);
  const pick = e.pointerType === "touch" ? TOUCH_RADIUS : PICK_RADIUS;
  const handle = pickHandle(s, pick);
  if (handle) {
    ui.lastDown = null;
    ui.tdrag = { id: e.pointerId, ...ui.sel, incoming: handle.incoming };
    return;
  }
  const radius = pick / view.scale;
  const near = engine.nearestPoint(p.x, p.y, radius);
  const now = performance.now();
  if (near) {
    const { contour: k, index: i } = near;
    const last = ui.lastDown;
    const again = last && now - last.time < DOUBLE_CLICK_MS && last.contour === k &&
      last.index === i;
    const drawing = engine.active() === k && !engine.closed(k);
    select(k, i);
    if (e.altKey || again) {
      // Alt+click or a double click: corner on or off.
      ui.lastDown = null;
      engine.toggleCorner(i);
      refresh();
      return;
    }
    ui.lastDown = { time: now, contour: k, index: i };
    if (drawing && i === 0 && engine.pointCount(k) >= 3) {
      // The first point of the contour being drawn: close it.
      engine.setClosed(true);
    }
    ui.drag = { id: e.pointerId, contour: k, index: i };
    refresh();
    return;
  }
  ui.lastDown = null;
  if (e.shiftKey) {
    const hit = engine.hit(p.x, p.y);
    if (hit && hit.distance * view.scale <= INSERT_RADIUS) {
      const i = engine.insertPoint(p.x, p.y);
      if (i >= 0) {
        select(engine.active(), i);
        ui.drag = { id: e.pointerId, contour: engine.active(), index: i };
        refresh();
        return;
      }
    }
  }
  if (e.pointerType === "touch") {
    // A finger adds its point when it lifts without moving (a tap); a drag pans, and a
    // second finger makes a pinch.
    ui.tap = { id: e.pointerId, s, p };
    return;
  }
  const at = addPoint(placed(p));
  ui.drag = { id: e.pointerId, ...at };
  refresh();
});

// A new point at `p`: at the end of the open contour being drawn, or the start of a new one;
// selected. Returns {contour, index}.
function addPoint(p) {
  const active = engine.active();
  let k;
  if (active >= 0 && !engine.closed(active)) {
    k = active;
    engine.addPoint(p.x, p.y);
  } else {
    k = engine.startContour(p.x, p.y);
  }
  const i = engine.pointCount(k) - 1;
  select(k, i);
  return { contour: k, index: i };
}

canvas.addEventListener("pointermove", (e) => {
  const s = screenPos(e);
  if (ui.pointers.has(e.pointerId)) ui.pointers.set(e.pointerId, s);
  if (ui.pinch) {
    if (ui.pointers.size >= 2) applyPinch();
    return;
  }
  if (ui.tap && ui.tap.id === e.pointerId &&
      Math.hypot(s.x - ui.tap.s.x, s.y - ui.tap.s.y) > TAP_SLOP) {
    ui.pan = { id: e.pointerId, x: ui.tap.s.x, y: ui.tap.s.y, tx: view.tx, ty: view.ty };
    ui.tap = null;
  }
  if (ui.pan && ui.pan.id === e.pointerId) {
    view.tx = ui.pan.tx + s.x - ui.pan.x;
    view.ty = ui.pan.ty + s.y - ui.pan.y;
    draw();
    return;
  }
  if (ui.tdrag && ui.tdrag.id === e.pointerId) {
    dragHandle(s);
    return;
  }
  const p = toDoc(s);
  if (ui.drag && ui.drag.id === e.pointerId) {
    const t0 = performance.now();
    engine.setActive(ui.drag.contour);
    const q = placed(p);
    const errors = engine.dragPoint(ui.drag.index, q.x, q.y);
    draw();
    ui.lastUpdateMs = performance.now() - t0;
    ui.message = errors > 0 ? engine.lastError() : "";
    status();
    return;
  }
  if (e.pointerType === "touch") return;
  ui.hover = placed(p);
  const near = engine.nearestPoint(p.x, p.y, PICK_RADIUS / view.scale);
  const active = engine.active();
  canvas.classList.toggle("move", !!near && !ui.space);
  canvas.classList.toggle("close", !!near && near.contour === active && near.index === 0 &&
    !engine.closed(active) && engine.pointCount(active) >= 3);
  draw();
});

function pointerEnd(e) {
  ui.pointers.delete(e.pointerId);
  if (canvas.hasPointerCapture(e.pointerId)) canvas.releasePointerCapture(e.pointerId);
  if (ui.pinch) {
    if (ui.pointers.size < 2) {
      ui.pinch = null;
      autosave();
    }
    return;
  }
  if (ui.pan && ui.pan.id === e.pointerId) {
    ui.pan = null;
    if (!ui.space) canvas.classList.remove("pan");
    autosave();
    return;
  }
  if (ui.drag && ui.drag.id === e.pointerId) endDrag();
  if (ui.tdrag && ui.tdrag.id === e.pointerId) endDrag();
  if (ui.tap && ui.tap.id === e.pointerId) {
    const { p } = ui.tap;
    ui.tap = null;
    if (e.type === "pointerup") {
      addPoint(placed(p));
      refresh();
    }
  }
}
canvas.addEventListener("pointerup", pointerEnd);
canvas.addEventListener("pointercancel", pointerEnd);
canvas.addEventListener("pointerleave", () => {
  if (ui.hover && !ui.drag) {
    ui.hover = null;
    draw();
  }
});

canvas.addEventListener("wheel", (e) => {
  e.preventDefault();
  const unit = e.deltaMode === 1 ? 16 : e.deltaMode === 2 ? H : 1;
  zoomAbout(screenPos(e), Math.exp(-e.deltaY * unit * 0.0015));
}, { passive: false });

// ---- Controls ----

// A control gives the focus back once used, so Space and the arrows go to the drawing (the
// shortcuts work with the focus anywhere but in a text field in any case).
for (const el of document.querySelectorAll("header button, header select, header input")) {
  el.addEventListener("change", () => el.blur());
  if (el instanceof HTMLButtonElement) el.addEventListener("click", () => el.blur());
}

$("scheme").addEventListener("change", (e) => { engine.setScheme(e.target.value); refresh(); });
$("closed").addEventListener("change", (e) => {
  if (engine.active() < 0) return;
  engine.setClosed(e.target.checked);
  refresh();
});
$("comb").addEventListener("change", (e) => { ui.comb = e.target.checked; draw(); });
function setSnap(on) {
  ui.snap = on;
  $("snap").checked = on;
  localStorage.setItem(SNAP_KEY, on ? "1" : "0");
}
$("snap").addEventListener("change", (e) => setSnap(e.target.checked));
$("comb-scale").addEventListener("input", () => draw());
$("shape").addEventListener("input", (e) => {
  const sel = selection();
  if (!sel) return;
  engine.setActive(sel.contour);
  engine.dragShape(sel.index, Number(e.target.value));
  refresh();
});
$("shape").addEventListener("change", () => { engine.endDrag(); refresh(); });

function toggleCorner() {
  const sel = selection();
  if (!sel) return;
  engine.setActive(sel.contour);
  engine.toggleCorner(sel.index);
  refresh();
}
$("corner").addEventListener("click", toggleCorner);
$("free-tangent").addEventListener("click", clearTangent);
$("join").addEventListener("click", smoothJoin);

function deleteSelected() {
  const sel = selection();
  if (!sel) return;
  if (engine.pointCount(sel.contour) <= 1) {
    // The last point: the contour goes.
    engine.deleteContour(sel.contour);
    ui.sel = null;
  } else {
    engine.setActive(sel.contour);
    engine.deletePoint(sel.index);
    ui.sel = { contour: sel.contour, index: Math.max(0, sel.index - 1) };
  }
  refresh();
}
$("delete").addEventListener("click", deleteSelected);

// Escape: the contour being drawn ends (the next click starts a new one) and nothing is
// selected.
function escape() {
  select(-1, -1);
  refresh({ keepMessage: true });
}
$("new-contour").addEventListener("click", escape);
$("delete-contour").addEventListener("click", () => {
  const k = engine.active();
  if (k < 0) return;
  engine.deleteContour(k);
  ui.sel = null;
  refresh();
});

function undo() { endDrag(); engine.undo(); refresh(); }
function redo() { endDrag(); engine.redo(); refresh(); }
$("undo").addEventListener("click", undo);
$("redo").addEventListener("click", redo);
$("fit").addEventListener("click", fit);
$("clear").addEventListener("click", () => {
  if (!engine.clear()) return;
  ui.sel = null;
  refresh();
  ui.message = "cleared: Undo brings the drawing back";
  status();
});

function download(text, name, type) {
  const blob = new Blob([text], { type });
  const a = document.createElement("a");
  a.href = URL.createObjectURL(blob);
  a.download = name;
  a.click();
  setTimeout(() => URL.revokeObjectURL(a.href), 0);
}

// The SVG export: the drawing in its own coordinates, on a page that holds it.
function svgText() {
  const b = engine.bounds();
  const w = b ? Math.ceil(Math.max(b.x1, 0) + 20) : Math.round(W);
  const h = b ? Math.ceil(Math.max(b.y1, 0) + 20) : Math.round(H);
  return engine.exportSvg(w, h, true);
}
function save() { download(engine.save(), "drawing.kappa.json", "application/json"); }

// The drawing as a UFO glyph (glif.js): the opened glyph's name, advance and lib kept.
function glifText() {
  const outlines = [];
  for (let k = 0; k < engine.contourCount(); k++) {
    outlines.push(pathElements(engine.contourPathData(k)));
  }
  const { contours } = JSON.parse(engine.save());
  return writeGlif({ outlines, docs: contours, glyph: ui.glyph });
}
function glifName() {
  return ui.glyph?.documentElement.getAttribute("name") || "drawing";
}
$("export-glif").addEventListener("click",
  () => download(glifText(), `${glifName()}.glif`, "application/xml"));
$("save").addEventListener("click", save);
$("export").addEventListener("click", () => download(svgText(), "drawing.svg", "image/svg+xml"));

// Opens a drawing from text (a file, a drop or a paste): an undoable step.
function openText(text) {
  endDrag();
  let glyph = null;
  if (isGlif(text)) {
    try {
      const scheme = engine.scheme();
      const parsed = parseGlif(text, scheme, Editor.neutralShape(scheme));
      glyph = parsed.glyph;
      text = JSON.stringify({ contours: parsed.docs });
    } catch (e) {
      ui.message = `not opened: ${e.message}`;
      status();
      return false;
    }
  }
  const r = engine.open(text, true);
  if (r < 0) {
    ui.message = `not opened: ${engine.lastError()}`;
    status();
    return false;
  }
  ui.sel = null;
  ui.glyph = glyph;
  refresh();
  fit();
  return true;
}
$("open").addEventListener("change", async (e) => {
  const file = e.target.files[0];
  e.target.value = "";
  if (file) openText(await file.text());
});
window.addEventListener("dragover", (e) => e.preventDefault());
window.addEventListener("drop", async (e) => {
  e.preventDefault();
  const file = e.dataTransfer.files[0];
  if (file) openText(await file.text());
  else {
    const text = e.dataTransfer.getData("text/plain");
    if (text) openText(text);
  }
});

const isTextField = (t) => t instanceof HTMLTextAreaElement || !!t?.isContentEditable ||
  (t instanceof HTMLInputElement &&
    !["checkbox", "radio", "range", "button", "submit", "reset", "file", "color"].includes(t.type));

document.addEventListener("paste", (e) => {
  if (isTextField(e.target)) return;
  const text = e.clipboardData?.getData("text/plain") ?? "";
  const t = text.trim();
  if (t.startsWith("{") || t.startsWith("[") || t.startsWith("<")) {
    e.preventDefault();
    openText(text);
  }
});

// ---- Keyboard: wherever the focus is, except in a text field ----

function nudge(dx, dy) {
  const sel = selection();
  if (!sel) return false;
  const p = engine.points(sel.contour)[sel.index];
  engine.setActive(sel.contour);
  const q = placed({ x: p.x + dx, y: p.y + dy });
  engine.movePoint(sel.index, q.x, q.y);
  refresh();
  return true;
}

const ARROWS = { ArrowLeft: [-1, 0], ArrowRight: [1, 0], ArrowUp: [0, -1], ArrowDown: [0, 1] };

document.addEventListener("keydown", (e) => {
  if (isTextField(e.target)) return;
  const mod = e.ctrlKey || e.metaKey;
  const key = e.key.length === 1 ? e.key.toLowerCase() : e.key;
  let handled = true;
  if (mod && !e.altKey && key === "z") {
    if (e.shiftKey) redo(); else undo();
  } else if (mod && !e.altKey && key === "y") {
    redo();
  } else if (mod && !e.altKey && key === "s") {
    save();
  } else if (mod && !e.altKey && key === "0") {
    fit();
  } else if (mod || e.altKey) {
    // Copy, paste and every other browser shortcut pass through.
    handled = false;
  } else if (key === "Escape") {
    if (ui.drag) handled = false; else escape();
  } else if (key === "Delete" || key === "Backspace") {
    deleteSelected();
  } else if (key in ARROWS) {
    const step = e.shiftKey ? 10 : 1;
    handled = nudge(ARROWS[key][0] * step, ARROWS[key][1] * step);
  } else if (key === "c") {
    toggleCorner();
  } else if (key === "t") {
    clearTangent();
  } else if (key === "j") {
    smoothJoin();
  } else if (key === "f") {
    fit();
  } else if (key === "g") {
    setSnap(!ui.snap);
  } else if (key === " ") {
    ui.space = true;
    canvas.classList.add("pan");
  } else {
    handled = false;
  }
  if (handled) e.preventDefault();
});
document.addEventListener("keyup", (e) => {
  if (e.key === " ") {
    ui.space = false;
    if (!ui.pan) canvas.classList.remove("pan");
  }
});
window.addEventListener("blur", () => { ui.space = false; canvas.classList.remove("pan"); });
window.addEventListener("pagehide", saveNow);

// ---- The page's API (used by the browser test; handy from the console too) ----

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

// The contour an API call means by default: the active one, else the first.
const current = () => Math.max(0, engine.active());
const edit = (f) => { const r = f(); refresh(); return r; };

window.kappa = {
  engine,
  reset(scheme = "ek-cubic") {
    engine.reset(scheme);
    ui.sel = null;
    Object.assign(view, { scale: 1, tx: 0, ty: 0 });
    refresh();
  },
  contours: () => engine.contourCount(),
  active: () => engine.active(),
  setActive(k) { select(k, -1); refresh({ keepMessage: true }); },
  points: (k = current()) => engine.points(k),
  pieces: (k = current()) => engine.pieces(k),
  scheme: () => engine.scheme(),
  closed: (k = current()) => engine.closed(k),
  addPoint: (x, y) => edit(() => engine.addPoint(x, y)),
  startContour: (x, y) => edit(() => engine.startContour(x, y)),
  insertPoint: (x, y) => edit(() => engine.insertPoint(x, y)),
  drag(i, x, y) { const e = engine.dragPoint(i, x, y); draw(); return e; },
  endDrag() { engine.endDrag(); refresh(); },
  movePoint: (i, x, y) => edit(() => engine.movePoint(i, x, y)),
  deletePoint: (i) => edit(() => engine.deletePoint(i)),
  setShape: (i, a) => edit(() => engine.setShape(i, a)),
  toggleCorner: (i) => edit(() => engine.toggleCorner(i)),
  setClosed: (c) => edit(() => engine.setClosed(c)),
  tangents: (k = current()) => engine.tangents(k),
  setTangent: (i, x, y, incoming = false) => edit(() => engine.setTangent(i, x, y, incoming)),
  clearTangent: (i, incoming = false) => edit(() => engine.clearTangent(i, incoming)),
  smoothJoin: (i) => edit(() => engine.smoothJoin(i)),
  // The selected point's tangent handles in screen px (for a pointer to drag).
  handles: () => handles().map((h) => ({ incoming: h.incoming, set: h.set, knob: h.knob })),
  canUndo: () => engine.canUndo(),
  exportGlif: () => glifText(),
  setScheme: (s) => edit(() => engine.setScheme(s)),
  deleteContour: (k) => edit(() => engine.deleteContour(k)),
  clear: () => edit(() => engine.clear()),
  undo: () => edit(() => engine.undo()),
  redo: () => edit(() => engine.redo()),
  select(k, i) { select(k, i); refresh({ keepMessage: true }); },
  selected: () => (ui.sel ? ui.sel.index : -1),
  selection: () => ui.sel,
  setComb(on) { ui.comb = on; $("comb").checked = on; draw(); },
  setSnap,
  evalCurve: (k, piece, seg, t) => engine.evalCurve(k, piece, seg, t),
  hit: (x, y) => engine.hit(x, y),
  pathElements: () => pathElements(engine.pathData()),
  // The comb's teeth as drawn ([base, tip] pairs in doc coordinates) and its scale.
  comb() {
    const els = pathElements(engine.combData(combLength(), COMB_PERCENTILE, COMB_CLIP,
      combSamples(totalPoints())));
    const teeth = [];
    for (let i = 0; i + 1 < els.length; i++) {
      const [a, b] = [els[i], els[i + 1]];
      // A tooth: a move to the base then a line to the tip, the next element a move again.
      if (a[0] === 0 && b[0] === 1 && (i + 2 >= els.length || els[i + 2][0] === 0)) {
        teeth.push([{ x: a[1], y: a[2] }, { x: b[1], y: b[2] }]);
      }
    }
    return { teeth, scale: engine.combScale(), length: combLength() };
  },
  exportSvg: () => svgText(),
  save: () => engine.save(),
  open: (text) => openText(text),
  lastError: () => engine.lastError(),
  status: () => $("status").textContent,
  view: () => ({ ...view, width: W, height: H }),
  setView(v) { Object.assign(view, v); draw(); status(); },
  fit,
  toScreen,
  saveNow,

  // Drag latency measured here in the page: `updates` drag updates of point `index` of the
  // active contour, back and forth by up to `amplitude` px like a hand (one gesture). Each
  // update is the move, the warm re-solve, the path and the curvature comb encoded and
  // copied out of the module as Float64Arrays; with `draw`, also the canvas drawing of path, comb
  // and points, rasterized (a pixel read back). Times in ms.
  benchDrag({ index = 30, updates = 1000, amplitude = 1.25, draw: withDraw = false } = {}) {
    if (engine.active() < 0) engine.setActive(0);
    const base = engine.points(engine.active())[index];
    const length = combLength();
    const samples = combSamples(totalPoints());
    draw();
    const scale = ui.combScale;
    const times = new Float64Array(updates);
    let errors = 0, iterations = 0, sink = 0;
    ui.drag = { id: -1, contour: engine.active(), index };
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
        sink += engine.combData(length, COMB_PERCENTILE, COMB_CLIP, samples, scale).length;
      }
      times[k - 1] = performance.now() - t0;
      iterations += engine.lastIterations();
    }
    const total = performance.now() - start;
    ui.drag = null;
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

// Start: the drawing and view kept in this browser, if any.
new ResizeObserver(resize).observe(stage);
resize();
setSnap(localStorage.getItem(SNAP_KEY) === "1");
const kept = localStorage.getItem(STORAGE_KEY);
if (kept) {
  if (engine.open(kept, false) < 0) localStorage.removeItem(STORAGE_KEY);
  try {
    const v = JSON.parse(localStorage.getItem(VIEW_KEY) ?? "null");
    if (v && [v.scale, v.tx, v.ty].every(Number.isFinite) && v.scale > 0) {
      Object.assign(view, { scale: v.scale, tx: v.tx, ty: v.ty });
    }
  } catch {
    // A view that does not parse is left at the default.
  }
}
refresh();
document.body.dataset.ready = "1";
