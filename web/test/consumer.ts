// A web editor's use of the kappa-web package, type-checked by package.test.mjs
// (tsc --noEmit semantics, strict): the package's types must accept it as written.
import init, { Editor, type Point, type Piece, type Hit, type SchemeName } from "../www/pkg/kappa_web.js";

export async function demo(): Promise<string> {
  await init();
  const scheme: SchemeName = "ek-cubic";
  const editor = new Editor(scheme);
  const failed: number = editor.addPoint(100, 100) + editor.addPoint(200, 50) + editor.addPoint(300, 120);
  editor.setClosed(true);
  const points: Point[] = editor.points(0);
  const pieces: Piece[] = editor.pieces(0);
  const hit: Hit | null = editor.hit(150, 90);
  const path: Float64Array = editor.pathData();
  const comb: Float64Array = editor.combData(40, 0.75, 3, 16);
  editor.dragPoint(1, 201, 51);
  editor.endDrag();
  editor.setTangent(1, 1, 0);
  const t = editor.tangents(0)[1];
  const out: [number, number] | null = t.out;
  const near = editor.nearestPoint(200, 50, 8);
  const k: number = near ? near.contour : editor.active();
  const opened: number = editor.open(editor.save(), false);
  const neutral: number = Editor.neutralShape("ek-trig");
  editor.free();
  return `${failed} ${points.length} ${pieces[0].tMax.length} ${hit?.distance} ${path.length} ` +
    `${comb.length} ${out} ${k} ${opened} ${neutral}`;
}
