// The 3D view's colours and leaves (src/serve/page/paint3d.js), a pure
// module: counts and values worked by hand.

import assert from 'node:assert/strict';
import { test } from 'node:test';
import { leafTriangles, rgb, stemColours } from '../../src/serve/page/paint3d.js';

const BLACK = [0, 0, 0];

test('each stem takes its colour by index, and the stroke past the colours', () => {
  const space = {
    stems: new Array(3 * 8).fill(0),
    colors: ['#ff0000', '#00ff00'],
    stem_colors: [1, 0, 7],
  };
  assert.deepEqual([...stemColours(space, BLACK)], [0, 1, 0, 1, 0, 0, 0, 0, 0]);
});

test('an answer without colours paints every stem in the stroke', () => {
  const grey = rgb('#808080', BLACK);
  assert.deepEqual(grey, [128 / 255, 128 / 255, 128 / 255]);
  const got = stemColours({ stems: new Array(16).fill(0) }, grey);
  assert.deepEqual([...got], [...Float32Array.from([...grey, ...grey])]);
  assert.deepEqual(rgb('nope', BLACK), BLACK);
});

test('a leaf of n vertices is a fan of n - 2 triangles with its normal and colour', () => {
  // A unit square in the z = 0 plane, counter-clockwise seen from +z, and
  // a triangle in the x = 0 plane; a two-point "polygon" draws nothing.
  const space = {
    stems: [],
    colors: ['#000000', '#00ff00'],
    leaves: [
      { color: 1, points: [0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0] },
      { color: 0, points: [0, 0, 0, 0, 1, 0, 0, 0, 1] },
      { color: 1, points: [0, 0, 0, 1, 1, 1] },
    ],
  };
  const t = leafTriangles(space, BLACK);
  assert.equal(t.count, 2 * 3 + 3);
  // The square's fan: (0, 1, 2) and (0, 2, 3).
  assert.deepEqual([...t.pos.slice(0, 18)], [0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 0, 0, 1, 1, 0, 0, 1, 0]);
  for (let v = 0; v < 6; v++) {
    assert.deepEqual([...t.nrm.slice(v * 3, v * 3 + 3)], [0, 0, 1]);
    assert.deepEqual([...t.col.slice(v * 3, v * 3 + 3)], [0, 1, 0]);
  }
  // The triangle (0,0,0), (0,1,0), (0,0,1): its normal is +x.
  assert.deepEqual([...t.nrm.slice(18, 21)], [1, 0, 0]);
  assert.deepEqual([...t.col.slice(18, 21)], [0, 0, 0]);
});
