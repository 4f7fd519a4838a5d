// The page's LAYOUT writer (src/serve/page/layout.js), a pure module,
// tested in Node without a browser: `node --test tests/page` (.ci/run).
// Expected texts are written out by hand from the rule the module keeps:
// an edit rewrites only the numbers that changed, in the shape's own
// spelling, and every span after the edit moves by the edit's length.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { num, round, shapeText, rewriteShape, rebase, deleteShape } from '../../src/serve/page/layout.js';

test('numbers: three decimals, never -0; radii to one decimal', () => {
  assert.equal(num(1 / 3), '0.333');
  assert.equal(num(-0.0001), '0');
  assert.equal(num(12), '12');
  assert.equal(round(1.26), 1.3);
});

test('a moved shape keeps its spelling: only changed numbers are written', () => {
  const t = '(clRed)<Rectangle (10, 20), 30,40>';
  const moved = { type: 'Rectangle', name: 'clRed', x: 15, y: 20, w: 30, h: 40 };
  assert.equal(shapeText(t, moved, moved), '(clRed)<Rectangle (15, 20), 30,40>');
  // Corners stay corners, in their written order (x2 before x1 here).
  const c = '(#0f0) Rectangle (40,0,10,30)';
  const s = { type: 'Rectangle', name: '#0f0', x: 12, y: 0, w: 30, h: 30 };
  assert.equal(shapeText(c, s, s), '(#0f0) Rectangle (42,0,12,30)');
  // A new colour is written; the rest stays.
  const red = { ...moved, name: 'clBlue' };
  assert.equal(shapeText(t, red, moved), '(clBlue)<Rectangle (15, 20), 30,40>');
});

// A document of two shapes on two lines, spans by hand.
function doc() {
  const text = 'LAYOUT\n(clRed) Rectangle (0,0),10,10\n(clBlue) Ellipse (5,5),20,20\nENDLAYOUT\n';
  const a = text.indexOf('(clRed)');
  const b = text.indexOf('(clBlue)');
  return {
    text,
    shapes: [
      { type: 'Rectangle', name: 'clRed', x: 0, y: 0, w: 10, h: 10, start: a, end: text.indexOf('\n', a) },
      { type: 'Ellipse', name: 'clBlue', x: 5, y: 5, w: 20, h: 20, start: b, end: text.indexOf('\n', b) },
    ],
    layout: [0, text.indexOf('ENDLAYOUT') + 'ENDLAYOUT'.length],
    root: null,
    rootAt: null,
  };
}

test('rewriting a shape moves the spans after it by the length it gained', () => {
  const d = doc();
  const out = rewriteShape(d, 0, { ...d.shapes[0], x: 100 });
  assert.equal(out.text, 'LAYOUT\n(clRed) Rectangle (100,0),10,10\n(clBlue) Ellipse (5,5),20,20\nENDLAYOUT\n');
  assert.equal(out.shapes[1].start, d.shapes[1].start + 2);
  assert.equal(out.text.slice(out.shapes[1].start, out.shapes[1].end), '(clBlue) Ellipse (5,5),20,20');
  assert.equal(out.layout[1], d.layout[1] + 2);
});

test('a typed edit outside every span rebases; one inside waits for the answer', () => {
  const d = doc();
  const typed = '# a comment\n' + d.text;
  const out = rebase(d, typed);
  assert.equal(out.shapes[0].start, d.shapes[0].start + 12);
  assert.equal(out.text.slice(out.shapes[0].start, out.shapes[0].end), '(clRed) Rectangle (0,0),10,10');
  assert.equal(rebase(d, d.text.replace('(0,0)', '(1,0)')), null);
});

test('deleting a shape removes its line and nothing else', () => {
  const out = deleteShape(doc(), 0);
  assert.equal(out.text, 'LAYOUT\n(clBlue) Ellipse (5,5),20,20\nENDLAYOUT\n');
  assert.equal(out.shapes.length, 1);
  assert.equal(out.text.slice(out.shapes[0].start, out.shapes[0].end), '(clBlue) Ellipse (5,5),20,20');
});
