// The npm package web/build.sh makes (web/www/pkg/): its package.json, and its TypeScript
// types, read with the TypeScript compiler: the class Editor declares every engine method
// the page calls, and a web editor's code that uses the package (consumer.ts) type-checks.

import { test } from "node:test";
import assert from "node:assert/strict";
import fs from "node:fs";
import path from "node:path";
import { fileURLToPath } from "node:url";
import ts from "typescript";

const HERE = path.dirname(fileURLToPath(import.meta.url));
const PKG = path.resolve(HERE, "../www/pkg");
const APP = path.resolve(HERE, "../www/app.js");

test("package.json names the module, its types and files that exist", () => {
  const pkg = JSON.parse(fs.readFileSync(path.join(PKG, "package.json"), "utf8"));
  assert.equal(pkg.name, "kappa-web");
  assert.match(pkg.version, /^\d+\.\d+\.\d+/);
  assert.equal(pkg.type, "module");
  assert.equal(pkg.module, "kappa_web.js");
  assert.equal(pkg.types, "kappa_web.d.ts");
  for (const f of [pkg.module, pkg.types, ...pkg.files]) {
    assert.ok(fs.existsSync(path.join(PKG, f)), `${f} missing from the package`);
  }
});

test("the .d.ts declares the class Editor with every method the page calls", () => {
  const file = path.join(PKG, "kappa_web.d.ts");
  const src = ts.createSourceFile(file, fs.readFileSync(file, "utf8"), ts.ScriptTarget.Latest, true);
  const editor = src.statements.find((s) => ts.isClassDeclaration(s) && s.name?.text === "Editor");
  assert.ok(editor, "no class Editor");
  assert.ok(editor.modifiers?.some((m) => m.kind === ts.SyntaxKind.ExportKeyword), "Editor not exported");
  const members = new Map();
  for (const m of editor.members) {
    if (ts.isConstructorDeclaration(m)) members.set("constructor", m);
    else if (ts.isMethodDeclaration(m) && m.name) members.set(m.name.getText(src), m);
  }
  assert.ok(members.has("constructor"), "Editor has no constructor");
  // engine.method( and Editor.method( in the page.
  const app = fs.readFileSync(APP, "utf8");
  const used = new Set([...app.matchAll(/\b(?:engine|Editor)\.(\w+)\(/g)].map((m) => m[1]));
  assert.ok(used.size > 40, `only ${used.size} engine methods found in app.js`);
  const missing = [...used].filter((name) => !members.has(name));
  assert.deepEqual(missing, [], "methods the page calls that the types do not declare");
  // Queries return the declared objects, not `any`.
  const returns = (name) => members.get(name).type?.getText(src);
  assert.equal(returns("points"), "Point[]");
  assert.equal(returns("pieces"), "Piece[]");
  assert.equal(returns("hit"), "Hit | null");
  assert.equal(returns("pathData"), "Float64Array");
  for (const name of ["Point", "Piece", "Tangents", "Hit", "CurvePoint", "PointRef", "Bounds", "SchemeName"]) {
    assert.ok(src.statements.some((s) => s.name?.text === name), `type ${name} not declared`);
  }
  // The default export initialises the module.
  assert.ok(src.statements.some((s) => ts.isFunctionDeclaration(s) && s.name?.text === "__wbg_init" &&
    s.modifiers?.some((m) => m.kind === ts.SyntaxKind.DefaultKeyword)), "no default init export");
});

test("a web editor's code using the package type-checks (strict)", () => {
  const program = ts.createProgram([path.join(HERE, "consumer.ts")], {
    strict: true, noEmit: true, target: ts.ScriptTarget.ES2022, module: ts.ModuleKind.ES2022,
    // The generated class has [Symbol.dispose] (explicit resource management): lib esnext.
    moduleResolution: ts.ModuleResolutionKind.Bundler, lib: ["lib.esnext.d.ts", "lib.dom.d.ts"],
    skipLibCheck: false, types: [],
  });
  const diagnostics = ts.getPreEmitDiagnostics(program).map((d) =>
    ts.formatDiagnostic(d, { getCanonicalFileName: (f) => f, getCurrentDirectory: () => HERE, getNewLine: () => "\n" }));
  assert.deepEqual(diagnostics, []);
});
