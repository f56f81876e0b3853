// Browser test of the path-tool page: headless Debian Chromium driven by Playwright.
//
// KAPPA_WEB_URL: the served page (web/test/run.sh starts the server and sets it).
// KAPPA_BLESS=1: write the golden screenshot (tests/golden/web-path-tool.png) and the README
// picture (docs/path-tool.png) instead of comparing.

import { test, before, after } from "node:test";
import assert from "node:assert/strict";
import fs from "node:fs";
import path from "node:path";
import { fileURLToPath } from "node:url";
import { chromium } from "playwright-core";
import { PNG } from "pngjs";

const HERE = path.dirname(fileURLToPath(import.meta.url));
const ROOT = path.resolve(HERE, "../..");
const GOLDEN = path.join(ROOT, "tests/golden/web-path-tool.png");
const README_PICTURE = path.join(ROOT, "docs/path-tool.png");
const OUT = path.join(ROOT, "target/web");
const URL = process.env.KAPPA_WEB_URL ?? "http://127.0.0.1:8000/";
const BLESS = !!process.env.KAPPA_BLESS;

// Screenshot comparison: a pixel differs when a channel is off by more than PIXEL_TOLERANCE
// (of 255); the picture matches when at most MAX_DIFFERING of its pixels differ (anti-aliasing
// may move by a pixel between Chromium builds; a wrong curve moves thousands).
const PIXEL_TOLERANCE = 32;
const MAX_DIFFERING = 0.002;

// Interpolation tolerances in px, on a 900×600 canvas: the solved curve (κ, εκ-cubic and
// εκ-trig, evaluated exactly in the engine) passes through its points to 1e-9 of the drawing
// size, ~6e-7 px; the drawn path is exact Bézier for κ and εκ-cubic (rounding only) and a
// cubic fit within 1e-4 of the piece size for εκ-trig (≤ 0.06 px here).
const CURVE_TOL = 1e-6;
const DRAWN_TOL = { "kappa": 1e-6, "ek-cubic": 1e-6, "ek-trig": 0.06 };
// Drag latency target per update, ms (issue 8), asserted on the median: the machine is
// shared, and a preempted update says nothing about the engine (mean and p95 are printed).
const LATENCY_TARGET_MS = 1;

const FLAGS = [
  "--headless", "--no-sandbox", "--disable-gpu", "--disable-quic", "--no-first-run",
  "--disable-background-networking", "--disable-component-update", "--disable-sync",
];

let browser, page;

before(async () => {
  // Playwright gives every launch a fresh temporary profile (user-data-dir).
  browser = await chromium.launch({ executablePath: "/usr/bin/chromium", headless: true, args: FLAGS });
  page = await browser.newPage({ viewport: { width: 1000, height: 720 }, deviceScaleFactor: 1 });
  const problems = [];
  page.on("pageerror", (e) => problems.push(String(e)));
  page.on("console", (m) => { if (m.type() === "error") problems.push(m.text()); });
  page.problems = problems;
  await page.goto(URL);
  await page.waitForSelector("body[data-ready='1']", { timeout: 15000 });
  fs.mkdirSync(OUT, { recursive: true });
});

after(async () => {
  await browser?.close();
});

// Canvas coordinates → page coordinates (inside the border).
async function canvasOrigin() {
  return page.evaluate(() => {
    const c = document.getElementById("canvas");
    const r = c.getBoundingClientRect();
    return { x: r.left + c.clientLeft, y: r.top + c.clientTop };
  });
}

// Checks in the page that every piece passes through its points: at the peak parameter of
// each segment and at the ends of open pieces, that |κ| peaks there (is no smaller at
// t_max ± 1e-3) and is continuous at the joints; and that the drawn path comes within
// `drawnTol` of every point. Returns the worst errors.
async function checkCurve(drawnTol) {
  const r = await page.evaluate(() => {
    const k = window.kappa;
    const pts = k.points();
    const pieces = k.pieces();
    let worst = 0, worstPeak = 0, worstJoint = 0, segments = 0;
    const bad = [];
    const d = (a, p) => Math.hypot(a.x - p.x, a.y - p.y);
    const collapsed = (pk, j) => {
      const [a, m, b] = [0, 0.5, 1].map((t) => k.evalCurve(pk, j, t));
      return d(a, m) === 0 && d(m, b) === 0;
    };
    pieces.forEach((piece, pk) => {
      if (piece.failed) bad.push(`piece ${pk} failed: ${k.lastError()}`);
      const q = piece.points.map((i) => pts[i]);
      const n = piece.tMax.length;
      segments += n;
      // Segment j peaks at point j (closed) or j + 1 (open); a two-point piece is a line.
      const peakPoint = (j) => piece.closed ? q[j] : q.length === 2 ? null : q[j + 1];
      let kmax = 0;
      for (let j = 0; j < n; j++) {
        kmax = Math.max(kmax, Math.abs(k.evalCurve(pk, j, piece.tMax[j]).curvature));
      }
      for (let j = 0; j < n; j++) {
        const t = piece.tMax[j];
        const at = k.evalCurve(pk, j, t);
        const p = peakPoint(j);
        if (p) worst = Math.max(worst, d(at, p));
        for (const s of [t - 1e-3, t + 1e-3]) {
          if (p && s > 0 && s < 1) {
            const excess = Math.abs(k.evalCurve(pk, j, s).curvature) - Math.abs(at.curvature);
            worstPeak = Math.max(worstPeak, excess / kmax);
          }
        }
        // |κ| is continuous at every joint; a segment collapsed onto its point (an
        // inflection through the point) is stepped over.
        const next = collapsed(pk, (j + 1) % n) ? (j + 2) % n : (j + 1) % n;
        if (!collapsed(pk, j) && (piece.closed || next > j)) {
          const a = Math.abs(k.evalCurve(pk, j, 1).curvature);
          const b = Math.abs(k.evalCurve(pk, next, 0).curvature);
          worstJoint = Math.max(worstJoint, Math.abs(a - b) / kmax);
        }
      }
      if (!piece.closed && n > 0) {
        worst = Math.max(worst, d(k.evalCurve(pk, 0, 0), q[0]));
        worst = Math.max(worst, d(k.evalCurve(pk, n - 1, 1), q[q.length - 1]));
      }
    });
    // The drawn path: nearest point of its elements to each input point (64 samples, then
    // golden-section refinement).
    const els = k.pathElements();
    const evalEl = (e, start, t) => {
      const u = 1 - t;
      switch (e[0]) {
        case 1: return { x: u * start.x + t * e[1], y: u * start.y + t * e[2] };
        case 2: return {
          x: u * u * start.x + 2 * u * t * e[1] + t * t * e[3],
          y: u * u * start.y + 2 * u * t * e[2] + t * t * e[4],
        };
        case 3: return {
          x: u * u * u * start.x + 3 * u * u * t * e[1] + 3 * u * t * t * e[3] + t * t * t * e[5],
          y: u * u * u * start.y + 3 * u * u * t * e[2] + 3 * u * t * t * e[4] + t * t * t * e[6],
        };
      }
      return null;
    };
    let drawn = 0;
    for (const p of pts) {
      let best = Infinity, cur = null, first = null;
      for (const e of els) {
        if (e[0] === 0) { cur = first = { x: e[1], y: e[2] }; continue; }
        if (e[0] === 4) { cur = first; continue; }
        let bi = 0, bd = Infinity;
        for (let i = 0; i <= 64; i++) {
          const dd = d(evalEl(e, cur, i / 64), p);
          if (dd < bd) { bd = dd; bi = i; }
        }
        let a = Math.max(0, bi - 1) / 64, b = Math.min(64, bi + 1) / 64;
        const g = (Math.sqrt(5) - 1) / 2;
        for (let it = 0; it < 80; it++) {
          const x1 = b - g * (b - a), x2 = a + g * (b - a);
          if (d(evalEl(e, cur, x1), p) < d(evalEl(e, cur, x2), p)) b = x2; else a = x1;
        }
        best = Math.min(best, bd, d(evalEl(e, cur, (a + b) / 2), p));
        const n = e.length;
        cur = { x: e[n - 2], y: e[n - 1] };
      }
      drawn = Math.max(drawn, best);
    }
    return { worst, worstPeak, worstJoint, drawn, segments, pieces: pieces.length, bad };
  });
  assert.deepEqual(r.bad, []);
  assert.ok(r.segments > 0, "no curve");
  assert.ok(r.worst <= CURVE_TOL, `curve misses a point by ${r.worst} px`);
  assert.ok(r.worstPeak <= 1e-9, `|κ| rises next to a peak by ${r.worstPeak} of max |κ|`);
  assert.ok(r.worstJoint <= 1e-6, `|κ| jumps at a joint by ${r.worstJoint} of max |κ|`);
  assert.ok(r.drawn <= drawnTol, `drawn path misses a point by ${r.drawn} px`);
  return r;
}

function comparePng(actualBuf, goldenPath) {
  const actual = PNG.sync.read(actualBuf);
  const expected = PNG.sync.read(fs.readFileSync(goldenPath));
  assert.equal(`${actual.width}x${actual.height}`, `${expected.width}x${expected.height}`,
    "screenshot size");
  const diff = new PNG({ width: actual.width, height: actual.height });
  let differing = 0;
  for (let i = 0; i < actual.data.length; i += 4) {
    let off = 0;
    for (let c = 0; c < 3; c++) off = Math.max(off, Math.abs(actual.data[i + c] - expected.data[i + c]));
    const bad = off > PIXEL_TOLERANCE;
    if (bad) differing++;
    diff.data[i] = bad ? 255 : expected.data[i] * 0.3 + 178;
    diff.data[i + 1] = bad ? 0 : expected.data[i + 1] * 0.3 + 178;
    diff.data[i + 2] = bad ? 0 : expected.data[i + 2] * 0.3 + 178;
    diff.data[i + 3] = 255;
  }
  const fraction = differing / (actual.width * actual.height);
  if (fraction > MAX_DIFFERING) {
    fs.writeFileSync(path.join(OUT, "web-path-tool.actual.png"), actualBuf);
    fs.writeFileSync(path.join(OUT, "web-path-tool.diff.png"), PNG.sync.write(diff));
  }
  return fraction;
}

// The six clicks, the drag and the shape of the screenshot.
const CLICKS = [[210, 160], [450, 90], [700, 170], [720, 420], [460, 520], [170, 400]];
const DRAG_FROM = 1, DRAG_TO = [480, 60];

test("clicks, a drag and a shape edit keep the curve through every point", async () => {
  const o = await canvasOrigin();
  await page.selectOption("#scheme", "ek-cubic");
  for (const [x, y] of CLICKS) await page.mouse.click(o.x + x, o.y + y);
  let pts = await page.evaluate(() => window.kappa.points());
  assert.equal(pts.length, 6);
  pts.forEach((p, i) => {
    assert.ok(p.x === CLICKS[i][0] && p.y === CLICKS[i][1],
      `point ${i} at ${p.x},${p.y}, clicked ${CLICKS[i]}`);
  });
  const open = await checkCurve(DRAWN_TOL["ek-cubic"]);
  assert.equal(open.segments, 4);

  // Drag point 1 with the mouse: the exported SVG changes (path and point).
  const svgBefore = await page.evaluate(() => window.kappa.exportSvg());
  const [fx, fy] = CLICKS[DRAG_FROM];
  await page.mouse.move(o.x + fx, o.y + fy);
  await page.mouse.down();
  await page.mouse.move(o.x + DRAG_TO[0], o.y + DRAG_TO[1], { steps: 12 });
  await page.mouse.up();
  pts = await page.evaluate(() => window.kappa.points());
  assert.deepEqual([pts[DRAG_FROM].x, pts[DRAG_FROM].y], DRAG_TO);
  const svgAfter = await page.evaluate(() => window.kappa.exportSvg());
  const pathData = (svg) => svg.match(/<path d="([^"]*)"/)[1];
  assert.notEqual(pathData(svgAfter), pathData(svgBefore), "exported path unchanged by the drag");
  assert.ok(svgAfter.includes(`cx="${pts[DRAG_FROM].x}" cy="${pts[DRAG_FROM].y}"`));
  assert.ok(!svgBefore.includes(`cx="${pts[DRAG_FROM].x}" cy="${pts[DRAG_FROM].y}"`));
  await checkCurve(DRAWN_TOL["ek-cubic"]);

  // Close the path, select point 3 by clicking it and sharpen it with the slider.
  await page.check("#closed");
  await page.mouse.click(o.x + CLICKS[3][0], o.y + CLICKS[3][1]);
  assert.equal(await page.evaluate(() => window.kappa.selected()), 3);
  await page.locator("#shape").fill("0.9");
  pts = await page.evaluate(() => window.kappa.points());
  assert.equal(pts[3].shape, 0.9);
  const closed = await checkCurve(DRAWN_TOL["ek-cubic"]);
  assert.equal(closed.segments, 6);
  assert.equal(closed.pieces, 1);

  // Undo and redo through the buttons: the shape edit goes and comes back.
  await page.click("#undo");
  assert.equal(await page.evaluate(() => window.kappa.points()[3].shape), 2 / 3);
  await page.click("#redo");
  assert.equal(await page.evaluate(() => window.kappa.points()[3].shape), 0.9);

  // Every scheme through the same points; a corner splits the closed path into one open piece.
  for (const scheme of ["kappa", "ek-trig", "ek-cubic"]) {
    await page.selectOption("#scheme", scheme);
    assert.equal(await page.evaluate(() => window.kappa.scheme()), scheme);
    const r = await checkCurve(DRAWN_TOL[scheme]);
    console.log(`${scheme}: worst point error ${r.worst.toExponential(2)} px on the curve, ` +
      `${r.drawn.toExponential(2)} px on the drawn path`);
  }
  // A corner at point 0 (selected by a click): the closed path becomes one open piece from
  // point 0 round to itself, 5 segments with a tangent break at point 0.
  await page.mouse.click(o.x + CLICKS[0][0], o.y + CLICKS[0][1]);
  await page.click("#corner");
  const cornered = await checkCurve(DRAWN_TOL["ek-cubic"]);
  assert.equal(cornered.pieces, 1);
  assert.equal(cornered.segments, 5);
  assert.deepEqual(await page.evaluate(() => window.kappa.pieces()[0].points), [0, 1, 2, 3, 4, 5, 0]);
  const tangents = await page.evaluate(() => {
    const k = window.kappa;
    const n = k.pieces()[0].tMax.length;
    const dir = (a, b) => { const l = Math.hypot(b.x - a.x, b.y - a.y); return [(b.x - a.x) / l, (b.y - a.y) / l]; };
    const end = dir(k.evalCurve(0, n - 1, 1 - 1e-6), k.evalCurve(0, n - 1, 1));
    const start = dir(k.evalCurve(0, 0, 0), k.evalCurve(0, 0, 1e-6));
    return end[0] * start[1] - end[1] * start[0];
  });
  assert.ok(Math.abs(tangents) > 0.05, `no tangent break at the corner (cross ${tangents})`);
  // Shift+click on the curve between points 4 and 5 inserts a point there (on the old
  // curve, nearest to the click); the Delete key removes it again.
  const before = await page.evaluate(() => window.kappa.points());
  const mid = await page.evaluate(([a, b]) => window.kappa.hit((a[0] + b[0]) / 2, (a[1] + b[1]) / 2),
    [CLICKS[4], CLICKS[5]]);
  const at = [Math.round(mid.x), Math.round(mid.y)];
  const onCurve = await page.evaluate(([x, y]) => window.kappa.hit(x, y), at);
  await page.keyboard.down("Shift");
  await page.mouse.click(o.x + at[0], o.y + at[1]);
  await page.keyboard.up("Shift");
  pts = await page.evaluate(() => window.kappa.points());
  assert.equal(pts.length, 7);
  assert.ok(Math.hypot(pts[5].x - onCurve.x, pts[5].y - onCurve.y) < 1e-9, "inserted off the curve");
  await checkCurve(DRAWN_TOL["ek-cubic"]);
  await page.keyboard.press("Delete");
  assert.deepEqual(await page.evaluate(() => window.kappa.points()), before);

  // The Export SVG button downloads what exportSvg(false) gives.
  const [download] = await Promise.all([page.waitForEvent("download"), page.click("#export")]);
  const exported = fs.readFileSync(await download.path(), "utf8");
  assert.equal(exported, await page.evaluate(() => window.kappa.exportSvg(false)));
  assert.ok(exported.startsWith("<svg") && exported.includes("<path d=\"M"));

  // Select point 3 again for the picture.
  await page.mouse.click(o.x + CLICKS[3][0], o.y + CLICKS[3][1]);
  assert.deepEqual(page.problems, []);

  // The screenshot: canvas compared with the golden; the whole page for the README.
  const shot = await page.locator("#canvas").screenshot();
  const full = await page.screenshot();
  fs.writeFileSync(path.join(OUT, "web-path-tool.png"), shot);
  fs.writeFileSync(path.join(OUT, "page.png"), full);
  if (BLESS || !fs.existsSync(GOLDEN)) {
    assert.ok(BLESS, `no golden ${GOLDEN}: run with KAPPA_BLESS=1`);
    fs.writeFileSync(GOLDEN, shot);
    fs.mkdirSync(path.dirname(README_PICTURE), { recursive: true });
    fs.writeFileSync(README_PICTURE, full);
    console.log(`blessed ${GOLDEN} and ${README_PICTURE}`);
  } else {
    const fraction = comparePng(shot, GOLDEN);
    console.log(`screenshot: ${(100 * fraction).toFixed(3)}% of pixels differ from the golden`);
    assert.ok(fraction <= MAX_DIFFERING,
      `${(100 * fraction).toFixed(3)}% of pixels differ (see ${OUT})`);
  }
});

// A 100-point closed star polygon, the native bench's (benches/solve.rs) scaled 2.5× onto
// the canvas.
function star(n) {
  return Array.from({ length: n }, (_, i) => {
    const th = (i / n) * 2 * Math.PI;
    const r = i % 2 === 0 ? 250 : 225;
    return [450 + r * Math.cos(th), 300 + r * Math.sin(th)];
  });
}

test("drag latency on a 100-point path", async () => {
  const rows = [];
  for (const scheme of ["kappa", "ek-cubic", "ek-trig"]) {
    await page.evaluate(([scheme, pts]) => {
      const k = window.kappa;
      k.reset(scheme);
      for (const [x, y] of pts) k.engine.addPoint(x, y);
      k.setClosed(true);
    }, [scheme, star(100)]);
    const r0 = await checkCurve(DRAWN_TOL[scheme]);
    assert.equal(r0.segments, 100);
    // 200 updates first, not measured: V8 runs new wasm code in its baseline tier until it is
    // hot, and the first scheme would pay for that.
    await page.evaluate(() => window.kappa.benchDrag({ index: 30, updates: 200 }));
    const engine = await page.evaluate(() => window.kappa.benchDrag({ index: 30, updates: 1000 }));
    const drawn = await page.evaluate(() =>
      window.kappa.benchDrag({ index: 30, updates: 1000, draw: true }));
    assert.equal(engine.errors, 0);
    assert.equal(drawn.errors, 0);
    // The bench leaves the path as it was, still right.
    await checkCurve(DRAWN_TOL[scheme]);
    rows.push({ scheme, engine, drawn });
    const ms = (r) => `mean ${r.mean.toFixed(3)} ms, p50 ${r.p50.toFixed(3)} ms, ` +
      `p95 ${r.p95.toFixed(3)} ms, max ${r.max.toFixed(3)} ms`;
    console.log(`drag update, 100 points, ${scheme}: ${ms(engine)} ` +
      `(${engine.iterations.toFixed(2)} iterations/update); with canvas drawing: ${ms(drawn)} ` +
      `[1000 updates each, crossOriginIsolated ${engine.crossOriginIsolated}]`);
  }
  fs.writeFileSync(path.join(OUT, "latency.json"), JSON.stringify(rows, null, 2));
  for (const { scheme, engine } of rows) {
    assert.ok(engine.p50 < LATENCY_TARGET_MS,
      `${scheme}: median drag update ${engine.p50} ms, target < ${LATENCY_TARGET_MS} ms`);
  }
  assert.deepEqual(page.problems, []);
});

// The first shapes a designer clicks: a wave whose middle point lies on the line through
// its neighbours, and a point-symmetric S (an inflection through an input point each).
const WAVE = [[100, 300], [250, 200], [400, 300], [550, 400], [700, 300]];
const S_CURVE = [[560, 150], [450, 95], [340, 150], [360, 250], [450, 300], [540, 350],
  [560, 450], [450, 505], [340, 450]];

test("a clicked wave and a symmetric S are drawn in every scheme", async () => {
  const o = await canvasOrigin();
  for (const scheme of ["kappa", "ek-cubic", "ek-trig"]) {
    for (const shape of [WAVE, S_CURVE]) {
      await page.evaluate((s) => window.kappa.reset(s), scheme);
      await page.selectOption("#scheme", scheme);
      for (const [x, y] of shape) await page.mouse.click(o.x + x, o.y + y);
      await page.mouse.move(o.x + 880, o.y + 580);
      const r = await checkCurve(DRAWN_TOL[scheme]);
      assert.equal(r.pieces, 1, `${scheme}`);
      assert.equal(await page.evaluate(() => window.kappa.lastError()), "", `${scheme}`);
      const drawn = await page.evaluate(() => window.kappa.pathElements().length);
      assert.ok(drawn >= shape.length - 3, `${scheme}: ${drawn} path elements`);
    }
  }
  fs.writeFileSync(path.join(OUT, "web-s-curve.png"), await page.locator("#canvas").screenshot());
});

test("a solve that does not converge shows its best curve, flagged, and undo brings it back", async () => {
  // The κ-curve of a dense sine (40 samples) does not converge.
  const pts = Array.from({ length: 40 }, (_, i) => [20 + 21 * i, 300 + 100 * Math.sin(0.3 * i)]);
  const r = await page.evaluate((pts) => {
    const k = window.kappa;
    k.reset("kappa");
    for (const [x, y] of pts) k.addPoint(x, y);
    return { error: k.lastError(), pieces: k.pieces(), elements: k.pathElements().length,
      status: k.status() };
  }, pts);
  assert.match(r.error, /did not converge/);
  assert.ok(r.pieces[0].failed && r.elements >= 30, `${r.elements} path elements`);
  assert.match(r.status, /did not converge/);
  fs.writeFileSync(path.join(OUT, "web-unconverged.png"), await page.locator("#canvas").screenshot());
  // An edit that solves (εκ-cubic), then undo into the failed state: curve and message return.
  const back = await page.evaluate(() => {
    const k = window.kappa;
    for (let i = 0; i < 40; i++) k.setShape(i, 0.8);
    k.setScheme("ek-cubic");
    const solved = k.lastError();
    k.undo();
    return { solved, error: k.lastError(), failed: k.pieces()[0].failed,
      elements: k.pathElements().length };
  });
  assert.equal(back.solved, "");
  assert.match(back.error, /did not converge/);
  assert.ok(back.failed && back.elements >= 30);
});

test("drag updates of a 300-point path that does not converge stay within a frame", async () => {
  // The κ-curve of a dense sine does not converge: each update's solve is capped (the
  // engine's DRAG_WORK), the flagged curve stays on screen, and mouse up finishes it.
  const r = await page.evaluate(() => {
    const k = window.kappa;
    // Drawn as εκ-trig (each click solves quickly), then switched to κ (one failing solve).
    k.reset("ek-trig");
    for (let i = 0; i < 300; i++) k.engine.addPoint(20 + 2.8 * i, 300 + 100 * Math.sin(0.21 * i));
    k.setScheme("kappa");
    k.setComb(false);
    const base = k.points()[150];
    const times = [], iterations = [];
    for (let u = 1; u <= 20; u++) {
      const t0 = performance.now();
      k.drag(150, base.x, base.y + 0.5 * u);
      times.push(performance.now() - t0);
      iterations.push(k.engine.lastIterations());
    }
    const shown = k.pathElements().length;
    const failed = k.pieces()[0].failed;
    const t0 = performance.now();
    k.endDrag();
    const end = performance.now() - t0;
    times.sort((a, b) => a - b);
    return { median: times[10], max: times[19], iterations, shown, failed, end };
  });
  console.log(`300-point failing drag: median ${r.median.toFixed(2)} ms, max ${r.max.toFixed(2)} ms ` +
    `per update (iterations ${Math.max(...r.iterations)}), end_drag ${r.end.toFixed(0)} ms`);
  assert.ok(r.failed && r.shown > 250, `${r.shown} path elements`);
  assert.ok(Math.max(...r.iterations) <= 50, `${r.iterations}`);
});
