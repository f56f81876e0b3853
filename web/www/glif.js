// UFO glyph files (.glif, format 2) for the path tool: a glyph whose <lib> holds the κ
// source under KAPPA_LIB_KEY (as `kappa font --out X.ufo` writes it) opens as that drawing,
// with every contour, corner and tangent; another glyph opens with its on-curve points as
// κ points (corners where the outline is not smooth). A drawing saves as a glyph with the
// engine's outline as cubic contours and its κ source in the lib.
//
// Glyphs are y-up, the page is y-down: y is negated on the way in and on the way out (points
// and tangents alike), so a glyph comes back with the coordinates it had.

import { MOVE_TO, LINE_TO, QUAD_TO, CURVE_TO, CLOSE } from "./path.js";

export const KAPPA_LIB_KEY = "org.kappa.contours";

// Whether `text` looks like a glyph file.
export const isGlif = (text) => /<glyph[\s>]/.test(text.slice(0, 4096));

const flipPoint = (p) => {
  const q = { ...p, y: -p.y };
  if (p.tangent) q.tangent = [p.tangent[0], -p.tangent[1]];
  if (p.tangent_in) q.tangent_in = [p.tangent_in[0], -p.tangent_in[1]];
  return q;
};

// The κ documents with y negated (tangents too) and without their saved solutions, which
// hold the solver's state in the other orientation (the engine solves afresh).
export function flipDocs(docs) {
  return docs.map((d) => {
    const { solution: _solution, ...rest } = d;
    return { ...rest, points: d.points.map(flipPoint) };
  });
}

function libValue(doc, key) {
  const dict = doc.querySelector("glyph > lib > dict");
  if (!dict) return null;
  for (const k of dict.children) {
    if (k.tagName === "key" && k.textContent === key) return k.nextElementSibling;
  }
  return null;
}

// Parses a glyph: {glyph (its XML document), docs (PathDocs in page coordinates), source:
// "kappa" when the lib held them, else "outline"}. Throws with a message a person can read.
export function parseGlif(text, scheme, neutralShape) {
  const glyph = new DOMParser().parseFromString(text, "application/xml");
  const bad = glyph.querySelector("parsererror");
  if (bad || glyph.documentElement.tagName !== "glyph") {
    throw new Error("not a glyph file (.glif): the XML does not parse to a <glyph>");
  }
  const value = libValue(glyph, KAPPA_LIB_KEY);
  if (value) {
    let docs;
    try {
      docs = JSON.parse(value.textContent);
    } catch (e) {
      throw new Error(`the glyph's ${KAPPA_LIB_KEY} is not JSON: ${e.message}`);
    }
    if (!Array.isArray(docs)) docs = docs.contours ?? [docs];
    return { glyph, docs: flipDocs(docs), source: "kappa" };
  }
  const docs = [];
  for (const contour of glyph.querySelectorAll("glyph > outline > contour")) {
    const pts = [...contour.querySelectorAll("point")];
    const open = pts.length > 0 && pts[0].getAttribute("type") === "move";
    const points = [];
    for (const p of pts) {
      const type = p.getAttribute("type");
      if (!type || type === "offcurve") continue;
      const x = Number(p.getAttribute("x")), y = Number(p.getAttribute("y"));
      if (!Number.isFinite(x) || !Number.isFinite(y)) {
        throw new Error(`a point of the glyph has no finite x and y (${p.outerHTML})`);
      }
      points.push({ x, y: -y, shape: neutralShape, corner: p.getAttribute("smooth") !== "yes" });
    }
    if (points.length === 0) continue;
    if (open) {
      points[0].corner = false;
      points[points.length - 1].corner = false;
    }
    docs.push({ points, closed: !open && points.length >= 3, scheme });
  }
  if (docs.length === 0) throw new Error("the glyph has no contours to edit");
  return { glyph, docs, source: "outline" };
}

const num = (v) => {
  const r = Math.round(v * 1000) / 1000;
  return String(Object.is(r, -0) ? 0 : r);
};

// A contour of the engine's outline (its path elements, page coordinates) as glif <point>
// lines: cubics (quadratics raised), lines, y negated, the start point last-typed when closed.
function contourXml(els, indent) {
  const segs = []; // {type, off: [[x, y]...], end: [x, y]}
  let start = null, closed = false, last = null;
  for (const el of els) {
    const [verb, ...c] = el;
    if (verb === MOVE_TO) {
      start = [c[0], c[1]];
      last = start;
    } else if (verb === LINE_TO) {
      segs.push({ type: "line", off: [], end: [c[0], c[1]] });
      last = [c[0], c[1]];
    } else if (verb === QUAD_TO) {
      const q0 = last, q1 = [c[0], c[1]], q2 = [c[2], c[3]];
      const c1 = [q0[0] + 2 / 3 * (q1[0] - q0[0]), q0[1] + 2 / 3 * (q1[1] - q0[1])];
      const c2 = [q2[0] + 2 / 3 * (q1[0] - q2[0]), q2[1] + 2 / 3 * (q1[1] - q2[1])];
      segs.push({ type: "curve", off: [c1, c2], end: q2 });
      last = q2;
    } else if (verb === CURVE_TO) {
      const off = [[c[0], c[1]], [c[2], c[3]]], end = [c[4], c[5]];
      // A straight cubic (a line piece) is a line.
      const chord = [end[0] - last[0], end[1] - last[1]];
      const len = Math.hypot(...chord);
      const onChord = len > 0 && off.every((q) => {
        const v = [q[0] - last[0], q[1] - last[1]];
        const along = (v[0] * chord[0] + v[1] * chord[1]) / len;
        return Math.abs(v[0] * chord[1] - v[1] * chord[0]) / len < 1e-9 * (1 + len) &&
          along >= 0 && along <= len;
      });
      segs.push(onChord ? { type: "line", off: [], end } : { type: "curve", off, end });
      last = [c[4], c[5]];
    } else if (verb === CLOSE) {
      closed = true;
    }
  }
  if (!start) return "";
  const same = (a, b) => Math.hypot(a[0] - b[0], a[1] - b[1]) < 1e-9;
  // The on-curve points in order, each with the off-curve points before it.
  let nodes;
  if (closed) {
    if (segs.length && same(segs[segs.length - 1].end, start)) {
      const end = segs.pop();
      nodes = [{ type: end.type, off: end.off, at: start }];
    } else {
      nodes = [{ type: "line", off: [], at: start }];
    }
    // The closing segment's off-curve points go at the end of the list (glif order).
    const first = nodes[0];
    nodes = [{ ...first, off: [] }, ...segs.map((s) => ({ type: s.type, off: s.off, at: s.end }))];
    nodes.trailing = first.off;
  } else {
    nodes = [{ type: "move", off: [], at: start },
      ...segs.map((s) => ({ type: s.type, off: s.off, at: s.end }))];
    nodes.trailing = [];
  }
  // Smooth: the directions in and out of an on-curve point agree.
  const n = nodes.length;
  const dirIn = (k) => {
    const node = k === 0 && closed ? { ...nodes[0], off: nodes.trailing } : nodes[k];
    const prev = k > 0 ? nodes[k - 1].at : closed ? nodes[n - 1].at : null;
    const from = node.off.length ? node.off[node.off.length - 1] : prev;
    return from && [node.at[0] - from[0], node.at[1] - from[1]];
  };
  const dirOut = (k) => {
    const next = k + 1 < n ? nodes[k + 1] : closed ? { ...nodes[0], off: nodes.trailing } : null;
    if (!next) return null;
    const to = next.off.length ? next.off[0] : next.at;
    return [to[0] - nodes[k].at[0], to[1] - nodes[k].at[1]];
  };
  const smooth = (k) => {
    const a = dirIn(k), b = dirOut(k);
    if (!a || !b) return false;
    const la = Math.hypot(...a), lb = Math.hypot(...b);
    if (la === 0 || lb === 0) return false;
    const cross = (a[0] * b[1] - a[1] * b[0]) / (la * lb);
    return Math.abs(cross) < 1e-6 && a[0] * b[0] + a[1] * b[1] > 0;
  };
  const pt = (p, attrs = "") => `${indent}  <point x="${num(p[0])}" y="${num(-p[1])}"${attrs}/>\n`;
  let out = `${indent}<contour>\n`;
  nodes.forEach((node, k) => {
    for (const o of node.off) out += pt(o);
    out += pt(node.at, ` type="${node.type}"${node.type !== "move" && smooth(k) ? ' smooth="yes"' : ""}`);
  });
  for (const o of nodes.trailing) out += pt(o);
  return `${out}${indent}</contour>\n`;
}

const escapeXml = (s) => s.replace(/&/g, "&amp;").replace(/</g, "&lt;").replace(/>/g, "&gt;")
  .replace(/"/g, "&quot;");

// The glyph file of a drawing: `outlines` (per contour, its engine path elements), `docs`
// (the drawing's PathDocs, page coordinates). With `glyph` (an opened glyph's XML document)
// its name, advance, unicodes, anchors and other lib keys are kept; else the glyph is
// `name` with advance `advance`.
export function writeGlif({ outlines, docs, glyph = null, name = "drawing", advance = 0 }) {
  const outline = outlines.map((els) => contourXml(els, "    ")).join("");
  const source = JSON.stringify(flipDocs(docs));
  if (!glyph) {
    return `<?xml version="1.0" encoding="UTF-8"?>
<glyph name="${escapeXml(name)}" format="2">
  <advance width="${num(advance)}"/>
  <outline>
${outline}  </outline>
  <lib>
    <dict>
      <key>${KAPPA_LIB_KEY}</key>
      <string>${escapeXml(source)}</string>
    </dict>
  </lib>
</glyph>
`;
  }
  const doc = glyph.cloneNode(true);
  const root = doc.documentElement;
  root.setAttribute("format", "2");
  const parsed = new DOMParser().parseFromString(
    `<outline>\n${outline}  </outline>`, "application/xml").documentElement;
  const fresh = doc.importNode(parsed, true);
  const old = root.querySelector(":scope > outline");
  if (old) root.replaceChild(fresh, old);
  else root.appendChild(fresh);
  let value = libValue(doc, KAPPA_LIB_KEY);
  if (!value) {
    let lib = root.querySelector(":scope > lib");
    if (!lib) lib = root.appendChild(doc.createElement("lib"));
    let dict = lib.querySelector(":scope > dict");
    if (!dict) dict = lib.appendChild(doc.createElement("dict"));
    const key = dict.appendChild(doc.createElement("key"));
    key.textContent = KAPPA_LIB_KEY;
    value = dict.appendChild(doc.createElement("string"));
  }
  value.textContent = source;
  return `<?xml version="1.0" encoding="UTF-8"?>\n${new XMLSerializer().serializeToString(doc)}\n`;
}
