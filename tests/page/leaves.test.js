// The leaf control's text edits (src/serve/page/leaves.js, keys.js), pure
// modules, tested in Node without a browser: `node --test tests/page`.
// Spans and expected texts are counted by hand from the text below.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { surfaces, leafShown, withLeaf } from '../../src/serve/page/leaves.js';

const TEXT = [
  'Oak', // 0..3
  '(1, 2, 0)', // 4..13
  'L=12(0.5) S=#5b3a1e..#3b5e2b P=L # P=Q', // 14..52: `P=L` at 43..46
  'RULE', // 53
  'R1: [+F]', // 58
  'SEED', // 67
  'F R1', // 72
  'ENDSEED', // 77
  'SURFACES # leaves', // 85..102
  'surface L { [{.+f.-f.}] }', // 103..128: `L` at 111
  '  surface K { [{.+f.}] } # a second', // 129..: `K` at 139
  '# surface Z { }', // a comment, no surface
  'surface L { [{.f.}] }', // L again: listed once
  'ENDSURFACES',
  'surface Q { [{.f.}] }', // after the block: none
  'LAYOUT',
  'ENDLAYOUT',
  '',
].join('\n');

const lineOf = (t, i) => t.split('\n')[i];
const changedLines = (a, b) => {
  const [x, y] = [a.split('\n'), b.split('\n')];
  assert.equal(x.length, y.length);
  return x.filter((l, i) => l !== y[i]).length;
};

test('the surfaces of the SURFACES block, each name where it is written', () => {
  assert.deepEqual(surfaces(TEXT), [
    { name: 'L', start: 111, end: 112 },
    { name: 'K', start: 139, end: 140 },
  ]);
  assert.equal(TEXT.slice(111, 112), 'L');
  assert.equal(TEXT.slice(139, 140), 'K');
  // No block, or a keyword only in a comment: no surfaces.
  assert.deepEqual(surfaces('A\nRULE\nSEED\nF\nENDSEED\n'), []);
  assert.deepEqual(surfaces('# SURFACES\nsurface L { [{.f.}] }\n'), []);
  // Unclosed: up to LAYOUT.
  assert.deepEqual(surfaces('SURFACES\nsurface M { f }\nLAYOUT\nsurface N { f }\n'), [
    { name: 'M', start: 17, end: 18 },
  ]);
});

test('the leaf shown is the header\'s P=, not one in a comment', () => {
  assert.equal(leafShown(TEXT), 'L');
  assert.equal(leafShown(TEXT.replace(' P=L', '')), 'none');
});

test('choosing a leaf rewrites only P=; none removes only that key', () => {
  const k = withLeaf(TEXT, 'K');
  assert.equal(lineOf(k, 2), 'L=12(0.5) S=#5b3a1e..#3b5e2b P=K # P=Q');
  assert.equal(k, TEXT.slice(0, 45) + 'K' + TEXT.slice(46));
  const none = withLeaf(TEXT, 'none');
  assert.equal(lineOf(none, 2), 'L=12(0.5) S=#5b3a1e..#3b5e2b # P=Q');
  assert.equal(none, TEXT.slice(0, 42) + TEXT.slice(46));
  assert.equal(changedLines(TEXT, none), 1);
  // None again: nothing to remove.
  assert.equal(withLeaf(none, 'none'), none);
  // A header without P= gets it at its end, before RULE.
  const back = withLeaf(none, 'L');
  assert.equal(lineOf(back, 2), 'L=12(0.5) S=#5b3a1e..#3b5e2b P=L # P=Q');
  assert.equal(back, TEXT);
});
