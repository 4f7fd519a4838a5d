// The page's volume meshes (src/serve/page/meshes.js), a pure module,
// tested in Node: outlines of the answer's shapes and their triangles,
// checked by areas worked out by hand (a triangulation of a simple polygon
// covers it exactly once: its triangles' areas sum to the polygon's).
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { outline, triangulate } from '../../src/serve/page/meshes.js';

const area = (pts, [a, b, c]) =>
  Math.abs((pts[b][0] - pts[a][0]) * (pts[c][1] - pts[a][1]) - (pts[b][1] - pts[a][1]) * (pts[c][0] - pts[a][0])) / 2;

test('a rectangle is its four corners, in order', () => {
  assert.deepEqual(outline({ type: 'Rectangle', x: 1, y: 2, w: 3, h: 4 }), [[1, 2], [4, 2], [4, 6], [1, 6]]);
});

test('a polygon of n points is cut into n - 2 triangles that cover it once', () => {
  // An L shape: a 20 x 20 square less its 10 x 10 top-right quarter: 300.
  const l = [[0, 0], [10, 0], [10, 10], [20, 10], [20, 20], [0, 20]];
  for (const pts of [l, [...l].reverse()]) {
    const tris = triangulate(pts);
    assert.equal(tris.length, pts.length - 2);
    const sum = tris.reduce((s, t) => s + area(pts, t), 0);
    assert.ok(Math.abs(sum - 300) < 1e-9, `area ${sum}`);
  }
});

test('an ellipse outline lies on its ellipse and its triangles approach its area', () => {
  const pts = outline({ type: 'Ellipse', x: 0, y: 0, w: 40, h: 20 });
  for (const [x, y] of pts) {
    const e = ((x - 20) / 20) ** 2 + ((y - 10) / 10) ** 2;
    assert.ok(Math.abs(e - 1) < 1e-9, `(${x}, ${y}) is off the ellipse`);
  }
  const sum = triangulate(pts).reduce((s, t) => s + area(pts, t), 0);
  // An inscribed 64-gon holds (64 / 2pi) sin(2pi / 64) of the area.
  const inscribed = Math.PI * 20 * 10 * (64 / (2 * Math.PI)) * Math.sin((2 * Math.PI) / 64);
  assert.ok(Math.abs(sum - inscribed) < 1e-6, `${sum} against ${inscribed}`);
});
